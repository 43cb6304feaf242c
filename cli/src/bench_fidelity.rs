//! `craterfield bench fidelity`: how faithfully each reconstruction method of the
//! reduced-scale pipeline keeps the terrain's shape, scene by scene and scale by scale,
//! against exact evaluation at every pixel (see `render2d::fidelity` for the metrics), with
//! a verdict on each target at scale 1/16. `--out DIR` writes side-by-side pictures.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use craterfield::render2d::fidelity::{self, FeatureKind, Fidelity, Recall};
use craterfield::render2d::twin::{exact_field, render_direct};
use craterfield::render2d::{
    ExactRenderOptions, FieldImage, Reconstruction, RenderOptions, Scale, Upsample, field_image,
    render_exact, render_twin,
};
use craterfield::visdiff::{self, DiffOptions};
use image::RgbaImage;
use serde::Serialize;

use crate::fidelity_scenes::{self, NAMES, Scene};

/// What to measure (the command's arguments).
#[derive(clap::Args)]
pub(crate) struct Options {
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write side-by-side pictures (exact, then every method at 1/16) of a few scenes here.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The prospero expression (default: tests/data/prospero.vm).
    #[arg(long)]
    pub prospero: Option<PathBuf>,
    /// Seed of the level's barrage.
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
    /// Seed of the `level-reseeded` scene's barrage (default: a new one every run).
    #[arg(long)]
    pub reseed: Option<u64>,
    /// Only these scenes, comma-separated (default: all).
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Worker threads (0: all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
}

/// A reconstruction method as the bench names it.
#[derive(Clone, Copy)]
struct Method {
    name: &'static str,
    reconstruction: Reconstruction,
    upsample: Upsample,
}

const METHODS: [Method; 5] = [
    Method {
        name: "bilinear",
        reconstruction: Reconstruction::Off,
        upsample: Upsample::Bilinear,
    },
    Method {
        name: "bicubic",
        reconstruction: Reconstruction::Off,
        upsample: Upsample::BSpline,
    },
    Method {
        name: "divergence",
        reconstruction: Reconstruction::Divergence,
        upsample: Upsample::BSpline,
    },
    Method {
        name: "planes",
        reconstruction: Reconstruction::Planes,
        upsample: Upsample::BSpline,
    },
    Method {
        name: "refine",
        reconstruction: Reconstruction::Refine,
        upsample: Upsample::BSpline,
    },
];

const SCALES: [Scale; 4] = [
    Scale::Quarter,
    Scale::Eighth,
    Scale::Sixteenth,
    Scale::ThirtySecond,
];

/// The scale the targets are judged at.
const TARGET_SCALE: u32 = 16;

/// One scene, method and scale.
#[derive(Serialize)]
struct Row {
    scene: &'static str,
    method: &'static str,
    scale: u32,
    mismatch_pct: f64,
    /// `null` where the scene has no solid feature present in the ground truth.
    solid_recall: Option<f64>,
    gap_recall: Option<f64>,
    solid_target_recall: Option<f64>,
    gap_target_recall: Option<f64>,
    mean_offset_px: f64,
    max_offset_px: f64,
    /// Pixels inside in both images whose materials differ, percent of all pixels.
    material_mismatch_pct: f64,
    /// Features at least 1 px wide (solids and gaps) kept, over those in the truth.
    recall_1px: Option<f64>,
    /// FLIP of the shaded picture against the exact render (only at the target scale).
    flip: Option<f64>,
    /// Features behind the recalls: present in the truth, and kept.
    solid_target: Recall,
    gap_target: Recall,
    solid: Recall,
    gap: Recall,
    /// Time of the twin's three passes, milliseconds.
    render_ms: f64,
}

/// A scene's size and setup times.
#[derive(Serialize)]
struct SceneInfo {
    scene: &'static str,
    width: u32,
    height: u32,
    features: usize,
    build_ms: f64,
    truth_ms: f64,
}

/// A target's verdict.
#[derive(Serialize)]
struct Verdict {
    target: String,
    /// `None` (`null`) when the scenes run have nothing to judge it on.
    passed: Option<bool>,
    detail: String,
}

/// A target feature `planes` lost at the target scale.
#[derive(Serialize)]
struct LostFeature {
    scene: &'static str,
    kind: FeatureKind,
    width_px: f32,
    /// Mean of its centre-line points, pixels.
    at_px: [f32; 2],
}

#[derive(Serialize)]
struct Report {
    rows: Vec<Row>,
    best: &'static str,
    targets: Vec<Verdict>,
    scenes: Vec<SceneInfo>,
    /// Features at least 2 px wide that `planes` lost at 1/16.
    lost: Vec<LostFeature>,
    notes: Vec<String>,
}

pub(crate) fn fidelity(options: &Options) -> Result<ExitCode, String> {
    let prospero = options
        .prospero
        .clone()
        .unwrap_or_else(|| PathBuf::from("tests/data/prospero.vm"));
    let names = scene_names(&options.scenes)?;
    let mut report = Report {
        rows: Vec::new(),
        best: "",
        targets: Vec::new(),
        scenes: Vec::new(),
        lost: Vec::new(),
        notes: Vec::new(),
    };
    // A barrage no run has seen before, printed so that a failure can be replayed.
    let reseeded = options.reseed.unwrap_or_else(|| {
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(1, |d| d.as_nanos() as u64)
    });
    report.notes.push(format!(
        "level-reseeded: barrage seed {reseeded} (--reseed {reseeded} repeats it)"
    ));
    for name in names {
        if name == "prospero" && !prospero.is_file() {
            report.notes.push(format!(
                "prospero skipped: {} is not a file; pass --prospero FILE",
                prospero.display()
            ));
            continue;
        }
        let start = Instant::now();
        let seed = if name == "level-reseeded" {
            reseeded
        } else {
            options.seed
        };
        let scene = fidelity_scenes::build(name, &prospero, seed)?;
        let build_ms = ms_since(start);
        measure_scene(&scene, build_ms, options, &mut report)?;
    }
    report.best = best_method(&report.rows);
    report.targets = verdicts(&report.rows);
    if options.json {
        let text = serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?;
        println!("{text}");
    } else {
        print_table(&report);
    }
    Ok(ExitCode::SUCCESS)
}

fn scene_names(wanted: &[String]) -> Result<Vec<&'static str>, String> {
    if wanted.is_empty() {
        return Ok(NAMES.to_vec());
    }
    wanted
        .iter()
        .map(|w| {
            NAMES
                .iter()
                .copied()
                .find(|n| n == w)
                .ok_or_else(|| format!("unknown scene {w:?}; the scenes are {}", NAMES.join(", ")))
        })
        .collect()
}

