//! The counting backend: the scalar lane that also counts the floating-point operations it
//! performs, per thread, for the tracer's flops-per-frame figures.
//!
//! The convention is the reference paper's: one flop per arithmetic operation (add, sub,
//! mul, div, sqrt, min, max; a fused multiply-add is two) or math-library call (a call
//! wrapped in [`Pack::as_one_op`], as every function of [`crate::march3d::math`] is).
//! Sign flips, rounding, comparisons, selects and mask, integer and bit operations count
//! nothing.

use std::cell::Cell;

use super::scalar::Scalar;
use super::{Pack, PackKernel};

thread_local! {
    /// Operations counted on this thread since the last [`take_flops`].
    static FLOPS: Cell<u64> = const { Cell::new(0) };
    /// How many [`Pack::as_one_op`] calls this thread is inside (counting is off while > 0).
    static SUSPENDED: Cell<u32> = const { Cell::new(0) };
}

/// The counting backend's token: one `f32` lane, the scalar backend's arithmetic.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Counting;

/// This thread's count, which is then reset to zero.
pub(crate) fn take_flops() -> u64 {
    FLOPS.with(|c| c.replace(0))
}

/// This thread's count so far (the tests read it without resetting it).
#[cfg(test)]
pub(crate) fn flops() -> u64 {
    FLOPS.with(Cell::get)
}

/// Adds `n` to this thread's count unless an [`Pack::as_one_op`] call is running.
#[inline(always)]
fn count(n: u64) {
    if SUSPENDED.with(Cell::get) == 0 {
        FLOPS.with(|c| c.set(c.get().wrapping_add(n)));
    }
}

/// Resumes counting when dropped, so a panic inside `as_one_op` cannot leave it off.
struct Suspension;

impl Suspension {
    fn begin() -> Suspension {
        SUSPENDED.with(|s| s.set(s.get() + 1));
        Suspension
    }
}

impl Drop for Suspension {
    fn drop(&mut self) {
        SUSPENDED.with(|s| s.set(s.get() - 1));
    }
}

impl Pack for Counting {
    const WIDTH: usize = 1;
    type F = f32;
    type M = bool;
    type I = i32;

    #[inline]
    fn call<K: PackKernel>(self, k: K) -> K::Output {
        // Out of line, like the SIMD backends' target-feature functions: a kernel is
        // compiled once per call type, not inlined into each caller.
        #[inline(never)]
        fn inner<K: PackKernel>(k: K) -> K::Output {
            k.run(Counting)
        }
        inner(k)
    }

    #[inline(always)]
    fn tally(self, n: u64) {
        count(n);
    }

    #[inline(always)]
    fn as_one_op<R>(self, f: impl FnOnce() -> R) -> R {
        let r = {
            let _off = Suspension::begin();
            f()
        };
        // Inside an enclosing call this is suppressed too: nested calls count once in all.
        count(1);
        r
    }

