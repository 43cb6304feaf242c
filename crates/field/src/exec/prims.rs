//! The coarse instructions on lanes: primitives, noise, the wave polynomial and the smooth
//! operators, each the reference formula of [`crate::primitives`],
//! [`crate::noise`] and [`craterfield_core::det::math`] with branches turned into
//! selects (both sides computed, the lane's side kept) and data-dependent loops run over the
//! union of the lanes' ranges with the lanes outside masked off.

use glam::Vec2;

use super::value::{P2, Val, clamp};
use craterfield_core::det::math::TAU;
use craterfield_core::simd::Lanes;

/// Parameter reader over a tape's parameter words.
#[derive(Clone, Copy)]
pub(crate) struct Params<'a>(pub &'a [u32]);

impl Params<'_> {
    #[inline(always)]
    pub(crate) fn f(&self, i: usize) -> f32 {
        f32::from_bits(self.0.get(i).copied().unwrap_or(0))
    }
    #[inline(always)]
    pub(crate) fn u(&self, i: usize) -> u32 {
        self.0.get(i).copied().unwrap_or(0)
    }
    #[inline(always)]
    pub(crate) fn v2(&self, i: usize) -> Vec2 {
        Vec2::new(self.f(i), self.f(i + 1))
    }
}

/// `primitives::circle`.
#[inline(always)]
pub(crate) fn circle<L: Lanes, V: Val<L>>(l: L, p: P2<V>, c: Vec2, r: f32) -> V {
    p.minus(l, c).length(l).offset(l, -r)
}

/// `primitives::aabox`.
#[inline(always)]
pub(crate) fn aabox<L: Lanes, V: Val<L>>(l: L, p: P2<V>, c: Vec2, h: Vec2) -> V {
    let q = p.minus(l, c);
    let qx = q.x.abs(l).offset(l, -h.x);
    let qy = q.y.abs(l).offset(l, -h.y);
    let zero = V::cst(l, 0.0);
    let outside = P2::new(qx.max(l, zero), qy.max(l, zero)).length(l);
    let inside = qx.max(l, qy).min(l, zero);
    outside.add(l, inside)
}

/// `primitives::oriented_box`.
#[inline(always)]
pub(crate) fn oriented_box<L: Lanes, V: Val<L>>(
    l: L,
    p: P2<V>,
    mid: Vec2,
    dir: Vec2,
    half: Vec2,
) -> V {
    let q = p.minus(l, mid);
    let along = q.x.scale(l, dir.x).add(l, q.y.scale(l, dir.y));
    let across = q.y.scale(l, dir.x).sub(l, q.x.scale(l, dir.y));
    aabox(l, P2::new(along, across), Vec2::ZERO, half)
}

/// `primitives::segment_distance_squared`.
#[inline(always)]
fn segment_distance_squared<L: Lanes, V: Val<L>>(l: L, w: P2<V>, e: Vec2, inv_e2: f32) -> V {
    let t = clamp(l, w.dot_c(l, e).scale(l, inv_e2), 0.0, 1.0);
    let b = P2::new(w.x.sub(l, t.scale(l, e.x)), w.y.sub(l, t.scale(l, e.y)));
    b.length_squared(l)
}

/// `primitives::capsule`.
#[inline(always)]
pub(crate) fn capsule<L: Lanes, V: Val<L>>(
    l: L,
    p: P2<V>,
    a: Vec2,
    ba: Vec2,
    inv_ba2: f32,
    r: f32,
) -> V {
    segment_distance_squared(l, p.minus(l, a), ba, inv_ba2)
        .sqrt(l)
        .offset(l, -r)
}

/// `primitives::polygon`; parameters: count, points, inverse squared edge lengths.
#[inline(always)]
pub(crate) fn polygon<L: Lanes, V: Val<L>>(l: L, p: P2<V>, prm: Params<'_>) -> V {
    let n = prm.u(0) as usize;
    if n == 0 {
        return V::cst(l, f32::INFINITY);
    }
    let pt = |i: usize| prm.v2(1 + 2 * i);
    let inv = |i: usize| prm.f(1 + 2 * n + i);
    let mut d2 = p.minus(l, pt(0)).length_squared(l);
    let mut inside = l.lt(l.splat(0.0), l.splat(0.0));
    let py = p.y.v();
    let mut j = n - 1;
    for i in 0..n {
        let (vi, vj) = (pt(i), pt(j));
        let e = vj - vi;
        let w = p.minus(l, vi);
        d2 = d2.min(l, segment_distance_squared(l, w, e, inv(i)));
        let c1 = l.ge(py, l.splat(vi.y));
        let c2 = l.lt(py, l.splat(vj.y));
        let c3 = l.gt(l.mul(l.splat(e.x), w.y.v()), l.mul(l.splat(e.y), w.x.v()));
        let all = l.and(l.and(c1, c2), c3);
        let none = l.and(l.and(l.not(c1), l.not(c2)), l.not(c3));
        inside = l.xor(inside, l.or(all, none));
        j = i;
    }
    let d = d2.sqrt(l);
    V::select(l, inside, d.neg(l), d)
}

