//! `craterfield march3d`: renders a 3D scene (builtin or RON file) with the CPU sphere
//! tracer or the GPU raymarcher and writes a PNG.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use craterfield::backend::Backend;
use craterfield::march3d::compile::{CompileOptions, Optimization, WorldCompiler};
use craterfield::march3d::cpu::{self, TraceOptions};
use craterfield::march3d::plan3d::Shading;
use craterfield::march3d::scene::Scene;
use craterfield::march3d::simd;
use craterfield::march3d::{Camera3d, Plan};

/// Options of `march3d`.
#[derive(clap::Args, Debug, Clone)]
pub(crate) struct Options {
    /// A builtin scene (scene0, mandelbulb, sparse, forest) or a RON scene file.
    #[arg(long, default_value = "scene0")]
    pub scene: String,
    /// Image size, WxH (default: the scene's).
    #[arg(long)]
    pub size: Option<String>,
    /// `cpu` (the SIMD sphere tracer) or `gpu` (the emitted WGSL raymarcher).
    #[arg(long, default_value = "cpu")]
    pub backend: String,
    /// CPU threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// CPU instruction set of the tracer: scalar, avx2 or neon (default: the widest
    /// available, capped by CRATERFIELD_BACKEND).
    #[arg(long)]
    pub isa: Option<String>,
    /// `paper` (the reference renderer's settings: every object every step), `all` (every
    /// emitter optimization) or `naive` (none). Default: `paper` for scenes lit the paper's
    /// way, `all` for worlds.
    #[arg(long)]
    pub preset: Option<String>,
    /// Switch optimizations off, comma-separated (e.g. `guards,lod`).
    #[arg(long, value_delimiter = ',')]
    pub no: Vec<String>,
    /// Largest surface error, in pixels, of an object's simplified form (LOD) where the
    /// emitter uses it.
    #[arg(long, default_value_t = CompileOptions::default().lod_pixels)]
    pub lod_pixels: f32,
    /// Also render with the counting backend and print SDF evaluations, steps and flops.
    #[arg(long)]
    pub count: bool,
    /// The PNG to write.
    #[arg(long, default_value = "out/march3d.png")]
    pub out: PathBuf,
}

/// Parses `WxH`.
pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("size `{s}` is not WxH"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in `{s}`"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in `{s}`"))?;
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!("size `{s}` must be 1..=16384 on each side"));
    }
    Ok((w, h))
}

/// The emit options of a preset name for `scene`.
pub(crate) fn preset(
    scene: &Scene,
    name: Option<&str>,
    off: &[String],
) -> Result<CompileOptions, String> {
    let paper_lit = matches!(
        scene.lighting,
        craterfield::march3d::scene::Lighting::Paper(_)
    );
    let mut opts = match name {
        Some("paper") => CompileOptions::paper(),
        Some("all") => CompileOptions::default(),
        Some("naive") => CompileOptions::naive(),
        None if paper_lit => CompileOptions::paper(),
        None => CompileOptions::default(),
        Some(other) => return Err(format!("unknown preset `{other}` (paper, all, naive)")),
    };
    for name in off {
        let o = Optimization::ALL
            .into_iter()
            .find(|o| o.name() == name.as_str())
            .ok_or_else(|| {
                let names: Vec<_> = Optimization::ALL.iter().map(|o| o.name()).collect();
                format!(
                    "unknown optimization `{name}` (one of {})",
                    names.join(", ")
                )
            })?;
        opts = opts.without(o);
    }
    Ok(opts)
}

/// The scene's plan and camera for an image of `size`.
pub(crate) fn plan_for(
    scene: &Scene,
    opts: &CompileOptions,
    size: (u32, u32),
) -> Result<(Plan, Camera3d), String> {
    let camera = scene.camera.camera().map_err(|e| e.to_string())?;
    let mut opts = opts.clone();
    opts.aspect = size.0 as f32 / size.1 as f32;
    opts.height = size.1;
    let emitter = WorldCompiler::new(scene).map_err(|e| e.to_string())?;
    let plan = emitter.emit(&camera, &opts).map_err(|e| e.to_string())?;
    Ok((plan, camera))
}

