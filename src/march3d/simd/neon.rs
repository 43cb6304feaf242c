//! The NEON backend of the tracer: 4 lanes of `float32x4_t` with fused multiply-add
//! (aarch64 Advanced SIMD). NEON's `fmin`/`fmax` propagate NaN, unlike the trait's x86 rule,
//! so min and max are compare + select here.

use std::arch::aarch64::*;

use super::{Pack, PackKernel};
use crate::backend::Backend;

/// The NEON backend's token; it exists only where the CPU has Advanced SIMD.
#[derive(Clone, Copy, Debug)]
pub struct Neon(());

impl Neon {
    /// The token, if this CPU has NEON (every aarch64 Linux CPU does; still detected).
    pub fn new() -> Option<Neon> {
        Backend::Neon.is_available().then_some(Neon(()))
    }
}

impl Pack for Neon {
    const WIDTH: usize = 4;
    type F = float32x4_t;
    type M = uint32x4_t;
    type I = int32x4_t;

    #[inline]
    fn call<K: PackKernel>(self, k: K) -> K::Output {
        // Out of line: a kernel is compiled once per call type, not into each caller.
        #[inline(never)]
        #[target_feature(enable = "neon")]
        unsafe fn inner<K: PackKernel>(p: Neon, k: K) -> K::Output {
            k.run(p)
        }
        // SAFETY: a `Neon` token exists only after runtime detection of NEON.
        unsafe { inner(self, k) }
    }

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
        // SAFETY: NEON is available.
        unsafe { vdivq_f32(a, b) }
    }
    #[inline(always)]
    fn fma(self, a: float32x4_t, b: float32x4_t, c: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `fmla` is the fused `c + a * b`.
        unsafe { vfmaq_f32(c, a, b) }
    }
    #[inline(always)]
    fn fnma(self, a: float32x4_t, b: float32x4_t, c: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `fmls` is the fused `c - a * b`.
        unsafe { vfmsq_f32(c, a, b) }
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
    fn round(self, a: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `frintn` rounds to nearest, ties to even.
        unsafe { vrndnq_f32(a) }
    }
    #[inline(always)]
    fn min(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        // NEON's `fmin` propagates NaN; the trait's min returns `b` then, as x86 does.
        self.select(self.lt(a, b), a, b)
    }
    #[inline(always)]
    fn max(self, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        self.select(self.gt(a, b), a, b)
    }
    #[inline(always)]
    fn lt(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available. False on NaN.
        unsafe { vcltq_f32(a, b) }
    }
    #[inline(always)]
    fn le(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available. False on NaN.
        unsafe { vcleq_f32(a, b) }
    }
    #[inline(always)]
    fn gt(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available. False on NaN.
        unsafe { vcgtq_f32(a, b) }
    }
    #[inline(always)]
    fn ge(self, a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available. False on NaN.
        unsafe { vcgeq_f32(a, b) }
    }
    #[inline(always)]
    fn select(self, m: uint32x4_t, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. Mask lanes are all ones or all zeros.
        unsafe { vbslq_f32(m, a, b) }
    }
    #[inline(always)]
    fn select_i(self, m: uint32x4_t, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available. Mask lanes are all ones or all zeros.
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
    fn and_not(self, a: uint32x4_t, b: uint32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available. `bic` is `a & !b`.
        unsafe { vbicq_u32(a, b) }
    }
    #[inline(always)]
    fn not(self, a: uint32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vmvnq_u32(a) }
    }
    #[inline(always)]
    fn none(self) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vdupq_n_u32(0) }
    }
    #[inline(always)]
    fn all_set(self) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vdupq_n_u32(u32::MAX) }
    }
    #[inline(always)]
    fn bitmask(self, m: uint32x4_t) -> u32 {
        const LANE: [i32; 4] = [0, 1, 2, 3];
        // SAFETY: NEON is available; `LANE` holds 4 integers. Each lane's top bit moves to
        // bit `lane` and the horizontal add packs them (the x86 `movemask` rule).
        unsafe { vaddvq_u32(vshlq_u32(vshrq_n_u32::<31>(m), vld1q_s32(LANE.as_ptr()))) }
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
    fn eq_i(self, a: int32x4_t, b: int32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available.
        unsafe { vceqq_s32(a, b) }
    }
    #[inline(always)]
    fn round_i(self, v: float32x4_t) -> int32x4_t {
        // SAFETY: NEON is available. `fcvtns` rounds to nearest, ties to even.
        unsafe { vcvtnq_s32_f32(v) }
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
    fn sub_i(self, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { vsubq_s32(a, b) }
    }
    #[inline(always)]
    fn and_i(self, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { vandq_s32(a, b) }
    }
    #[inline(always)]
    fn or_i(self, a: int32x4_t, b: int32x4_t) -> int32x4_t {
        // SAFETY: NEON is available.
        unsafe { vorrq_s32(a, b) }
    }
    #[inline(always)]
    fn shl_i<const N: i32>(self, a: int32x4_t) -> int32x4_t {
        // By register, not immediate: the immediate forms reject some shifts in 0..32.
        // SAFETY: NEON is available.
        unsafe { vshlq_s32(a, vdupq_n_s32(N)) }
    }
    #[inline(always)]
    fn shr_i<const N: i32>(self, a: int32x4_t) -> int32x4_t {
        // A negative count shifts right; on the unsigned view the shift is logical.
        // SAFETY: NEON is available; the casts are bit reinterpretations.
        unsafe { vreinterpretq_s32_u32(vshlq_u32(vreinterpretq_u32_s32(a), vdupq_n_s32(-N))) }
    }
    #[inline(always)]
    fn bits(self, a: float32x4_t) -> int32x4_t {
        // SAFETY: NEON is available; a bit reinterpretation.
        unsafe { vreinterpretq_s32_f32(a) }
    }
    #[inline(always)]
    fn from_bits(self, a: int32x4_t) -> float32x4_t {
        // SAFETY: NEON is available; a bit reinterpretation.
        unsafe { vreinterpretq_f32_s32(a) }
    }
}
