//! The tracer's lanes on AVX-512F (x86_64, detected at run time): what [`Pack`] adds to the
//! exact lanes of `craterfield-core`'s [`Avx512`] token, 16 lanes with `__mmask16` masks.
//! AVX-512F has fused multiply-add on 512-bit registers, so no other feature is needed.

use std::arch::x86_64::*;

use craterfield_core::simd::Avx512;

use super::{Pack, PackKernel};

impl Pack for Avx512 {
    const STREAM_PAIRS: bool = true;

    #[inline]
    fn call<K: PackKernel>(self, k: K) -> K::Output {
        // Out of line: a kernel is compiled once per call type, not into each caller.
        #[inline(never)]
        #[target_feature(enable = "avx512f")]
        unsafe fn inner<K: PackKernel>(p: Avx512, k: K) -> K::Output {
            k.run(p)
        }
        // SAFETY: an `Avx512` token exists only after runtime detection of AVX-512F.
        unsafe { inner(self, k) }
    }
    #[inline(always)]
    fn fma(self, a: __m512, b: __m512, c: __m512) -> __m512 {
        // SAFETY: AVX-512F is available (the token exists); it includes 512-bit FMA.
        unsafe { _mm512_fmadd_ps(a, b, c) }
    }
    #[inline(always)]
    fn fnma(self, a: __m512, b: __m512, c: __m512) -> __m512 {
        // SAFETY: AVX-512F is available. `vfnmadd` is `-(a * b) + c`.
        unsafe { _mm512_fnmadd_ps(a, b, c) }
    }
    #[inline(always)]
    fn rsqrt(self, a: __m512) -> __m512 {
        // SAFETY: AVX-512F is available; `vrsqrt14ps` is AVX-512F. Its estimate is within
        // 2^-14; one Newton step `y (3/2 - a/2 y^2)` squares that error.
        unsafe {
            let y = _mm512_rsqrt14_ps(a);
            let half_a_y = _mm512_mul_ps(_mm512_mul_ps(a, _mm512_set1_ps(0.5)), y);
            _mm512_mul_ps(y, _mm512_fnmadd_ps(half_a_y, y, _mm512_set1_ps(1.5)))
        }
    }
    #[inline(always)]
    fn round(self, a: __m512) -> __m512 {
        // SAFETY: AVX-512F is available. Nearest with ties to even, whatever MXCSR says.
        unsafe { _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(a) }
    }
    #[inline(always)]
    fn and_not(self, a: __mmask16, b: __mmask16) -> __mmask16 {
        a & !b
    }
    #[inline(always)]
    fn none(self) -> __mmask16 {
        0
    }
    #[inline(always)]
    fn all_set(self) -> __mmask16 {
        0xffff
    }
    #[inline(always)]
    fn bitmask(self, m: __mmask16) -> u32 {
        m as u32
    }
    #[inline(always)]
    fn eq_i(self, a: __m512i, b: __m512i) -> __mmask16 {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_cmpeq_epi32_mask(a, b) }
    }
    #[inline(always)]
    fn round_i(self, v: __m512) -> __m512i {
        // SAFETY: AVX-512F is available. Rounds to nearest even under the default MXCSR
        // mode, which Rust code never changes.
        unsafe { _mm512_cvtps_epi32(v) }
    }
    #[inline(always)]
    fn sub_i(self, a: __m512i, b: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_sub_epi32(a, b) }
    }
    #[inline(always)]
    fn and_i(self, a: __m512i, b: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_and_si512(a, b) }
    }
    #[inline(always)]
    fn or_i(self, a: __m512i, b: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available.
        unsafe { _mm512_or_si512(a, b) }
    }
    #[inline(always)]
    fn shl_n<const N: i32>(self, a: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available. A per-lane shift by the same count (the immediate
        // form takes an unsigned constant, which `N` cannot be turned into here).
        unsafe { _mm512_sllv_epi32(a, _mm512_set1_epi32(N)) }
    }
    #[inline(always)]
    fn shr_n<const N: i32>(self, a: __m512i) -> __m512i {
        // SAFETY: AVX-512F is available. A logical shift, as `shl_n`.
        unsafe { _mm512_srlv_epi32(a, _mm512_set1_epi32(N)) }
    }
}
