//! Body-body contacts: a sorted uniform-grid broadphase and segment-segment narrowphase
//! (circles are segments of length zero), resolved with a position split by inverse mass
//! and a normal impulse with restitution and friction.
//!
//! Pairs are found and resolved in a fixed order (ascending index pairs), so the result
//! does not depend on hashing or threads.
//!
//! Bodies piled at one point share a cell, where the pairs are quadratic: the candidates
//! visited in one tick are bounded by a budget ([`PAIR_TESTS_PER_BODY`] per body allowed in
//! the world). Past it the later bodies (in index order) get no body contacts that tick:
//! deterministic, and a pile of projectiles costs what the budget allows, not 34 ms a tick.

use glam::Vec2;

use craterfield_core::det::math::{clamp, max, min};

use super::body::Body;

/// Candidate pair tests per tick, per body the settings allow (`max_bodies`).
pub(crate) const PAIR_TESTS_PER_BODY: u64 = 32;

/// Fraction of the overlap removed per tick.
const PUSH_APART: f32 = 0.5;

/// A pair of overlapping bodies, by index, with the contact normal (from `a` to `b`) and
/// the overlap depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Overlap {
    /// First body (lower index).
    pub a: usize,
    /// Second body.
    pub b: usize,
    /// Unit normal from `a` towards `b`.
    pub normal: Vec2,
    /// How far they overlap.
    pub depth: f32,
}

/// A reusable broadphase: cell keys sorted with body indices.
///
/// The cells are sized for the small bodies (debris, projectiles): twice the largest
/// bounding radius among bodies no larger than twice the mean (but at least a sixteenth of
/// the widest body's). A small body looks for
/// partners in the 3 x 3 cells around its own; a large one (a vehicle) in every cell its
/// reach covers, and a pair with a large body is found from the large body's side only.
/// Sizing the cells by the vehicles instead put hundreds of debris bodies in one cell.
#[derive(Clone, Debug, Default)]
pub(crate) struct Broadphase {
    keys: Vec<(u64, u32)>,
}

fn cell_of(p: Vec2, inv: f32) -> (i32, i32) {
    // Saturating casts: far-away bodies share the edge cells, which is only slower.
    ((p.x * inv).floor() as i32, (p.y * inv).floor() as i32)
}

/// Column-major cell key, ordered like the signed coordinates (sign bits flipped).
fn key(cx: i32, cy: i32) -> u64 {
    let order = |v: i32| u64::from(v as u32 ^ 0x8000_0000);
    (order(cx) << 32) | order(cy)
}

/// The candidate tests of one tick, against the budget.
struct Tests {
    done: u64,
    budget: u64,
}

impl Tests {
    /// Counts one test; `false` once the budget has run out.
    fn take(&mut self) -> bool {
        self.done += 1;
        self.done <= self.budget
    }
}

impl Broadphase {
    /// Every overlapping pair, in ascending `(a, b)` order, into `out`, testing at most
    /// `budget` candidate pairs (small bodies first, in index order, then large ones;
    /// those left when it runs out get none). Returns whether the budget ran out.
    pub(crate) fn overlaps(
        &mut self,
        bodies: &[Body],
        out: &mut Vec<Overlap>,
        budget: u64,
    ) -> bool {
        out.clear();
        let widest = bodies.iter().map(Body::bounding_radius).fold(0.0, max);
        if bodies.len() < 2 || widest <= 0.0 {
            return false;
        }
        let mean = bodies.iter().map(Body::bounding_radius).sum::<f32>() / bodies.len() as f32;
        let large = |b: &Body| b.bounding_radius() > 2.0 * mean;
        let small_reach = (bodies.iter())
            .filter(|b| !large(b))
            .map(Body::bounding_radius)
            .fold(0.0, max);
        // At least a sixteenth of the widest body: a large body then scans at most about
        // 65 columns however small the debris (radii may differ 65,536-fold).
        let size = (2.0 * small_reach).max(widest / 16.0);
        let inv = 1.0 / size;
        self.keys.clear();
        self.keys.extend(bodies.iter().enumerate().map(|(i, b)| {
            let (cx, cy) = cell_of(b.pos, inv);
            (key(cx, cy), i as u32)
        }));
        self.keys.sort_unstable();
        let mut tests = Tests { done: 0, budget };
        let complete = self.small_pairs(bodies, inv, &large, out, &mut tests)
            && self.large_pairs(bodies, inv, widest, &large, out, &mut tests);
        out.sort_unstable_by_key(|o| (o.a, o.b));
        !complete
    }

