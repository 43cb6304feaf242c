//! Bevy renders a cratered level headlessly through the plugin (a 2D camera with a
//! `TerrainView`, drawing into an image), and the picture matches the library's CPU twin
//! of the same view within the project's GPU/twin tolerance; a sprite spawned over the
//! terrain is drawn over it. The library's renderers on Bevy's own wgpu 29 device.
//!
//! Without an adapter the tests report themselves ignored, and fail when `CI` is set.

use std::sync::{Arc, Mutex};

use bevy::camera::RenderTarget;
use bevy::core_pipeline::tonemapping::DebandDither;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::pipelined_rendering::PipelinedRenderingPlugin;
use bevy::render::render_resource::TextureFormat;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use craterfield_bevy::craterfield::field2d::{Event, Graph, Level, Sdf, Terrain};
use craterfield_bevy::craterfield::render2d::twin::render_twin;
use craterfield_bevy::craterfield::render2d::{
    Camera as TerrainCamera, ExactRenderOptions, render_exact,
};
use craterfield_bevy::craterfield::visdiff::{DiffOptions, compare};
use craterfield_bevy::prelude::*;
use craterfield_bevy::{TerrainFrameCosts, install_match};
use image::RgbaImage;
use libtest_mimic::{Arguments, Failed, Trial};

const SIZE: (u32, u32) = (480, 270);

/// Craters where the ground is, on the default level.
fn crater_events(level: &Level, count: u32) -> Vec<Event> {
    let terrain = level.terrain().expect("the default level builds a terrain");
    let b = level.bounds();
    (0..count)
        .map(|i| {
            let x = b.min.x + (b.max.x - b.min.x) * ((i as f32 * 0.618_034).fract());
            let mut y = b.max.y;
            while y > b.min.y && terrain.distance(Vec2::new(x, y)) > 0.0 {
                y -= 8.0;
            }
            let radius = 12.0 + 30.0 * ((i as f32 * 0.414_214).fract());
            Event::carve(Vec2::new(x, y), radius).expect("a finite explosion")
        })
        .collect()
}

fn view_camera(level: &Level) -> TerrainCamera {
    let b = level.bounds();
    TerrainCamera {
        center: (b.min + b.max) * 0.5,
        units_per_pixel: (b.max.x - b.min.x) / SIZE.0 as f32,
        width: SIZE.0,
        height: SIZE.1,
    }
}

/// A headless app: no window, the render world in step with the main world.
fn headless_app() -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            })
            .disable::<WinitPlugin>()
            .disable::<PipelinedRenderingPlugin>(),
    )
    .add_plugins(CraterfieldPlugin);
    app.finish();
    app.cleanup();
    app
}

/// What Bevy drew, and the terrain and palette it drew.
struct Rendered {
    image: RgbaImage,
    terrain: Terrain<Graph>,
    palette: Vec<[u8; 3]>,
}

/// Renders the cratered default level (and optionally a sprite) through the plugin.
fn render_through_bevy(sprite: Option<(Vec2, Vec2, Color)>) -> Result<Rendered, Failed> {
    let level = Level::default_level();
    let mut cf = Craterfield::new(&level, Settings::default(), 1)?;
    for e in crater_events(&level, 60) {
        cf.apply_edit(e)?;
    }
    let terrain = cf.world().terrain().clone();
    let palette = cf.palette().to_vec();
    let mut app = headless_app();
    app.world_mut().commands().queue(install_match(cf));
    let target = Image::new_target_texture(SIZE.0, SIZE.1, TextureFormat::Rgba8UnormSrgb, None);
    let handle = app.world_mut().resource_mut::<Assets<Image>>().add(target);
    let c = view_camera(&level);
    app.world_mut().spawn((
        Camera2d,
        RenderTarget::Image(handle.clone().into()),
        TerrainView::default(),
        DebandDither::Disabled,
        Transform::from_xyz(c.center.x, c.center.y, 0.0),
        Projection::Orthographic(OrthographicProjection {
            scale: c.units_per_pixel,
            ..OrthographicProjection::default_2d()
        }),
    ));
    if let Some((at, size, color)) = sprite {
        app.world_mut().spawn((
            Sprite::from_color(color, size),
            Transform::from_xyz(at.x, at.y, 1.0),
        ));
    }
    for _ in 0..3 {
        app.update();
    }
    let captured: Arc<Mutex<Option<Image>>> = Arc::default();
    let slot = captured.clone();
    app.world_mut().spawn(Screenshot::image(handle)).observe(
        move |shot: On<ScreenshotCaptured>| {
            *slot.lock().unwrap() = Some(shot.image.clone());
        },
    );
    for _ in 0..60 {
        app.update();
        if captured.lock().unwrap().is_some() {
            break;
        }
    }
    let costs = app.world().resource::<TerrainFrameCosts>().snapshot();
    if let Some(e) = costs.last_error.or(costs.last_draw_error) {
        return Err(format!("the plugin reported: {e}").into());
    }
    eprintln!("terrain frames drawn: {}", costs.frames);
    let image = captured
        .lock()
        .unwrap()
        .take()
        .ok_or("no screenshot came back")?;
    let rgba = image
        .try_into_dynamic()
        .map_err(|e| e.to_string())?
        .to_rgba8();
    Ok(Rendered {
        image: rgba,
        terrain,
        palette,
    })
}