/// `primitives::ellipse` (the closest-point solver runs on values, as in the reference).
#[inline(always)]
pub(crate) fn ellipse<L: Lanes, V: Val<L>>(l: L, p: P2<V>, c: Vec2, radii: Vec2) -> V {
    let local = p.minus(l, c);
    let (lx, ly) = (local.x.v(), local.y.v());
    let (qx, qy) = ellipse_closest(l, l.abs(lx), l.abs(ly), radii);
    let zero = l.splat(0.0);
    let qx = l.select(l.lt(lx, zero), l.neg(qx), qx);
    let qy = l.select(l.lt(ly, zero), l.neg(qy), qy);
    let d = P2::new(
        local.x.offset_v(l, l.neg(qx)),
        local.y.offset_v(l, l.neg(qy)),
    )
    .length(l);
    let nx = l.div(lx, l.splat(radii.x));
    let ny = l.div(ly, l.splat(radii.y));
    let inside = l.lt(l.add(l.mul(nx, nx), l.mul(ny, ny)), l.splat(1.0));
    V::select(l, inside, d.neg(l), d)
}

/// `primitives::ellipse_closest_first_quadrant` on lanes.
#[inline(always)]
fn ellipse_closest<L: Lanes>(l: L, px: L::F, py: L::F, r: Vec2) -> (L::F, L::F) {
    let (a, b) = (r.x, r.y);
    let (sa, sb) = (l.splat(a), l.splat(b));
    let zero = l.splat(0.0);
    let one = l.splat(1.0);
    let mut tx = l.splat(std::f32::consts::FRAC_1_SQRT_2);
    let mut ty = tx;
    let ab = a * a - b * b;
    let (sab, snab) = (l.splat(ab), l.splat(-ab));
    for _ in 0..crate::primitives::ELLIPSE_ITERATIONS {
        let x = l.mul(sa, tx);
        let y = l.mul(sb, ty);
        let ex = l.div(l.mul(sab, l.mul(l.mul(tx, tx), tx)), sa);
        let ey = l.div(l.mul(snab, l.mul(l.mul(ty, ty), ty)), sb);
        let rx = l.sub(x, ex);
        let ry = l.sub(y, ey);
        let qx = l.sub(px, ex);
        let qy = l.sub(py, ey);
        let rl = l.sqrt(l.add(l.mul(rx, rx), l.mul(ry, ry)));
        let ql = l.sqrt(l.add(l.mul(qx, qx), l.mul(qy, qy)));
        let moved = l.gt(ql, zero);
        // (No closures here: a closure is compiled without the backend's instruction set.)
        let nx = l.div(l.add(l.div(l.mul(qx, rl), ql), ex), sa);
        let ny = l.div(l.add(l.div(l.mul(qy, rl), ql), ey), sb);
        let nx = l.min(l.max(nx, zero), one);
        let ny = l.min(l.max(ny, zero), one);
        tx = l.select(moved, nx, tx);
        ty = l.select(moved, ny, ty);
        let t = l.sqrt(l.add(l.mul(tx, tx), l.mul(ty, ty)));
        let norm = l.gt(t, zero);
        tx = l.select(norm, l.div(tx, t), tx);
        ty = l.select(norm, l.div(ty, t), ty);
    }
    (l.mul(sa, tx), l.mul(sb, ty))
}

/// `primitives::ring`.
#[inline(always)]
pub(crate) fn ring<L: Lanes, V: Val<L>>(l: L, p: P2<V>, c: Vec2, r: f32, hw: f32) -> V {
    p.minus(l, c).length(l).offset(l, -r).abs(l).offset(l, -hw)
}

