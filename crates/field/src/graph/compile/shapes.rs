//! Lowering the shape primitives: each validates its fields (naming the first bad one)
//! and gets its exact bounds and cost.

use glam::Vec2;

use super::{Compiler, invalid};
use crate::aabb::Aabb;
use crate::error::LevelError;
use crate::graph::{Exactness, NodeInfo, Op};
use crate::node::{Node, P2};
use craterfield_core::det::math::{self, sin_cos_deg};

impl Compiler<'_> {
    /// The primitive `node` lowered, or `None` when it is not a primitive.
    pub(super) fn shape(
        &self,
        node: &Node,
        path: &str,
    ) -> Result<Option<(Op, NodeInfo)>, LevelError> {
        Ok(Some(match node {
            Node::Circle { center, radius } => {
                let c = self.point(path, "center", *center)?;
                let r = self.positive(path, "radius", *radius)?;
                Self::primitive(Op::Circle { c, r }, Aabb::centered(c, Vec2::splat(r)), 1)
            }
            Node::Box { center, half_size } => {
                let c = self.point(path, "center", *center)?;
                let h = self.point(path, "half_size", *half_size)?;
                self.positive(path, "half_size.x", h.x)?;
                self.positive(path, "half_size.y", h.y)?;
                Self::primitive(Op::Box { c, h }, Aabb::centered(c, h), 1)
            }
            Node::RoundedBox {
                center,
                half_size,
                radius,
            } => {
                let c = self.point(path, "center", *center)?;
                let h = self.point(path, "half_size", *half_size)?;
                self.positive(path, "half_size.x", h.x)?;
                self.positive(path, "half_size.y", h.y)?;
                let r = self.non_negative(path, "radius", *radius)?;
                if r > h.x.min(h.y) {
                    return Err(invalid(
                        path,
                        "radius",
                        format!(
                            "{r} is larger than the smaller half extent {}",
                            h.x.min(h.y)
                        ),
                    ));
                }
                Self::primitive(
                    Op::RoundedBox {
                        c,
                        inner: h - Vec2::splat(r),
                        r,
                    },
                    Aabb::centered(c, h),
                    1,
                )
            }
            Node::OrientedBox { a, b, thickness } => {
                let a = self.point(path, "a", *a)?;
                let b = self.point(path, "b", *b)?;
                let th = self.positive(path, "thickness", *thickness)?;
                let len = (b - a).length();
                if len.is_nan() || len <= 0.0 {
                    return Err(invalid(path, "b", "is degenerate: a and b coincide".into()));
                }
                let dir = (b - a) / len;
                let half = Vec2::new(len * 0.5, th * 0.5);
                let mid = (a + b) * 0.5;
                let bounds = Aabb::of_points([a, b]).expand(th * 0.5);
                Self::primitive(Op::OrientedBox { mid, dir, half }, bounds, 1)
            }
            Node::Capsule { a, b, radius } => {
                let a = self.point(path, "a", *a)?;
                let b = self.point(path, "b", *b)?;
                let r = self.positive(path, "radius", *radius)?;
                let ba = b - a;
                let l2 = ba.dot(ba);
                let inv_ba2 = if l2 > 0.0 { 1.0 / l2 } else { 0.0 };
                Self::primitive(
                    Op::Capsule { a, ba, inv_ba2, r },
                    Aabb::of_points([a, b]).expand(r),
                    1,
                )
            }
            Node::Triangle { a, b, c } => {
                let pts = self.polygon_points(path, &[*a, *b, *c])?;
                self.polygon(pts)
            }
            Node::Polygon { points } => {
                let pts = self.polygon_points(path, points)?;
                self.polygon(pts)
            }
            Node::Ellipse { center, radii } => {
                let c = self.point(path, "center", *center)?;
                let r = self.point(path, "radii", *radii)?;
                self.positive(path, "radii.x", r.x)?;
                self.positive(path, "radii.y", r.y)?;
                if r.x.max(r.y) > 100.0 * r.x.min(r.y) {
                    return Err(invalid(
                        path,
                        "radii",
                        format!("axis ratio of {r} exceeds 100 (use a capsule or box)"),
                    ));
                }
                Self::primitive(Op::Ellipse { c, radii: r }, Aabb::centered(c, r), 3)
            }
            Node::Ring {
                center,
                radius,
                width,
            } => {
                let c = self.point(path, "center", *center)?;
                let r = self.positive(path, "radius", *radius)?;
                let w = self.positive(path, "width", *width)?;
                Self::primitive(
                    Op::Ring {
                        c,
                        r,
                        half_width: w * 0.5,
                    },
                    Aabb::centered(c, Vec2::splat(r + w * 0.5)),
                    1,
                )
            }
            Node::Arc {
                center,
                radius,
                width,
                aperture,
                rotation,
            } => self.arc(path, *center, *radius, *width, *aperture, *rotation)?,
            Node::HalfPlane { point, normal } => {
                let p = self.point(path, "point", *point)?;
                let n = self.point(path, "normal", *normal)?;
                let len = n.length();
                if len.is_nan() || len <= 0.0 {
                    return Err(invalid(
                        path,
                        "normal",
                        "must not be the zero vector".into(),
                    ));
                }
                let n = n / len;
                let bounds = half_plane_bounds(n, p);
                Self::primitive(
                    Op::HalfPlane {
                        n,
                        offset: p.dot(n),
                    },
                    bounds,
                    1,
                )
            }
            Node::HeightProfile { x0, dx, heights } => {
                self.height_profile(path, *x0, *dx, heights)?
            }
            _ => return Ok(None),
        }))
    }

    fn arc(
        &self,
        path: &str,
        center: P2,
        radius: f32,
        width: f32,
        aperture: f32,
        rotation: f32,
    ) -> Result<(Op, NodeInfo), LevelError> {
        let c = self.point(path, "center", center)?;
        let ra = self.positive(path, "radius", radius)?;
        let w = self.positive(path, "width", width)?;
        let ap = self.positive(path, "aperture", aperture)?;
        if ap > 180.0 {
            return Err(invalid(
                path,
                "aperture",
                format!("must be at most 180 degrees, got {ap}"),
            ));
        }
        let rot = self.num(path, "rotation", rotation)?;
        let (s, co) = sin_cos_deg(ap);
        let (rs, rc) = sin_cos_deg(rot);
        let bounds = Aabb::centered(c, Vec2::splat(ra + w * 0.5));
        Ok(Self::primitive(
            Op::Arc {
                c,
                rot: Vec2::new(rc, rs),
                sc: Vec2::new(s, co),
                ra,
                rb: w * 0.5,
            },
            bounds,
            1,
        ))
    }

    fn height_profile(
        &self,
        path: &str,
        x0: f32,
        dx: f32,
        heights: &[f32],
    ) -> Result<(Op, NodeInfo), LevelError> {
        let x0 = self.num(path, "x0", x0)?;
        let dx = self.positive(path, "dx", dx)?;
        if heights.len() < 2 {
            return Err(invalid(
                path,
                "heights",
                format!("needs at least 2 samples, got {}", heights.len()),
            ));
        }
        if heights.len() > self.limits.max_points {
            return Err(invalid(
                path,
                "heights",
                format!(
                    "{} samples exceed the limit of {}",
                    heights.len(),
                    self.limits.max_points
                ),
            ));
        }
        let mut pts = Vec::with_capacity(heights.len());
        for (i, &h) in heights.iter().enumerate() {
            let y = self.num(path, &format!("heights[{i}]"), h)?;
            pts.push(Vec2::new(x0 + dx * i as f32, y));
        }
        let last_x = pts[pts.len() - 1].x;
        self.num(path, "dx", last_x)?;
        let inv_e2: Vec<f32> = pts
            .windows(2)
            .map(|w| 1.0 / (w[1] - w[0]).length_squared())
            .collect();
        let top = pts.iter().fold(f32::NEG_INFINITY, |m, p| math::max(m, p.y));
        let bounds = Aabb::new(
            Vec2::new(f32::NEG_INFINITY, f32::NEG_INFINITY),
            Vec2::new(f32::INFINITY, top),
        );
        Ok(Self::primitive(Op::Height { pts, dx, inv_e2 }, bounds, 8))
    }

    fn primitive(op: Op, bounds: Aabb, cost: u64) -> (Op, NodeInfo) {
        (
            op,
            NodeInfo {
                exactness: Exactness::Exact,
                lipschitz: 1.0,
                bounds,
                cost,
            },
        )
    }

    fn polygon_points(&self, path: &str, points: &[P2]) -> Result<Vec<Vec2>, LevelError> {
        if points.len() < 3 {
            return Err(invalid(
                path,
                "points",
                format!("needs at least 3 vertices, got {}", points.len()),
            ));
        }
        if points.len() > self.limits.max_points {
            return Err(invalid(
                path,
                "points",
                format!(
                    "{} vertices exceed the limit of {}",
                    points.len(),
                    self.limits.max_points
                ),
            ));
        }
        let pts = points
            .iter()
            .enumerate()
            .map(|(i, p)| self.point(path, &format!("points[{i}]"), *p))
            .collect::<Result<Vec<_>, _>>()?;
        check_simple_polygon(&pts).map_err(|reason| invalid(path, "points", reason))?;
        Ok(pts)
    }

    fn polygon(&self, pts: Vec<Vec2>) -> (Op, NodeInfo) {
        let n = pts.len();
        let inv_e2 = (0..n)
            .map(|i| {
                let e = pts[(i + n - 1) % n] - pts[i];
                1.0 / e.length_squared()
            })
            .collect();
        let bounds = Aabb::of_points(pts.iter().copied());
        let cost = 1 + n as u64 / 4;
        Self::primitive(Op::Polygon { pts, inv_e2 }, bounds, cost)
    }
}

