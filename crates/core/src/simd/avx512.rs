//! The AVX-512 backend: 16 lanes of `__m512` with `__mmask16` masks (x86_64 with AVX-512F,
//! detected at run time; FMA is never used).

use std::arch::x86_64::*;

use super::{Kernel, Lanes};
use crate::backend::Backend;

/// The AVX-512 backend's token; it exists only where the CPU has AVX-512F.
#[derive(Clone, Copy, Debug)]
pub struct Avx512(());

impl Avx512 {
    /// The token, if this CPU has AVX-512F.
    pub fn new() -> Option<Avx512> {
        Backend::Avx512.is_available().then_some(Avx512(()))
    }

    /// Runs `k` in a function compiled with AVX-512F enabled.
    #[inline]
    pub fn call<K: Kernel>(self, k: K) -> K::Output {
        #[target_feature(enable = "avx512f")]
        unsafe fn inner<K: Kernel>(l: Avx512, k: K) -> K::Output {
            k.run::<Avx512, { super::SIMD_BLOCK }>(l)
        }
        // SAFETY: an `Avx512` token exists only after runtime detection of AVX-512F.
        unsafe { inner(self, k) }
    }
}

impl Lanes for Avx512 {
    const WIDTH: usize = 16;
    type F = __m512;
    type M = __mmask16;
    type I = __m512i;

