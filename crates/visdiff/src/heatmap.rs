//! Difference heat-maps: a report's per-pixel error drawn with the magma colour ramp (black,
//! purple, orange, pale yellow), so that where two images differ, and how much, shows at a
//! glance.

use image::{Rgba, RgbaImage};
use serde::{Deserialize, Serialize};

use super::DiffReport;

/// Which per-pixel error a heat-map shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum HeatSource {
    /// The largest channel difference, scaled so that the report's largest error is the top
    /// of the ramp (even a one-level difference is visible). The default.
    #[default]
    Pixel,
    /// The FLIP error, unscaled: `0` is the bottom of the ramp, `1` the top.
    Perceptual,
}

/// A heat-map of `report`'s per-pixel error: exactly black where the error is zero, then the
/// magma ramp up to pale yellow at the top of the scale (see [`HeatSource`]); opaque.
pub fn heatmap(report: &DiffReport, source: HeatSource) -> RgbaImage {
    let ramp = magma();
    let levels: Vec<f32> = match source {
        HeatSource::Pixel => {
            let top = f32::from(report.max.max(1));
            report
                .pixel_errors()
                .iter()
                .map(|&e| f32::from(e) / top)
                .collect()
        }
        HeatSource::Perceptual => report.flip_map().to_vec(),
    };
    let mut image = RgbaImage::new(report.width, report.height);
    for (pixel, &t) in image.pixels_mut().zip(&levels) {
        *pixel = color(&ramp, t);
    }
    image
}

fn color(ramp: &[[u8; 3]], t: f32) -> Rgba<u8> {
    // Zero error is pure black, not the ramp's near-black first entry, so that "equal" is
    // unambiguous in the picture.
    let equal = t <= 0.0 || t.is_nan();
    if equal {
        return Rgba([0, 0, 0, 255]);
    }
    let last = ramp.len() - 1;
    let index = ((t.min(1.0) * last as f32).round() as usize).clamp(1, last);
    let [r, g, b] = ramp[index];
    Rgba([r, g, b, 255])
}

/// FLIP's magma colour map, 256 entries.
fn magma() -> Vec<[u8; 3]> {
    let lut = nv_flip::magma_lut().to_vec();
    lut.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_runs_from_dark_to_pale_yellow() {
        let ramp = magma();
        assert_eq!(ramp.len(), 256);
        let lum = |c: [u8; 3]| u32::from(c[0]) + u32::from(c[1]) + u32::from(c[2]);
        assert!(lum(ramp[0]) < 20, "{:?}", ramp[0]);
        let top = ramp[255];
        assert!(top[0] > 240 && top[1] > 240 && top[2] > 150 && top[2] < top[0]);
        assert!(lum(ramp[64]) < lum(ramp[128]) && lum(ramp[128]) < lum(ramp[192]));
        assert_eq!(color(&ramp, 0.0), Rgba([0, 0, 0, 255]));
        assert_ne!(color(&ramp, 0.001), Rgba([0, 0, 0, 255]));
    }
}
