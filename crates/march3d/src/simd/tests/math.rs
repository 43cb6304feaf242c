//! The polynomial math against double precision, on every backend.

use super::super::{Pack, PackKernel};
use super::{WIDEST, on_every_backend, pad};
use crate::math;

// ---------------------------------------------------------------------------------------
// Polynomial math against double precision.

/// A function of `math`.
#[derive(Clone, Copy, Debug, PartialEq)]
enum MathFn {
    Exp,
    Exp2,
    Log,
    Log2,
    Sin,
    Cos,
    /// `sin_cos`, its sine (`false`) or cosine (`true`).
    SinCos(bool),
    /// `pow(x, y)` with `y` from the second column.
    Pow,
}

/// Evaluates one function of `math` over `xs` (and `ys` for `pow`) on a backend.
#[derive(Clone)]
struct MathKernel<'a> {
    f: MathFn,
    xs: &'a [f32],
    ys: &'a [f32],
}

impl PackKernel for MathKernel<'_> {
    type Output = Vec<f32>;

    #[inline(always)]
    fn run<P: Pack>(self, p: P) -> Vec<f32> {
        let w = P::WIDTH;
        let mut out = vec![0.0; self.xs.len()];
        for (k, o) in out.chunks_exact_mut(w).enumerate() {
            let r = k * w..(k + 1) * w;
            let x = p.load(&self.xs[r.clone()]);
            let v = match self.f {
                MathFn::Exp => math::exp(p, x),
                MathFn::Exp2 => math::exp2(p, x),
                MathFn::Log => math::log(p, x),
                MathFn::Log2 => math::log2(p, x),
                MathFn::Sin => math::sin(p, x),
                MathFn::Cos => math::cos(p, x),
                MathFn::SinCos(second) => {
                    let (s, c) = math::sin_cos(p, x);
                    if second { c } else { s }
                }
                MathFn::Pow => math::pow(p, x, p.load(&self.ys[r])),
            };
            p.store(v, o);
        }
        out
    }
}

/// The value in double precision.
fn exact(f: MathFn, x: f32, y: f32) -> f64 {
    let x = x as f64;
    match f {
        MathFn::Exp => x.exp(),
        MathFn::Exp2 => x.exp2(),
        MathFn::Log => x.ln(),
        MathFn::Log2 => x.log2(),
        MathFn::Sin | MathFn::SinCos(false) => x.sin(),
        MathFn::Cos | MathFn::SinCos(true) => x.cos(),
        MathFn::Pow => x.powf(y as f64),
    }
}

/// The spacing of `f32` values at `v` (at least the smallest subnormal).
fn ulp(v: f64) -> f64 {
    let a = (v.abs() as f32).abs();
    if !a.is_finite() {
        return f64::INFINITY;
    }
    let next = f32::from_bits(a.to_bits() + 1);
    (next as f64 - a as f64).max(f64::from(f32::from_bits(1)))
}

/// The largest error of `f` on every backend over `xs`, in ulp of the exact value, with
/// the input where it occurs.
fn max_ulp_error(f: MathFn, xs: &[f32], ys: &[f32]) -> Vec<(&'static str, f64, f32)> {
    let len = xs.len();
    let ys = if ys.is_empty() { xs } else { ys };
    values(f, xs, ys)
        .into_iter()
        .map(|(name, got)| {
            let mut worst = (0.0f64, 0.0f32);
            for ((&x, &y), &g) in xs.iter().zip(ys).zip(&got[..len]) {
                let e = exact(f, x, y);
                let err = (g as f64 - e).abs() / ulp(e);
                assert!(!err.is_nan(), "{name} {f:?}({x:e}) = {g:e}, exact {e:e}");
                if err > worst.0 {
                    worst = (err, x);
                }
            }
            (name, worst.0, worst.1)
        })
        .collect()
}

/// `n` evenly spaced values over [lo, hi].
fn sweep(lo: f32, hi: f32, n: usize) -> Vec<f32> {
    (0..n)
        .map(|i| lo + (hi - lo) * (i as f64 / (n - 1) as f64) as f32)
        .collect()
}

/// Every `stride`-th positive normal float.
fn normals(stride: u32) -> Vec<f32> {
    (0x0080_0000..0x7f80_0000u32)
        .step_by(stride as usize)
        .map(f32::from_bits)
        .collect()
}

fn assert_within(f: MathFn, xs: &[f32], bound: f64) {
    for (backend, err, at) in max_ulp_error(f, xs, &[]) {
        eprintln!("{backend:>8} {f:?}: max error {err:.3} ulp at {at:e}");
        assert!(
            err <= bound,
            "{backend} {f:?}: {err} ulp at {at:e} (bound {bound})"
        );
    }
}

