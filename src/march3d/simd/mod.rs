//! Lane primitives of the CPU sphere tracer, one module per instruction set, and the one
//! place that chooses among them.
//!
//! Unlike the 2D field's lanes (`field2d::simd`), which must give the same bits everywhere,
//! rendering is not on the determinism contract: these lanes may fuse multiply-adds and use
//! polynomial approximations of `sin`, `cos`, `exp` and `log` (in [`super::math`], written
//! once over this trait). A backend is a zero-sized token type implementing [`Pack`]; the
//! tracer is generic over it and instantiated per backend inside a function compiled with
//! the backend's instruction set (`Pack::call`). Tokens of SIMD backends exist only after
//! runtime detection, which is what makes their intrinsics sound; `unsafe` lives only in the
//! per-architecture files.
//!
//! Choosing: [`best`] picks AVX2+FMA (8 lanes) on x86_64 or NEON (4 lanes) on aarch64, else
//! the scalar path. Detection, the environment variable `CRATERFIELD_BACKEND` that caps the
//! choice, and the errors are shared with the 2D field's lanes in [`crate::backend`]; the
//! `force-scalar` feature compiles only the scalar path.

use crate::backend::{Backend, BackendError};

pub(crate) mod count;
pub(crate) mod scalar;
#[cfg(test)]
mod tests;

#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
mod avx2;
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

/// The operations of one register of `f32` lanes, its masks and its `i32` lanes.
///
/// Semantics: IEEE single precision; `fma` may be fused or not (backends without FMA
/// multiply then add); comparisons are ordered (false on NaN); `min`/`max` return the second
/// operand when either is NaN (the x86 rule, which the other backends copy).
pub trait Pack: Copy + Send + Sync + 'static {
    /// Lanes per register.
    const WIDTH: usize;
    /// `WIDTH` floats.
    type F: Copy;
    /// `WIDTH` booleans.
    type M: Copy;
    /// `WIDTH` 32-bit integers.
    type I: Copy;

    /// Runs `k` compiled for this backend's instruction set.
    fn call<K: PackKernel>(self, k: K) -> K::Output;

    /// Every lane `v`.
    fn splat(self, v: f32) -> Self::F;
    /// Lanes from `s[..WIDTH]`.
    fn load(self, s: &[f32]) -> Self::F;
    /// Writes the lanes to `out[..WIDTH]`.
    fn store(self, v: Self::F, out: &mut [f32]);
    /// `a + b`.
    fn add(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a - b`.
    fn sub(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a * b`.
    fn mul(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a / b`.
    fn div(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a * b + c`, fused where the instruction set has it.
    fn fma(self, a: Self::F, b: Self::F, c: Self::F) -> Self::F;
    /// `c - a * b`, fused where the instruction set has it.
    fn fnma(self, a: Self::F, b: Self::F, c: Self::F) -> Self::F;
    /// Square root (correctly rounded).
    fn sqrt(self, a: Self::F) -> Self::F;
    /// Sign flipped.
    fn neg(self, a: Self::F) -> Self::F;
    /// Sign cleared.
    fn abs(self, a: Self::F) -> Self::F;
    /// Round towards minus infinity.
    fn floor(self, a: Self::F) -> Self::F;
    /// Round to nearest, ties to even.
    fn round(self, a: Self::F) -> Self::F;
    /// `if a < b { a } else { b }`.
    fn min(self, a: Self::F, b: Self::F) -> Self::F;
    /// `if a > b { a } else { b }`.
    fn max(self, a: Self::F, b: Self::F) -> Self::F;

    /// `a < b`.
    fn lt(self, a: Self::F, b: Self::F) -> Self::M;
    /// `a <= b`.
    fn le(self, a: Self::F, b: Self::F) -> Self::M;
    /// `a > b`.
    fn gt(self, a: Self::F, b: Self::F) -> Self::M;
    /// `a >= b`.
    fn ge(self, a: Self::F, b: Self::F) -> Self::M;
    /// `if m { a } else { b }` per lane.
    fn select(self, m: Self::M, a: Self::F, b: Self::F) -> Self::F;
    /// `if m { a } else { b }` per lane.
    fn select_i(self, m: Self::M, a: Self::I, b: Self::I) -> Self::I;
    /// Lanewise and.
    fn and(self, a: Self::M, b: Self::M) -> Self::M;
    /// Lanewise or.
    fn or(self, a: Self::M, b: Self::M) -> Self::M;
    /// `a and not b`.
    fn and_not(self, a: Self::M, b: Self::M) -> Self::M;
    /// Lanewise not.
    fn not(self, a: Self::M) -> Self::M;
    /// Every lane false.
    fn none(self) -> Self::M;
    /// Every lane true.
    fn all_set(self) -> Self::M;
    /// Bit `i` set when lane `i` is (loop control and counting only).
    fn bitmask(self, m: Self::M) -> u32;
    /// Whether any lane is set.
    #[inline(always)]
    fn any(self, m: Self::M) -> bool {
        self.bitmask(m) != 0
    }
    /// How many lanes are set.
    #[inline(always)]
    fn count(self, m: Self::M) -> u32 {
        self.bitmask(m).count_ones()
    }

    /// Every lane `v`.
    fn splat_i(self, v: i32) -> Self::I;
    /// Lanes from `s[..WIDTH]`.
    fn load_i(self, s: &[i32]) -> Self::I;
    /// Writes the lanes to `out[..WIDTH]`.
    fn store_i(self, v: Self::I, out: &mut [i32]);
    /// `a == b`.
    fn eq_i(self, a: Self::I, b: Self::I) -> Self::M;
    /// `v as i32` after rounding to nearest (values in `i32` range).
    fn round_i(self, v: Self::F) -> Self::I;
    /// `v as f32`.
    fn to_f32(self, v: Self::I) -> Self::F;
    /// Wrapping `a + b`.
    fn add_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// Wrapping `a - b`.
    fn sub_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a & b`.
    fn and_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a | b`.
    fn or_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// Shift left by `N` (< 32).
    fn shl_i<const N: i32>(self, a: Self::I) -> Self::I;
    /// Logical shift right by `N` (< 32).
    fn shr_i<const N: i32>(self, a: Self::I) -> Self::I;
    /// The float's bits.
    fn bits(self, a: Self::F) -> Self::I;
    /// A float from bits.
    // Named after `f32::from_bits`; `self` is the backend token, not the value converted.
    #[allow(clippy::wrong_self_convention)]
    fn from_bits(self, a: Self::I) -> Self::F;

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

/// The backends the tracer has code for (the others fall back as [`crate::backend`] says).
pub const TRACER_BACKENDS: [Backend; 3] = [Backend::Scalar, Backend::Avx2, Backend::Neon];

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
        Backend::Scalar => Ok(scalar::Scalar.call(k)),
        #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
        Backend::Avx2 => avx2::Avx2::new()
            .map(|p| p.call(k))
            .ok_or_else(|| backend.unavailable_to(&TRACER_BACKENDS)),
        #[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
        Backend::Neon => neon::Neon::new()
            .map(|p| p.call(k))
            .ok_or_else(|| backend.unavailable_to(&TRACER_BACKENDS)),
        #[allow(unreachable_patterns)]
        _ => check(backend).and_then(|b| Err(b.unavailable_to(&TRACER_BACKENDS))),
    }
}
