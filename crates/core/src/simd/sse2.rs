//! The SSE2 backend: 4 lanes of `__m128` (the x86_64 baseline). SSE2 lacks `roundps`,
//! `pmulld` and `blendvps`: floor, 32-bit multiply and select are built from SSE2 operations
//! with the same results.

use std::arch::x86_64::*;

use super::{Kernel, Lanes};
use crate::backend::Backend;

/// The SSE2 backend's token.
#[derive(Clone, Copy, Debug)]
pub struct Sse2(());

impl Sse2 {
    /// The token (SSE2 is part of x86_64, but it is still detected, like every backend).
    pub fn new() -> Option<Sse2> {
        Backend::Sse2.is_available().then_some(Sse2(()))
    }

    /// Runs `k` in a function compiled with SSE2 enabled (as all x86_64 code is).
    #[inline]
    pub fn call<K: Kernel>(self, k: K) -> K::Output {
        #[target_feature(enable = "sse2")]
        unsafe fn inner<K: Kernel>(l: Sse2, k: K) -> K::Output {
            k.run::<Sse2, { super::SIMD_BLOCK }>(l)
        }
        // SAFETY: an `Sse2` token exists only after runtime detection of SSE2.
        unsafe { inner(self, k) }
    }
}

impl Lanes for Sse2 {
    const WIDTH: usize = 4;
    type F = __m128;
    type M = __m128;
    type I = __m128i;

