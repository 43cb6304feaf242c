//! `craterfield bench march3d`: the 3D renderers measured in one run.
//!
//! 1. The reference paper's scene0 and Mandelbulb at 1280x720 with the `paper` preset on
//!    the CPU sphere tracer: seconds per frame on the scalar path and on the widest SIMD
//!    path, one thread and all threads; GFLOP per frame from the counting backend (one flop
//!    per arithmetic operation or math-library call, the paper's convention); flops per
//!    cycle from those and the measured time at the stated clock.
//!    With `--reference BIN` (repeatable), the reference renderer's binaries run on the same
//!    scenes in the same run (`bench_reference3d`), in rounds with ours (one frame of every
//!    configuration per round, so that a slow spell of a shared machine falls on all of
//!    them), and each row shows the fastest one's time over ours. The FLIP of our pictures
//!    against the reference's vendored pictures (and against each binary's output) is
//!    printed.
//! 2. The forest world: SDF evaluations and march steps per pixel (counting backend) and
//!    GPU frame time with every emitter optimization on, all off (naive), and each one off,
//!    plus the visual difference of the optimized render against the naive one.
//! 3. Every builtin scene on the GPU at `--gpu-size` (1920x1080): the first frame, pipeline
//!    creation included, and the next.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use craterfield::backend::Backend;
use craterfield::march3d::compile::{CompileOptions, Optimization};
use craterfield::march3d::cpu::{self, TraceOptions};
use craterfield::march3d::gpu::MarchGpuError;
use craterfield::march3d::scene::Scene;
use craterfield::march3d::simd;
use craterfield::march3d::{Camera3d, Plan};
use craterfield::visdiff::{DiffOptions, compare};
use serde::Serialize;

use crate::bench_reference3d::{self as reference, Fidelity, RefRow};
use crate::march3d_cmd::{parse_size, plan_for};
use crate::tails::Tails;

/// Options of `bench march3d`.
#[derive(clap::Args, Debug, Clone)]
pub(crate) struct Options {
    /// Print one JSON object instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Timed frames per CPU configuration and reference run (median, p95, p99 and max are
    /// reported; the scalar path is timed once).
    #[arg(long, default_value_t = 9)]
    pub frames: u32,
    /// The clock in GHz used for flops per cycle (default: the nominal frequency the
    /// operating system reports).
    #[arg(long)]
    pub ghz: Option<f64>,
    /// Size of the paper scenes.
    #[arg(long, default_value = "1280x720")]
    pub size: String,
    /// Size of the forest world's counted and GPU renders.
    #[arg(long, default_value = "320x180")]
    pub world_size: String,
    /// Skip the scalar path (it takes tens of seconds per frame).
    #[arg(long)]
    pub no_scalar: bool,
    /// A reference renderer binary to time beside ours (repeatable; `scripts/reference-march3d`
    /// builds one).
    #[arg(long)]
    pub reference: Vec<PathBuf>,
    /// The reference renderer's pictures of scene0 and mandelbulb.
    #[arg(long, default_value = "tests/data/march3d-reference")]
    pub pictures: PathBuf,
    /// Size of the GPU frame of every builtin scene.
    #[arg(long, default_value = "1920x1080")]
    pub gpu_size: String,
    /// Skip the GPU frames of the builtin scenes.
    #[arg(long)]
    pub no_gpu_frames: bool,
    /// Timed GPU frames of each builtin scene, after the first.
    #[arg(long, default_value_t = 5)]
    pub gpu_frames: u32,
}

/// One builtin scene's GPU frames.
#[derive(Serialize)]
struct GpuFrame {
    scene: String,
    nodes: usize,
    /// The first frame, pipeline creation included (wall clock).
    first_ms: f64,
    /// The frames after it (GPU timestamps where the adapter has them).
    ms: Tails,
    frames: u32,
}