/// `primitives::rotate_inverse`.
#[inline(always)]
fn rotate_inverse<L: Lanes, V: Val<L>>(l: L, p: P2<V>, cos: f32, sin: f32) -> P2<V> {
    P2::new(
        p.x.scale(l, cos).add(l, p.y.scale(l, sin)),
        p.y.scale(l, cos).sub(l, p.x.scale(l, sin)),
    )
}

/// `primitives::arc`.
#[inline(always)]
pub(crate) fn arc<L: Lanes, V: Val<L>>(
    l: L,
    p: P2<V>,
    c: Vec2,
    rot: Vec2,
    sc: Vec2,
    ra: f32,
    rb: f32,
) -> V {
    let q = rotate_inverse(l, p.minus(l, c), rot.x, rot.y);
    let q = P2::new(q.x.abs(l), q.y);
    let cap = l.gt(l.mul(l.splat(sc.y), q.x.v()), l.mul(l.splat(sc.x), q.y.v()));
    let end = q.minus(l, sc * ra).length(l);
    let body = q.length(l).offset(l, -ra).abs(l);
    V::select(l, cap, end, body).offset(l, -rb)
}

/// `primitives::half_plane`.
#[inline(always)]
pub(crate) fn half_plane<L: Lanes, V: Val<L>>(l: L, p: P2<V>, n: Vec2, offset: f32) -> V {
    p.dot_c(l, n).offset(l, -offset)
}

/// Per-lane `primitives::segment_index` as floats (integral, in `0..segments`).
#[inline(always)]
fn segment_index<L: Lanes>(l: L, x: L::F, x0: f32, dx: f32, segments: usize) -> L::F {
    let f = l.floor(l.div(l.sub(x, l.splat(x0)), l.splat(dx)));
    let top = l.splat((segments - 1) as f32);
    l.select(l.gt(f, l.splat(0.0)), l.min(f, top), l.splat(0.0))
}

/// Lanes of `f32` as an array (for per-lane table lookups, which have no SIMD form here).
#[inline(always)]
fn lanes_of<L: Lanes>(l: L, v: L::F) -> [f32; 16] {
    let mut out = [0.0; 16];
    l.store(v, &mut out);
    out
}

#[inline(always)]
fn from_lanes<L: Lanes>(l: L, v: &[f32; 16]) -> L::F {
    l.load(v)
}

/// `primitives::height_profile`; parameters: count, dx, points, inverse squared lengths.
/// Segments are searched within the point's vertical gap to the ground, or within `cap`
/// where that is less (see `Tape::with_height_cap`; a NaN gap stays NaN).
#[inline(always)]
pub(crate) fn height_profile<L: Lanes, V: Val<L>>(l: L, p: P2<V>, prm: Params<'_>, cap: f32) -> V {
    let n = prm.u(0) as usize;
    if n < 2 {
        return V::cst(l, f32::INFINITY);
    }
    let dx = prm.f(1);
    let pt = |i: usize| prm.v2(2 + 2 * i);
    let (first, last) = (pt(0), pt(n - 1));
    let segments = n - 1;
    let (px, py) = (p.x.v(), p.y.v());
    let ground = ground_height(l, px, first, last, segments, dx, &pt);
    let gap = l.abs(l.sub(py, ground));
    let reach = l.select(l.gt(gap, l.splat(cap)), l.splat(cap), gap);
    let mut d2 = V::cst(l, f32::INFINITY);
    let dy = p.y.offset(l, -first.y);
    d2 = V::select(l, l.lt(px, l.splat(first.x)), dy.mul(l, dy), d2);
    let dy = p.y.offset(l, -last.y);
    let right = l.gt(px, l.splat(last.x));
    d2 = V::select(l, right, d2.min(l, dy.mul(l, dy)), d2);
    // lo = index(x - reach) - 1 (saturating), hi = min(index(x + reach) + 1, segments - 1).
    let lo = l.max(
        l.sub(
            segment_index(l, l.sub(px, reach), first.x, dx, segments),
            l.splat(1.0),
        ),
        l.splat(0.0),
    );
    let hi = l.min(
        l.add(
            segment_index(l, l.add(px, reach), first.x, dx, segments),
            l.splat(1.0),
        ),
        l.splat((segments - 1) as f32),
    );
    let (los, his) = (lanes_of(l, lo), lanes_of(l, hi));
    let w = L::WIDTH;
    let start = los[..w].iter().fold(f32::INFINITY, |m, &v| m.min(v)) as usize;
    let end = his[..w].iter().fold(0.0f32, |m, &v| m.max(v)) as usize;
    let end = end.min(segments - 1);
    // The segments' words as slices, read in one pass: this loop is most of a profile's
    // cost (a point within the band of the ground reads up to 18 segments), and reading
    // each word through `Params` checked it against the tape's length every time.
    let words = (start <= end)
        .then(|| {
            let points = prm.0.get(2 + 2 * start..2 + 2 * (end + 2))?;
            let inverses = prm.0.get(2 + 2 * n + start..2 + 2 * n + end + 1)?;
            Some((points, inverses))
        })
        .flatten();
    // A tape shorter than its count says (the compiler writes none) reads no segments.
    let (points, inverses) = words.unwrap_or((&[], &[]));
    let word = |i: usize| f32::from_bits(points[i]);
    for (k, &inv_e2) in inverses.iter().enumerate() {
        let a = Vec2::new(word(2 * k), word(2 * k + 1));
        let b = Vec2::new(word(2 * k + 2), word(2 * k + 3));
        let inv_e2 = f32::from_bits(inv_e2);
        d2 = nearer_segment(l, p, d2, (lo, hi), start + k, (a, b), inv_e2);
    }
    let d = d2.sqrt(l);
    V::select(l, l.lt(py, ground), d.neg(l), d)
}

