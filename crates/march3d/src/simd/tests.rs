//! One conformance suite for every lane backend this machine has: each operation applied
//! lane by lane to awkward inputs and compared with plain `f32` arithmetic, the polynomial
//! math compared with double precision over dense ranges, and the counting backend's
//! tallies.

use super::count::{self, Counting};
use super::{Pack, PackKernel, TRACER_BACKENDS};
use crate::math;
use craterfield_core::backend::{BACKEND_ENV, Backend, BackendError};
use craterfield_core::simd::{Lanes, Scalar};

/// Floats that break careless lane code: signed zeros, infinities, NaN, subnormals, the
/// extremes, halfway cases for rounding, and ordinary values.
fn float_inputs() -> Vec<f32> {
    let mut v = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -0.5,
        1.5,
        2.5,
        -2.5,
        0.3,
        -0.3,
        3.75,
        -7.25,
        1e-3,
        123.456,
        -98765.43,
        1e20,
        -3e30,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        1e-40,
        -1e-42,
        f32::from_bits(1),
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        8_388_607.5,
        16_777_217.0,
        2_147_483_520.0,
        -2_147_483_648.0,
        std::f32::consts::PI,
        -std::f32::consts::E,
    ];
    v.push(f32::from_bits(0x7fc0_1234));
    v
}

/// 32-bit integers for the integer lanes.
fn int_inputs() -> Vec<i32> {
    vec![
        0,
        1,
        -1,
        2,
        7,
        -8,
        255,
        0x3f80_0000,
        0x7f80_0000,
        0x007f_ffff,
        i32::MAX,
        i32::MIN,
        i32::MIN + 1,
        123_456_789,
        -987_654_321,
        0x5555_5555,
    ]
}

/// `v` padded with zeros to a multiple of 8 lanes (a multiple of every backend's width).
fn pad<T: Copy + Default>(mut v: Vec<T>) -> Vec<T> {
    while !v.len().is_multiple_of(8) {
        v.push(T::default());
    }
    v
}

/// Every pair `(a, b)` of `xs`, as two padded columns.
fn pairs<T: Copy + Default>(xs: &[T]) -> (Vec<T>, Vec<T>) {
    let (a, b) = xs
        .iter()
        .flat_map(|&a| xs.iter().map(move |&b| (a, b)))
        .unzip();
    (pad(a), pad(b))
}

/// Every triple of `xs`, as three padded columns.
fn triples(xs: &[f32]) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
    let mut cols = (Vec::new(), Vec::new(), Vec::new());
    for &a in xs {
        for &b in xs {
            for &c in xs {
                cols.0.push(a);
                cols.1.push(b);
                cols.2.push(c);
            }
        }
    }
    (pad(cols.0), pad(cols.1), pad(cols.2))
}

/// The inputs of the operation suite.
#[derive(Clone)]
struct Inputs {
    x: Vec<f32>,
    pa: Vec<f32>,
    pb: Vec<f32>,
    ta: Vec<f32>,
    tb: Vec<f32>,
    tc: Vec<f32>,
    /// Floats inside the `i32` range, for `round_i`.
    xr: Vec<f32>,
    i: Vec<i32>,
    ia: Vec<i32>,
    ib: Vec<i32>,
}

impl Inputs {
    fn new() -> Inputs {
        let f = float_inputs();
        let (pa, pb) = pairs(&f);
        let (ta, tb, tc) = triples(&f);
        let xr = f
            .iter()
            .copied()
            .filter(|x| x.abs() < 2_147_483_520.0)
            .collect();
        let ints = int_inputs();
        let (ia, ib) = pairs(&ints);
        Inputs {
            x: pad(f),
            pa,
            pb,
            ta,
            tb,
            tc,
            xr: pad(xr),
            i: pad(ints),
            ia,
            ib,
        }
    }
}