#[test]
fn exp_is_within_one_and_a_half_ulp_down_into_the_subnormals() {
    let mut xs = sweep(-87.0, 88.7, 1_000_001);
    xs.extend(sweep(-1.0, 1.0, 200_001));
    xs.extend(sweep(-104.0, -87.0, 100_001));
    assert_within(MathFn::Exp, &xs, 1.5);
    let mut xs = sweep(-126.0, 127.99, 1_000_001);
    xs.extend(sweep(-1.0, 1.0, 200_001));
    xs.extend(sweep(-150.0, -126.0, 100_001));
    assert_within(MathFn::Exp2, &xs, 1.5);
}

#[test]
fn log_is_within_two_and_a_half_ulp_over_the_positive_normals() {
    let mut xs = normals(1021);
    xs.extend(sweep(0.5, 2.0, 500_001));
    assert_within(MathFn::Log, &xs, 1.5);
    assert_within(MathFn::Log2, &xs, 2.5);
}

#[test]
fn sin_and_cos_are_within_three_ulp_up_to_8192() {
    let mut xs = sweep(-8192.0, 8192.0, 1_000_001);
    xs.extend(sweep(-7.0, 7.0, 500_001));
    // Floats next to multiples of pi/2, where the reduction cancels most digits.
    for k in -5215..=5215 {
        let c = (k as f64 * std::f64::consts::FRAC_PI_2) as f32;
        let b = c.to_bits();
        xs.extend([c, f32::from_bits(b + 1), f32::from_bits(b.wrapping_sub(1))]);
    }
    xs.retain(|x| x.abs() <= 8192.0);
    for f in [
        MathFn::Sin,
        MathFn::Cos,
        MathFn::SinCos(false),
        MathFn::SinCos(true),
    ] {
        assert_within(f, &xs, 3.0);
    }
}

#[test]
fn pow_error_grows_only_with_the_exponent_it_computes() {
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    for x in sweep(1e-3, 1e3, 1001) {
        for y in sweep(-4.0, 4.0, 201) {
            xs.push(x);
            ys.push(y);
        }
    }
    // Specular highlights: cosines raised to the Phong exponent.
    for x in sweep(0.0, 1.0, 1001) {
        for y in [1.0, 8.0, 15.0, 32.0, 64.0] {
            xs.push(x);
            ys.push(y);
        }
    }
    for (backend, got) in values(MathFn::Pow, &xs, &ys) {
        let mut worst = 0.0f64;
        for ((&x, &y), &g) in xs.iter().zip(&ys).zip(&got) {
            let e = exact(MathFn::Pow, x, y);
            let err = (g as f64 - e).abs() / ulp(e);
            // log2's error is multiplied by |t| = |y log2 x| in the result's exponent.
            let t = (y as f64 * (x as f64).log2()).abs();
            assert!(
                err <= 2.0 + 1.5 * t || e < f32::MIN_POSITIVE as f64,
                "{backend} pow({x:e}, {y:e}) = {g:e}: {err} ulp, exact {e:e}"
            );
            worst = worst.max(err / (1.0 + t));
        }
        eprintln!("{backend:>8} Pow: max error {worst:.3} ulp per unit of |y log2 x| + 1");
    }
}

/// `f` at the given points on every backend.
fn values(f: MathFn, xs: &[f32], ys: &[f32]) -> Vec<(&'static str, Vec<f32>)> {
    let n = xs.len();
    // Padding with ones keeps every function's padding lanes ordinary.
    let padded = |v: &[f32]| {
        let mut v = v.to_vec();
        v.resize(n.next_multiple_of(WIDEST), 1.0);
        v
    };
    let (xs, ys) = (padded(xs), padded(ys));
    let k = MathKernel {
        f,
        xs: &xs,
        ys: &ys,
    };
    on_every_backend(k)
        .into_iter()
        .map(|(name, _, mut v)| {
            v.truncate(n);
            (name, v)
        })
        .collect()
}

