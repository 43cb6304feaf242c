//! The 3D raymarcher on a browser's WebGPU: every builtin scene compiled (the paper scenes
//! with the paper's preset, the worlds with every optimization), marched by `Marcher` on the
//! page's device with its async constructor and readback, and compared with the CPU tracer
//! at the tolerance of `march3d_gpu.rs`. WebAssembly only: `scripts/test` runs it with
//! wasm-bindgen-test in headless Chromium (SwiftShader's WebGPU, on the CPU).

#![cfg(target_family = "wasm")]

use craterfield::gpu::GpuContext;
use craterfield::march3d::compile::{CompileOptions, emit};
use craterfield::march3d::cpu::{self, TraceOptions};
use craterfield::march3d::gpu::Marcher;
use craterfield::march3d::scene::{BUILTIN, Lighting, Scene};
use craterfield::visdiff::{DiffOptions, compare};
use image::RgbaImage;
use wasm_bindgen_test::{console_log, wasm_bindgen_test, wasm_bindgen_test_configure};

wasm_bindgen_test_configure!(run_in_browser);

const SIZE: (u32, u32) = (256, 144);

#[wasm_bindgen_test]
async fn every_builtin_scene_marches_on_webgpu_as_on_the_cpu() {
    let ctx = GpuContext::new_async()
        .await
        .expect("the browser gives a WebGPU adapter and device");
    let mut marcher = Marcher::new_async(&ctx.device, &ctx.queue)
        .await
        .expect("marcher");
    // The tolerance of tests/march3d_gpu.rs, which says why: the GPU's own roundings move
    // grazing hits and shadow edges by a step.
    let options = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.025,
        max_mean: 1.5,
        max_error: f64::INFINITY,
        max_percentile: f64::INFINITY,
        max_flip: f64::INFINITY,
        ..DiffOptions::default()
    };
    for name in BUILTIN {
        let scene = Scene::builtin(name).expect("builtin scene");
        let camera = scene.camera.camera().expect("builtin camera");
        let preset = match scene.lighting {
            Lighting::Paper(_) => CompileOptions::paper(),
            Lighting::World(_) => CompileOptions::default(),
        };
        let opts = CompileOptions {
            aspect: SIZE.0 as f32 / SIZE.1 as f32,
            height: SIZE.1,
            ..preset
        };
        let plan = emit(&scene, &camera, &opts).expect("emit");
        let started = web_time::Instant::now();
        let gpu = marcher
            .render_to_rgba_async(&plan, &camera, SIZE.0, SIZE.1)
            .await
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let gpu_ms = started.elapsed().as_secs_f64() * 1e3;
        let cpu = cpu::render(&plan, &camera, SIZE.0, SIZE.1, &TraceOptions::default())
            .expect("CPU tracer");
        let gpu = RgbaImage::from_raw(SIZE.0, SIZE.1, gpu).expect("GPU image size");
        let cpu = RgbaImage::from_raw(SIZE.0, SIZE.1, cpu.rgba).expect("CPU image size");
        let report = compare(&cpu, &gpu, &options).expect("comparable images");
        console_log!(
            "{name}: {:.3}% of pixels differ by > {} levels, mean {:.3}, max {} \
             ({gpu_ms:.0} ms from submission to pixels, pipeline included)",
            100.0 * report.differing_fraction,
            options.pixel_tolerance,
            report.mean,
            report.max
        );
        assert!(report.passed(), "{name}: {}", report.failure_summary());
    }
}
