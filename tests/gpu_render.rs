//! GPU renderer tests on whatever adapter wgpu finds (Mesa's lavapipe in CI): the GPU image
//! against the CPU twin for every mode and scale, golden images, the pipeline cache, and the
//! incremental explosion-grid uploads.
//!
//! Runs on the shared GPU harness (`common::gpu`): a machine without an adapter reports every
//! test as ignored (never as passed); with `CI` set a missing adapter fails instead.

mod common;

use std::path::PathBuf;

use common::craters::{crater, cratered};
use common::gpu::TestResult;
use common::shade_steps::shade_steps;
use craterfield::field2d::{Event, Graph, Level, Terrain};
use craterfield::gpu::READBACK_FORMAT;
use craterfield::gpu::{GpuContext, GpuError, Offscreen, Timestamps};
use craterfield::render2d::emit::EmitError;
use craterfield::render2d::gpu::{Pipeline, render_to_image};
use craterfield::render2d::gpu::{RenderError, TerrainRenderer};
use craterfield::render2d::twin::{exact_field, render_refine, render_twin};
use craterfield::render2d::{
    Camera, ExactRenderOptions, Reconstruction, RenderOptions, Scale, Upsample, render_exact,
};
use craterfield::visdiff::{DiffOptions, DiffReport, check_golden, compare};
use glam::Vec2;
use image::RgbaImage;
use libtest_mimic::Failed;

fn palette(level: &Level) -> Vec<[u8; 3]> {
    level.materials().iter().map(|m| m.color).collect()
}

fn camera(center: Vec2, upp: f32, w: u32, h: u32) -> Camera {
    Camera {
        center,
        units_per_pixel: upp,
        width: w,
        height: h,
    }
}

fn gpu_image(
    ctx: &GpuContext,
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    cam: &Camera,
    options: &RenderOptions,
    pipeline: Pipeline,
) -> Result<RgbaImage, RenderError> {
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())?;
    r.prepare(terrain, palette, cam)?;
    render_to_image(&r, cam.width, cam.height, pipeline)
}

fn out_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-render");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

/// Fails with the report and writes both images and a heat-map when over tolerance.
fn expect_close(name: &str, gpu: &RgbaImage, cpu: &RgbaImage, tol: &DiffOptions) -> TestResult {
    let report: DiffReport = compare(gpu, cpu, tol).map_err(|e| e.to_string())?;
    if report.passed() {
        return Ok(());
    }
    let dir = out_dir();
    let _ = gpu.save(dir.join(format!("{name}.gpu.png")));
    let _ = cpu.save(dir.join(format!("{name}.cpu.png")));
    Err(format!(
        "{name}: GPU differs from the CPU twin: {} (images in {})",
        report.failure_summary(),
        dir.display()
    )
    .into())
}

fn twin_tolerance() -> DiffOptions {
    DiffOptions {
        pixel_tolerance: 12,
        max_differing_fraction: 0.01,
        max_mean: 1.0,
        max_percentile: 12.0,
        ..DiffOptions::default()
    }
}

fn methods() -> Vec<(Reconstruction, Upsample)> {
    vec![
        (Reconstruction::Off, Upsample::Bilinear),
        (Reconstruction::Off, Upsample::BSpline),
        (Reconstruction::Off, Upsample::CatmullRom),
        (Reconstruction::Divergence, Upsample::BSpline),
        (Reconstruction::Planes, Upsample::BSpline),
    ]
}

fn gpu_matches_twin_every_mode_and_scale(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 300);
    let pal = palette(&level);
    let cams = [
        camera(Vec2::new(1400.0, 900.0), 1.0, 320, 180),
        camera(Vec2::new(2700.0, 650.0), 0.75, 256, 144),
    ];
    for (ci, cam) in cams.iter().enumerate() {
        for scale in Scale::ALL {
            for (reconstruction, upsample) in methods() {
                let options = RenderOptions {
                    scale,
                    reconstruction,
                    upsample,
                    ..RenderOptions::default()
                };
                let gpu = gpu_image(ctx, &terrain, &pal, cam, &options, Pipeline::Reduced)
                    .map_err(|e| e.to_string())?;
                let cpu =
                    render_twin(&terrain, &pal, cam, &options, 0).map_err(|e| e.to_string())?;
                let name = format!(
                    "cam{ci}-s{}-{}-{}",
                    scale.divisor(),
                    reconstruction.name(),
                    upsample.name()
                );
                expect_close(&name, &gpu, &cpu, &twin_tolerance())?;
            }
        }
    }
    Ok(())
}

