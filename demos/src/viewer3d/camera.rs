//! [`ViewCamera`]: the viewer's camera, an orbit camera (drag to orbit a pivot, wheel to
//! zoom, arrow keys to orbit) or a fly camera (WASD/QE to move, drag or arrow keys to
//! look), both starting at the scene file's camera.
//!
//! One state serves both modes: an eye, a view direction as yaw and pitch about the
//! scene's up vector, and the distance to the orbit pivot straight ahead. Orbiting keeps
//! the pivot and moves the eye; flying moves the eye and the pivot with it. Switching modes
//! therefore never jumps.

use craterfield::march3d::Camera3d;
use craterfield::march3d::scene::CameraSpec;
use glam::Vec3;

/// How input moves the camera.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CameraMode {
    /// Drag orbits the pivot, the wheel zooms, arrow keys orbit.
    #[default]
    Orbit,
    /// WASD moves, Q and E go down and up, drag and arrow keys look around.
    Fly,
}

impl CameraMode {
    /// The other mode.
    pub fn toggled(self) -> CameraMode {
        match self {
            CameraMode::Orbit => CameraMode::Fly,
            CameraMode::Fly => CameraMode::Orbit,
        }
    }
}

/// One frame's camera input.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ViewInput {
    /// Pointer drag over the view, in points.
    pub(crate) drag: glam::Vec2,
    /// Wheel scroll over the view, in points (positive: away from the user, zoom in).
    pub(crate) scroll: f32,
    /// Movement keys held: x right (D - A), y up (E - Q), z forward (W - S).
    pub(crate) walk: Vec3,
    /// Arrow keys held: x right, y up.
    pub(crate) turn: glam::Vec2,
    /// Whether Shift is held (faster flight).
    pub(crate) fast: bool,
    /// Seconds since the last frame.
    pub(crate) dt: f32,
}

impl ViewInput {
    /// Whether held keys keep the camera moving (the view must keep redrawing).
    pub(crate) fn keys_held(&self) -> bool {
        self.walk != Vec3::ZERO || self.turn != glam::Vec2::ZERO
    }
}

/// Radians per point dragged.
const DRAG_RADIANS: f32 = 0.008;
/// Radians per second an arrow key turns.
const KEY_RADIANS: f32 = 1.2;
/// Zoom factor per point scrolled: `exp(-scroll * ZOOM_RATE)`.
const ZOOM_RATE: f32 = 0.002;
/// Pitch stays this far from straight up or down, so the up vector stays usable.
const PITCH_LIMIT: f32 = 1.5;
/// Closest and farthest orbit distance, as fractions of the starting distance.
const ZOOM_RANGE: (f32, f32) = (0.02, 50.0);
/// Fly speed in starting orbit distances per second.
const FLY_SPEED: f32 = 0.5;
/// Shift multiplies the fly speed by this.
const FAST: f32 = 4.0;

/// The viewer's camera (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ViewCamera {
    eye: Vec3,
    yaw: f32,
    pitch: f32,
    distance: f32,
    start_distance: f32,
    fov: f32,
    up: Vec3,
    /// The horizontal direction of yaw 0 (perpendicular to `up`).
    ahead: Vec3,
}

impl ViewCamera {
    /// The scene's camera, orbiting a pivot `pivot_depth` ahead of the eye.
    pub(crate) fn from_spec(spec: &CameraSpec, pivot_depth: f32) -> Result<ViewCamera, String> {
        let camera = spec.camera().map_err(|e| e.to_string())?;
        let up = spec
            .up
            .try_normalize()
            .ok_or("the camera's up vector is zero")?;
        let forward = camera.forward;
        let ahead = (forward - up * forward.dot(up))
            .try_normalize()
            .ok_or("the camera looks along its up vector")?;
        let distance = if pivot_depth.is_finite() && pivot_depth > 0.0 {
            pivot_depth
        } else {
            (spec.look_at - spec.position).length()
        };
        Ok(ViewCamera {
            eye: spec.position,
            yaw: 0.0,
            pitch: forward.dot(up).clamp(-1.0, 1.0).asin(),
            distance,
            start_distance: distance,
            fov: spec.fov,
            up,
            ahead,
        })
    }

