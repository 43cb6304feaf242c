//! The renderers on a wgpu 29 device made by the caller, as a Bevy 0.19 game hands over its
//! `RenderDevice`: the refine renderer draws a cratered level that matches the CPU twin and
//! the exact render, and the 3D marcher marches a builtin scene that matches the CPU tracer.
//! This workspace's lock resolves wgpu 29 (the project's resolves 30); the library type-checks
//! against either, and these tests show it also draws the same pictures on 29.
//!
//! Without an adapter the tests report themselves ignored, and fail when `CI` is set.

use bevy::math::Vec2;
use craterfield::field2d::{Event, Graph, Level, Sdf, Terrain};
use craterfield::gpu::{READBACK_FORMAT, device_limits};
use craterfield::march3d::compile::{CompileOptions, emit};
use craterfield::march3d::cpu::{self, TraceOptions};
use craterfield::march3d::gpu::Marcher;
use craterfield::march3d::scene::Scene;
use craterfield::render2d::gpu::{Pipeline, TerrainRenderer, render_to_image};
use craterfield::render2d::twin::render_twin;
use craterfield::render2d::{
    Camera, ExactRenderOptions, Reconstruction, RenderOptions, render_exact,
};
use craterfield::visdiff::{DiffOptions, compare};
use image::RgbaImage;
use libtest_mimic::{Arguments, Failed, Trial};

/// The caller's device: made here with this crate's wgpu 29, not by the library.
struct CallerDevice {
    device: wgpu::Device,
    queue: wgpu::Queue,
    name: String,
}

fn caller_device() -> Result<CallerDevice, String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
        .map_err(|e| format!("no adapter: {e}"))?;
    let descriptor = wgpu::DeviceDescriptor {
        label: Some("the caller's device"),
        required_limits: device_limits(&adapter.limits()),
        ..Default::default()
    };
    let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
        .map_err(|e| format!("no device: {e}"))?;
    let info = adapter.get_info();
    Ok(CallerDevice {
        device,
        queue,
        name: format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type),
    })
}

/// The default level after `count` deterministic explosions where the ground is.
fn cratered(level: &Level, count: u32) -> Terrain<Graph> {
    let mut terrain = level.terrain().expect("the default level builds a terrain");
    let b = level.bounds();
    for i in 0..count {
        let x = b.min.x + (b.max.x - b.min.x) * ((i as f32 * 0.618_034).fract());
        let mut y = b.max.y;
        while y > b.min.y && terrain.distance(Vec2::new(x, y)) > 0.0 {
            y -= 8.0;
        }
        let radius = 12.0 + 30.0 * ((i as f32 * 0.414_214).fract());
        let event = Event::carve(Vec2::new(x, y), radius).expect("a finite explosion");
        terrain.apply(event).expect("the explosion applies");
    }
    terrain
}

/// Keeps a rendered picture for a look (in the target's temporary folder).
fn save(name: &str, image: &RgbaImage) {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    if let Err(e) = image.save(&path) {
        eprintln!("could not keep {}: {e}", path.display());
    }
}