/// Mode refine on the GPU draws the exact picture: every pixel is either proven (sky, or
/// solid with its material, where only the interior depth shade is interpolated) or
/// evaluated exactly, so it matches the CPU's exact render and the CPU twin's refine at the
/// tolerance of float differences, at every scale, and it evaluates only a small part of
/// the frame.
fn refine_matches_exact_and_twin(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 300);
    let pal = palette(&level);
    let cams = [
        camera(Vec2::new(1400.0, 380.0), 1.0, 320, 180),
        camera(Vec2::new(2500.0, 300.0), 0.75, 258, 141),
    ];
    let tol = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.002,
        max_mean: 0.5,
        ..DiffOptions::default()
    };
    for (ci, cam) in cams.iter().enumerate() {
        let exact = render_exact(&terrain, &pal, cam, &ExactRenderOptions::default()).unwrap();
        for scale in Scale::ALL {
            let options = RenderOptions {
                scale,
                reconstruction: Reconstruction::Refine,
                ..RenderOptions::default()
            };
            let mut r =
                TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())
                    .map_err(|e| e.to_string())?;
            r.prepare(&terrain, &pal, cam).map_err(|e| e.to_string())?;
            let gpu = render_to_image(&r, cam.width, cam.height, Pipeline::Reduced)
                .map_err(|e| e.to_string())?;
            let stats = r.refine_stats().map_err(|e| e.to_string())?;
            let name = format!("cam{ci}-s{}-refine", scale.divisor());
            expect_close(&format!("{name}-vs-exact"), &gpu, &exact, &tol)?;
            let twin = render_twin(&terrain, &pal, cam, &options, 0).map_err(|e| e.to_string())?;
            expect_close(&format!("{name}-vs-twin"), &gpu, &twin, &tol)?;
            let blocks = u64::from(cam.width.div_ceil(4)) * u64::from(cam.height.div_ceil(4));
            if stats.blocks != blocks
                || stats.sky_blocks + stats.solid_blocks + stats.refined_blocks != blocks
            {
                return Err(format!("{name}: block counts do not add up: {stats:?}").into());
            }
            if stats.refined_pixel_fraction() > 0.5
                || stats.sky_blocks == 0
                || stats.solid_blocks == 0
            {
                return Err(format!("{name}: the proofs decided too little: {stats:?}").into());
            }
            eprintln!(
                "{name}: {:.2}% of blocks and {:.2}% of pixels exact, {} evaluations",
                100.0 * stats.refined_block_fraction(),
                100.0 * stats.refined_pixel_fraction(),
                stats.exact_evaluations
            );
        }
    }
    Ok(())
}

/// On ground cratered thousands of times, where most blocks are proven from the events of
/// their cells, mode refine on the GPU draws what the GPU's own full-resolution direct pass
/// draws: exact blocks are evaluated by the same code, proven sky and deep blocks have the
/// same colours, and only the depth shade of shaded blocks is interpolated (a wrong proof
/// would turn solid pixels into sky or back, a difference of a hundred levels or more). The
/// GPU proves about as much as the twin, which also reads material margins.
fn refine_on_cratered_ground_is_the_direct_render(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 3000);
    let pal = palette(&level);
    let cam = camera(Vec2::new(1400.0, 380.0), 1.0, 320, 180);
    let options = RenderOptions {
        reconstruction: Reconstruction::Refine,
        ..RenderOptions::default()
    };
    let direct = gpu_image(ctx, &terrain, &pal, &cam, &options, Pipeline::Direct)
        .map_err(|e| e.to_string())?;
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())
        .map_err(|e| e.to_string())?;
    r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
    let refine =
        render_to_image(&r, cam.width, cam.height, Pipeline::Reduced).map_err(|e| e.to_string())?;
    let shade_only = DiffOptions {
        pixel_tolerance: 24,
        max_differing_fraction: 0.0,
        max_mean: 0.5,
        ..DiffOptions::default()
    };
    expect_close("cratered-refine-vs-direct", &refine, &direct, &shade_only)?;
    let gpu = r.refine_stats().map_err(|e| e.to_string())?;
    let (_, twin) = render_refine(&terrain, &pal, &cam, &options, 0).map_err(|e| e.to_string())?;
    eprintln!(
        "cratered: GPU {:.2}% of pixels exact, twin {:.2}%",
        100.0 * gpu.refined_pixel_fraction(),
        100.0 * twin.refined_pixel_fraction()
    );
    if gpu.refined_pixels > twin.refined_pixels * 3 / 2 + 64 {
        return Err(format!("the GPU proved much less than the twin: {gpu:?} vs {twin:?}").into());
    }
    Ok(())
}

