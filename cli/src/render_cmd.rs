//! `craterfield render`: any level (after a seeded barrage, or at a tick of a replay) drawn
//! the way a user inspects one, in any mode and scale, on the GPU or the CPU twin, and with
//! `--compare-exact` measured against the exact render: inside/outside and material
//! mismatch of the pipeline's field and FLIP of the picture, with a heat-map beside it.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use craterfield::field2d::{Graph, Level, Terrain};
use craterfield::gpu::GpuContext;
use craterfield::gpu::READBACK_FORMAT;
use craterfield::render2d::gpu::TerrainRenderer;
use craterfield::render2d::gpu::{Pipeline, render_to_image};
use craterfield::render2d::twin::{exact_field, render_direct, render_refine_overlay};
use craterfield::render2d::{
    Camera, FieldImage, Reconstruction, RenderOptions, Scale, Upsample, field_image, render_twin,
};
use craterfield::sim::World;
use craterfield::visdiff::{self, DiffOptions, HeatSource};
use glam::Vec2;
use image::RgbaImage;
use serde::Serialize;

use crate::barrage;
use crate::replay_cmd;

/// Pixels above which the CPU computes field images in stripes and shows progress.
const STRIPE_PIXELS: u64 = 4 << 20;
/// Rows of one stripe.
const STRIPE_ROWS: u32 = 512;

/// The command's arguments.
#[derive(clap::Args, Debug)]
pub(crate) struct Options {
    /// The level (default: the embedded default level).
    #[arg(long)]
    pub level: Option<PathBuf>,
    /// Fire a seeded random barrage of this many craters and fills at the surface first.
    #[arg(long, default_value_t = 0, conflicts_with = "replay")]
    pub events: usize,
    /// Seed of the barrage.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Draw the terrain of this replay at `--tick` instead.
    #[arg(long)]
    pub replay: Option<PathBuf>,
    /// The replay's tick (default: its last).
    #[arg(long, requires = "replay")]
    pub tick: Option<u32>,
    /// Reconstruction mode, or `exact` for the full-resolution exact render.
    #[arg(long, default_value = "refine")]
    pub mode: String,
    /// Reduced-scale divisor: 1, 4, 8, 16 or 32.
    #[arg(long, default_value_t = 16)]
    pub scale: u32,
    /// Upsampling filter of modes off and divergence: bilinear, bspline or catmull-rom.
    #[arg(long, default_value = "bspline")]
    pub upsample: String,
    /// Image width (with only a width, the level's bounds are fitted to it).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height (with `--width`: the view is the bounds' centre at the width's zoom).
    #[arg(long)]
    pub height: Option<u32>,
    /// The world rectangle to draw, `X0,Y0,X1,Y1` (with `--width`, default 1920 pixels).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub view: Vec<f32>,
    /// gpu, cpu, or auto (the GPU where wgpu finds an adapter).
    #[arg(long, default_value = "auto")]
    pub backend: String,
    /// Also render the exact image: write a heat-map beside the output and print the
    /// mismatch against it.
    #[arg(long)]
    pub compare_exact: bool,
    /// Tint the pixels `refine` evaluated exactly (CPU only).
    #[arg(long)]
    pub show_refined: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Render this many frames and report the median, p95, p99 and max frame time.
    #[arg(long, default_value_t = 1)]
    pub frames: u32,
    /// Worker threads of the CPU paths (0: all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// The PNG to write.
    #[arg(long)]
    pub out: PathBuf,
}

/// What `--compare-exact` measured.
#[derive(Serialize, Debug, Clone, Copy)]
struct Comparison {
    mismatch_pct: f64,
    material_mismatch_pct: f64,
    flip: f64,
}

#[derive(Serialize)]
struct Report {
    out: String,
    width: u32,
    height: u32,
    mode: String,
    scale: u32,
    renderer: String,
    frames: u32,
    render_ms: f64,
    render_ms_p95: f64,
    render_ms_p99: f64,
    render_ms_max: f64,
    #[serde(flatten)]
    comparison: Option<Comparison>,
    heatmap: Option<String>,
}

/// What to draw with.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Backend {
    Gpu,
    Cpu,
    Auto,
}

/// The mode: a pipeline configuration or the exact render.
#[derive(Clone, Debug)]
enum Mode {
    Pipeline(RenderOptions),
    Exact,
}

