//! Golden-image checks for tests: compare a rendered image with a committed reference PNG,
//! create or refresh the reference on request, and leave the evidence next to it on failure.
//!
//! For `check_golden("hills", &image, dir, &options)` the reference is `dir/hills.png`. With
//! `CRATERFIELD_UPDATE_GOLDEN=1` in the environment the image is written there and the check
//! passes. Otherwise a missing reference fails with instructions, and a mismatch writes
//! `dir/hills.actual.png` (what was rendered) and `dir/hills.heat.png` (where it differs)
//! and fails naming the exceeded metrics and both files. A passing check removes stale
//! `.actual.png` / `.heat.png` files of the same name.

use std::path::{Path, PathBuf};

use image::RgbaImage;
use thiserror::Error;

use super::{DiffError, DiffOptions, DiffReport, HeatSource, compare, heatmap, load_png, save_png};

/// The environment variable that makes [`check_golden`] (re)write references: set it to `1`.
pub const UPDATE_GOLDEN_ENV: &str = "CRATERFIELD_UPDATE_GOLDEN";

/// Whether a golden check compares with the reference or replaces it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GoldenMode {
    /// Compare with the reference; fail when it is missing or differs.
    Check,
    /// Write the image as the new reference and pass.
    Update,
}

impl GoldenMode {
    /// [`GoldenMode::Update`] when [`UPDATE_GOLDEN_ENV`] is `1`, else [`GoldenMode::Check`].
    pub fn from_env() -> GoldenMode {
        match std::env::var(UPDATE_GOLDEN_ENV) {
            Ok(v) if v == "1" => GoldenMode::Update,
            _ => GoldenMode::Check,
        }
    }
}

/// Why a golden check failed.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum GoldenError {
    /// The name is empty or not a plain file name.
    #[error(
        "golden image name {name:?} must be non-empty and use only letters, digits, '-', '_' and '.'"
    )]
    BadName {
        /// The name.
        name: String,
    },
    /// There is no reference image yet.
    #[error(
        "golden image {reference} does not exist: run the test with {UPDATE_GOLDEN_ENV}=1 to create it from the current output, then look at it and commit it"
    )]
    Missing {
        /// Where the reference should be.
        reference: PathBuf,
    },
    /// The image differs from the reference beyond the thresholds.
    #[error(
        "golden image {reference} does not match: {failures}; wrote {actual} and {heat} (rerun with {UPDATE_GOLDEN_ENV}=1 to accept the new output)"
    )]
    Mismatch {
        /// The reference.
        reference: PathBuf,
        /// The exceeded metrics, formatted.
        failures: String,
        /// Where the rendered image was written.
        actual: PathBuf,
        /// Where the heat-map was written.
        heat: PathBuf,
        /// The full comparison.
        report: Box<DiffReport>,
    },
    /// The image and the reference are not the same size.
    #[error(
        "golden image {reference} is {expected_width}x{expected_height} but the output is {width}x{height}; wrote {actual} (rerun with {UPDATE_GOLDEN_ENV}=1 to accept it)"
    )]
    SizeMismatch {
        /// The reference.
        reference: PathBuf,
        /// Reference width.
        expected_width: u32,
        /// Reference height.
        expected_height: u32,
        /// Output width.
        width: u32,
        /// Output height.
        height: u32,
        /// Where the rendered image was written.
        actual: PathBuf,
    },
    /// Reading, comparing or writing failed.
    #[error(transparent)]
    Diff(#[from] DiffError),
}

/// Compares `actual` with the golden image `dir/<name>.png`, in the mode that
/// [`UPDATE_GOLDEN_ENV`] selects (see the module documentation).
pub fn check_golden(
    name: &str,
    actual: &RgbaImage,
    dir: &Path,
    options: &DiffOptions,
) -> Result<DiffReport, GoldenError> {
    check_golden_with(name, actual, dir, options, GoldenMode::from_env())
}

/// [`check_golden`] with the mode given instead of read from the environment.
pub fn check_golden_with(
    name: &str,
    actual: &RgbaImage,
    dir: &Path,
    options: &DiffOptions,
    mode: GoldenMode,
) -> Result<DiffReport, GoldenError> {
    let files = GoldenFiles::new(name, dir)?;
    if mode == GoldenMode::Update {
        save_png(actual, &files.reference)?;
        files.remove_evidence();
        return Ok(DiffReport::identical(
            actual.width(),
            actual.height(),
            options,
        ));
    }
    if !files.reference.is_file() {
        return Err(GoldenError::Missing {
            reference: files.reference,
        });
    }
    let expected = load_png(&files.reference)?;
    if expected.dimensions() != actual.dimensions() {
        save_png(actual, &files.actual)?;
        return Err(GoldenError::SizeMismatch {
            reference: files.reference,
            expected_width: expected.width(),
            expected_height: expected.height(),
            width: actual.width(),
            height: actual.height(),
            actual: files.actual,
        });
    }
    let report = compare(&expected, actual, options)?;
    if report.passed() {
        files.remove_evidence();
        return Ok(report);
    }
    save_png(actual, &files.actual)?;
    save_png(&heatmap(&report, HeatSource::Pixel), &files.heat)?;
    Err(GoldenError::Mismatch {
        reference: files.reference,
        failures: report.failure_summary(),
        actual: files.actual,
        heat: files.heat,
        report: Box::new(report),
    })
}

/// The reference and the evidence files of one golden image.
struct GoldenFiles {
    reference: PathBuf,
    actual: PathBuf,
    heat: PathBuf,
}

impl GoldenFiles {
    fn new(name: &str, dir: &Path) -> Result<GoldenFiles, GoldenError> {
        let plain = !name.is_empty()
            && !name.starts_with('.')
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'));
        if !plain {
            return Err(GoldenError::BadName { name: name.into() });
        }
        Ok(GoldenFiles {
            reference: dir.join(format!("{name}.png")),
            actual: dir.join(format!("{name}.actual.png")),
            heat: dir.join(format!("{name}.heat.png")),
        })
    }

    /// Removes the evidence of an earlier failure (missing files are fine).
    fn remove_evidence(&self) {
        for path in [&self.actual, &self.heat] {
            // Best effort: a file that cannot be removed only leaves stale evidence behind.
            let _ = std::fs::remove_file(path);
        }
    }
}