/// The interior shade of the GPU's proven solid blocks has no block steps when zoomed
/// out, where the clamp contour of the terrain's distance and the creases under peaks cut
/// the lit rim with hard edges: few pixels off the exact render by more than 8 levels, and
/// the error does not jump across block edges more often than inside blocks.
fn refine_shade_has_no_block_steps(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 600);
    let pal = palette(&level);
    let options = RenderOptions {
        reconstruction: Reconstruction::Refine,
        ..RenderOptions::default()
    };
    let deep = -(options.shade.outline_px + 0.5);
    let b = level.bounds();
    let mut failures = Vec::new();
    for width in [470, 940, 1920] {
        let cam = Camera::fit(b.min, b.max, width);
        let exact = render_exact(&terrain, &pal, &cam, &ExactRenderOptions::default()).unwrap();
        let truth = exact_field(&terrain, &cam, 0).map_err(|e| e.to_string())?;
        let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())
            .map_err(|e| e.to_string())?;
        r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
        let gpu = render_to_image(&r, cam.width, cam.height, Pipeline::Reduced)
            .map_err(|e| e.to_string())?;
        let stats = r.refine_stats().map_err(|e| e.to_string())?;
        let s = shade_steps(&gpu, &exact, &truth.distance_px, deep);
        eprintln!(
            "width {width} (upp {:.2}): {s:?}, {:.2}% of blocks exact, {} evaluations",
            cam.units_per_pixel,
            100.0 * stats.refined_block_fraction(),
            stats.exact_evaluations
        );
        if s.stepped() {
            let dir = out_dir();
            let _ = gpu.save(dir.join(format!("steps-{width}.gpu.png")));
            let _ = exact.save(dir.join(format!("steps-{width}.exact.png")));
            failures.push(format!("width {width}: {s:?}"));
        }
    }
    if failures.is_empty() {
        return Ok(());
    }
    Err(format!(
        "block steps in the interior shade (more than 10 + 0.01% of the interior pixels \
         off by more than 8 levels, or the error jumping across block edges more than \
         twice as often as inside blocks; images in {}): {failures:#?}",
        out_dir().display()
    )
    .into())
}

fn example_levels_match_twin(ctx: &GpuContext) -> TestResult {
    for name in ["caverns", "skyrealm"] {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("levels/{name}.ron"));
        let level = Level::load(&path).map_err(|e| e.to_string())?;
        let terrain = cratered(&level, 100);
        let pal = palette(&level);
        let b = level.bounds();
        let cam = Camera::fit(b.min, b.max, 384);
        let options = RenderOptions::default();
        let gpu = gpu_image(ctx, &terrain, &pal, &cam, &options, Pipeline::Reduced)
            .map_err(|e| e.to_string())?;
        let cpu = render_twin(&terrain, &pal, &cam, &options, 0).map_err(|e| e.to_string())?;
        expect_close(name, &gpu, &cpu, &twin_tolerance())?;
    }
    Ok(())
}

fn direct_matches_exact_reference(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 200);
    let pal = palette(&level);
    let cam = camera(Vec2::new(1300.0, 800.0), 1.0, 320, 200);
    let gpu = gpu_image(
        ctx,
        &terrain,
        &pal,
        &cam,
        &RenderOptions::default(),
        Pipeline::Direct,
    )
    .map_err(|e| e.to_string())?;
    let exact = render_exact(&terrain, &pal, &cam, &ExactRenderOptions::default()).unwrap();
    expect_close("direct-vs-exact", &gpu, &exact, &twin_tolerance())
}

