//! [`View`]: where the sandbox looks (centre and zoom), pan and zoom about the cursor, and
//! the mapping between the panel's screen points and world units.

use craterfield::field2d::Aabb;
use craterfield::render2d::Camera;
use glam::Vec2;

/// Closest and farthest zoom, world units per pixel.
const ZOOM_RANGE: (f32, f32) = (0.05, 64.0);

/// The sandbox's 2D camera, independent of the panel's size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// World point at the panel's centre.
    pub center: Vec2,
    /// World units per physical pixel.
    pub units_per_pixel: f32,
}

/// A panel on screen: its rectangle in points and the points-to-pixels factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Screen {
    /// The panel's rectangle, points.
    pub rect: egui::Rect,
    /// Physical pixels per point.
    pub pixels_per_point: f32,
}

impl Screen {
    /// The panel's size in physical pixels (at least 1 each way).
    pub fn pixels(&self) -> [u32; 2] {
        let s = self.rect.size() * self.pixels_per_point;
        [(s.x.round() as u32).max(1), (s.y.round() as u32).max(1)]
    }
}

impl View {
    /// The whole `bounds` in a panel of `pixels`.
    pub fn fit(bounds: Aabb, pixels: [u32; 2]) -> View {
        let size = bounds.max - bounds.min;
        let upp = (size.x / pixels[0].max(1) as f32).max(size.y / pixels[1].max(1) as f32);
        View {
            center: (bounds.min + bounds.max) * 0.5,
            units_per_pixel: upp.clamp(ZOOM_RANGE.0, ZOOM_RANGE.1),
        }
    }

    /// The library camera for a panel of `pixels`.
    pub fn camera(&self, pixels: [u32; 2]) -> Camera {
        Camera {
            center: self.center,
            units_per_pixel: self.units_per_pixel,
            width: pixels[0],
            height: pixels[1],
        }
    }

    /// The world point under `pos` (points).
    pub fn to_world(&self, screen: &Screen, pos: egui::Pos2) -> Vec2 {
        let d = (pos - screen.rect.center()) * screen.pixels_per_point;
        self.center + Vec2::new(d.x, -d.y) * self.units_per_pixel
    }

    /// The screen point (points) of world point `p`.
    pub fn to_screen(&self, screen: &Screen, p: Vec2) -> egui::Pos2 {
        let d = (p - self.center) / self.units_per_pixel / screen.pixels_per_point;
        screen.rect.center() + egui::vec2(d.x, -d.y)
    }

    /// A world length in points.
    pub fn length_to_points(&self, screen: &Screen, units: f32) -> f32 {
        units / self.units_per_pixel / screen.pixels_per_point
    }

    /// Moves the view with a drag of `delta` points (the world follows the pointer).
    pub fn pan(&mut self, screen: &Screen, delta: egui::Vec2) {
        let d = delta * screen.pixels_per_point * self.units_per_pixel;
        self.center -= Vec2::new(d.x, -d.y);
    }

    /// Zooms by `factor` (above 1 zooms in) keeping the world point under `pos` fixed.
    pub fn zoom_about(&mut self, screen: &Screen, pos: egui::Pos2, factor: f32) {
        if !(factor.is_finite() && factor > 0.0) {
            return;
        }
        let anchor = self.to_world(screen, pos);
        let upp = (self.units_per_pixel / factor).clamp(ZOOM_RANGE.0, ZOOM_RANGE.1);
        self.center = anchor + (self.center - anchor) * (upp / self.units_per_pixel);
        self.units_per_pixel = upp;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn screen() -> Screen {
        Screen {
            rect: egui::Rect::from_min_size(egui::pos2(100.0, 50.0), egui::vec2(400.0, 300.0)),
            pixels_per_point: 2.0,
        }
    }

    #[test]
    fn screen_and_world_round_trip_and_zoom_keeps_the_cursor_point() {
        let s = screen();
        let mut v = View {
            center: Vec2::new(1000.0, 500.0),
            units_per_pixel: 2.0,
        };
        let pos = egui::pos2(150.0, 300.0);
        let w = v.to_world(&s, pos);
        assert!((v.to_screen(&s, w) - pos).length() < 1e-3);
        // y is up in the world, down on screen.
        assert!(v.to_world(&s, egui::pos2(300.0, 60.0)).y > v.center.y);
        v.zoom_about(&s, pos, 2.0);
        assert_eq!(v.units_per_pixel, 1.0);
        assert!((v.to_world(&s, pos) - w).length() < 1e-3);
        v.pan(&s, egui::vec2(10.0, 0.0));
        assert!((v.to_world(&s, pos + egui::vec2(10.0, 0.0)) - w).length() < 1e-3);
        assert_eq!(s.pixels(), [800, 600]);
    }
}
