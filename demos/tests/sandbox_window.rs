//! The real `sandbox` binary in a real window: started under Xvfb with `--frames 120
//! --screenshot`, it must exit 0 and leave a screenshot whose terrain view shows sky and
//! ground. Needs an adapter and `xvfb-run` (`scripts/test` installs Xvfb when missing):
//! without either the test reports itself ignored, and fails when `CI` is set.

use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

use libtest_mimic::{Arguments, Failed, Trial};

/// The window's inner size (points; Xvfb runs at one pixel per point).
const SIZE: (u32, u32) = (960, 540);

fn xvfb_run() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join("xvfb-run"))
        .find(|p| p.is_file())
}

fn the_binary_draws_the_terrain_in_a_window() -> Result<(), Failed> {
    let xvfb = xvfb_run().ok_or("xvfb-run is not installed")?;
    let dir = std::env::temp_dir().join(format!("sandbox-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let shot = dir.join("sandbox.png");
    let started = Instant::now();
    let output = Command::new("timeout")
        .arg("300")
        .arg(&xvfb)
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(env!("CARGO_BIN_EXE_sandbox"))
        .args(["--frames", "120", "--screenshot"])
        .arg(&shot)
        .args(["--size", &format!("{}x{}", SIZE.0, SIZE.1)])
        .output()
        .map_err(|e| format!("starting {}: {e}", xvfb.display()))?;
    let took = started.elapsed();
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(format!(
            "sandbox exited with {} after {took:?}:\n{stderr}",
            output.status
        )
        .into());
    }
    eprintln!("sandbox ran 120 frames in {:.1} s", took.as_secs_f64());
    check_screenshot(&craterfield::visdiff::load_png(&shot).map_err(|e| e.to_string())?)?;
    std::fs::remove_dir_all(&dir).ok();
    Ok(())
}

/// The terrain view (left of the side panel) shows both the level's sky (blue over red)
/// and its ground (red over blue), each over a tenth of it.
fn check_screenshot(image: &image::RgbaImage) -> Result<(), Failed> {
    if image.dimensions() != SIZE {
        return Err(format!("the screenshot is {:?}, not {SIZE:?}", image.dimensions()).into());
    }
    let view_width = SIZE.0 - 320;
    let (mut sky, mut ground, mut all) = (0u32, 0u32, 0u32);
    for y in 0..SIZE.1 {
        for x in 0..view_width {
            let [r, g, b, _] = image.get_pixel(x, y).0;
            all += 1;
            if i32::from(b) > i32::from(r) + 40 && b > 60 {
                sky += 1;
            } else if i32::from(r) > i32::from(b) + 4 && g < 200 {
                ground += 1;
            }
        }
    }
    let (sky, ground) = (
        f64::from(sky) / f64::from(all),
        f64::from(ground) / f64::from(all),
    );
    eprintln!(
        "terrain view: {:.0}% sky, {:.0}% ground",
        sky * 100.0,
        ground * 100.0
    );
    if sky < 0.1 || ground < 0.1 {
        return Err(format!(
            "the screenshot does not show the terrain: {:.1}% sky, {:.1}% ground",
            sky * 100.0,
            ground * 100.0
        )
        .into());
    }
    Ok(())
}

fn main() {
    let args = Arguments::from_args();
    let ci = std::env::var_os("CI").is_some();
    let adapter = craterfield_demos::common::require_adapter();
    let missing = match (&adapter, xvfb_run()) {
        (Err(e), _) => Some(e.to_string()),
        (Ok(_), None) => Some("xvfb-run is not installed".to_string()),
        (Ok(_), Some(_)) => None,
    };
    if let Some(why) = &missing {
        eprintln!("{why}");
    }
    let trial = Trial::test(
        "the_binary_draws_the_terrain_in_a_window",
        move || match &missing {
            None => the_binary_draws_the_terrain_in_a_window(),
            Some(why) if ci => {
                Err(format!("{why}, and CI is set: this test must run in CI").into())
            }
            Some(why) => Err(why.clone().into()),
        },
    )
    .with_ignored_flag(missing_and_not_ci(ci));
    libtest_mimic::run(&args, vec![trial]).exit()
}

fn missing_and_not_ci(ci: bool) -> bool {
    !ci && (craterfield_demos::common::require_adapter().is_err() || xvfb_run().is_none())
}
