//! Exact lane primitives, one module per instruction set, and the one place that chooses
//! among them.
//!
//! A backend is a zero-sized token type implementing [`Lanes`]: the operations of one SIMD
//! register of `f32` lanes (and of the masks and `i32` lanes that go with it). The field's
//! tape interpreter (`craterfield-field`'s `exec`) is written once, generic over `Lanes`,
//! and instantiated per backend through [`run`]; the 3D tracer's lanes
//! (`craterfield-march3d`) implement their own trait, with fused multiply-adds, on the same
//! tokens. The tokens of the SIMD backends can only be made after runtime detection of
//! their instruction set, which is what makes their `unsafe` intrinsics sound; `unsafe`
//! lives only in the per-architecture files.
//!
//! Every operation is exactly rounded or a bit operation, with the project's semantics
//! (the determinism contract of `docs/ARCHITECTURE.md`): `min(a, b) = if a < b { a } else
//! { b }`, `max` likewise, comparisons are ordered (false on NaN), `floor` keeps the sign of
//! zero, and float-to-int conversion saturates with NaN giving 0 (Rust's `as i32`). No FMA,
//! no estimates, no horizontal reductions: a lane computes what the scalar code computes.
//!
//! Choosing: this stack has code for every [`Backend`]; detection, the default choice
//! ([`Backend::best`], capped by the environment variable `CRATERFIELD_BACKEND`) and the
//! errors are in [`crate::backend`]. Building with the feature `force-scalar` makes the
//! scalar backend the only one.

use crate::backend::{Backend, BackendError};

mod scalar;

#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
mod avx2;
#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
mod avx512;
#[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
mod neon;
#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
mod sse2;

#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
pub use avx2::Avx2;
#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
pub use avx512::Avx512;
#[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
pub use neon::Neon;
pub use scalar::Scalar;
#[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
pub use sse2::Sse2;

/// The operations of one register of `f32` lanes. See the module doc for the semantics.
pub trait Lanes: Copy + Send + Sync + 'static {
    /// Lanes per register.
    const WIDTH: usize;
    /// `WIDTH` floats.
    type F: Copy;
    /// `WIDTH` booleans.
    type M: Copy;
    /// `WIDTH` 32-bit integers.
    type I: Copy;

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
    /// Correctly rounded square root.
    fn sqrt(self, a: Self::F) -> Self::F;
    /// Sign flipped.
    fn neg(self, a: Self::F) -> Self::F;
    /// Sign cleared.
    fn abs(self, a: Self::F) -> Self::F;
    /// Round towards minus infinity; `-0.0` stays `-0.0`, NaN stays NaN.
    fn floor(self, a: Self::F) -> Self::F;
    /// `if a < b { a } else { b }`.
    fn min(self, a: Self::F, b: Self::F) -> Self::F;
    /// `if a > b { a } else { b }`.
    fn max(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a < b` (false on NaN).
    fn lt(self, a: Self::F, b: Self::F) -> Self::M;
    /// `a > b` (false on NaN).
    fn gt(self, a: Self::F, b: Self::F) -> Self::M;
    /// `a <= b` (false on NaN).
    fn le(self, a: Self::F, b: Self::F) -> Self::M;
    /// `a >= b` (false on NaN).
    fn ge(self, a: Self::F, b: Self::F) -> Self::M;
    /// `a == a` (false on NaN).
    fn not_nan(self, a: Self::F) -> Self::M;
    /// `if m { a } else { b }` per lane.
    fn select(self, m: Self::M, a: Self::F, b: Self::F) -> Self::F;
    /// `if m { a } else { b }` per lane.
    fn select_i(self, m: Self::M, a: Self::I, b: Self::I) -> Self::I;
    /// Lanewise and.
    fn and(self, a: Self::M, b: Self::M) -> Self::M;
    /// Lanewise or.
    fn or(self, a: Self::M, b: Self::M) -> Self::M;
    /// Lanewise exclusive or.
    fn xor(self, a: Self::M, b: Self::M) -> Self::M;
    /// Lanewise not.
    fn not(self, a: Self::M) -> Self::M;
    /// Whether any lane is set (loop control only, never a value).
    fn any(self, m: Self::M) -> bool;
    /// Every lane `v`.
    fn splat_i(self, v: i32) -> Self::I;
    /// Lanes from `s[..WIDTH]`.
    fn load_i(self, s: &[i32]) -> Self::I;
    /// Writes the lanes to `out[..WIDTH]`.
    fn store_i(self, v: Self::I, out: &mut [i32]);
    /// `v as i32` (truncating, saturating, NaN gives 0).
    fn to_i32(self, v: Self::F) -> Self::I;
    /// `v as f32` (round to nearest even).
    fn to_f32(self, v: Self::I) -> Self::F;
    /// Wrapping `a + b`.
    fn add_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// Wrapping `a * b`.
    fn mul_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a ^ b`.
    fn xor_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// Logical shift right of the 32 bits by `n` (< 32).
    fn shr_i(self, a: Self::I, n: u32) -> Self::I;
    /// `a < b` (signed).
    fn lt_i(self, a: Self::I, b: Self::I) -> Self::M;
    /// `a > b` (signed).
    fn gt_i(self, a: Self::I, b: Self::I) -> Self::M;
    /// The mask's bits as floats (all ones or zero), for storage in a float register.
    fn mask_bits(self, m: Self::M) -> Self::F;
    /// A mask from bits stored by [`Lanes::mask_bits`].
    fn bits_mask(self, f: Self::F) -> Self::M;
    /// The integers' bits as floats, for storage in a float register.
    fn int_bits(self, i: Self::I) -> Self::F;
    /// Integers from bits stored by [`Lanes::int_bits`].
    fn bits_int(self, f: Self::F) -> Self::I;
}

