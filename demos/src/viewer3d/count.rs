//! The panel's count mode: the CPU tracer's counting backend on the current view at a
//! reduced size, on a background thread so the window keeps drawing.
//!
//! The library's counted render reports totals over the frame; to show tails as well, each
//! pixel is counted on its own as a one-pixel frame whose camera looks along that pixel's
//! ray (a one-pixel frame's only ray is its camera's forward direction, and the tracer
//! uses nothing else of the camera but its position).

use std::sync::mpsc;
use std::time::Instant;

use craterfield::march3d::cpu;
use craterfield::march3d::{Camera3d, Plan};

use crate::common::Tails;

/// The most pixels a count covers; the view's aspect is kept.
pub(crate) const COUNT_PIXELS: u32 = 16_000;

/// SDF evaluations and march steps per pixel of one counted frame.
#[derive(Clone, Debug, PartialEq)]
pub struct CountReport {
    /// Counted image size in pixels.
    pub size: [u32; 2],
    /// Mean SDF evaluations per pixel (every ray of the pixel: primary, shadow, occlusion,
    /// normals, reflections).
    pub evals_mean: f64,
    /// Tails of the SDF evaluations per pixel.
    pub evals: Tails,
    /// Mean march steps per pixel.
    pub steps_mean: f64,
    /// Tails of the march steps per pixel.
    pub steps: Tails,
    /// Floating-point operations of the whole counted frame, in billions.
    pub gflop: f64,
    /// Seconds the count took.
    pub seconds: f64,
}

/// A count running on its own thread.
pub(crate) struct CountJob {
    result: mpsc::Receiver<Result<CountReport, String>>,
}

impl CountJob {
    /// Starts counting `plan` seen by `camera` at `size`.
    pub(crate) fn start(plan: Plan, camera: Camera3d, size: [u32; 2]) -> CountJob {
        let (send, result) = mpsc::channel();
        std::thread::spawn(move || {
            // The receiver is gone only if the viewer closed or moved on.
            let _ = send.send(count(&plan, &camera, size));
        });
        CountJob { result }
    }

    /// The result, once there is one.
    pub(crate) fn poll(&self) -> Option<Result<CountReport, String>> {
        match self.result.try_recv() {
            Ok(result) => Some(result),
            Err(mpsc::TryRecvError::Empty) => None,
            Err(mpsc::TryRecvError::Disconnected) => {
                Some(Err("the count stopped without a result".into()))
            }
        }
    }
}

/// The count mode: nothing asked yet, running, or its last result.
pub(crate) enum CountState {
    /// No count was asked for (or the scene changed since).
    Idle,
    /// A count is running.
    Running(CountJob),
    /// The last count's result.
    Done(CountReport),
    /// Why the last count failed.
    Failed(String),
}

impl CountState {
    /// Takes a finished job's result; returns whether a job is still running.
    pub(crate) fn poll(&mut self) -> bool {
        let CountState::Running(job) = self else {
            return false;
        };
        match job.poll() {
            None => true,
            Some(Ok(report)) => {
                *self = CountState::Done(report);
                false
            }
            Some(Err(message)) => {
                *self = CountState::Failed(message);
                false
            }
        }
    }

    /// The last result, if the last count succeeded.
    pub(crate) fn report(&self) -> Option<&CountReport> {
        match self {
            CountState::Done(report) => Some(report),
            _ => None,
        }
    }
}

/// The count size for a view of `view` pixels: the same aspect, at most [`COUNT_PIXELS`].
pub(crate) fn count_size(view: [u32; 2]) -> [u32; 2] {
    let [w, h] = view.map(|s| s.max(1) as f64);
    let scale = (f64::from(COUNT_PIXELS) / (w * h)).sqrt().min(1.0);
    [
        (w * scale).round().max(1.0) as u32,
        (h * scale).round().max(1.0) as u32,
    ]
}

