//! The scene distance `map(p) -> (d, material)` of a plan for a packet of points, from the
//! per-frame constants (`super::constants`): every node's guard, lift, blend, displacement
//! and row repetition evaluated over lanes, with material tracking by masks.

use super::constants::{NodeC, PrimC, SceneConstants, ShapeC};
use super::lanes::{MAX_WIDTH, V3};
use super::prims::{mandelbulb, prim_distance};
use crate::noise::noise3;
use crate::plan3d::{EARLY_OUT_MARGIN, SKY};
use crate::simd::{Pack, PackKernel};

/// The material lane value of the background (`SKY` as `i32`).
pub(crate) const SKY_I: i32 = SKY as i32;

/// How much work the evaluations did: SDF evaluations and march steps (exact per ray on
/// one-lane backends; packet-level counts elsewhere).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Tally {
    pub sdf: u64,
    pub steps: u64,
}

/// The scene distance and (when `mats`) the nearest material at `q`. `active` marks the
/// lanes whose result matters: work that no active lane needs is skipped.
///
/// Every caller (the march, normals, shadows, occlusion) goes through one out-of-line copy
/// of the scene per backend, compiled with the backend's instruction set by `Pack::call`:
/// inlined at each call site, the whole scene evaluator was copied a dozen times per
/// backend, which made the crate take many minutes to compile for no speed gained (a
/// scene evaluation costs far more than the call).
#[inline(always)]
pub(crate) fn map<P: Pack>(
    p: P,
    s: &SceneConstants,
    q: V3<P>,
    active: P::M,
    mats: bool,
    tally: &mut Tally,
) -> (P::F, P::I) {
    let (d, m, _) = map_io(p, s, q, active, (mats, false), tally);
    (d, m)
}

/// [`map`], and the distance to everything but [`SceneConstants::planes`] (the scene
/// distance where there are none).
#[inline(always)]
pub(crate) fn map_split<P: Pack>(
    p: P,
    s: &SceneConstants,
    q: V3<P>,
    active: P::M,
    mats: bool,
    tally: &mut Tally,
) -> (P::F, P::I, P::F) {
    map_io(p, s, q, active, (mats, true), tally)
}

/// [`map_split`] when `rest`, else [`map`] (with a meaningless third value).
#[inline(always)]
fn map_io<P: Pack>(
    p: P,
    s: &SceneConstants,
    q: V3<P>,
    active: P::M,
    (mats, rest): (bool, bool),
    tally: &mut Tally,
) -> (P::F, P::I, P::F) {
    let input = MapIn {
        q: [lanes(p, q.x), lanes(p, q.y), lanes(p, q.z)],
        active: lanes(p, p.select(active, p.splat(1.0), p.splat(0.0))),
    };
    let out = p.call(MapCall {
        s,
        input: &input,
        mats,
        rest,
        tally,
    });
    (p.load(&out.d), p.load_i(&out.m), p.load(&out.rest))
}

/// `v`'s lanes in memory (a function, not a closure: a closure may be compiled out of line,
/// without the backend's instruction set).
#[inline(always)]
fn lanes<P: Pack>(p: P, v: P::F) -> [f32; MAX_WIDTH] {
    let mut a = [0.0; MAX_WIDTH];
    p.store(v, &mut a);
    a
}

/// The lanes of one [`map`] call's point, in memory (a kernel is generic over the backend,
/// so its inputs cannot be one backend's registers).
struct MapIn {
    q: [[f32; MAX_WIDTH]; 3],
    active: [f32; MAX_WIDTH],
}

/// What one [`map`] call returns, in memory; returned by value, so that the caller does not
/// zero a buffer for the kernel to overwrite (those stores showed in profiles).
struct MapOut {
    d: [f32; MAX_WIDTH],
    m: [i32; MAX_WIDTH],
    rest: [f32; MAX_WIDTH],
}

/// [`map_inline`] as a kernel, so that `Pack::call` compiles it once per backend.
struct MapCall<'a> {
    s: &'a SceneConstants,
    input: &'a MapIn,
    mats: bool,
    rest: bool,
    tally: &'a mut Tally,
}