    /// Pairs of two small bodies, from the 3 x 3 cells around each; `false` when the
    /// budget ran out.
    fn small_pairs(
        &self,
        bodies: &[Body],
        inv: f32,
        large: &impl Fn(&Body) -> bool,
        out: &mut Vec<Overlap>,
        tests: &mut Tests,
    ) -> bool {
        for (i, body) in bodies.iter().enumerate() {
            if large(body) {
                continue;
            }
            let (cx, cy) = cell_of(body.pos, inv);
            for dx in -1..=1 {
                let column = cx.saturating_add(dx);
                let rows = (cy.saturating_sub(1), cy.saturating_add(1));
                for j in self.column(column, rows) {
                    // Every key visited is work, the ones skipped as `j <= i` too.
                    if !tests.take() {
                        return false;
                    }
                    let other = &bodies[j];
                    if j <= i || large(other) || !near(body, other) {
                        continue;
                    }
                    if let Some(o) = overlap(body, other) {
                        out.push(Overlap { a: i, b: j, ..o });
                    }
                }
            }
        }
        true
    }

    /// Pairs with a large body, from every cell within its reach plus the widest body's;
    /// `false` when the budget ran out.
    fn large_pairs(
        &self,
        bodies: &[Body],
        inv: f32,
        widest: f32,
        large: &impl Fn(&Body) -> bool,
        out: &mut Vec<Overlap>,
        tests: &mut Tests,
    ) -> bool {
        for (i, body) in bodies.iter().enumerate() {
            if !large(body) {
                continue;
            }
            let reach = Vec2::splat(body.bounding_radius() + widest);
            let (x0, y0) = cell_of(body.pos - reach, inv);
            let (x1, y1) = cell_of(body.pos + reach, inv);
            for column in x0..=x1 {
                for j in self.column(column, (y0, y1)) {
                    if !tests.take() {
                        return false;
                    }
                    let other = &bodies[j];
                    // Two large bodies: found from the lower index only.
                    if j == i || (large(other) && j < i) || !near(body, other) {
                        continue;
                    }
                    // The lower index first, as every pair is tested.
                    let (a, b) = (i.min(j), i.max(j));
                    if let Some(o) = overlap(&bodies[a], &bodies[b]) {
                        out.push(Overlap { a, b, ..o });
                    }
                }
            }
        }
        true
    }

    /// The bodies keyed in `column` between rows `rows.0` and `rows.1` (a run of the
    /// sorted keys: they sort by column, then row).
    fn column(&self, column: i32, rows: (i32, i32)) -> impl Iterator<Item = usize> + '_ {
        let (lo, hi) = (key(column, rows.0), key(column, rows.1));
        let start = self.keys.partition_point(|e| e.0 < lo);
        (self.keys[start..].iter())
            .take_while(move |e| e.0 <= hi)
            .map(|&(_, j)| j as usize)
    }
}

/// Whether the bodies' bounding discs overlap (the cheap test before the exact one).
fn near(a: &Body, b: &Body) -> bool {
    let d = b.pos - a.pos;
    let reach = a.bounding_radius() + b.bounding_radius();
    d.x * d.x + d.y * d.y < reach * reach
}

/// Closest points of segments `p0-p1` and `q0-q1`.
pub(crate) fn closest_points(p0: Vec2, p1: Vec2, q0: Vec2, q1: Vec2) -> (Vec2, Vec2) {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    let r = p0 - q0;
    let a = d1.x * d1.x + d1.y * d1.y;
    let e = d2.x * d2.x + d2.y * d2.y;
    let f = d2.x * r.x + d2.y * r.y;
    let (s, t);
    if a <= 1e-12 && e <= 1e-12 {
        return (p0, q0);
    }
    if a <= 1e-12 {
        s = 0.0;
        t = clamp(f / e, 0.0, 1.0);
    } else {
        let c = d1.x * r.x + d1.y * r.y;
        if e <= 1e-12 {
            t = 0.0;
            s = clamp(-c / a, 0.0, 1.0);
        } else {
            let b = d1.x * d2.x + d1.y * d2.y;
            let denom = a * e - b * b;
            let s0 = if denom > 1e-12 {
                clamp((b * f - c * e) / denom, 0.0, 1.0)
            } else {
                0.0
            };
            let t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                t = 0.0;
                s = clamp(-c / a, 0.0, 1.0);
            } else if t0 > 1.0 {
                t = 1.0;
                s = clamp((b - c) / a, 0.0, 1.0);
            } else {
                t = t0;
                s = s0;
            }
        }
    }
    (p0 + d1 * s, q0 + d2 * t)
}

/// The overlap of two bodies, if any (indices left 0).
pub(crate) fn overlap(a: &Body, b: &Body) -> Option<Overlap> {
    let (a0, a1) = a.segment();
    let (b0, b1) = b.segment();
    let (pa, pb) = closest_points(a0, a1, b0, b1);
    let d = pb - pa;
    let dist2 = d.x * d.x + d.y * d.y;
    let reach = a.radius + b.radius;
    let overlapping = dist2 < reach * reach;
    if !overlapping {
        return None;
    }
    let dist = dist2.sqrt();
    let normal = if dist > 1e-6 {
        Vec2::new(d.x / dist, d.y / dist)
    } else {
        Vec2::Y
    };
    Some(Overlap {
        a: 0,
        b: 0,
        normal,
        depth: reach - dist,
    })
}

