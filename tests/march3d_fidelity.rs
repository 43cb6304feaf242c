//! What the CPU sphere tracer draws, against what it must draw: the paper scenes against the
//! reference renderer's own pictures (FLIP), every builtin scene with LOD on against LOD off
//! (and the work LOD saves, from the counting backend), and grazing cameras over the worlds'
//! terrain, which must never show sky below the horizon. `march3d_gpu` holds the GPU
//! raymarcher to the same views.

mod march3d_views;

use craterfield::march3d::compile::CompileOptions;
use craterfield::march3d::cpu::{self, TraceOptions};
use image::RgbaImage;
use march3d_views::{
    LOD_LEVELS, LOD_MAX_FRACTION, PAPER_SCENES, REFERENCE_MAX_FLIP, REFERENCE_SIZE, VIEW_SIZE,
    against_reference, grazing_views, lod_difference, lod_pairs, plan, sky_below_horizon,
};

fn image(r: cpu::Rendered) -> RgbaImage {
    RgbaImage::from_raw(r.width, r.height, r.rgba).expect("image size")
}

#[test]
fn paper_scenes_match_the_reference_renderers_pictures() {
    let (w, h) = REFERENCE_SIZE;
    for name in PAPER_SCENES {
        let (plan, camera) = plan(name, &CompileOptions::paper(), REFERENCE_SIZE);
        let ours = cpu::render(&plan, &camera, w, h, &TraceOptions::default()).unwrap();
        let report = against_reference(name, ours.rgba);
        eprintln!(
            "{name}: FLIP {:.4} against the reference's picture ({:.2}% of pixels more than 2 levels apart)",
            report.flip,
            report.differing_fraction * 100.0
        );
        assert!(
            report.flip <= REFERENCE_MAX_FLIP,
            "{name}: FLIP {} > {REFERENCE_MAX_FLIP}",
            report.flip
        );
    }
}

#[test]
fn lod_cannot_be_seen_and_still_saves_work() {
    let (w, h) = VIEW_SIZE;
    for (name, [on, off]) in lod_pairs() {
        let (img_on, stats_on) = cpu::render_counted(&on.0, &on.1, w, h, 0).unwrap();
        let (img_off, stats_off) = cpu::render_counted(&off.0, &off.1, w, h, 0).unwrap();
        let report = lod_difference(&image(img_on), &image(img_off));
        let px = (w * h) as f64;
        eprintln!(
            "{name}: {:.3}% of pixels more than {LOD_LEVELS} levels apart; SDF evaluations/px {:.2} with LOD, {:.2} without; steps/px {:.2}, {:.2}",
            report.differing_fraction * 100.0,
            stats_on.sdf_evals as f64 / px,
            stats_off.sdf_evals as f64 / px,
            stats_on.steps as f64 / px,
            stats_off.steps as f64 / px,
        );
        assert!(
            report.differing_fraction <= LOD_MAX_FRACTION,
            "{name}: LOD visible in {:.3}% of pixels",
            report.differing_fraction * 100.0
        );
        assert!(stats_on.sdf_evals <= stats_off.sdf_evals, "{name}");
        assert!(stats_on.steps <= stats_off.steps, "{name}");
        if on.0.nodes != off.0.nodes {
            // Some object took a simplified form: it must have saved evaluations.
            assert!(stats_on.sdf_evals < stats_off.sdf_evals, "{name}");
        }
    }
}

#[test]
fn the_worlds_use_simplified_forms_at_the_test_size() {
    // Otherwise the LOD test above compares a plan with itself.
    for (name, [on, off]) in lod_pairs() {
        if matches!(name, "sparse" | "forest") {
            assert_ne!(on.0.nodes, off.0.nodes, "{name}");
        }
    }
}

#[test]
fn grazing_rays_never_draw_sky_below_the_horizon() {
    let (w, h) = VIEW_SIZE;
    let views = grazing_views();
    assert!(views.len() >= 24, "every world scene has grazing views");
    for (name, plan, camera) in views {
        let img = image(cpu::render(&plan, &camera, w, h, &TraceOptions::default()).unwrap());
        let leaks = sky_below_horizon(&img, &camera, &plan);
        assert_eq!(leaks, 0, "{name}: {leaks} sky pixels below the horizon");
    }
}
