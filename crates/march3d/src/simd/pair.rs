//! Two registers of a backend as one pack of twice its width: every operation is issued
//! once per half, so two independent dependency chains run side by side.
//!
//! A long chain of dependent operations (the Mandelbulb's power iteration: a square root
//! and a division per iteration, each waiting on the last) leaves the execution units idle
//! while one register's result is in flight; the other half fills that time. The ray
//! streams march in pairs on the backends that set [`Pack::STREAM_PAIRS`], in scenes whose
//! distance is such a chain (`SceneConstants::long_chains`). Lane `i` of the
//! low half is lane `i` of the pair, lane `i` of the high half is lane `WIDTH + i`, and each
//! lane's bits are the backend's: a pair changes the schedule, never a result.

use craterfield_core::simd::Lanes;

use super::{Pack, PackKernel};

/// `P`'s lanes twice over (the low half first).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pair<P>(pub P);

/// Operations applied to each half: `$t` names the argument types (`F`, `M` or `I`) and
/// the result type.
macro_rules! halves {
    ($($name:ident($($arg:ident: $t:ident),*) -> $ret:ident;)*) => {
        $(
            #[inline(always)]
            fn $name(self, $($arg: Self::$t),*) -> Self::$ret {
                (self.0.$name($($arg.0),*), self.0.$name($($arg.1),*))
            }
        )*
    };
}

impl<P: Pack> Lanes for Pair<P> {
    const WIDTH: usize = 2 * P::WIDTH;
    type F = (P::F, P::F);
    type M = (P::M, P::M);
    type I = (P::I, P::I);

    #[inline(always)]
    fn splat(self, v: f32) -> Self::F {
        let s = self.0.splat(v);
        (s, s)
    }
    #[inline(always)]
    fn load(self, s: &[f32]) -> Self::F {
        (self.0.load(s), self.0.load(&s[P::WIDTH..]))
    }
    #[inline(always)]
    fn store(self, v: Self::F, out: &mut [f32]) {
        self.0.store(v.0, out);
        self.0.store(v.1, &mut out[P::WIDTH..]);
    }
    #[inline(always)]
    fn any(self, m: Self::M) -> bool {
        self.0.any(self.0.or(m.0, m.1))
    }
    #[inline(always)]
    fn splat_i(self, v: i32) -> Self::I {
        let s = self.0.splat_i(v);
        (s, s)
    }
    #[inline(always)]
    fn load_i(self, s: &[i32]) -> Self::I {
        (self.0.load_i(s), self.0.load_i(&s[P::WIDTH..]))
    }
    #[inline(always)]
    fn store_i(self, v: Self::I, out: &mut [i32]) {
        self.0.store_i(v.0, out);
        self.0.store_i(v.1, &mut out[P::WIDTH..]);
    }
    #[inline(always)]
    fn shr_i(self, a: Self::I, n: u32) -> Self::I {
        (self.0.shr_i(a.0, n), self.0.shr_i(a.1, n))
    }

    halves! {
        add(a: F, b: F) -> F;
        sub(a: F, b: F) -> F;
        mul(a: F, b: F) -> F;
        div(a: F, b: F) -> F;
        sqrt(a: F) -> F;
        neg(a: F) -> F;
        abs(a: F) -> F;
        floor(a: F) -> F;
        min(a: F, b: F) -> F;
        max(a: F, b: F) -> F;
        lt(a: F, b: F) -> M;
        gt(a: F, b: F) -> M;
        le(a: F, b: F) -> M;
        ge(a: F, b: F) -> M;
        not_nan(a: F) -> M;
        select(m: M, a: F, b: F) -> F;
        select_i(m: M, a: I, b: I) -> I;
        and(a: M, b: M) -> M;
        or(a: M, b: M) -> M;
        xor(a: M, b: M) -> M;
        not(a: M) -> M;
        to_i32(v: F) -> I;
        to_f32(v: I) -> F;
        add_i(a: I, b: I) -> I;
        mul_i(a: I, b: I) -> I;
        xor_i(a: I, b: I) -> I;
        lt_i(a: I, b: I) -> M;
        gt_i(a: I, b: I) -> M;
        mask_bits(m: M) -> F;
        bits_mask(f: F) -> M;
        int_bits(i: I) -> F;
        bits_int(f: F) -> I;
    }
}

