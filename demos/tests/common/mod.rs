//! The harness of the demos' UI tests (`harness = false`): every test drives an app through
//! egui_kittest on the adapter wgpu finds (Mesa's lavapipe in CI). Without an adapter each
//! test reports itself ignored, never passed; with `CI` set a missing adapter fails every
//! test instead. Snapshot images are compared with the library's `visdiff` against
//! `tests/snapshots/<name>.png`; `CRATERFIELD_UPDATE_GOLDEN=1` rewrites them.

#![allow(dead_code, unreachable_pub)]

use std::path::PathBuf;
use std::sync::OnceLock;

use craterfield::visdiff::{DiffOptions, check_golden};
use libtest_mimic::{Arguments, Failed, Trial};

/// What a UI test returns.
pub type TestResult = Result<(), Failed>;

/// A named UI test.
pub type UiTest = (&'static str, fn() -> TestResult);

/// Whether wgpu finds an adapter (asked once).
fn have_adapter() -> bool {
    static FOUND: OnceLock<bool> = OnceLock::new();
    *FOUND.get_or_init(|| match craterfield_demos::common::require_adapter() {
        Ok(info) => {
            eprintln!("GPU adapter: {} ({:?})", info.name, info.backend);
            true
        }
        Err(e) => {
            eprintln!("{e}");
            false
        }
    })
}

/// Runs `tests` with libtest's command line and exits. The tests run one at a time: each
/// makes its own device, and lavapipe already uses every core.
pub fn run(tests: &[UiTest]) -> ! {
    let mut args = Arguments::from_args();
    args.test_threads = Some(1);
    let ci = std::env::var_os("CI").is_some();
    let missing = !have_adapter();
    let trials = tests
        .iter()
        .map(|&(name, test)| {
            Trial::test(name, move || {
                if have_adapter() {
                    test()
                } else if ci {
                    Err("no GPU adapter, and CI is set: the demos' UI tests must run in CI".into())
                } else {
                    Err("no GPU adapter".into())
                }
            })
            .with_ignored_flag(missing && !ci)
        })
        .collect();
    libtest_mimic::run(&args, trials).exit()
}

/// The folder of the committed snapshots.
pub fn snapshot_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots")
}

/// Compares `image` with the committed snapshot `name` (see the module docs). The UI's
/// text and the terrain are drawn by the same driver every time; the tolerance allows
/// for a few edge pixels of a different rasterizer.
pub fn check_snapshot(name: &str, image: &image::RgbaImage) -> TestResult {
    let options = DiffOptions {
        pixel_tolerance: 8,
        max_differing_fraction: 0.002,
        max_mean: 0.5,
        ..DiffOptions::default()
    };
    check_golden(name, image, &snapshot_dir(), &options)
        .map(|_| ())
        .map_err(|e| e.to_string().into())
}

/// Fails with `message` unless `cond` holds.
pub fn ensure(cond: bool, message: impl Into<String>) -> TestResult {
    if cond {
        Ok(())
    } else {
        Err(message.into().into())
    }
}
