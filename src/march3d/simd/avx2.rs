//! The AVX2 backend of the tracer: 8 lanes of `__m256`, with fused multiply-add (x86_64,
//! AVX2 and FMA detected at run time).

use std::arch::x86_64::*;

use super::{Pack, PackKernel};
use crate::backend::Backend;

/// The AVX2+FMA backend's token; it exists only where the CPU has both.
#[derive(Clone, Copy, Debug)]
pub(super) struct Avx2(());

impl Avx2 {
    /// The token, if this CPU has AVX2 and FMA. `Backend::Avx2` is available only where
    /// both are (see `crate::backend`), which the `fma` target feature of `call` needs.
    pub(super) fn new() -> Option<Avx2> {
        Backend::Avx2.is_available().then_some(Avx2(()))
    }
}

impl Pack for Avx2 {
    const WIDTH: usize = 8;
    type F = __m256;
    type M = __m256;
    type I = __m256i;

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
    fn round(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available. Nearest with ties to even, whatever MXCSR says.
        unsafe { _mm256_round_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(a) }
    }
    #[inline(always)]
    fn min(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. `vminps a, b` is `a < b ? a : b`, the trait's min.
        unsafe { _mm256_min_ps(a, b) }
    }
    #[inline(always)]
    fn max(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. `vmaxps a, b` is `a > b ? a : b`, the trait's max.
        unsafe { _mm256_max_ps(a, b) }
    }
    #[inline(always)]
    fn lt(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. Ordered, quiet: false on NaN.
        unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(a, b) }
    }
    #[inline(always)]
    fn le(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. Ordered, quiet: false on NaN.
        unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(a, b) }
    }
    #[inline(always)]
    fn gt(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. Ordered, quiet: false on NaN.
        unsafe { _mm256_cmp_ps::<_CMP_GT_OQ>(a, b) }
    }
    #[inline(always)]
    fn ge(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. Ordered, quiet: false on NaN.
        unsafe { _mm256_cmp_ps::<_CMP_GE_OQ>(a, b) }
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
    fn and_not(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: AVX is available. `vandnps b, a` is `!b & a`.
        unsafe { _mm256_andnot_ps(b, a) }
    }
    #[inline(always)]
    fn not(self, a: __m256) -> __m256 {
        // SAFETY: AVX is available.
        unsafe { _mm256_xor_ps(a, _mm256_castsi256_ps(_mm256_set1_epi32(-1))) }
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
    fn shl_i<const N: i32>(self, a: __m256i) -> __m256i {
        // SAFETY: AVX2 is available.
        unsafe { _mm256_slli_epi32::<N>(a) }
    }
    #[inline(always)]
    fn shr_i<const N: i32>(self, a: __m256i) -> __m256i {
        // SAFETY: AVX2 is available. A logical shift.
        unsafe { _mm256_srli_epi32::<N>(a) }
    }
    #[inline(always)]
    fn bits(self, a: __m256) -> __m256i {
        // SAFETY: AVX is available; a bit reinterpretation.
        unsafe { _mm256_castps_si256(a) }
    }
    #[inline(always)]
    fn from_bits(self, a: __m256i) -> __m256 {
        // SAFETY: AVX is available; a bit reinterpretation.
        unsafe { _mm256_castsi256_ps(a) }
    }
}