    #[inline(always)]
    fn splat(self, v: f32) -> __m128 {
        // SAFETY: SSE2 is available (the token exists).
        unsafe { _mm_set1_ps(v) }
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> __m128 {
        let s = &s[..4];
        // SAFETY: SSE2 is available; `s` holds 4 floats (checked above), unaligned load.
        unsafe { _mm_loadu_ps(s.as_ptr()) }
    }
    #[inline(always)]
    fn store(self, v: __m128, out: &mut [f32]) {
        let out = &mut out[..4];
        // SAFETY: SSE2 is available; `out` holds 4 floats (checked above), unaligned store.
        unsafe { _mm_storeu_ps(out.as_mut_ptr(), v) }
    }
    #[inline(always)]
    fn add(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_add_ps(a, b) }
    }
    #[inline(always)]
    fn sub(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_sub_ps(a, b) }
    }
    #[inline(always)]
    fn mul(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_mul_ps(a, b) }
    }
    #[inline(always)]
    fn div(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_div_ps(a, b) }
    }
    #[inline(always)]
    fn sqrt(self, a: __m128) -> __m128 {
        // SAFETY: SSE2 is available. `sqrtps` is correctly rounded.
        unsafe { _mm_sqrt_ps(a) }
    }
    #[inline(always)]
    fn neg(self, a: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_xor_ps(a, _mm_set1_ps(-0.0)) }
    }
    #[inline(always)]
    fn abs(self, a: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_andnot_ps(_mm_set1_ps(-0.0), a) }
    }
    #[inline(always)]
    fn floor(self, a: __m128) -> __m128 {
        // Truncate through i32 where |a| < 2^23 (beyond, every float is an integer or NaN
        // and stays as it is), step down where truncation rounded up, and put the sign
        // back so that -0.0 stays -0.0 (floor never changes the sign).
        // SAFETY: SSE2 is available.
        unsafe {
            let sign = _mm_set1_ps(-0.0);
            let small = _mm_cmplt_ps(_mm_andnot_ps(sign, a), _mm_set1_ps(8_388_608.0));
            let t = _mm_cvtepi32_ps(_mm_cvttps_epi32(a));
            let t = _mm_sub_ps(t, _mm_and_ps(_mm_cmpgt_ps(t, a), _mm_set1_ps(1.0)));
            let t = _mm_or_ps(t, _mm_and_ps(a, sign));
            self.select(small, t, a)
        }
    }
    #[inline(always)]
    fn min(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available. `minps a, b` is `a < b ? a : b`, the project's min.
        unsafe { _mm_min_ps(a, b) }
    }
    #[inline(always)]
    fn max(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available. `maxps a, b` is `a > b ? a : b`, the project's max.
        unsafe { _mm_max_ps(a, b) }
    }
    #[inline(always)]
    fn lt(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_cmplt_ps(a, b) }
    }
    #[inline(always)]
    fn gt(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_cmpgt_ps(a, b) }
    }
    #[inline(always)]
    fn le(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_cmple_ps(a, b) }
    }
    #[inline(always)]
    fn ge(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_cmpge_ps(a, b) }
    }
    #[inline(always)]
    fn not_nan(self, a: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_cmpord_ps(a, a) }
    }
    #[inline(always)]
    fn select(self, m: __m128, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available. Mask lanes are all ones or all zeros.
        unsafe { _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b)) }
    }
    #[inline(always)]
    fn select_i(self, m: __m128, a: __m128i, b: __m128i) -> __m128i {
        // SAFETY: SSE2 is available; the casts are bit reinterpretations.
        unsafe { _mm_castps_si128(self.select(m, _mm_castsi128_ps(a), _mm_castsi128_ps(b))) }
    }
    #[inline(always)]
    fn and(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_and_ps(a, b) }
    }
    #[inline(always)]
    fn or(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_or_ps(a, b) }
    }
    #[inline(always)]
    fn xor(self, a: __m128, b: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_xor_ps(a, b) }
    }
    #[inline(always)]
    fn not(self, a: __m128) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_xor_ps(a, _mm_castsi128_ps(_mm_set1_epi32(-1))) }
    }
    #[inline(always)]
    fn any(self, m: __m128) -> bool {
        // SAFETY: SSE2 is available.
        unsafe { _mm_movemask_ps(m) != 0 }
    }
    #[inline(always)]
    fn splat_i(self, v: i32) -> __m128i {
        // SAFETY: SSE2 is available.
        unsafe { _mm_set1_epi32(v) }
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> __m128i {
        let s = &s[..4];
        // SAFETY: SSE2 is available; `s` holds 4 integers (checked above), unaligned load.
        unsafe { _mm_loadu_si128(s.as_ptr().cast()) }
    }
    #[inline(always)]
    fn store_i(self, v: __m128i, out: &mut [i32]) {
        let out = &mut out[..4];
        // SAFETY: SSE2 is available; `out` holds 4 integers (checked above), unaligned store.
        unsafe { _mm_storeu_si128(out.as_mut_ptr().cast(), v) }
    }
    #[inline(always)]
    fn to_i32(self, v: __m128) -> __m128i {
        // SAFETY: SSE2 is available. `cvttps2dq` gives i32::MIN for NaN and out-of-range
        // lanes: NaN lanes are cleared and large positive lanes set to i32::MAX, which is
        // what Rust's saturating `as i32` gives.
        unsafe {
            let t = _mm_cvttps_epi32(v);
            let t = _mm_and_si128(t, _mm_castps_si128(self.not_nan(v)));
            let big = _mm_cmpge_ps(v, _mm_set1_ps(2_147_483_648.0));
            self.select_i(big, _mm_set1_epi32(i32::MAX), t)
        }
    }
    #[inline(always)]
    fn to_f32(self, v: __m128i) -> __m128 {
        // SAFETY: SSE2 is available. Rounds to nearest even (the default MXCSR mode).
        unsafe { _mm_cvtepi32_ps(v) }
    }
    #[inline(always)]
    fn add_i(self, a: __m128i, b: __m128i) -> __m128i {
        // SAFETY: SSE2 is available.
        unsafe { _mm_add_epi32(a, b) }
    }
    #[inline(always)]
    fn mul_i(self, a: __m128i, b: __m128i) -> __m128i {
        // The even and odd lanes' 64-bit products, whose low halves are shuffled together.
        // SAFETY: SSE2 is available.
        unsafe {
            let even = _mm_mul_epu32(a, b);
            let odd = _mm_mul_epu32(_mm_srli_epi64::<32>(a), _mm_srli_epi64::<32>(b));
            let even = _mm_shuffle_epi32::<0b00_00_10_00>(even);
            let odd = _mm_shuffle_epi32::<0b00_00_10_00>(odd);
            _mm_unpacklo_epi32(even, odd)
        }
    }
    #[inline(always)]
    fn xor_i(self, a: __m128i, b: __m128i) -> __m128i {
        // SAFETY: SSE2 is available.
        unsafe { _mm_xor_si128(a, b) }
    }
    #[inline(always)]
    fn shr_i(self, a: __m128i, n: u32) -> __m128i {
        // SAFETY: SSE2 is available.
        unsafe { _mm_srl_epi32(a, _mm_cvtsi32_si128(n as i32)) }
    }
    #[inline(always)]
    fn lt_i(self, a: __m128i, b: __m128i) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_castsi128_ps(_mm_cmpgt_epi32(b, a)) }
    }
    #[inline(always)]
    fn gt_i(self, a: __m128i, b: __m128i) -> __m128 {
        // SAFETY: SSE2 is available.
        unsafe { _mm_castsi128_ps(_mm_cmpgt_epi32(a, b)) }
    }
    #[inline(always)]
    fn mask_bits(self, m: __m128) -> __m128 {
        m
    }
    #[inline(always)]
    fn bits_mask(self, f: __m128) -> __m128 {
        f
    }
    #[inline(always)]
    fn int_bits(self, i: __m128i) -> __m128 {
        // SAFETY: SSE2 is available; a bit reinterpretation.
        unsafe { _mm_castsi128_ps(i) }
    }
    #[inline(always)]
    fn bits_int(self, f: __m128) -> __m128i {
        // SAFETY: SSE2 is available; a bit reinterpretation.
        unsafe { _mm_castps_si128(f) }
    }
}
