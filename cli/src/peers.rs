//! The peer of `bench eval`: fidget 0.5 (feature `peers`, off by default so that neither
//! the library nor the test suite ever compiles it).
//!
//! Both renders sample pixel centres, row 0 at the top, like craterfield's: fidget's image
//! renderer samples the lower-left corner of each pixel, so its world-to-model transform is
//! shifted by half a pixel (exact in `f32` for power-of-two sizes over [-1, 1]).

use std::time::Instant;

use fidget::context::Context;
use fidget::eval::MathFunction;
use fidget::raster::pixel::{EvalConfig, RenderConfig, render};
use fidget::render::{ImageSize, RenderHints, ThreadPool};
use fidget::shape::Shape;

/// One timed peer run: milliseconds after parsing, and the image (row 0 at the top).
pub(crate) struct PeerRun {
    pub ms: f64,
    pub image: Vec<bool>,
}

fn shape<F: MathFunction>(text: &str) -> Result<Shape<F>, String> {
    let (ctx, root) =
        Context::from_text(text.as_bytes()).map_err(|e| format!("fidget parse: {e}"))?;
    Shape::<F>::new(&ctx, root).map_err(|e| format!("fidget shape: {e}"))
}

fn pool(threads: usize) -> Result<Option<ThreadPool>, String> {
    if threads <= 1 {
        return Ok(None);
    }
    let p = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| e.to_string())?;
    Ok(Some(ThreadPool::Custom(p)))
}

/// fidget's pruned render (interval tiles and tape simplification).
fn pruned<F: MathFunction + RenderHints>(
    text: &str,
    size: u32,
    threads: usize,
) -> Result<PeerRun, String> {
    let pool = pool(threads)?;
    let shape: Shape<F> = shape(text)?;
    let half = 1.0 / size as f32;
    let cfg = RenderConfig {
        world_to_model: nalgebra::Matrix3::new_translation(&nalgebra::Vector2::new(half, half)),
        ..RenderConfig::from_size(ImageSize::new(size, size))
    };
    let eval_cfg = EvalConfig {
        threads: pool.as_ref(),
        ..Default::default()
    };
    let t = Instant::now();
    let bound = shape
        .try_into()
        .map_err(|_| "fidget: the shape has free variables".to_string())?;
    let img = render::<F>(bound, &cfg, &eval_cfg).ok_or("fidget render cancelled")?;
    let image = img.iter().map(|p| p.inside()).collect();
    Ok(PeerRun {
        ms: t.elapsed().as_secs_f64() * 1e3,
        image,
    })
}

/// The full, unsimplified tape at every pixel centre through fidget's float-slice
/// evaluator, one row per call, one thread.
fn brute<F: MathFunction>(text: &str, size: usize) -> Result<PeerRun, String> {
    let shape: Shape<F> = shape(text)?;
    let t = Instant::now();
    let tape = shape.float_slice_tape(Default::default());
    let mut eval = Shape::<F>::new_float_slice_eval();
    let step = 2.0 / size as f32;
    let zs = vec![0.0f32; size];
    let mut xs = vec![0.0f32; size];
    let mut ys = vec![0.0f32; size];
    let mut image = vec![false; size * size];
    for (j, row) in image.chunks_mut(size).enumerate() {
        for i in 0..size {
            xs[i] = (i as f32 + 0.5) * step - 1.0;
            ys[i] = 1.0 - (j as f32 + 0.5) * step;
        }
        let v = eval
            .eval(&tape, &xs, &ys, &zs)
            .map_err(|e| format!("fidget eval: {e}"))?;
        for (o, v) in row.iter_mut().zip(v) {
            *o = *v < 0.0;
        }
    }
    Ok(PeerRun {
        ms: t.elapsed().as_secs_f64() * 1e3,
        image,
    })
}

/// fidget's JIT, pruned render.
pub(crate) fn jit_pruned(text: &str, size: u32, threads: usize) -> Result<PeerRun, String> {
    pruned::<fidget::jit::JitFunction>(text, size, threads)
}

/// fidget's VM, pruned render.
pub(crate) fn vm_pruned(text: &str, size: u32, threads: usize) -> Result<PeerRun, String> {
    pruned::<fidget::vm::VmFunction>(text, size, threads)
}

/// fidget's JIT, full tape at every pixel.
pub(crate) fn jit_brute(text: &str, size: u32) -> Result<PeerRun, String> {
    brute::<fidget::jit::JitFunction>(text, size as usize)
}

/// fidget's VM, full tape at every pixel.
pub(crate) fn vm_brute(text: &str, size: u32) -> Result<PeerRun, String> {
    brute::<fidget::vm::VmFunction>(text, size as usize)
}
