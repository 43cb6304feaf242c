//! The sandbox driven through its real UI with egui_kittest on the adapter wgpu finds:
//! clicks carve and fill through the simulation, keys drive the vehicle, the panel's
//! toggles reach the renderer, a bad level shows its error, a saved replay loads and
//! verifies, and scrubbing reaches a tick's exact state. The terrain view after an edit
//! is compared with a committed snapshot.

mod common;

use common::{TestResult, check_snapshot, ensure};
use craterfield::field2d::{DEFAULT_LEVEL_RON, Level, Sdf};
use craterfield::render2d::{ExactRenderOptions, Reconstruction, Scale, render_exact};
use craterfield_demos::common::{FrameDriver, wgpu_setup};
use craterfield_demos::sandbox::view::{Screen, View};
use craterfield_demos::sandbox::{SandboxApp, TERRAIN_VIEW_LABEL, Verified};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::Vec2;

const SIZE: egui::Vec2 = egui::vec2(900.0, 600.0);

fn harness_with(level: Option<&std::path::Path>) -> Harness<'static, SandboxApp> {
    let level = level.map(|p| p.to_path_buf());
    let mut h = Harness::builder()
        .with_size(SIZE)
        .with_step_dt(1.0 / 60.0)
        .wgpu_setup(wgpu_setup())
        .build_eframe(move |cc| {
            SandboxApp::new(cc, level.as_deref(), FrameDriver::interactive(), false)
                .expect("the sandbox starts")
        });
    h.run_steps(2);
    h
}

fn harness() -> Harness<'static, SandboxApp> {
    harness_with(None)
}

fn screen(h: &Harness<'_, SandboxApp>) -> Screen {
    Screen {
        rect: h.get_by_label(TERRAIN_VIEW_LABEL).rect(),
        pixels_per_point: 1.0,
    }
}

fn view(h: &Harness<'_, SandboxApp>) -> Result<View, String> {
    h.state()
        .view()
        .ok_or_else(|| "the view is not set after the first frame".into())
}

/// A screen point over solid ground `depth` units below the surface, near the panel's
/// horizontal centre, and the point `height` units above that surface.
fn ground_and_air(
    h: &Harness<'_, SandboxApp>,
    depth: f32,
    height: f32,
) -> Result<(egui::Pos2, egui::Pos2), String> {
    let s = screen(h);
    let v = view(h)?;
    let terrain = h.state().session().world().terrain();
    let x = s.rect.center().x + 30.0;
    let mut y = s.rect.top() + 5.0;
    while y < s.rect.bottom() {
        let w = v.to_world(&s, egui::pos2(x, y));
        // Ground at least 100 units thick under the surface (not a floating island), with
        // open air above it.
        let solid_below =
            (0..=10).all(|k| terrain.distance(w - Vec2::new(0.0, k as f32 * 10.0)) < 0.0);
        let air_above = (1..=4).all(|k| {
            terrain.distance(w + Vec2::new(0.0, k as f32 * height.max(20.0) / 4.0 + 4.0)) > 0.0
        });
        if solid_below && air_above {
            let ground = v.to_screen(&s, w - Vec2::new(0.0, depth));
            let air = v.to_screen(&s, w + Vec2::new(0.0, height));
            return Ok((ground, air));
        }
        y += 1.0;
    }
    Err("no ground under the panel's centre".into())
}

fn click(h: &mut Harness<'_, SandboxApp>, pos: egui::Pos2, button: egui::PointerButton) {
    h.event(egui::Event::PointerMoved(pos));
    h.step();
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos,
            button,
            pressed,
            modifiers: egui::Modifiers::default(),
        });
        h.step();
    }
    // The edit waits for the next tick boundary.
    h.run_steps(3);
}

fn world_at(h: &Harness<'_, SandboxApp>, pos: egui::Pos2) -> Result<Vec2, String> {
    Ok(view(h)?.to_world(&screen(h), pos))
}

