//! The 3D viewer driven through its real UI with egui_kittest on wgpu: the scene renders,
//! the panel's switches recompile the plan, the camera follows drags and keys, the scene
//! picker and a bad scene file behave, and the count mode counts. Run with the other UI
//! tests (see `common`).

mod common;

use std::path::PathBuf;
use std::time::Duration;

use common::{TestResult, check_snapshot, ensure};
use craterfield::march3d::compile::Optimization;
use craterfield_demos::common::{FrameDriver, wgpu_setup};
use craterfield_demos::viewer3d::{CameraMode, SceneSource, Viewer3dApp};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use image::RgbaImage;

/// The harness window in points (one pixel per point). Small, because every frame marches
/// the whole view on the CPU under lavapipe; the panel scrolls what does not fit.
const SIZE: [f32; 2] = [640.0, 400.0];

/// The scene of the tests that need any world: terrain, sky and a few objects, at a
/// fraction of the forest's cost per frame.
const CHEAP_WORLD: &str = "sparse";

/// Frames the count test waits for the count at most (with a pause before each).
const COUNT_WAIT_FRAMES: usize = 120;

fn main() {
    common::run(&[
        (
            "default_view_renders_sky_and_ground",
            default_view_renders_sky_and_ground,
        ),
        (
            "the_view_shows_the_marchers_bytes",
            the_view_shows_the_marchers_bytes,
        ),
        (
            "optimization_switch_recompiles_the_plan",
            optimization_switch_recompiles_the_plan,
        ),
        (
            "drag_and_keys_move_the_camera",
            drag_and_keys_move_the_camera,
        ),
        (
            "another_builtin_changes_the_picture",
            another_builtin_changes_the_picture,
        ),
        (
            "bad_scene_file_shows_its_error",
            bad_scene_file_shows_its_error,
        ),
        (
            "count_mode_counts_evaluations",
            count_mode_counts_evaluations,
        ),
    ])
}

/// The viewer on `source`, one frame run.
fn viewer(source: SceneSource) -> Harness<'static, Viewer3dApp> {
    let mut harness = Harness::builder()
        .with_size(SIZE)
        .wgpu_setup(wgpu_setup())
        .build_eframe(|cc| {
            Viewer3dApp::new(cc, source, FrameDriver::interactive(), false)
                .unwrap_or_else(|e| panic!("the viewer did not start: {e}"))
        });
    harness.run();
    harness
}

fn builtin(name: &str) -> SceneSource {
    SceneSource::Builtin(name.into())
}

/// What the panel shows are the marcher's own bytes, colours included: the texture reaches
/// egui's gamma-space blending unchanged (a view that decoded sRGB would darken it).
fn the_view_shows_the_marchers_bytes() -> TestResult {
    let mut harness = viewer(builtin(CHEAP_WORLD));
    harness.set_render_cursor(false);
    harness.run();
    let window = harness.render()?;
    let app = harness.state();
    let (Some(plan), Some(camera), Some(rect), Some([w, h])) =
        (app.plan(), app.camera(), app.image_rect(), app.image_size())
    else {
        return Err("the viewer drew nothing".into());
    };
    let shown =
        image::imageops::crop_imm(&window, rect.left() as u32, rect.top() as u32, w, h).to_image();
    let ctx = craterfield::gpu::GpuContext::new().map_err(|e| e.to_string())?;
    let mut marcher = craterfield::march3d::gpu::Marcher::new(&ctx.device, &ctx.queue)
        .map_err(|e| e.to_string())?;
    let bytes = marcher
        .render_to_rgba(plan, &camera, w, h)
        .map_err(|e| e.to_string())?;
    let off = shown
        .as_raw()
        .chunks(4)
        .zip(bytes.chunks(4))
        .filter(|(a, b)| a[..3].iter().zip(&b[..3]).any(|(x, y)| x.abs_diff(*y) > 6))
        .count();
    let fraction = off as f64 / f64::from(w * h);
    ensure(
        fraction < 0.01,
        format!(
            "{:.1}% of the view differs from the marcher's bytes",
            fraction * 100.0
        ),
    )
}

/// Opens the builtin `name` through the panel's scene picker.
fn pick_scene(harness: &mut Harness<'static, Viewer3dApp>, name: &str) {
    harness.get_by_label("Scene").click();
    harness.run();
    harness.get_by_label(name).click();
    harness.run();
}

