//! Visual diff: how far apart two RGBA images are, pixel by pixel and as a person would see
//! it, with thresholds that say whether they count as the same picture.
//!
//! [`compare`] measures, for two images of one size (a reference `a` and a test image `b`):
//!
//! * the **per-pixel error** `e = max over R, G, B, A of |a - b|` (0..=255);
//! * **differing pixels**: those with `e > pixel_tolerance`, as a count and a fraction;
//! * the **mean**, the **max** and a high **percentile** (nearest rank, 99th by default) of
//!   `e` over all pixels;
//! * the **FLIP** score: the mean of NVIDIA's FLIP perceptual error map (each pixel in
//!   `[0, 1]`, from colour differences after a contrast-sensitivity blur for the given
//!   pixels per degree, plus edge and point features), computed on the RGB channels.
//!
//! Each metric has a threshold in [`DiffOptions`]; the [`DiffReport`] lists the thresholds
//! that were exceeded and [`DiffReport::passed`] says whether there were none. [`heatmap`]
//! draws a report's per-pixel error as a picture, and [`golden`] keeps reference PNGs for
//! tests.
//!
//! On WebAssembly FLIP is not available (its C++ does not build for the browser): there
//! [`compare`] measures the pixel statistics alone ([`DiffReport::flip_measured`] is
//! false), and the heat-maps and golden files, which are files on disk, are not built.

#![forbid(unsafe_code)]

#[cfg(not(target_family = "wasm"))]
pub mod golden;
#[cfg(not(target_family = "wasm"))]
mod heatmap;
mod metrics;
mod perceptual;
mod report;

use std::path::{Path, PathBuf};

use image::RgbaImage;
use serde::{Deserialize, Serialize};
use thiserror::Error;

#[cfg(not(target_family = "wasm"))]
pub use golden::{GoldenError, GoldenMode, UPDATE_GOLDEN_ENV, check_golden, check_golden_with};
#[cfg(not(target_family = "wasm"))]
pub use heatmap::{HeatSource, heatmap};
pub use report::{DiffReport, Failure, Metric};

/// Largest image compared, in pixels (4096 x 4096): the perceptual metric keeps several
/// floating-point copies of both images, so this bounds the memory a comparison takes.
pub const MAX_PIXELS: u64 = 4096 * 4096;

/// FLIP's default viewing condition: a 0.7 m distance from a 0.69 m wide 3840-pixel monitor.
pub const DEFAULT_PIXELS_PER_DEGREE: f32 = 67.0;

/// Thresholds of a comparison. A metric passes when its value is at most its limit; an
/// infinite limit turns the check off.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DiffOptions {
    /// A pixel differs when some channel differs by more than this.
    pub pixel_tolerance: u8,
    /// Largest accepted fraction (0..=1) of differing pixels.
    pub max_differing_fraction: f64,
    /// Largest accepted mean of the per-pixel error (0..=255).
    pub max_mean: f64,
    /// Largest accepted per-pixel error anywhere (0..=255).
    pub max_error: f64,
    /// Which percentile of the per-pixel error is reported and checked (0 < p <= 100).
    pub percentile: f64,
    /// Largest accepted value of that percentile (0..=255).
    pub max_percentile: f64,
    /// Largest accepted FLIP score (mean perceptual error, 0..=1).
    pub max_flip: f64,
    /// Pixels per degree of visual angle the FLIP score assumes (how closely the image is
    /// looked at: more pixels per degree hide finer differences).
    pub pixels_per_degree: f32,
}

impl Default for DiffOptions {
    /// Limits meant for renders of one scene by two implementations: a few anti-aliased edge
    /// pixels may differ, no region may change visibly.
    fn default() -> Self {
        DiffOptions {
            pixel_tolerance: 2,
            max_differing_fraction: 0.001,
            max_mean: 0.5,
            max_error: f64::INFINITY,
            percentile: 99.0,
            max_percentile: 16.0,
            max_flip: 0.01,
            pixels_per_degree: DEFAULT_PIXELS_PER_DEGREE,
        }
    }
}

/// Why two images could not be compared, read or written.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum DiffError {
    /// The images are not the same size.
    #[error(
        "image sizes differ: reference is {a_width}x{a_height}, test image is {b_width}x{b_height}"
    )]
    SizeMismatch {
        /// Reference width.
        a_width: u32,
        /// Reference height.
        a_height: u32,
        /// Test image width.
        b_width: u32,
        /// Test image height.
        b_height: u32,
    },
    /// The images have no pixels, or more than [`MAX_PIXELS`].
    #[error("image size {width}x{height} must have between 1 and {MAX_PIXELS} pixels")]
    BadSize {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// A threshold or parameter is NaN or out of its range.
    #[error("diff option {name} = {value} is invalid: {reason}")]
    BadOption {
        /// The option.
        name: &'static str,
        /// Its value, formatted.
        value: String,
        /// What it must be.
        reason: &'static str,
    },
    /// An image file could not be read or decoded.
    #[error("cannot read image {path}: {reason}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// An image file could not be encoded or written.
    #[error("cannot write image {path}: {reason}")]
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
}

/// Compares the test image `b` with the reference `a` and checks every metric against its
/// threshold in `options`.
pub fn compare(
    a: &RgbaImage,
    b: &RgbaImage,
    options: &DiffOptions,
) -> Result<DiffReport, DiffError> {
    check_options(options)?;
    check_sizes(a, b)?;
    let errors = metrics::pixel_errors(a, b);
    let stats = metrics::PixelStats::of(&errors, options.pixel_tolerance, options.percentile);
    // Pictures whose colours are identical have a zero perceptual error everywhere; skip the
    // (costly) filter passes then.
    let flip = if metrics::rgb_equal(a, b) {
        Some(vec![0.0; errors.len()])
    } else {
        perceptual::flip_map(a, b, options.pixels_per_degree)
    };
    Ok(DiffReport::new(
        a.dimensions(),
        errors,
        stats,
        flip,
        options,
    ))
}

