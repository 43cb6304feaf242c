//! Sphere tracing of a packet of rays with active-lane masks (plain and over-relaxed),
//! soft shadows, and surface normals, as the plan's "Marching" and "Normals" sections
//! define them.

use super::constants::SceneConstants;
use super::eval::{Tally, map, map_split};
use super::lanes::V3;
use super::prims::ray_meets_sphere;
use crate::plan3d::March;
use crate::simd::Pack;

/// Per-frame march constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MarchC {
    pub m: March,
    /// `escape^2` (the escape test compares squared lengths).
    pub escape2: f32,
}

impl MarchC {
    pub(super) fn new(m: &March) -> MarchC {
        MarchC {
            m: *m,
            escape2: m.escape * m.escape,
        }
    }
}

/// What a packet's march found.
pub(crate) struct Hit<P: Pack> {
    /// Lanes that hit.
    pub hit: P::M,
    /// Distance along the ray.
    pub t: P::F,
    /// Material of the hit (`SKY` elsewhere).
    pub m: P::I,
    /// The scene distance at the hit point.
    pub d: P::F,
}

/// Marches the lanes of `live` from `o` along unit `dir`.
#[inline(always)]
pub(crate) fn march<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    o: V3<P>,
    dir: V3<P>,
    live: P::M,
    tally: &mut Tally,
) -> Hit<P> {
    let mut h = if mc.m.relax > 1.0 {
        march_relaxed(p, s, mc, o, dir, live, tally)
    } else {
        march_plain(p, s, mc, o, dir, live, tally)
    };
    find_materials(p, s, (o, dir), &mut h, tally);
    h
}

/// The materials of the hits of a march that kept distances only: one more full
/// evaluation at each hit.
#[inline(always)]
pub(crate) fn find_materials<P: Pack>(
    p: P,
    s: &SceneConstants,
    (o, dir): (V3<P>, V3<P>),
    h: &mut Hit<P>,
    tally: &mut Tally,
) {
    if !s.material_ids && p.any(h.hit) {
        let q = dir.mul_add(p, h.t, o);
        let (_, m) = map(p, s, q, h.hit, true, tally);
        h.m = p.select_i(h.hit, m, h.m);
    }
}

#[inline(always)]
fn march_plain<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    o: V3<P>,
    dir: V3<P>,
    live: P::M,
    tally: &mut Tally,
) -> Hit<P> {
    let mut st = PlainState::start(p, live);
    for _ in 0..mc.m.max_steps {
        if !p.any(st.active) {
            break;
        }
        plain_step(p, s, mc, (o, dir), &mut st, tally);
    }
    Hit {
        hit: st.hit,
        t: st.t,
        m: st.m,
        d: st.d,
    }
}

/// The lanes of a plain march between steps.
pub(crate) struct PlainState<P: Pack> {
    /// Distance along the ray.
    pub t: P::F,
    /// Lanes still marching.
    pub active: P::M,
    /// Lanes that hit, with the material and scene distance of their hit.
    pub hit: P::M,
    pub m: P::I,
    pub d: P::F,
}

impl<P: Pack> PlainState<P> {
    /// Every lane of `live` at the ray's origin, nothing hit.
    #[inline(always)]
    pub(crate) fn start(p: P, live: P::M) -> PlainState<P> {
        PlainState {
            t: p.splat(0.0),
            active: live,
            hit: p.none(),
            m: p.splat_i(super::eval::SKY_I),
            d: p.splat(0.0),
        }
    }
}