fn golden_images(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 150);
    let pal = palette(&level);
    let cam = camera(Vec2::new(1180.0, 1120.0), 1.0, 256, 160);
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let tol = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.005,
        ..DiffOptions::default()
    };
    for (name, reconstruction, pipeline) in [
        ("gpu-planes", Reconstruction::Planes, Pipeline::Reduced),
        (
            "gpu-divergence",
            Reconstruction::Divergence,
            Pipeline::Reduced,
        ),
        ("gpu-direct", Reconstruction::Planes, Pipeline::Direct),
    ] {
        let options = RenderOptions {
            reconstruction,
            ..RenderOptions::default()
        };
        let img =
            gpu_image(ctx, &terrain, &pal, &cam, &options, pipeline).map_err(|e| e.to_string())?;
        check_golden(name, &img, &dir, &tol).map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn pipeline_cache_hits_on_same_visible_set(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = level.terrain().map_err(|e| e.to_string())?;
    let pal = palette(&level);
    let mut r = TerrainRenderer::new(
        &ctx.device,
        &ctx.queue,
        READBACK_FORMAT,
        RenderOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    let a = r
        .prepare(
            &terrain,
            &pal,
            &camera(Vec2::new(600.0, 500.0), 1.0, 256, 144),
        )
        .map_err(|e| e.to_string())?;
    let b = r
        .prepare(
            &terrain,
            &pal,
            &camera(Vec2::new(604.0, 502.0), 1.0, 256, 144),
        )
        .map_err(|e| e.to_string())?;
    let c = r
        .prepare(
            &terrain,
            &pal,
            &camera(Vec2::new(3300.0, 1200.0), 1.0, 256, 144),
        )
        .map_err(|e| e.to_string())?;
    if a.pipeline_hit || !b.pipeline_hit || c.pipeline_hit {
        return Err(format!(
            "expected miss, hit, miss; got {} {} {}",
            a.pipeline_hit, b.pipeline_hit, c.pipeline_hit
        )
        .into());
    }
    if a.pipeline_key != b.pipeline_key || a.pipeline_key == c.pipeline_key || c.culled_nodes == 0 {
        return Err(format!("keys {a:?} {b:?} {c:?}").into());
    }
    if r.cache_counters() != (1, 2) {
        return Err(format!("counters {:?}", r.cache_counters()).into());
    }
    Ok(())
}

fn uploads_are_incremental(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let mut terrain = cratered(&level, 200);
    let pal = palette(&level);
    let cam = camera(Vec2::new(1400.0, 800.0), 1.0, 256, 144);
    let options = RenderOptions::default();
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())
        .map_err(|e| e.to_string())?;
    let first = r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
    let cells = terrain.grid().dims();
    let total = (cells.0 * cells.1) as usize;
    if first.upload.cells != total || first.upload.events != terrain.events().len() {
        return Err(format!("first upload {:?} (cells {total})", first.upload).into());
    }
    let idle = r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
    if idle.upload.events != 0 || idle.upload.cells != 0 || idle.upload.bytes != 0 {
        return Err(format!("an unchanged terrain uploaded {:?}", idle.upload).into());
    }
    terrain
        .apply(Event::carve(Vec2::new(1400.0, 760.0), 40.0).map_err(|e| e.to_string())?)
        .map_err(|e| e.to_string())?;
    let one = r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
    if one.upload.events != 1 || one.upload.cells == 0 || one.upload.cells > 16 {
        return Err(format!("one explosion uploaded {:?}", one.upload).into());
    }
    let gpu =
        render_to_image(&r, cam.width, cam.height, Pipeline::Reduced).map_err(|e| e.to_string())?;
    let cpu = render_twin(&terrain, &pal, &cam, &options, 0).map_err(|e| e.to_string())?;
    expect_close("after-incremental-upload", &gpu, &cpu, &twin_tolerance())
}

fn errors_are_values(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = level.terrain().map_err(|e| e.to_string())?;
    let pal = palette(&level);
    let mut r = TerrainRenderer::new(
        &ctx.device,
        &ctx.queue,
        READBACK_FORMAT,
        RenderOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    match render_to_image(&r, 64, 64, Pipeline::Reduced) {
        Err(RenderError::NotPrepared) => {}
        other => return Err(format!("render before prepare gave {:?}", other.map(|_| ())).into()),
    }
    for bad in [
        camera(Vec2::new(f32::NAN, 0.0), 1.0, 64, 64),
        camera(Vec2::ZERO, 0.0, 64, 64),
        camera(Vec2::ZERO, 1.0, 0, 64),
    ] {
        match r.prepare(&terrain, &pal, &bad) {
            Err(RenderError::Camera(_)) => {}
            other => return Err(format!("bad camera {bad:?} gave {:?}", other.map(|_| ())).into()),
        }
    }
    match TerrainRenderer::new(
        &ctx.device,
        &ctx.queue,
        wgpu::TextureFormat::Depth32Float,
        RenderOptions::default(),
    ) {
        Err(RenderError::TargetFormat(_)) => {}
        other => return Err(format!("a depth target gave {:?}", other.map(|_| ())).into()),
    }
    // A level whose shader would inline 3^9 copies of a shared node: refused before the
    // driver compiles anything (Mesa's compiler ran out of memory on such a module).
    let mut nodes = String::new();
    for i in 0..9 {
        let next = i + 1;
        nodes += &format!(
            "\"n{i}\": Union([Ref(\"n{next}\"), Translate(offset: (1.0, 0.0), node: Ref(\"n{next}\")), Translate(offset: (0.0, 1.0), node: Ref(\"n{next}\"))]),\n"
        );
    }
    let dag = Level::from_ron(&format!(
        "Level(name: \"dag\", bounds: (min: (0.0, 0.0), max: (1024.0, 1024.0)), \
         materials: [(name: \"soil\", color: (1, 2, 3))], root: Ref(\"n0\"), \
         nodes: {{ {nodes} \"n9\": Circle(center: (500.0, 500.0), radius: 20.0) }})"
    ))
    .map_err(|e| e.to_string())?;
    let dag_terrain = dag.terrain().map_err(|e| e.to_string())?;
    match r.prepare(&dag_terrain, &pal, &camera(Vec2::splat(512.0), 1.0, 64, 64)) {
        Err(RenderError::ShaderTooLarge(EmitError::TooLarge {
            what: "inlined statements",
            ..
        })) => {}
        other => return Err(format!("a 3^9 DAG level gave {:?}", other.map(|_| ())).into()),
    }
    // Targets past the device's limits, of several aspect ratios: an error, never wgpu's
    // validation panic. The readback buffer of the widest one is past `max_buffer_size`
    // while each side is within `max_texture_dimension_2d`.
    let side = ctx.device.limits().max_texture_dimension_2d;
    let rows = ctx.device.limits().max_buffer_size / (u64::from(side) * 4) + 1;
    let mut sizes = vec![(side + 1, 16), (16, side + 1), (0, 16)];
    if rows <= u64::from(side) {
        sizes.push((side, rows as u32));
    }
    for (w, h) in sizes {
        match craterfield::gpu::Offscreen::new(&ctx.device, w, h) {
            Err(GpuError::LimitsTooLow { .. }) => {}
            other => return Err(format!("a {w}x{h} target gave {:?}", other.map(|_| ())).into()),
        }
    }
    Ok(())
}

/// Renders the prepared frame into a fresh texture of `format` by recording the pre-passes
/// and drawing pass 3 into a render pass of the test's own, and reads the bytes back.
fn draw_in_own_pass(
    ctx: &GpuContext,
    r: &TerrainRenderer,
    cam: &Camera,
    format: wgpu::TextureFormat,
) -> Result<Vec<u8>, Failed> {
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("test target"),
        size: wgpu::Extent3d {
            width: cam.width,
            height: cam.height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let row = (cam.width * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test readback"),
        size: u64::from(row) * u64::from(cam.height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    r.encode_prepasses(&mut encoder)
        .map_err(|e| e.to_string())?;
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("the game's pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::RED),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        r.draw(&mut pass).map_err(|e| e.to_string())?;
    }
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(cam.height),
            },
        },
        texture.size(),
    );
    ctx.queue.submit([encoder.finish()]);
    let slice = buffer.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| e.to_string())?;
    let data = slice.get_mapped_range().map_err(|e| e.to_string())?;
    let mut pixels = Vec::new();
    for line in data.chunks(row as usize) {
        pixels.extend_from_slice(&line[..cam.width as usize * 4]);
    }
    Ok(pixels)
}

fn draws_into_the_callers_render_pass_and_srgb_targets(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 100);
    let pal = palette(&level);
    let refine = RenderOptions {
        reconstruction: Reconstruction::Refine,
        ..RenderOptions::default()
    };
    for (options, center) in [
        (RenderOptions::default(), Vec2::new(1250.0, 700.0)),
        (refine, Vec2::new(1250.0, 380.0)),
    ] {
        own_pass_and_srgb_match(ctx, &terrain, &pal, &camera(center, 1.0, 200, 120), options)?;
    }
    Ok(())
}