impl PackKernel for MapCall<'_> {
    type Output = MapOut;

    #[inline(always)]
    fn run<P: Pack>(self, p: P) -> MapOut {
        let [x, y, z] = &self.input.q;
        let q = V3 {
            x: p.load(x),
            y: p.load(y),
            z: p.load(z),
        };
        let active = p.gt(p.load(&self.input.active), p.splat(0.5));
        let (d, m, rest) = map_inline(p, self.s, q, active, (self.mats, self.rest), self.tally);
        let mut out = MapOut {
            d: [0.0; MAX_WIDTH],
            m: [0; MAX_WIDTH],
            rest: [0.0; MAX_WIDTH],
        };
        p.store(d, &mut out.d);
        p.store_i(m, &mut out.m);
        p.store(rest, &mut out.rest);
        out
    }
}

/// The body of [`map_split`] (of [`map`] unless `rest`).
#[inline(always)]
fn map_inline<P: Pack>(
    p: P,
    s: &SceneConstants,
    q: V3<P>,
    active: P::M,
    (mats, rest_wanted): (bool, bool),
    tally: &mut Tally,
) -> (P::F, P::I, P::F) {
    let mut d = p.splat(f32::INFINITY);
    let mut m = p.splat_i(SKY_I);
    if let Some(t) = &s.terrain {
        tally.sdf += 1;
        let h = t.fbm.height_only(p, q.x, q.z);
        d = p.mul(p.sub(q.y, h), p.splat(t.step_scale));
        m = p.splat_i(t.material);
    }
    let mut above = p.none();
    let (mut de, mut me) = (d, m);
    if let Some(top) = s.early_out {
        let dtop = p.sub(q.y, p.splat(top));
        above = p.gt(q.y, p.splat(top + EARLY_OUT_MARGIN));
        let sky = p.lt(dtop, d);
        de = p.min(dtop, d);
        me = p.select_i(sky, p.splat_i(SKY_I), m);
        if !p.any(p.and_not(active, above)) {
            return (de, me, de);
        }
    }
    // The distance without the landing planes, kept only where there are some.
    let split = rest_wanted && !s.planes.is_empty();
    let mut rest = d;
    for node in &s.nodes {
        let in_rest = split && !node.plane;
        if !in_rest && beaten(p, node, q, d, active) {
            continue;
        }
        let dn = node_distance(p, s, node, q, active, tally);
        if mats {
            m = p.select_i(p.lt(dn, d), p.splat_i(node.material), m);
        }
        d = p.min(dn, d);
        if split && !node.plane {
            rest = p.min(dn, rest);
        }
    }
    if !split {
        rest = d;
    }
    if s.early_out.is_some() {
        d = p.select(above, de, d);
        m = p.select_i(above, me, m);
    }
    (d, m, rest)
}

/// Whether, in every active lane, what is nearer so far (`d`) is nearer than `node` can be
/// ([`super::constants::FarBound`]): then the node changes no bit, and is not evaluated.
#[inline(always)]
fn beaten<P: Pack>(p: P, node: &NodeC, q: V3<P>, d: P::F, active: P::M) -> bool {
    let Some(far) = &node.far else {
        return false;
    };
    let r2 = q.sub_c(p, far.centre).len2(p);
    let r = p.sqrt(r2);
    let bound = far.lines[1..]
        .iter()
        .fold(line_at(p, far.lines[0], r), |b, &l| {
            p.max(b, line_at(p, l, r))
        });
    let beaten = p.and(p.ge(r2, p.splat(far.radius2)), p.lt(d, bound));
    !p.any(p.and_not(active, beaten))
}

/// `slope * r + offset` (a function, not a closure, for the reason of `V3::dot_row`).
#[inline(always)]
fn line_at<P: Pack>(p: P, (slope, offset): (f32, f32), r: P::F) -> P::F {
    p.fma(p.splat(slope), r, p.splat(offset))
}

/// One node's distance at `q` (world space).
#[inline(always)]
fn node_distance<P: Pack>(
    p: P,
    s: &SceneConstants,
    node: &NodeC,
    q: V3<P>,
    active: P::M,
    tally: &mut Tally,
) -> P::F {
    if node.ground {
        tally.sdf += 1;
    }
    let q = if node.lift == 0.0 {
        q
    } else {
        V3 {
            y: p.sub(q.y, p.splat(node.lift)),
            ..q
        }
    };
    match &node.guard {
        None => shape_distance(p, s, &node.shape, q, active, tally),
        Some(g) => {
            let b = q.sub_c(p, g.centre).abs(p).sub_c(p, g.half).max0(p).len(p);
            let far = p.gt(b, p.splat(g.margin));
            let near = p.and_not(active, far);
            if !p.any(near) {
                return b;
            }
            let d = shape_distance(p, s, &node.shape, q, near, tally);
            p.select(far, b, d)
        }
    }
}