    #[inline(always)]
    fn splat(self, v: f32) -> __m512 {
        // SAFETY: AVX-512F is available (the token exists).
        unsafe { _mm512_set1_ps(v) }
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> __m512 {
        let s = &s[..16];
        // SAFETY: AVX-512F is available; `s` holds 16 floats (checked above).
        unsafe { _mm512_loadu_ps(s.as_ptr()) }
    }
    #[inline(always)]
    fn store(self, v: __m512, out: &mut [f32]) {
        let out = &mut out[..16];
        // SAFETY: AVX-512F is available; `out` holds 16 floats (checked above).
        unsafe { _mm512_storeu_ps(out.as_mut_ptr(), v) }
    }
    #[inline(always)]
    fn add(self, a: __m512, b: __m512) -> __m512 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_add_ps(a, b) }
    }
    #[inline(always)]
    fn sub(self, a: __m512, b: __m512) -> __m512 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_sub_ps(a, b) }
    }
    #[inline(always)]
    fn mul(self, a: __m512, b: __m512) -> __m512 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_mul_ps(a, b) }
    }
    #[inline(always)]
    fn div(self, a: __m512, b: __m512) -> __m512 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_div_ps(a, b) }
    }
    #[inline(always)]
    fn sqrt(self, a: __m512) -> __m512 {
        // SAFETY: AVX-512F is available. `vsqrtps` is correctly rounded.
        unsafe { _mm512_sqrt_ps(a) }
    }
    #[inline(always)]
    fn neg(self, a: __m512) -> __m512 {
        // SAFETY: AVX-512F is available; xor of the sign bit on the integer view.
        unsafe {
            _mm512_castsi512_ps(_mm512_xor_si512(
                _mm512_castps_si512(a),
                _mm512_set1_epi32(i32::MIN),
            ))
        }
    }
    #[inline(always)]
    fn abs(self, a: __m512) -> __m512 {
        // SAFETY: AVX-512F is available; clears the sign bit on the integer view.
        unsafe {
            _mm512_castsi512_ps(_mm512_and_si512(
                _mm512_castps_si512(a),
                _mm512_set1_epi32(i32::MAX),
            ))
        }
    }
    #[inline(always)]
    fn floor(self, a: __m512) -> __m512 {
        // SAFETY: AVX-512F is available. `vrndscaleps` with scale 0 rounding down keeps
        // the sign of zero and NaN.
        unsafe { _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(a) }
    }
    #[inline(always)]
    fn min(self, a: __m512, b: __m512) -> __m512 {
        // SAFETY: AVX-512F is available. `vminps a, b` is `a < b ? a : b`.
        unsafe { _mm512_min_ps(a, b) }
    }
    #[inline(always)]
    fn max(self, a: __m512, b: __m512) -> __m512 {
        // SAFETY: AVX-512F is available. `vmaxps a, b` is `a > b ? a : b`.
        unsafe { _mm512_max_ps(a, b) }
    }
    #[inline(always)]
    fn lt(self, a: __m512, b: __m512) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OQ>(a, b) }
    }
    #[inline(always)]
    fn gt(self, a: __m512, b: __m512) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmp_ps_mask::<_CMP_GT_OQ>(a, b) }
    }
    #[inline(always)]
    fn le(self, a: __m512, b: __m512) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OQ>(a, b) }
    }
    #[inline(always)]
    fn ge(self, a: __m512, b: __m512) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmp_ps_mask::<_CMP_GE_OQ>(a, b) }
    }
    #[inline(always)]
    fn not_nan(self, a: __m512) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmp_ps_mask::<_CMP_ORD_Q>(a, a) }
    }
    #[inline(always)]
    fn select(self, m: __mmask16, a: __m512, b: __m512) -> __m512 {
        // SAFETY: AVX-512F is available. Takes `a` where the mask bit is set.
        unsafe { _mm512_mask_blend_ps(m, b, a) }
    }
    #[inline(always)]
    fn select_i(self, m: __mmask16, a: __m512i, b: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_mask_blend_epi32(m, b, a) }
    }
    #[inline(always)]
    fn and(self, a: __mmask16, b: __mmask16) -> __mmask16 {
        a & b
    }
    #[inline(always)]
    fn or(self, a: __mmask16, b: __mmask16) -> __mmask16 {
        a | b
    }
    #[inline(always)]
    fn xor(self, a: __mmask16, b: __mmask16) -> __mmask16 {
        a ^ b
    }
    #[inline(always)]
    fn not(self, a: __mmask16) -> __mmask16 {
        !a
    }
    #[inline(always)]
    fn any(self, m: __mmask16) -> bool {
        m != 0
    }
    #[inline(always)]
    fn splat_i(self, v: i32) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_set1_epi32(v) }
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> __m512i {
        let s = &s[..16];
        // SAFETY: AVX-512F is available; `s` holds 16 integers (checked above).
        unsafe { _mm512_loadu_si512(s.as_ptr().cast()) }
    }
    #[inline(always)]
    fn store_i(self, v: __m512i, out: &mut [i32]) {
        let out = &mut out[..16];
        // SAFETY: AVX-512F is available; `out` holds 16 integers (checked above).
        unsafe { _mm512_storeu_si512(out.as_mut_ptr().cast(), v) }
    }
    #[inline(always)]
    fn to_i32(self, v: __m512) -> __m512i {
        // SAFETY: AVX-512F is available. `vcvttps2dq` gives i32::MIN for NaN and
        // out-of-range lanes: NaN lanes become 0 and large positive lanes i32::MAX, as
        // Rust's saturating `as i32` gives.
        unsafe {
            let t = _mm512_cvttps_epi32(v);
            let t = _mm512_maskz_mov_epi32(self.not_nan(v), t);
            let big = _mm512_cmp_ps_mask::<_CMP_GE_OQ>(v, _mm512_set1_ps(2_147_483_648.0));
            _mm512_mask_blend_epi32(big, t, _mm512_set1_epi32(i32::MAX))
        }
    }
    #[inline(always)]
    fn to_f32(self, v: __m512i) -> __m512 {
        // SAFETY: AVX-512F is available. Rounds to nearest even (the MXCSR default).
        unsafe { _mm512_cvtepi32_ps(v) }
    }
    #[inline(always)]
    fn add_i(self, a: __m512i, b: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_add_epi32(a, b) }
    }
    #[inline(always)]
    fn mul_i(self, a: __m512i, b: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_mullo_epi32(a, b) }
    }
    #[inline(always)]
    fn xor_i(self, a: __m512i, b: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_xor_si512(a, b) }
    }
    #[inline(always)]
    fn shr_i(self, a: __m512i, n: u32) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_srl_epi32(a, _mm_cvtsi32_si128(n as i32)) }
    }
    #[inline(always)]
    fn lt_i(self, a: __m512i, b: __m512i) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmplt_epi32_mask(a, b) }
    }
    #[inline(always)]
    fn gt_i(self, a: __m512i, b: __m512i) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmpgt_epi32_mask(a, b) }
    }
    #[inline(always)]
    fn mask_bits(self, m: __mmask16) -> __m512 {
        // SAFETY: AVX-512F is available; all ones where the mask bit is set.
        unsafe { _mm512_castsi512_ps(_mm512_maskz_mov_epi32(m, _mm512_set1_epi32(-1))) }
    }
    #[inline(always)]
    fn bits_mask(self, f: __m512) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_test_epi32_mask(_mm512_castps_si512(f), _mm512_castps_si512(f)) }
    }
    #[inline(always)]
    fn int_bits(self, i: __m512i) -> __m512 {
        // SAFETY: AVX-512F is available; a bit reinterpretation.
        unsafe { _mm512_castsi512_ps(i) }
    }
    #[inline(always)]
    fn bits_int(self, f: __m512) -> __m512i {
        // SAFETY: AVX-512F is available; a bit reinterpretation.
        unsafe { _mm512_castps_si512(f) }
    }
}