/// One named column of results, as bits.
type Column = (&'static str, Vec<u32>);

/// Applies every lane operation to the inputs on a backend.
#[derive(Clone)]
struct OpsKernel(Inputs);

fn map1<P: Pack>(p: P, a: &[f32], f: impl Fn(P::F) -> P::F) -> Vec<u32> {
    let mut out = vec![0.0; a.len()];
    for (x, o) in a.chunks_exact(P::WIDTH).zip(out.chunks_exact_mut(P::WIDTH)) {
        p.store(f(p.load(x)), o);
    }
    out.into_iter().map(f32::to_bits).collect()
}

fn map2<P: Pack>(p: P, a: &[f32], b: &[f32], f: impl Fn(P::F, P::F) -> P::F) -> Vec<u32> {
    let mut out = vec![0.0; a.len()];
    let w = P::WIDTH;
    for (k, o) in out.chunks_exact_mut(w).enumerate() {
        let r = k * w..(k + 1) * w;
        p.store(f(p.load(&a[r.clone()]), p.load(&b[r])), o);
    }
    out.into_iter().map(f32::to_bits).collect()
}

fn map3<P: Pack>(
    p: P,
    (a, b, c): (&[f32], &[f32], &[f32]),
    f: impl Fn(P::F, P::F, P::F) -> P::F,
) -> Vec<u32> {
    let mut out = vec![0.0; a.len()];
    let w = P::WIDTH;
    for (k, o) in out.chunks_exact_mut(w).enumerate() {
        let r = k * w..(k + 1) * w;
        let v = f(p.load(&a[r.clone()]), p.load(&b[r.clone()]), p.load(&c[r]));
        p.store(v, o);
    }
    out.into_iter().map(f32::to_bits).collect()
}

/// A mask as 1.0 / 0.0 lanes.
fn mask_lanes<P: Pack>(p: P, a: &[f32], b: &[f32], f: impl Fn(P::F, P::F) -> P::M) -> Vec<u32> {
    map2(p, a, b, |x, y| {
        p.select(f(x, y), p.splat(1.0), p.splat(0.0))
    })
}

/// Per lane: bit `lane` of the chunk's `bitmask`, then the chunk's `count` and `any`, so a
/// reference that knows the width can check them.
fn mask_summaries<P: Pack>(p: P, a: &[f32], b: &[f32]) -> [Vec<u32>; 3] {
    let w = P::WIDTH;
    let mut bits = Vec::new();
    let mut counts = Vec::new();
    let mut anys = Vec::new();
    for k in 0..a.len() / w {
        let r = k * w..(k + 1) * w;
        let m = p.lt(p.load(&a[r.clone()]), p.load(&b[r]));
        let bm = p.bitmask(m);
        assert!(w == 32 || bm >> w == 0, "bitmask has bits beyond the lanes");
        for lane in 0..w {
            bits.push((bm >> lane) & 1);
            counts.push(p.count(m));
            anys.push(p.any(m) as u32);
        }
    }
    [bits, counts, anys]
}

fn map_i2<P: Pack>(p: P, a: &[i32], b: &[i32], f: impl Fn(P::I, P::I) -> P::I) -> Vec<u32> {
    let mut out = vec![0; a.len()];
    let w = P::WIDTH;
    for (k, o) in out.chunks_exact_mut(w).enumerate() {
        let r = k * w..(k + 1) * w;
        p.store_i(f(p.load_i(&a[r.clone()]), p.load_i(&b[r])), o);
    }
    out.into_iter().map(|v| v as u32).collect()
}

fn map_fi<P: Pack>(p: P, a: &[f32], f: impl Fn(P::F) -> P::I) -> Vec<u32> {
    let mut out = vec![0; a.len()];
    for (x, o) in a.chunks_exact(P::WIDTH).zip(out.chunks_exact_mut(P::WIDTH)) {
        p.store_i(f(p.load(x)), o);
    }
    out.into_iter().map(|v| v as u32).collect()
}

fn map_if<P: Pack>(p: P, a: &[i32], f: impl Fn(P::I) -> P::F) -> Vec<u32> {
    let mut out = vec![0.0; a.len()];
    for (x, o) in a.chunks_exact(P::WIDTH).zip(out.chunks_exact_mut(P::WIDTH)) {
        p.store(f(p.load_i(x)), o);
    }
    out.into_iter().map(f32::to_bits).collect()
}

impl PackKernel for OpsKernel {
    type Output = Vec<Column>;

    fn run<P: Pack>(self, p: P) -> Vec<Column> {
        let n = &self.0;
        let (x, a, b) = (&n.x[..], &n.pa[..], &n.pb[..]);
        let t = (&n.ta[..], &n.tb[..], &n.tc[..]);
        let (ia, ib) = (&n.ia[..], &n.ib[..]);
        let one = p.splat(1.0);
        let zero = p.splat(0.0);
        let as_f = |m: P::M| p.select(m, one, zero);
        let [bitmask, count, any] = mask_summaries(p, a, b);
        vec![
            ("load/store", map1(p, x, |v| v)),
            ("splat", {
                let mut out = vec![0.0; x.len() * P::WIDTH];
                for (&v, o) in x.iter().zip(out.chunks_exact_mut(P::WIDTH)) {
                    p.store(p.splat(v), o);
                }
                out.chunks_exact(P::WIDTH)
                    .map(|c| {
                        assert!(c.iter().all(|l| l.to_bits() == c[0].to_bits()));
                        c[0].to_bits()
                    })
                    .collect()
            }),
            ("neg", map1(p, x, |v| p.neg(v))),
            ("abs", map1(p, x, |v| p.abs(v))),
            ("floor", map1(p, x, |v| p.floor(v))),
            ("round", map1(p, x, |v| p.round(v))),
            ("sqrt", map1(p, x, |v| p.sqrt(v))),
            ("add", map2(p, a, b, |u, v| p.add(u, v))),
            ("sub", map2(p, a, b, |u, v| p.sub(u, v))),
            ("mul", map2(p, a, b, |u, v| p.mul(u, v))),
            ("div", map2(p, a, b, |u, v| p.div(u, v))),
            ("min", map2(p, a, b, |u, v| p.min(u, v))),
            ("max", map2(p, a, b, |u, v| p.max(u, v))),
            ("fma", map3(p, t, |u, v, w| p.fma(u, v, w))),
            ("fnma", map3(p, t, |u, v, w| p.fnma(u, v, w))),
            ("lt", mask_lanes(p, a, b, |u, v| p.lt(u, v))),
            ("le", mask_lanes(p, a, b, |u, v| p.le(u, v))),
            ("gt", mask_lanes(p, a, b, |u, v| p.gt(u, v))),
            ("ge", mask_lanes(p, a, b, |u, v| p.ge(u, v))),
            ("select", map2(p, a, b, |u, v| p.select(p.lt(u, v), v, u))),
            (
                "and",
                map2(p, a, b, |u, v| as_f(p.and(p.lt(u, v), p.ge(u, zero)))),
            ),
            (
                "or",
                map2(p, a, b, |u, v| as_f(p.or(p.lt(u, v), p.ge(u, zero)))),
            ),
            (
                "and_not",
                map2(p, a, b, |u, v| as_f(p.and_not(p.lt(u, v), p.ge(u, zero)))),
            ),
            ("not", map2(p, a, b, |u, v| as_f(p.not(p.lt(u, v))))),
            ("none", map1(p, x, |_| as_f(p.none()))),
            ("all_set", map1(p, x, |_| as_f(p.all_set()))),
            ("bitmask", bitmask),
            ("count", count),
            ("any", any),
            ("bits", map_fi(p, x, |v| p.bits_int(v))),
            ("from_bits", map_if(p, &n.i, |v| p.int_bits(v))),
            ("round_i", map_fi(p, &n.xr, |v| p.round_i(v))),
            ("to_f32", map_if(p, &n.i, |v| p.to_f32(v))),
            ("splat_i", {
                let mut out = vec![0; n.i.len()];
                for (&v, o) in n.i.iter().zip(out.iter_mut()) {
                    let mut lanes = vec![0; P::WIDTH];
                    p.store_i(p.splat_i(v), &mut lanes);
                    assert!(lanes.iter().all(|&l| l == lanes[0]));
                    *o = lanes[0] as u32;
                }
                out
            }),
            ("eq_i", {
                let sel = |u, v| p.select_i(p.eq_i(u, v), p.splat_i(1), p.splat_i(0));
                map_i2(p, ia, ib, sel)
            }),
            ("select_i", {
                let odd = |u| p.eq_i(p.and_i(u, p.splat_i(1)), p.splat_i(1));
                map_i2(p, ia, ib, |u, v| p.select_i(odd(u), u, v))
            }),
            ("add_i", map_i2(p, ia, ib, |u, v| p.add_i(u, v))),
            ("sub_i", map_i2(p, ia, ib, |u, v| p.sub_i(u, v))),
            ("and_i", map_i2(p, ia, ib, |u, v| p.and_i(u, v))),
            ("or_i", map_i2(p, ia, ib, |u, v| p.or_i(u, v))),
            ("shl_i 0", map_i2(p, ia, ib, |u, _| p.shl_n::<0>(u))),
            ("shl_i 1", map_i2(p, ia, ib, |u, _| p.shl_n::<1>(u))),
            ("shl_i 23", map_i2(p, ia, ib, |u, _| p.shl_n::<23>(u))),
            ("shl_i 31", map_i2(p, ia, ib, |u, _| p.shl_n::<31>(u))),
            ("shr_i 0", map_i2(p, ia, ib, |u, _| p.shr_n::<0>(u))),
            ("shr_i 1", map_i2(p, ia, ib, |u, _| p.shr_n::<1>(u))),
            ("shr_i 23", map_i2(p, ia, ib, |u, _| p.shr_n::<23>(u))),
            ("shr_i 31", map_i2(p, ia, ib, |u, _| p.shr_n::<31>(u))),
        ]
    }
}

/// The same columns from plain `f32`/`i32` arithmetic, for a backend `width` lanes wide.
// Negated comparisons are the point: a mask's `not` is true on NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn reference(n: &Inputs, width: usize) -> Vec<Column> {
    let f1 = |f: fn(f32) -> f32| n.x.iter().map(|&v| f(v).to_bits()).collect::<Vec<_>>();
    let f2 = |f: fn(f32, f32) -> f32| {
        n.pa.iter()
            .zip(&n.pb)
            .map(|(&u, &v)| f(u, v).to_bits())
            .collect::<Vec<_>>()
    };
    let b2 = |f: fn(f32, f32) -> bool| {
        n.pa.iter()
            .zip(&n.pb)
            .map(|(&u, &v)| if f(u, v) { 1.0f32 } else { 0.0 }.to_bits())
            .collect::<Vec<_>>()
    };
    let i2 = |f: fn(i32, i32) -> i32| {
        n.ia.iter()
            .zip(&n.ib)
            .map(|(&u, &v)| f(u, v) as u32)
            .collect::<Vec<_>>()
    };
    let lt: Vec<u32> =
        n.pa.iter()
            .zip(&n.pb)
            .map(|(u, v)| (u < v) as u32)
            .collect();
    let count: Vec<u32> = lt
        .chunks(width)
        .flat_map(|c| {
            let s = c.iter().sum::<u32>();
            std::iter::repeat_n(s, c.len())
        })
        .collect();
    let any = count.iter().map(|&c| (c > 0) as u32).collect();
    let fma_placeholder = Vec::new();
    vec![
        ("load/store", f1(|v| v)),
        ("splat", f1(|v| v)),
        ("neg", f1(|v| -v)),
        ("abs", f1(f32::abs)),
        ("floor", f1(f32::floor)),
        ("round", f1(f32::round_ties_even)),
        ("sqrt", f1(f32::sqrt)),
        ("add", f2(|u, v| u + v)),
        ("sub", f2(|u, v| u - v)),
        ("mul", f2(|u, v| u * v)),
        ("div", f2(|u, v| u / v)),
        ("min", f2(|u, v| if u < v { u } else { v })),
        ("max", f2(|u, v| if u > v { u } else { v })),
        ("fma", fma_placeholder.clone()),
        ("fnma", fma_placeholder),
        ("lt", b2(|u, v| u < v)),
        ("le", b2(|u, v| u <= v)),
        ("gt", b2(|u, v| u > v)),
        ("ge", b2(|u, v| u >= v)),
        ("select", f2(|u, v| if u < v { v } else { u })),
        ("and", b2(|u, v| u < v && u >= 0.0)),
        ("or", b2(|u, v| u < v || u >= 0.0)),
        ("and_not", b2(|u, v| u < v && !(u >= 0.0))),
        ("not", b2(|u, v| !(u < v))),
        ("none", f1(|_| 0.0)),
        ("all_set", f1(|_| 1.0)),
        ("bitmask", lt),
        ("count", count),
        ("any", any),
        ("bits", n.x.iter().map(|v| v.to_bits()).collect()),
        ("from_bits", n.i.iter().map(|&v| v as u32).collect()),
        (
            "round_i",
            n.xr.iter()
                .map(|v| v.round_ties_even() as i32 as u32)
                .collect(),
        ),
        (
            "to_f32",
            n.i.iter().map(|&v| (v as f32).to_bits()).collect(),
        ),
        ("splat_i", n.i.iter().map(|&v| v as u32).collect()),
        ("eq_i", i2(|u, v| (u == v) as i32)),
        ("select_i", i2(|u, v| if u & 1 == 1 { u } else { v })),
        ("add_i", i2(i32::wrapping_add)),
        ("sub_i", i2(i32::wrapping_sub)),
        ("and_i", i2(|u, v| u & v)),
        ("or_i", i2(|u, v| u | v)),
        ("shl_i 0", i2(|u, _| u)),
        ("shl_i 1", i2(|u, _| ((u as u32) << 1) as i32)),
        ("shl_i 23", i2(|u, _| ((u as u32) << 23) as i32)),
        ("shl_i 31", i2(|u, _| ((u as u32) << 31) as i32)),
        ("shr_i 0", i2(|u, _| u)),
        ("shr_i 1", i2(|u, _| ((u as u32) >> 1) as i32)),
        ("shr_i 23", i2(|u, _| ((u as u32) >> 23) as i32)),
        ("shr_i 31", i2(|u, _| ((u as u32) >> 31) as i32)),
    ]
}

