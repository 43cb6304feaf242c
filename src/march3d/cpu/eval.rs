//! The scene distance `map(p) -> (d, material)` of a plan for a packet of points: the plan's
//! nodes compiled once per frame into lane-ready constants, then every primitive, guard,
//! lift, blend, displacement, row repetition and the Mandelbulb evaluated over lanes with
//! material tracking by masks.

use glam::{Mat3, Vec2, Vec3};

use super::lanes::V3;
use crate::emit::plan3d::{
    EARLY_OUT_MARGIN, Guard, Hash, Lift, Node, Plan, Prim, PrimKind, SKY, Shape, Sphere,
    VALUE_NOISE3_SLOPE,
};
use crate::march3d::math;
use crate::march3d::noise::{FbmLanes, noise3};
use crate::march3d::simd::{Pack, PackKernel};

/// The material lane value of the background (`SKY` as `i32`).
pub(crate) const SKY_I: i32 = SKY as i32;

/// How much work the evaluations did: SDF evaluations and march steps (exact per ray on
/// one-lane backends; packet-level counts elsewhere).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Tally {
    pub sdf: u64,
    pub steps: u64,
}

/// A primitive with its per-frame constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PrimC {
    centre: Vec3,
    rot: Option<[f32; 9]>,
    kind: PrimK,
}

#[derive(Clone, Copy, Debug)]
enum PrimK {
    Sphere {
        r: f32,
    },
    Box {
        half: Vec3,
    },
    RoundBox {
        inner: Vec3,
        r: f32,
    },
    Capsule {
        a: Vec3,
        ba: Vec3,
        inv_baba: f32,
        r: f32,
    },
    Torus {
        major: f32,
        minor: f32,
    },
    Cylinder {
        r: f32,
        h: f32,
    },
    CappedCone {
        h: f32,
        r1: f32,
        r2: f32,
        k2: Vec2,
        inv_k2k2: f32,
    },
    Octahedron {
        s: f32,
    },
    Ellipsoid {
        inv_r: Vec3,
        inv_r2: Vec3,
    },
    /// `p.y - offset` (an up-facing plane, the common case).
    PlaneY {
        offset: f32,
    },
    Plane {
        normal: Vec3,
        offset: f32,
    },
}

/// A node's geometry with its per-frame constants.
#[derive(Clone, Debug)]
enum ShapeC {
    Prim(PrimC),
    Blend {
        inv_k: f32,
        k_quarter: f32,
        parts: Vec<PrimC>,
    },
    Displaced {
        prim: PrimC,
        amp: f32,
        freq: f32,
        scale: f32,
    },
    Rows {
        part: PrimC,
        spacing: f32,
        inv_spacing: f32,
        count: u32,
        nearest: bool,
    },
    Mandelbulb {
        centre: Vec3,
        iterations: u32,
        bailout: f32,
        /// Beyond `radius + margin` from the centre every lane takes the distance to the
        /// sphere of this radius (which contains the bulb) instead of the iteration.
        skip: Option<(f32, f32)>,
    },
}

/// A node ready to evaluate.
#[derive(Clone, Debug)]
pub(crate) struct NodeC {
    material: i32,
    /// The height subtracted from `p.y` (0 for `Lift::None`).
    lift: f32,
    /// Whether the lift is the terrain height computed at evaluation time (counted as an
    /// SDF evaluation; the value is the same every call, so it is computed once per frame).
    ground: bool,
    guard: Option<Guard>,
    shape: ShapeC,
}

/// The terrain, prepared.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TerrainC {
    pub fbm: FbmLanes,
    pub material: i32,
    pub step_scale: f32,
    pub analytic_normal: bool,
}

/// Everything `map` needs, computed once per frame.
#[derive(Clone, Debug)]
pub(crate) struct Scene {
    pub terrain: Option<TerrainC>,
    pub early_out: Option<f32>,
    pub nodes: Vec<NodeC>,
    pub material_ids: bool,
    pub hash: Hash,
}

/// The radius around a power-8 Mandelbulb's centre outside which its distance estimate
/// (any iteration count, bailout >= 4) stays positive; see the tests.
pub(crate) const BULB_RADIUS: f32 = 1.25;