fn save(path: &Path, w: u32, h: u32, rgba: Vec<u8>) -> Result<(), String> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let img = image::RgbaImage::from_raw(w, h, rgba).ok_or("image buffer has the wrong size")?;
    img.save(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}

fn run_inner(o: &Options) -> Result<(), String> {
    let scene = Scene::named_or_file(&o.scene).map_err(|e| e.to_string())?;
    let size = match &o.size {
        Some(s) => parse_size(s)?,
        None => scene.size,
    };
    let mut opts = preset(&scene, o.preset.as_deref(), &o.no)?;
    opts.lod_pixels = o.lod_pixels;
    let (plan, camera) = plan_for(&scene, &opts, size)?;
    let kind = match plan.shading {
        Shading::Paper(_) => "paper shading",
        Shading::World(_) => "world shading",
    };
    let (rgba, what) = match o.backend.as_str() {
        "cpu" => {
            let backend = match &o.isa {
                Some(name) => Some(name.parse::<Backend>().map_err(|e| e.to_string())?),
                None => None,
            };
            let topts = TraceOptions {
                threads: o.threads,
                backend,
                ..TraceOptions::default()
            };
            let start = Instant::now();
            let img =
                cpu::render(&plan, &camera, size.0, size.1, &topts).map_err(|e| e.to_string())?;
            let isa = backend.unwrap_or_else(simd::best);
            let threads = if o.threads == 0 {
                std::thread::available_parallelism().map_or(1, |n| n.get())
            } else {
                o.threads
            };
            (
                img.rgba,
                format!(
                    "CPU sphere tracer ({isa}, {threads} threads) in {:.3} s",
                    start.elapsed().as_secs_f64()
                ),
            )
        }
        "gpu" => gpu_render(&plan, &camera, size)?,
        other => return Err(format!("unknown backend `{other}` (cpu or gpu)")),
    };
    save(&o.out, size.0, size.1, rgba)?;
    println!(
        "wrote {} ({}x{}, {} nodes, {} steps, {kind}, rendered by the {what})",
        o.out.display(),
        size.0,
        size.1,
        plan.nodes.len(),
        plan.march.max_steps
    );
    if o.count {
        let (_, stats) = cpu::render_counted(&plan, &camera, size.0, size.1, o.threads)
            .map_err(|e| e.to_string())?;
        let px = stats.pixels.max(1) as f64;
        println!(
            "counted: {:.2} SDF evaluations/px, {:.2} march steps/px, {:.3} GFLOP/frame",
            stats.sdf_evals as f64 / px,
            stats.steps as f64 / px,
            stats.flops as f64 * 1e-9
        );
    }
    Ok(())
}

fn gpu_render(
    plan: &Plan,
    camera: &Camera3d,
    size: (u32, u32),
) -> Result<(Vec<u8>, String), String> {
    use craterfield::gpu::GpuContext;
    use craterfield::march3d::gpu::{MarchGpuError, Marcher};
    // A plan past the shader budget is not a failure of the GPU: say so, and where it renders.
    let refused = |e: MarchGpuError| match e {
        MarchGpuError::TooLarge { .. } => {
            format!("refused: {e}, with --backend cpu")
        }
        e => e.to_string(),
    };
    let ctx = GpuContext::new().map_err(|e| e.to_string())?;
    let mut marcher = Marcher::new(&ctx.device, &ctx.queue).map_err(|e| e.to_string())?;
    let (rgba, ms) = marcher
        .render_timed(plan, camera, size.0, size.1)
        .map_err(refused)?;
    Ok((
        rgba,
        format!("GPU raymarcher on {} in {ms:.1} ms", ctx.describe()),
    ))
}

/// Runs the command.
pub(crate) fn run(o: &Options) -> Result<ExitCode, String> {
    run_inner(o).map(|()| ExitCode::SUCCESS)
}
