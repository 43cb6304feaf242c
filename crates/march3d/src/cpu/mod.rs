//! The CPU SIMD sphere tracer: renders a [`Plan`] for a [`Camera3d`] into RGBA8 pixels.
//!
//! Rays travel in vertical SoA packets of `P::WIDTH` pixels in a near-square block (4x4 on
//! AVX-512, 4x2 on AVX2, 2x2 on NEON, 1 scalar), so that a packet's lanes finish their
//! marches at similar steps, with active-lane masks; the image is cut into square tiles
//! that threads take from an atomic counter, and each thread's whole share of the frame
//! runs inside one [`PackKernel::run`], so every lane operation inlines into code compiled
//! for the instruction set. Each lane's arithmetic depends only on its own pixel, so the
//! image does not depend on the thread count, the tile size or the packet shape.
//!
//! Two shortcuts of the march find the surfaces plain sphere tracing finds, in fewer
//! steps, in scenes without terrain: a ray lands on a bare plane in closed form when
//! nothing else is nearer than the plane along it (rays grazing a floor took hundreds of
//! geometrically shrinking steps), and a ray that can meet no node's bounding sphere and
//! no plane ahead stops as a miss at once. Soft-shadow rays take every step: their value
//! depends on each distance along the way.
//!
//! [`render_counted`] runs the one-lane `Counting` backend and reports SDF evaluations
//! and march steps over every ray of every pixel (primary, reflected, shadow, occlusion,
//! normals) and the floating-point operations of the frame.

mod constants;
mod eval;
mod lanes;
mod march;
mod prims;
mod shade;
mod stream;
#[cfg(test)]
mod tests;

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use thiserror::Error;

use self::eval::Tally;
use self::lanes::MAX_WIDTH;
use self::shade::{Frame, camera_rays, packet_shape, shade};
use super::simd::count::{self, Counting};
use super::simd::{self, Pack, PackKernel};
use crate::plan3d::{Camera3d, Plan, PlanError, Shading};
use craterfield_core::backend::{Backend, BackendError};

/// The longest image side accepted.
pub const MAX_SIDE: u32 = 16_384;
/// The most pixels accepted.
pub const MAX_PIXELS: u64 = 64 * 1024 * 1024;

/// How to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraceOptions {
    /// Worker threads; 0 means every core.
    pub threads: usize,
    /// The instruction set; `None` means [`simd::best`].
    pub backend: Option<Backend>,
    /// The side of the square tiles threads take, in pixels.
    pub tile: u32,
}

impl Default for TraceOptions {
    fn default() -> Self {
        TraceOptions {
            threads: 0,
            backend: None,
            tile: 32,
        }
    }
}

/// A rendered image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rendered {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA8, row-major, alpha 255.
    pub rgba: Vec<u8>,
}

/// What a counted frame did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Pixels rendered.
    pub pixels: u64,
    /// SDF evaluations (primitive distances, terrain heights, bounding spheres,
    /// Mandelbulbs) over every ray of every pixel.
    pub sdf_evals: u64,
    /// March steps over every ray (primary, reflected, shadow) of every pixel.
    pub steps: u64,
    /// Floating-point operations of the frame (one per arithmetic operation or
    /// math-library call; a fused multiply-add is two).
    pub flops: u64,
}

impl Stats {
    /// SDF evaluations per pixel.
    pub fn sdf_evals_per_pixel(&self) -> f64 {
        self.sdf_evals as f64 / self.pixels.max(1) as f64
    }

    /// March steps per pixel.
    pub fn steps_per_pixel(&self) -> f64 {
        self.steps as f64 / self.pixels.max(1) as f64
    }

    /// Floating-point operations per pixel.
    pub fn flops_per_pixel(&self) -> f64 {
        self.flops as f64 / self.pixels.max(1) as f64
    }

    /// Billions of floating-point operations.
    pub fn gflop(&self) -> f64 {
        self.flops as f64 * 1e-9
    }
}