/// One plain sphere-tracing step of the active lanes (each lane's result depends on its
/// own ray alone, which lets [`super::stream`] refill lanes as their rays finish).
#[inline(always)]
pub(crate) fn plain_step<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    (o, dir): (V3<P>, V3<P>),
    st: &mut PlainState<P>,
    tally: &mut Tally,
) {
    let (thr, per_t) = (p.splat(mc.m.hit), p.splat(mc.m.hit_per_t));
    let (esc2, far, sf) = (
        p.splat(mc.escape2),
        p.splat(mc.m.far),
        p.splat(mc.m.step_factor),
    );
    let t = st.t;
    let mut active = st.active;
    let q = dir.mul_add(p, t, o);
    let (d, dm, rest) = map_split(p, s, q, active, s.material_ids, tally);
    tally.steps += p.count(active) as u64;
    let new = p.and(active, p.lt(d, p.fma(per_t, t, thr)));
    st.hit = p.or(st.hit, new);
    st.m = p.select_i(new, dm, st.m);
    st.d = p.select(new, d, st.d);
    let out = p.or(p.gt(q.len2(p), esc2), p.gt(t, far));
    active = p.and_not(p.and_not(active, new), out);
    let step = p.mul(d, sf);
    let (step, ahead) = land_on_planes(p, s, (o, dir, q, t), (rest, step), (esc2, far));
    if let Some(bounds) = &s.bounds {
        active = p.and_not(active, can_meet_nothing(p, bounds, (q, dir), ahead));
    }
    st.t = p.select(active, p.add(t, step), t);
    st.active = active;
}

/// The step onto the nearest plane ahead, where the ray reaches it before anything else
/// can be met: when the distance to everything else (`rest`) is at least the distance to
/// the plane along the ray, the segment up to the plane lies inside the sphere `rest`
/// proves empty. Sphere tracing would approach the plane geometrically (about
/// `ln(d / hit) / |cos|` steps, hundreds for rays that graze the floor); this lands in one,
/// on the same surface. Landings past the escape radius or `far` are not taken, so rays
/// miss where plain steps would. Otherwise `step` is unchanged.
#[inline(always)]
fn land_on_planes<P: Pack>(
    p: P,
    s: &SceneConstants,
    (o, dir, q, t): (V3<P>, V3<P>, V3<P>, P::F),
    (rest, step): (P::F, P::F),
    (esc2, far): (P::F, P::F),
) -> (P::F, P::F) {
    let mut ahead = p.splat(f32::INFINITY);
    if s.planes.is_empty() {
        return (step, ahead);
    }
    let zero = p.splat(0.0);
    for pl in &s.planes {
        let n = V3::splat(p, pl.n);
        let dist = p.sub(n.dot(p, q), p.splat(pl.c));
        let closing = p.neg(n.dot(p, dir));
        let toward = p.and(p.gt(dist, zero), p.gt(closing, zero));
        ahead = p.select(toward, p.min(ahead, p.div(dist, closing)), ahead);
    }
    let t_land = p.add(t, ahead);
    let inside = p.and(
        p.le(dir.mul_add(p, t_land, o).len2(p), esc2),
        p.le(t_land, far),
    );
    let land = p.and(inside, p.and(p.ge(rest, ahead), p.gt(ahead, step)));
    (p.select(land, ahead, step), ahead)
}

/// Lanes whose ray from `q` along `dir` can meet none of `bounds` (it starts outside each
/// and points away from it, or passes it by) and has no plane `ahead`: every surface lies
/// inside its node's bound, so such a ray misses, and marching it on to the escape radius
/// would only confirm that.
#[inline(always)]
fn can_meet_nothing<P: Pack>(
    p: P,
    bounds: &[crate::plan3d::Sphere],
    (q, dir): (V3<P>, V3<P>),
    ahead: P::F,
) -> P::M {
    let mut may = p.lt(ahead, p.splat(f32::INFINITY));
    for s in bounds {
        let inside = p.lt(
            V3::splat(p, s.centre).sub(p, q).len2(p),
            p.splat(s.radius * s.radius),
        );
        may = p.or(may, p.or(inside, ray_meets_sphere(p, q, dir, s)));
    }
    p.and_not(p.all_set(), may)
}