fn ms_since(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

fn render_options(method: Method, scale: Scale) -> RenderOptions {
    RenderOptions {
        scale,
        reconstruction: method.reconstruction,
        upsample: method.upsample,
        ..RenderOptions::default()
    }
}

/// Every method at every scale on one scene, and its pictures when asked.
fn measure_scene(
    scene: &Scene,
    build_ms: f64,
    options: &Options,
    report: &mut Report,
) -> Result<(), String> {
    let camera = &scene.camera;
    let start = Instant::now();
    let truth_field = exact_field(&scene.terrain, camera, options.threads)
        .map_err(|e| format!("{}: {e}", scene.name))?;
    let truth = &truth_field.distance_px;
    let shade = RenderOptions::default().shade;
    let exact_image = render_direct(
        &scene.terrain,
        &scene.palette,
        camera,
        &shade,
        options.threads,
    )
    .map_err(|e| format!("{}: {e}", scene.name))?;
    report.scenes.push(SceneInfo {
        scene: scene.name,
        width: camera.width,
        height: camera.height,
        features: scene.features.len(),
        build_ms,
        truth_ms: ms_since(start),
    });
    for method in METHODS {
        for scale in SCALES {
            let start = Instant::now();
            let field = field_image(
                &scene.terrain,
                camera,
                &render_options(method, scale),
                options.threads,
            )
            .map_err(|e| format!("{} {}: {e}", scene.name, method.name))?;
            let render_ms = ms_since(start);
            let f = fidelity::measure(
                camera.width,
                camera.height,
                truth,
                &field.distance_px,
                &scene.features,
            )
            .map_err(|e| format!("{} {}: {e}", scene.name, method.name))?;
            let flip = if scale.divisor() == TARGET_SCALE {
                let image = render_twin(
                    &scene.terrain,
                    &scene.palette,
                    camera,
                    &render_options(method, scale),
                    options.threads,
                )
                .map_err(|e| format!("{} {}: {e}", scene.name, method.name))?;
                let diff = visdiff::compare(&exact_image, &image, &DiffOptions::default())
                    .map_err(|e| e.to_string())?;
                Some(diff.flip)
            } else {
                None
            };
            let extra = Extra {
                material_mismatch_pct: material_mismatch(&truth_field, &field),
                recall_1px: recall_1px(scene, truth, &field.distance_px),
                flip,
            };
            report
                .rows
                .push(row(scene.name, method.name, scale, &f, extra, render_ms));
            if method.name == "planes" && scale.divisor() == TARGET_SCALE {
                report
                    .lost
                    .extend(lost_features(scene, truth, &field.distance_px));
            }
        }
    }
    if let Some(dir) = &options.out {
        write_pictures(scene, dir, options.threads)?;
    }
    Ok(())
}

/// Pixels inside in both fields whose materials differ, percent of all pixels.
fn material_mismatch(truth: &FieldImage, test: &FieldImage) -> f64 {
    let differ = (0..truth.distance_px.len())
        .filter(|&i| {
            truth.distance_px[i] < 0.0
                && test.distance_px[i] < 0.0
                && truth.material[i] != test.material[i]
        })
        .count();
    100.0 * differ as f64 / truth.distance_px.len().max(1) as f64
}

/// Features at least 1 px wide present in both, over those present in the truth.
fn recall_1px(scene: &Scene, truth: &[f32], test: &[f32]) -> Option<f64> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let wide = scene.features.iter().filter(|f| f.width_px >= 1.0);
    let present: Vec<_> = wide
        .filter(|f| fidelity::feature_present(w, h, truth, f))
        .collect();
    let kept = present
        .iter()
        .filter(|f| fidelity::feature_present(w, h, test, f))
        .count();
    (!present.is_empty()).then(|| kept as f64 / present.len() as f64)
}

