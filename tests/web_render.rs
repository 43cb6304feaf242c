//! The refine renderer on a browser's WebGPU: `TerrainRenderer` made with its async
//! constructor on the page's device, a cratered level drawn and read back asynchronously,
//! compared with the CPU twin and the exact render (the tolerances of `gpu_render.rs`), and
//! the three passes timed with timestamp queries. WebAssembly only: `scripts/test` runs it
//! with wasm-bindgen-test in headless Chromium (SwiftShader's WebGPU, on the CPU).

#![cfg(target_family = "wasm")]

mod common;

use common::craters::cratered;
use craterfield::field2d::Level;
use craterfield::gpu::{GpuContext, Offscreen, READBACK_FORMAT, Timestamps};
use craterfield::render2d::gpu::{Pipeline, TerrainRenderer, render_to_image_async};
use craterfield::render2d::twin::render_twin;
use craterfield::render2d::{
    Camera, ExactRenderOptions, Reconstruction, RenderOptions, render_exact,
};
use craterfield::visdiff::{DiffOptions, compare};
use glam::Vec2;
use image::RgbaImage;
use wasm_bindgen_test::{console_log, wasm_bindgen_test, wasm_bindgen_test_configure};

wasm_bindgen_test_configure!(run_in_browser);

/// Frames timed for the pass times' tails.
const TIMED_FRAMES: usize = 30;

fn expect_close(name: &str, gpu: &RgbaImage, cpu: &RgbaImage, tol: &DiffOptions) {
    let report = compare(gpu, cpu, tol).expect("comparable images");
    console_log!(
        "{name}: {:.4}% of pixels differ by more than {}, mean {:.3}, max {}",
        100.0 * report.differing_fraction,
        report.pixel_tolerance,
        report.mean,
        report.max
    );
    assert!(report.passed(), "{name}: {}", report.failure_summary());
}

/// Median, p95, p99 and max of `v`, nearest rank.
fn tails(mut v: Vec<f64>) -> [f64; 4] {
    v.sort_by(f64::total_cmp);
    let at = |p: f64| v[((p * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1];
    [at(0.5), at(0.95), at(0.99), v[v.len() - 1]]
}

#[wasm_bindgen_test]
async fn refine_on_webgpu_draws_the_twin_and_the_exact_picture() {
    let ctx = GpuContext::new_async().await.expect(
        "the browser gives a WebGPU adapter and device (run Chromium with --enable-unsafe-webgpu)",
    );
    console_log!("adapter: {} ({:?})", ctx.describe(), ctx.info.driver);
    let level = Level::default_level();
    let terrain = cratered(&level, 300);
    let palette: Vec<[u8; 3]> = level.materials().iter().map(|m| m.color).collect();
    let camera = Camera {
        center: Vec2::new(1400.0, 380.0),
        units_per_pixel: 1.0,
        width: 320,
        height: 180,
    };
    let options = RenderOptions {
        reconstruction: Reconstruction::Refine,
        ..RenderOptions::default()
    };
    let mut renderer =
        TerrainRenderer::new_async(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())
            .await
            .expect("the renderer's pipelines validate on WebGPU");
    renderer
        .prepare(&terrain, &palette, &camera)
        .expect("prepare");
    craterfield::gpu::settle()
        .await
        .expect("the level's field pipelines validate");

    let gpu = render_to_image_async(&renderer, camera.width, camera.height, Pipeline::Reduced)
        .await
        .expect("render and read back");
    let stats = renderer
        .refine_stats_async()
        .await
        .expect("refine counters");
    console_log!(
        "refine: {:.2}% of blocks and {:.2}% of pixels exact",
        100.0 * stats.refined_block_fraction(),
        100.0 * stats.refined_pixel_fraction()
    );
    let tol = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.002,
        max_mean: 0.5,
        ..DiffOptions::default()
    };
    let twin = render_twin(&terrain, &palette, &camera, &options, 0).expect("twin");
    expect_close("refine vs the CPU twin", &gpu, &twin, &tol);
    let exact = render_exact(&terrain, &palette, &camera, &ExactRenderOptions::default())
        .expect("exact render");
    expect_close("refine vs the exact render", &gpu, &exact, &tol);

    let Some(stamps) = Timestamps::new(&ctx.device, &ctx.queue, 2) else {
        panic!("the browser's WebGPU device has no timestamp queries");
    };
    let target = Offscreen::new(&ctx.device, camera.width, camera.height).expect("target");
    let mut passes: [Vec<f64>; 3] = Default::default();
    for _ in 0..TIMED_FRAMES {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let (set, index) = stamps.pair(0).expect("a pair");
        renderer
            .render_timed_passes(&mut encoder, target.view(), set, index)
            .expect("timed frame");
        stamps.encode_resolve(&mut encoder);
        ctx.queue.submit([encoder.finish()]);
        let marks = stamps
            .read_marks_ms_async(&ctx.device)
            .await
            .expect("timestamps");
        for (pass, times) in passes.iter_mut().enumerate() {
            times.push(marks[pass + 1] - marks[pass]);
        }
    }
    for (pass, times) in passes.into_iter().enumerate() {
        let [median, p95, p99, max] = tails(times);
        console_log!(
            "pass {} ({} frames of {}x{}): median {median:.3} ms, p95 {p95:.3}, p99 {p99:.3}, max {max:.3}",
            pass + 1,
            TIMED_FRAMES,
            camera.width,
            camera.height
        );
    }
}
