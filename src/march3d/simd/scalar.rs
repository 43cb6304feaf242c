//! The scalar backend: one `f32` lane, plain Rust, every platform (the fallback and the
//! reference the SIMD backends are tested against).

use super::{Pack, PackKernel};

/// The scalar backend's token.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Scalar;

impl Pack for Scalar {
    const WIDTH: usize = 1;
    type F = f32;
    type M = bool;
    type I = i32;

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
    fn splat(self, v: f32) -> f32 {
        v
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> f32 {
        s[0]
    }
    #[inline(always)]
    fn store(self, v: f32, out: &mut [f32]) {
        out[0] = v;
    }
    #[inline(always)]
    fn add(self, a: f32, b: f32) -> f32 {
        a + b
    }
    #[inline(always)]
    fn sub(self, a: f32, b: f32) -> f32 {
        a - b
    }
    #[inline(always)]
    fn mul(self, a: f32, b: f32) -> f32 {
        a * b
    }
    #[inline(always)]
    fn div(self, a: f32, b: f32) -> f32 {
        a / b
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
    fn sqrt(self, a: f32) -> f32 {
        a.sqrt()
    }
    #[inline(always)]
    fn neg(self, a: f32) -> f32 {
        -a
    }
    #[inline(always)]
    fn abs(self, a: f32) -> f32 {
        a.abs()
    }
    #[inline(always)]
    fn floor(self, a: f32) -> f32 {
        a.floor()
    }
    #[inline(always)]
    fn round(self, a: f32) -> f32 {
        a.round_ties_even()
    }
    #[inline(always)]
    fn min(self, a: f32, b: f32) -> f32 {
        if a < b { a } else { b }
    }
    #[inline(always)]
    fn max(self, a: f32, b: f32) -> f32 {
        if a > b { a } else { b }
    }
    #[inline(always)]
    fn lt(self, a: f32, b: f32) -> bool {
        a < b
    }
    #[inline(always)]
    fn le(self, a: f32, b: f32) -> bool {
        a <= b
    }
    #[inline(always)]
    fn gt(self, a: f32, b: f32) -> bool {
        a > b
    }
    #[inline(always)]
    fn ge(self, a: f32, b: f32) -> bool {
        a >= b
    }
    #[inline(always)]
    fn select(self, m: bool, a: f32, b: f32) -> f32 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn select_i(self, m: bool, a: i32, b: i32) -> i32 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn and(self, a: bool, b: bool) -> bool {
        a & b
    }
    #[inline(always)]
    fn or(self, a: bool, b: bool) -> bool {
        a | b
    }
    #[inline(always)]
    fn and_not(self, a: bool, b: bool) -> bool {
        a & !b
    }
    #[inline(always)]
    fn not(self, a: bool) -> bool {
        !a
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
    fn splat_i(self, v: i32) -> i32 {
        v
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> i32 {
        s[0]
    }
    #[inline(always)]
    fn store_i(self, v: i32, out: &mut [i32]) {
        out[0] = v;
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
    fn to_f32(self, v: i32) -> f32 {
        v as f32
    }
    #[inline(always)]
    fn add_i(self, a: i32, b: i32) -> i32 {
        a.wrapping_add(b)
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
    fn shl_i<const N: i32>(self, a: i32) -> i32 {
        ((a as u32) << N) as i32
    }
    #[inline(always)]
    fn shr_i<const N: i32>(self, a: i32) -> i32 {
        ((a as u32) >> N) as i32
    }
    #[inline(always)]
    fn bits(self, a: f32) -> i32 {
        a.to_bits() as i32
    }
    #[inline(always)]
    fn from_bits(self, a: i32) -> f32 {
        f32::from_bits(a as u32)
    }
}