/// Why a frame cannot be rendered.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum TraceError {
    /// A side is 0 or above [`MAX_SIDE`], or the image has more than [`MAX_PIXELS`].
    #[error(
        "cannot render {width}x{height}: each side must be 1..={MAX_SIDE} and the image at most {MAX_PIXELS} pixels"
    )]
    BadSize {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// The tile side is 0.
    #[error("the tile side must be at least one pixel")]
    BadTile,
    /// The camera has a non-finite or degenerate value.
    #[error("bad camera: {0}")]
    BadCamera(String),
    /// The plan has a value the renderers cannot use.
    #[error("bad plan: {0}")]
    BadPlan(#[from] PlanError),
    /// The backend is not available, or the tracer has no code for it.
    #[error(transparent)]
    Backend(#[from] BackendError),
}

/// Renders `plan` seen by `camera` at `width x height`.
pub fn render(
    plan: &Plan,
    camera: &Camera3d,
    width: u32,
    height: u32,
    opts: &TraceOptions,
) -> Result<Rendered, TraceError> {
    check(plan, camera, width, height)?;
    if opts.tile == 0 {
        return Err(TraceError::BadTile);
    }
    let backend = match opts.backend {
        Some(backend) => simd::check(backend)?,
        None => simd::best(),
    };
    let frame = Frame::new(plan, camera, width, height);
    let (img, _) = run_threads(&frame, opts.threads, opts.tile, |job| {
        simd::run(backend, job).map_err(TraceError::from)
    })?;
    Ok(img)
}

/// Renders with the one-lane counting backend and returns the image with its statistics.
pub fn render_counted(
    plan: &Plan,
    camera: &Camera3d,
    width: u32,
    height: u32,
    threads: usize,
) -> Result<(Rendered, Stats), TraceError> {
    check(plan, camera, width, height)?;
    let frame = Frame::new(plan, camera, width, height);
    let (img, totals) = run_threads(&frame, threads, TraceOptions::default().tile, |job| {
        count::take_flops();
        let mut out = Counting.call(job);
        out.flops = count::take_flops();
        Ok(out)
    })?;
    let stats = Stats {
        pixels: width as u64 * height as u64,
        sdf_evals: totals.tally.sdf,
        steps: totals.tally.steps,
        flops: totals.flops,
    };
    Ok((img, stats))
}

/// Validates the size, the camera and the plan.
fn check(plan: &Plan, camera: &Camera3d, width: u32, height: u32) -> Result<(), TraceError> {
    if width == 0
        || height == 0
        || width > MAX_SIDE
        || height > MAX_SIDE
        || width as u64 * height as u64 > MAX_PIXELS
    {
        return Err(TraceError::BadSize { width, height });
    }
    let c = camera;
    let vecs = [c.position, c.forward, c.right, c.up];
    if !vecs.iter().all(|v| v.is_finite()) {
        return Err(TraceError::BadCamera("a vector is not finite".into()));
    }
    if !(c.tan_half_fov.is_finite() && c.tan_half_fov > 0.0) {
        return Err(TraceError::BadCamera(format!(
            "tan_half_fov {} is not a positive number",
            c.tan_half_fov
        )));
    }
    if [c.forward, c.right, c.up]
        .iter()
        .any(|v| (v.length() - 1.0).abs() > 1e-3)
    {
        return Err(TraceError::BadCamera(
            "direction vectors must be unit".into(),
        ));
    }
    Ok(plan.validate()?)
}

/// What one worker produced: finished tiles and its counts.
#[derive(Default)]
struct Totals {
    tally: Tally,
    flops: u64,
}

/// One worker's share of the frame: it takes tiles from the shared counter until none is
/// left, renders each and hands the pixels over.
struct Worker<'a> {
    frame: &'a Frame,
    tiles: &'a [(u32, u32, u32, u32)],
    next: &'a AtomicUsize,
    out: &'a Mutex<Vec<u8>>,
}

/// What [`Worker`] returns.
struct WorkerOut {
    tally: Tally,
    flops: u64,
}

impl PackKernel for Worker<'_> {
    type Output = WorkerOut;

    #[inline(always)]
    fn run<P: Pack>(self, p: P) -> WorkerOut {
        let mut tally = Tally::default();
        let mut buf = Vec::new();
        loop {
            let k = self.next.fetch_add(1, Ordering::Relaxed);
            let Some(&(x0, y0, x1, y1)) = self.tiles.get(k) else {
                break;
            };
            buf.clear();
            buf.resize(((x1 - x0) * (y1 - y0) * 4) as usize, 0);
            render_tile(p, self.frame, (x0, y0, x1, y1), &mut buf, &mut tally);
            let w = self.frame.width as usize;
            let row = ((x1 - x0) * 4) as usize;
            let mut out = self.out.lock().unwrap_or_else(|e| e.into_inner());
            for (r, y) in (y0..y1).enumerate() {
                let at = (y as usize * w + x0 as usize) * 4;
                out[at..at + row].copy_from_slice(&buf[r * row..(r + 1) * row]);
            }
        }
        WorkerOut { tally, flops: 0 }
    }
}