pub(crate) fn run(options: &Options) -> Result<ExitCode, String> {
    let mode = parse_mode(options)?;
    let backend = match options.backend.as_str() {
        "gpu" => Backend::Gpu,
        "cpu" => Backend::Cpu,
        "auto" => Backend::Auto,
        other => return Err(format!("--backend {other}: expected gpu, cpu or auto")),
    };
    if options.show_refined && backend == Backend::Gpu {
        return Err("--show-refined draws with the CPU twin: use --backend cpu".into());
    }
    let level = load_level(options.level.as_deref())?;
    let terrain = terrain(options, &level)?;
    let camera = camera(options, &level)?;
    let palette: Vec<[u8; 3]> = level.materials().iter().map(|m| m.color).collect();
    let mut times = Vec::new();
    let mut drawn = None;
    for _ in 0..options.frames.max(1) {
        let start = Instant::now();
        drawn = Some(draw(options, &mode, backend, &terrain, &palette, &camera)?);
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    let (image, renderer) = drawn.ok_or("no frame rendered")?;
    times.sort_by(f64::total_cmp);
    let at = |q: f64| times[((times.len() as f64 * q).ceil() as usize).clamp(1, times.len()) - 1];
    let render_ms = times[times.len() / 2];
    let tails = [at(0.95), at(0.99), times[times.len() - 1]];
    visdiff::save_png(&image, &options.out).map_err(|e| e.to_string())?;
    let (comparison, heatmap) = if options.compare_exact {
        let (c, path) = compare(options, &mode, &terrain, &palette, &camera, &image)?;
        (Some(c), Some(path))
    } else {
        (None, None)
    };
    let report = Report {
        out: options.out.display().to_string(),
        width: camera.width,
        height: camera.height,
        mode: options.mode.clone(),
        scale: options.scale,
        renderer,
        frames: times.len() as u32,
        render_ms,
        render_ms_p95: tails[0],
        render_ms_p99: tails[1],
        render_ms_max: tails[2],
        comparison,
        heatmap: heatmap.map(|p| p.display().to_string()),
    };
    print_report(&report, options.json)?;
    Ok(ExitCode::SUCCESS)
}

fn parse_mode(options: &Options) -> Result<Mode, String> {
    let scale = Scale::from_divisor(options.scale)
        .ok_or_else(|| format!("--scale {}: expected 1, 4, 8, 16 or 32", options.scale))?;
    let upsample = Upsample::ALL
        .into_iter()
        .find(|u| u.name() == options.upsample)
        .ok_or_else(|| {
            format!(
                "--upsample {}: expected bilinear, bspline or catmull-rom",
                options.upsample
            )
        })?;
    if options.mode == "exact" {
        return Ok(Mode::Exact);
    }
    let reconstruction = Reconstruction::from_name(&options.mode).ok_or_else(|| {
        format!(
            "--mode {}: expected refine, planes, divergence, off or exact",
            options.mode
        )
    })?;
    Ok(Mode::Pipeline(RenderOptions {
        scale,
        reconstruction,
        upsample,
        ..RenderOptions::default()
    }))
}

fn load_level(path: Option<&Path>) -> Result<Level, String> {
    match path {
        Some(p) => Level::load(p).map_err(|e| format!("{}: {e}", p.display())),
        None => Ok(Level::default_level()),
    }
}

/// The terrain to draw: the level after the barrage, or a replay's at its tick.
fn terrain(options: &Options, level: &Level) -> Result<Terrain<Graph>, String> {
    if let Some(file) = &options.replay {
        let world: World = replay_cmd::world_at(file, options.tick, level)?;
        return Ok(world.terrain().clone());
    }
    let mut terrain = level.terrain().map_err(|e| e.to_string())?;
    barrage::fire_seeded(level, &mut terrain, options.events, options.seed, |_| {});
    Ok(terrain)
}

/// The camera of `--view`, `--width`/`--height`, or the level's bounds fitted to 1920.
fn camera(options: &Options, level: &Level) -> Result<Camera, String> {
    let b = level.bounds();
    let camera = match (options.view.as_slice(), options.width, options.height) {
        ([x0, y0, x1, y1], width, None) => {
            let (min, max) = (Vec2::new(*x0, *y0), Vec2::new(*x1, *y1));
            if !(min.is_finite() && max.is_finite() && max.x > min.x && max.y > min.y) {
                return Err(format!(
                    "--view {x0},{y0},{x1},{y1}: expected finite X0 < X1 and Y0 < Y1"
                ));
            }
            fit(min, max, width.unwrap_or(1920))?
        }
        ([_, _, _, _], _, Some(_)) => {
            return Err("--view sets the height from the width: give --width only".into());
        }
        ([], width, None) => fit(b.min, b.max, width.unwrap_or(1920))?,
        ([], Some(width), Some(height)) => {
            let upp = (b.max.x - b.min.x) / width.max(1) as f32;
            Camera {
                center: (b.min + b.max) * 0.5,
                units_per_pixel: upp,
                width,
                height,
            }
        }
        ([], None, Some(_)) => return Err("--height needs --width".into()),
        _ => return Err("--view takes four numbers: X0,Y0,X1,Y1".into()),
    };
    camera
        .validate()
        .map_err(|e| format!("cannot render this view: {e}"))?;
    Ok(camera)
}

/// `[min, max]` fitted to `width` pixels, the height following the aspect ratio.
fn fit(min: Vec2, max: Vec2, width: u32) -> Result<Camera, String> {
    let upp = (max.x - min.x) / width.max(1) as f32;
    let height = ((max.y - min.y) / upp).round();
    if !(1.0..=1.0e6).contains(&height) {
        return Err(format!(
            "a view {} x {} world units at {width} pixels wide is {height} pixels high: cannot render it",
            max.x - min.x,
            max.y - min.y
        ));
    }
    Ok(Camera {
        center: (min + max) * 0.5,
        units_per_pixel: upp,
        width,
        height: height as u32,
    })
}

fn draw(
    options: &Options,
    mode: &Mode,
    backend: Backend,
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
) -> Result<(RgbaImage, String), String> {
    let gpu = match (backend, mode) {
        (Backend::Cpu, _) => None,
        (_, _) if options.show_refined => None,
        (b, m) => match draw_gpu(m, terrain, palette, camera) {
            Ok(drawn) => Some(drawn),
            Err(e) if b == Backend::Gpu => return Err(format!("GPU: {e}")),
            Err(e) => {
                eprintln!("note: drawing on the CPU ({e})");
                None
            }
        },
    };
    if let Some(drawn) = gpu {
        return Ok(drawn);
    }
    let image = whole(camera, |c| draw_cpu(options, mode, terrain, palette, c))?;
    Ok((image, "CPU".into()))
}

fn draw_gpu(
    mode: &Mode,
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
) -> Result<(RgbaImage, String), String> {
    let ctx = GpuContext::new().map_err(|e| e.to_string())?;
    let (options, pipeline) = match mode {
        Mode::Pipeline(o) => (o.clone(), Pipeline::Reduced),
        Mode::Exact => (RenderOptions::default(), Pipeline::Direct),
    };
    let mut r = TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options)
        .map_err(|e| e.to_string())?;
    r.prepare(terrain, palette, camera)
        .map_err(|e| e.to_string())?;
    let image =
        render_to_image(&r, camera.width, camera.height, pipeline).map_err(|e| e.to_string())?;
    Ok((image, format!("GPU ({})", ctx.describe())))
}