/// `d2` lowered to segment `i`'s (from `a` to `b`) squared distance in the lanes whose
/// segment range `lo..=hi` holds it.
#[inline(always)]
fn nearer_segment<L: Lanes, V: Val<L>>(
    l: L,
    p: P2<V>,
    d2: V,
    (lo, hi): (L::F, L::F),
    i: usize,
    (a, b): (Vec2, Vec2),
    inv_e2: f32,
) -> V {
    let s = segment_distance_squared(l, p.minus(l, a), b - a, inv_e2);
    if L::WIDTH == 1 {
        // One lane: the loop's range is the lane's own, so every segment is in it.
        return d2.min(l, s);
    }
    let fi = l.splat(i as f32);
    let active = l.and(l.le(lo, fi), l.le(fi, hi));
    V::select(l, active, d2.min(l, s), d2)
}

/// [`height_profile`] at one point, reading the parameter words in place: the
/// specializer bounds a profile over each cell this way without copying a long profile's
/// points per cell.
pub(crate) fn height_profile_at(params: &[u32], p: Vec2) -> f32 {
    use super::value::Fv;
    use craterfield_core::simd::Scalar;
    height_profile(
        Scalar,
        P2::new(Fv(p.x), Fv(p.y)),
        Params(params),
        f32::INFINITY,
    )
    .0
}

/// `primitives::ground_height` per lane.
#[inline(always)]
fn ground_height<L: Lanes>(
    l: L,
    x: L::F,
    first: Vec2,
    last: Vec2,
    segments: usize,
    dx: f32,
    pt: &impl Fn(usize) -> Vec2,
) -> L::F {
    let idx = lanes_of(l, segment_index(l, x, first.x, dx, segments));
    let (mut ax, mut ay, mut bx, mut by) = ([0.0; 16], [0.0; 16], [0.0; 16], [0.0; 16]);
    for k in 0..L::WIDTH {
        let i = idx[k] as usize;
        let (a, b) = (pt(i), pt(i + 1));
        (ax[k], ay[k], bx[k], by[k]) = (a.x, a.y, b.x, b.y);
    }
    let (ax, ay, bx, by) = (
        from_lanes(l, &ax),
        from_lanes(l, &ay),
        from_lanes(l, &bx),
        from_lanes(l, &by),
    );
    let t = l.div(l.sub(x, ax), l.sub(bx, ax));
    let mid = l.add(ay, l.mul(l.sub(by, ay), t));
    // `x <= first.x` (and NaN) take the left end, `x >= last.x` the right end.
    let left = l.not(l.gt(x, l.splat(first.x)));
    let right = l.ge(x, l.splat(last.x));
    l.select(
        left,
        l.splat(first.y),
        l.select(right, l.splat(last.y), mid),
    )
}

/// `primitives::smooth_min` (`max = false`) and `smooth_max` (`max = true`).
#[inline(always)]
pub(crate) fn smooth<L: Lanes, V: Val<L>>(l: L, a: V, b: V, k: f32, max: bool) -> V {
    let m = if max { a.max(l, b) } else { a.min(l, b) };
    let hk = a.sub(l, b).abs(l).scale(l, -1.0).offset(l, k);
    let h = hk.div(l, V::cst(l, k));
    let t = h.mul(l, h).scale(l, k * 0.25);
    let blended = if max { m.add(l, t) } else { m.sub(l, t) };
    V::select(l, l.gt(hk.v(), l.splat(0.0)), blended, m)
}

