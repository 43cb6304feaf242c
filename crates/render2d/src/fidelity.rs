//! Fidelity of a reconstructed distance image: how faithfully the reduced-scale pipeline
//! keeps the terrain's shape, measured against the exact field at every pixel.
//!
//! Both images are per-pixel signed distances in **pixels**, row-major, row 0 at the top:
//! the ground truth from exact evaluation at pixel centres ([`exact_distances`]) and the
//! test image (the twin's `FieldImage::distance_px`). Pixel `(x, y)` is centred on the
//! continuous pixel coordinates `(x + 0.5, y + 0.5)` (those of
//! [`Camera::world_to_pixel`]). A pixel is **inside** when its distance is `< 0`.
//!
//! * **Mismatched pixels**: the percentage of pixels whose inside/outside state differs
//!   between the two images.
//! * **Contour offset**: in each image, every pair of horizontally or vertically adjacent
//!   pixels whose inside states differ holds one zero crossing, placed on the segment
//!   between their centres by linear interpolation (`t = d0 / (d0 - d1)`). Every crossing of
//!   either image is given its distance to the nearest crossing of the other image, capped at
//!   [`OFFSET_CAP_PX`] (also when the other image has none). The **mean offset** is the
//!   mean of these distances over the crossings of both images, the **max offset** their
//!   largest (a capped, symmetric Hausdorff distance); both are 0 when neither image has a
//!   crossing. Nearest crossings are found through a uniform grid of buckets.
//! * **Feature recall**: a scene declares thin features analytically as a [`Feature`]: a
//!   centre-line polyline in pixel coordinates, a width and a kind. The centre line is
//!   sampled every [`SAMPLE_STEP_PX`] (segment ends included); a sample is judged at the
//!   pixel containing it (the nearest pixel centre), and samples outside the image are left
//!   out. A feature is **present** in an image when it has a sample in the image and at
//!   least [`PRESENCE_FRACTION`] of its samples have `d <= 0` (solid) or `d >= 0` (gap).
//!   Recall is the number of features present in both images over the number present in the
//!   ground truth, reported separately for solids and gaps, and for the features at least
//!   [`TARGET_WIDTH_PX`] wide (the target); it is undefined when no feature of the group is
//!   present in the ground truth.

mod contour;
mod features;

use glam::Vec2;
use serde::Serialize;
use thiserror::Error;

use super::camera::Camera;
use super::camera::CameraError;
use craterfield_field::Sdf;
use craterfield_field::Terrain;
use craterfield_field::tape::EvalError;

/// Largest distance a contour offset counts, pixels.
pub const OFFSET_CAP_PX: f32 = 32.0;
/// Spacing of the centre-line samples of a feature, pixels.
pub const SAMPLE_STEP_PX: f32 = 1.0;
/// Fraction of a feature's samples that must be on the right side for it to be present.
pub const PRESENCE_FRACTION: f64 = 0.9;
/// Width from which a feature counts towards the target recall, pixels.
pub const TARGET_WIDTH_PX: f32 = 2.0;
/// Largest image measured, pixels (16384 x 16384 would take gigabytes of crossings).
pub const MAX_PIXELS: u64 = 8192 * 8192;

/// Whether a feature is material or air.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FeatureKind {
    /// A thin solid (a line, a bridge, a small island): present where `d <= 0`.
    Solid,
    /// A thin gap (a crack, a slit): present where `d >= 0`.
    Gap,
}

/// A thin feature a scene declares, in continuous pixel coordinates (y down).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Feature {
    /// Solid or gap.
    pub kind: FeatureKind,
    /// The centre line, one or more points (one point: a dot).
    pub centre_line: Vec<Vec2>,
    /// Full width across the centre line, pixels.
    pub width_px: f32,
}

/// Features present in the ground truth, and how many of them the test image kept.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Recall {
    /// Features present in the ground truth.
    pub in_truth: usize,
    /// Of those, the ones also present in the test image.
    pub kept: usize,
}

impl Recall {
    /// `kept / in_truth`, or `None` when no feature is present in the ground truth.
    pub fn ratio(&self) -> Option<f64> {
        (self.in_truth > 0).then(|| self.kept as f64 / self.in_truth as f64)
    }
}

