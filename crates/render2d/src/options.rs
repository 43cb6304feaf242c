//! Options of the reduced-scale render pipeline, shared by the GPU renderer and its CPU twin
//! so that both draw the same picture from the same settings.

use glam::Vec2;
use serde::{Deserialize, Serialize};

/// How much smaller than the output the SDF pass runs, per axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Scale {
    /// Full resolution: one texel per pixel.
    Full,
    /// 1/4 per axis (16x fewer texels).
    Quarter,
    /// 1/8 per axis (64x fewer texels).
    Eighth,
    /// 1/16 per axis (256x fewer texels), the default.
    #[default]
    Sixteenth,
    /// 1/32 per axis (1024x fewer texels).
    ThirtySecond,
}

impl Scale {
    /// Every scale, finest first.
    pub const ALL: [Scale; 5] = [
        Scale::Full,
        Scale::Quarter,
        Scale::Eighth,
        Scale::Sixteenth,
        Scale::ThirtySecond,
    ];

    /// Output pixels per texel along one axis (1, 4, 8, 16 or 32).
    pub fn divisor(self) -> u32 {
        match self {
            Scale::Full => 1,
            Scale::Quarter => 4,
            Scale::Eighth => 8,
            Scale::Sixteenth => 16,
            Scale::ThirtySecond => 32,
        }
    }

    /// The scale with the given divisor, if it is one of the supported ones.
    pub fn from_divisor(divisor: u32) -> Option<Scale> {
        Scale::ALL.into_iter().find(|s| s.divisor() == divisor)
    }
}

/// Pass 2: how thin features lost between texels are brought back.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Reconstruction {
    /// No reconstruction: the sampled distances are upsampled as they are.
    Off,
    /// The divergence heuristic: where the divergence of the packed gradient says "local
    /// minimum", the distance is lowered by up to one texel (brings back thin solids, fattens
    /// them, loses thin gaps).
    Divergence,
    /// Tangent planes: every texel's distance and gradient give the plane
    /// `d_i + g_i . (p - c_i)`; per pixel, planes of texels whose gradients diverge are
    /// combined by `max`, converging ones by `min`, and the results blended. Keeps thin
    /// solids and thin gaps at their true width.
    Planes,
    /// Proven exact: the `planes` texels, and a proof per 4x4 pixel block from the field's
    /// Lipschitz bound and each texel's material margin that no surface crosses the block
    /// and no other material wins in it; blocks without such a proof are evaluated exactly
    /// at every pixel. Inside/outside and materials are the exact render's at every pixel
    /// (see `docs/render2d-pipeline.md`, "Refine"). Needs the field in pass 3, so only the
    /// renderers that hold the terrain draw it. The default.
    #[default]
    Refine,
}

impl Reconstruction {
    /// Every mode.
    pub const ALL: [Reconstruction; 4] = [
        Reconstruction::Off,
        Reconstruction::Divergence,
        Reconstruction::Planes,
        Reconstruction::Refine,
    ];

    /// The mode's name as the CLI and the benchmarks print it.
    pub fn name(self) -> &'static str {
        match self {
            Reconstruction::Off => "off",
            Reconstruction::Divergence => "divergence",
            Reconstruction::Planes => "planes",
            Reconstruction::Refine => "refine",
        }
    }

    /// The mode called `name` (as [`Reconstruction::name`] prints it).
    pub fn from_name(name: &str) -> Option<Reconstruction> {
        Reconstruction::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether pass 3 reads the `planes` pair values (modes `planes` and `refine`).
    pub fn uses_planes(self) -> bool {
        matches!(self, Reconstruction::Planes | Reconstruction::Refine)
    }
}

/// Pass 3: how the reduced-scale distance is interpolated to output pixels (modes `off` and
/// `divergence`; the `planes` mode has its own interpolant).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Upsample {
    /// Bilinear: one hardware-filtered tap.
    Bilinear,
    /// Cubic B-spline from four bilinear taps (smooth, approximating). The default.
    #[default]
    BSpline,
    /// Catmull-Rom cubic (interpolating, sharper; may overshoot).
    CatmullRom,
}

impl Upsample {
    /// Every filter.
    pub const ALL: [Upsample; 3] = [Upsample::Bilinear, Upsample::BSpline, Upsample::CatmullRom];

    /// The filter's name as the CLI and the benchmarks print it.
    pub fn name(self) -> &'static str {
        match self {
            Upsample::Bilinear => "bilinear",
            Upsample::BSpline => "bspline",
            Upsample::CatmullRom => "catmull-rom",
        }
    }
}

/// Colours and shading of the final pass.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShadeOptions {
    /// Sky colour at the top of the image.
    pub sky_top: [u8; 3],
    /// Sky colour at the bottom of the image.
    pub sky_bottom: [u8; 3],
    /// Width of the dark outline inside the surface, pixels.
    pub outline_px: f32,
    /// Depth over which the interior darkens, pixels.
    pub shade_depth_px: f32,
    /// Direction the light comes from (world space; normalized where used).
    pub light: Vec2,
}

impl Default for ShadeOptions {
    fn default() -> Self {
        ShadeOptions {
            sky_top: [40, 64, 112],
            sky_bottom: [150, 180, 214],
            outline_px: 1.5,
            shade_depth_px: 28.0,
            light: Vec2::new(-0.35, 0.94),
        }
    }
}

/// Everything that decides what the reduced-scale pipeline draws.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RenderOptions {
    /// Scale of passes 1 and 2.
    pub scale: Scale,
    /// Pass 2 mode.
    pub reconstruction: Reconstruction,
    /// Pass 3 filter (ignored by [`Reconstruction::Planes`]).
    pub upsample: Upsample,
    /// Colours and shading.
    pub shade: ShadeOptions,
}
