//! The shading formula of the render pipeline (`docs/render2d-pipeline.md`, "Shading"): one
//! pixel's colour from its distance in pixels, unit normal, base colour and sky colour. The
//! twin and the full-resolution exact reference both shade through [`Shader`], so their
//! pictures differ only where their fields do.

use glam::Vec2;
use thiserror::Error;

use crate::options::ShadeOptions;

/// Colour of a material that is not in the palette.
pub const MISSING_MATERIAL: [u8; 3] = [255, 0, 255];

/// A shading option that cannot be drawn with.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum ShadeError {
    /// `shade_depth_px` is not a positive finite number.
    #[error("shade option shade_depth_px = {0} must be positive and finite")]
    ShadeDepth(f32),
    /// `outline_px` is not finite.
    #[error("shade option outline_px = {0} must be finite")]
    Outline(f32),
    /// `light` is not finite.
    #[error("shade option light = {0} must be finite")]
    Light(Vec2),
}

/// Checks that `options` shade to finite colours.
pub fn check_shade(options: &ShadeOptions) -> Result<(), ShadeError> {
    let depth = options.shade_depth_px;
    let depth_ok = depth.is_finite() && depth > 0.0;
    if !depth_ok {
        return Err(ShadeError::ShadeDepth(depth));
    }
    if !options.outline_px.is_finite() {
        return Err(ShadeError::Outline(options.outline_px));
    }
    if !options.light.is_finite() {
        return Err(ShadeError::Light(options.light));
    }
    Ok(())
}

/// [`ShadeOptions`] prepared for one image: colours as floats, the light normalized.
#[derive(Clone, Debug, PartialEq)]
pub struct Shader {
    sky_top: [f32; 3],
    sky_bottom: [f32; 3],
    outline_px: f32,
    shade_depth_px: f32,
    light: Vec2,
    height: f32,
}

impl Shader {
    /// Shading for an image `height` pixels high.
    pub fn new(options: &ShadeOptions, height: u32) -> Shader {
        Shader {
            sky_top: options.sky_top.map(f32::from),
            sky_bottom: options.sky_bottom.map(f32::from),
            outline_px: options.outline_px,
            shade_depth_px: options.shade_depth_px,
            light: unit_or(options.light, Vec2::Y),
            height: height.max(1) as f32,
        }
    }

    /// Sky colour of image row `y`: `mix(sky_top, sky_bottom, y / H)`.
    pub fn sky(&self, y: u32) -> [f32; 3] {
        let t = y as f32 / self.height;
        let (top, bottom) = (self.sky_top, self.sky_bottom);
        [
            mix(top[0], bottom[0], t),
            mix(top[1], bottom[1], t),
            mix(top[2], bottom[2], t),
        ]
    }

    /// Whether the colour at `d_px` depends on the normal (elsewhere any normal will do).
    pub fn needs_normal(&self, d_px: f32) -> bool {
        d_px < 0.5 && d_px > -self.shade_depth_px * 0.5
    }

    /// Depth in pixels from which on the colour no longer depends on the distance: at
    /// `d_px <= -interior_depth()` every pixel of a row and material has the same colour
    /// (full coverage, darkest shade, no rim, no outline).
    pub fn interior_depth(&self) -> f32 {
        let exact = self.shade_depth_px.max(self.outline_px + 0.5).max(0.5);
        // A hair deeper, so that rounding in `d_px + outline_px + 0.5` cannot leave a trace
        // of outline.
        exact * (1.0 + 1.0e-6) + 1.0e-3
    }

    /// The sky colour of image row `y`, rounded: what [`Shader::shade`] gives wherever the
    /// pixel is not covered.
    pub fn sky_rgb(&self, y: u32) -> [u8; 3] {
        self.sky(y).map(to_u8)
    }

    /// The pixel's colour: the formula of the pipeline doc, in floats, rounded once.
    /// `base` is `None` for a material that is not in the palette (drawn magenta).
    pub fn shade(&self, d_px: f32, normal: Vec2, base: Option<[u8; 3]>, sky: [f32; 3]) -> [u8; 3] {
        let coverage = (0.5 - d_px).clamp(0.0, 1.0);
        let covered = coverage > 0.0;
        if !covered {
            // `mix(sky, color, 0)` is the sky: the rest of the formula cannot matter.
            return [to_u8(sky[0]), to_u8(sky[1]), to_u8(sky[2])];
        }
        let base = base.unwrap_or(MISSING_MATERIAL);
        let depth = (-d_px / self.shade_depth_px).clamp(0.0, 1.0);
        let darken = 1.0 - 0.4 * depth;
        let half_depth = self.shade_depth_px * 0.5;
        let lit_rim = d_px > -half_depth;
        let gain = if lit_rim {
            let lit = normal.x * self.light.x + normal.y * self.light.y;
            let rim = (1.0 + d_px / half_depth).clamp(0.0, 1.0);
            1.0 + 0.35 * lit * rim
        } else {
            1.0
        };
        let outline = (d_px + self.outline_px + 0.5).clamp(0.0, 1.0) * coverage;
        let channel = |i: usize| {
            let b = f32::from(base[i]);
            let mut color = b * darken;
            if lit_rim {
                color *= gain;
            }
            let color = mix(color, b * 0.35, outline);
            to_u8(mix(sky[i], color, coverage))
        };
        [channel(0), channel(1), channel(2)]
    }
}