/// `noise::lattice_value` per lane.
#[inline(always)]
fn lattice_value<L: Lanes>(l: L, ix: L::I, iy: L::I, seed: u32) -> L::F {
    let c = |v: u32| l.splat_i(v as i32);
    let mut h = l.add_i(
        l.add_i(
            l.add_i(l.mul_i(ix, c(0x8da6_b343)), l.mul_i(iy, c(0xd816_3841))),
            c(seed.wrapping_mul(0xcb1a_b31f)),
        ),
        c(0x9e37_79b9),
    );
    h = l.xor_i(h, l.shr_i(h, 15));
    h = l.mul_i(h, c(0x2c1b_3c6d));
    h = l.xor_i(h, l.shr_i(h, 12));
    h = l.mul_i(h, c(0x297a_2d39));
    h = l.xor_i(h, l.shr_i(h, 15));
    let top = l.to_f32(l.shr_i(h, 8));
    l.sub(l.mul(top, l.splat(1.0 / 8_388_608.0)), l.splat(1.0))
}

/// `noise::fade`: `t * t * (t.scale(-2).offset(3))`.
#[inline(always)]
fn fade<L: Lanes, V: Val<L>>(l: L, t: V) -> V {
    t.mul(l, t).mul(l, t.scale(l, -2.0).offset(l, 3.0))
}

/// `noise::value_noise`.
#[inline(always)]
pub(crate) fn value_noise<L: Lanes, V: Val<L>>(l: L, x: V, y: V, seed: u32) -> V {
    let fx0 = l.floor(x.v());
    let fy0 = l.floor(y.v());
    let ix = l.to_i32(fx0);
    let iy = l.to_i32(fy0);
    let tx = x.offset_v(l, l.neg(fx0));
    let ty = y.offset_v(l, l.neg(fy0));
    let ux = fade(l, tx);
    let uy = fade(l, ty);
    let one = l.splat_i(1);
    let (ix1, iy1) = (l.add_i(ix, one), l.add_i(iy, one));
    let v00 = lattice_value(l, ix, iy, seed);
    let v10 = lattice_value(l, ix1, iy, seed);
    let v01 = lattice_value(l, ix, iy1, seed);
    let v11 = lattice_value(l, ix1, iy1, seed);
    let bottom = ux.scale_v(l, l.sub(v10, v00)).offset_v(l, v00);
    let top = ux.scale_v(l, l.sub(v11, v01)).offset_v(l, v01);
    bottom.add(l, uy.mul(l, top.sub(l, bottom)))
}

/// `detmath::sin_turns` per lane.
#[inline(always)]
pub(crate) fn sin_turns<L: Lanes>(l: L, t: L::F) -> L::F {
    let r = l.sub(t, l.floor(l.add(t, l.splat(0.5))));
    let hi = l.gt(r, l.splat(0.25));
    let lo = l.lt(r, l.splat(-0.25));
    let r = l.select(
        hi,
        l.sub(l.splat(0.5), r),
        l.select(lo, l.sub(l.splat(-0.5), r), r),
    );
    let x = l.mul(r, l.splat(TAU));
    let x2 = l.mul(x, x);
    let p = l.splat(-2.505_210_8e-8_f32);
    let p = l.add(l.mul(p, x2), l.splat(2.755_731_9e-6));
    let p = l.sub(l.mul(p, x2), l.splat(1.984_127e-4));
    let p = l.add(l.mul(p, x2), l.splat(8.333_333e-3));
    let p = l.sub(l.mul(p, x2), l.splat(1.666_666_7e-1));
    let p = l.add(l.mul(p, x2), l.splat(1.0));
    l.mul(x, p)
}

/// The wave instruction: `t.chain(sin_turns(t), TAU * cos_turns(t))`.
#[inline(always)]
pub(crate) fn wave<L: Lanes, V: Val<L>>(l: L, t: V) -> V {
    let tv = t.v();
    let s = sin_turns(l, tv);
    let c = sin_turns(l, l.add(tv, l.splat(0.25)));
    t.chain(l, s, l.mul(l.splat(TAU), c))
}