#[test]
fn math_edge_cases() {
    let inf = f32::INFINITY;
    let nan = f32::NAN;
    let check = |f: MathFn, xs: &[f32], ys: &[f32], want: &[f32]| {
        for (backend, got) in values(f, xs, ys) {
            for ((x, g), w) in xs.iter().zip(&got).zip(want) {
                let ok = (g.is_nan() && w.is_nan()) || g.to_bits() == w.to_bits();
                assert!(ok, "{backend} {f:?}({x:e}) = {g:e}, want {w:e}");
            }
        }
    };
    check(
        MathFn::Exp,
        &[0.0, inf, -inf, nan, 88.8, -104.0, -110.0, 1e30, -1e30],
        &[],
        &[1.0, inf, 0.0, nan, inf, 0.0, 0.0, inf, 0.0],
    );
    check(
        MathFn::Exp2,
        &[0.0, 1.0, 10.0, -3.0, inf, -inf, nan, 128.0, -149.0, -151.0],
        &[],
        &[
            1.0,
            2.0,
            1024.0,
            0.125,
            inf,
            0.0,
            nan,
            inf,
            f32::from_bits(1),
            0.0,
        ],
    );
    check(
        MathFn::Log,
        &[1.0, inf, -1.0, nan, -inf],
        &[],
        &[0.0, inf, nan, nan, nan],
    );
    check(
        MathFn::Log2,
        &[1.0, 2.0, 0.25, 1024.0, inf, -2.0],
        &[],
        &[0.0, 1.0, -2.0, 10.0, inf, nan],
    );
    check(
        MathFn::Sin,
        &[0.0, inf, -inf, nan],
        &[],
        &[0.0, nan, nan, nan],
    );
    check(MathFn::Cos, &[0.0, inf, nan], &[], &[1.0, nan, nan]);
    check(
        MathFn::Pow,
        &[0.0, -1.0, -8.0, 2.0, 4.0, 1.0],
        &[2.0, 2.0, 1.0 / 3.0, 0.0, 0.5, 7.5],
        &[0.0, 0.0, 0.0, 1.0, 2.0, 1.0],
    );
    // Zero and subnormals: large and negative, finite.
    for f in [MathFn::Log, MathFn::Log2] {
        for (backend, got) in values(f, &[0.0, 1e-40, f32::from_bits(1)], &[]) {
            for g in got {
                assert!(g.is_finite() && g < -80.0, "{backend} {f:?} of tiny: {g}");
            }
        }
    }
}

#[test]
fn sin_cos_equals_sin_and_cos() {
    let xs = sweep(-100.0, 100.0, 10_001);
    let s = values(MathFn::Sin, &xs, &[]);
    let c = values(MathFn::Cos, &xs, &[]);
    let ss = values(MathFn::SinCos(false), &xs, &[]);
    let cc = values(MathFn::SinCos(true), &xs, &[]);
    for i in 0..s.len() {
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&s[i].1), bits(&ss[i].1), "{}", s[i].0);
        assert_eq!(bits(&c[i].1), bits(&cc[i].1), "{}", c[i].0);
    }
}

#[test]
fn math_results_agree_across_backends() {
    // Same polynomial, same operation order: lanes differ at most by the fused rounding.
    let xs = sweep(-50.0, 50.0, 100_001);
    let pos: Vec<f32> = xs.iter().map(|x| x.abs() + 1e-3).collect();
    for (f, input) in [
        (MathFn::Exp, &xs),
        (MathFn::Sin, &xs),
        (MathFn::Cos, &xs),
        (MathFn::Log, &pos),
    ] {
        let runs = values(f, input, &[]);
        let (base, rest) = runs.split_first().expect("the scalar backend always runs");
        for (backend, got) in rest {
            for ((x, a), b) in input.iter().zip(&base.1).zip(got) {
                let err = (*a as f64 - *b as f64).abs() / ulp(*a as f64);
                assert!(
                    err <= 2.0,
                    "{f:?}({x:e}): {} {a:e} vs {backend} {b:e}",
                    base.0
                );
            }
        }
    }
}

/// Runs a [`MathKernel`] `reps` times and returns the seconds it took.
#[derive(Clone)]
struct Timed<'a>(MathKernel<'a>, usize);

impl PackKernel for Timed<'_> {
    type Output = f64;

    #[inline(always)]
    fn run<P: Pack>(self, p: P) -> f64 {
        let t = std::time::Instant::now();
        for _ in 0..self.1 {
            std::hint::black_box(self.0.clone().run(p));
        }
        t.elapsed().as_secs_f64()
    }
}

/// Throughput of the polynomial math per backend against the standard library; a
/// measurement, not a check (`cargo test --release -- --ignored --nocapture math_throughput`).
#[test]
#[ignore = "a measurement; prints nanoseconds per value"]
fn math_throughput() {
    use std::hint::black_box;
    let xs = pad(sweep(0.001, 80.0, 1 << 16));
    let ys = vec![15.0; xs.len()];
    let reps = 50;
    let per_value = |secs: f64| secs * 1e9 / (reps * xs.len()) as f64;
    type StdFn = fn(f32) -> f32;
    let fns: [(MathFn, StdFn); 5] = [
        (MathFn::Exp, f32::exp),
        (MathFn::Log, f32::ln),
        (MathFn::Sin, f32::sin),
        (MathFn::Cos, f32::cos),
        (MathFn::Pow, |x| x.powf(15.0)),
    ];
    for (f, std_fn) in fns {
        let t = std::time::Instant::now();
        for _ in 0..reps {
            let v: Vec<f32> = xs.iter().map(|&x| std_fn(black_box(x))).collect();
            black_box(v);
        }
        let mut line = format!("{f:?}: std {:.2}", per_value(t.elapsed().as_secs_f64()));
        let k = MathKernel {
            f,
            xs: &xs,
            ys: &ys,
        };
        for (name, _, secs) in on_every_backend(Timed(k, reps)) {
            line += &format!(", {name} {:.2}", per_value(secs));
        }
        eprintln!("{line} ns/value");
    }
}