fn save(name: &str, image: &RgbaImage) {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    if let Err(e) = image.save(&path) {
        eprintln!("could not keep {}: {e}", path.display());
    }
}

/// The tolerance of the project's GPU tests for refine against the twin and the exact render.
fn tolerance() -> DiffOptions {
    DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.002,
        max_mean: 0.5,
        ..DiffOptions::default()
    }
}

fn bevy_draws_the_twin() -> Result<(), Failed> {
    let Rendered {
        image,
        terrain,
        palette,
    } = render_through_bevy(None)?;
    let level = Level::default_level();
    let camera = view_camera(&level);
    let options = TerrainView::default().options;
    let twin = render_twin(&terrain, &palette, &camera, &options, 0)?;
    let exact = render_exact(&terrain, &palette, &camera, &ExactRenderOptions::default())?;
    save("bevy-terrain.png", &image);
    save("bevy-terrain-twin.png", &twin);
    for (what, reference) in [("the CPU twin", &twin), ("the exact render", &exact)] {
        let report = compare(&image, reference, &tolerance())?;
        eprintln!(
            "Bevy's frame vs {what}: {:.4}% of pixels differ by more than {}, mean {:.3}, max {}",
            100.0 * report.differing_fraction,
            tolerance().pixel_tolerance,
            report.mean,
            report.max
        );
        if !report.passed() {
            return Err(format!("Bevy's frame vs {what}: {}", report.failure_summary()).into());
        }
    }
    Ok(())
}

fn sprites_draw_over_the_terrain() -> Result<(), Failed> {
    let level = Level::default_level();
    let camera = view_camera(&level);
    // A magenta square in the middle of the view, over sky and ground alike.
    let half = 20.0 * camera.units_per_pixel;
    let sprite = (
        camera.center,
        Vec2::splat(2.0 * half),
        Color::srgb(1.0, 0.0, 1.0),
    );
    let Rendered {
        image,
        terrain,
        palette,
    } = render_through_bevy(Some(sprite))?;
    save("bevy-terrain-sprite.png", &image);
    let twin = render_twin(
        &terrain,
        &palette,
        &camera,
        &TerrainView::default().options,
        0,
    )?;
    let (cx, cy) = (SIZE.0 / 2, SIZE.1 / 2);
    let (mut inside, mut magenta, mut outside, mut matches) = (0, 0, 0, 0);
    for (x, y, p) in image.enumerate_pixels() {
        let in_sprite = x.abs_diff(cx) < 18 && y.abs_diff(cy) < 18;
        let near_edge = x.abs_diff(cx) < 22 && y.abs_diff(cy) < 22;
        if in_sprite {
            inside += 1;
            magenta += u32::from(p.0[0] > 240 && p.0[1] < 16 && p.0[2] > 240);
        } else if !near_edge {
            outside += 1;
            let t = twin.get_pixel(x, y).0;
            matches += u32::from((0..3).all(|c| p.0[c].abs_diff(t[c]) <= 8));
        }
    }
    eprintln!(
        "sprite: {magenta} of {inside} pixels magenta; elsewhere {matches} of {outside} as the twin"
    );
    if magenta != inside {
        return Err(format!(
            "the sprite is not drawn over the terrain: {magenta} of {inside} pixels"
        )
        .into());
    }
    if f64::from(matches) < 0.998 * f64::from(outside) {
        return Err(
            format!("around the sprite only {matches} of {outside} pixels are the twin's").into(),
        );
    }
    Ok(())
}

fn adapter() -> Result<String, String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
        .map_err(|e| format!("no adapter: {e}"))?;
    let info = adapter.get_info();
    Ok(format!(
        "{} ({:?}, {:?})",
        info.name, info.backend, info.device_type
    ))
}

fn main() {
    let args = Arguments::from_args();
    let available = match adapter() {
        Ok(name) => {
            eprintln!("adapter: {name}");
            true
        }
        Err(e) if std::env::var_os("CI").is_some() => {
            eprintln!("{e}; CI is set, so a missing adapter fails");
            std::process::exit(1);
        }
        Err(e) => {
            eprintln!("{e}: the render tests are reported as ignored");
            false
        }
    };
    type Test = fn() -> Result<(), Failed>;
    let tests: [(&str, Test); 2] = [
        ("bevy_draws_the_twin", bevy_draws_the_twin),
        (
            "sprites_draw_over_the_terrain",
            sprites_draw_over_the_terrain,
        ),
    ];
    let trials = tests
        .into_iter()
        .map(|(name, test)| Trial::test(name, test).with_ignored_flag(!available))
        .collect();
    libtest_mimic::run(&args, trials).exit();
}