#[derive(Serialize)]
struct Row {
    scene: String,
    #[serde(rename = "impl")]
    implementation: String,
    threads: usize,
    seconds: Tails,
    frames: u32,
    gflop: f64,
    flops_per_cycle: f64,
    speedup_vs_scalar: Option<f64>,
}

#[derive(Serialize)]
struct EmitterRow {
    config: String,
    sdf_evals_per_px: f64,
    steps_per_px: f64,
    gpu_ms: Option<f64>,
    /// The GPU raymarcher refused the plan: its shader is past the marcher's budget
    /// (`MarchGpuError::TooLarge`), so it has no GPU time.
    gpu_refused: bool,
    nodes: usize,
    max_steps: u32,
}

#[derive(Serialize)]
struct Report {
    clock_ghz: f64,
    clock_source: String,
    adapter: String,
    rows: Vec<Row>,
    reference: Vec<RefRow>,
    fidelity: Vec<Fidelity>,
    emitter: Vec<EmitterRow>,
    world_size: String,
    naive_vs_all: Option<VisualDiff>,
    gpu_size: String,
    gpu_frames: Vec<GpuFrame>,
}

#[derive(Serialize)]
struct VisualDiff {
    differing_fraction: f64,
    pixel_tolerance: u8,
    mean: f64,
    flip: f64,
}

/// The nominal clock from `/proc/cpuinfo`, in GHz.
fn os_clock_ghz() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/cpuinfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("cpu MHz"))?;
    let mhz: f64 = line.split(':').nth(1)?.trim().parse().ok()?;
    Some(mhz / 1000.0)
}

/// One frame of `plan` on `isa` with `threads` threads: the seconds it took.
fn time_frame(
    plan: &Plan,
    cam: &Camera3d,
    size: (u32, u32),
    isa: Backend,
    threads: usize,
) -> Result<f64, String> {
    let opts = TraceOptions {
        threads,
        backend: Some(isa),
        ..TraceOptions::default()
    };
    let t = Instant::now();
    cpu::render(plan, cam, size.0, size.1, &opts).map_err(|e| e.to_string())?;
    Ok(t.elapsed().as_secs_f64())
}

/// Our picture of each paper scene (widest instruction set, all threads) against the
/// vendored reference pictures and each reference binary's last output.
fn fidelity_rows(o: &Options) -> Result<Vec<Fidelity>, String> {
    let size = parse_size(&o.size)?;
    let mut out = Vec::new();
    for name in ["scene0", "mandelbulb"] {
        let scene = Scene::builtin(name).map_err(|e| e.to_string())?;
        let (plan, cam) = plan_for(&scene, &CompileOptions::paper(), size)?;
        let ours = cpu::render(&plan, &cam, size.0, size.1, &TraceOptions::default())
            .map_err(|e| e.to_string())?;
        let ours = image::RgbaImage::from_raw(size.0, size.1, ours.rgba).ok_or("bad image")?;
        let vendored = o.pictures.join(format!("{name}.png"));
        let mut against: Vec<(String, PathBuf)> = Vec::new();
        if vendored.exists() {
            against.push((vendored.display().to_string(), vendored));
        } else {
            eprintln!(
                "  no {}: FLIP against the vendored picture skipped",
                vendored.display()
            );
        }
        against.extend(o.reference.iter().map(|b| {
            (
                format!("the picture of ref {}", reference::label(b)),
                reference::reference_output(b, name),
            )
        }));
        for (what, path) in against {
            out.push(reference::fidelity(name, &ours, (&what, &path))?);
        }
    }
    Ok(out)
}