/// The features at least 2 px wide present in the truth and missing from `test`.
fn lost_features(scene: &Scene, truth: &[f32], test: &[f32]) -> Vec<LostFeature> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    scene
        .features
        .iter()
        .filter(|f| f.width_px >= fidelity::TARGET_WIDTH_PX)
        .filter(|f| fidelity::feature_present(w, h, truth, f))
        .filter(|f| !fidelity::feature_present(w, h, test, f))
        .map(|f| {
            let n = f.centre_line.len().max(1) as f32;
            let mid = f.centre_line.iter().fold(glam::Vec2::ZERO, |a, &p| a + p) / n;
            LostFeature {
                scene: scene.name,
                kind: f.kind,
                width_px: f.width_px,
                at_px: [mid.x, mid.y],
            }
        })
        .collect()
}

/// What a row measures besides [`Fidelity`].
struct Extra {
    material_mismatch_pct: f64,
    recall_1px: Option<f64>,
    flip: Option<f64>,
}

fn row(
    scene: &'static str,
    method: &'static str,
    scale: Scale,
    f: &Fidelity,
    extra: Extra,
    render_ms: f64,
) -> Row {
    Row {
        material_mismatch_pct: extra.material_mismatch_pct,
        recall_1px: extra.recall_1px,
        flip: extra.flip,
        scene,
        method,
        scale: scale.divisor(),
        mismatch_pct: f.mismatched_pct,
        solid_recall: f.solid.ratio(),
        gap_recall: f.gap.ratio(),
        solid_target_recall: f.solid_target.ratio(),
        gap_target_recall: f.gap_target.ratio(),
        mean_offset_px: f.mean_offset_px,
        max_offset_px: f.max_offset_px,
        solid_target: f.solid_target,
        gap_target: f.gap_target,
        solid: f.solid,
        gap: f.gap,
        render_ms,
    }
}

