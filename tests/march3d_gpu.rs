//! The GPU raymarcher on whatever adapter wgpu finds (Mesa's lavapipe in CI): each scene
//! rendered on the GPU against the CPU tracer with the visual diff, the shader cache, the
//! caller's-encoder path, and errors for bad input.
//!
//! Runs on the shared GPU harness (`common::gpu`): a machine without an adapter reports every
//! test as ignored (never as passed); with `CI` set a missing adapter fails instead.

mod common;
mod march3d_plans;

use std::path::PathBuf;

use common::gpu::TestResult;
use craterfield::emit::plan3d::Plan;
use craterfield::gpu::{GpuContext, Timestamps};
use craterfield::march3d::compile::{CompileOptions, emit};
use craterfield::march3d::cpu::{self, TraceOptions};
use craterfield::march3d::gpu::{MarchGpuError, Marcher};
use craterfield::march3d::scene::{BUILTIN, Lighting, Scene};
use craterfield::visdiff::{DiffOptions, compare};
use image::RgbaImage;
use march3d_plans::all_plans;

/// Small images: lavapipe runs the shader on the CPU and the paper scenes march up to 3000
/// steps per ray.
const SIZE: (u32, u32) = (256, 144);

/// Where the tests leave their pictures for people to look at.
fn out_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("march3d_gpu");
    std::fs::create_dir_all(&dir).expect("output directory");
    dir
}

fn render(ctx: &GpuContext, plan: &Plan, camera: &craterfield::march3d::Camera3d) -> RgbaImage {
    let mut marcher = Marcher::new(&ctx.device, &ctx.queue).expect("marcher");
    let (pixels, ms) = marcher
        .render_timed(plan, camera, SIZE.0, SIZE.1)
        .expect("render");
    eprintln!("  {:.1} ms", ms);
    RgbaImage::from_raw(SIZE.0, SIZE.1, pixels).expect("image size")
}

fn every_plan_renders(ctx: &GpuContext) -> TestResult {
    for (name, plan, camera) in all_plans() {
        let image = render(ctx, &plan, &camera);
        let path = out_dir().join(format!("{name}_gpu.png"));
        image.save(&path)?;
        eprintln!("{name}: {}", path.display());
    }
    Ok(())
}

/// The plans of the comparison: every builtin scene (the paper scenes with the paper
/// preset, the worlds with every optimization on and with none) and the hand-built plans.
fn comparison_plans() -> Vec<(String, Plan, craterfield::march3d::Camera3d)> {
    let mut out = Vec::new();
    for name in BUILTIN {
        let scene = Scene::builtin(name).expect("builtin scene");
        let camera = scene.camera.camera().expect("builtin camera");
        let aspect = SIZE.0 as f32 / SIZE.1 as f32;
        let presets = match scene.lighting {
            Lighting::Paper(_) => vec![("", CompileOptions::paper())],
            Lighting::World(_) => vec![
                ("-all", CompileOptions::default()),
                ("-naive", CompileOptions::naive()),
            ],
        };
        for (suffix, opts) in presets {
            let opts = CompileOptions { aspect, ..opts };
            let plan = emit(&scene, &camera, &opts).expect("emit");
            out.push((format!("{name}{suffix}"), plan, camera));
        }
    }
    out.extend(
        all_plans()
            .into_iter()
            .map(|(name, plan, camera)| (format!("hand-{name}"), plan, camera)),
    );
    out
}