    /// The unit view direction.
    pub(crate) fn forward(&self) -> Vec3 {
        let side = self.up.cross(self.ahead);
        let level = self.ahead * self.yaw.cos() + side * self.yaw.sin();
        level * self.pitch.cos() + self.up * self.pitch.sin()
    }

    /// The point the orbit mode turns around.
    pub(crate) fn pivot(&self) -> Vec3 {
        self.eye + self.forward() * self.distance
    }

    /// The renderers' camera; `None` only if the state became degenerate (it cannot,
    /// given the pitch limit, but the caller keeps its last camera rather than panic).
    pub(crate) fn camera(&self) -> Option<Camera3d> {
        Camera3d::looking(self.eye, self.forward(), self.up, self.fov)
    }

    /// Moves the camera by one frame's input; returns whether it moved.
    pub(crate) fn apply(&mut self, input: &ViewInput, mode: CameraMode) -> bool {
        let before = self.clone();
        match mode {
            CameraMode::Orbit => self.orbit(input),
            CameraMode::Fly => self.fly(input),
        }
        *self != before
    }

    fn orbit(&mut self, input: &ViewInput) {
        let pivot = self.pivot();
        self.turn(input);
        let (near, far) = ZOOM_RANGE;
        self.distance = (self.distance * (-input.scroll * ZOOM_RATE).exp())
            .clamp(self.start_distance * near, self.start_distance * far);
        self.eye = pivot - self.forward() * self.distance;
    }

    fn fly(&mut self, input: &ViewInput) {
        self.turn(input);
        let forward = self.forward();
        let right = self.up.cross(forward).normalize_or_zero();
        let speed = self.start_distance * FLY_SPEED * if input.fast { FAST } else { 1.0 };
        let step = right * input.walk.x + self.up * input.walk.y + forward * input.walk.z;
        self.eye += step * speed * input.dt;
    }

    /// Drag and arrow keys turn the view (both modes turn the same way: dragging right
    /// looks right in flight and swings the eye left around the pivot in orbit).
    fn turn(&mut self, input: &ViewInput) {
        let keys = input.turn * KEY_RADIANS * input.dt;
        self.yaw += input.drag.x * DRAG_RADIANS + keys.x;
        self.pitch =
            (self.pitch - input.drag.y * DRAG_RADIANS + keys.y).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> CameraSpec {
        CameraSpec {
            position: Vec3::new(0.0, 5.0, -24.0),
            look_at: Vec3::new(2.0, 2.5, 10.0),
            up: Vec3::Y,
            fov: 50.0,
        }
    }

    #[test]
    fn it_starts_at_the_scene_camera() {
        let view = ViewCamera::from_spec(&spec(), 30.0).unwrap();
        let a = view.camera().unwrap();
        let b = spec().camera().unwrap();
        assert!((a.position - b.position).length() < 1e-5);
        assert!((a.forward - b.forward).length() < 1e-5, "{a:?} {b:?}");
        assert!((a.up - b.up).length() < 1e-5);
    }

    #[test]
    fn orbit_keeps_the_pivot_and_fly_keeps_the_direction() {
        let mut view = ViewCamera::from_spec(&spec(), 30.0).unwrap();
        let pivot = view.pivot();
        let drag = ViewInput {
            drag: glam::Vec2::new(40.0, -10.0),
            scroll: 50.0,
            ..ViewInput::default()
        };
        assert!(view.apply(&drag, CameraMode::Orbit));
        assert!((view.pivot() - pivot).length() < 1e-3);
        assert!(view.distance < 30.0);
        let forward = view.forward();
        let walk = ViewInput {
            walk: Vec3::Z,
            dt: 0.1,
            ..ViewInput::default()
        };
        let eye = view.eye;
        assert!(view.apply(&walk, CameraMode::Fly));
        assert!((view.forward() - forward).length() < 1e-6);
        assert!((view.eye - eye).dot(forward) > 0.0);
        assert!(!view.apply(&ViewInput::default(), CameraMode::Fly));
    }

    #[test]
    fn pitch_stops_short_of_the_poles() {
        let mut view = ViewCamera::from_spec(&spec(), 30.0).unwrap();
        let up = ViewInput {
            drag: glam::Vec2::new(0.0, -1.0e6),
            ..ViewInput::default()
        };
        view.apply(&up, CameraMode::Orbit);
        assert!(view.camera().is_some());
    }
}