/// The method with the lowest mean mismatch over the scenes at the target scale.
fn best_method(rows: &[Row]) -> &'static str {
    let mean_mismatch = |m: &Method| {
        let v: Vec<f64> = target_rows(rows, m.name).map(|r| r.mismatch_pct).collect();
        v.iter().sum::<f64>() / v.len().max(1) as f64
    };
    METHODS
        .iter()
        .min_by(|a, b| mean_mismatch(a).total_cmp(&mean_mismatch(b)))
        .map_or("", |m| m.name)
}

fn target_rows<'a>(rows: &'a [Row], method: &'a str) -> impl Iterator<Item = &'a Row> + 'a {
    rows.iter()
        .filter(move |r| r.method == method && r.scale == TARGET_SCALE)
}

/// The targets at scale 1/16.
fn verdicts(rows: &[Row]) -> Vec<Verdict> {
    let mut out = Vec::new();
    for rival in ["divergence", "bicubic"] {
        out.push(beats_verdict(rows, rival));
    }
    out.push(recall_verdict(rows, "solid", 0.99, |r| r.solid_target));
    out.push(recall_verdict(rows, "gap", 0.95, |r| r.gap_target));
    out.push(offset_verdict(rows));
    out.extend(refine_verdicts(rows));
    out
}

/// The targets of `refine` at 1/16, on every scene: inside/outside and material mismatch at
/// most 0.01%, every feature at least 1 px wide kept, mean contour offset at most 0.05 px,
/// FLIP against the exact render at most 0.003.
fn refine_verdicts(rows: &[Row]) -> Vec<Verdict> {
    type Pick = fn(&Row) -> Option<f64>;
    let checks: [(&str, Pick, f64, bool); 5] = [
        (
            "inside/outside mismatch <= 0.01%",
            |r| Some(r.mismatch_pct),
            0.01,
            false,
        ),
        (
            "material mismatch <= 0.01%",
            |r| Some(r.material_mismatch_pct),
            0.01,
            false,
        ),
        (
            "recall of features >= 1 px wide 100%",
            |r| r.recall_1px,
            1.0,
            true,
        ),
        (
            "mean contour offset <= 0.05 px",
            |r| Some(r.mean_offset_px),
            0.05,
            false,
        ),
        (
            "FLIP against the exact render <= 0.003",
            |r| r.flip,
            0.003,
            false,
        ),
    ];
    checks
        .into_iter()
        .map(|(what, pick, goal, at_least)| {
            let judged: Vec<(&str, f64)> = target_rows(rows, "refine")
                .filter_map(|r| pick(r).map(|v| (r.scene, v)))
                .collect();
            let failing: Vec<String> = judged
                .iter()
                .filter(|(_, v)| if at_least { *v < goal } else { *v > goal })
                .map(|(s, v)| format!("{s} {v:.4}"))
                .collect();
            let worst = judged.iter().map(|(_, v)| *v).fold(
                if at_least { f64::INFINITY } else { 0.0 },
                |a, v| {
                    if at_least { a.min(v) } else { a.max(v) }
                },
            );
            Verdict {
                target: format!("refine {what} on every scene"),
                passed: (!judged.is_empty()).then_some(failing.is_empty()),
                detail: if failing.is_empty() {
                    format!("worst {worst:.4} over {} scenes", judged.len())
                } else {
                    format!("failing: {}", failing.join(", "))
                },
            }
        })
        .collect()
}