/// Fraction of the pixels within `r` points of `pos` that differ between two renders.
fn changed_fraction(a: &image::RgbaImage, b: &image::RgbaImage, pos: egui::Pos2, r: i32) -> f64 {
    let (mut changed, mut all) = (0, 0);
    for dy in -r..=r {
        for dx in -r..=r {
            let (x, y) = (pos.x as i32 + dx, pos.y as i32 + dy);
            if x < 0 || y < 0 || x as u32 >= a.width() || y as u32 >= a.height() {
                continue;
            }
            all += 1;
            if a.get_pixel(x as u32, y as u32) != b.get_pixel(x as u32, y as u32) {
                changed += 1;
            }
        }
    }
    f64::from(changed) / f64::from(all.max(1))
}

fn crop_to_view(h: &Harness<'_, SandboxApp>, image: &image::RgbaImage) -> image::RgbaImage {
    let r = screen(h).rect;
    image::imageops::crop_imm(
        image,
        r.left() as u32,
        r.top() as u32,
        r.width() as u32,
        r.height() as u32,
    )
    .to_image()
}

/// Zooms in with the wheel over the terrain view's centre; returns the zoom factor seen.
fn wheel_zoom_in(h: &mut Harness<'_, SandboxApp>) -> Result<f32, String> {
    let before = view(h)?.units_per_pixel;
    let at = screen(h).rect.center();
    h.event(egui::Event::PointerMoved(at));
    h.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, 240.0),
        phase: egui::TouchPhase::Move,
        source: egui::MouseWheelSource::Unknown,
        modifiers: egui::Modifiers::default(),
    });
    h.run_steps(20);
    Ok(before / view(h)?.units_per_pixel)
}

fn a_click_carves_and_a_right_click_fills() -> TestResult {
    let mut h = harness();
    h.set_render_cursor(false);
    h.get_by_label("Brush").click();
    h.run_steps(2);
    h.get_by_role_and_label(egui::Role::Slider, "radius")
        .set_value_accesskit(90.0);
    h.run_steps(2);
    ensure(
        h.state().brush().radius == 90.0,
        format!("brush radius {}", h.state().brush().radius),
    )?;
    let zoom = wheel_zoom_in(&mut h)?;
    ensure(zoom > 1.5, format!("the wheel zoomed by {zoom} only"))?;
    let (ground, air) = ground_and_air(&h, 30.0, 200.0)?;
    let before = h.render()?;
    let events = h.state().session().world().terrain().events_applied();
    let g = world_at(&h, ground)?;
    ensure(
        h.state().session().world().terrain().distance(g) < 0.0,
        "the click point starts solid",
    )?;
    click(&mut h, ground, egui::PointerButton::Primary);
    let terrain = h.state().session().world().terrain();
    ensure(
        terrain.events_applied() == events + 1,
        format!(
            "one event applied, not {}",
            terrain.events_applied() - events
        ),
    )?;
    ensure(
        terrain.distance(g) > 0.0,
        "the click point is air after the carve",
    )?;
    ensure(
        h.state().session().timeline().edits().len() == 1,
        "the edit is recorded",
    )?;
    let after = h.render()?;
    let near = changed_fraction(&before, &after, ground, 8);
    ensure(
        near > 0.5,
        format!(
            "only {:.0}% of the pixels at the click changed",
            near * 100.0
        ),
    )?;
    check_snapshot("sandbox_carved", &crop_to_view(&h, &after))?;

    let a = world_at(&h, air)?;
    ensure(
        h.state().session().world().terrain().distance(a) > 0.0,
        "the fill point starts in the air",
    )?;
    click(&mut h, air, egui::PointerButton::Secondary);
    ensure(
        h.state().session().world().terrain().distance(a) < 0.0,
        "the fill point is solid after the fill",
    )?;
    ensure(
        h.state().session().timeline().edits().len() == 2,
        "both edits are recorded",
    )
}