fn draw_cpu(
    options: &Options,
    mode: &Mode,
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
) -> Result<RgbaImage, String> {
    let threads = options.threads;
    match mode {
        Mode::Exact => render_direct(terrain, palette, camera, &Default::default(), threads),
        Mode::Pipeline(o) if options.show_refined => {
            render_refine_overlay(terrain, palette, camera, o, threads).map(|(image, _)| image)
        }
        Mode::Pipeline(o) => render_twin(terrain, palette, camera, o, threads),
    }
    .map_err(|e| e.to_string())
}

/// Renders `camera`'s image in one piece, with a spinner on stderr when it is large. Not in
/// stripes: the sky's gradient spans the image's height, so each stripe would restart it.
fn whole(
    camera: &Camera,
    render: impl FnOnce(&Camera) -> Result<RgbaImage, String>,
) -> Result<RgbaImage, String> {
    let pixels = u64::from(camera.width) * u64::from(camera.height);
    let spinner = (pixels > STRIPE_PIXELS && std::io::stderr().is_terminal()).then(|| {
        let s = indicatif::ProgressBar::new_spinner();
        s.set_message(format!("rendering {}x{}", camera.width, camera.height));
        s.enable_steady_tick(std::time::Duration::from_millis(120));
        s
    });
    let image = render(camera);
    if let Some(s) = spinner {
        s.finish_and_clear();
    }
    image
}

/// The camera of image rows `y0..y0 + rows` of `camera`.
fn stripe_camera(camera: &Camera, y0: u32, rows: u32) -> Camera {
    let upp = camera.units_per_pixel;
    let shift = (camera.height as f32 * 0.5) - (y0 as f32 + rows as f32 * 0.5);
    Camera {
        center: camera.center + Vec2::new(0.0, shift * upp),
        units_per_pixel: upp,
        width: camera.width,
        height: rows,
    }
}

