//! Polynomial `exp`, `log`, `pow`, `sin` and `cos` in single precision, written once over
//! any [`Pack`] so that every backend of the tracer computes them in its own lanes.
//!
//! Each function reduces its argument to a short interval (by powers of two, or by
//! multiples of pi/2 in the Cody-Waite manner) and evaluates a minimax polynomial there with
//! multiply-adds. Each public function counts as one operation on the counting backend
//! ([`Pack::as_one_op`]), the reference paper's convention for math-library calls. The
//! closures handed to `as_one_op` are `#[inline(always)]`: without it they are compiled
//! outside the backend's instruction set (see [`PackKernel`](super::simd::PackKernel)).
//!
//! Measured accuracy against double precision over dense sweeps (the tests check these
//! bounds, with a little margin, on every backend, fused and unfused):
//!
//! * `exp` on [-104, 88.7] (subnormal results included): at most 1.0 ulp; `exp2` on
//!   [-150, 128): at most 1.0 ulp.
//! * `log` over the positive normals: at most 0.85 ulp; `log2`: 1.0 ulp with fused
//!   multiply-adds, 1.9 ulp without.
//! * `sin` and `cos` for |x| <= 8192, including the floats next to multiples of pi/2: at
//!   most 2.3 ulp. Beyond that the reduction loses accuracy gradually (its products are
//!   exact up to |x| of about 12800); beyond 2^24 the results mean nothing.
//! * `pow(x, y)`: `log2`'s error is multiplied by `|y log2 x|` in the result: at most
//!   1.4 ulp per unit of `1 + |y log2 x|`.
//!
//! Edge cases: `exp` gives +inf from 88.73 up and 0 from -103.3 down; `log` of 0 and of
//! subnormals gives about -88 (`log2` about -127) rather than -inf; `log` of negative
//! numbers and NaN gives NaN, of +inf +inf; `sin` and `cos` of infinities and NaN give
//! NaN; `pow` gives 0 for `x <= 0`.

use super::simd::Pack;

/// log2(e).
const LOG2_E: f32 = std::f32::consts::LOG2_E;
/// ln(2), split in two: a high part with few bits (so `n * LN2_HI` is exact for the
/// exponents that occur) and the rest.
const LN2_HI: f32 = 0.693_359_4;
const LN2_LO: f32 = -2.121_944_4e-4;

/// 2/pi.
const FRAC_2_PI: f32 = std::f32::consts::FRAC_2_PI;
/// pi/2 in four parts; the first three have 11 significant bits, so `q * PIO2_n` is exact
/// for |q| < 2^13 even without a fused multiply-add (|x| up to about 12800).
const PIO2_1: f32 = 1.570_312_5;
const PIO2_2: f32 = 4.837_513e-4;
const PIO2_3: f32 = 7.549_533_6e-8;
const PIO2_4: f32 = 2.563_344e-12;

/// `e^x`.
#[inline(always)]
pub fn exp<P: Pack>(p: P, x: P::F) -> P::F {
    p.as_one_op(
        #[inline(always)]
        || {
            // Beyond these the result is +inf or rounds to 0 anyway; the clamp keeps n in
            // [-150, 128] (NaN passes through).
            let x = clamp(p, x, -104.0, 89.0);
            let ni = p.round_i(p.mul(x, p.splat(LOG2_E)));
            let n = p.to_f32(ni);
            // Cody-Waite: x - n ln 2 in two steps keeps the reduced argument exact.
            let r = p.fnma(n, p.splat(LN2_HI), x);
            let r = p.fnma(n, p.splat(LN2_LO), r);
            scale(p, exp_poly(p, r), ni)
        },
    )
}

/// `2^x`.
#[inline(always)]
pub fn exp2<P: Pack>(p: P, x: P::F) -> P::F {
    p.as_one_op(
        #[inline(always)]
        || {
            let x = clamp(p, x, -151.0, 129.0);
            let ni = p.round_i(x);
            let n = p.to_f32(ni);
            // `x - n` is exact; scaling by ln 2 costs half an ulp of a number below 0.35.
            let r = p.mul(p.sub(x, n), p.splat(std::f32::consts::LN_2));
            scale(p, exp_poly(p, r), ni)
        },
    )
}

/// `x` limited to [lo, hi], NaN kept (the min/max rule returns the second operand on NaN).
#[inline(always)]
fn clamp<P: Pack>(p: P, x: P::F, lo: f32, hi: f32) -> P::F {
    p.max(p.splat(lo), p.min(p.splat(hi), x))
}

