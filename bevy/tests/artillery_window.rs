//! The artillery example in a real window: started under Xvfb with `--frames 300
//! --screenshot` (every player the AI, one tick per frame), it must exit 0 and leave a
//! screenshot that shows the terrain (sky and ground), the players' vehicles in their
//! colours, and a crater: ground of the untouched level that is sky in the screenshot,
//! where the run reports an explosion. Needs an adapter and `xvfb-run` (`scripts/test`
//! installs Xvfb): without them the test reports itself ignored, and fails when `CI` is set.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use bevy::math::Vec2;
use craterfield_bevy::craterfield::field2d::{Level, Sdf};
use craterfield_bevy::craterfield::render2d::Camera;
use libtest_mimic::{Arguments, Failed, Trial};

/// The example's window (Xvfb runs at one pixel per point).
const SIZE: (u32, u32) = (1280, 720);
const FRAMES: u32 = 300;

fn xvfb_run() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join("xvfb-run"))
        .find(|p| p.is_file())
}

/// The example binary, built beside this test by `cargo test`.
fn example() -> Result<PathBuf, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let deps = exe.parent().ok_or("no folder")?;
    let path = deps.parent().ok_or("no folder")?.join("examples/artillery");
    if path.is_file() {
        Ok(path)
    } else {
        Err(format!(
            "{} is not built (cargo test builds the examples)",
            path.display()
        ))
    }
}

fn the_game_plays_in_a_window() -> Result<(), Failed> {
    let xvfb = xvfb_run().ok_or("xvfb-run is not installed")?;
    let dir = std::env::temp_dir().join(format!("artillery-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let shot = dir.join("artillery.png");
    let started = Instant::now();
    let output = Command::new("timeout")
        .arg("600")
        .arg(&xvfb)
        .args(["-a", "-s", "-screen 0 1600x900x24"])
        .arg(example()?)
        .args(["--frames", &FRAMES.to_string(), "--screenshot"])
        .arg(&shot)
        .args(["--assets", concat!(env!("CARGO_MANIFEST_DIR"), "/assets")])
        .output()
        .map_err(|e| format!("starting {}: {e}", xvfb.display()))?;
    let took = started.elapsed();
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(format!(
            "artillery exited with {} after {took:?}:\n{stdout}\n{stderr}",
            output.status
        )
        .into());
    }
    eprintln!(
        "artillery ran {FRAMES} frames in {:.1} s\n{stdout}",
        took.as_secs_f64()
    );
    let image = image::open(&shot)
        .map_err(|e| format!("{}: {e}", shot.display()))?
        .to_rgba8();
    let kept = Path::new(env!("CARGO_TARGET_TMPDIR")).join("artillery.png");
    image.save(&kept).ok();
    check_screenshot(&image, &stdout)?;
    std::fs::remove_dir_all(&dir).ok();
    Ok(())
}

/// The example's camera at the screenshot, as its summary reports it.
fn camera(stdout: &str) -> Result<Camera, String> {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("camera center ("))
        .ok_or("the run did not report its camera")?;
    let n = numbers(line);
    if n.len() < 3 {
        return Err(format!("cannot read the camera from {line:?}"));
    }
    Ok(Camera {
        center: Vec2::new(n[0], n[1]),
        units_per_pixel: n[2],
        width: SIZE.0,
        height: SIZE.1,
    })
}

/// The decimal numbers in a line, in order.
fn numbers(line: &str) -> Vec<f32> {
    line.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter_map(|s| s.parse().ok())
        .collect()
}

fn is_sky(p: [u8; 4]) -> bool {
    i32::from(p[2]) > i32::from(p[0]) + 30
}

