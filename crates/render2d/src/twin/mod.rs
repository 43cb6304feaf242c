//! The CPU twin of the reduced-scale render pipeline: the same three passes as the GPU
//! renderer, computed exactly as `docs/render2d-pipeline.md` writes them. It is the
//! fallback renderer where no GPU adapter exists and the reference the GPU images are
//! diffed against.
//!
//! 1. [`sdf_pass`]: the terrain sampled at every texel of the [`Lattice`] with the SIMD
//!    batch evaluator, values rounded through `f16` as the GPU texture stores them.
//! 2. [`reconstruct`]: the divergence heuristic, or the pair values of the tangent-plane
//!    reconstruction.
//! 3. [`render_lowres`] (upsample and shade) or [`field_image_lowres`] (upsample only).
//!
//! [`render_twin`] and [`field_image`] run all three. Pass 3 works one lattice quad (an
//! `s x s` pixel block) at a time: quads whose distance bounds prove them all sky or all
//! deep interior are filled without per-pixel work, the others evaluate the interpolant
//! row by row. [`render_lowres_per_pixel`] is the same pass written pixel by pixel straight
//! from the formulas; the fast path gives the identical image (tested).
//!
//! Every pass splits its work over `threads` scoped threads (0: all cores); the output does
//! not depend on the thread count.

mod blocks;
mod f16;
mod frame;
mod paint;
mod reconstruct;
mod refine;
mod sdf;
mod shade;
mod threads;
mod upsample;

use glam::Vec2;
use thiserror::Error;

use super::camera::CameraError;
use super::lattice::Lattice;
use craterfield_field::tape::EvalError;

pub use f16::{F16_MAX, f16_bits, f16_to_f32, round_f16};
pub use frame::{
    exact_field, field_image, field_image_lowres, render_direct, render_lowres,
    render_lowres_per_pixel, render_refine, render_refine_overlay, render_twin,
};
pub use reconstruct::reconstruct;
pub use refine::{BLOCK as REFINE_BLOCK, RefineStats};
pub use sdf::sdf_pass;
pub use shade::{MISSING_MATERIAL, ShadeError, Shader, check_shade, shade};

/// One reduced-scale texel as pass 1 stores it (values already rounded through `f16`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Texel {
    /// Signed distance, world units (clamped to the terrain's band).
    pub d: f32,
    /// Gradient of the distance (unit length, or zero where the field is flat).
    pub g: Vec2,
    /// Material of the winning surface.
    pub material: u16,
}

/// Output of passes 1 and 2: the lattice, its texels (row-major, row 0 = top) and, after
/// the `planes` reconstruction, the four pair values per texel (right, down, diag, anti).
#[derive(Clone, Debug, PartialEq)]
pub struct LowRes {
    /// Where the texels sit.
    pub lattice: Lattice,
    /// `lattice.cols * lattice.rows` texels, row-major.
    pub texels: Vec<Texel>,
    /// Pair values of the `planes` reconstruction, one `[right, down, diag, anti]` per
    /// texel; `None` in the other modes.
    pub pairs: Option<Vec<[f32; 4]>>,
    /// How fast the field may change per world unit (see [`slope_bound`]): the `planes`
    /// interpolant is clamped to `d_k +- slope |p - C_k|` of every quad texel.
    pub slope: f32,
}

/// Largest slope bound used: beyond it the bounds say nothing anyway, and it keeps
/// `slope * 0` finite.
pub const MAX_SLOPE: f32 = 1.0e6;

/// The slope bound used for a field with Lipschitz bound `lipschitz` (at least 1, capped
/// at [`MAX_SLOPE`]; NaN gives the cap). Inside baked brick cells the field is a bilinear
/// interpolant, whose gradient may exceed the bound by up to `sqrt(2)`; the clamp accepts
/// that there (a guaranteed bound would be `sqrt(2)` times looser and leave most phantom
/// fragments of the planes' `max` in place, as `bench fidelity` showed).
pub fn slope_bound(lipschitz: f32) -> f32 {
    let s = lipschitz.max(1.0);
    if s < MAX_SLOPE { s } else { MAX_SLOPE }
}

/// Per-pixel result of pass 3 before shading (row-major, row 0 = top).
#[derive(Clone, Debug, PartialEq)]
pub struct FieldImage {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Reconstructed signed distance, pixels (negative inside).
    pub distance_px: Vec<f32>,
    /// Unit normal (bilinear gradient, normalized; zero where the gradient vanishes).
    pub normal: Vec<Vec2>,
    /// Material (of the nearest texel).
    pub material: Vec<u16>,
}

/// Why the twin cannot render.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum TwinError {
    /// The camera cannot be rendered (see [`crate::Camera::validate`]).
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
    /// The terrain's batch evaluator failed.
    #[error("terrain evaluation: {0}")]
    Eval(#[from] EvalError),
    /// A shading option is unusable.
    #[error(transparent)]
    Shade(#[from] ShadeError),
    /// A lattice given to [`sdf_pass`] is not one a camera can produce.
    #[error(
        "lattice {lattice:?} must have 2..={max_side} columns and rows, a positive finite \
         spacing and texel centres within +-1e7 world units"
    )]
    BadLattice {
        /// The lattice.
        lattice: Lattice,
        /// Largest accepted columns or rows.
        max_side: u32,
    },
    /// A [`LowRes`] buffer does not have one entry per texel.
    #[error("low-res {buffer} has {len} entries, its lattice has {expected} texels")]
    BufferSize {
        /// `"texels"` or `"pairs"`.
        buffer: &'static str,
        /// Entries found.
        len: usize,
        /// Texels of the lattice.
        expected: usize,
    },
    /// Pass 3 in mode `planes` was given a [`LowRes`] without pair values.
    #[error("the planes reconstruction needs pair values: run `reconstruct` in mode planes")]
    MissingPairs,
    /// Mode `refine` evaluates the field in pass 3: it is drawn from the terrain
    /// ([`render_twin`], [`field_image`]), not from reduced-scale textures alone.
    #[error("the refine reconstruction evaluates the field in pass 3: render it from the terrain")]
    NeedsField,
    /// A [`LowRes`] was computed for another camera or scale than pass 3 is drawing.
    #[error("low-res lattice {found:?} is not the camera's lattice {expected:?}")]
    LatticeMismatch {
        /// The low-res lattice.
        found: Lattice,
        /// The lattice of the camera and scale.
        expected: Lattice,
    },
}
