//! The AVX2 backend: 8 lanes of `__m256` (x86_64, detected at run time; FMA is never used).

use std::arch::x86_64::*;

use super::{Kernel, Lanes};
use crate::backend::Backend;

/// The AVX2 backend's token; it exists only where the CPU has AVX2.
#[derive(Clone, Copy, Debug)]
pub struct Avx2(());

impl Avx2 {
    /// The token, if this CPU has AVX2 (and FMA3, which this backend leaves unused: see
    /// `crate::backend`).
    pub fn new() -> Option<Avx2> {
        Backend::Avx2.is_available().then_some(Avx2(()))
    }

    /// Runs `k` in a function compiled with AVX2 enabled.
    #[inline]
    pub fn call<K: Kernel>(self, k: K) -> K::Output {
        #[target_feature(enable = "avx2")]
        unsafe fn inner<K: Kernel>(l: Avx2, k: K) -> K::Output {
            k.run::<Avx2, { super::SIMD_BLOCK }>(l)
        }
        // SAFETY: an `Avx2` token exists only after runtime detection of AVX2.
        unsafe { inner(self, k) }
    }
}

impl Lanes for Avx2 {
    const WIDTH: usize = 8;
    type F = __m256;
    type M = __m256;
    type I = __m256i;

    #[inline(always)]
    fn splat(self, v: f32) -> __m256 {
        // SAFETY: AVX is available (the token exists).
        unsafe { _mm256_set1_ps(v) }
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> __m256 {
        let s = &s[..8];
        // SAFETY: AVX is available; `s` holds 8 floats (checked above), unaligned load.
        unsafe { _mm256_loadu_ps(s.as_ptr()) }
    }
    #[inline(always)]
    fn store(self, v: __m256, out: &mut [f32]) {
        let out = &mut out[..8];
        // SAFETY: AVX is available; `out` holds 8 floats (checked above), unaligned store.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), v) }
    }
    #[inline(always)]
    fn add(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_add_ps(a, b) }
    }
    #[inline(always)]
    fn sub(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_sub_ps(a, b) }
    }
    #[inline(always)]
    fn mul(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_mul_ps(a, b) }
    }
    #[inline(always)]
    fn div(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_div_ps(a, b) }
    }
    #[inline(always)]
    fn sqrt(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available. `vsqrtps` is correctly rounded.
        unsafe { _mm256_sqrt_ps(a) }
    }
    #[inline(always)]
    fn neg(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_xor_ps(a, _mm256_set1_ps(-0.0)) }
    }
    #[inline(always)]
    fn abs(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), a) }
    }
    #[inline(always)]
    fn floor(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available. `vroundps` keeps the sign of zero and NaN.
        unsafe { _mm256_round_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(a) }
    }
    #[inline(always)]
    fn min(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. `vminps a, b` is `a < b ? a : b`, the project's min.
        unsafe { _mm256_min_ps(a, b) }
    }
    #[inline(always)]
    fn max(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. `vmaxps a, b` is `a > b ? a : b`, the project's max.
        unsafe { _mm256_max_ps(a, b) }
    }
    #[inline(always)]
    fn lt(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(a, b) }
    }
    #[inline(always)]
    fn gt(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_cmp_ps::<_CMP_GT_OQ>(a, b) }
    }
    #[inline(always)]
    fn le(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(a, b) }
    }
    #[inline(always)]
    fn ge(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_cmp_ps::<_CMP_GE_OQ>(a, b) }
    }
    #[inline(always)]
    fn not_nan(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_cmp_ps::<_CMP_ORD_Q>(a, a) }
    }
    #[inline(always)]
    fn select(self, m: __m256, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. Mask lanes are all ones or all zeros.
        unsafe { _mm256_blendv_ps(b, a, m) }
    }
    #[inline(always)]
    fn select_i(self, m: __m256, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: AVX is available; the casts are bit reinterpretations.
        unsafe {
            _mm256_castps_si256(_mm256_blendv_ps(
                _mm256_castsi256_ps(b),
                _mm256_castsi256_ps(a),
                m,
            ))
        }
    }
    #[inline(always)]
    fn and(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_and_ps(a, b) }
    }
    #[inline(always)]
    fn or(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_or_ps(a, b) }
    }
    #[inline(always)]
    fn xor(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_xor_ps(a, b) }
    }
    #[inline(always)]
    fn not(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_xor_ps(a, _mm256_castsi256_ps(_mm256_set1_epi32(-1))) }
    }
    #[inline(always)]
    fn any(self, m: __m256) -> bool {
        // SAFETY: AVX is available.
        unsafe { _mm256_movemask_ps(m) != 0 }
    }
    #[inline(always)]
    fn splat_i(self, v: i32) -> __m256i {
        // SAFETY: AVX is available.
        unsafe { _mm256_set1_epi32(v) }
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> __m256i {
        let s = &s[..8];
        // SAFETY: AVX is available; `s` holds 8 integers (checked above), unaligned load.
        unsafe { _mm256_loadu_si256(s.as_ptr().cast()) }
    }
    #[inline(always)]
    fn store_i(self, v: __m256i, out: &mut [i32]) {
        let out = &mut out[..8];
        // SAFETY: AVX is available; `out` holds 8 integers (checked above), unaligned store.
        unsafe { _mm256_storeu_si256(out.as_mut_ptr().cast(), v) }
    }
    #[inline(always)]
    fn to_i32(self, v: __m256) -> __m256i {
        // SAFETY: AVX2 is available. `vcvttps2dq` gives i32::MIN for NaN and out-of-range
        // lanes: NaN lanes are cleared and large positive lanes set to i32::MAX, which is
        // what Rust's saturating `as i32` gives.
        unsafe {
            let t = _mm256_cvttps_epi32(v);
            let t = _mm256_and_si256(t, _mm256_castps_si256(self.not_nan(v)));
            let big = _mm256_cmp_ps::<_CMP_GE_OQ>(v, _mm256_set1_ps(2_147_483_648.0));
            self.select_i(big, _mm256_set1_epi32(i32::MAX), t)
        }
    }
    #[inline(always)]
    fn to_f32(self, v: __m256i) -> __m256 {
        // SAFETY: AVX is available. Rounds to nearest even (the default MXCSR mode).
        unsafe { _mm256_cvtepi32_ps(v) }
    }
    #[inline(always)]
    fn add_i(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_add_epi32(a, b) }
    }
    #[inline(always)]
    fn mul_i(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_mullo_epi32(a, b) }
    }
    #[inline(always)]
    fn xor_i(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_xor_si256(a, b) }
    }
    #[inline(always)]
    fn shr_i(self, a: __m256i, n: u32) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_srl_epi32(a, _mm_cvtsi32_si128(n as i32)) }
    }
    #[inline(always)]
    fn lt_i(self, a: __m256i, b: __m256i) -> __m256 {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_castsi256_ps(_mm256_cmpgt_epi32(b, a)) }
    }
    #[inline(always)]
    fn gt_i(self, a: __m256i, b: __m256i) -> __m256 {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_castsi256_ps(_mm256_cmpgt_epi32(a, b)) }
    }
    #[inline(always)]
    fn mask_bits(self, m: __m256) -> __m256 {
        m
    }
    #[inline(always)]
    fn bits_mask(self, f: __m256) -> __m256 {
        f
    }
    #[inline(always)]
    fn int_bits(self, i: __m256i) -> __m256 {
        // SAFETY: AVX is available; a bit reinterpretation.
        unsafe { _mm256_castsi256_ps(i) }
    }
    #[inline(always)]
    fn bits_int(self, f: __m256) -> __m256i {
        // SAFETY: AVX is available; a bit reinterpretation.
        unsafe { _mm256_castps_si256(f) }
    }
}