/// Equal bits, or both NaN (payloads and NaN signs are not part of the contract).
fn same_float(a: u32, b: u32) -> bool {
    let (fa, fb) = (f32::from_bits(a), f32::from_bits(b));
    a == b || (fa.is_nan() && fb.is_nan())
}

/// A backend's `fma`/`fnma` column equals, lane by lane, either the fused or the unfused
/// result.
fn check_fused(backend: &str, n: &Inputs, name: &str, got: &[u32]) {
    let negate = name == "fnma";
    for (k, &g) in got.iter().enumerate() {
        let (a, b, c) = (n.ta[k], n.tb[k], n.tc[k]);
        let (fused, unfused) = if negate {
            ((-a).mul_add(b, c), c - a * b)
        } else {
            (a.mul_add(b, c), a * b + c)
        };
        assert!(
            same_float(g, fused.to_bits()) || same_float(g, unfused.to_bits()),
            "{backend} {name}({a:e}, {b:e}, {c:e}) = {:e}, expected {fused:e} (fused) or \
             {unfused:e}",
            f32::from_bits(g)
        );
    }
}

/// Checks one backend's columns against the reference.
fn check_columns(backend: &str, width: usize, n: &Inputs, got: &[Column]) {
    let want = reference(n, width);
    assert_eq!(got.len(), want.len());
    for ((name, g), (wname, w)) in got.iter().zip(&want) {
        assert_eq!(name, wname);
        if *name == "fma" || *name == "fnma" {
            check_fused(backend, n, name, g);
            continue;
        }
        assert_eq!(g.len(), w.len(), "{backend} {name}: column length");
        // Integer and bit columns must match exactly; float columns up to NaN payloads.
        let exact = name.ends_with("_i")
            || name.contains("_i ")
            || matches!(*name, "bits" | "bitmask" | "count" | "any");
        for (k, (&gv, &wv)) in g.iter().zip(w).enumerate() {
            let ok = if exact { gv == wv } else { same_float(gv, wv) };
            assert!(
                ok,
                "{backend} {name} at {k}: got {gv:#010x} ({:e}), want {wv:#010x} ({:e})",
                f32::from_bits(gv),
                f32::from_bits(wv)
            );
        }
    }
}