#[inline(always)]
fn shape_distance<P: Pack>(
    p: P,
    s: &SceneConstants,
    shape: &ShapeC,
    q: V3<P>,
    active: P::M,
    tally: &mut Tally,
) -> P::F {
    match shape {
        ShapeC::Prim(prim) => {
            tally.sdf += 1;
            prim_distance(p, prim, q, active)
        }
        ShapeC::Blend {
            inv_k,
            k_quarter,
            parts,
        } => {
            tally.sdf += parts.len() as u64;
            let mut d = p.splat(f32::INFINITY);
            for (i, part) in parts.iter().enumerate() {
                let dp = prim_distance(p, part, q, active);
                d = if i == 0 {
                    dp
                } else {
                    smin(p, d, dp, *inv_k, *k_quarter)
                };
            }
            d
        }
        ShapeC::Displaced {
            prim,
            amp,
            freq,
            scale,
        } => {
            tally.sdf += 1;
            let d = prim_distance(p, prim, q, active);
            let f = p.splat(*freq);
            let n = noise3(p, s.hash, p.mul(q.x, f), p.mul(q.y, f), p.mul(q.z, f));
            let n = p.sub(n, p.splat(0.5));
            p.mul(p.fma(p.splat(*amp), n, d), p.splat(*scale))
        }
        ShapeC::Rows {
            part,
            spacing,
            inv_spacing,
            count,
            nearest,
        } => rows_distance(
            p,
            part,
            (*spacing, *inv_spacing, *count, *nearest),
            q,
            active,
            tally,
        ),
        ShapeC::Mandelbulb {
            centre,
            iterations,
            bailout,
            derivative,
        } => {
            // No bounding-sphere shortcut: its distance is larger than the estimate's, and
            // soft shadows read every distance along the light ray, so it would change the
            // picture.
            let c = q.sub_c(p, *centre);
            tally.sdf += 1;
            mandelbulb(p, c, (*iterations, *bailout, *derivative), active)
        }
    }
}

/// The polynomial smooth minimum `min(a, b) - h*h*k/4`, `h = max(k - |a - b|, 0) / k`.
#[inline(always)]
fn smin<P: Pack>(p: P, a: P::F, b: P::F, inv_k: f32, k_quarter: f32) -> P::F {
    let h = p.mul(
        p.max(
            p.sub(p.splat(1.0 / inv_k), p.abs(p.sub(a, b))),
            p.splat(0.0),
        ),
        p.splat(inv_k),
    );
    p.fnma(p.mul(h, h), p.splat(k_quarter), p.min(a, b))
}

/// Row repetition along +z: the nearest row and its neighbour, or every row.
#[inline(always)]
fn rows_distance<P: Pack>(
    p: P,
    part: &PrimC,
    (spacing, inv_spacing, count, nearest): (f32, f32, u32, bool),
    q: V3<P>,
    active: P::M,
    tally: &mut Tally,
) -> P::F {
    let row_at = |i: P::F| V3 {
        z: p.fnma(i, p.splat(spacing), q.z),
        ..q
    };
    if !nearest {
        tally.sdf += count as u64;
        let mut d = p.splat(f32::INFINITY);
        for i in 0..count {
            d = p.min(d, prim_distance(p, part, row_at(p.splat(i as f32)), active));
        }
        return d;
    }
    let last = p.splat((count - 1) as f32);
    let z = p.sub(q.z, p.splat(part.centre.z));
    let c = p.max(
        p.splat(0.0),
        p.min(last, p.round(p.mul(z, p.splat(inv_spacing)))),
    );
    tally.sdf += 1;
    let d = prim_distance(p, part, row_at(c), active);
    // The neighbour on the side of z: c + sign(z - c * spacing), when in range.
    let off = p.fnma(c, p.splat(spacing), z);
    let up = p.gt(off, p.splat(0.0));
    let down = p.lt(off, p.splat(0.0));
    let n = p.add(c, p.select(up, p.splat(1.0), p.splat(-1.0)));
    let valid = p.and(p.or(up, down), p.and(p.ge(n, p.splat(0.0)), p.le(n, last)));
    let need = p.and(active, valid);
    if !p.any(need) {
        return d;
    }
    tally.sdf += 1;
    let d2 = prim_distance(p, part, row_at(n), need);
    p.select(valid, p.min(d, d2), d)
}
