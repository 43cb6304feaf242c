//! Every lane operation, applied lane by lane to awkward inputs on every backend, against
//! plain `f32`/`i32` arithmetic.

use super::super::{Pack, PackKernel, TRACER_BACKENDS};
use super::{float_inputs, int_inputs, on_every_backend, pad, pairs, triples};
use craterfield_core::backend::{BACKEND_ENV, Backend, BackendError};

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
        match super::super::run(isa, OpsKernel(n.clone())) {
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
        let best = super::super::best();
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
        if let Ok(w) = super::super::run(isa, Width) {
            assert_eq!(w, isa.width(), "{isa}");
        }
    }
}

/// `rsqrt` of the inputs, lane by lane.
#[derive(Clone)]
struct RsqrtKernel(Vec<f32>);

impl PackKernel for RsqrtKernel {
    type Output = Vec<u32>;

    fn run<P: Pack>(self, p: P) -> Vec<u32> {
        map1(p, &self.0, |v| p.rsqrt(v))
    }
}

#[test]
fn rsqrt_is_within_its_bound_on_every_backend() {
    // Every binade of the normals, at mantissas near the ends and the middle of the
    // estimates' tables, and a dense sweep of two binades.
    let mantissas = [1.0, 1.0 + f32::EPSILON, 1.25, 1.5, 1.732_050_8, 1.999_999_9];
    let mut xs: Vec<f32> = (-126..=127)
        .flat_map(|e| mantissas.map(|m| m * 2f32.powi(e)))
        .collect();
    xs.extend((0..20_000).map(|k| 1.0 + 3.0 * k as f32 / 20_000.0));
    let n = xs.len();
    for (backend, _, got) in on_every_backend(RsqrtKernel(pad(xs.clone()))) {
        for (&x, &g) in xs.iter().zip(&got[..n]) {
            let want = 1.0 / f64::from(x).sqrt();
            let err = (f64::from(f32::from_bits(g)) - want).abs() / want;
            assert!(
                err <= 2f64.powi(-21),
                "{backend} rsqrt({x:e}) = {:e}, want {want:e} (relative error {err:e})",
                f32::from_bits(g)
            );
        }
    }
}
