//! The counting backend: what it counts, and that counting is per thread.

use super::super::Pack;
use super::super::count::{self, Counting};
use crate::math;
use craterfield_core::simd::{Lanes, Scalar};

// ---------------------------------------------------------------------------------------
// The counting backend.

/// Runs `f` on the counting backend and returns its result with the flops it counted.
fn counted<R>(f: impl FnOnce(Counting) -> R) -> (R, u64) {
    count::take_flops();
    let r = f(Counting);
    (r, count::take_flops())
}

#[test]
fn arithmetic_counts_one_flop_and_fma_two() {
    let ((), n) = counted(|p| {
        let (a, b) = (p.splat(2.0), p.splat(3.0));
        // add, mul, sqrt, div, sub, min, max: 7; fma and fnma: 4.
        let s = p.add(a, b);
        let m = p.mul(s, b);
        let r = p.sqrt(m);
        let d = p.div(r, a);
        let e = p.sub(d, b);
        let lo = p.min(e, a);
        let hi = p.max(lo, b);
        let f = p.fma(hi, a, b);
        let g = p.fnma(f, a, b);
        assert_eq!(g, 3.0 - (3.0 * 2.0 + 3.0) * 2.0);
    });
    assert_eq!(n, 11);
}

#[test]
fn rsqrt_counts_one_flop_as_the_square_root_it_replaces() {
    let (r, n) = counted(|p| p.rsqrt(p.splat(4.0)));
    assert_eq!((r, n), (0.5, 1));
}

#[test]
fn free_operations_count_nothing() {
    let ((), n) = counted(|p| {
        let a = p.load(&[1.5]);
        let b = p.neg(p.abs(p.floor(p.round(a))));
        let m = p.and(p.lt(a, b), p.not(p.ge(a, b)));
        let m = p.or(p.and_not(m, p.gt(a, b)), p.le(a, b));
        let v = p.select(m, a, b);
        let i = p.select_i(m, p.round_i(v), p.splat_i(3));
        let i = p.shr_n::<1>(p.shl_n::<2>(p.add_i(p.sub_i(i, p.splat_i(1)), i)));
        let i = p.or_i(p.and_i(i, p.bits_int(v)), p.splat_i(0));
        let _ = p.int_bits(i);
        let _ = p.to_f32(i);
        let _ = p.eq_i(i, i);
        let _ = (p.bitmask(m), p.any(m), p.count(m), p.none(), p.all_set());
        let mut out = [0.0];
        p.store(v, &mut out);
    });
    assert_eq!(n, 0);
}

#[test]
fn math_calls_count_one_flop_each_and_nesting_counts_once() {
    let (_, n) = counted(|p| {
        let x = p.splat(0.7);
        let a = math::exp(p, x);
        let b = math::pow(p, a, x);
        let (s, c) = math::sin_cos(p, b);
        p.add(s, c)
    });
    // exp, pow (which calls log2 and exp2 inside), sin_cos, and the add.
    assert_eq!(n, 4);

    let (_, n) = counted(|p| {
        p.as_one_op(|| {
            let x = p.mul(p.splat(2.0), p.splat(3.0));
            p.tally(100);
            p.as_one_op(|| p.fma(x, x, x))
        })
    });
    assert_eq!(n, 1);
}

#[test]
fn tally_adds_and_take_resets() {
    let ((), n) = counted(|p| {
        p.tally(7);
        p.tally(5);
        let _ = p.add(p.splat(1.0), p.splat(2.0));
    });
    assert_eq!(n, 13);
    assert_eq!(count::flops(), 0);
    Counting.tally(3);
    assert_eq!(count::flops(), 3);
    assert_eq!(count::take_flops(), 3);
    assert_eq!(count::flops(), 0);
    // Tallies on the other backends go nowhere.
    Scalar.tally(9);
    assert_eq!(count::flops(), 0);
}

#[test]
fn counts_are_per_thread() {
    count::take_flops();
    let p = Counting;
    let _ = p.mul(p.splat(2.0), p.splat(2.0));
    let other = std::thread::spawn(|| {
        let p = Counting;
        for _ in 0..10 {
            let _ = p.add(p.splat(1.0), p.splat(1.0));
        }
        count::take_flops()
    })
    .join()
    .expect("the counting thread does not panic");
    assert_eq!(other, 10);
    assert_eq!(count::take_flops(), 1);
}

#[test]
fn a_panic_inside_as_one_op_does_not_leave_counting_off() {
    count::take_flops();
    let r = std::panic::catch_unwind(|| {
        Counting.as_one_op(|| -> () { panic!("inside a counted call") });
    });
    assert!(r.is_err());
    let _ = Counting.add(1.0, 2.0);
    assert_eq!(count::take_flops(), 1);
}