fn own_pass_and_srgb_match(
    ctx: &GpuContext,
    terrain: &Terrain<Graph>,
    pal: &[[u8; 3]],
    cam: &Camera,
    options: RenderOptions,
) -> TestResult {
    let mode = options.reconstruction.name();
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())
        .map_err(|e| e.to_string())?;
    r.prepare(terrain, pal, cam).map_err(|e| e.to_string())?;
    let own = draw_in_own_pass(ctx, &r, cam, READBACK_FORMAT)?;
    let reference =
        render_to_image(&r, cam.width, cam.height, Pipeline::Reduced).map_err(|e| e.to_string())?;
    if own != reference.as_raw().as_slice() {
        return Err(format!("{mode}: drawing into the caller's pass differs from render()").into());
    }
    // An sRGB target stores the same bytes: the shader hands it linear values.
    let srgb = wgpu::TextureFormat::Rgba8UnormSrgb;
    let mut s =
        TerrainRenderer::new(&ctx.device, &ctx.queue, srgb, options).map_err(|e| e.to_string())?;
    s.prepare(terrain, pal, cam).map_err(|e| e.to_string())?;
    let bytes = draw_in_own_pass(ctx, &s, cam, srgb)?;
    let worst = bytes
        .iter()
        .zip(&own)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap_or(0);
    if worst > 1 {
        return Err(format!(
            "{mode}: an sRGB target differs from the linear one by {worst} levels"
        )
        .into());
    }
    Ok(())
}