/// One pixel's colour with `options` (see [`Shader::shade`]; prepare a [`Shader`] once per
/// image instead where many pixels are shaded).
pub fn shade(
    d_px: f32,
    normal: Vec2,
    base: Option<[u8; 3]>,
    sky: [f32; 3],
    options: &ShadeOptions,
) -> [u8; 3] {
    Shader::new(options, 1).shade(d_px, normal, base, sky)
}

/// `v` scaled to unit length, or `fallback` where it has no direction.
pub(crate) fn unit_or(v: Vec2, fallback: Vec2) -> Vec2 {
    let len2 = v.x * v.x + v.y * v.y;
    let usable = len2 > 0.0 && len2.is_finite();
    if usable {
        v * (1.0 / len2.sqrt())
    } else {
        fallback
    }
}

/// `a + (b - a) t`.
pub(super) fn mix(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}

/// A colour channel clamped to `0..255` and rounded to the nearest integer, halves away
/// from zero: `v.clamp(0.0, 255.0).round() as u8` without a library call (the fraction
/// `v - trunc(v)` is exact).
fn to_u8(v: f32) -> u8 {
    let v = v.clamp(0.0, 255.0);
    let whole = v as u8;
    let up = v - f32::from(whole) >= 0.5;
    whole + u8::from(up)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shader() -> Shader {
        Shader::new(&ShadeOptions::default(), 100)
    }

    #[test]
    fn sky_outside_and_flat_colour_deep_inside() {
        let s = shader();
        let sky = s.sky(50);
        assert_eq!(
            s.shade(0.5, Vec2::Y, Some([100, 100, 100]), sky),
            sky.map(to_u8)
        );
        assert_eq!(s.shade(40.0, Vec2::ZERO, None, sky), sky.map(to_u8));
        let deep = s.interior_depth();
        let a = s.shade(-deep, Vec2::Y, Some([100, 50, 200]), sky);
        let b = s.shade(-deep * 3.0, Vec2::X, Some([100, 50, 200]), sky);
        assert_eq!(a, b);
        assert_eq!(a, [60, 30, 120]);
    }

    #[test]
    fn surface_is_outlined_lit_and_antialiased() {
        let s = shader();
        let sky = s.sky(0);
        let base = Some([200, 100, 60]);
        // One pixel inside, the outline is full: base * 0.35, fully covered.
        assert_eq!(s.shade(-1.0, Vec2::Y, base, sky), [70, 35, 21]);
        // On the surface the pixel is half sky.
        let edge = s.shade(0.0, Vec2::Y, base, sky);
        for i in 0..3 {
            let (lo, hi) = (sky[i].min(70.0), sky[i].max(200.0));
            assert!((lo..=hi).contains(&f32::from(edge[i])), "{edge:?}");
        }
        // Below the outline a surface facing the light is brighter than one facing away.
        let toward = s.shade(-4.0, Vec2::new(-0.35, 0.94).normalize(), base, sky);
        let away = s.shade(-4.0, -Vec2::new(-0.35, 0.94).normalize(), base, sky);
        assert!(
            toward[0] > away[0] && toward[1] > away[1],
            "{toward:?} {away:?}"
        );
        // Unknown materials are magenta.
        assert_eq!(s.shade(-100.0, Vec2::ZERO, None, sky), [153, 0, 153]);
    }

    #[test]
    fn channel_rounding_is_round_half_away_from_zero() {
        let mut values = vec![
            f32::NAN,
            -1.0,
            -0.5,
            0.0,
            0.49999997,
            0.5,
            254.5,
            255.0,
            300.0,
        ];
        values.extend((0..=2600).map(|i| i as f32 * 0.1 - 2.0));
        values.extend((0..=255).map(|i| i as f32 + 0.5));
        for v in values {
            assert_eq!(to_u8(v), v.clamp(0.0, 255.0).round() as u8, "{v}");
        }
    }

    #[test]
    fn bad_options_are_named() {
        let bad = |f: fn(&mut ShadeOptions)| {
            let mut o = ShadeOptions::default();
            f(&mut o);
            check_shade(&o)
        };
        assert_eq!(
            bad(|o| o.shade_depth_px = 0.0),
            Err(ShadeError::ShadeDepth(0.0))
        );
        assert!(matches!(
            bad(|o| o.outline_px = f32::NAN),
            Err(ShadeError::Outline(_))
        ));
        assert!(matches!(
            bad(|o| o.light.x = f32::INFINITY),
            Err(ShadeError::Light(_))
        ));
        assert_eq!(check_shade(&ShadeOptions::default()), Ok(()));
    }
}