fn half_plane_bounds(n: Vec2, p: Vec2) -> Aabb {
    let mut b = Aabb::EVERYTHING;
    // Solid is dot(q - p, n) < 0; only axis-aligned normals give a finite side.
    if n.y == 0.0 {
        if n.x > 0.0 {
            b.max.x = p.x
        } else {
            b.min.x = p.x
        }
    } else if n.x == 0.0 {
        if n.y > 0.0 {
            b.max.y = p.y
        } else {
            b.min.y = p.y
        }
    }
    b
}

/// Most edge-pair tests (and grid insertions) one polygon's simplicity check may cost:
/// about a tenth of a second. Ordinary polygons of the largest accepted size need a few
/// times their vertex count; a polygon whose edges pile into a few places (a star of long
/// spikes) is refused with a message instead of taking quadratic time.
const SIMPLICITY_BUDGET: u64 = 1 << 25;

/// Checks that a polygon has non-zero area, no repeated consecutive vertices and no
/// intersecting non-adjacent edges. Edges are bucketed in a uniform grid of about one cell
/// per edge, and only edges sharing a cell are tested against each other, within
/// [`SIMPLICITY_BUDGET`].
fn check_simple_polygon(pts: &[Vec2]) -> Result<(), String> {
    let n = pts.len();
    for i in 0..n {
        if pts[i] == pts[(i + 1) % n] {
            return Err(format!(
                "degenerate polygon: vertices {i} and {} coincide at {}",
                (i + 1) % n,
                pts[i]
            ));
        }
    }
    let area2: f64 = (0..n)
        .map(|i| {
            let (a, b) = (pts[i].as_dvec2(), pts[(i + 1) % n].as_dvec2());
            a.x * b.y - b.x * a.y
        })
        .sum();
    if area2.abs() < 1e-9 {
        return Err("degenerate polygon: zero area".into());
    }
    if n == 4
        && (segments_intersect(pts[0], pts[1], pts[2], pts[3])
            || segments_intersect(pts[1], pts[2], pts[3], pts[0]))
    {
        return Err("polygon is not simple: its edges cross".into());
    }
    if n > 4 {
        check_edges_apart(pts)?;
    }
    Ok(())
}

