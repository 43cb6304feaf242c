//! Feature presence and recall: a declared thin solid or gap is present in a distance image
//! when its centre line lies on the right side of the contour almost everywhere.

use glam::Vec2;

use super::{
    Feature, FeatureKind, FidelityError, PRESENCE_FRACTION, Recall, SAMPLE_STEP_PX, TARGET_WIDTH_PX,
};

/// Most centre-line samples one feature may have (a polyline 1,000,000 px long).
const MAX_SAMPLES: f32 = 1.0e6;

/// Recall of every group of features.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Recalls {
    pub solid: Recall,
    pub gap: Recall,
    pub solid_target: Recall,
    pub gap_target: Recall,
}

/// Checks that every feature has a finite, bounded centre line and a positive width.
pub(super) fn check(features: &[Feature]) -> Result<(), FidelityError> {
    for (index, f) in features.iter().enumerate() {
        let bad = |reason| Err(FidelityError::BadFeature { index, reason });
        if f.centre_line.is_empty() {
            return bad("the centre line has no point");
        }
        if !f.centre_line.iter().all(|p| p.is_finite()) {
            return bad("a centre-line point is not finite");
        }
        let width_valid = f.width_px.is_finite() && f.width_px > 0.0;
        if !width_valid {
            return bad("the width must be positive and finite");
        }
        let length: f32 = f.centre_line.windows(2).map(|s| s[0].distance(s[1])).sum();
        let bounded = length / SAMPLE_STEP_PX <= MAX_SAMPLES;
        if !bounded {
            return bad("the centre line is longer than 1,000,000 samples");
        }
    }
    Ok(())
}

/// Recall of `features` in `test` relative to `truth` (checked images and features).
pub(super) fn recall(
    width: u32,
    height: u32,
    truth: &[f32],
    test: &[f32],
    features: &[Feature],
) -> Recalls {
    let mut r = Recalls::default();
    for f in features {
        if !present(width, height, truth, f) {
            continue;
        }
        let kept = usize::from(present(width, height, test, f));
        let target = f.width_px >= TARGET_WIDTH_PX;
        let (all, wide) = match f.kind {
            FeatureKind::Solid => (&mut r.solid, &mut r.solid_target),
            FeatureKind::Gap => (&mut r.gap, &mut r.gap_target),
        };
        all.in_truth += 1;
        all.kept += kept;
        if target {
            wide.in_truth += 1;
            wide.kept += kept;
        }
    }
    r
}

/// Whether `feature` is present in the distance image (see the module documentation of
/// `fidelity`).
pub(super) fn present(width: u32, height: u32, d: &[f32], feature: &Feature) -> bool {
    let (mut inside_image, mut on_side) = (0usize, 0usize);
    for p in samples(&feature.centre_line) {
        let (x, y) = (p.x.floor(), p.y.floor());
        let in_image = x >= 0.0 && y >= 0.0 && x < width as f32 && y < height as f32;
        if !in_image {
            continue;
        }
        inside_image += 1;
        let v = d[y as usize * width as usize + x as usize];
        let right_side = match feature.kind {
            FeatureKind::Solid => v <= 0.0,
            FeatureKind::Gap => v >= 0.0,
        };
        on_side += usize::from(right_side);
    }
    inside_image > 0 && on_side as f64 >= PRESENCE_FRACTION * inside_image as f64
}

/// Points along the polyline at most [`SAMPLE_STEP_PX`] apart: each segment's start, evenly
/// spaced points inside it, and the last point.
fn samples(line: &[Vec2]) -> impl Iterator<Item = Vec2> + '_ {
    let segments = line.windows(2).flat_map(|s| {
        let steps = (s[0].distance(s[1]) / SAMPLE_STEP_PX).ceil().max(1.0) as u32;
        (0..steps).map(move |i| s[0].lerp(s[1], i as f32 / steps as f32))
    });
    segments.chain(line.last().copied())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_at_most_a_step_apart_and_cover_both_ends() {
        let line = [Vec2::ZERO, Vec2::new(10.0, 0.0), Vec2::new(10.0, 2.5)];
        let s: Vec<Vec2> = samples(&line).collect();
        assert_eq!(s.first(), Some(&Vec2::ZERO));
        assert_eq!(s.last(), Some(&Vec2::new(10.0, 2.5)));
        assert_eq!(s.len(), 10 + 3 + 1);
        assert!(s.windows(2).all(|w| w[0].distance(w[1]) <= 1.0 + 1e-6));
        assert_eq!(samples(&[Vec2::ONE]).count(), 1);
    }

    #[test]
    fn presence_needs_ninety_percent_of_the_samples() {
        // A 20-pixel row: solid except for the last `holes` pixels.
        let feature = Feature {
            kind: FeatureKind::Solid,
            centre_line: vec![Vec2::new(0.5, 0.5), Vec2::new(19.5, 0.5)],
            width_px: 1.0,
        };
        let row = |holes: usize| -> Vec<f32> {
            (0..20)
                .map(|i| if i < 20 - holes { -1.0 } else { 1.0 })
                .collect()
        };
        assert!(present(20, 1, &row(0), &feature));
        assert!(present(20, 1, &row(2), &feature), "18 of 20 is 90%");
        assert!(!present(20, 1, &row(3), &feature));
        let gap = Feature {
            kind: FeatureKind::Gap,
            ..feature.clone()
        };
        assert!(present(20, 1, &row(20), &gap));
        assert!(!present(20, 1, &row(0), &gap));
        // Entirely outside the image: present nowhere.
        let outside = Feature {
            centre_line: vec![Vec2::new(-5.0, 0.5)],
            ..feature
        };
        assert!(!present(20, 1, &row(0), &outside));
    }
}