/// Runs `k` on every backend this machine has: (name, width, output).
fn on_every_backend<K: PackKernel + Clone>(k: K) -> Vec<(&'static str, usize, K::Output)> {
    let mut out = vec![
        ("scalar", Scalar::WIDTH, Pack::call(Scalar, k.clone())),
        ("counting", Counting::WIDTH, Counting.call(k.clone())),
    ];
    #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
    if let Some(p) = craterfield_core::simd::Avx2::new() {
        out.push((
            "avx2",
            craterfield_core::simd::Avx2::WIDTH,
            Pack::call(p, k.clone()),
        ));
    }
    #[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
    if let Some(p) = craterfield_core::simd::Neon::new() {
        out.push((
            "neon",
            craterfield_core::simd::Neon::WIDTH,
            Pack::call(p, k.clone()),
        ));
    }
    out
}

#[test]
fn every_lane_operation_matches_plain_arithmetic_on_every_backend() {
    let n = Inputs::new();
    let runs = on_every_backend(OpsKernel(n.clone()));
    for (backend, width, got) in &runs {
        check_columns(backend, *width, &n, got);
    }
    #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
    if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
        assert!(runs.iter().any(|r| r.0 == "avx2"), "AVX2+FMA went untested");
    }
}

#[test]
fn every_available_isa_runs_kernels() {
    let n = Inputs::new();
    for isa in Backend::ALL {
        match super::run(isa, OpsKernel(n.clone())) {
            Ok(got) => {
                assert!(isa.is_available(), "{isa} ran but says it is unavailable");
                check_columns(isa.name(), isa.width(), &n, &got);
            }
            Err(e) if TRACER_BACKENDS.contains(&isa) => {
                assert!(!isa.is_available(), "{isa} is available but failed: {e}");
                assert!(matches!(e, BackendError::Unavailable { backend, .. } if backend == isa));
            }
            Err(e) => assert!(matches!(e, BackendError::Unsupported { .. }), "{isa}: {e}"),
        }
    }
    if std::env::var_os(BACKEND_ENV).is_none() {
        let best = super::best();
        assert!(best.is_available());
        // The best is the widest available.
        for isa in TRACER_BACKENDS {
            assert!(!isa.is_available() || best.width() >= isa.width());
        }
    }
}

#[test]
fn each_backend_reports_its_own_width() {
    struct Width;
    impl PackKernel for Width {
        type Output = usize;
        fn run<P: Pack>(self, _p: P) -> usize {
            P::WIDTH
        }
    }
    for isa in TRACER_BACKENDS {
        if let Ok(w) = super::run(isa, Width) {
            assert_eq!(w, isa.width(), "{isa}");
        }
    }
}

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
        v.resize(n.next_multiple_of(8), 1.0);
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