/// Whether edges `i` and `j` (`i < j`) of an `n`-gon share a vertex.
fn adjacent(i: usize, j: usize, n: usize) -> bool {
    j == i + 1 || (i == 0 && j == n - 1)
}

/// No two non-adjacent edges of a polygon (more than 4 vertices) touch.
fn check_edges_apart(pts: &[Vec2]) -> Result<(), String> {
    let n = pts.len();
    let edge = |i: usize| (pts[i].as_dvec2(), pts[(i + 1) % n].as_dvec2());
    let (lo, hi) = pts.iter().fold(
        (glam::DVec2::splat(f64::MAX), glam::DVec2::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(p.as_dvec2()), hi.max(p.as_dvec2())),
    );
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    let size = (hi - lo).max(glam::DVec2::splat(1e-30)) / side as f64;
    let cell = |v: f64, lo: f64, size: f64| (((v - lo) / size) as usize).min(side - 1);
    let mut work = 0u64;
    let over_budget = || {
        format!(
            "polygon of {n} vertices is too costly to check for crossing edges (its edges crowd into few places; past {SIMPLICITY_BUDGET} tests): split it into simpler polygons"
        )
    };
    // Each edge goes into every cell its bounding box covers.
    let mut cells: Vec<Vec<u32>> = vec![Vec::new(); side * side];
    for i in 0..n {
        let (a, b) = edge(i);
        let (x0, x1) = (
            cell(a.x.min(b.x), lo.x, size.x),
            cell(a.x.max(b.x), lo.x, size.x),
        );
        let (y0, y1) = (
            cell(a.y.min(b.y), lo.y, size.y),
            cell(a.y.max(b.y), lo.y, size.y),
        );
        work += ((x1 - x0 + 1) * (y1 - y0 + 1)) as u64;
        if work > SIMPLICITY_BUDGET {
            return Err(over_budget());
        }
        for y in y0..=y1 {
            for x in x0..=x1 {
                cells[y * side + x].push(i as u32);
            }
        }
    }
    for list in &cells {
        work += (list.len() * list.len().saturating_sub(1) / 2) as u64;
        if work > SIMPLICITY_BUDGET {
            return Err(over_budget());
        }
        for (k, &i) in list.iter().enumerate() {
            for &j in &list[k + 1..] {
                let (i, j) = (i.min(j) as usize, i.max(j) as usize);
                if adjacent(i, j, n) {
                    continue;
                }
                let ((a, b), (c, d)) = (edge(i), edge(j));
                if segments_intersect_f64(a, b, c, d) {
                    return Err(format!("polygon is not simple: edge {i} crosses edge {j}"));
                }
            }
        }
    }
    Ok(())
}

