//! The NEON backend: 4 lanes of `float32x4_t` (aarch64 Advanced SIMD). NEON's `fmin`/`fmax`
//! follow IEEE-754's minimum (NaN-propagating, `-0 < +0`), not the project's definition, so
//! min and max are compare + select here.

use std::arch::aarch64::*;

use super::{Kernel, Lanes};
use crate::backend::Backend;

/// The NEON backend's token; it exists only where the CPU has Advanced SIMD.
#[derive(Clone, Copy, Debug)]
pub struct Neon(());

impl Neon {
    /// The token, if this CPU has NEON (every aarch64 Linux CPU does; still detected).
    pub fn new() -> Option<Neon> {
        Backend::Neon.is_available().then_some(Neon(()))
    }

    /// Runs `k` in a function compiled with NEON enabled.
    #[inline]
    pub fn call<K: Kernel>(self, k: K) -> K::Output {
        #[target_feature(enable = "neon")]
        unsafe fn inner<K: Kernel>(l: Neon, k: K) -> K::Output {
            k.run::<Neon, { super::SIMD_BLOCK }>(l)
        }
        // SAFETY: a `Neon` token exists only after runtime detection of NEON.
        unsafe { inner(self, k) }
    }
}

impl Lanes for Neon {
    const WIDTH: usize = 4;
    type F = float32x4_t;
    type M = uint32x4_t;
    type I = int32x4_t;

    #[inline(always)]
    fn splat(self, v: f32) -> float32x4_t {
        // SAFETY: NEON is available (the token exists).
        unsafe { vdupq_n_f32(v) }
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> float32x4_t {
        let s = &s[..4];
        // SAFETY: NEON is available; `s` holds 4 floats (checked above).
        unsafe { vld1q_f32(s.as_ptr()) }
    }
    #[inline(always)]
    fn store(self, v: float32x4_t, out: &mut [f32]) {
        let out = &mut out[..4];
        // SAFETY: NEON is available; `out` holds 4 floats (checked above).
        unsafe { vst1q_f32(out.as_mut_ptr(), v) }
    }
    #[inline(always)]
    fn add(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available.
        unsafe { vaddq_f32(a, b) }
    }
    #[inline(always)]
    fn sub(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available.
        unsafe { vsubq_f32(a, b) }
    }
    #[inline(always)]
    fn mul(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available.
        unsafe { vmulq_f32(a, b) }
    }
    #[inline(always)]
    fn div(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `fdiv` is correctly rounded.
        unsafe { vdivq_f32(a, b) }
    }
    #[inline(always)]
    fn sqrt(self, a: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `fsqrt` is correctly rounded.
        unsafe { vsqrtq_f32(a) }
    }
    #[inline(always)]
    fn neg(self, a: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available.
        unsafe { vnegq_f32(a) }
    }
    #[inline(always)]
    fn abs(self, a: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available.
        unsafe { vabsq_f32(a) }
    }
    #[inline(always)]
    fn floor(self, a: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `frintm` keeps the sign of zero and NaN.
        unsafe { vrndmq_f32(a) }
    }
    #[inline(always)]
    fn min(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        self.select(self.lt(a, b), a, b)
    }
    #[inline(always)]
    fn max(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        self.select(self.gt(a, b), a, b)
    }
    #[inline(always)]
    fn lt(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vcltq_f32(a, b) }
    }
    #[inline(always)]
    fn gt(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vcgtq_f32(a, b) }
    }
    #[inline(always)]
    fn le(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vcleq_f32(a, b) }
    }
    #[inline(always)]
    fn ge(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vcgeq_f32(a, b) }
    }
    #[inline(always)]
    fn not_nan(self, a: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vceqq_f32(a, a) }
    }
    #[inline(always)]
    fn select(self, m: uint32x4_t, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. Mask lanes are all ones or all zeros.
        unsafe { vbslq_f32(m, a, b) }
    }
    #[inline(always)]
    fn select_i(self, m: uint32x4_t, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { vbslq_s32(m, a, b) }
    }
    #[inline(always)]
    fn and(self, a: uint32x4_t, b: uint32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vandq_u32(a, b) }
    }
    #[inline(always)]
    fn or(self, a: uint32x4_t, b: uint32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vorrq_u32(a, b) }
    }
    #[inline(always)]
    fn xor(self, a: uint32x4_t, b: uint32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { veorq_u32(a, b) }
    }
    #[inline(always)]
    fn not(self, a: uint32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vmvnq_u32(a) }
    }
    #[inline(always)]
    fn any(self, m: uint32x4_t) -> bool {
        // SAFETY: NEON is available.
        unsafe { vmaxvq_u32(m) != 0 }
    }
    #[inline(always)]
    fn splat_i(self, v: i32) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { vdupq_n_s32(v) }
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> int32x4_t {
        let s = &s[..4];
        // SAFETY: NEON is available; `s` holds 4 integers (checked above).
        unsafe { vld1q_s32(s.as_ptr()) }
    }
    #[inline(always)]
    fn store_i(self, v: int32x4_t, out: &mut [i32]) {
        let out = &mut out[..4];
        // SAFETY: NEON is available; `out` holds 4 integers (checked above).
        unsafe { vst1q_s32(out.as_mut_ptr(), v) }
    }
    #[inline(always)]
    fn to_i32(self, v: float32x4_t) -> int32x4_t {
        // SAFETY: NEON is available. `fcvtzs` truncates, saturates and gives 0 for NaN:
        // exactly Rust's `as i32`.
        unsafe { vcvtq_s32_f32(v) }
    }
    #[inline(always)]
    fn to_f32(self, v: int32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. Rounds to nearest even (the FPCR default).
        unsafe { vcvtq_f32_s32(v) }
    }
    #[inline(always)]
    fn add_i(self, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { vaddq_s32(a, b) }
    }
    #[inline(always)]
    fn mul_i(self, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { vmulq_s32(a, b) }
    }
    #[inline(always)]
    fn xor_i(self, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { veorq_s32(a, b) }
    }
    #[inline(always)]
    fn shr_i(self, a: int32x4_t, n: u32) -> int32x4_t {
        // A negative shift count shifts right; on the unsigned view it is logical.
        // SAFETY: NEON is available.
        unsafe {
            vreinterpretq_s32_u32(vshlq_u32(
                vreinterpretq_u32_s32(a),
                vdupq_n_s32(-(n as i32)),
            ))
        }
    }
    #[inline(always)]
    fn lt_i(self, a: int32x4_t, b: int32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vcltq_s32(a, b) }
    }
    #[inline(always)]
    fn gt_i(self, a: int32x4_t, b: int32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vcgtq_s32(a, b) }
    }
    #[inline(always)]
    fn mask_bits(self, m: uint32x4_t) -> float32x4_t {
        // SAFETY: NEON is available; a bit reinterpretation.
        unsafe { vreinterpretq_f32_u32(m) }
    }
    #[inline(always)]
    fn bits_mask(self, f: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available; a bit reinterpretation.
        unsafe { vreinterpretq_u32_f32(f) }
    }
    #[inline(always)]
    fn int_bits(self, i: int32x4_t) -> float32x4_t {
        // SAFETY: NEON is available; a bit reinterpretation.
        unsafe { vreinterpretq_f32_s32(i) }
    }
    #[inline(always)]
    fn bits_int(self, f: float32x4_t) -> int32x4_t {
        // SAFETY: NEON is available; a bit reinterpretation.
        unsafe { vreinterpretq_s32_f32(f) }
    }
}
