//! `craterfield bench render2d`: frame times at 1920x1080 on the default level after 10,000
//! explosions, side by side in one run on the adapter wgpu finds: full-resolution direct
//! evaluation vs the reduced-scale pipeline at every scale and mode (GPU time from timestamp
//! queries where the device has them, else wall time with a sync per frame), and the CPU
//! twin's frame time. The pairs the targets compare (planes and refine at 1/16, on each
//! side) take their frames in turn, so that the machine's drift falls on both alike.

use std::process::ExitCode;
use std::time::Instant;

use craterfield::field2d::{Graph, Level, Terrain};
use craterfield::gpu::{GpuContext, GpuError, Offscreen, READBACK_FORMAT, Timestamps};
use craterfield::render2d::gpu::{RenderError, TerrainRenderer};
use craterfield::render2d::twin::{render_direct, render_refine, render_twin};
use craterfield::render2d::{Camera, Reconstruction, RefineStats, RenderOptions, Scale, Upsample};
use glam::Vec2;
use serde::Serialize;

use crate::barrage;
use crate::tails::Tails;

/// Options of `bench render2d`.
#[derive(clap::Args, Debug, Clone)]
pub(crate) struct Options {
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Explosions fired into the default level first.
    #[arg(long, default_value_t = 10_000)]
    pub explosions: usize,
    /// Timed frames per configuration (after two warm-up frames).
    #[arg(long, default_value_t = 8)]
    pub frames: u32,
    /// Image width.
    #[arg(long, default_value_t = 1920)]
    pub width: u32,
    /// Image height.
    #[arg(long, default_value_t = 1080)]
    pub height: u32,
    /// Time the CPU rows only (no adapter is asked for): for profiling the twin.
    #[arg(long)]
    pub cpu_only: bool,
}

#[derive(Serialize)]
struct Row {
    pipeline: &'static str,
    scale: u32,
    mode: String,
    /// Median ms per frame.
    ms: f64,
    p95: f64,
    p99: f64,
    max: f64,
}

impl Row {
    fn new(pipeline: &'static str, scale: u32, mode: &str, t: Tails) -> Row {
        Row {
            pipeline,
            scale,
            mode: mode.into(),
            ms: t.median,
            p95: t.p95,
            p99: t.p99,
            max: t.max,
        }
    }
}

#[derive(Serialize)]
struct Report {
    adapter: String,
    timing: &'static str,
    rows: Vec<Row>,
    cpu_twin_ms: f64,
    cpu_twin_threads: usize,
    cpu_rows: Vec<CpuRow>,
    refine: RefineStats,
    /// What the GPU's refine did at 1/16 (absent without an adapter).
    gpu_refine: Option<RefineStats>,
}

const MODES: [(Reconstruction, Upsample, &str); 5] = [
    (Reconstruction::Off, Upsample::Bilinear, "off-bilinear"),
    (Reconstruction::Off, Upsample::BSpline, "off"),
    (Reconstruction::Divergence, Upsample::BSpline, "divergence"),
    (Reconstruction::Planes, Upsample::BSpline, "planes"),
    (Reconstruction::Refine, Upsample::BSpline, "refine"),
];

/// Tails `frames` frames recorded by `record`: GPU timestamps when available, else wall
/// time of submit + wait.
type Timestamp<'a> = Option<(&'a wgpu::QuerySet, u32)>;