impl PrimC {
    fn new(prim: &Prim) -> PrimC {
        let rot = prim.rotation.map(row_major);
        let kind = match prim.kind {
            PrimKind::Sphere { r } => PrimK::Sphere { r },
            PrimKind::Box { half } => PrimK::Box { half },
            PrimKind::RoundBox { half, r } => PrimK::RoundBox {
                inner: half - Vec3::splat(r),
                r,
            },
            PrimKind::Capsule { a, b, r } => {
                let ba = b - a;
                let baba = ba.dot(ba);
                PrimK::Capsule {
                    a,
                    ba,
                    inv_baba: if baba > 0.0 { 1.0 / baba } else { 0.0 },
                    r,
                }
            }
            PrimKind::Torus { major, minor } => PrimK::Torus { major, minor },
            PrimKind::Cylinder { r, h } => PrimK::Cylinder { r, h },
            PrimKind::CappedCone { h, r1, r2 } => {
                let k2 = Vec2::new(r2 - r1, 2.0 * h);
                PrimK::CappedCone {
                    h,
                    r1,
                    r2,
                    k2,
                    inv_k2k2: 1.0 / k2.dot(k2),
                }
            }
            PrimKind::Octahedron { s } => PrimK::Octahedron { s },
            PrimKind::Ellipsoid { r } => PrimK::Ellipsoid {
                inv_r: r.recip(),
                inv_r2: (r * r).recip(),
            },
            PrimKind::Plane { normal, offset } if normal == Vec3::Y && rot.is_none() => {
                // Fold the translation into the offset: no per-lane subtraction.
                return PrimC {
                    centre: Vec3::ZERO,
                    rot: None,
                    kind: PrimK::PlaneY {
                        offset: offset + prim.centre.y,
                    },
                };
            }
            PrimKind::Plane { normal, offset } => PrimK::Plane { normal, offset },
        };
        PrimC {
            centre: prim.centre,
            rot,
            kind,
        }
    }
}

fn row_major(m: Mat3) -> [f32; 9] {
    let r = m.transpose().to_cols_array();
    [r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]]
}

impl Scene {
    /// Compiles the plan's nodes and terrain (the plan must be valid).
    pub(super) fn new(plan: &Plan) -> Scene {
        let terrain = plan.terrain.map(|t| TerrainC {
            fbm: FbmLanes::new(&t.fbm, plan.hash),
            material: t.material as i32,
            step_scale: t.step_scale,
            analytic_normal: t.analytic_normal,
        });
        let nodes = plan.nodes.iter().map(|n| compile_node(plan, n)).collect();
        Scene {
            terrain,
            early_out: plan.early_out,
            nodes,
            material_ids: plan.material_ids,
            hash: plan.hash,
        }
    }
}

fn compile_node(plan: &Plan, node: &Node) -> NodeC {
    let (lift, ground) = match node.lift {
        Lift::None => (0.0, false),
        Lift::Baked(y) => (y, false),
        Lift::Ground { x, z } => match &plan.terrain {
            Some(t) => (t.fbm.height(plan.hash, x, z).0, true),
            None => (0.0, true),
        },
    };
    let shape = match &node.shape {
        Shape::Prim(prim) => ShapeC::Prim(PrimC::new(prim)),
        Shape::Blend { k, parts } => ShapeC::Blend {
            inv_k: 1.0 / k,
            k_quarter: 0.25 * k,
            parts: parts.iter().map(PrimC::new).collect(),
        },
        Shape::Displaced { prim, amp, freq } => ShapeC::Displaced {
            prim: PrimC::new(prim),
            amp: *amp,
            freq: *freq,
            scale: 1.0 / (1.0 + amp * freq * VALUE_NOISE3_SLOPE),
        },
        Shape::Rows {
            part,
            spacing,
            count,
            nearest,
        } => ShapeC::Rows {
            part: PrimC::new(part),
            spacing: *spacing,
            inv_spacing: 1.0 / spacing,
            count: (*count).max(1),
            nearest: *nearest,
        },
        Shape::Mandelbulb {
            centre,
            iterations,
            bailout,
        } => ShapeC::Mandelbulb {
            centre: *centre,
            iterations: *iterations,
            bailout: *bailout,
            skip: (*bailout >= 4.0).then_some((BULB_RADIUS, 0.5)),
        },
    };
    NodeC {
        material: node.material as i32,
        lift,
        ground,
        guard: node.guard,
        shape,
    }
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
    s: &Scene,
    q: V3<P>,
    active: P::M,
    mats: bool,
    tally: &mut Tally,
) -> (P::F, P::I) {
    let mut io = MapIo::default();
    p.store(q.x, &mut io.x);
    p.store(q.y, &mut io.y);
    p.store(q.z, &mut io.z);
    p.store(p.select(active, p.splat(1.0), p.splat(0.0)), &mut io.active);
    p.call(MapCall {
        s,
        io: &mut io,
        mats,
        tally,
    });
    (p.load(&io.d), p.load_i(&io.m))
}

