//! Rendering the terrain to pixels.
//!
//! [`exact`] is the CPU ground truth: the exact field evaluated at every pixel, anti-aliased
//! and shaded. The reduced-scale GPU pipeline and its CPU twin are measured against it.

pub mod camera;
pub mod exact;
pub mod overlay;

pub use camera::Camera;
pub use exact::{ExactRenderOptions, render_exact};