/// Largest image file [`load_png`] reads, bytes (an uncompressed RGBA image of
/// [`MAX_PIXELS`] pixels, and then some).
pub const MAX_IMAGE_FILE_BYTES: u64 = 4 * MAX_PIXELS + (1 << 20);

/// Reads a PNG (or any format the `image` crate decodes here) as RGBA from a regular file
/// of at most [`MAX_IMAGE_FILE_BYTES`], refusing images over [`MAX_PIXELS`] before decoding
/// them.
pub fn load_png(path: &Path) -> Result<RgbaImage, DiffError> {
    let read_error = |reason: String| DiffError::Read {
        path: path.to_path_buf(),
        reason,
    };
    let bytes = craterfield_core::files::read(path, MAX_IMAGE_FILE_BYTES)
        .map_err(|e| read_error(e.to_string()))?;
    let reader = || {
        image::ImageReader::new(std::io::Cursor::new(&bytes))
            .with_guessed_format()
            .map_err(|e| read_error(e.to_string()))
    };
    let (width, height) = reader()?
        .into_dimensions()
        .map_err(|e| read_error(e.to_string()))?;
    check_size(width, height).map_err(|e| read_error(e.to_string()))?;
    let decoded = reader()?.decode().map_err(|e| read_error(e.to_string()))?;
    Ok(decoded.to_rgba8())
}

/// Writes `image` as a PNG, creating the parent folder when missing.
pub fn save_png(image: &RgbaImage, path: &Path) -> Result<(), DiffError> {
    let write_error = |reason: String| DiffError::Write {
        path: path.to_path_buf(),
        reason,
    };
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(|e| write_error(e.to_string()))?;
    }
    image
        .save_with_format(path, image::ImageFormat::Png)
        .map_err(|e| write_error(e.to_string()))
}

fn check_sizes(a: &RgbaImage, b: &RgbaImage) -> Result<(), DiffError> {
    if a.dimensions() != b.dimensions() {
        return Err(DiffError::SizeMismatch {
            a_width: a.width(),
            a_height: a.height(),
            b_width: b.width(),
            b_height: b.height(),
        });
    }
    check_size(a.width(), a.height())
}

fn check_size(width: u32, height: u32) -> Result<(), DiffError> {
    let pixels = u64::from(width) * u64::from(height);
    if pixels == 0 || pixels > MAX_PIXELS {
        return Err(DiffError::BadSize { width, height });
    }
    Ok(())
}

fn check_options(o: &DiffOptions) -> Result<(), DiffError> {
    let limits = [
        ("max_differing_fraction", o.max_differing_fraction),
        ("max_mean", o.max_mean),
        ("max_error", o.max_error),
        ("max_percentile", o.max_percentile),
        ("max_flip", o.max_flip),
    ];
    for (name, value) in limits {
        let valid = value >= 0.0; // false for NaN
        if !valid {
            return Err(DiffError::BadOption {
                name,
                value: value.to_string(),
                reason: "must be a number >= 0 (infinity turns the check off)",
            });
        }
    }
    let percentile_valid = o.percentile > 0.0 && o.percentile <= 100.0;
    if !percentile_valid {
        return Err(DiffError::BadOption {
            name: "percentile",
            value: o.percentile.to_string(),
            reason: "must be in (0, 100]",
        });
    }
    // Below one pixel per degree FLIP's filters are wider than any image and its score is
    // not a number.
    let ppd = o.pixels_per_degree;
    if !(ppd.is_finite() && (1.0..=1.0e4).contains(&ppd)) {
        return Err(DiffError::BadOption {
            name: "pixels_per_degree",
            value: ppd.to_string(),
            reason: "must be finite, from 1 to 10000",
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_options_and_sizes() {
        let img = RgbaImage::new(4, 4);
        for bad in [
            DiffOptions {
                max_mean: f64::NAN,
                ..DiffOptions::default()
            },
            DiffOptions {
                max_flip: -1.0,
                ..DiffOptions::default()
            },
            DiffOptions {
                percentile: 0.0,
                ..DiffOptions::default()
            },
            DiffOptions {
                pixels_per_degree: f32::INFINITY,
                ..DiffOptions::default()
            },
            DiffOptions {
                pixels_per_degree: 1e-20,
                ..DiffOptions::default()
            },
            DiffOptions {
                pixels_per_degree: 0.5,
                ..DiffOptions::default()
            },
        ] {
            assert!(
                matches!(compare(&img, &img, &bad), Err(DiffError::BadOption { .. })),
                "{bad:?}"
            );
        }
        let other = RgbaImage::new(4, 5);
        let err = compare(&img, &other, &DiffOptions::default()).unwrap_err();
        assert!(err.to_string().contains("4x4") && err.to_string().contains("4x5"));
        let empty = RgbaImage::new(0, 3);
        assert!(matches!(
            compare(&empty, &empty, &DiffOptions::default()),
            Err(DiffError::BadSize { .. })
        ));
    }

    #[test]
    fn a_score_that_is_not_a_number_fails() {
        let errors = vec![0u8; 16];
        let stats = metrics::PixelStats::of(&errors, 2, 99.0);
        let mut flip = vec![0.0f32; 16];
        flip[3] = f32::NAN;
        let report = DiffReport::new((4, 4), errors, stats, Some(flip), &DiffOptions::default());
        assert!(report.flip.is_nan());
        assert!(!report.passed(), "a NaN FLIP score passed");
        assert!(
            report.failure_summary().contains("NaN"),
            "{}",
            report.failure_summary()
        );
    }
}