/// Every builtin scene on the GPU at `--gpu-size`, with its own preset.
fn gpu_frames(o: &Options, gpu: &mut Option<Gpu>) -> Result<Vec<GpuFrame>, String> {
    let Some(g) = gpu else {
        return Ok(Vec::new());
    };
    if o.no_gpu_frames {
        return Ok(Vec::new());
    }
    let size = parse_size(&o.gpu_size)?;
    let mut out = Vec::new();
    for name in craterfield::march3d::scene::BUILTIN {
        let scene = Scene::builtin(name).map_err(|e| e.to_string())?;
        let opts = crate::march3d_cmd::preset(&scene, None, &[])?;
        let (plan, cam) = plan_for(&scene, &opts, size)?;
        let t = Instant::now();
        match g.marcher.render_timed(&plan, &cam, size.0, size.1) {
            Err(e @ MarchGpuError::TooLarge { .. }) => {
                eprintln!("  {name}: refused on the GPU: {e}");
                continue;
            }
            first => first.map_err(|e| e.to_string())?,
        };
        let first_ms = t.elapsed().as_secs_f64() * 1e3;
        let frames = o.gpu_frames.max(1);
        let mut times = Vec::new();
        for _ in 0..frames {
            let (_, ms) = g
                .marcher
                .render_timed(&plan, &cam, size.0, size.1)
                .map_err(|e| e.to_string())?;
            times.push(ms);
        }
        let ms = Tails::of(times);
        eprintln!(
            "  {name} on the GPU at {}: median {:.1} ms",
            o.gpu_size, ms.median
        );
        out.push(GpuFrame {
            scene: name.to_string(),
            nodes: plan.nodes.len(),
            first_ms,
            ms,
            frames,
        });
    }
    Ok(out)
}

/// The paper scenes' rows, ours and each reference binary's, timed in rounds: a round runs
/// every configuration of a scene and thread count once, so that a slow spell of the machine
/// (on a shared one they last seconds) falls on all of them and the ratios stay fair. The
/// scalar path runs in the first round only.
fn paper_rows(
    o: &Options,
    ghz: f64,
    all_threads: usize,
) -> Result<(Vec<Row>, Vec<RefRow>), String> {
    let size = parse_size(&o.size)?;
    let best = simd::best();
    let mut threads = vec![1];
    if all_threads > 1 {
        threads.push(all_threads);
    }
    // AVX2 beside a wider best: the reference renderer is AVX2 code.
    let mut isas: Vec<Backend> = Vec::new();
    if !o.no_scalar && best != Backend::Scalar {
        isas.push(Backend::Scalar);
    }
    if best == Backend::Avx512 && Backend::Avx2.is_available() {
        isas.push(Backend::Avx2);
    }
    isas.push(best);
    let (mut rows, mut refs) = (Vec::new(), Vec::new());
    for name in ["scene0", "mandelbulb"] {
        let scene = Scene::builtin(name).map_err(|e| e.to_string())?;
        let (plan, cam) = plan_for(&scene, &CompileOptions::paper(), size)?;
        let (_, stats) = cpu::render_counted(&plan, &cam, size.0, size.1, all_threads)
            .map_err(|e| e.to_string())?;
        let gflop = stats.flops as f64 * 1e-9;
        for &t in &threads {
            let mut ours = vec![Vec::new(); isas.len()];
            let mut theirs = vec![Vec::new(); o.reference.len()];
            for round in 0..o.frames.max(1) {
                for (bin, v) in o.reference.iter().zip(&mut theirs) {
                    v.push(reference::time_reference_once(bin, name, t)?);
                }
                for (&isa, v) in isas.iter().zip(&mut ours) {
                    if isa != Backend::Scalar || round == 0 {
                        v.push(time_frame(&plan, &cam, size, isa, t)?);
                    }
                }
            }
            for (bin, v) in o.reference.iter().zip(theirs) {
                let row = RefRow {
                    scene: name.to_string(),
                    binary: reference::label(bin),
                    threads: t,
                    frames: v.len() as u32,
                    seconds: Tails::of(v),
                    flip_vs_vendored: None,
                };
                if !o.json {
                    eprintln!(
                        "  reference {} {name} x{t}: {:.3} s",
                        row.binary, row.seconds.median
                    );
                }
                refs.push(row);
            }
            let scalar = isas.iter().position(|&i| i == Backend::Scalar);
            let scalar_s = scalar.map(|k| Tails::of(ours[k].clone()).median);
            for (&isa, v) in isas.iter().zip(ours) {
                let frames = v.len() as u32;
                let seconds = Tails::of(v);
                let s = seconds.median;
                rows.push(Row {
                    scene: name.to_string(),
                    implementation: isa.name().to_string(),
                    threads: t,
                    seconds,
                    frames,
                    gflop,
                    flops_per_cycle: gflop * 1e9 / (s * ghz * 1e9 * t as f64),
                    speedup_vs_scalar: scalar_s.map(|sc| sc / s),
                });
                if !o.json {
                    eprintln!("  {name} {} x{t}: {s:.3} s", isa.name());
                }
            }
        }
        // Every run of a binary writes the same picture: compared once, after the last.
        for bin in &o.reference {
            let flip = reference::flip_vs_vendored(bin, &o.pictures, name)?;
            let label = reference::label(bin);
            for row in refs
                .iter_mut()
                .filter(|r| r.scene == name && r.binary == label)
            {
                row.flip_vs_vendored = flip;
            }
        }
    }
    // The table lists each binary's rows together.
    let order = |r: &RefRow| {
        o.reference
            .iter()
            .position(|b| reference::label(b) == r.binary)
    };
    refs.sort_by_key(|r| order(r));
    Ok((rows, refs))
}

