//! Distance formulas of the primitives, generic over [`Num`] so one formula gives the
//! distance (`f32`) and the distance with its analytic gradient ([`Dual`](craterfield_core::det::math::Dual)).
//!
//! Each function takes the query point already relative to nothing in particular (world or
//! local space of the node) and constants precomputed by the compiler. Only deterministic
//! operations are used (see [`craterfield_core::det::math`]).

use glam::Vec2;

use craterfield_core::det::math::{self, Num, V2, nclamp, nmax, nmin};

/// Disc of radius `r` around `c`.
#[inline]
pub fn circle<N: Num>(p: V2<N>, c: Vec2, r: f32) -> N {
    p.minus(c).length().offset(-r)
}

/// Axis-aligned box with centre `c` and half extents `h`.
#[inline]
pub fn aabox<N: Num>(p: V2<N>, c: Vec2, h: Vec2) -> N {
    let q = p.minus(c);
    let qx = q.x.abs().offset(-h.x);
    let qy = q.y.abs().offset(-h.y);
    let zero = N::constant(0.0);
    let outside = V2::new(nmax(qx, zero), nmax(qy, zero)).length();
    let inside = nmin(nmax(qx, qy), zero);
    outside + inside
}

/// Box of half extents `half` (along `dir`, across `dir`) centred on `mid`; `dir` is unit.
#[inline]
pub fn oriented_box<N: Num>(p: V2<N>, mid: Vec2, dir: Vec2, half: Vec2) -> N {
    let q = p.minus(mid);
    let along = q.x.scale(dir.x) + q.y.scale(dir.y);
    let across = q.y.scale(dir.x) - q.x.scale(dir.y);
    aabox(V2::new(along, across), Vec2::ZERO, half)
}

/// Points within `r` of the segment from `a` to `a + ba`; `inv_ba2 = 1 / |ba|²` (0 when the
/// segment is a point).
#[inline]
pub fn capsule<N: Num>(p: V2<N>, a: Vec2, ba: Vec2, inv_ba2: f32, r: f32) -> N {
    segment_distance_squared(p.minus(a), ba, inv_ba2)
        .sqrt()
        .offset(-r)
}

/// Squared distance from `w = p - a` to the segment `a .. a + e`.
#[inline]
fn segment_distance_squared<N: Num>(w: V2<N>, e: Vec2, inv_e2: f32) -> N {
    let t = nclamp(w.dot_c(e).scale(inv_e2), 0.0, 1.0);
    let b = V2::new(w.x - t.scale(e.x), w.y - t.scale(e.y));
    b.length_squared()
}

/// Simple polygon with vertices `pts` (either winding); `inv_e2[i] = 1 / |pts[i-1] - pts[i]|²`.
/// Inside/outside by crossing parity, so winding does not matter.
pub fn polygon<N: Num>(p: V2<N>, pts: &[Vec2], inv_e2: &[f32]) -> N {
    let Some(&first) = pts.first() else {
        return N::constant(f32::INFINITY);
    };
    let mut d2 = p.minus(first).length_squared();
    let mut inside = false;
    let mut j = pts.len() - 1;
    for (i, (&vi, &inv)) in pts.iter().zip(inv_e2).enumerate() {
        let vj = pts[j];
        let e = vj - vi;
        let w = p.minus(vi);
        d2 = nmin(d2, segment_distance_squared(w, e, inv));
        let wv = w.value();
        let py = p.y.value();
        let c1 = py >= vi.y;
        let c2 = py < vj.y;
        let c3 = e.x * wv.y > e.y * wv.x;
        if (c1 && c2 && c3) || (!c1 && !c2 && !c3) {
            inside = !inside;
        }
        j = i;
    }
    let d = d2.sqrt();
    if inside { -d } else { d }
}

/// Number of fixed iterations of the ellipse closest-point solver.
pub const ELLIPSE_ITERATIONS: usize = 5;

/// Axis-aligned ellipse with centre `c` and semi-axes `radii`.
///
/// The closest boundary point is found by a fixed number of iterations of the curvature
/// (evolute) method, using only `+ - * / sqrt`; the distance to it is then exact up to the
/// solver's convergence (relative error below 1e-4 for axis ratios up to 100). Holding the
/// closest point constant gives the gradient `(p - q) / |p - q|` (envelope theorem).
pub fn ellipse<N: Num>(p: V2<N>, c: Vec2, radii: Vec2) -> N {
    let local = p.minus(c);
    let lv = local.value();
    let q = ellipse_closest_first_quadrant(Vec2::new(lv.x.abs(), lv.y.abs()), radii);
    let q = Vec2::new(
        if lv.x < 0.0 { -q.x } else { q.x },
        if lv.y < 0.0 { -q.y } else { q.y },
    );
    let d = local.minus(q).length();
    let nx = lv.x / radii.x;
    let ny = lv.y / radii.y;
    if nx * nx + ny * ny < 1.0 { -d } else { d }
}

fn ellipse_closest_first_quadrant(p: Vec2, r: Vec2) -> Vec2 {
    let (a, b) = (r.x, r.y);
    let mut tx = std::f32::consts::FRAC_1_SQRT_2;
    let mut ty = std::f32::consts::FRAC_1_SQRT_2;
    let ab = a * a - b * b;
    for _ in 0..ELLIPSE_ITERATIONS {
        let x = a * tx;
        let y = b * ty;
        let ex = ab * (tx * tx * tx) / a;
        let ey = -ab * (ty * ty * ty) / b;
        let rx = x - ex;
        let ry = y - ey;
        let qx = p.x - ex;
        let qy = p.y - ey;
        let rl = (rx * rx + ry * ry).sqrt();
        let ql = (qx * qx + qy * qy).sqrt();
        if ql > 0.0 {
            tx = math::clamp((qx * rl / ql + ex) / a, 0.0, 1.0);
            ty = math::clamp((qy * rl / ql + ey) / b, 0.0, 1.0);
        }
        let t = (tx * tx + ty * ty).sqrt();
        if t > 0.0 {
            tx /= t;
            ty /= t;
        }
    }
    Vec2::new(a * tx, b * ty)
}

