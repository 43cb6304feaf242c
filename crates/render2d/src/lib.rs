//! Rendering the terrain to pixels: the 2D emitter ([`emit`], always built), and with the
//! feature `raster` the CPU renderers, with `gpu` the wgpu renderer.
//!
//! `exact` is the CPU ground truth: the exact field evaluated at every pixel, anti-aliased
//! and shaded. The reduced-scale pipeline (SDF pass at 1/16 scale, reconstruction, upsample
//! and shade) is configured by `options`, laid out by `lattice`, and measured against it.

#![forbid(unsafe_code)]

pub mod emit;

#[cfg(feature = "raster")]
pub(crate) mod camera;
#[cfg(feature = "raster")]
pub(crate) mod exact;
#[cfg(feature = "raster")]
pub mod fidelity;
#[cfg(feature = "gpu")]
pub mod gpu;
#[cfg(feature = "raster")]
pub(crate) mod lattice;
#[cfg(feature = "raster")]
pub(crate) mod options;
#[cfg(feature = "raster")]
pub mod overlay;
#[cfg(feature = "raster")]
pub mod twin;

#[cfg(feature = "raster")]
pub use camera::{Camera, CameraError, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE};
#[cfg(feature = "raster")]
pub use exact::{ExactRenderOptions, render_exact};
#[cfg(feature = "raster")]
pub use lattice::Lattice;
#[cfg(feature = "raster")]
pub use options::{Reconstruction, RenderOptions, Scale, ShadeOptions, Upsample};
#[cfg(feature = "raster")]
pub use twin::{
    FieldImage, LowRes, RefineStats, Texel, TwinError, field_image, render_refine, render_twin,
};
