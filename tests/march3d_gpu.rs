//! The GPU raymarcher on whatever adapter wgpu finds (Mesa's lavapipe in CI): each scene
//! rendered on the GPU against the CPU tracer with the visual diff, the shader cache, the
//! caller's-encoder path, and errors for bad input.
//!
//! Runs with its own harness so that a machine without an adapter reports every test as
//! ignored (never as passed); with `CI` set a missing adapter fails instead.

mod march3d_plans;

use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};

use craterfield::march3d::gpu::{MarchGpuError, Marcher};
use craterfield::march3d::plan::Plan;
use craterfield::render2d::gpu::GpuContext;
use image::RgbaImage;
use libtest_mimic::{Arguments, Failed, Trial};
use march3d_plans::all_plans;

type TestResult = Result<(), Failed>;
type GpuTest = fn(&GpuContext) -> TestResult;

/// Small images: lavapipe runs the shader on the CPU and the paper scenes march up to 3000
/// steps per ray.
const SIZE: (u32, u32) = (256, 144);

fn context() -> Option<Arc<Mutex<GpuContext>>> {
    static CONTEXT: OnceLock<Option<Arc<Mutex<GpuContext>>>> = OnceLock::new();
    CONTEXT
        .get_or_init(|| match GpuContext::new() {
            Ok(ctx) => {
                eprintln!("GPU adapter: {}", ctx.describe());
                Some(Arc::new(Mutex::new(ctx)))
            }
            Err(e) => {
                eprintln!("no GPU adapter: {e}");
                None
            }
        })
        .clone()
}

/// Where the tests leave their pictures for people to look at.
fn out_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("march3d_gpu");
    std::fs::create_dir_all(&dir).expect("output directory");
    dir
}

fn render(ctx: &GpuContext, plan: &Plan, camera: &craterfield::march3d::Camera) -> RgbaImage {
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

fn bad_input_is_an_error(ctx: &GpuContext) -> TestResult {
    let mut marcher = Marcher::new(&ctx.device, &ctx.queue)?;
    let (_, plan, camera) = all_plans().remove(0);
    let zero = marcher.render_to_rgba(&plan, &camera, 0, 10);
    assert!(matches!(zero, Err(MarchGpuError::Size { .. })), "{zero:?}");
    let huge = marcher.render_to_rgba(&plan, &camera, 1 << 20, 10);
    assert!(matches!(huge, Err(MarchGpuError::Size { .. })), "{huge:?}");
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

fn main() {
    let args = Arguments::from_args();
    let tests: [(&str, GpuTest); 2] = [
        ("every_plan_renders", every_plan_renders),
        ("bad_input_is_an_error", bad_input_is_an_error),
    ];
    let ctx = context();
    let ci = std::env::var_os("CI").is_some();
    let trials = tests
        .into_iter()
        .map(|(name, test)| {
            let ctx = ctx.clone();
            let missing = ctx.is_none();
            Trial::test(name, move || match ctx {
                Some(ctx) => {
                    let ctx = ctx.lock().unwrap_or_else(|e| e.into_inner());
                    test(&ctx)
                }
                None => Err("no GPU adapter, and CI is set: GPU tests must run in CI".into()),
            })
            .with_ignored_flag(missing && !ci)
        })
        .collect();
    libtest_mimic::run(&args, trials).exit();
}