fn segments_intersect(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> bool {
    segments_intersect_f64(a.as_dvec2(), b.as_dvec2(), c.as_dvec2(), d.as_dvec2())
}

fn segments_intersect_f64(a: glam::DVec2, b: glam::DVec2, c: glam::DVec2, d: glam::DVec2) -> bool {
    let orient = |p: glam::DVec2, q: glam::DVec2, r: glam::DVec2| (q - p).perp_dot(r - p);
    let (o1, o2, o3, o4) = (
        orient(a, b, c),
        orient(a, b, d),
        orient(c, d, a),
        orient(c, d, b),
    );
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    let on = |p: glam::DVec2, q: glam::DVec2, r: glam::DVec2, o: f64| {
        o == 0.0
            && r.x >= p.x.min(q.x)
            && r.x <= p.x.max(q.x)
            && r.y >= p.y.min(q.y)
            && r.y <= p.y.max(q.y)
    };
    on(a, b, c, o1) || on(a, b, d, o2) || on(c, d, a, o3) || on(c, d, b, o4)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quadratic definition: some non-adjacent pair of edges touches.
    fn crosses_brute(pts: &[Vec2]) -> bool {
        let n = pts.len();
        (0..n).any(|i| {
            (i + 2..n).any(|j| {
                !adjacent(i, j, n)
                    && segments_intersect(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n])
            })
        })
    }

    fn xorshift(state: &mut u64) -> f32 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 40) as f32 / (1u64 << 24) as f32
    }

    #[test]
    fn the_grid_check_agrees_with_the_quadratic_one() {
        let mut state = 0x2545_f491_4f6c_dd1d;
        let (mut simple, mut crossing) = (0, 0);
        for case in 0..3000 {
            let n = 5 + case % 40;
            // Star-shaped around the centre (simple) with some vertices jittered, snapped
            // to a coarse grid so that touching and collinear edges occur too.
            let jitter = (case % 3) as f32 * 0.6;
            let pts: Vec<Vec2> = (0..n)
                .map(|k| {
                    let t = k as f32 / n as f32 * std::f32::consts::TAU;
                    let r = 20.0 + 20.0 * xorshift(&mut state);
                    let p = Vec2::new(t.cos(), t.sin()) * r
                        + (Vec2::new(xorshift(&mut state), xorshift(&mut state)) - 0.5)
                            * 60.0
                            * jitter;
                    (p / 4.0).round() * 4.0
                })
                .collect();
            if pts.windows(2).any(|w| w[0] == w[1]) || pts[0] == pts[n - 1] {
                continue;
            }
            let want = crosses_brute(&pts);
            let got = check_edges_apart(&pts).is_err();
            assert_eq!(got, want, "{pts:?}");
            if want {
                crossing += 1;
            } else {
                simple += 1;
            }
        }
        assert!(
            simple > 300 && crossing > 300,
            "{simple} simple, {crossing} crossing"
        );
    }

    #[test]
    fn large_polygons_are_checked_and_crowded_ones_refused() {
        // A height profile of 65,532 samples closed below: accepted.
        let mut pts: Vec<Vec2> = (0..65_532)
            .map(|i| {
                let x = i as f32 * 0.25;
                Vec2::new(
                    x,
                    300.0 + 80.0 * (x / 200.0).sin() + 30.0 * (x / 37.0).sin(),
                )
            })
            .collect();
        let right = pts[pts.len() - 1].x;
        pts.extend([Vec2::new(right, 0.0), Vec2::new(0.0, 0.0)]);
        pts.reverse();
        check_simple_polygon(&pts).unwrap();
        // The same with one sample pulled below the floor: found.
        let mut bad = pts.clone();
        bad[30_000].y = -5.0;
        let e = check_simple_polygon(&bad).unwrap_err();
        assert!(e.contains("crosses"), "{e}");
        // A star of 32,768 long spikes: every edge passes near the centre.
        let star: Vec<Vec2> = (0..65_536)
            .map(|k| {
                let t = k as f32 / 65_536.0 * std::f32::consts::TAU;
                let r = if k % 2 == 0 { 1000.0 } else { 1.0 };
                Vec2::new(t.cos(), t.sin()) * r
            })
            .collect();
        let e = check_simple_polygon(&star).unwrap_err();
        assert!(e.contains("too costly"), "{e}");
    }
}