/// Records one frame's commands, with the timestamp pair to write if any.
trait Record: FnMut(&mut wgpu::CommandEncoder, Timestamp<'_>) -> Result<(), RenderError> {}
impl<T: FnMut(&mut wgpu::CommandEncoder, Timestamp<'_>) -> Result<(), RenderError>> Record for T {}

fn encode_frame(
    ctx: &GpuContext,
    record: &mut dyn Record,
    ts: Timestamp<'_>,
) -> Result<wgpu::CommandBuffer, RenderError> {
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    record(&mut encoder, ts)?;
    Ok(encoder.finish())
}

fn wait(ctx: &GpuContext) -> Result<(), GpuError> {
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map(|_| ())
        .map_err(|e| GpuError::DeviceLost(e.to_string()))
}

/// Tails `frames` frames recorded by `record` after two warm-up frames: GPU timestamps when
/// available, else wall time of submit + wait.
fn time_frames(
    ctx: &GpuContext,
    frames: u32,
    mut record: impl Record,
) -> Result<Tails, RenderError> {
    let [times] = time_interleaved(ctx, frames, [&mut record])?;
    Ok(times)
}

/// [`time_frames`] for several configurations at once, their frames taken in turn, so
/// that a machine that slows down or speeds up during the run does so for all of them
/// alike (the targets compare such rows).
fn time_interleaved<const N: usize>(
    ctx: &GpuContext,
    frames: u32,
    mut records: [&mut dyn Record; N],
) -> Result<[Tails; N], RenderError> {
    for _ in 0..2 {
        for record in records.iter_mut() {
            ctx.queue.submit([encode_frame(ctx, *record, None)?]);
            wait(ctx)?;
        }
    }
    let stamps: Option<Vec<Timestamps>> = records
        .iter()
        .map(|_| Timestamps::new(&ctx.device, &ctx.queue, frames))
        .collect();
    match stamps {
        Some(stamps) => {
            for i in 0..frames {
                for (record, ts) in records.iter_mut().zip(&stamps) {
                    ctx.queue.submit([encode_frame(ctx, *record, ts.pair(i))?]);
                    wait(ctx)?;
                }
            }
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
            for ts in &stamps {
                ts.encode_resolve(&mut encoder);
            }
            ctx.queue.submit([encoder.finish()]);
            let ms = stamps
                .iter()
                .map(|ts| ts.read_ms(&ctx.device))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(per_configuration(ms))
        }
        None => {
            let mut ms = vec![Vec::new(); N];
            for _ in 0..frames {
                for (record, ms) in records.iter_mut().zip(&mut ms) {
                    let t = Instant::now();
                    ctx.queue.submit([encode_frame(ctx, *record, None)?]);
                    wait(ctx)?;
                    ms.push(t.elapsed().as_secs_f64() * 1e3);
                }
            }
            Ok(per_configuration(ms))
        }
    }
}

/// The times of each of `N` configurations, from their frame times (one list each).
fn per_configuration<const N: usize>(mut ms: Vec<Vec<f64>>) -> [Tails; N] {
    std::array::from_fn(|i| Tails::of(ms.get_mut(i).map(std::mem::take).unwrap_or_default()))
}

fn scene(explosions: usize) -> Result<(Level, Terrain<Graph>), String> {
    let level = Level::default_level();
    let mut terrain = level.terrain().map_err(|e| e.to_string())?;
    barrage::fire_seeded(&level, &mut terrain, explosions, 0x005e_ed2d, |_| {});
    Ok((level, terrain))
}

fn gpu_rows(
    ctx: &GpuContext,
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
    frames: u32,
) -> Result<(Vec<Row>, Option<RefineStats>), RenderError> {
    let target = Offscreen::new(&ctx.device, camera.width, camera.height)?;
    let format = READBACK_FORMAT;
    let mut rows = Vec::new();
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, format, RenderOptions::default())?;
    r.prepare(terrain, palette, camera)?;
    let ms = time_frames(ctx, frames.min(4), |enc, ts| {
        r.render_direct(enc, target.view(), ts)
    })?;
    rows.push(Row::new("full-res", 1, "direct", ms));
    let mut refine = None;
    for scale in Scale::ALL {
        for (reconstruction, upsample, name) in MODES {
            // The target's pair at 1/16 is timed together, below.
            let paired = [Reconstruction::Planes, Reconstruction::Refine];
            if scale == Scale::Sixteenth && paired.contains(&reconstruction) {
                continue;
            }
            r.set_options(RenderOptions {
                scale,
                reconstruction,
                upsample,
                ..RenderOptions::default()
            });
            r.prepare(terrain, palette, camera)?;
            let ms = time_frames(ctx, frames, |enc, ts| {
                r.render_timed(enc, target.view(), ts)
            })?;
            rows.push(Row::new("reduced", scale.divisor(), name, ms));
        }
        if scale == Scale::Sixteenth {
            let (planes, refined, stats) =
                sixteenth_pair(ctx, terrain, palette, camera, target.view(), frames)?;
            rows.push(Row::new("reduced", 16, "planes", planes));
            rows.push(Row::new("reduced", 16, "refine", refined));
            refine = Some(stats);
        }
    }
    Ok((rows, refine))
}

/// The 1/16 `planes` and `refine` frames, timed in turn (the target compares them), and
/// what refine did.
fn sixteenth_pair(
    ctx: &GpuContext,
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
    view: &wgpu::TextureView,
    frames: u32,
) -> Result<(Tails, Tails, RefineStats), RenderError> {
    let renderer = |reconstruction| -> Result<TerrainRenderer, RenderError> {
        let options = RenderOptions {
            scale: Scale::Sixteenth,
            reconstruction,
            upsample: Upsample::BSpline,
            ..RenderOptions::default()
        };
        let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options)?;
        r.prepare(terrain, palette, camera)?;
        Ok(r)
    };
    let (planes, refine) = (
        renderer(Reconstruction::Planes)?,
        renderer(Reconstruction::Refine)?,
    );
    let [planes_t, refine_t] = time_interleaved(
        ctx,
        frames,
        [
            &mut |enc: &mut wgpu::CommandEncoder, ts: Timestamp<'_>| {
                planes.render_timed(enc, view, ts)
            },
            &mut |enc: &mut wgpu::CommandEncoder, ts: Timestamp<'_>| {
                refine.render_timed(enc, view, ts)
            },
        ],
    )?;
    Ok((planes_t, refine_t, refine.refine_stats()?))
}