/// Renders the pixels `[x0, x1) x [y0, y1)` into `buf` (RGBA8 rows of the tile).
#[inline(always)]
fn render_tile<P: Pack>(
    p: P,
    f: &Frame,
    (x0, y0, x1, y1): (u32, u32, u32, u32),
    buf: &mut [u8],
    tally: &mut Tally,
) {
    let (pw, ph) = packet_shape::<P>();
    let mut lanes = [[0.0f32; MAX_WIDTH]; 3];
    let mut valid = [0.0f32; MAX_WIDTH];
    // Paper shading truncates, as the reference renderer's cast does; worlds round.
    let rounding = match f.shading {
        Shading::Paper(_) => 0.0,
        Shading::World(_) => 0.5,
    };
    // Which pixel of the tile lane `lane` of the packet at (i0, j0) is, if it is inside.
    let pixel = |i0: u32, j0: u32, lane: u32| {
        let (i, j) = (i0 + lane % pw, j0 + lane / pw);
        (i < x1 && j < y1).then(|| ((j - y0) * (x1 - x0) + (i - x0)) as usize * 4)
    };
    // The tile's packets are shaded together, so that their rays can share lanes.
    let mut corners = Vec::new();
    let mut dirs = Vec::new();
    let mut lives = Vec::new();
    for j0 in (y0..y1).step_by(ph as usize) {
        for i0 in (x0..x1).step_by(pw as usize) {
            for (lane, v) in valid.iter_mut().enumerate().take(P::WIDTH) {
                *v = if pixel(i0, j0, lane as u32).is_some() {
                    1.0
                } else {
                    0.0
                };
            }
            corners.push((i0, j0));
            lives.push(p.gt(p.load(&valid), p.splat(0.5)));
            dirs.push(camera_rays(p, f, (i0, j0)));
        }
    }
    let colours = shade(p, f, &dirs, &lives, tally);
    for (&(i0, j0), c) in corners.iter().zip(&colours) {
        p.store(c.x, &mut lanes[0]);
        p.store(c.y, &mut lanes[1]);
        p.store(c.z, &mut lanes[2]);
        for lane in 0..P::WIDTH {
            let Some(at) = pixel(i0, j0, lane as u32) else {
                continue;
            };
            let px = &mut buf[at..at + 4];
            for (ch, v) in px.iter_mut().zip(&lanes) {
                *ch = to_byte(v[lane], rounding);
            }
            px[3] = 255;
        }
    }
}

/// The scene distance of `plan` at one point, on the scalar lanes (for the emitter's tests).
#[cfg(test)]
pub(crate) fn distance_at(plan: &Plan, q: glam::Vec3) -> f32 {
    use self::lanes::V3;
    use crate::simd::Lanes;
    let p = craterfield_core::simd::Scalar;
    let s = constants::SceneConstants::new(plan);
    let q = V3 {
        x: q.x,
        y: q.y,
        z: q.z,
    };
    let all = p.gt(p.splat(1.0), p.splat(0.0));
    eval::map(p, &s, q, all, false, &mut Tally::default()).0
}

/// `floor(clamp(c, 0, 1) * 255 + rounding)`: 0.5 rounds, 0 truncates.
fn to_byte(c: f32, rounding: f32) -> u8 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    (c * 255.0 + rounding).floor() as u8
}

/// Cuts the frame into tiles and runs `threads` workers (0: every core), each through
/// `go`, which runs the worker kernel on a backend.
fn run_threads<G>(
    frame: &Frame,
    threads: usize,
    tile: u32,
    go: G,
) -> Result<(Rendered, Totals), TraceError>
where
    G: Fn(Worker<'_>) -> Result<WorkerOut, TraceError> + Sync,
{
    let (w, h) = (frame.width, frame.height);
    let mut tiles = Vec::new();
    for y in (0..h).step_by(tile as usize) {
        for x in (0..w).step_by(tile as usize) {
            tiles.push((x, y, (x + tile).min(w), (y + tile).min(h)));
        }
    }
    let threads = craterfield_core::threads::resolve(threads).clamp(1, tiles.len().max(1));
    let next = AtomicUsize::new(0);
    let out = Mutex::new(vec![0u8; w as usize * h as usize * 4]);
    let worker = || Worker {
        frame,
        tiles: &tiles,
        next: &next,
        out: &out,
    };
    let results: Vec<Result<WorkerOut, TraceError>> = if threads == 1 {
        vec![go(worker())]
    } else {
        std::thread::scope(|s| {
            let handles: Vec<_> = (0..threads)
                .map(|_| {
                    let job = worker();
                    let go = &go;
                    s.spawn(move || go(job))
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
                .collect()
        })
    };
    let mut totals = Totals::default();
    for r in results {
        let r = r?;
        totals.tally.sdf += r.tally.sdf;
        totals.tally.steps += r.tally.steps;
        totals.flops += r.flops;
    }
    let rgba = out.into_inner().unwrap_or_else(|e| e.into_inner());
    Ok((
        Rendered {
            width: w,
            height: h,
            rgba,
        },
        totals,
    ))
}
