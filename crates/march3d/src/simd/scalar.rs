//! The tracer's scalar lanes: what [`Pack`] adds to `craterfield-core`'s [`Scalar`] token (one
//! `f32` lane, plain Rust, every platform; the fallback and the reference the SIMD backends
//! are tested against). Without FMA hardware `fma` multiplies, then adds.

use craterfield_core::simd::Scalar;

use super::{Pack, PackKernel};

impl Pack for Scalar {
    #[inline]
    fn call<K: PackKernel>(self, k: K) -> K::Output {
        // Out of line, like the SIMD backends' target-feature functions: a kernel is
        // compiled once per call type, not inlined into each caller.
        #[inline(never)]
        fn inner<K: PackKernel>(k: K) -> K::Output {
            k.run(Scalar)
        }
        inner(k)
    }
    #[inline(always)]
    fn fma(self, a: f32, b: f32, c: f32) -> f32 {
        // Unfused: a software fused multiply-add would be far slower than the SIMD paths.
        a * b + c
    }
    #[inline(always)]
    fn fnma(self, a: f32, b: f32, c: f32) -> f32 {
        c - a * b
    }
    #[inline(always)]
    fn rsqrt(self, a: f32) -> f32 {
        1.0 / a.sqrt()
    }
    #[inline(always)]
    fn round(self, a: f32) -> f32 {
        a.round_ties_even()
    }
    #[inline(always)]
    fn and_not(self, a: bool, b: bool) -> bool {
        a & !b
    }
    #[inline(always)]
    fn none(self) -> bool {
        false
    }
    #[inline(always)]
    fn all_set(self) -> bool {
        true
    }
    #[inline(always)]
    fn bitmask(self, m: bool) -> u32 {
        m as u32
    }
    #[inline(always)]
    fn eq_i(self, a: i32, b: i32) -> bool {
        a == b
    }
    #[inline(always)]
    fn round_i(self, v: f32) -> i32 {
        v.round_ties_even() as i32
    }
    #[inline(always)]
    fn sub_i(self, a: i32, b: i32) -> i32 {
        a.wrapping_sub(b)
    }
    #[inline(always)]
    fn and_i(self, a: i32, b: i32) -> i32 {
        a & b
    }
    #[inline(always)]
    fn or_i(self, a: i32, b: i32) -> i32 {
        a | b
    }
    #[inline(always)]
    fn shl_n<const N: i32>(self, a: i32) -> i32 {
        ((a as u32) << N) as i32
    }
    #[inline(always)]
    fn shr_n<const N: i32>(self, a: i32) -> i32 {
        ((a as u32) >> N) as i32
    }
}