/// The window's image and the part of it the view covers.
fn render(harness: &mut Harness<'static, Viewer3dApp>) -> Result<(RgbaImage, RgbaImage), String> {
    let rect = harness
        .state()
        .image_rect()
        .ok_or("the view was not laid out")?;
    let image = harness.render()?;
    let view = image::imageops::crop_imm(
        &image,
        rect.min.x.round() as u32,
        rect.min.y.round() as u32,
        rect.width().round() as u32,
        rect.height().round() as u32,
    )
    .to_image();
    Ok((image, view))
}

/// Mean colour of the rows `rows` (fractions of the height) of `image`.
fn band_mean(image: &RgbaImage, rows: std::ops::Range<f32>) -> [f64; 3] {
    let h = image.height() as f32;
    let (y0, y1) = ((rows.start * h) as u32, (rows.end * h) as u32);
    let mut sum = [0.0; 3];
    let mut n = 0.0;
    for y in y0..y1 {
        for x in 0..image.width() {
            let p = image.get_pixel(x, y);
            for (s, c) in sum.iter_mut().zip(p.0) {
                *s += f64::from(c);
            }
            n += 1.0;
        }
    }
    sum.map(|s| s / f64::max(n, 1.0))
}

/// Mean absolute difference per channel of two images of one size.
fn mean_difference(a: &RgbaImage, b: &RgbaImage) -> f64 {
    let total: f64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(x, y)| f64::from(x.abs_diff(*y)))
        .sum();
    total / a.as_raw().len().max(1) as f64
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Covers the panel's times (different on every run) before a snapshot.
fn mask_times(harness: &mut Harness<'static, Viewer3dApp>) {
    let rects: Vec<egui::Rect> = ["viewer CPU", "march pass"]
        .iter()
        .flat_map(|text| harness.query_all_by_label_contains(text).map(|n| n.rect()))
        .collect();
    for rect in rects {
        harness.mask(rect);
    }
}

fn default_view_renders_sky_and_ground() -> TestResult {
    let mut harness = viewer(builtin(SceneSource::DEFAULT_BUILTIN));
    let app = harness.state();
    ensure(app.error().is_none(), format!("error: {:?}", app.error()))?;
    ensure(app.scene_name() == Some("forest"), "the forest is open")?;
    let stats = app.plan_stats().ok_or("no plan")?.clone();
    ensure(
        stats.visible > 0 && stats.culled() > 0,
        format!("culling: {stats:?}"),
    )?;
    let (_, view) = render(&mut harness)?;
    let sky = band_mean(&view, 0.0..0.1);
    let ground = band_mean(&view, 0.75..1.0);
    // The sky is a bright blue; the ground below is darker and not blue.
    ensure(
        sky[2] > sky[0] + 20.0 && sky[2] > 120.0,
        format!("sky {sky:?}"),
    )?;
    ensure(
        distance(sky, ground) > 40.0,
        format!("sky {sky:?}, ground {ground:?}"),
    )?;
    ensure(
        ground[2] < sky[2],
        format!("sky {sky:?}, ground {ground:?}"),
    )?;
    mask_times(&mut harness);
    let (masked, _) = render(&mut harness)?;
    check_snapshot("viewer3d_default", &masked)
}

fn optimization_switch_recompiles_the_plan() -> TestResult {
    let mut harness = viewer(builtin(CHEAP_WORLD));
    let key = harness.state().plan().ok_or("no plan")?.key;
    let guards = Optimization::AabbGuards;
    harness.get_by_label(guards.name()).click();
    harness.run();
    let app = harness.state();
    let options = app.compile_options().ok_or("no options")?;
    ensure(!options.on(guards), "the switch turned the guards off")?;
    let plan = app.plan().ok_or("no plan")?;
    ensure(plan.key != key, "the plan was emitted again")?;
    ensure(
        plan.nodes.iter().all(|n| n.guard.is_none()),
        "no node has a guard",
    )?;
    harness.get_by_label(guards.name()).click();
    harness.run();
    let app = harness.state();
    ensure(
        app.compile_options().is_some_and(|o| o.on(guards)),
        "back on",
    )?;
    ensure(
        app.plan().map(|p| p.key) == Some(key),
        "the first plan is back",
    )
}