/// `e^r` for |r| <= ln(2)/2.
#[inline(always)]
fn exp_poly<P: Pack>(p: P, r: P::F) -> P::F {
    // e^r = 1 + (r + r^2 q(r)), q of degree 5 (Cephes' minimax), evaluated in two halves
    // for instruction-level parallelism.
    let r2 = p.mul(r, r);
    let a = p.fma(r, p.splat(1.987_569_1e-4), p.splat(1.398_199_9e-3));
    let a = p.fma(a, r, p.splat(8.333_452e-3));
    let b = p.fma(r, p.splat(4.166_579_6e-2), p.splat(1.666_666_6e-1));
    let b = p.fma(b, r, p.splat(0.5));
    let q = p.fma(a, p.mul(r2, r), b);
    p.add(p.fma(q, r2, r), p.splat(1.0))
}

/// `e 2^n` for n in [-151, 129], in two factors so that each is a normal power of two:
/// the product overflows to +inf or rounds into the subnormals as it should.
#[inline(always)]
fn scale<P: Pack>(p: P, e: P::F, n: P::I) -> P::F {
    // n1 = floor(n / 2) with a logical shift of a biased (non-negative) n.
    let n1 = p.sub_i(p.shr_n::<1>(p.add_i(n, p.splat_i(1024))), p.splat_i(512));
    let n2 = p.sub_i(n, n1);
    p.mul(p.mul(e, pow2(p, n1)), pow2(p, n2))
}

/// `2^k` for k in [-126, 127], from the exponent field.
#[inline(always)]
fn pow2<P: Pack>(p: P, k: P::I) -> P::F {
    p.int_bits(p.shl_n::<23>(p.add_i(k, p.splat_i(127))))
}

/// The natural logarithm, for `x > 0`.
#[inline(always)]
pub fn log<P: Pack>(p: P, x: P::F) -> P::F {
    p.as_one_op(
        #[inline(always)]
        || {
            let (e, f, lnf) = log_parts(p, x);
            // e ln 2 + ln(1 + f), with ln 2 split so the sum keeps its low bits.
            let y = p.fma(e, p.splat(LN2_LO), lnf);
            let y = p.add(f, y);
            let y = p.fma(e, p.splat(LN2_HI), y);
            log_special(p, x, y)
        },
    )
}

/// The base-2 logarithm, for `x > 0`.
#[inline(always)]
pub fn log2<P: Pack>(p: P, x: P::F) -> P::F {
    p.as_one_op(
        #[inline(always)]
        || {
            let (e, f, lnf) = log_parts(p, x);
            // log2(1 + f) = (f + lnf) log2(e), with f's product kept exact-ish by splitting the
            // constant's rounding error into a second multiply-add.
            const LOG2_E_LO: f32 = 1.925_963e-8;
            let s = p.add(f, lnf);
            let y = p.fma(s, p.splat(LOG2_E_LO), p.mul(lnf, p.splat(LOG2_E)));
            let y = p.fma(f, p.splat(LOG2_E), y);
            let y = p.add(e, y);
            log_special(p, x, y)
        },
    )
}

/// Splits `x = 2^e (1 + f)` with `1 + f` in [sqrt(1/2), sqrt(2)) and returns `(e, f,
/// ln(1 + f) - f)`.
#[inline(always)]
fn log_parts<P: Pack>(p: P, x: P::F) -> (P::F, P::F, P::F) {
    let bits = p.bits_int(x);
    // The mantissa with the exponent of 0.5: m in [0.5, 1).
    let m = p.int_bits(p.or_i(
        p.and_i(bits, p.splat_i(0x007f_ffff)),
        p.splat_i(0x3f00_0000),
    ));
    let e = p.to_f32(p.sub_i(
        p.shr_n::<23>(p.and_i(bits, p.splat_i(0x7f80_0000))),
        p.splat_i(126),
    ));
    // Below sqrt(1/2) use 2m and one exponent less, so that f is centred on 0.
    let small = p.lt(m, p.splat(std::f32::consts::FRAC_1_SQRT_2));
    let e = p.select(small, p.sub(e, p.splat(1.0)), e);
    let m = p.select(small, p.add(m, m), m);
    let f = p.sub(m, p.splat(1.0));
    // ln(1 + f) = f - f^2/2 + f^3 q(f), q of degree 8 (Cephes' minimax), by Estrin.
    let f2 = p.mul(f, f);
    let f4 = p.mul(f2, f2);
    let q01 = p.fma(f, p.splat(-2.499_999_4e-1), p.splat(3.333_333e-1));
    let q23 = p.fma(f, p.splat(-1.666_805_7e-1), p.splat(2.000_071_4e-1));
    let q45 = p.fma(f, p.splat(-1.242_014_1e-1), p.splat(1.424_932_3e-1));
    let q67 = p.fma(f, p.splat(-1.151_461e-1), p.splat(1.167_699_84e-1));
    let q03 = p.fma(q23, f2, q01);
    let q47 = p.fma(q67, f2, q45);
    let q = p.fma(p.splat(7.037_683_6e-2), f4, q47);
    let q = p.fma(q, f4, q03);
    let lnf = p.fnma(p.splat(0.5), f2, p.mul(p.mul(f2, f), q));
    (e, f, lnf)
}