/// Pushes an overlapping pair apart and removes their approach velocity (with
/// restitution and friction), split by inverse mass.
pub(crate) fn resolve(a: &mut Body, b: &mut Body, o: &Overlap) {
    let total = a.inv_mass + b.inv_mass;
    if total <= 0.0 {
        return;
    }
    let n = o.normal;
    let push = o.depth * PUSH_APART / total;
    a.pos -= n * (push * a.inv_mass);
    b.pos += n * (push * b.inv_mass);
    let rel = b.vel - a.vel;
    let vn = rel.x * n.x + rel.y * n.y;
    if vn >= 0.0 {
        return;
    }
    let e = min(a.restitution, b.restitution);
    let j = -(1.0 + e) * vn / total;
    let t = Vec2::new(n.y, -n.x);
    let vt = rel.x * t.x + rel.y * t.y;
    let mu = (a.friction * b.friction).sqrt();
    let jt = clamp(-vt / total, -mu * j, mu * j);
    let impulse = n * j + t * jt;
    a.vel -= impulse * a.inv_mass;
    b.vel += impulse * b.inv_mass;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::BodyKind;

    /// A pile of bodies at one point visits at most the budget's candidates, keeps the
    /// ascending order and the pairs of the first bodies; spread bodies are never cut.
    #[test]
    fn a_pile_costs_the_budget_and_no_more() {
        let pile: Vec<Body> = (0..2000)
            .map(|i| Body::new(i, BodyKind::Debris, Vec2::new(5.0, 5.0), 2.0))
            .collect();
        let mut bp = Broadphase::default();
        let mut all = Vec::new();
        assert!(!bp.overlaps(&pile[..100], &mut all, u64::MAX));
        assert_eq!(all.len(), 100 * 99 / 2);
        let mut cut = Vec::new();
        assert!(bp.overlaps(&pile, &mut cut, 50_000));
        assert!(cut.len() <= 50_000 && !cut.is_empty());
        assert!(cut.windows(2).all(|w| (w[0].a, w[0].b) < (w[1].a, w[1].b)));
        assert_eq!((cut[0].a, cut[0].b), (0, 1));
        // The same budget, twice: the same pairs (no hashing, no threads).
        let mut again = Vec::new();
        bp.overlaps(&pile, &mut again, 50_000);
        assert_eq!(cut, again);
        // Bodies spread out on a line touch only their neighbours: far below any budget.
        let line: Vec<Body> = (0..2000)
            .map(|i| Body::new(i, BodyKind::Debris, Vec2::new(i as f32 * 3.9, 0.0), 2.0))
            .collect();
        let mut pairs = Vec::new();
        assert!(!bp.overlaps(&line, &mut pairs, 2000 * PAIR_TESTS_PER_BODY));
        assert_eq!(pairs.len(), 1999);
    }

    /// Small and large bodies mixed, some debris a thousand times smaller than the large
    /// bodies: the broadphase finds exactly the overlapping pairs that testing every pair
    /// finds, with the same normals and depths.
    #[test]
    fn mixed_sizes_give_every_overlapping_pair() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for round in 0..20 {
            let bodies: Vec<Body> = (0..300)
                .map(|i| {
                    let pos = Vec2::new(next() * 200.0, next() * 60.0);
                    // The last rounds: debris a thousand times smaller than the large.
                    let radius = if i % 25 == round % 25 {
                        6.0 + next() * 10.0
                    } else if round >= 15 {
                        0.005 + next() * 0.01
                    } else {
                        0.3 + next() * 2.0
                    };
                    Body::new(i, BodyKind::Debris, pos, radius)
                })
                .collect();
            let mut found = Vec::new();
            assert!(!Broadphase::default().overlaps(&bodies, &mut found, u64::MAX));
            let mut every = Vec::new();
            for a in 0..bodies.len() {
                for b in a + 1..bodies.len() {
                    if let Some(o) = overlap(&bodies[a], &bodies[b]) {
                        every.push(Overlap { a, b, ..o });
                    }
                }
            }
            assert!(every.len() > 20, "{}", every.len());
            assert_eq!(found, every, "round {round}");
        }
    }

    #[test]
    fn closest_points_of_segments() {
        let (p, q) = closest_points(
            Vec2::new(0.0, 0.0),
            Vec2::new(10.0, 0.0),
            Vec2::new(5.0, 3.0),
            Vec2::new(5.0, 8.0),
        );
        assert_eq!((p, q), (Vec2::new(5.0, 0.0), Vec2::new(5.0, 3.0)));
        let (p, q) = closest_points(
            Vec2::ZERO,
            Vec2::ZERO,
            Vec2::new(-2.0, 1.0),
            Vec2::new(2.0, 1.0),
        );
        assert_eq!((p, q), (Vec2::ZERO, Vec2::new(0.0, 1.0)));
        let (p, q) = closest_points(
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(3.0, 0.0),
            Vec2::new(4.0, 0.0),
        );
        assert_eq!((p, q), (Vec2::new(1.0, 0.0), Vec2::new(3.0, 0.0)));
    }
}
