//! The 3D SDF world renderer: scenes, their emitted form, and a SIMD CPU sphere tracer; the
//! GPU raymarcher runs the same emitted form as WGSL.
//!
//! * [`plan`]: the emitted world for one camera, the contract both renderers execute.
//! * [`simd`]: lane primitives per instruction set (AVX2+FMA, NEON, scalar, counting).
//! * [`math`]: polynomial `exp`, `log`, `sin`, `cos` over those lanes.

#[cfg(feature = "gpu")]
pub mod gpu;
pub mod cpu;
pub mod math;
pub mod noise;
pub mod plan;
pub mod scene;
pub mod simd;

pub use plan::{Camera, Plan};
