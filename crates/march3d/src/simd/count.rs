//! The counting backend: the scalar lane that also counts the floating-point operations it
//! performs, per thread, for the tracer's flops-per-frame figures.
//!
//! The convention is the reference paper's: one flop per arithmetic operation (add, sub,
//! mul, div, sqrt, min, max; a fused multiply-add is two) or math-library call (a call
//! wrapped in [`Pack::as_one_op`], as every function of [`crate::math`] is).
//! Sign flips, rounding, comparisons, selects and mask, integer and bit operations count
//! nothing.

use std::cell::Cell;

use craterfield_core::simd::{Lanes, Scalar};

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

/// Methods that only forward to the scalar lanes (operations the convention counts as
/// nothing: sign flips, rounding, comparisons, selects, mask, integer and bit operations).
macro_rules! forward_to_scalar {
    ($($name:ident($($arg:ident: $ty:ty),*) -> $ret:ty;)*) => {
        $(
            #[inline(always)]
            fn $name(self, $($arg: $ty),*) -> $ret {
                Scalar.$name($($arg),*)
            }
        )*
    };
}

impl Lanes for Counting {
    const WIDTH: usize = 1;
    type F = f32;
    type M = bool;
    type I = i32;

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
    fn sqrt(self, a: f32) -> f32 {
        count(1);
        Scalar.sqrt(a)
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

    forward_to_scalar! {
        splat(v: f32) -> f32;
        load(s: &[f32]) -> f32;
        store(v: f32, out: &mut [f32]) -> ();
        neg(a: f32) -> f32;
        abs(a: f32) -> f32;
        floor(a: f32) -> f32;
        lt(a: f32, b: f32) -> bool;
        gt(a: f32, b: f32) -> bool;
        le(a: f32, b: f32) -> bool;
        ge(a: f32, b: f32) -> bool;
        not_nan(a: f32) -> bool;
        select(m: bool, a: f32, b: f32) -> f32;
        select_i(m: bool, a: i32, b: i32) -> i32;
        and(a: bool, b: bool) -> bool;
        or(a: bool, b: bool) -> bool;
        xor(a: bool, b: bool) -> bool;
        not(a: bool) -> bool;
        any(m: bool) -> bool;
        splat_i(v: i32) -> i32;
        load_i(s: &[i32]) -> i32;
        store_i(v: i32, out: &mut [i32]) -> ();
        to_i32(v: f32) -> i32;
        to_f32(v: i32) -> f32;
        add_i(a: i32, b: i32) -> i32;
        mul_i(a: i32, b: i32) -> i32;
        xor_i(a: i32, b: i32) -> i32;
        shr_i(a: i32, n: u32) -> i32;
        lt_i(a: i32, b: i32) -> bool;
        gt_i(a: i32, b: i32) -> bool;
        mask_bits(m: bool) -> f32;
        bits_mask(f: f32) -> bool;
        int_bits(i: i32) -> f32;
        bits_int(f: f32) -> i32;
    }
}

impl Pack for Counting {
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
    fn rsqrt(self, a: f32) -> f32 {
        // One operation, as the square root it replaces.
        count(1);
        Scalar.rsqrt(a)
    }
    #[inline(always)]
    fn shl_n<const N: i32>(self, a: i32) -> i32 {
        Scalar.shl_n::<N>(a)
    }
    #[inline(always)]
    fn shr_n<const N: i32>(self, a: i32) -> i32 {
        Scalar.shr_n::<N>(a)
    }

    forward_to_scalar! {
        round(a: f32) -> f32;
        and_not(a: bool, b: bool) -> bool;
        none() -> bool;
        all_set() -> bool;
        bitmask(m: bool) -> u32;
        eq_i(a: i32, b: i32) -> bool;
        round_i(v: f32) -> i32;
        sub_i(a: i32, b: i32) -> i32;
        and_i(a: i32, b: i32) -> i32;
        or_i(a: i32, b: i32) -> i32;
    }
}