struct Gpu {
    ctx: craterfield::gpu::GpuContext,
    marcher: craterfield::march3d::gpu::Marcher,
}

fn gpu() -> Result<Gpu, String> {
    let ctx = craterfield::gpu::GpuContext::new().map_err(|e| e.to_string())?;
    let marcher = craterfield::march3d::gpu::Marcher::new(&ctx.device, &ctx.queue)
        .map_err(|e| e.to_string())?;
    Ok(Gpu { ctx, marcher })
}

fn emitter_rows(
    o: &Options,
    gpu: &mut Option<Gpu>,
) -> Result<(Vec<EmitterRow>, Option<VisualDiff>), String> {
    let size = parse_size(&o.world_size)?;
    let scene = Scene::builtin("forest").map_err(|e| e.to_string())?;
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut configs = vec![
        ("naive".to_string(), CompileOptions::naive()),
        ("all".to_string(), CompileOptions::default()),
    ];
    for opt in Optimization::ALL {
        configs.push((
            format!("no-{}", opt.name()),
            CompileOptions::default().without(opt),
        ));
    }
    let mut rows = Vec::new();
    let mut images = Vec::new();
    for (config, opts) in configs {
        let (plan, cam) = plan_for(&scene, &opts, size)?;
        let (img, stats) =
            cpu::render_counted(&plan, &cam, size.0, size.1, threads).map_err(|e| e.to_string())?;
        let px = stats.pixels.max(1) as f64;
        let mut gpu_refused = false;
        let gpu_ms = match gpu {
            // The first frame compiles the pipeline; the second is timed.
            Some(g) => match g.marcher.render_timed(&plan, &cam, size.0, size.1) {
                Err(e @ MarchGpuError::TooLarge { .. }) => {
                    eprintln!("  forest {config}: refused on the GPU: {e}");
                    gpu_refused = true;
                    None
                }
                first => {
                    first.map_err(|e| e.to_string())?;
                    let (_, ms) = g
                        .marcher
                        .render_timed(&plan, &cam, size.0, size.1)
                        .map_err(|e| e.to_string())?;
                    Some(ms)
                }
            },
            None => None,
        };
        if !o.json {
            eprintln!(
                "  forest {config}: {:.1} evals/px",
                stats.sdf_evals as f64 / px
            );
        }
        if config == "naive" || config == "all" {
            images.push(img);
        }
        rows.push(EmitterRow {
            config,
            sdf_evals_per_px: stats.sdf_evals as f64 / px,
            steps_per_px: stats.steps as f64 / px,
            gpu_ms,
            gpu_refused,
            nodes: plan.nodes.len(),
            max_steps: plan.march.max_steps,
        });
    }
    // The hash defines the terrain's shape (a different noise, not an approximation of
    // it), so the optimized picture is compared with the naive emit of the same terrain.
    let reference = CompileOptions {
        enabled: vec![Optimization::DotFractHash],
        ..CompileOptions::naive()
    };
    let (plan, cam) = plan_for(&scene, &reference, size)?;
    let (naive, _) =
        cpu::render_counted(&plan, &cam, size.0, size.1, threads).map_err(|e| e.to_string())?;
    let diff = match images.as_slice() {
        [_, all] => {
            let a = image::RgbaImage::from_raw(size.0, size.1, naive.rgba).ok_or("bad image")?;
            let b =
                image::RgbaImage::from_raw(size.0, size.1, all.rgba.clone()).ok_or("bad image")?;
            let opts = DiffOptions {
                pixel_tolerance: 16,
                ..DiffOptions::default()
            };
            let r = compare(&a, &b, &opts).map_err(|e| e.to_string())?;
            Some(VisualDiff {
                differing_fraction: r.differing_fraction,
                pixel_tolerance: r.pixel_tolerance,
                mean: r.mean,
                flip: r.flip,
            })
        }
        _ => None,
    };
    Ok((rows, diff))
}