/// What one pixel's rays did.
#[derive(Clone, Copy, Default)]
struct PixelCount {
    evals: u64,
    steps: u64,
    flops: u64,
}

fn count(plan: &Plan, camera: &Camera3d, size: [u32; 2]) -> Result<CountReport, String> {
    let started = Instant::now();
    let pixels: Vec<(u32, u32)> = (0..size[1])
        .flat_map(|j| (0..size[0]).map(move |i| (i, j)))
        .collect();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let chunk = pixels.len().div_ceil(threads).max(1);
    let counts = std::thread::scope(|s| {
        let workers: Vec<_> = pixels
            .chunks(chunk)
            .map(|share| s.spawn(move || count_pixels(plan, camera, size, share)))
            .collect();
        workers
            .into_iter()
            .map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect::<Result<Vec<_>, String>>()
    })?;
    let counts: Vec<PixelCount> = counts.into_iter().flatten().collect();
    Ok(report(&counts, size, started.elapsed().as_secs_f64()))
}

fn count_pixels(
    plan: &Plan,
    camera: &Camera3d,
    size: [u32; 2],
    pixels: &[(u32, u32)],
) -> Result<Vec<PixelCount>, String> {
    pixels
        .iter()
        .map(|&(i, j)| {
            let one = pixel_camera(camera, camera.ray(i, j, size[0], size[1]));
            let (_, stats) = cpu::render_counted(plan, &one, 1, 1, 1).map_err(|e| e.to_string())?;
            Ok(PixelCount {
                evals: stats.sdf_evals,
                steps: stats.steps,
                flops: stats.flops,
            })
        })
        .collect()
}

/// `camera` turned to look along `ray` (unit), with an orthonormal right and up.
fn pixel_camera(camera: &Camera3d, ray: glam::Vec3) -> Camera3d {
    let right = (camera.right - ray * camera.right.dot(ray)).normalize_or(camera.right);
    Camera3d {
        forward: ray,
        right,
        up: ray.cross(right),
        ..*camera
    }
}

fn report(counts: &[PixelCount], size: [u32; 2], seconds: f64) -> CountReport {
    let evals: Vec<f64> = counts.iter().map(|c| c.evals as f64).collect();
    let steps: Vec<f64> = counts.iter().map(|c| c.steps as f64).collect();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    CountReport {
        size,
        evals_mean: mean(&evals),
        evals: Tails::of(&evals),
        steps_mean: mean(&steps),
        steps: Tails::of(&steps),
        gflop: counts.iter().map(|c| c.flops as f64).sum::<f64>() * 1e-9,
        seconds,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use craterfield::march3d::compile::{CompileOptions, emit};
    use craterfield::march3d::scene::Scene;

    #[test]
    fn the_count_size_keeps_the_aspect() {
        let [w, h] = count_size([1600, 900]);
        assert!(w * h <= COUNT_PIXELS + w + h, "{w}x{h}");
        assert!((w as f32 / h as f32 - 16.0 / 9.0).abs() < 0.05);
        assert_eq!(count_size([20, 10]), [20, 10]);
        assert_eq!(count_size([0, 0]), [1, 1]);
    }

    #[test]
    fn per_pixel_counts_add_up_to_the_frame_count() {
        let scene = Scene::builtin("forest").unwrap();
        let camera = scene.camera.camera().unwrap();
        let plan = emit(&scene, &camera, &CompileOptions::default()).unwrap();
        let size = [24, 14];
        let report = count(&plan, &camera, size).unwrap();
        let (_, frame) = cpu::render_counted(&plan, &camera, size[0], size[1], 1).unwrap();
        assert!(report.evals_mean > 0.0 && report.evals.max >= report.evals.median);
        // The one-pixel rays match the frame's rays up to rounding.
        let ratio = report.evals_mean / frame.sdf_evals_per_pixel();
        assert!((ratio - 1.0).abs() < 0.02, "{ratio}");
    }
}
