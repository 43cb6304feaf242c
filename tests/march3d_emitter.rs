//! The 3D emitter's optimizations, measured by the counting tracer: the optimized forest
//! world needs at least 5x fewer SDF evaluations per pixel than the naive emit, looks the
//! same within the visual-diff tolerance, and every switch changes what it claims to.

use craterfield::march3d::Camera3d;
use craterfield::march3d::compile::{CompileOptions, Optimization, WorldCompiler};
use craterfield::march3d::cpu::{Rendered, Stats, render_counted};
use craterfield::march3d::scene::Scene;
use craterfield::visdiff::{DiffOptions, compare};

const W: u32 = 128;
const H: u32 = 72;

fn forest() -> (WorldCompiler, Camera3d) {
    let scene = Scene::builtin("forest").unwrap();
    let camera = scene.camera.camera().unwrap();
    (WorldCompiler::new(&scene).unwrap(), camera)
}

fn counted(e: &WorldCompiler, camera: &Camera3d, opts: &CompileOptions) -> (Rendered, Stats) {
    let plan = e.emit(camera, opts).unwrap();
    render_counted(&plan, camera, W, H, 0).unwrap()
}

/// The naive emit with the optimized plan's noise hash.
fn naive_same_terrain() -> CompileOptions {
    CompileOptions {
        enabled: vec![Optimization::DotFractHash],
        ..CompileOptions::naive()
    }
}

fn image(r: &Rendered) -> image::RgbaImage {
    image::RgbaImage::from_raw(r.width, r.height, r.rgba.clone()).unwrap()
}

#[test]
fn the_optimized_forest_needs_five_times_fewer_evaluations_and_looks_the_same() {
    let (e, camera) = forest();
    let (_, naive) = counted(&e, &camera, &CompileOptions::naive());
    let (all_img, all) = counted(&e, &camera, &CompileOptions::default());
    let ratio = naive.sdf_evals as f64 / all.sdf_evals as f64;
    assert!(ratio >= 5.0, "naive/all SDF evaluations = {ratio:.2}");
    // The hash defines the terrain's shape (a different noise, not an approximation of
    // it), so the picture is compared with the naive emit of the same terrain.
    let (naive_img, _) = counted(&e, &camera, &naive_same_terrain());
    let report = compare(
        &image(&naive_img),
        &image(&all_img),
        &DiffOptions {
            pixel_tolerance: 16,
            // The cheap shadow (terrain samples and bounding spheres instead of a soft-shadow
            // march) and far LOD spheres are approximations by design: they move shadow
            // edges and far silhouettes, nothing else.
            max_differing_fraction: 0.08,
            max_mean: 4.0,
            max_percentile: f64::INFINITY,
            max_flip: 0.08,
            ..DiffOptions::default()
        },
    )
    .unwrap();
    eprintln!(
        "naive/all evaluations {ratio:.1}; image: {:.2}% over 16 levels, mean {:.2}, FLIP {:.4}",
        report.differing_fraction * 100.0,
        report.mean,
        report.flip
    );
    assert!(report.passed(), "{}", report.failure_summary());
}

#[test]
fn each_switch_costs_evaluations_or_steps_when_off() {
    let (e, camera) = forest();
    let (_, all) = counted(&e, &camera, &CompileOptions::default());
    // The switches that only change how a value is computed (hash, normals, material IDs
    // after the march) still cost evaluations; every one is measured here.
    for opt in [
        Optimization::FrustumCull,
        Optimization::AabbGuards,
        Optimization::HeightEarlyOut,
        Optimization::ConstantBaking,
        Optimization::MaterialIds,
        Optimization::TerrainShadow,
        Optimization::AnalyticNormal,
    ] {
        let (_, off) = counted(&e, &camera, &CompileOptions::default().without(opt));
        assert!(
            off.sdf_evals > all.sdf_evals,
            "no-{}: {} evaluations, all: {}",
            opt.name(),
            off.sdf_evals,
            all.sdf_evals
        );
    }
    let (_, no_lipschitz) = counted(
        &e,
        &camera,
        &CompileOptions::default().without(Optimization::LipschitzStep),
    );
    assert!(no_lipschitz.steps > all.steps);
}