/// The lanes of one [`map`] call, in memory (a kernel is generic over the backend, so its
/// inputs cannot be one backend's registers).
struct MapIo {
    x: [f32; MAP_LANES],
    y: [f32; MAP_LANES],
    z: [f32; MAP_LANES],
    active: [f32; MAP_LANES],
    d: [f32; MAP_LANES],
    m: [i32; MAP_LANES],
}

/// The widest packet any backend has.
const MAP_LANES: usize = 16;

impl Default for MapIo {
    fn default() -> MapIo {
        MapIo {
            x: [0.0; MAP_LANES],
            y: [0.0; MAP_LANES],
            z: [0.0; MAP_LANES],
            active: [0.0; MAP_LANES],
            d: [0.0; MAP_LANES],
            m: [0; MAP_LANES],
        }
    }
}

/// [`map_inline`] as a kernel, so that `Pack::call` compiles it once per backend.
struct MapCall<'a> {
    s: &'a Scene,
    io: &'a mut MapIo,
    mats: bool,
    tally: &'a mut Tally,
}

impl PackKernel for MapCall<'_> {
    type Output = ();

    #[inline(always)]
    fn run<P: Pack>(self, p: P) {
        let q = V3 {
            x: p.load(&self.io.x),
            y: p.load(&self.io.y),
            z: p.load(&self.io.z),
        };
        let active = p.gt(p.load(&self.io.active), p.splat(0.5));
        let (d, m) = map_inline(p, self.s, q, active, self.mats, self.tally);
        p.store(d, &mut self.io.d);
        p.store_i(m, &mut self.io.m);
    }
}

/// The body of [`map`].
#[inline(always)]
fn map_inline<P: Pack>(
    p: P,
    s: &Scene,
    q: V3<P>,
    active: P::M,
    mats: bool,
    tally: &mut Tally,
) -> (P::F, P::I) {
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
            return (de, me);
        }
    }
    for node in &s.nodes {
        let dn = node_distance(p, s, node, q, active, tally);
        if mats {
            m = p.select_i(p.lt(dn, d), p.splat_i(node.material), m);
        }
        d = p.min(dn, d);
    }
    if s.early_out.is_some() {
        d = p.select(above, de, d);
        m = p.select_i(above, me, m);
    }
    (d, m)
}