/// NaN for negative or NaN arguments, +inf for +inf; `y` otherwise.
#[inline(always)]
fn log_special<P: Pack>(p: P, x: P::F, y: P::F) -> P::F {
    let y = p.select(p.gt(x, p.splat(f32::MAX)), p.splat(f32::INFINITY), y);
    p.select(p.ge(x, p.splat(0.0)), y, p.splat(f32::NAN))
}

/// `x^y` for `x > 0`, as `2^(y log2 x)`; 0 where `x <= 0`.
#[inline(always)]
pub fn pow<P: Pack>(p: P, x: P::F, y: P::F) -> P::F {
    p.as_one_op(
        #[inline(always)]
        || {
            let r = exp2(p, p.mul(y, log2(p, x)));
            p.select(p.gt(x, p.splat(0.0)), r, p.splat(0.0))
        },
    )
}

/// The sine.
#[inline(always)]
pub fn sin<P: Pack>(p: P, x: P::F) -> P::F {
    p.as_one_op(
        #[inline(always)]
        || {
            let (q, r) = reduce(p, x);
            let (s, c) = sin_cos_poly(p, r);
            quadrant(p, q, s, c)
        },
    )
}

/// The cosine.
#[inline(always)]
pub fn cos<P: Pack>(p: P, x: P::F) -> P::F {
    p.as_one_op(
        #[inline(always)]
        || {
            let (q, r) = reduce(p, x);
            let (s, c) = sin_cos_poly(p, r);
            // cos(x) = sin(x + pi/2): one quadrant on.
            quadrant(p, p.add_i(q, p.splat_i(1)), s, c)
        },
    )
}

/// The sine and the cosine, sharing the reduction and both polynomials.
#[inline(always)]
pub fn sin_cos<P: Pack>(p: P, x: P::F) -> (P::F, P::F) {
    p.as_one_op(
        #[inline(always)]
        || {
            let (q, r) = reduce(p, x);
            let (s, c) = sin_cos_poly(p, r);
            (
                quadrant(p, q, s, c),
                quadrant(p, p.add_i(q, p.splat_i(1)), s, c),
            )
        },
    )
}

/// `x = q pi/2 + r` with |r| <= pi/4 (Cody-Waite, four parts of pi/2).
#[inline(always)]
fn reduce<P: Pack>(p: P, x: P::F) -> (P::I, P::F) {
    let t = p.mul(x, p.splat(FRAC_2_PI));
    let q = p.round_i(t);
    let qf = p.to_f32(q);
    let r = p.fnma(qf, p.splat(PIO2_1), x);
    let r = p.fnma(qf, p.splat(PIO2_2), r);
    let r = p.fnma(qf, p.splat(PIO2_3), r);
    let r = p.fnma(qf, p.splat(PIO2_4), r);
    (q, r)
}

/// `(sin r, cos r)` for |r| <= pi/4 (Cephes' minimax polynomials in r^2).
#[inline(always)]
fn sin_cos_poly<P: Pack>(p: P, r: P::F) -> (P::F, P::F) {
    let z = p.mul(r, r);
    let s = p.fma(z, p.splat(-1.951_529_6e-4), p.splat(8.332_161e-3));
    let s = p.fma(s, z, p.splat(-1.666_665_5e-1));
    let s = p.fma(p.mul(s, z), r, r);
    let c = p.fma(z, p.splat(2.443_315_7e-5), p.splat(-1.388_731_6e-3));
    let c = p.fma(c, z, p.splat(4.166_664_6e-2));
    let c = p.fma(p.mul(c, z), z, p.fnma(p.splat(0.5), z, p.splat(1.0)));
    (s, c)
}

/// sin of `q pi/2 + r` from `s = sin r`, `c = cos r`: quadrant `q mod 4` picks the
/// polynomial (odd quadrants take the cosine) and the sign (quadrants 2 and 3 negate).
#[inline(always)]
fn quadrant<P: Pack>(p: P, q: P::I, s: P::F, c: P::F) -> P::F {
    let one = p.splat_i(1);
    let two = p.splat_i(2);
    let v = p.select(p.eq_i(p.and_i(q, one), one), c, s);
    p.select(p.eq_i(p.and_i(q, two), two), p.neg(v), v)
}
