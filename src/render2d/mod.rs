//! Rendering the terrain to pixels.
//!
//! `exact` is the CPU ground truth: the exact field evaluated at every pixel, anti-aliased
//! and shaded. The reduced-scale pipeline (SDF pass at 1/16 scale, reconstruction, upsample
//! and shade) is configured by `options`, laid out by `lattice`, and measured against it.

pub(crate) mod camera;
pub(crate) mod exact;
pub mod fidelity;
#[cfg(feature = "gpu")]
pub mod gpu;
pub(crate) mod lattice;
pub(crate) mod options;
pub mod overlay;
pub mod twin;

pub use camera::{Camera, CameraError, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE};
pub use exact::{ExactRenderOptions, render_exact};
pub use lattice::Lattice;
pub use options::{Reconstruction, RenderOptions, Scale, ShadeOptions, Upsample};
pub use twin::{
    FieldImage, LowRes, RefineStats, Texel, TwinError, field_image, render_refine, render_twin,
};