/// `planes` beats `rival` on a scene when its mismatch is lower and neither its solid nor its
/// gap recall of the target features (at least 2 px wide) is lower. Lower recall of the
/// thinner features is named in the detail without failing the target.
fn beats_verdict(rows: &[Row], rival: &'static str) -> Verdict {
    let mut failures = Vec::new();
    let mut remarks = Vec::new();
    for p in target_rows(rows, "planes") {
        let Some(r) = target_rows(rows, rival).find(|r| r.scene == p.scene) else {
            continue;
        };
        let lower_mismatch = p.mismatch_pct < r.mismatch_pct;
        let recall_ok = not_lower(p.solid_target_recall, r.solid_target_recall)
            && not_lower(p.gap_target_recall, r.gap_target_recall);
        if !(lower_mismatch && recall_ok) {
            failures.push(format!(
                "{}: mismatch {:.3}% vs {:.3}%, recall >= 2 px solid {} vs {}, gap {} vs {}",
                p.scene,
                p.mismatch_pct,
                r.mismatch_pct,
                pct(p.solid_target_recall),
                pct(r.solid_target_recall),
                pct(p.gap_target_recall),
                pct(r.gap_target_recall)
            ));
        }
        let all_widths_ok =
            not_lower(p.solid_recall, r.solid_recall) && not_lower(p.gap_recall, r.gap_recall);
        if !all_widths_ok {
            remarks.push(format!(
                "{}: recall of all widths solid {} vs {}, gap {} vs {}",
                p.scene,
                pct(p.solid_recall),
                pct(r.solid_recall),
                pct(p.gap_recall),
                pct(r.gap_recall)
            ));
        }
    }
    let measured = target_rows(rows, "planes").count() > 0;
    let mut detail = if failures.is_empty() {
        "on every scene".to_string()
    } else {
        failures.join("; ")
    };
    if !remarks.is_empty() {
        detail = format!("{detail} (below the target width: {})", remarks.join("; "));
    }
    Verdict {
        target: format!(
            "planes beats {rival} on every scene (lower mismatch, recall of >= 2 px features not lower)"
        ),
        passed: measured.then_some(failures.is_empty()),
        detail,
    }
}

/// `a >= b` where both recalls are defined (an undefined recall compares as equal).
fn not_lower(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => a >= b,
        _ => true,
    }
}

/// Pooled over the scenes: features of the kind at least 2 px wide kept by `planes`.
fn recall_verdict(rows: &[Row], kind: &str, goal: f64, pick: impl Fn(&Row) -> Recall) -> Verdict {
    let mut total = Recall::default();
    let mut lost = Vec::new();
    for r in target_rows(rows, "planes") {
        let recall = pick(r);
        total.in_truth += recall.in_truth;
        total.kept += recall.kept;
        if recall.kept < recall.in_truth {
            lost.push(format!(
                "{} lost {}",
                r.scene,
                recall.in_truth - recall.kept
            ));
        }
    }
    let ratio = total.ratio();
    Verdict {
        target: format!(
            ">= {:.0}% of {kind} features >= 2 px wide kept",
            goal * 100.0
        ),
        passed: ratio.map(|v| v >= goal),
        detail: format!(
            "{} of {} kept ({}){}",
            total.kept,
            total.in_truth,
            pct(ratio),
            if lost.is_empty() {
                String::new()
            } else {
                format!(": {}", lost.join(", "))
            }
        ),
    }
}

/// The mean contour offset of `planes` on every scene.
fn offset_verdict(rows: &[Row]) -> Verdict {
    let worst =
        target_rows(rows, "planes").max_by(|a, b| a.mean_offset_px.total_cmp(&b.mean_offset_px));
    Verdict {
        target: "mean contour offset < 0.5 px on every scene".into(),
        passed: worst.map(|r| r.mean_offset_px < 0.5),
        detail: worst.map_or("no scene".into(), |r| {
            format!("worst {} {:.3} px", r.scene, r.mean_offset_px)
        }),
    }
}

fn pct(v: Option<f64>) -> String {
    v.map_or("-".into(), |v| format!("{:.1}%", v * 100.0))
}

fn print_table(report: &Report) {
    for s in &report.scenes {
        println!(
            "scene {:<12} {}x{}, {} features; built in {:.0} ms, exact distances in {:.0} ms",
            s.scene, s.width, s.height, s.features, s.build_ms, s.truth_ms
        );
    }
    println!();
    println!(
        "{:<14} {:<10} {:>5} {:>10} {:>9} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9} {:>8} {:>9}",
        "scene",
        "method",
        "scale",
        "mismatch%",
        "material%",
        "flip",
        "all>=1",
        "solid",
        "gap",
        "solid>=2",
        "gap>=2",
        "mean off",
        "max off",
        "render ms"
    );
    for r in &report.rows {
        println!(
            "{:<14} {:<10} {:>5} {:>10.4} {:>9.4} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9.3} {:>8.2} {:>9.1}",
            r.scene,
            r.method,
            format!("1/{}", r.scale),
            r.mismatch_pct,
            r.material_mismatch_pct,
            r.flip.map_or("-".into(), |f| format!("{f:.4}")),
            pct(r.recall_1px),
            pct(r.solid_recall),
            pct(r.gap_recall),
            pct(r.solid_target_recall),
            pct(r.gap_target_recall),
            r.mean_offset_px,
            r.max_offset_px,
            r.render_ms
        );
    }
    println!();
    println!(
        "best at 1/{TARGET_SCALE} (lowest mean mismatch): {}",
        report.best
    );
    for v in &report.targets {
        let mark = match v.passed {
            Some(true) => "PASS",
            Some(false) => "FAIL",
            None => "N/A ",
        };
        println!("{mark} {}: {}", v.target, v.detail);
    }
    for l in &report.lost {
        println!(
            "planes 1/{TARGET_SCALE} lost: {} {:?} {} px wide around pixel ({:.0}, {:.0})",
            l.scene, l.kind, l.width_px, l.at_px[0], l.at_px[1]
        );
    }
    for n in &report.notes {
        println!("note: {n}");
    }
}