/// What the panel shows is the terrain as the exact CPU reference draws it, colours
/// included (the texture reaches egui's gamma-space blending unchanged): outside the
/// bodies, their labels and the aim line, almost every pixel agrees.
fn the_terrain_view_shows_the_exact_render() -> TestResult {
    let mut h = harness();
    h.set_render_cursor(false);
    h.run_steps(1);
    let image = h.render()?;
    let shown = crop_to_view(&h, &image);
    let camera = view(&h)?.camera([shown.width(), shown.height()]);
    let app = h.state();
    let level = app.session().level();
    let palette: Vec<[u8; 3]> = level.materials().iter().map(|m| m.color).collect();
    let exact = render_exact(
        app.session().world().terrain(),
        &palette,
        &camera,
        &ExactRenderOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    let off = shown
        .pixels()
        .zip(exact.pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0.iter()).any(|(x, y)| x.abs_diff(*y) > 12))
        .count();
    let fraction = off as f64 / f64::from(shown.width() * shown.height());
    ensure(
        fraction < 0.02,
        format!(
            "{:.1}% of the terrain view differs from the exact render",
            fraction * 100.0
        ),
    )
}

fn vehicle_x(h: &Harness<'_, SandboxApp>) -> Result<f32, String> {
    h.state()
        .session()
        .world()
        .vehicle(0)
        .map(|b| b.pos.x)
        .ok_or_else(|| "no vehicle 0".into())
}

fn keys_drive_the_vehicle() -> TestResult {
    let mut idle = harness();
    idle.run_steps(60);
    let mut driven = harness();
    driven.key_down(egui::Key::D);
    driven.run_steps(60);
    driven.key_up(egui::Key::D);
    driven.run_steps(1);
    let ticks = (
        idle.state().session().world().tick(),
        driven.state().session().world().tick(),
    );
    ensure(
        ticks.0 >= 55 && ticks.1 >= 55,
        format!("ticks ran: {ticks:?}"),
    )?;
    let (x0, x1) = (vehicle_x(&idle)?, vehicle_x(&driven)?);
    ensure(
        x1 > x0 + 20.0,
        format!("holding D moved the vehicle from x {x0} to {x1} only"),
    )?;
    let mut back = harness();
    back.key_down(egui::Key::ArrowLeft);
    back.run_steps(60);
    let x2 = vehicle_x(&back)?;
    ensure(
        x2 < x0 - 20.0,
        format!("holding left moved the vehicle from x {x0} to {x2} only"),
    )
}

fn panel_toggles_change_the_renderer_options() -> TestResult {
    let mut h = harness();
    let before = h.render()?;
    h.get_by_label("Render").click();
    h.run_steps(2);
    h.get_by_label("planes").click();
    h.run_steps(2);
    h.get_by_label("1/4").click();
    h.run_steps(2);
    let o = h.state().render_options().ok_or("no renderer")?.clone();
    ensure(
        o.reconstruction == Reconstruction::Planes,
        format!("mode {:?}", o.reconstruction),
    )?;
    ensure(o.scale == Scale::Quarter, format!("scale {:?}", o.scale))?;
    h.get_by_label("Overlays").click();
    h.run_steps(2);
    h.get_by_label("explosion-grid cells").click();
    h.run_steps(2);
    let after = h.render()?;
    let view = crop_to_view(&h, &after);
    let old = crop_to_view(&h, &before);
    let differing = view
        .pixels()
        .zip(old.pixels())
        .filter(|(a, b)| a != b)
        .count();
    ensure(
        differing * 10 > (view.width() * view.height()) as usize,
        format!("the cell overlay changed only {differing} pixels"),
    )
}