/// One node's distance at `q` (world space).
#[inline(always)]
fn node_distance<P: Pack>(
    p: P,
    s: &Scene,
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
    s: &Scene,
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
            skip,
        } => {
            let c = q.sub_c(p, *centre);
            if let Some((radius, margin)) = skip {
                // The bounding sphere first: one SDF evaluation.
                tally.sdf += 1;
                let b = p.sub(c.len(p), p.splat(*radius));
                let far = p.gt(b, p.splat(*margin));
                let near = p.and_not(active, far);
                if !p.any(near) {
                    return b;
                }
                tally.sdf += 1;
                let d = mandelbulb(p, c, *iterations, *bailout, near);
                return p.select(far, b, d);
            }
            tally.sdf += 1;
            mandelbulb(p, c, *iterations, *bailout, active)
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

/// The distance of a primitive placed at `prim.centre` with its rotation.
#[inline(always)]
pub(crate) fn prim_distance<P: Pack>(p: P, prim: &PrimC, q: V3<P>, active: P::M) -> P::F {
    let mut l = q.sub_c(p, prim.centre);
    if let Some(r) = &prim.rot {
        l = l.rotate(p, r);
    }
    let zero = p.splat(0.0);
    match prim.kind {
        PrimK::Sphere { r } => p.sub(l.len(p), p.splat(r)),
        PrimK::Box { half } => {
            let b = l.abs(p).sub_c(p, half);
            p.add(b.max0(p).len(p), p.min(b.max_elem(p), zero))
        }
        PrimK::RoundBox { inner, r } => {
            let b = l.abs(p).sub_c(p, inner);
            p.sub(
                p.add(b.max0(p).len(p), p.min(b.max_elem(p), zero)),
                p.splat(r),
            )
        }
        PrimK::Capsule { a, ba, inv_baba, r } => {
            let pa = l.sub_c(p, a);
            let h = p.mul(pa.dot_c(p, ba), p.splat(inv_baba));
            let h = p.max(zero, p.min(p.splat(1.0), h));
            let v = V3::splat(p, ba).scale(p, h);
            p.sub(pa.sub(p, v).len(p), p.splat(r))
        }
        PrimK::Torus { major, minor } => {
            let rxz = p.sqrt(p.fma(l.x, l.x, p.mul(l.z, l.z)));
            let a = p.sub(rxz, p.splat(major));
            p.sub(p.sqrt(p.fma(a, a, p.mul(l.y, l.y))), p.splat(minor))
        }
        PrimK::Cylinder { r, h } => {
            let rxz = p.sqrt(p.fma(l.x, l.x, p.mul(l.z, l.z)));
            let dx = p.sub(rxz, p.splat(r));
            let dy = p.sub(p.abs(l.y), p.splat(h));
            let (ox, oy) = (p.max(dx, zero), p.max(dy, zero));
            p.add(
                p.min(p.max(dx, dy), zero),
                p.sqrt(p.fma(ox, ox, p.mul(oy, oy))),
            )
        }
        PrimK::CappedCone {
            h,
            r1,
            r2,
            k2,
            inv_k2k2,
        } => capped_cone(p, l, h, r1, r2, k2, inv_k2k2),
        PrimK::Octahedron { s } => octahedron(p, l, s, active),
        PrimK::Ellipsoid { inv_r, inv_r2 } => {
            let k0 = V3 {
                x: p.mul(l.x, p.splat(inv_r.x)),
                y: p.mul(l.y, p.splat(inv_r.y)),
                z: p.mul(l.z, p.splat(inv_r.z)),
            }
            .len(p);
            let k1 = V3 {
                x: p.mul(l.x, p.splat(inv_r2.x)),
                y: p.mul(l.y, p.splat(inv_r2.y)),
                z: p.mul(l.z, p.splat(inv_r2.z)),
            }
            .len(p);
            p.div(p.mul(k0, p.sub(k0, p.splat(1.0))), k1)
        }
        PrimK::PlaneY { offset } => p.sub(l.y, p.splat(offset)),
        PrimK::Plane { normal, offset } => p.sub(l.dot_c(p, normal), p.splat(offset)),
    }
}

#[inline(always)]
fn capped_cone<P: Pack>(p: P, l: V3<P>, h: f32, r1: f32, r2: f32, k2: Vec2, inv_k2k2: f32) -> P::F {
    let zero = p.splat(0.0);
    let qx = p.sqrt(p.fma(l.x, l.x, p.mul(l.z, l.z)));
    let qy = l.y;
    let rim = p.select(p.lt(qy, zero), p.splat(r1), p.splat(r2));
    let cax = p.sub(qx, p.min(qx, rim));
    let cay = p.sub(p.abs(qy), p.splat(h));
    // k1 - q = (r2 - qx, h - qy).
    let (kqx, kqy) = (p.sub(p.splat(r2), qx), p.sub(p.splat(h), qy));
    let t = p.mul(
        p.fma(kqx, p.splat(k2.x), p.mul(kqy, p.splat(k2.y))),
        p.splat(inv_k2k2),
    );
    let t = p.max(zero, p.min(p.splat(1.0), t));
    let cbx = p.fma(p.splat(k2.x), t, p.neg(kqx));
    let cby = p.fma(p.splat(k2.y), t, p.neg(kqy));
    let inside = p.and(p.lt(cbx, zero), p.lt(cay, zero));
    let dd = p.min(
        p.fma(cax, cax, p.mul(cay, cay)),
        p.fma(cbx, cbx, p.mul(cby, cby)),
    );
    let d = p.sqrt(dd);
    p.select(inside, p.neg(d), d)
}

/// The exact octahedron; the cheap plane bound `m / sqrt(3)` when no active lane lies in
/// one of the corner regions that need the full formula.
#[inline(always)]
fn octahedron<P: Pack>(p: P, l: V3<P>, s: f32, active: P::M) -> P::F {
    let a = l.abs(p);
    let m = p.sub(p.add(a.x, p.add(a.y, a.z)), p.splat(s));
    let plane = p.mul(m, p.splat(0.577_350_27));
    let three = p.splat(3.0);
    let c1 = p.lt(p.mul(three, a.x), m);
    let c2 = p.lt(p.mul(three, a.y), m);
    let c3 = p.lt(p.mul(three, a.z), m);
    let corner = p.or(c1, p.or(c2, c3));
    if !p.any(p.and(active, corner)) {
        return plane;
    }
    // q = p, p.yzx or p.zxy for the first region that holds.
    let qx = p.select(c1, a.x, p.select(c2, a.y, a.z));
    let qy = p.select(c1, a.y, p.select(c2, a.z, a.x));
    let qz = p.select(c1, a.z, p.select(c2, a.x, a.y));
    let sv = p.splat(s);
    let k = p.mul(p.splat(0.5), p.add(p.sub(qz, qy), sv));
    let k = p.max(p.splat(0.0), p.min(sv, k));
    let d = V3 {
        x: qx,
        y: p.add(p.sub(qy, sv), k),
        z: p.sub(qz, k),
    }
    .len(p);
    p.select(corner, d, plane)
}

/// The power-8 Mandelbulb's distance estimate at `c = p - centre`.
#[inline(always)]
pub(crate) fn mandelbulb<P: Pack>(
    p: P,
    c: V3<P>,
    iterations: u32,
    bailout: f32,
    active: P::M,
) -> P::F {
    let mut w = c;
    let mut m = w.len2(p);
    let mut dz = p.splat(1.0);
    let mut live = active;
    let bail = p.splat(bailout);
    for _ in 0..iterations {
        // dz = 8 m^3.5 dz + 1.
        let m3 = p.mul(p.mul(m, m), m);
        let k = p.mul(p.mul(p.splat(8.0), m3), p.sqrt(m));
        let ndz = p.fma(k, dz, p.splat(1.0));
        let nw = bulb8(p, w).add(p, c);
        let nm = nw.len2(p);
        dz = p.select(live, ndz, dz);
        w = V3::select(p, live, nw, w);
        m = p.select(live, nm, m);
        live = p.and_not(live, p.gt(nm, bail));
        if !p.any(live) {
            break;
        }
    }
    let num = p.mul(p.mul(p.splat(0.25), math::log(p, m)), p.sqrt(m));
    p.div(num, dz)
}

/// `w^8` in the spherical power-8 form `r^8 (sin b sin a, cos b, sin b cos a)`, `b = 8
/// acos(w.y / r)`, `a = 8 atan2(w.x, w.z)`, without trigonometry: with `rho = |w.xz|`, `r^8
/// (cos b, sin b) = (y + i rho)^8` and `(cos a, sin a) = ((z + i x) / rho)^8`, both by
/// three complex squarings.
#[inline(always)]
pub(crate) fn bulb8<P: Pack>(p: P, w: V3<P>) -> V3<P> {
    let two = p.splat(2.0);
    let rho2 = p.fma(w.x, w.x, p.mul(w.z, w.z));
    // rho = 0 (on the axis): a = 0 by atan2(0, 0); any unit (zn, xn) gives sin b = 0.
    let rho = p.sqrt(rho2);
    let inv = p.div(p.splat(1.0), p.max(rho, p.splat(1e-30)));
    let (xn, zn) = (p.mul(w.x, inv), p.mul(w.z, inv));
    // (zn + i xn)^8.
    let (mut ca, mut sa) = (p.fnma(xn, xn, p.mul(zn, zn)), p.mul(two, p.mul(xn, zn)));
    for _ in 0..2 {
        let (c2, s2) = (p.fnma(sa, sa, p.mul(ca, ca)), p.mul(two, p.mul(sa, ca)));
        (ca, sa) = (c2, s2);
    }
    // (y + i rho)^8.
    let (mut cb, mut sb) = (p.sub(p.mul(w.y, w.y), rho2), p.mul(two, p.mul(w.y, rho)));
    for _ in 0..2 {
        let (c2, s2) = (p.fnma(sb, sb, p.mul(cb, cb)), p.mul(two, p.mul(sb, cb)));
        (cb, sb) = (c2, s2);
    }
    V3 {
        x: p.mul(sb, sa),
        y: cb,
        z: p.mul(sb, ca),
    }
}

/// Whether `o + s * dir` for some `s > 0` meets the sphere (the terrain-and-bounds shadow's
/// ray test): `oc = centre - o, b = dot(oc, dir), c = dot(oc, oc) - r^2`, `b > 0 && b*b > c`.
#[inline(always)]
pub(crate) fn ray_meets_sphere<P: Pack>(p: P, o: V3<P>, dir: V3<P>, s: &Sphere) -> P::M {
    let oc = V3::splat(p, s.centre).sub(p, o);
    let b = oc.dot(p, dir);
    let c = p.sub(oc.len2(p), p.splat(s.radius * s.radius));
    p.and(p.gt(b, p.splat(0.0)), p.gt(p.mul(b, b), c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::march3d::simd::scalar::Scalar;

    /// The trigonometric form of the power-8 step, in f64.
    fn bulb8_trig(w: [f64; 3]) -> [f64; 3] {
        let r = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        let b = 8.0 * (w[1] / r).acos();
        let a = 8.0 * w[0].atan2(w[2]);
        let r8 = r.powi(8);
        [r8 * b.sin() * a.sin(), r8 * b.cos(), r8 * b.sin() * a.cos()]
    }

    /// The trig-free form of [`bulb8`] (the same complex squarings), in f64.
    fn bulb8_f64(w: [f64; 3]) -> [f64; 3] {
        let rho2 = w[0] * w[0] + w[2] * w[2];
        let rho = rho2.sqrt();
        // On the axis any unit direction will do, as in the lane version.
        let (xn, zn) = (w[0] / rho.max(1e-300), w[2] / rho.max(1e-300));
        let sq = |(c, s): (f64, f64)| (c * c - s * s, 2.0 * s * c);
        let (ca, sa) = sq(sq((zn * zn - xn * xn, 2.0 * xn * zn)));
        let (cb, sb) = sq(sq((w[1] * w[1] - rho2, 2.0 * w[1] * rho)));
        [sb * sa, cb, sb * ca]
    }

    fn points() -> impl Iterator<Item = [f64; 3]> {
        (0..2000).map(|i| {
            let f = i as f64;
            [
                (f * 0.731).sin() * 1.3,
                (f * 0.377).cos() * 1.1,
                (f * 1.913).sin() * 0.9,
            ]
        })
    }

    #[test]
    fn trig_free_bulb_step_equals_the_trigonometric_form() {
        for w in points() {
            let (a, b) = (bulb8_trig(w), bulb8_f64(w));
            let r8 = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).powi(4);
            for k in 0..3 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-9 * r8.max(1.0),
                    "{w:?}: {a:?} {b:?}"
                );
            }
        }
    }

    #[test]
    fn lane_bulb_step_follows_the_f64_form() {
        for w in points() {
            let b = bulb8_f64(w);
            let v = bulb8(
                Scalar,
                V3 {
                    x: w[0] as f32,
                    y: w[1] as f32,
                    z: w[2] as f32,
                },
            );
            let r8 = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).powi(4);
            for (got, want) in [v.x, v.y, v.z].into_iter().zip(b) {
                assert!(
                    (got as f64 - want).abs() <= 1e-5 * r8.max(1.0),
                    "{w:?}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn bulb_step_on_the_axis_is_finite() {
        let v = bulb8(
            Scalar,
            V3 {
                x: 0.0,
                y: 0.5,
                z: 0.0,
            },
        );
        assert_eq!((v.x, v.y, v.z), (0.0, 0.5f32.powi(8), 0.0));
    }

    #[test]
    fn bulb_distance_is_positive_outside_the_skip_radius() {
        // The skip sphere must contain the whole surface, for every iteration count.
        for iterations in 1..=8 {
            for (i, w) in points().enumerate() {
                let n = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
                let r = BULB_RADIUS as f64 * (1.0 + (i % 7) as f64 * 0.05);
                let c = V3 {
                    x: (w[0] / n * r) as f32,
                    y: (w[1] / n * r) as f32,
                    z: (w[2] / n * r) as f32,
                };
                let d = mandelbulb(Scalar, c, iterations, 256.0, true);
                assert!(d > 0.01, "{iterations} iterations at {r}: {d}");
            }
        }
    }
}