/// Annulus: points within `half_width` of the circle of radius `r` around `c`.
#[inline]
pub fn ring<N: Num>(p: V2<N>, c: Vec2, r: f32, half_width: f32) -> N {
    p.minus(c).length().offset(-r).abs().offset(-half_width)
}

/// Rotate `p` by the inverse of the rotation with the given cosine and sine.
#[inline]
pub fn rotate_inverse<N: Num>(p: V2<N>, cos: f32, sin: f32) -> V2<N> {
    V2::new(
        p.x.scale(cos) + p.y.scale(sin),
        p.y.scale(cos) - p.x.scale(sin),
    )
}

/// Arc of radius `ra` and half-width `rb` around `c`, opening half-angle with `sc = (sin,
/// cos)`, symmetric about the direction rotated by `(rot_cos, rot_sin)` from +y.
#[inline]
pub fn arc<N: Num>(p: V2<N>, c: Vec2, rot: Vec2, sc: Vec2, ra: f32, rb: f32) -> N {
    let q = rotate_inverse(p.minus(c), rot.x, rot.y);
    let q = V2::new(q.x.abs(), q.y);
    let qv = q.value();
    let d = if sc.y * qv.x > sc.x * qv.y {
        q.minus(sc * ra).length()
    } else {
        q.length().offset(-ra).abs()
    };
    d.offset(-rb)
}

/// Half-plane `dot(p, n) - offset` with unit `n`.
#[inline]
pub fn half_plane<N: Num>(p: V2<N>, n: Vec2, offset: f32) -> N {
    p.dot_c(n).offset(-offset)
}

/// Ground below the polyline through `pts` (equally spaced in x by `dx`, starting at
/// `pts[0].x`), extended flat beyond both ends; `inv_e2[i] = 1 / |pts[i+1] - pts[i]|²`.
///
/// Exact: the vertical gap to the ground line bounds the distance, so only the segments
/// within that reach in x can hold the closest point and only those are visited.
pub fn height_profile<N: Num>(p: V2<N>, pts: &[Vec2], dx: f32, inv_e2: &[f32]) -> N {
    let (Some(&first), Some(&last)) = (pts.first(), pts.last()) else {
        return N::constant(f32::INFINITY);
    };
    let pv = p.value();
    let ground = ground_height(pts, dx, pv.x);
    let reach = (pv.y - ground).abs();
    let mut d2 = N::constant(f32::INFINITY);
    if pv.x < first.x {
        let dy = p.y.offset(-first.y);
        d2 = dy * dy;
    }
    if pv.x > last.x {
        let dy = p.y.offset(-last.y);
        d2 = nmin(d2, dy * dy);
    }
    let segments = pts.len() - 1;
    let lo = segment_index(pv.x - reach, first.x, dx, segments).saturating_sub(1);
    let hi = (segment_index(pv.x + reach, first.x, dx, segments) + 1).min(segments - 1);
    for i in lo..=hi {
        let a = pts[i];
        let e = pts[i + 1] - a;
        d2 = nmin(d2, segment_distance_squared(p.minus(a), e, inv_e2[i]));
    }
    let d = d2.sqrt();
    if pv.y < ground { -d } else { d }
}

/// Index of the segment whose x-range holds `x`, clamped to `0..segments`.
fn segment_index(x: f32, x0: f32, dx: f32, segments: usize) -> usize {
    let f = ((x - x0) / dx).floor();
    if f > 0.0 {
        // Saturating cast; NaN never reaches here (the comparison is false for NaN).
        (f as usize).min(segments - 1)
    } else {
        0
    }
}

/// Height of the ground line at `x`.
pub fn ground_height(pts: &[Vec2], dx: f32, x: f32) -> f32 {
    let (Some(&first), Some(&last)) = (pts.first(), pts.last()) else {
        return f32::NEG_INFINITY;
    };
    // `<=` and NaN both take the left end.
    if x.is_nan() || x <= first.x {
        return first.y;
    }
    if x >= last.x {
        return last.y;
    }
    let i = segment_index(x, first.x, dx, pts.len() - 1);
    let a = pts[i];
    let b = pts[i + 1];
    let t = (x - a.x) / (b.x - a.x);
    a.y + (b.y - a.y) * t
}

/// Quadratic polynomial smooth minimum of width `k > 0`: `min(a, b) - h² k / 4` with
/// `h = max(k - |a - b|, 0) / k`. The correction is skipped by select when `h = 0` so the
/// result is then exactly `min(a, b)`, signed zeros included.
#[inline]
pub fn smooth_min<N: Num>(a: N, b: N, k: f32) -> N {
    let m = nmin(a, b);
    let hk = (a - b).abs().scale(-1.0).offset(k);
    if hk.value() > 0.0 {
        let h = hk / N::constant(k);
        m - (h * h).scale(k * 0.25)
    } else {
        m
    }
}

/// Smooth maximum: `-smooth_min(-a, -b, k)`, written out to keep the operation order fixed.
#[inline]
pub fn smooth_max<N: Num>(a: N, b: N, k: f32) -> N {
    let m = nmax(a, b);
    let hk = (a - b).abs().scale(-1.0).offset(k);
    if hk.value() > 0.0 {
        let h = hk / N::constant(k);
        m + (h * h).scale(k * 0.25)
    } else {
        m
    }
}