/// Work generic over the lanes: [`run`] instantiates it for a backend. `run` (the method)
/// must be `#[inline(always)]`, and so must everything it calls that touches lanes: the
/// SIMD backends call it from a function compiled with their instruction set enabled, and
/// only code inlined there is compiled with it.
pub trait Kernel {
    /// What the work returns.
    type Output;
    /// Does the work on lanes `l`, `NB` lane registers of points at a time.
    fn run<L: Lanes, const NB: usize>(self, l: L) -> Self::Output;
}

/// Lane registers per block on the SIMD backends: each decoded instruction is applied to
/// `SIMD_BLOCK * WIDTH` points. The scalar backend takes one point at a time.
#[cfg(all(
    any(target_arch = "x86_64", target_arch = "aarch64"),
    not(feature = "force-scalar")
))]
pub const SIMD_BLOCK: usize = 16;

/// Runs `k` on `backend`: the one place that turns a [`Backend`] value into code.
pub fn run<K: Kernel>(backend: Backend, k: K) -> Result<K::Output, BackendError> {
    match backend {
        Backend::Scalar => Ok(k.run::<scalar::Scalar, 1>(scalar::Scalar)),
        #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
        Backend::Sse2 => match sse2::Sse2::new() {
            Some(l) => Ok(l.call(k)),
            None => Err(unavailable(backend)),
        },
        #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
        Backend::Avx2 => match avx2::Avx2::new() {
            Some(l) => Ok(l.call(k)),
            None => Err(unavailable(backend)),
        },
        #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
        Backend::Avx512 => match avx512::Avx512::new() {
            Some(l) => Ok(l.call(k)),
            None => Err(unavailable(backend)),
        },
        #[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
        Backend::Neon => match neon::Neon::new() {
            Some(l) => Ok(l.call(k)),
            None => Err(unavailable(backend)),
        },
        #[allow(unreachable_patterns)]
        _ => Err(unavailable(backend)),
    }
}

/// The error for a backend whose token could not be made.
fn unavailable(backend: Backend) -> BackendError {
    backend.unavailable_to(&Backend::ALL)
}