/// The GPU image against the CPU tracer's. Both execute the same plan with the same
/// formulas in f32, but not the same roundings: the GPU contracts multiply-adds its own
/// way and has its own `exp`, `log`, `pow`, `sqrt`, the CPU uses polynomial `exp`, `log`,
/// `pow`, `sin`. Over smooth regions that moves a colour by a level or two (mean error
/// under 1.5 levels: no region may drift). Where a ray grazes a surface, an ulp decides at
/// which step the distance drops under the hit threshold (which grows with `t` in the
/// worlds), and the hit point moves along the surface by up to a step; the worlds' hard
/// terrain-and-bounds shadow test then flips pixels along every bounding sphere's shadow
/// edge, as the Mandelbulb's fractal surface flips pixels along its detail. Measured on
/// lavapipe: at most 1.7% of the pixels (forest, every optimization) differ by more than
/// 8 levels, most scenes under 0.1%; 2.5% bounds that, where a shifted, missing or
/// differently lit object changes far more.
fn gpu_matches_the_cpu_tracer(ctx: &GpuContext) -> TestResult {
    let options = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.025,
        max_mean: 1.5,
        max_error: f64::INFINITY,
        percentile: 99.0,
        max_percentile: f64::INFINITY,
        max_flip: f64::INFINITY,
        ..DiffOptions::default()
    };
    let mut failures = Vec::new();
    let mut marcher = Marcher::new(&ctx.device, &ctx.queue)?;
    for (name, plan, camera) in comparison_plans() {
        let (gpu, ms) = marcher.render_timed(&plan, &camera, SIZE.0, SIZE.1)?;
        let cpu = cpu::render(&plan, &camera, SIZE.0, SIZE.1, &TraceOptions::default())?;
        let gpu = RgbaImage::from_raw(SIZE.0, SIZE.1, gpu).ok_or("GPU image size")?;
        let cpu = RgbaImage::from_raw(SIZE.0, SIZE.1, cpu.rgba).ok_or("CPU image size")?;
        gpu.save(out_dir().join(format!("{name}_gpu.png")))?;
        cpu.save(out_dir().join(format!("{name}_cpu.png")))?;
        let report = compare(&cpu, &gpu, &options)?;
        eprintln!(
            "{name}: {:.3}% of pixels differ by > {} levels, mean {:.3}, p99 {}, max {} ({ms:.1} ms {})",
            report.differing_fraction * 100.0,
            options.pixel_tolerance,
            report.mean,
            report.percentile_value,
            report.max,
            if marcher.gpu_timestamps() {
                "GPU"
            } else {
                "wall"
            }
        );
        if !report.passed() {
            failures.push(format!("{name}: {}", report.failure_summary()));
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failures.join("\n").into())
    }
}

fn bad_input_is_an_error(ctx: &GpuContext) -> TestResult {
    let mut marcher = Marcher::new(&ctx.device, &ctx.queue)?;
    let (_, plan, camera) = all_plans().remove(0);
    let zero = marcher.render_to_rgba(&plan, &camera, 0, 10);
    assert!(matches!(zero, Err(MarchGpuError::Size { .. })), "{zero:?}");
    // Past a side, past the pixel budget at the largest side, and every aspect ratio.
    for (w, h) in [
        (1 << 20, 10),
        (16_384, 16_384),
        (16_384, 4_097),
        (4_097, 16_384),
    ] {
        let huge = marcher.render_to_rgba(&plan, &camera, w, h);
        assert!(
            matches!(huge, Err(MarchGpuError::Size { .. })),
            "{w}x{h}: {huge:?}"
        );
    }
    let mut bad_camera = camera;
    bad_camera.position.x = f32::NAN;
    let nan = marcher.render_to_rgba(&plan, &bad_camera, 8, 8);
    assert!(matches!(nan, Err(MarchGpuError::Camera)), "{nan:?}");
    let mut bad_plan = plan.clone();
    bad_plan.march.hit = f32::INFINITY;
    bad_plan.key ^= 1;
    let err = marcher.render_to_rgba(&bad_plan, &camera, 8, 8);
    assert!(matches!(err, Err(MarchGpuError::Plan(_))), "{err:?}");
    Ok(())
}