/// Per-pass timestamps: four marks in order, and the same picture as an untimed render, in
/// every mode (refine's compute passes sit between pass 1 and pass 3).
fn per_pass_timestamps_are_ordered_and_draw_the_same(ctx: &GpuContext) -> TestResult {
    let Some(stamps) = Timestamps::new(&ctx.device, &ctx.queue, 2) else {
        return Err("this adapter has no timestamp queries: the test cannot time passes".into());
    };
    let level = Level::default_level();
    let terrain = cratered(&level, 60);
    let pal = palette(&level);
    let b = level.bounds();
    let cam = camera((b.min + b.max) * 0.5, 4.0, 320, 180);
    for mode in Reconstruction::ALL {
        let options = RenderOptions {
            reconstruction: mode,
            ..RenderOptions::default()
        };
        let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options)
            .map_err(|e| e.to_string())?;
        r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
        let target =
            Offscreen::new(&ctx.device, cam.width, cam.height).map_err(|e| e.to_string())?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let (set, index) = stamps.pair(0).ok_or("no pair 0")?;
        r.render_timed_passes(&mut encoder, target.view(), set, index)
            .map_err(|e| e.to_string())?;
        stamps.encode_resolve(&mut encoder);
        target.encode_copy(&mut encoder);
        ctx.queue.submit([encoder.finish()]);
        let timed = target.read(&ctx.device).map_err(|e| e.to_string())?;
        let marks = stamps
            .read_marks_ms(&ctx.device)
            .map_err(|e| e.to_string())?;
        let name = mode.name();
        if marks.len() != 4 || marks.windows(2).any(|w| w[1] < w[0]) {
            return Err(format!("{name}: timestamps out of order: {marks:?}").into());
        }
        let untimed = render_to_image(&r, cam.width, cam.height, Pipeline::Reduced)
            .map_err(|e| e.to_string())?;
        if timed != untimed {
            return Err(format!("{name}: the timed render differs from render()").into());
        }
    }
    Ok(())
}