/// Over-relaxed sphere tracing: steps of `relax * d` while the unbounding spheres of
/// consecutive points overlap; when they do not, back to the previous point and plain
/// steps from there on (per lane).
#[inline(always)]
fn march_relaxed<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    o: V3<P>,
    dir: V3<P>,
    live: P::M,
    tally: &mut Tally,
) -> Hit<P> {
    let zero = p.splat(0.0);
    let one = p.splat(1.0);
    let mut t = zero;
    let mut omega = p.splat(mc.m.relax);
    let (mut t_prev, mut d_prev, mut step) = (zero, zero, zero);
    let mut active = live;
    let mut hit = p.none();
    let mut m = p.splat_i(super::eval::SKY_I);
    let mut dh = zero;
    // Lanes whose last step landed on a plane: proven safe, so not checked for overlap.
    let mut landed = p.none();
    let (thr, per_t) = (p.splat(mc.m.hit), p.splat(mc.m.hit_per_t));
    let (esc2, far, sf) = (
        p.splat(mc.escape2),
        p.splat(mc.m.far),
        p.splat(mc.m.step_factor),
    );
    for k in 0..mc.m.max_steps {
        if !p.any(active) {
            break;
        }
        let q = dir.mul_add(p, t, o);
        let (d, dm, rest) = map_split(p, s, q, active, s.material_ids, tally);
        tally.steps += p.count(active) as u64;
        let relaxing = p.and_not(p.gt(omega, one), landed);
        let fail = if k == 0 {
            p.none()
        } else {
            p.and(p.and(active, relaxing), p.lt(p.add(p.abs(d), d_prev), step))
        };
        let ok = p.and_not(active, fail);
        let new = p.and(ok, p.lt(d, p.fma(per_t, t, thr)));
        hit = p.or(hit, new);
        m = p.select_i(new, dm, m);
        dh = p.select(new, d, dh);
        let out = p.and(ok, p.or(p.gt(q.len2(p), esc2), p.gt(t, far)));
        active = p.and_not(p.and_not(active, new), out);
        // Failed lanes: the previous point plus a plain step, relaxation off.
        let t_back = p.fma(d_prev, sf, t_prev);
        omega = p.select(fail, one, omega);
        let adv = p.and_not(active, fail);
        t_prev = p.select(adv, t, t_prev);
        d_prev = p.select(adv, d, d_prev);
        step = p.select(adv, p.mul(p.mul(omega, d), sf), step);
        let (landing, ahead) = land_on_planes(p, s, (o, dir, q, t), (rest, step), (esc2, far));
        landed = p.and(adv, p.gt(landing, step));
        step = p.select(adv, landing, step);
        if let Some(bounds) = &s.bounds {
            let gone = p.and(adv, can_meet_nothing(p, bounds, (q, dir), ahead));
            active = p.and_not(active, gone);
        }
        t = p.select(fail, t_back, p.select(adv, p.add(t, step), t));
    }
    Hit { hit, t, m, d: dh }
}

/// The soft shadow from `pos` (normal `n`) towards unit `l`, up to `limit`: 0 blocked, 1
/// lit, in between in the penumbra (`min(k h / s)`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn soft_shadow<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    (pos, n, l): (V3<P>, V3<P>, V3<P>),
    limit: P::F,
    k: f32,
    steps: u32,
    live: P::M,
    tally: &mut Tally,
) -> P::F {
    let mut st = ShadowState::start(p, mc, (pos, n), live);
    for _ in 0..steps {
        if !p.any(st.active) {
            break;
        }
        shadow_step(p, s, mc, (l, limit, k), &mut st, tally);
    }
    st.res
}

/// The lanes of a soft-shadow march between steps.
pub(crate) struct ShadowState<P: Pack> {
    /// The point reached.
    pub x: V3<P>,
    /// The distance travelled, plus the ray's offset.
    pub s: P::F,
    /// The shadow so far.
    pub res: P::F,
    /// The previous step's scene distance.
    pub prev: P::F,
    pub active: P::M,
}

impl<P: Pack> ShadowState<P> {
    /// The lanes of `live` at `pos` (normal `n`), moved off the surface.
    #[inline(always)]
    pub(crate) fn start(p: P, mc: &MarchC, (pos, n): (V3<P>, V3<P>), live: P::M) -> Self {
        // The ray starts at `q` with `s` already at the offset, as the reference renderer's
        // does: `s` runs `ray_offset` ahead of the distance travelled from `q`.
        ShadowState {
            x: n.mul_add(p, p.splat(mc.m.ray_offset), pos),
            s: p.splat(mc.m.ray_offset),
            res: p.splat(1.0),
            prev: p.splat(1e20),
            active: live,
        }
    }
}