fn drag_and_keys_move_the_camera() -> TestResult {
    let mut harness = viewer(builtin(CHEAP_WORLD));
    let start = harness.state().camera().ok_or("no camera")?;
    let centre = harness.state().image_rect().ok_or("no view")?.center();
    // Orbit: drag right.
    harness.drag_at(centre);
    harness.hover_at(centre + egui::vec2(60.0, 0.0));
    harness.drop_at(centre + egui::vec2(60.0, 0.0));
    harness.run();
    let orbited = harness.state().camera().ok_or("no camera")?;
    ensure(
        orbited.position != start.position,
        "the drag orbited the eye",
    )?;
    ensure(
        orbited.forward.x > start.forward.x,
        format!("dragging right turns the view right: {start:?} -> {orbited:?}"),
    )?;
    // The arrow keys orbit too.
    harness.key_down(egui::Key::ArrowLeft);
    harness.step();
    harness.key_up(egui::Key::ArrowLeft);
    harness.run();
    let turned = harness.state().camera().ok_or("no camera")?;
    ensure(
        turned.forward.x < orbited.forward.x,
        "the left arrow turns left",
    )?;
    // F switches to flight; W flies forward.
    harness.key_press(egui::Key::F);
    harness.run();
    ensure(
        harness.state().camera_mode() == CameraMode::Fly,
        "F toggles flight",
    )?;
    harness.key_down(egui::Key::W);
    harness.step();
    harness.key_up(egui::Key::W);
    harness.run();
    let flown = harness.state().camera().ok_or("no camera")?;
    let moved = flown.position - turned.position;
    ensure(
        moved.dot(turned.forward) > 0.1,
        format!("W moves ahead: {moved:?}"),
    )?;
    ensure(
        (flown.forward - turned.forward).length() < 1e-5,
        "W does not turn",
    )?;
    // The panel switches back.
    harness.get_by_label("Orbit").click();
    harness.run();
    ensure(
        harness.state().camera_mode() == CameraMode::Orbit,
        "the panel's Orbit",
    )
}

fn another_builtin_changes_the_picture() -> TestResult {
    let mut harness = viewer(builtin(CHEAP_WORLD));
    let (_, before) = render(&mut harness)?;
    pick_scene(&mut harness, "scene0");
    let app = harness.state();
    ensure(
        app.scene_name() == Some("scene0"),
        format!("{:?}", app.source()),
    )?;
    let (_, after) = render(&mut harness)?;
    ensure(
        before.dimensions() == after.dimensions(),
        "the view kept its size",
    )?;
    let change = mean_difference(&before, &after);
    ensure(change > 2.0, format!("mean difference {change:.2} of 255"))
}

fn bad_scene_file_shows_its_error() -> TestResult {
    let path = scratch_file(
        "viewer3d_bad_scene.ron",
        "Scene(name: \"broken\", camera: (",
    )?;
    let mut harness = viewer(SceneSource::File(path.clone()));
    let app = harness.state();
    ensure(app.scene_name().is_none(), "no scene is shown")?;
    let error = app.error().ok_or("no error")?.to_string();
    ensure(
        error.contains("viewer3d_bad_scene.ron"),
        format!("names the file: {error}"),
    )?;
    ensure(
        harness.query_by_label_contains("scene syntax").is_some(),
        "the panel shows the syntax error",
    )?;
    // The picker still opens a builtin.
    pick_scene(&mut harness, CHEAP_WORLD);
    let app = harness.state();
    let recovered = app.scene_name() == Some(CHEAP_WORLD) && app.error().is_none();
    ensure(recovered, "the picker opened a builtin")?;
    std::fs::remove_file(&path).map_err(|e| e.to_string())?;
    Ok(())
}

fn count_mode_counts_evaluations() -> TestResult {
    let mut harness = viewer(builtin(CHEAP_WORLD));
    harness.get_by_label("Count evaluations (CPU)").click();
    harness.run();
    // Each frame marches the view too; wait between frames, not in them.
    for _ in 0..COUNT_WAIT_FRAMES {
        if harness.state().count_report().is_some() {
            break;
        }
        std::thread::sleep(Duration::from_millis(500));
        harness.step();
    }
    harness.run();
    let report = harness
        .state()
        .count_report()
        .ok_or("the count did not finish")?
        .clone();
    ensure(report.evals_mean > 0.0, format!("{report:?}"))?;
    ensure(
        report.evals.max >= report.evals.median,
        format!("{report:?}"),
    )?;
    ensure(report.steps_mean > 0.0, format!("{report:?}"))?;
    ensure(
        harness.query_by_label_contains("counted at").is_some(),
        "the panel shows the count",
    )
}

/// Writes `text` to a file named `name` in the system's temporary folder.
fn scratch_file(name: &str, text: &str) -> Result<PathBuf, String> {
    let path = std::env::temp_dir().join(format!("{}-{name}", std::process::id()));
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}