    #[inline(always)]
    fn splat(self, v: f32) -> f32 {
        Scalar.splat(v)
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> f32 {
        Scalar.load(s)
    }
    #[inline(always)]
    fn store(self, v: f32, out: &mut [f32]) {
        Scalar.store(v, out)
    }
    #[inline(always)]
    fn add(self, a: f32, b: f32) -> f32 {
        count(1);
        Scalar.add(a, b)
    }
    #[inline(always)]
    fn sub(self, a: f32, b: f32) -> f32 {
        count(1);
        Scalar.sub(a, b)
    }
    #[inline(always)]
    fn mul(self, a: f32, b: f32) -> f32 {
        count(1);
        Scalar.mul(a, b)
    }
    #[inline(always)]
    fn div(self, a: f32, b: f32) -> f32 {
        count(1);
        Scalar.div(a, b)
    }
    #[inline(always)]
    fn fma(self, a: f32, b: f32, c: f32) -> f32 {
        count(2);
        Scalar.fma(a, b, c)
    }
    #[inline(always)]
    fn fnma(self, a: f32, b: f32, c: f32) -> f32 {
        count(2);
        Scalar.fnma(a, b, c)
    }
    #[inline(always)]
    fn sqrt(self, a: f32) -> f32 {
        count(1);
        Scalar.sqrt(a)
    }
    #[inline(always)]
    fn neg(self, a: f32) -> f32 {
        Scalar.neg(a)
    }
    #[inline(always)]
    fn abs(self, a: f32) -> f32 {
        Scalar.abs(a)
    }
    #[inline(always)]
    fn floor(self, a: f32) -> f32 {
        Scalar.floor(a)
    }
    #[inline(always)]
    fn round(self, a: f32) -> f32 {
        Scalar.round(a)
    }
    #[inline(always)]
    fn min(self, a: f32, b: f32) -> f32 {
        count(1);
        Scalar.min(a, b)
    }
    #[inline(always)]
    fn max(self, a: f32, b: f32) -> f32 {
        count(1);
        Scalar.max(a, b)
    }
    #[inline(always)]
    fn lt(self, a: f32, b: f32) -> bool {
        Scalar.lt(a, b)
    }
    #[inline(always)]
    fn le(self, a: f32, b: f32) -> bool {
        Scalar.le(a, b)
    }
    #[inline(always)]
    fn gt(self, a: f32, b: f32) -> bool {
        Scalar.gt(a, b)
    }
    #[inline(always)]
    fn ge(self, a: f32, b: f32) -> bool {
        Scalar.ge(a, b)
    }
    #[inline(always)]
    fn select(self, m: bool, a: f32, b: f32) -> f32 {
        Scalar.select(m, a, b)
    }
    #[inline(always)]
    fn select_i(self, m: bool, a: i32, b: i32) -> i32 {
        Scalar.select_i(m, a, b)
    }
    #[inline(always)]
    fn and(self, a: bool, b: bool) -> bool {
        Scalar.and(a, b)
    }
    #[inline(always)]
    fn or(self, a: bool, b: bool) -> bool {
        Scalar.or(a, b)
    }
    #[inline(always)]
    fn and_not(self, a: bool, b: bool) -> bool {
        Scalar.and_not(a, b)
    }
    #[inline(always)]
    fn not(self, a: bool) -> bool {
        Scalar.not(a)
    }
    #[inline(always)]
    fn none(self) -> bool {
        Scalar.none()
    }
    #[inline(always)]
    fn all_set(self) -> bool {
        Scalar.all_set()
    }
    #[inline(always)]
    fn bitmask(self, m: bool) -> u32 {
        Scalar.bitmask(m)
    }
    #[inline(always)]
    fn splat_i(self, v: i32) -> i32 {
        Scalar.splat_i(v)
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> i32 {
        Scalar.load_i(s)
    }
    #[inline(always)]
    fn store_i(self, v: i32, out: &mut [i32]) {
        Scalar.store_i(v, out)
    }
    #[inline(always)]
    fn eq_i(self, a: i32, b: i32) -> bool {
        Scalar.eq_i(a, b)
    }
    #[inline(always)]
    fn round_i(self, v: f32) -> i32 {
        Scalar.round_i(v)
    }
    #[inline(always)]
    fn to_f32(self, v: i32) -> f32 {
        Scalar.to_f32(v)
    }
    #[inline(always)]
    fn add_i(self, a: i32, b: i32) -> i32 {
        Scalar.add_i(a, b)
    }
    #[inline(always)]
    fn sub_i(self, a: i32, b: i32) -> i32 {
        Scalar.sub_i(a, b)
    }
    #[inline(always)]
    fn and_i(self, a: i32, b: i32) -> i32 {
        Scalar.and_i(a, b)
    }
    #[inline(always)]
    fn or_i(self, a: i32, b: i32) -> i32 {
        Scalar.or_i(a, b)
    }
    #[inline(always)]
    fn shl_i<const N: i32>(self, a: i32) -> i32 {
        Scalar.shl_i::<N>(a)
    }
    #[inline(always)]
    fn shr_i<const N: i32>(self, a: i32) -> i32 {
        Scalar.shr_i::<N>(a)
    }
    #[inline(always)]
    fn bits(self, a: f32) -> i32 {
        Scalar.bits(a)
    }
    #[inline(always)]
    fn from_bits(self, a: i32) -> f32 {
        Scalar.from_bits(a)
    }
}