fn check_screenshot(image: &image::RgbaImage, stdout: &str) -> Result<(), Failed> {
    if image.dimensions() != SIZE {
        return Err(format!("the screenshot is {:?}, not {SIZE:?}", image.dimensions()).into());
    }
    let level = Level::default_level();
    let terrain = level.terrain().map_err(|e| e.to_string())?;
    let camera = camera(stdout)?;
    // Terrain: the untouched level's sky and ground are both on screen, mostly as drawn.
    let (mut sky, mut ground, mut agree, mut all) = (0u32, 0u32, 0u32, 0u32);
    for y in (0..SIZE.1).step_by(4) {
        for x in (0..SIZE.0).step_by(4) {
            let p = image.get_pixel(x, y).0;
            let solid = terrain.distance(camera.pixel_to_world(x, y)) < 0.0;
            all += 1;
            sky += u32::from(is_sky(p));
            ground += u32::from(!is_sky(p));
            agree += u32::from(solid != is_sky(p));
        }
    }
    let share = |n: u32| f64::from(n) / f64::from(all);
    eprintln!(
        "screenshot: {:.0}% sky, {:.0}% ground, {:.1}% as the untouched level",
        100.0 * share(sky),
        100.0 * share(ground),
        100.0 * share(agree)
    );
    if share(sky) < 0.1 || share(ground) < 0.1 || share(agree) < 0.9 {
        return Err("the screenshot does not show the level's terrain".into());
    }
    // Players: each colour of the example's first two players on some pixels.
    let red = image
        .pixels()
        .filter(|p| p.0[0] > 200 && p.0[1] < 90 && p.0[2] < 80)
        .count();
    let blue = image
        .pixels()
        .filter(|p| p.0[0] < 80 && p.0[1] > 110 && p.0[1] < 170 && p.0[2] > 220)
        .count();
    eprintln!("player pixels: {red} red, {blue} blue");
    if red < 40 || blue < 40 {
        return Err(
            format!("the players are not on screen: {red} red and {blue} blue pixels").into(),
        );
    }
    // A crater: around a reported carve inside the untouched ground, sky now.
    let carves: Vec<(Vec2, f32)> = stdout
        .lines()
        .filter(|l| l.starts_with("event Carve at ("))
        .filter_map(|l| {
            let n = numbers(l);
            (n.len() >= 3).then(|| (Vec2::new(n[0], n[1]), n[2]))
        })
        .collect();
    let mut best = 0.0f64;
    for (center, radius) in &carves {
        let (mut was_ground, mut now_sky) = (0u32, 0u32);
        let r = radius * 0.8;
        let steps = 12;
        for i in -steps..=steps {
            for j in -steps..=steps {
                let offset = Vec2::new(i as f32, j as f32) / steps as f32 * r;
                if offset.length() > r {
                    continue;
                }
                let w = *center + offset;
                if terrain.distance(w) >= -1.0 {
                    continue;
                }
                let px = camera.world_to_pixel(w);
                if px.x < 0.0 || px.y < 0.0 || px.x >= SIZE.0 as f32 || px.y >= SIZE.1 as f32 {
                    continue;
                }
                was_ground += 1;
                now_sky += u32::from(is_sky(image.get_pixel(px.x as u32, px.y as u32).0));
            }
        }
        if was_ground >= 20 {
            best = best.max(f64::from(now_sky) / f64::from(was_ground));
        }
    }
    eprintln!(
        "{} carves reported; the best crater shows {:.0}% sky where the level was ground",
        carves.len(),
        best * 100.0
    );
    if best < 0.6 {
        return Err(format!(
            "no crater in the screenshot ({} carves reported)",
            carves.len()
        )
        .into());
    }
    Ok(())
}

fn adapter() -> Result<(), String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    pollster::block_on(instance.request_adapter(&Default::default()))
        .map(|_| ())
        .map_err(|e| format!("no adapter: {e}"))
}

/// Why the test cannot run here, if it cannot.
fn missing() -> Option<String> {
    if let Err(e) = adapter() {
        return Some(e);
    }
    if xvfb_run().is_none() {
        return Some("xvfb-run is not installed".to_string());
    }
    example().err()
}

fn main() {
    let args = Arguments::from_args();
    let ci = std::env::var_os("CI").is_some();
    let missing = missing();
    if let Some(why) = &missing {
        eprintln!("{why}");
    }
    let ignored = !ci && missing.is_some();
    let trial = Trial::test("the_game_plays_in_a_window", move || match &missing {
        None => the_game_plays_in_a_window(),
        Some(why) if ci => Err(format!("{why}, and CI is set: this test must run in CI").into()),
        Some(why) => Err(why.clone().into()),
    })
    .with_ignored_flag(ignored);
    libtest_mimic::run(&args, vec![trial]).exit()
}
