//! The CPU sphere tracer's lanes: [`Pack`], the fused multiply-add extension of
//! `craterfield-core`'s exact lanes, one file per instruction set, and the one place that
//! chooses among them.
//!
//! Unlike the 2D field, which must give the same bits everywhere, rendering is not on the
//! determinism contract: these lanes may fuse multiply-adds and use polynomial approximations
//! of `sin`, `cos`, `exp` and `log` (in [`super::math`], written once over this trait). A
//! backend is one of `craterfield-core`'s token types (which exist only after runtime
//! detection, what makes the intrinsics sound) implementing [`Pack`]; the tracer is generic
//! over it and instantiated per backend inside a function compiled with the backend's
//! instruction set (`Pack::call`). `unsafe` lives only in the per-architecture files.
//!
//! Choosing: [`best`] picks AVX-512F (16 lanes) or AVX2+FMA (8 lanes) on x86_64, NEON (4
//! lanes) on aarch64, else the scalar path. Detection, the environment variable `CRATERFIELD_BACKEND` that caps the
//! choice, and the errors are the field's too ([`craterfield_core::backend`]); the
//! `force-scalar` feature compiles only the scalar path.

use craterfield_core::backend::{Backend, BackendError};
pub use craterfield_core::simd::{Lanes, Scalar};

pub(crate) use pair::Pair;

pub(crate) mod count;
mod pair;
mod scalar;
#[cfg(test)]
mod tests;

#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
mod avx2;
#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
mod avx512;
#[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
mod neon;

/// Work generic over a [`Pack`], run by [`Pack::call`] inside a function compiled for the
/// backend's instruction set (so that every `#[inline(always)]` lane operation inlines).
///
/// Only code inlined into that function gets the instruction set: mark `run`, every generic
/// helper it calls, and closures passed to [`Pack::as_one_op`] `#[inline(always)]`. A
/// function left out of line is compiled for the baseline CPU, and each lane operation in
/// it becomes a call (measured: a polynomial `exp` over AVX2 lanes took 16 ns per value
/// instead of 0.35).
pub trait PackKernel {
    /// What the work returns.
    type Output;
    /// Does the work on backend `p`.
    fn run<P: Pack>(self, p: P) -> Self::Output;
}

/// What the tracer adds to the exact lanes of [`Lanes`] (whose operations, shared with the
/// field, are exactly rounded: `min`/`max` return the second operand when either is NaN,
/// comparisons are ordered): fused multiply-adds, rounding, and the mask and integer
/// operations its math library needs.
///
/// `fma` may be fused or not (backends without FMA multiply then add). This trait and its
/// implementations live in this crate alone, so the deterministic field, which depends on
/// `craterfield-core` and not on this crate, cannot name a fused lane.
pub trait Pack: Lanes {
    /// Whether the ray streams march two of this backend's registers per step (a `Pair`)
    /// in scenes whose distance is a long chain of dependent operations (the Mandelbulb's),
    /// where the operations' latency, not their throughput, bounds a march: true on the
    /// x86_64 vector backends, where it was measured.
    const STREAM_PAIRS: bool = false;
    /// Runs `k` compiled for this backend's instruction set.
    fn call<K: PackKernel>(self, k: K) -> K::Output;
    /// `a * b + c`, fused where the instruction set has it.
    fn fma(self, a: Self::F, b: Self::F, c: Self::F) -> Self::F;
    /// `c - a * b`, fused where the instruction set has it.
    fn fnma(self, a: Self::F, b: Self::F, c: Self::F) -> Self::F;
    /// `1 / sqrt(a)` for positive normal `a`, to within 2^-21 relative (a few units in the
    /// last place; exact on the scalar path), other inputs unspecified. An estimate refined
    /// by Newton's step: a square root or a division occupies AVX-512's divider for 10 to
    /// 12 cycles per register, this the multiply units for a few.
    fn rsqrt(self, a: Self::F) -> Self::F;
    /// Round to nearest, ties to even.
    fn round(self, a: Self::F) -> Self::F;
    /// `a and not b`.
    fn and_not(self, a: Self::M, b: Self::M) -> Self::M;
    /// Every lane false.
    fn none(self) -> Self::M;
    /// Every lane true.
    fn all_set(self) -> Self::M;
    /// Bit `i` set when lane `i` is (loop control and counting only).
    fn bitmask(self, m: Self::M) -> u32;
    /// How many lanes are set.
    #[inline(always)]
    fn count(self, m: Self::M) -> u32 {
        self.bitmask(m).count_ones()
    }
    /// `a == b`.
    fn eq_i(self, a: Self::I, b: Self::I) -> Self::M;
    /// `v as i32` after rounding to nearest (values in `i32` range).
    fn round_i(self, v: Self::F) -> Self::I;
    /// Wrapping `a - b`.
    fn sub_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a & b`.
    fn and_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a | b`.
    fn or_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// Shift left by `N` (< 32).
    fn shl_n<const N: i32>(self, a: Self::I) -> Self::I;
    /// Logical shift right by `N` (< 32).
    fn shr_n<const N: i32>(self, a: Self::I) -> Self::I;
    /// Adds `n` floating-point operations to the counter of the counting backend; a no-op
    /// elsewhere. The tracer calls it for work it does outside the lane operations.
    #[inline(always)]
    fn tally(self, _n: u64) {}
    /// Counts as one operation whatever `f` does (math-library calls count as one flop, the
    /// convention of the reference paper); a plain call elsewhere.
    #[inline(always)]
    fn as_one_op<R>(self, f: impl FnOnce() -> R) -> R {
        f()
    }
}

/// The backends the tracer has code for (the others fall back as [`craterfield_core::backend`] says).
pub const TRACER_BACKENDS: [Backend; 4] = [
    Backend::Scalar,
    Backend::Avx2,
    Backend::Avx512,
    Backend::Neon,
];

/// What [`Backend::check_of`] and the errors call the tracer.
const TRACER: &str = "the CPU sphere tracer";

/// The tracer's default backend: the widest of [`TRACER_BACKENDS`] available here, capped
/// by `CRATERFIELD_BACKEND`.
pub fn best() -> Backend {
    Backend::best_of(&TRACER_BACKENDS)
}

/// `Ok(backend)` if the tracer has code for it and it is available here.
pub fn check(backend: Backend) -> Result<Backend, BackendError> {
    backend.check_of(&TRACER_BACKENDS, TRACER)
}

/// Runs `k` on `backend`: the one place that turns a [`Backend`] value into tracer code.
pub fn run<K: PackKernel>(backend: Backend, k: K) -> Result<K::Output, BackendError> {
    match backend {
        Backend::Scalar => Ok(Pack::call(Scalar, k)),
        #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
        Backend::Avx2 => craterfield_core::simd::Avx2::new()
            .map(|p| Pack::call(p, k))
            .ok_or_else(|| backend.unavailable_to(&TRACER_BACKENDS)),
        #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
        Backend::Avx512 => craterfield_core::simd::Avx512::new()
            .map(|p| Pack::call(p, k))
            .ok_or_else(|| backend.unavailable_to(&TRACER_BACKENDS)),
        #[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
        Backend::Neon => craterfield_core::simd::Neon::new()
            .map(|p| Pack::call(p, k))
            .ok_or_else(|| backend.unavailable_to(&TRACER_BACKENDS)),
        #[allow(unreachable_patterns)]
        _ => check(backend).and_then(|b| Err(b.unavailable_to(&TRACER_BACKENDS))),
    }
}