fn progress(done: u32, total: u32) {
    let mut err = std::io::stderr();
    if !err.is_terminal() {
        return;
    }
    let width = 40;
    let filled = (done as usize * width) / total.max(1) as usize;
    let bar = format!("{}{}", "#".repeat(filled), "-".repeat(width - filled));
    let _ = write!(err, "\r[{bar}] {done}/{total} stripes");
    if done == total {
        let _ = writeln!(err);
    }
    let _ = err.flush();
}

/// The exact render, its comparison with `image`, and the heat-map's path.
fn compare(
    options: &Options,
    mode: &Mode,
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
    image: &RgbaImage,
) -> Result<(Comparison, PathBuf), String> {
    let threads = options.threads;
    let exact = whole(camera, |c| {
        render_direct(terrain, palette, c, &Default::default(), threads).map_err(|e| e.to_string())
    })?;
    let truth = striped_field(camera, |c| exact_field(terrain, c, threads))?;
    let test = match mode {
        Mode::Exact => truth.clone(),
        Mode::Pipeline(o) => striped_field(camera, |c| field_image(terrain, c, o, threads))?,
    };
    let (mismatch_pct, material_mismatch_pct) = mismatches(&truth, &test);
    let report =
        visdiff::compare(&exact, image, &DiffOptions::default()).map_err(|e| e.to_string())?;
    let heat = visdiff::heatmap(&report, HeatSource::Pixel);
    let path = heatmap_path(&options.out);
    visdiff::save_png(&heat, &path).map_err(|e| e.to_string())?;
    Ok((
        Comparison {
            mismatch_pct,
            material_mismatch_pct,
            flip: report.flip,
        },
        path,
    ))
}

/// [`striped`] for field images.
fn striped_field(
    camera: &Camera,
    mut field: impl FnMut(&Camera) -> Result<FieldImage, craterfield::render2d::TwinError>,
) -> Result<FieldImage, String> {
    let pixels = u64::from(camera.width) * u64::from(camera.height);
    if pixels <= STRIPE_PIXELS {
        return field(camera).map_err(|e| e.to_string());
    }
    let mut out = FieldImage {
        width: camera.width,
        height: camera.height,
        distance_px: Vec::new(),
        normal: Vec::new(),
        material: Vec::new(),
    };
    let stripes = camera.height.div_ceil(STRIPE_ROWS);
    let mut y0 = 0;
    while y0 < camera.height {
        progress(y0 / STRIPE_ROWS, stripes);
        let rows = STRIPE_ROWS.min(camera.height - y0);
        let part = field(&stripe_camera(camera, y0, rows)).map_err(|e| e.to_string())?;
        out.distance_px.extend(part.distance_px);
        out.normal.extend(part.normal);
        out.material.extend(part.material);
        y0 += rows;
    }
    progress(stripes, stripes);
    Ok(out)
}

/// Percentages of pixels whose inside/outside state differs, and of pixels inside in both
/// whose material differs.
fn mismatches(truth: &FieldImage, test: &FieldImage) -> (f64, f64) {
    let n = truth.distance_px.len().max(1) as f64;
    let mut inside = 0u64;
    let mut material = 0u64;
    for i in 0..truth.distance_px.len() {
        let (a, b) = (truth.distance_px[i] < 0.0, test.distance_px[i] < 0.0);
        if a != b {
            inside += 1;
        } else if a && truth.material[i] != test.material[i] {
            material += 1;
        }
    }
    (100.0 * inside as f64 / n, 100.0 * material as f64 / n)
}

/// `out.png` -> `out-heatmap.png`.
fn heatmap_path(out: &Path) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or("render".into(), |s| s.to_string_lossy());
    out.with_file_name(format!("{stem}-heatmap.png"))
}

fn print_report(report: &Report, json: bool) -> Result<(), String> {
    if json {
        println!(
            "{}",
            serde_json::to_string(report).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    println!(
        "wrote {} ({}x{}, mode {}, scale 1/{}) with {} in {:.1} ms",
        report.out,
        report.width,
        report.height,
        report.mode,
        report.scale,
        report.renderer,
        report.render_ms
    );
    if report.frames > 1 {
        println!(
            "{} frames: median {:.2} ms, p95 {:.2}, p99 {:.2}, max {:.2}",
            report.frames,
            report.render_ms,
            report.render_ms_p95,
            report.render_ms_p99,
            report.render_ms_max
        );
    }
    if let (Some(c), Some(h)) = (&report.comparison, &report.heatmap) {
        println!(
            "against the exact render: inside/outside mismatch {:.4}% of pixels, material mismatch {:.4}%, FLIP {:.5}; heat-map {h}",
            c.mismatch_pct, c.material_mismatch_pct, c.flip
        );
    }
    Ok(())
}