fn a_bad_level_shows_its_error() -> TestResult {
    let dir = std::env::temp_dir().join(format!("sandbox-ui-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let bad = dir.join("bad.ron");
    // Break one primitive's radius deep in the graph.
    let broken = DEFAULT_LEVEL_RON.replacen("radius: ", "radius: -", 1);
    std::fs::write(&bad, broken).map_err(|e| e.to_string())?;
    let mut h = harness_with(Some(&bad));
    let e = h
        .state()
        .level_error()
        .ok_or("a bad level given at start shows no error")?
        .to_string();
    ensure(
        e.contains("radius") && e.contains("must be"),
        format!("the error names the field: {e}"),
    )?;
    ensure(
        h.query_by_label_contains("Level error").is_some(),
        "the error panel is shown",
    )?;

    // The same through the panel's field, and a file that is not a level at all.
    h.get_by_label("Level").click();
    h.run_steps(2);
    let garbage = dir.join("garbage.ron");
    std::fs::write(&garbage, [0xff, 0xfe, 0x00, 0x41]).map_err(|e| e.to_string())?;
    h.get_by_label("Level file").focus();
    h.get_by_label("Level file")
        .type_text(&garbage.display().to_string());
    h.run_steps(2);
    h.get_by_label("Load level").click();
    h.run_steps(3);
    let e = h
        .state()
        .level_error()
        .ok_or("no error for a binary file")?
        .to_string();
    ensure(
        e.contains("garbage.ron"),
        format!("the error names the file: {e}"),
    )?;
    ensure(
        h.query_by_label_contains("garbage.ron").is_some(),
        "the error is on screen",
    )?;
    ensure(
        h.state().session().level().name() == Level::default_level().name(),
        "the match continues",
    )
}

fn replay_path(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("sandbox-ui-{}-{name}.replay", std::process::id()))
}

fn set_replay_path(h: &mut Harness<'_, SandboxApp>, path: &std::path::Path) {
    let field = h.get_by_label("Replay file");
    field.focus();
    field.type_text(&path.display().to_string());
    h.run_steps(2);
}

fn a_saved_replay_loads_and_verifies() -> TestResult {
    let mut h = harness();
    let (ground, _) = ground_and_air(&h, 10.0, 0.0)?;
    click(&mut h, ground, egui::PointerButton::Primary);
    h.key_down(egui::Key::D);
    h.run_steps(40);
    h.key_up(egui::Key::D);
    h.run_steps(20);
    let path = replay_path("saved");
    // Clear the default name first.
    h.get_by_label("Replay file").focus();
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.key_press(egui::Key::Backspace);
    set_replay_path(&mut h, &path);
    h.get_by_label("Save replay").click();
    h.run_steps(2);
    let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let recorded = craterfield::net::replay::Replay::decode(&bytes)
        .map_err(|e| e.to_string())?
        .ticks();
    ensure(recorded >= 60, format!("only {recorded} ticks saved"))?;
    h.get_by_label("Load replay").click();
    h.run_steps(2);
    match h.state().session().verified() {
        Some(Verified::Passed { ticks, hashes }) => {
            ensure(
                *ticks == recorded,
                format!("verified {ticks} of {recorded} ticks"),
            )?;
            ensure(*hashes >= 2, format!("{hashes} hashes compared"))?;
        }
        other => return Err(format!("replay verify: {other:?}").into()),
    }
    ensure(
        h.query_by_label_contains("replay verify: ok").is_some(),
        "the panel shows the verification",
    )?;
    ensure(
        h.state().session().timeline().edits().len() == 1,
        "the edit came back with the replay",
    )?;
    std::fs::remove_file(&path).ok();
    Ok(())
}

fn scrubbing_reaches_the_ticks_state() -> TestResult {
    let mut h = harness();
    let (ground, _) = ground_and_air(&h, 10.0, 0.0)?;
    h.key_down(egui::Key::D);
    h.run_steps(30);
    click(&mut h, ground, egui::PointerButton::Primary);
    h.run_steps(140);
    h.key_up(egui::Key::D);
    h.run_steps(10);
    let ticks = h.state().session().timeline().ticks();
    ensure(ticks > 150, format!("only {ticks} ticks recorded"))?;
    for target in [17, 130, ticks - 3, 40] {
        let expected = h
            .state()
            .session()
            .timeline()
            .hash_at(target)
            .ok_or("no hash")?;
        h.get_by_role_and_label(egui::Role::Slider, "tick")
            .set_value_accesskit(f64::from(target));
        h.run_steps(2);
        let world = h.state().session().world();
        ensure(
            world.tick() == target,
            format!("scrubbed to {} instead of {target}", world.tick()),
        )?;
        ensure(
            world.state_hash() == expected,
            format!(
                "tick {target}: hash {:#x}, recorded {expected:#x}",
                world.state_hash()
            ),
        )?;
    }
    ensure(
        h.state().session().divergence().is_none(),
        "playback diverged",
    )
}

/// A file dropped on the window, as eframe hands it over.
#[derive(Debug)]
struct DroppedPath(std::path::PathBuf);

impl egui::DroppedFile for DroppedPath {
    fn path(&self) -> &std::path::Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

fn drop_file(h: &mut Harness<'_, SandboxApp>, path: &std::path::Path) {
    h.input_mut()
        .dropped_files
        .push(std::sync::Arc::new(DroppedPath(path.to_path_buf())));
    h.run_steps(2);
}

fn dropped_levels_and_replays_load() -> TestResult {
    let mut h = harness();
    // The default level under another name, written where a user would keep it.
    let level_file =
        std::env::temp_dir().join(format!("sandbox-ui-{}-other.ron", std::process::id()));
    let renamed = DEFAULT_LEVEL_RON.replacen("name: \"Default\"", "name: \"Other\"", 1);
    std::fs::write(&level_file, renamed).map_err(|e| e.to_string())?;
    drop_file(&mut h, &level_file);
    let expected = Level::load(&level_file).map_err(|e| e.to_string())?;
    std::fs::remove_file(&level_file).ok();
    ensure(expected.name() == "Other", "the renamed level")?;
    ensure(
        h.state().session().level().name() == expected.name(),
        format!(
            "a dropped level starts a match on it, not on {}",
            h.state().session().level().name()
        ),
    )?;
    ensure(
        h.state().level_error().is_none(),
        "no error for a good level",
    )?;

    // A replay of this match, dropped back: it loads and verifies.
    h.run_steps(60);
    let path = replay_path("dropped");
    let bytes = h.state().session().replay_bytes()?;
    std::fs::write(&path, bytes).map_err(|e| e.to_string())?;
    drop_file(&mut h, &path);
    std::fs::remove_file(&path).ok();
    ensure(
        matches!(
            h.state().session().verified(),
            Some(Verified::Passed { .. })
        ),
        format!(
            "the dropped replay verifies: {:?}",
            h.state().session().verified()
        ),
    )?;

    // A dropped file that is not a level shows its error and keeps the match.
    let bad = std::env::temp_dir().join(format!("sandbox-ui-{}-dropped.ron", std::process::id()));
    std::fs::write(&bad, "not a level").map_err(|e| e.to_string())?;
    drop_file(&mut h, &bad);
    std::fs::remove_file(&bad).ok();
    let e = h
        .state()
        .level_error()
        .ok_or("no error for a dropped bad level")?;
    ensure(
        e.contains("dropped.ron"),
        format!("the error names the file: {e}"),
    )?;
    ensure(
        h.state().session().level().name() == expected.name(),
        "the match on the good level goes on",
    )
}

fn main() {
    common::run(&[
        (
            "a_click_carves_and_a_right_click_fills",
            a_click_carves_and_a_right_click_fills,
        ),
        (
            "the_terrain_view_shows_the_exact_render",
            the_terrain_view_shows_the_exact_render,
        ),
        ("keys_drive_the_vehicle", keys_drive_the_vehicle),
        (
            "panel_toggles_change_the_renderer_options",
            panel_toggles_change_the_renderer_options,
        ),
        ("a_bad_level_shows_its_error", a_bad_level_shows_its_error),
        (
            "a_saved_replay_loads_and_verifies",
            a_saved_replay_loads_and_verifies,
        ),
        (
            "scrubbing_reaches_the_ticks_state",
            scrubbing_reaches_the_ticks_state,
        ),
        (
            "dropped_levels_and_replays_load",
            dropped_levels_and_replays_load,
        ),
    ])
}