/// Tails `frames` CPU frames of `render` after two warm-up frames.
fn cpu_times(frames: u32, mut render: impl FnMut() -> Result<(), String>) -> Result<Tails, String> {
    let [times] = cpu_times_interleaved(frames, [&mut render])?;
    Ok(times)
}

/// A CPU frame renderer being timed.
type CpuRender<'a> = dyn FnMut() -> Result<(), String> + 'a;

/// [`cpu_times`] for several renderers, their frames taken in turn (see [`time_interleaved`]).
fn cpu_times_interleaved<const N: usize>(
    frames: u32,
    mut renders: [&mut CpuRender<'_>; N],
) -> Result<[Tails; N], String> {
    let mut ms = vec![Vec::new(); N];
    for i in 0..frames + 2 {
        for (render, ms) in renders.iter_mut().zip(&mut ms) {
            let t = Instant::now();
            render()?;
            if i >= 2 {
                ms.push(t.elapsed().as_secs_f64() * 1e3);
            }
        }
    }
    Ok(per_configuration(ms))
}

/// One CPU configuration's frame times.
#[derive(Serialize)]
struct CpuRow {
    pipeline: &'static str,
    scale: u32,
    mode: &'static str,
    times: Tails,
}

/// The CPU rows: full-resolution direct evaluation, the twin at 1/16 in modes planes and
/// refine; and what refine did.
fn cpu_rows(
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
    frames: u32,
) -> Result<(Vec<CpuRow>, RefineStats), String> {
    let err = |e: craterfield::render2d::TwinError| e.to_string();
    let shade = RenderOptions::default().shade;
    let direct = cpu_times(frames.min(4), || {
        render_direct(terrain, palette, camera, &shade, 0)
            .map(|_| ())
            .map_err(err)
    })?;
    let planes = RenderOptions {
        reconstruction: Reconstruction::Planes,
        ..RenderOptions::default()
    };
    let refine = RenderOptions {
        reconstruction: Reconstruction::Refine,
        ..RenderOptions::default()
    };
    let mut stats = RefineStats::default();
    // In turn, as on the GPU: the target compares these two.
    let [planes_t, refine_t] = cpu_times_interleaved(
        frames,
        [
            &mut || {
                render_twin(terrain, palette, camera, &planes, 0)
                    .map(|_| ())
                    .map_err(err)
            },
            &mut || {
                stats = render_refine(terrain, palette, camera, &refine, 0)
                    .map_err(err)?
                    .1;
                Ok(())
            },
        ],
    )?;
    let row = |pipeline, scale, mode, times| CpuRow {
        pipeline,
        scale,
        mode,
        times,
    };
    Ok((
        vec![
            row("full-res", 1, "direct", direct),
            row("twin", 16, "planes", planes_t),
            row("twin", 16, "refine", refine_t),
        ],
        stats,
    ))
}

pub(crate) fn run(options: &Options) -> Result<ExitCode, String> {
    let (level, terrain) = scene(options.explosions)?;
    let palette: Vec<[u8; 3]> = level.materials().iter().map(|m| m.color).collect();
    let b = level.bounds();
    let camera = Camera {
        center: (b.min + b.max) * 0.5 + Vec2::new(0.0, -150.0),
        units_per_pixel: 1.0,
        width: options.width,
        height: options.height,
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (cpu_rows, refine) = cpu_rows(&terrain, &palette, &camera, options.frames)?;
    let cpu_twin_ms = cpu_rows[1].times.median;
    let context = (!options.cpu_only).then(GpuContext::new);
    let (adapter, timing, (rows, gpu_refine)) = match context {
        None => (
            "not asked for (--cpu-only)".into(),
            "none",
            (Vec::new(), None),
        ),
        Some(Ok(ctx)) => {
            let timing = if ctx.timestamps {
                "GPU timestamp queries"
            } else {
                "wall time, submit + wait per frame"
            };
            let rows = gpu_rows(&ctx, &terrain, &palette, &camera, options.frames)
                .map_err(|e| e.to_string())?;
            (ctx.describe(), timing, rows)
        }
        Some(Err(e)) => (format!("none ({e})"), "none", (Vec::new(), None)),
    };
    let report = Report {
        adapter,
        timing,
        rows,
        cpu_twin_ms,
        cpu_twin_threads: threads,
        cpu_rows,
        refine,
        gpu_refine,
    };
    if options.json {
        println!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        print_table(&report, options);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(report: &Report, options: &Options) {
    println!(
        "bench render2d: default level after {} explosions, {}x{}",
        options.explosions, options.width, options.height
    );
    println!("adapter: {} (timing: {})", report.adapter, report.timing);
    if !report.rows.is_empty() {
        println!(
            "{:<10} {:>5} {:<14} {:>10} {:>10} {:>10} {:>10}",
            "pipeline", "scale", "mode", "median ms", "p95", "p99", "max"
        );
    }
    for r in &report.rows {
        println!(
            "{:<10} {:>5} {:<14} {:>10.3} {:>10.3} {:>10.3} {:>10.3}",
            r.pipeline,
            format!("1/{}", r.scale),
            r.mode,
            r.ms,
            r.p95,
            r.p99,
            r.max
        );
    }
    println!("CPU, {} threads:", report.cpu_twin_threads);
    println!(
        "{:<10} {:>5} {:<14} {:>10} {:>10} {:>10} {:>10}",
        "pipeline", "scale", "mode", "median ms", "p95", "p99", "max"
    );
    for r in &report.cpu_rows {
        let t = r.times;
        println!(
            "{:<10} {:>5} {:<14} {:>10.3} {:>10.3} {:>10.3} {:>10.3}",
            r.pipeline,
            format!("1/{}", r.scale),
            r.mode,
            t.median,
            t.p95,
            t.p99,
            t.max
        );
    }
    print_refine("CPU twin", &report.refine);
    if let Some(s) = &report.gpu_refine {
        print_refine("GPU", s);
    }
    let full = report
        .rows
        .iter()
        .find(|r| r.pipeline == "full-res")
        .map(|r| r.ms);
    let sixteenth = report
        .rows
        .iter()
        .find(|r| r.pipeline == "reduced" && r.scale == 16 && r.mode == "planes")
        .map(|r| r.ms);
    if let (Some(full), Some(s16)) = (full, sixteenth) {
        let speedup = full / s16;
        let verdict = if speedup >= 5.0 { "met" } else { "NOT met" };
        println!("1/16 planes vs full-res direct: {speedup:.1}x faster (target >= 5x: {verdict})");
    }
    let cpu = |mode: &str| {
        report
            .cpu_rows
            .iter()
            .find(|r| r.mode == mode)
            .map(|r| r.times.median)
    };
    if let (Some(direct), Some(planes), Some(refine)) =
        (cpu("direct"), cpu("planes"), cpu("refine"))
    {
        print_refine_targets("CPU", direct, planes, refine);
    }
    let gpu = |mode: &str| {
        report
            .rows
            .iter()
            .find(|r| r.scale == 16 && r.mode == mode)
            .map(|r| r.ms)
    };
    match (full, gpu("planes"), gpu("refine")) {
        (Some(direct), Some(planes), Some(refine)) => {
            print_refine_targets("GPU", direct, planes, refine);
        }
        _ => println!("GPU refine: not measured (no adapter)"),
    }
    let verdict = if report.cpu_twin_ms < 15.0 {
        "met"
    } else {
        "NOT met"
    };
    println!("CPU twin target < 15 ms per 1080p frame: {verdict}");
}

fn print_refine(what: &str, s: &RefineStats) {
    println!(
        "refine ({what}, 1/16): {} of {} blocks refined ({:.2}%), {} of {} pixels ({:.2}%), {} exact evaluations per frame",
        s.refined_blocks,
        s.blocks,
        100.0 * s.refined_block_fraction(),
        s.refined_pixels,
        s.pixels,
        100.0 * s.refined_pixel_fraction(),
        s.exact_evaluations
    );
}

/// Refine's frame time against planes and direct evaluation (median ms), with the targets.
fn print_refine_targets(what: &str, direct: f64, planes: f64, refine: f64) {
    let met = |ok: bool| if ok { "met" } else { "NOT met" };
    println!(
        "{what} refine vs planes (1/16): {:.2}x the frame time (target <= 1.5x: {}); vs full-res direct: {:.1}x faster (target >= 4x: {})",
        refine / planes,
        met(refine / planes <= 1.5),
        direct / refine,
        met(direct / refine >= 4.0)
    );
}