/// One soft-shadow step towards unit `l` of the active lanes (per lane, as
/// [`plain_step`]).
#[inline(always)]
pub(crate) fn shadow_step<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    (l, limit, k): (V3<P>, P::F, f32),
    st: &mut ShadowState<P>,
    tally: &mut Tally,
) {
    let (thr, kv, esc2) = (p.splat(mc.m.hit), p.splat(k), p.splat(mc.escape2));
    let zero = p.splat(0.0);
    let mut active = st.active;
    let (h, _) = map(p, s, st.x, active, false, tally);
    tally.steps += p.count(active) as u64;
    let blocked = p.and(active, p.lt(h, thr));
    let mut res = p.select(blocked, p.splat(0.0), st.res);
    active = p.and_not(active, blocked);
    // The closest approach between this sphere and the previous one.
    let h2 = p.mul(h, h);
    let y = p.div(h2, p.mul(p.splat(2.0), st.prev));
    let d = p.sqrt(p.max(p.fnma(y, y, h2), zero));
    let along = p.sub(st.s, y);
    let bound = p.and(active, p.gt(along, zero));
    res = p.select(bound, p.min(res, p.div(p.mul(kv, d), along)), res);
    st.prev = p.select(active, h, st.prev);
    st.s = p.select(active, p.add(st.s, h), st.s);
    st.x = V3::select(p, active, l.mul_add(p, h, st.x), st.x);
    let done = p.or(p.gt(st.s, limit), p.gt(st.x.len2(p), esc2));
    st.res = res;
    st.active = p.and_not(active, done);
}

/// Surface normals of the hits in `live` at `q` (material `m`, scene distance `d` there):
/// the terrain's analytic or central-difference normal on terrain, forward differences
/// elsewhere.
#[inline(always)]
pub(crate) fn normal<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    (q, m, d): (V3<P>, P::I, P::F),
    live: P::M,
    tally: &mut Tally,
) -> V3<P> {
    let e = mc.m.normal_eps;
    let ter = match &s.terrain {
        Some(t) => p.and(live, p.eq_i(m, p.splat_i(t.material))),
        None => p.none(),
    };
    let obj = p.and_not(live, ter);
    let mut n = V3::splat(p, glam::Vec3::Y);
    if p.any(obj) {
        let mut g = [d; 3];
        for (axis, gi) in g.iter_mut().enumerate() {
            let dq = shifted(p, q, axis, e);
            *gi = p.sub(map(p, s, dq, obj, false, tally).0, d);
        }
        let f = V3 {
            x: g[0],
            y: g[1],
            z: g[2],
        }
        .normalize(p);
        n = V3::select(p, obj, f, n);
    }
    if let Some(t) = &s.terrain
        && p.any(ter)
    {
        let tn = if t.analytic_normal {
            tally.sdf += 1;
            let (_, gx, gz) = t.fbm.height(p, q.x, q.z);
            V3 {
                x: p.neg(gx),
                y: p.splat(1.0),
                z: p.neg(gz),
            }
            .normalize(p)
        } else {
            let mut g = [d; 3];
            for (axis, gi) in g.iter_mut().enumerate() {
                let a = map(p, s, shifted(p, q, axis, e), ter, false, tally).0;
                let b = map(p, s, shifted(p, q, axis, -e), ter, false, tally).0;
                *gi = p.sub(a, b);
            }
            V3 {
                x: g[0],
                y: g[1],
                z: g[2],
            }
            .normalize(p)
        };
        n = V3::select(p, ter, tn, n);
    }
    n
}

#[inline(always)]
fn shifted<P: Pack>(p: P, q: V3<P>, axis: usize, e: f32) -> V3<P> {
    let e = p.splat(e);
    match axis {
        0 => V3 {
            x: p.add(q.x, e),
            ..q
        },
        1 => V3 {
            y: p.add(q.y, e),
            ..q
        },
        _ => V3 {
            z: p.add(q.z, e),
            ..q
        },
    }
}