fn resizing_reallocates_and_matches_a_fresh_renderer(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let terrain = cratered(&level, 100);
    let pal = palette(&level);
    let options = RenderOptions::default();
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())
        .map_err(|e| e.to_string())?;
    let small = camera(Vec2::new(1250.0, 700.0), 1.0, 96, 64);
    let large = camera(Vec2::new(1250.0, 700.0), 1.0, 420, 260);
    for cam in [small, large, small] {
        r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
        let img = render_to_image(&r, cam.width, cam.height, Pipeline::Reduced)
            .map_err(|e| e.to_string())?;
        let fresh = gpu_image(ctx, &terrain, &pal, &cam, &options, Pipeline::Reduced)
            .map_err(|e| e.to_string())?;
        if img != fresh {
            return Err(format!(
                "after a resize to {}x{} the frame differs",
                cam.width, cam.height
            )
            .into());
        }
    }
    Ok(())
}

/// A terrain whose event log is compacted between frames (its events renumbered, the
/// dropped ones gone) draws what a fresh renderer of it draws: the mirror re-sends the
/// renumbered lists and events.
fn a_compacted_log_renders_as_a_fresh_upload(ctx: &GpuContext) -> TestResult {
    let level = Level::default_level();
    let b = level.bounds();
    let options = craterfield::field2d::TerrainOptions {
        max_events: 40,
        ..level.terrain_options()
    };
    let mut terrain =
        Terrain::new(level.graph().clone(), b.min, b.max, options).map_err(|e| e.to_string())?;
    let pal = palette(&level);
    let cam = camera(Vec2::new(1400.0, 800.0), 2.0, 320, 180);
    let render = RenderOptions::default();
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, render.clone())
        .map_err(|e| e.to_string())?;
    for round in 0..6u64 {
        crater(&mut terrain, &level, 60, 0x1234_5678 + round);
        r.prepare(&terrain, &pal, &cam).map_err(|e| e.to_string())?;
        let kept = render_to_image(&r, cam.width, cam.height, Pipeline::Reduced)
            .map_err(|e| e.to_string())?;
        let fresh = gpu_image(ctx, &terrain, &pal, &cam, &render, Pipeline::Reduced)
            .map_err(|e| e.to_string())?;
        if kept != fresh {
            return Err(format!("round {round}: the incrementally updated frame differs").into());
        }
    }
    if terrain.history_complete() {
        return Err("the log never compacted".into());
    }
    Ok(())
}

fn main() {
    common::gpu::run(&[
        (
            "refine_matches_exact_and_twin",
            refine_matches_exact_and_twin,
        ),
        (
            "refine_on_cratered_ground_is_the_direct_render",
            refine_on_cratered_ground_is_the_direct_render,
        ),
        (
            "refine_shade_has_no_block_steps",
            refine_shade_has_no_block_steps,
        ),
        (
            "gpu_matches_twin_every_mode_and_scale",
            gpu_matches_twin_every_mode_and_scale,
        ),
        ("example_levels_match_twin", example_levels_match_twin),
        (
            "direct_matches_exact_reference",
            direct_matches_exact_reference,
        ),
        ("golden_images", golden_images),
        (
            "pipeline_cache_hits_on_same_visible_set",
            pipeline_cache_hits_on_same_visible_set,
        ),
        ("uploads_are_incremental", uploads_are_incremental),
        ("errors_are_values", errors_are_values),
        (
            "draws_into_the_callers_render_pass_and_srgb_targets",
            draws_into_the_callers_render_pass_and_srgb_targets,
        ),
        (
            "per_pass_timestamps_are_ordered_and_draw_the_same",
            per_pass_timestamps_are_ordered_and_draw_the_same,
        ),
        (
            "resizing_reallocates_and_matches_a_fresh_renderer",
            resizing_reallocates_and_matches_a_fresh_renderer,
        ),
        (
            "a_compacted_log_renders_as_a_fresh_upload",
            a_compacted_log_renders_as_a_fresh_upload,
        ),
    ]);
}
