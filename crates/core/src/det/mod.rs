//! The deterministic foundation every other module builds on: float math whose every
//! operation is exactly rounded, so that every machine and every SIMD backend gets the same
//! bits ([`math`]), and the fixed-point numbers events and settings travel in ([`quant`]).
//!
//! The determinism contract (`docs/ARCHITECTURE.md`) is kept here: nothing in this module
//! calls a platform `sin`, `exp` or fused multiply-add.

pub mod math;
pub mod quant;
