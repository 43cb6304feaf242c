//! The 3D SDF world renderer: scenes, their emitted form, and a SIMD CPU sphere tracer; the
//! GPU raymarcher runs the same emitted form as WGSL.
//!
//! * [`scene`]: RON scene files, their validation, the builtin scenes.
//! * [`compile`]: a scene and a camera to a [`Plan`] (culling, LOD, step tiers, baking and
//!   the shader-side switches); the plan itself, the contract both renderers execute, is
//!   [`crate::plan3d`], and [`crate::codegen3d`] turns it into WGSL.
//! * [`noise`]: lattice hashes, value noise and FBM with analytic gradients.
//! * [`cpu`]: the SIMD sphere tracer and its counting mode.
//! * `gpu` (feature `gpu`): the raymarcher running the plan's emitted WGSL.
//! * [`simd`]: lane primitives per instruction set (AVX2+FMA, NEON, scalar, counting).
//! * [`math`]: polynomial `exp`, `log`, `sin`, `cos` over those lanes.

pub mod codegen3d;
pub mod compile;
pub mod cpu;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod math;
pub mod noise;
pub mod plan3d;
pub mod scene;
pub mod simd;

pub use plan3d::{Camera3d, Plan};