fn refine_draws_the_twin(gpu: &CallerDevice) -> Result<(), Failed> {
    let level = Level::default_level();
    let terrain = cratered(&level, 60);
    let palette: Vec<[u8; 3]> = level.materials().iter().map(|m| m.color).collect();
    let b = level.bounds();
    let camera = Camera {
        center: (b.min + b.max) * 0.5,
        units_per_pixel: (b.max.x - b.min.x) / 480.0,
        width: 480,
        height: 270,
    };
    let options = RenderOptions {
        reconstruction: Reconstruction::Refine,
        ..RenderOptions::default()
    };
    let mut renderer =
        TerrainRenderer::new(&gpu.device, &gpu.queue, READBACK_FORMAT, options.clone())?;
    renderer.prepare(&terrain, &palette, &camera)?;
    let image = render_to_image(&renderer, camera.width, camera.height, Pipeline::Reduced)?;
    let twin = render_twin(&terrain, &palette, &camera, &options, 0)?;
    let exact = render_exact(&terrain, &palette, &camera, &ExactRenderOptions::default())?;
    save("refine-wgpu29.png", &image);
    // The tolerance of the project's GPU tests for refine against the twin and the exact render.
    let tolerance = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.002,
        max_mean: 0.5,
        ..DiffOptions::default()
    };
    for (what, reference) in [("the CPU twin", &twin), ("the exact render", &exact)] {
        let report = compare(&image, reference, &tolerance)?;
        eprintln!(
            "refine on wgpu 29 vs {what}: {:.4}% of pixels differ by more than {}, mean {:.3}, max {}",
            100.0 * report.differing_fraction,
            tolerance.pixel_tolerance,
            report.mean,
            report.max
        );
        if !report.passed() {
            return Err(format!("refine vs {what}: {}", report.failure_summary()).into());
        }
    }
    Ok(())
}

fn marcher_draws_the_tracer(gpu: &CallerDevice) -> Result<(), Failed> {
    const SIZE: (u32, u32) = (192, 108);
    let scene = Scene::builtin("sparse")?;
    let camera = scene.camera.camera()?;
    let options = CompileOptions {
        aspect: SIZE.0 as f32 / SIZE.1 as f32,
        height: SIZE.1,
        ..CompileOptions::default()
    };
    let plan = emit(&scene, &camera, &options)?;
    let mut marcher = Marcher::new(&gpu.device, &gpu.queue)?;
    let rgba = marcher.render_to_rgba(&plan, &camera, SIZE.0, SIZE.1)?;
    let traced = cpu::render(&plan, &camera, SIZE.0, SIZE.1, &TraceOptions::default())?;
    let image = RgbaImage::from_raw(SIZE.0, SIZE.1, rgba).ok_or("GPU image size")?;
    let traced = RgbaImage::from_raw(SIZE.0, SIZE.1, traced.rgba).ok_or("CPU image size")?;
    // The tolerance of the project's march3d GPU tests (grazing hits move by a step).
    let tolerance = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.025,
        max_mean: 1.5,
        max_error: f64::INFINITY,
        max_percentile: f64::INFINITY,
        max_flip: f64::INFINITY,
        ..DiffOptions::default()
    };
    save("march3d-wgpu29.png", &image);
    let report = compare(&traced, &image, &tolerance)?;
    eprintln!(
        "march3d on wgpu 29 vs the CPU tracer: {:.3}% of pixels differ by more than {}, mean {:.3}",
        100.0 * report.differing_fraction,
        tolerance.pixel_tolerance,
        report.mean
    );
    if !report.passed() {
        return Err(format!("march3d: {}", report.failure_summary()).into());
    }
    Ok(())
}

fn main() {
    let args = Arguments::from_args();
    let gpu = match caller_device() {
        Ok(gpu) => {
            eprintln!("the caller's wgpu 29 device: {}", gpu.name);
            Some(std::sync::Arc::new(gpu))
        }
        Err(e) if std::env::var_os("CI").is_some() => {
            eprintln!("{e}; CI is set, so a missing adapter fails");
            std::process::exit(1);
        }
        Err(e) => {
            eprintln!("{e}: the GPU tests are reported as ignored");
            None
        }
    };
    type Test = fn(&CallerDevice) -> Result<(), Failed>;
    let tests: [(&str, Test); 2] = [
        ("refine_draws_the_twin", refine_draws_the_twin),
        ("marcher_draws_the_tracer", marcher_draws_the_tracer),
    ];
    let trials = tests
        .into_iter()
        .map(|(name, test)| match &gpu {
            Some(gpu) => {
                let gpu = gpu.clone();
                Trial::test(name, move || test(&gpu))
            }
            None => Trial::test(name, || Ok(())).with_ignored_flag(true),
        })
        .collect();
    libtest_mimic::run(&args, trials).exit();
}
