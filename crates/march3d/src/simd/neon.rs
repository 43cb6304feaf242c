//! The tracer's lanes on NEON with fused multiply-add (aarch64 Advanced SIMD): what [`Pack`]
//! adds to the exact lanes of `craterfield-core`'s [`Neon`] token.

use std::arch::aarch64::*;

use craterfield_core::simd::Neon;

use super::{Pack, PackKernel};

impl Pack for Neon {
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
    fn rsqrt(self, a: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `frsqrte` gives 8 bits; each `frsqrts` step (`(3 - a
        // y^2) / 2`) doubles them.
        unsafe {
            let mut y = vrsqrteq_f32(a);
            y = vmulq_f32(y, vrsqrtsq_f32(vmulq_f32(a, y), y));
            vmulq_f32(y, vrsqrtsq_f32(vmulq_f32(a, y), y))
        }
    }
    #[inline(always)]
    fn round(self, a: float32x4_t) -> float32x4_t {
        // SAFETY: NEON is available. `frintn` rounds to nearest, ties to even.
        unsafe { vrndnq_f32(a) }
    }
    #[inline(always)]
    fn and_not(self, a: uint32x4_t, b: uint32x4_t) -> uint32x4_t {
        // SAFETY: NEON is available. `bic` is `a & !b`.
        unsafe { vbicq_u32(a, b) }
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
    fn shl_n<const N: i32>(self, a: int32x4_t) -> int32x4_t {
        // By register, not immediate: the immediate forms reject some shifts in 0..32.
        // SAFETY: NEON is available.
        unsafe { vshlq_s32(a, vdupq_n_s32(N)) }
    }
    #[inline(always)]
    fn shr_n<const N: i32>(self, a: int32x4_t) -> int32x4_t {
        // A negative count shifts right; on the unsigned view the shift is logical.
        // SAFETY: NEON is available; the casts are bit reinterpretations.
        unsafe { vreinterpretq_s32_u32(vshlq_u32(vreinterpretq_u32_s32(a), vdupq_n_s32(-N))) }
    }
}