/// A kernel run on the pair of whatever backend runs it.
struct Paired<K>(K);

impl<K: PackKernel> PackKernel for Paired<K> {
    type Output = K::Output;
    #[inline(always)]
    fn run<Q: Pack>(self, q: Q) -> K::Output {
        self.0.run(Pair(q))
    }
}

impl<P: Pack> Pack for Pair<P> {
    /// Pairs do not pair again.
    const STREAM_PAIRS: bool = false;

    #[inline(always)]
    fn call<K: PackKernel>(self, k: K) -> K::Output {
        // The backend's own entry, so that the kernel is compiled with its instruction set.
        self.0.call(Paired(k))
    }
    #[inline(always)]
    fn rsqrt(self, a: Self::F) -> Self::F {
        (self.0.rsqrt(a.0), self.0.rsqrt(a.1))
    }
    #[inline(always)]
    fn round(self, a: Self::F) -> Self::F {
        (self.0.round(a.0), self.0.round(a.1))
    }
    #[inline(always)]
    fn fma(self, a: Self::F, b: Self::F, c: Self::F) -> Self::F {
        (self.0.fma(a.0, b.0, c.0), self.0.fma(a.1, b.1, c.1))
    }
    #[inline(always)]
    fn fnma(self, a: Self::F, b: Self::F, c: Self::F) -> Self::F {
        (self.0.fnma(a.0, b.0, c.0), self.0.fnma(a.1, b.1, c.1))
    }
    #[inline(always)]
    fn and_not(self, a: Self::M, b: Self::M) -> Self::M {
        (self.0.and_not(a.0, b.0), self.0.and_not(a.1, b.1))
    }
    #[inline(always)]
    fn none(self) -> Self::M {
        (self.0.none(), self.0.none())
    }
    #[inline(always)]
    fn all_set(self) -> Self::M {
        (self.0.all_set(), self.0.all_set())
    }
    #[inline(always)]
    fn bitmask(self, m: Self::M) -> u32 {
        // Bit `i` of a `u32`: pairs of at most 16-lane backends.
        const { assert!(2 * P::WIDTH <= 32) };
        self.0.bitmask(m.0) | (self.0.bitmask(m.1) << P::WIDTH)
    }
    #[inline(always)]
    fn eq_i(self, a: Self::I, b: Self::I) -> Self::M {
        (self.0.eq_i(a.0, b.0), self.0.eq_i(a.1, b.1))
    }
    #[inline(always)]
    fn round_i(self, v: Self::F) -> Self::I {
        (self.0.round_i(v.0), self.0.round_i(v.1))
    }
    #[inline(always)]
    fn sub_i(self, a: Self::I, b: Self::I) -> Self::I {
        (self.0.sub_i(a.0, b.0), self.0.sub_i(a.1, b.1))
    }
    #[inline(always)]
    fn and_i(self, a: Self::I, b: Self::I) -> Self::I {
        (self.0.and_i(a.0, b.0), self.0.and_i(a.1, b.1))
    }
    #[inline(always)]
    fn or_i(self, a: Self::I, b: Self::I) -> Self::I {
        (self.0.or_i(a.0, b.0), self.0.or_i(a.1, b.1))
    }
    #[inline(always)]
    fn shl_n<const N: i32>(self, a: Self::I) -> Self::I {
        (self.0.shl_n::<N>(a.0), self.0.shl_n::<N>(a.1))
    }
    #[inline(always)]
    fn shr_n<const N: i32>(self, a: Self::I) -> Self::I {
        (self.0.shr_n::<N>(a.0), self.0.shr_n::<N>(a.1))
    }
    #[inline(always)]
    fn tally(self, n: u64) {
        self.0.tally(n);
    }
    #[inline(always)]
    fn as_one_op<R>(self, f: impl FnOnce() -> R) -> R {
        self.0.as_one_op(f)
    }
}
