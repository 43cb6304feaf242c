//! The tracer's lanes on AVX2 with fused multiply-add (x86_64, detected at run time): what
//! [`Pack`] adds to the exact lanes of `craterfield-core`'s [`Avx2`] token. The token exists
//! only where the CPU has AVX2 and FMA (see `craterfield_core::backend`).

use std::arch::x86_64::*;

use craterfield_core::simd::Avx2;

use super::{Pack, PackKernel};

impl Pack for Avx2 {
    const STREAM_PAIRS: bool = true;

    #[inline]
    fn call<K: PackKernel>(self, k: K) -> K::Output {
        // Out of line: a kernel is compiled once per call type, not into each caller.
        #[inline(never)]
        #[target_feature(enable = "avx2,fma")]
        unsafe fn inner<K: PackKernel>(p: Avx2, k: K) -> K::Output {
            k.run(p)
        }
        // SAFETY: an `Avx2` token exists only after runtime detection of AVX2 and FMA.
        unsafe { inner(self, k) }
    }
    #[inline(always)]
    fn fma(self, a: __m256, b: __m256, c: __m256) -> __m256 {
        // SAFETY: FMA is available (detected with AVX2 before the token exists).
        unsafe { _mm256_fmadd_ps(a, b, c) }
    }
    #[inline(always)]
    fn fnma(self, a: __m256, b: __m256, c: __m256) -> __m256 {
        // SAFETY: FMA is available (detected with AVX2 before the token exists). `vfnmadd` is `-(a * b) + c`.
        unsafe { _mm256_fnmadd_ps(a, b, c) }
    }
    #[inline(always)]
    fn rsqrt(self, a: __m256) -> __m256 {
        // SAFETY: AVX and FMA are available (the token exists). `vrsqrtps` is within
        // 1.5 * 2^-12; one Newton step `y (3/2 - a/2 y^2)` squares that error.
        unsafe {
            let y = _mm256_rsqrt_ps(a);
            let half_a_y = _mm256_mul_ps(_mm256_mul_ps(a, _mm256_set1_ps(0.5)), y);
            _mm256_mul_ps(y, _mm256_fnmadd_ps(half_a_y, y, _mm256_set1_ps(1.5)))
        }
    }
    #[inline(always)]
    fn round(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available. Nearest with ties to even, whatever MXCSR says.
        unsafe { _mm256_round_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(a) }
    }
    #[inline(always)]
    fn and_not(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. `vandnps b, a` is `!b & a`.
        unsafe { _mm256_andnot_ps(b, a) }
    }
    #[inline(always)]
    fn none(self) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_setzero_ps() }
    }
    #[inline(always)]
    fn all_set(self) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_castsi256_ps(_mm256_set1_epi32(-1)) }
    }
    #[inline(always)]
    fn bitmask(self, m: __m256) -> u32 {
        // SAFETY: AVX is available. Takes each lane's sign bit, set in true mask lanes.
        unsafe { _mm256_movemask_ps(m) as u32 }
    }
    #[inline(always)]
    fn eq_i(self, a: __m256i, b: __m256i) -> __m256 {
        // SAFETY: AVX2 is available; the cast is a bit reinterpretation.
        unsafe { _mm256_castsi256_ps(_mm256_cmpeq_epi32(a, b)) }
    }
    #[inline(always)]
    fn round_i(self, v: __m256) -> __m256i {
        // SAFETY: AVX is available. Rounds to nearest even under the default MXCSR mode, which Rust code never changes.
        unsafe { _mm256_cvtps_epi32(v) }
    }
    #[inline(always)]
    fn sub_i(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_sub_epi32(a, b) }
    }
    #[inline(always)]
    fn and_i(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_and_si256(a, b) }
    }
    #[inline(always)]
    fn or_i(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_or_si256(a, b) }
    }
    #[inline(always)]
    fn shl_n<const N: i32>(self, a: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_slli_epi32::<N>(a) }
    }
    #[inline(always)]
    fn shr_n<const N: i32>(self, a: __m256i) -> __m256i {
        // SAFETY: AVX2 is available. A logical shift.
        unsafe { _mm256_srli_epi32::<N>(a) }
    }
}