/// Scenes pictured by `--out`, with the centre of the crop (pixels).
const PICTURES: [(&str, (u32, u32)); 5] = [
    ("thin-lines", (128, 128)),
    ("thin-gaps", (128, 128)),
    ("corners", (662, 346)),
    ("level-intact", (1100, 315)),
    ("level", (1090, 900)),
];
/// Side of each crop, pixels, and the magnification it is drawn at.
const CROP: u32 = 256;
const ZOOM: u32 = 2;
/// Gap between the panels, pixels.
const GUTTER: u32 = 8;

/// Writes `DIR/fidelity-<scene>.png`: crops of the exact render and of every method at 1/16,
/// left to right in the order exact, bilinear, bicubic, divergence, planes, refine.
fn write_pictures(scene: &Scene, dir: &Path, threads: usize) -> Result<(), String> {
    let Some(&(_, centre)) = PICTURES.iter().find(|(n, _)| *n == scene.name) else {
        return Ok(());
    };
    let camera = &scene.camera;
    let exact_options = ExactRenderOptions {
        threads,
        ..ExactRenderOptions::default()
    };
    let exact = render_exact(&scene.terrain, &scene.palette, camera, &exact_options)
        .map_err(|e| format!("{} exact: {e}", scene.name))?;
    let mut panels = vec![exact];
    for method in METHODS {
        let options = render_options(method, Scale::Sixteenth);
        let image = render_twin(&scene.terrain, &scene.palette, camera, &options, threads)
            .map_err(|e| format!("{} {}: {e}", scene.name, method.name))?;
        panels.push(image);
    }
    let side = CROP * ZOOM;
    let n = panels.len() as u32;
    let mut sheet = RgbaImage::from_pixel(
        n * side + (n - 1) * GUTTER,
        side,
        image::Rgba([255, 255, 255, 255]),
    );
    let x0 = centre
        .0
        .saturating_sub(CROP / 2)
        .min(camera.width.saturating_sub(CROP));
    let y0 = centre
        .1
        .saturating_sub(CROP / 2)
        .min(camera.height.saturating_sub(CROP));
    for (i, panel) in panels.iter().enumerate() {
        let left = i as u32 * (side + GUTTER);
        for y in 0..side.min(panel.height() * ZOOM) {
            for x in 0..side.min(panel.width() * ZOOM) {
                let (sx, sy) = (x0 + x / ZOOM, y0 + y / ZOOM);
                if sx < panel.width() && sy < panel.height() {
                    sheet.put_pixel(left + x, y, *panel.get_pixel(sx, sy));
                }
            }
        }
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    save(&sheet, &dir.join(format!("fidelity-{}.png", scene.name)))?;
    // The whole view, exact and planes, to see the crop in context.
    save(
        &panels[0],
        &dir.join(format!("fidelity-{}-exact.png", scene.name)),
    )?;
    for name in ["planes", "refine"] {
        let i = METHODS
            .iter()
            .position(|m| m.name == name)
            .ok_or("no such method")?;
        save(
            &panels[i + 1],
            &dir.join(format!("fidelity-{}-{name}.png", scene.name)),
        )?;
    }
    Ok(())
}

fn save(image: &RgbaImage, path: &Path) -> Result<(), String> {
    image
        .save(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}