/// Every fidelity figure of one test image.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Fidelity {
    /// Percentage (0..=100) of pixels whose inside state differs.
    pub mismatched_pct: f64,
    /// Mean contour offset, pixels.
    pub mean_offset_px: f64,
    /// Largest contour offset, pixels (at most [`OFFSET_CAP_PX`]).
    pub max_offset_px: f64,
    /// Zero crossings of the ground truth.
    pub truth_crossings: usize,
    /// Zero crossings of the test image.
    pub test_crossings: usize,
    /// Recall of all solid features.
    pub solid: Recall,
    /// Recall of all gap features.
    pub gap: Recall,
    /// Recall of the solid features at least [`TARGET_WIDTH_PX`] wide.
    pub solid_target: Recall,
    /// Recall of the gap features at least [`TARGET_WIDTH_PX`] wide.
    pub gap_target: Recall,
}

/// Why fidelity could not be measured.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum FidelityError {
    /// The image size is empty or over [`MAX_PIXELS`].
    #[error("image size {width}x{height} must have between 1 and {MAX_PIXELS} pixels")]
    BadSize {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// A distance buffer does not hold one value per pixel.
    #[error("{image} image has {len} distances, {width}x{height} needs {expected}")]
    BufferSize {
        /// `"truth"` or `"test"`.
        image: &'static str,
        /// Values given.
        len: usize,
        /// Width.
        width: u32,
        /// Height.
        height: u32,
        /// Values needed.
        expected: usize,
    },
    /// A distance is NaN.
    #[error("{image} image has a NaN distance at pixel ({x}, {y})")]
    NaN {
        /// `"truth"` or `"test"`.
        image: &'static str,
        /// Column.
        x: u32,
        /// Row.
        y: u32,
    },
    /// A feature has no centre line, a non-finite point or a width that is not positive.
    #[error("feature {index}: {reason}")]
    BadFeature {
        /// Index in the feature list.
        index: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// The camera cannot be rendered.
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
    /// The terrain's batch evaluator failed.
    #[error("terrain evaluation: {0}")]
    Eval(#[from] EvalError),
}

/// Measures `test` against `truth` (both `width x height` distances in pixels) and the
/// recall of `features`.
pub fn measure(
    width: u32,
    height: u32,
    truth: &[f32],
    test: &[f32],
    features: &[Feature],
) -> Result<Fidelity, FidelityError> {
    check_image("truth", width, height, truth)?;
    check_image("test", width, height, test)?;
    features::check(features)?;
    let truth_crossings = contour::zero_crossings(width, height, truth);
    let test_crossings = contour::zero_crossings(width, height, test);
    let offsets = contour::Offsets::between(&truth_crossings, &test_crossings, OFFSET_CAP_PX);
    let recall = features::recall(width, height, truth, test, features);
    Ok(Fidelity {
        mismatched_pct: mismatched_fraction(truth, test) * 100.0,
        mean_offset_px: offsets.mean,
        max_offset_px: offsets.max,
        truth_crossings: truth_crossings.len(),
        test_crossings: test_crossings.len(),
        solid: recall.solid,
        gap: recall.gap,
        solid_target: recall.solid_target,
        gap_target: recall.gap_target,
    })
}

/// Fraction of pixels whose inside state (`d < 0`) differs (same-length slices).
pub fn mismatched_fraction(truth: &[f32], test: &[f32]) -> f64 {
    let differing = truth
        .iter()
        .zip(test)
        .filter(|&(&a, &b)| (a < 0.0) != (b < 0.0))
        .count();
    differing as f64 / truth.len().max(1) as f64
}

/// Whether `feature` is present in the `width x height` distance image (see the module
/// documentation).
pub fn feature_present(width: u32, height: u32, distance_px: &[f32], feature: &Feature) -> bool {
    features::present(width, height, distance_px, feature)
}

/// The ground truth: the terrain's exact distance at every pixel centre of `camera`, in
/// pixels, row-major, evaluated with the batch evaluator on `threads` threads (0: all
/// cores).
pub fn exact_distances<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    camera: &Camera,
    threads: usize,
) -> Result<Vec<f32>, FidelityError> {
    camera.validate()?;
    let (w, h) = (camera.width as usize, camera.height as usize);
    let mut out = vec![0.0f32; w * h];
    let threads = craterfield_core::threads::resolve(threads);
    let rows_per_chunk = h.div_ceil(threads).max(1);
    if threads == 1 {
        exact_rows(terrain, camera, 0, &mut out)?;
        return Ok(out);
    }
    let results: Vec<Result<(), EvalError>> = std::thread::scope(|s| {
        let workers: Vec<_> = out
            .chunks_mut(rows_per_chunk * w)
            .enumerate()
            .map(|(i, chunk)| {
                s.spawn(move || exact_rows(terrain, camera, i * rows_per_chunk, chunk))
            })
            .collect();
        workers
            .into_iter()
            .map(|worker| {
                worker
                    .join()
                    .unwrap_or_else(|e| std::panic::resume_unwind(e))
            })
            .collect()
    });
    results.into_iter().collect::<Result<(), EvalError>>()?;
    Ok(out)
}

/// Exact distances (pixels) of the pixel rows from `first_row` that fill `out`.
fn exact_rows<F: Sdf>(
    terrain: &Terrain<F>,
    camera: &Camera,
    first_row: usize,
    out: &mut [f32],
) -> Result<(), EvalError> {
    let w = camera.width as usize;
    let points: Vec<Vec2> = (0..out.len())
        .map(|i| camera.pixel_to_world((i % w) as u32, (first_row + i / w) as u32))
        .collect();
    terrain.distances(&points, out)?;
    let upp = camera.units_per_pixel;
    for d in out.iter_mut() {
        *d /= upp;
    }
    Ok(())
}

fn check_image(
    image: &'static str,
    width: u32,
    height: u32,
    distances: &[f32],
) -> Result<(), FidelityError> {
    let pixels = u64::from(width) * u64::from(height);
    if pixels == 0 || pixels > MAX_PIXELS {
        return Err(FidelityError::BadSize { width, height });
    }
    let expected = pixels as usize;
    if distances.len() != expected {
        return Err(FidelityError::BufferSize {
            image,
            len: distances.len(),
            width,
            height,
            expected,
        });
    }
    if let Some(i) = distances.iter().position(|d| d.is_nan()) {
        return Err(FidelityError::NaN {
            image,
            x: (i % width as usize) as u32,
            y: (i / width as usize) as u32,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distances (pixels) of a solid vertical band of the given width centred at `cx`.
    fn band(width: u32, height: u32, cx: f32, band_width: f32) -> Vec<f32> {
        (0..width * height)
            .map(|i| ((i % width) as f32 + 0.5 - cx).abs() - band_width / 2.0)
            .collect()
    }

    #[test]
    fn identical_images_have_no_mismatch_and_no_offset() {
        let img = band(64, 32, 30.3, 5.0);
        let f = measure(64, 32, &img, &img, &[]).unwrap();
        assert_eq!(f.mismatched_pct, 0.0);
        assert_eq!((f.mean_offset_px, f.max_offset_px), (0.0, 0.0));
        assert_eq!(f.truth_crossings, 2 * 32, "two edges per row");
        assert_eq!(f.solid.ratio(), None);
    }

    #[test]
    fn a_shifted_edge_is_offset_by_the_shift() {
        let truth = band(64, 32, 30.3, 6.0);
        let test = band(64, 32, 30.55, 6.0);
        let f = measure(64, 32, &truth, &test, &[]).unwrap();
        assert!((f.mean_offset_px - 0.25).abs() < 1e-4, "{f:?}");
        assert!((f.max_offset_px - 0.25).abs() < 1e-4, "{f:?}");
        // Edges 27.3 -> 27.55 and 33.3 -> 33.55: the pixels centred at 27.5 and 33.5 flip.
        assert!((f.mismatched_pct - 200.0 / 64.0).abs() < 1e-9, "{f:?}");
    }

    #[test]
    fn a_lost_band_is_capped_and_counted() {
        // Inside: the pixels centred at 59.5, 60.5 and 61.5 of each row.
        let truth = band(128, 8, 60.2, 3.0);
        let test = vec![5.0f32; 128 * 8];
        let f = measure(128, 8, &truth, &test, &[]).unwrap();
        assert_eq!(f.test_crossings, 0);
        assert_eq!(f.mean_offset_px, f64::from(OFFSET_CAP_PX));
        assert!((f.mismatched_pct - 300.0 / 128.0).abs() < 1e-9);
    }

    #[test]
    fn recall_counts_features_present_in_the_truth() {
        let (w, h) = (64, 40);
        let truth = band(w, h, 20.0, 3.0);
        // The test image keeps the band but closes a gap around x = 45 that the truth has.
        let mut truth_with_gap = truth.clone();
        let mut test = truth.clone();
        for (i, (t, s)) in truth_with_gap.iter_mut().zip(&mut test).enumerate() {
            let x = (i % w as usize) as f32 + 0.5;
            if (40.0..50.0).contains(&x) {
                *t = -(x - 45.0).abs() + 0.5; // a 1 px slit inside solid
                *s = -3.0;
            }
        }
        let line = |x: f32, width_px: f32, kind| Feature {
            kind,
            centre_line: vec![Vec2::new(x, 2.0), Vec2::new(x, 38.0)],
            width_px,
        };
        let features = [
            line(20.0, 3.0, FeatureKind::Solid),
            line(45.0, 1.0, FeatureKind::Gap),
            // Not present in the truth: air at x = 5 is not solid.
            line(5.0, 2.0, FeatureKind::Solid),
        ];
        let f = measure(w, h, &truth_with_gap, &test, &features).unwrap();
        assert_eq!(
            f.solid,
            Recall {
                in_truth: 1,
                kept: 1
            }
        );
        assert_eq!(
            f.solid_target,
            Recall {
                in_truth: 1,
                kept: 1
            }
        );
        assert_eq!(
            f.gap,
            Recall {
                in_truth: 1,
                kept: 0
            }
        );
        assert_eq!(f.gap_target, Recall::default());
        assert_eq!(f.gap.ratio(), Some(0.0));
    }

    #[test]
    fn exact_distances_are_the_fields_distances_in_pixels() {
        use craterfield_field::Level;
        let terrain = Level::default_level().terrain().unwrap();
        let camera = Camera {
            center: Vec2::new(1216.5, 700.25),
            units_per_pixel: 1.5,
            width: 37,
            height: 23,
        };
        for threads in [1, 3] {
            let d = exact_distances(&terrain, &camera, threads).unwrap();
            assert_eq!(d.len(), 37 * 23);
            for (i, &v) in d.iter().enumerate() {
                let p = camera.pixel_to_world((i % 37) as u32, (i / 37) as u32);
                assert_eq!(v, terrain.distance(p) / 1.5, "pixel {i}");
            }
            assert!(d.iter().any(|&v| v < 0.0) && d.iter().any(|&v| v > 0.0));
        }
        let bad = Camera { width: 0, ..camera };
        assert!(matches!(
            exact_distances(&terrain, &bad, 1),
            Err(FidelityError::Camera(_))
        ));
    }

    #[test]
    fn rejects_bad_input_with_the_place_named() {
        let img = band(8, 8, 4.0, 2.0);
        let mut nan = img.clone();
        nan[8 * 3 + 5] = f32::NAN;
        let err = measure(8, 8, &img, &nan, &[]).unwrap_err();
        assert_eq!(
            err,
            FidelityError::NaN {
                image: "test",
                x: 5,
                y: 3
            }
        );
        assert!(matches!(
            measure(8, 8, &img, &img[1..], &[]),
            Err(FidelityError::BufferSize { image: "test", .. })
        ));
        assert!(matches!(
            measure(0, 8, &[], &[], &[]),
            Err(FidelityError::BadSize { .. })
        ));
        let bad = Feature {
            kind: FeatureKind::Solid,
            centre_line: vec![Vec2::new(1.0, f32::INFINITY)],
            width_px: 1.0,
        };
        assert!(matches!(
            measure(8, 8, &img, &img, &[bad]),
            Err(FidelityError::BadFeature { index: 0, .. })
        ));
    }
}