/// Runs the benchmark.
pub(crate) fn run(o: &Options) -> Result<ExitCode, String> {
    let (ghz, clock_source) = match (o.ghz, os_clock_ghz()) {
        (Some(g), _) => (g, "given with --ghz".to_string()),
        (None, Some(g)) => (g, "nominal clock from /proc/cpuinfo".to_string()),
        (None, None) => return Err("no clock frequency known: pass --ghz".to_string()),
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut gpu = gpu().ok();
    let adapter = gpu
        .as_ref()
        .map_or_else(|| "none".to_string(), |g| g.ctx.describe());
    let (rows, reference) = paper_rows(o, ghz, threads)?;
    let fidelity = fidelity_rows(o)?;
    let (emitter, naive_vs_all) = emitter_rows(o, &mut gpu)?;
    let gpu_frames = gpu_frames(o, &mut gpu)?;
    let report = Report {
        clock_ghz: ghz,
        clock_source,
        adapter,
        rows,
        reference,
        fidelity,
        emitter,
        world_size: o.world_size.clone(),
        naive_vs_all,
        gpu_size: o.gpu_size.clone(),
        gpu_frames,
    };
    if o.json {
        println!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        print_tables(&report, o);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_tables(r: &Report, o: &Options) {
    println!(
        "bench march3d: paper preset at {}, clock {:.3} GHz ({})",
        o.size, r.clock_ghz, r.clock_source
    );
    println!(
        "{:<11} {:<28} {:>7} {:>8} {:>8} {:>8} {:>8} {:>7} {:>11} {:>9} {:>12}",
        "scene",
        "impl",
        "threads",
        "median s",
        "p95",
        "p99",
        "max",
        "GFLOP",
        "flops/cycle",
        "vs scalar",
        "vs reference"
    );
    let times = |t: &Tails| {
        format!(
            "{:>8.3} {:>8.3} {:>8.3} {:>8.3}",
            t.median, t.p95, t.p99, t.max
        )
    };
    for row in &r.reference {
        println!(
            "{:<11} {:<28} {:>7} {} {:>7} {:>11} {:>9} {:>12}",
            row.scene,
            format!("ref {}", row.binary),
            row.threads,
            times(&row.seconds),
            "-",
            "-",
            "-",
            "-"
        );
    }
    for row in &r.rows {
        let vs = reference::best(&r.reference, &row.scene, row.threads)
            .map_or("-".to_string(), |b| {
                format!("{:.2}x", b.seconds.median / row.seconds.median)
            });
        println!(
            "{:<11} {:<28} {:>7} {} {:>7.2} {:>11.3} {:>9} {:>12}",
            row.scene,
            row.implementation,
            row.threads,
            times(&row.seconds),
            row.gflop,
            row.flops_per_cycle,
            row.speedup_vs_scalar
                .map_or("-".to_string(), |s| format!("{s:.1}x")),
            vs
        );
    }
    println!(
        "({} timed frames per row, the scalar path 1; percentiles nearest-rank, so with fewer than 20 frames p95 and p99 are the max)",
        o.frames.max(1)
    );
    if r.reference.is_empty() {
        println!("(no reference binary given: --reference BIN times one in the same run)");
    } else {
        println!(
            "reference times are whole processes (scene load, render, PNG write); vs reference = the fastest reference binary's median at the same thread count over ours"
        );
    }
    for row in r.reference.iter().filter(|row| row.threads == 1) {
        if let Some(f) = row.flip_vs_vendored {
            println!(
                "ref {} {}: its picture against the vendored one: FLIP {f:.4}",
                row.binary, row.scene
            );
        }
    }
    println!();
    println!(
        "paper scenes against the reference renderer's pictures (CPU tracer, {})",
        o.size
    );
    println!(
        "{:<11} {:>8} {:>12}  against",
        "scene", "FLIP", "> 2 levels"
    );
    for f in &r.fidelity {
        println!(
            "{:<11} {:>8.4} {:>11.2}%  {}",
            f.scene,
            f.flip,
            f.differing_fraction * 100.0,
            f.against
        );
    }
    println!();
    println!(
        "forest world at {}, GPU: {} (per-config GPU ms at the same size)",
        r.world_size, r.adapter
    );
    println!(
        "{:<20} {:>9} {:>10} {:>9} {:>6} {:>6}",
        "config", "evals/px", "steps/px", "gpu ms", "nodes", "steps"
    );
    let all = r
        .emitter
        .iter()
        .find(|e| e.config == "all")
        .map(|e| e.sdf_evals_per_px);
    for e in &r.emitter {
        println!(
            "{:<20} {:>9.1} {:>10.2} {:>9} {:>6} {:>6}",
            e.config,
            e.sdf_evals_per_px,
            e.steps_per_px,
            match e.gpu_ms {
                Some(m) => format!("{m:.2}"),
                None if e.gpu_refused => "refused".to_string(),
                None => "-".to_string(),
            },
            e.nodes,
            e.max_steps
        );
    }
    if r.emitter.iter().any(|e| e.gpu_refused) {
        println!(
            "refused: the config's shader is past the GPU raymarcher's budget of {} inlined statements (docs/limits.md); it has CPU figures only",
            craterfield::march3d::codegen3d::MARCH3D_BUDGET.max_inlined_statements
        );
    }
    if let (Some(all), Some(naive)) = (all, r.emitter.iter().find(|e| e.config == "naive")) {
        println!(
            "naive / all SDF evaluations per pixel: {:.1}x",
            naive.sdf_evals_per_px / all.max(1e-9)
        );
    }
    if let Some(d) = &r.naive_vs_all {
        println!(
            "all vs naive (same terrain hash) image: {:.2}% of pixels differ by more than {} levels, mean error {:.2}, FLIP {:.4}",
            d.differing_fraction * 100.0,
            d.pixel_tolerance,
            d.mean,
            d.flip
        );
    }
    if !r.gpu_frames.is_empty() {
        println!();
        println!(
            "builtin scenes on the GPU at {} ({}), each scene's own preset",
            r.gpu_size, r.adapter
        );
        println!(
            "{:<11} {:>6} {:>15} {:>10} {:>9} {:>9} {:>9}",
            "scene", "nodes", "first frame ms", "median ms", "p95", "p99", "max"
        );
        for g in &r.gpu_frames {
            println!(
                "{:<11} {:>6} {:>15.1} {:>10.1} {:>9.1} {:>9.1} {:>9.1}",
                g.scene, g.nodes, g.first_ms, g.ms.median, g.ms.p95, g.ms.p99, g.ms.max
            );
        }
        if let Some(g) = r.gpu_frames.first() {
            println!("({} timed frames per scene after the first)", g.frames);
        }
    }
}