fn the_cache_hits_on_an_unchanged_key_and_misses_on_a_new_one(ctx: &GpuContext) -> TestResult {
    let mut marcher = Marcher::new(&ctx.device, &ctx.queue)?;
    let (_, plan, camera) = all_plans().remove(0);
    let first = marcher.render_to_rgba(&plan, &camera, 32, 18)?;
    assert_eq!(
        marcher.cache_counters(),
        (0, 1),
        "the first render compiles"
    );
    // A moved camera with the same key is the same shader.
    let mut moved = camera;
    moved.position.x += 0.25;
    let second = marcher.render_to_rgba(&plan, &moved, 32, 18)?;
    assert_eq!(
        marcher.cache_counters(),
        (1, 1),
        "an unchanged key is a hit"
    );
    assert_ne!(first, second, "the camera still moved");
    let mut other = plan.clone();
    other.key ^= 0xff;
    other.nodes.pop();
    marcher.render_to_rgba(&other, &camera, 32, 18)?;
    assert_eq!(marcher.cache_counters(), (1, 2), "a new key is a miss");
    let again = marcher.render_to_rgba(&plan, &camera, 32, 18)?;
    assert_eq!(marcher.cache_counters(), (2, 2), "both stay cached");
    assert_eq!(first, again, "the cached pipeline renders the same pixels");
    Ok(())
}

/// A storage texture of the caller's, rendered through `encode_timed` on the caller's
/// encoder, holds the same pixels as `render_to_rgba`, with the pass's two timestamps in
/// order where the device has them; other formats are refused.
fn encoding_into_the_callers_texture_matches(ctx: &GpuContext) -> TestResult {
    let (w, h) = (40, 24);
    let mut marcher = Marcher::new(&ctx.device, &ctx.queue)?;
    let (_, plan, camera) = all_plans().remove(0);
    let expected = marcher.render_to_rgba(&plan, &camera, w, h)?;
    let make = |format, usage| {
        ctx.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("caller's target"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC;
    let texture = make(wgpu::TextureFormat::Rgba8Unorm, usage);
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let stamps = Timestamps::new(&ctx.device, &ctx.queue, 1);
    let pair = stamps.as_ref().and_then(|s| s.pair(0));
    marcher.encode_timed(&mut encoder, &plan, &camera, &view, pair)?;
    if let Some(s) = &stamps {
        s.encode_resolve(&mut encoder);
    }
    let row = (w * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("caller's readback"),
        size: u64::from(row * h),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(h),
            },
        },
        texture.size(),
    );
    ctx.queue.submit([encoder.finish()]);
    buffer
        .slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.expect("map"));
    ctx.device.poll(wgpu::PollType::wait_indefinitely())?;
    let got: Vec<u8> = buffer
        .slice(..)
        .get_mapped_range()?
        .chunks(row as usize)
        .flat_map(|line| line[..(w * 4) as usize].to_vec())
        .collect();
    assert_eq!(got, expected, "encode_timed() and render_to_rgba() differ");
    if let Some(s) = &stamps {
        let ms = s.read_ms(&ctx.device)?;
        assert!(
            ms.len() == 1 && (0.0..60_000.0).contains(&ms[0]),
            "pass time {ms:?}"
        );
    }
    let srgb = make(
        wgpu::TextureFormat::Rgba8UnormSrgb,
        wgpu::TextureUsages::COPY_SRC,
    );
    let srgb_view = srgb.create_view(&wgpu::TextureViewDescriptor::default());
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let refused = marcher.encode(&mut encoder, &plan, &camera, &srgb_view);
    assert!(
        matches!(refused, Err(MarchGpuError::Target { .. })),
        "{refused:?}"
    );
    Ok(())
}

fn main() {
    common::gpu::run(&[
        ("gpu_matches_the_cpu_tracer", gpu_matches_the_cpu_tracer),
        ("every_plan_renders", every_plan_renders),
        (
            "the_cache_hits_on_an_unchanged_key_and_misses_on_a_new_one",
            the_cache_hits_on_an_unchanged_key_and_misses_on_a_new_one,
        ),
        (
            "encoding_into_the_callers_texture_matches",
            encoding_into_the_callers_texture_matches,
        ),
        ("bad_input_is_an_error", bad_input_is_an_error),
    ]);
}
