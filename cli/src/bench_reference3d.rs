//! The reference CPU sphere tracer (ETH Zurich ASL 2020) beside ours in `bench march3d`:
//! its binaries timed in the same run on the paper scenes, and the FLIP of each picture
//! against the reference's vendored pictures.
//!
//! A reference binary is the `raymarcher` its makefile builds (`scripts/reference-march3d`
//! builds one from a checkout). It reads `../scenes/NAME.json` and writes
//! `../output/render_out/NAME.png` relative to its folder, so it runs there. Its time is the
//! whole process (scene load, render, PNG write), which counts a little against it: the PNG
//! write is about 4% of its scene0 profile.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

use craterfield::visdiff::{DiffOptions, compare, load_png};
use image::RgbaImage;
use serde::Serialize;

use crate::tails::Tails;

/// One reference binary's time on one scene at one thread count.
#[derive(Serialize, Clone)]
pub(crate) struct RefRow {
    pub scene: String,
    pub binary: String,
    pub threads: usize,
    /// Seconds per run, over `frames` runs.
    pub seconds: Tails,
    pub frames: u32,
    /// FLIP of its picture against the vendored reference picture (another build of the
    /// same program may round differently).
    pub flip_vs_vendored: Option<f64>,
}

/// A picture of ours against a reference picture.
#[derive(Serialize, Clone)]
pub(crate) struct Fidelity {
    pub scene: String,
    pub against: String,
    pub flip: f64,
    /// Pixels more than 2 levels apart, as a fraction.
    pub differing_fraction: f64,
}

/// A short name for a binary: the folder of its checkout (the binary sits in `build/`).
pub(crate) fn label(bin: &Path) -> String {
    bin.parent()
        .and_then(Path::parent)
        .and_then(Path::file_name)
        .map_or_else(|| bin.display().to_string(), |n| n.to_string_lossy().into())
}

/// Runs `bin` on `scene` once with `threads` OpenMP threads: the seconds it took.
pub(crate) fn time_reference_once(bin: &Path, scene: &str, threads: usize) -> Result<f64, String> {
    let dir = bin
        .parent()
        .ok_or_else(|| format!("{}: no folder", bin.display()))?;
    std::fs::create_dir_all(dir.join("../output/render_out"))
        .map_err(|e| format!("{}: {e}", dir.display()))?;
    let t = Instant::now();
    let status = Command::new(bin)
        .arg(scene)
        .current_dir(dir)
        .env("OMP_NUM_THREADS", threads.to_string())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .map_err(|e| format!("{}: {e}", bin.display()))?;
    let seconds = t.elapsed().as_secs_f64();
    if !status.success() {
        return Err(format!("{} {scene}: {status}", bin.display()));
    }
    Ok(seconds)
}

/// The picture `bin` wrote for `scene` on its last run.
pub(crate) fn reference_output(bin: &Path, scene: &str) -> PathBuf {
    bin.parent()
        .unwrap_or(Path::new("."))
        .join("../output/render_out")
        .join(format!("{scene}.png"))
}

/// FLIP (and pixels more than 2 levels apart) of `ours` against the picture at `path`,
/// reported as `what`.
pub(crate) fn fidelity(
    scene: &str,
    ours: &RgbaImage,
    (what, path): (&str, &Path),
) -> Result<Fidelity, String> {
    let theirs = load_png(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let options = DiffOptions {
        max_differing_fraction: 1.0,
        max_mean: 255.0,
        max_percentile: 255.0,
        max_flip: 1.0,
        ..DiffOptions::default()
    };
    let r = compare(&theirs, ours, &options).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(Fidelity {
        scene: scene.to_string(),
        against: what.to_string(),
        flip: r.flip,
        differing_fraction: r.differing_fraction,
    })
}

/// FLIP of the picture `bin` last wrote for `scene` against the vendored one in
/// `pictures` (every run writes the same picture, so it is compared once), if both exist.
pub(crate) fn flip_vs_vendored(
    bin: &Path,
    pictures: &Path,
    scene: &str,
) -> Result<Option<f64>, String> {
    let vendored = pictures.join(format!("{scene}.png"));
    match load_png(&reference_output(bin, scene)) {
        Ok(img) if vendored.exists() => {
            Ok(Some(fidelity(scene, &img, ("vendored", &vendored))?.flip))
        }
        _ => Ok(None),
    }
}

/// The fastest reference row for `scene` at `threads`.
pub(crate) fn best<'a>(rows: &'a [RefRow], scene: &str, threads: usize) -> Option<&'a RefRow> {
    rows.iter()
        .filter(|r| r.scene == scene && r.threads == threads)
        .min_by(|a, b| a.seconds.median.total_cmp(&b.seconds.median))
}
