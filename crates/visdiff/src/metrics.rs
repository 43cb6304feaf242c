//! Pixel-wise metrics: the per-pixel error (largest channel difference) and its statistics
//! (differing pixels, mean, max, nearest-rank percentile).

use image::RgbaImage;

/// Per-pixel error of two images of one size: the largest absolute difference of their
/// R, G, B and A values, row-major.
pub(crate) fn pixel_errors(a: &RgbaImage, b: &RgbaImage) -> Vec<u8> {
    a.as_raw()
        .chunks_exact(4)
        .zip(b.as_raw().chunks_exact(4))
        .map(|(pa, pb)| {
            pa.iter()
                .zip(pb)
                .map(|(x, y)| x.abs_diff(*y))
                .max()
                .unwrap_or(0)
        })
        .collect()
}

/// Whether the R, G and B values of the two images are identical everywhere.
pub(crate) fn rgb_equal(a: &RgbaImage, b: &RgbaImage) -> bool {
    a.as_raw()
        .chunks_exact(4)
        .zip(b.as_raw().chunks_exact(4))
        .all(|(pa, pb)| pa[..3] == pb[..3])
}

/// Statistics of a per-pixel error map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PixelStats {
    /// Pixels whose error exceeds the tolerance.
    pub differing: u64,
    /// Mean error.
    pub mean: f64,
    /// Largest error.
    pub max: u8,
    /// The requested percentile of the error.
    pub percentile_value: u8,
}

impl PixelStats {
    /// Statistics of `errors` (not empty) with pixels over `tolerance` counted as differing
    /// and the `percentile` (0 < p <= 100) taken by nearest rank.
    pub(crate) fn of(errors: &[u8], tolerance: u8, percentile: f64) -> PixelStats {
        let mut histogram = [0u64; 256];
        for &e in errors {
            histogram[e as usize] += 1;
        }
        let total: u64 = errors.len() as u64;
        let sum: u64 = histogram
            .iter()
            .enumerate()
            .map(|(v, &n)| v as u64 * n)
            .sum();
        let differing = histogram[tolerance as usize + 1..].iter().sum();
        let max = histogram.iter().rposition(|&n| n > 0).unwrap_or(0) as u8;
        PixelStats {
            differing,
            mean: sum as f64 / total.max(1) as f64,
            max,
            percentile_value: nearest_rank(&histogram, total, percentile),
        }
    }
}

/// The smallest value `v` such that at least `percentile`% of the values are `<= v`.
fn nearest_rank(histogram: &[u64; 256], total: u64, percentile: f64) -> u8 {
    let rank = ((percentile / 100.0 * total as f64).ceil() as u64).clamp(1, total.max(1));
    let mut seen = 0;
    for (value, &count) in histogram.iter().enumerate() {
        seen += count;
        if seen >= rank {
            return value as u8;
        }
    }
    255
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_a_known_error_map() {
        // 100 pixels: 90 zeros, 9 at 10, one at 200.
        let mut errors = vec![0u8; 90];
        errors.extend([10u8; 9]);
        errors.push(200);
        let s = PixelStats::of(&errors, 9, 99.0);
        assert_eq!(s.differing, 10);
        assert_eq!(s.max, 200);
        assert!((s.mean - (90.0 + 200.0) / 100.0).abs() < 1e-12);
        assert_eq!(
            s.percentile_value, 10,
            "the 99th value of 100 is the last 10"
        );
        assert_eq!(PixelStats::of(&errors, 9, 100.0).percentile_value, 200);
        assert_eq!(PixelStats::of(&errors, 9, 90.0).percentile_value, 0);
        assert_eq!(PixelStats::of(&errors, 200, 99.0).differing, 0);
        assert_eq!(PixelStats::of(&errors, 255, 99.0).differing, 0);
    }

    #[test]
    fn error_is_the_largest_channel_difference() {
        let a = RgbaImage::from_raw(2, 1, vec![10, 20, 30, 255, 0, 0, 0, 255]).unwrap();
        let b = RgbaImage::from_raw(2, 1, vec![13, 15, 30, 255, 0, 0, 0, 200]).unwrap();
        assert_eq!(pixel_errors(&a, &b), vec![5, 55]);
        assert!(!rgb_equal(&a, &b));
        assert!(rgb_equal(&a, &a));
    }
}
