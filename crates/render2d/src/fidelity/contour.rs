//! Zero crossings of a distance image on the edges between pixel centres, and the capped
//! symmetric nearest-crossing distances between two such sets.

use glam::Vec2;

/// Sub-pixel zero crossings of a `width x height` distance image, in continuous pixel
/// coordinates: one per horizontally or vertically adjacent pixel pair whose inside states
/// (`d < 0`) differ, placed by linear interpolation between the two centres.
pub(super) fn zero_crossings(width: u32, height: u32, d: &[f32]) -> Vec<Vec2> {
    let (w, h) = (width as usize, height as usize);
    let mut out = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let d0 = d[y * w + x];
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            if x + 1 < w
                && let Some(t) = crossing(d0, d[y * w + x + 1])
            {
                out.push(centre + Vec2::new(t, 0.0));
            }
            if y + 1 < h
                && let Some(t) = crossing(d0, d[(y + 1) * w + x])
            {
                out.push(centre + Vec2::new(0.0, t));
            }
        }
    }
    out
}

/// Where along `0..1` the linear interpolant from `d0` to `d1` changes inside state, if it
/// does.
fn crossing(d0: f32, d1: f32) -> Option<f32> {
    let changes = (d0 < 0.0) != (d1 < 0.0);
    changes.then(|| (d0 / (d0 - d1)).clamp(0.0, 1.0))
}

/// Mean and largest capped nearest-crossing distance over both sets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Offsets {
    pub mean: f64,
    pub max: f64,
}

impl Offsets {
    /// Every point of `a` measured to its nearest point of `b` and every point of `b` to its
    /// nearest of `a`, each distance capped at `cap`.
    pub(super) fn between(a: &[Vec2], b: &[Vec2], cap: f32) -> Offsets {
        let count = a.len() + b.len();
        if count == 0 {
            return Offsets {
                mean: 0.0,
                max: 0.0,
            };
        }
        let (to_b, to_a) = (Buckets::new(b), Buckets::new(a));
        let distances = a
            .iter()
            .map(|&p| to_b.nearest(p, cap))
            .chain(b.iter().map(|&p| to_a.nearest(p, cap)));
        let (sum, max) = distances.fold((0.0f64, 0.0f32), |(sum, max), d| {
            (sum + f64::from(d), max.max(d))
        });
        Offsets {
            mean: sum / count as f64,
            max: f64::from(max),
        }
    }
}

/// Side of a bucket, pixels: small enough that a search touches few points, large enough
/// that a capped search touches few buckets.
const BUCKET_PX: f32 = 4.0;

/// Points sorted into square buckets (compressed rows: `starts[k]..starts[k + 1]` of
/// `points` lie in bucket `k`).
struct Buckets {
    origin: Vec2,
    cols: i32,
    rows: i32,
    starts: Vec<u32>,
    points: Vec<Vec2>,
}

impl Buckets {
    /// Buckets over the points' bounding box (queries may lie anywhere).
    fn new(points: &[Vec2]) -> Buckets {
        let (min, max) = points.iter().fold(
            (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let (origin, span) = if points.is_empty() {
            (Vec2::ZERO, Vec2::ZERO)
        } else {
            (min, max - min)
        };
        let cols = (span.x / BUCKET_PX) as i32 + 1;
        let rows = (span.y / BUCKET_PX) as i32 + 1;
        let mut buckets = Buckets {
            origin,
            cols,
            rows,
            starts: vec![0; (cols * rows) as usize + 1],
            points: vec![Vec2::ZERO; points.len()],
        };
        buckets.fill(points);
        buckets
    }

    fn fill(&mut self, points: &[Vec2]) {
        let keys: Vec<usize> = points.iter().map(|&p| self.key(p)).collect();
        for &k in &keys {
            self.starts[k + 1] += 1;
        }
        for k in 1..self.starts.len() {
            self.starts[k] += self.starts[k - 1];
        }
        let mut next = self.starts.clone();
        for (&p, &k) in points.iter().zip(&keys) {
            self.points[next[k] as usize] = p;
            next[k] += 1;
        }
    }

    fn cell(&self, p: Vec2) -> (i32, i32) {
        let c = ((p - self.origin) / BUCKET_PX).floor();
        (c.x as i32, c.y as i32)
    }

    fn key(&self, p: Vec2) -> usize {
        let (cx, cy) = self.cell(p);
        (cy.clamp(0, self.rows - 1) * self.cols + cx.clamp(0, self.cols - 1)) as usize
    }

    /// Distance from `q` to the nearest stored point, or `cap` when none is nearer.
    fn nearest(&self, q: Vec2, cap: f32) -> f32 {
        if self.points.is_empty() {
            return cap;
        }
        let (qx, qy) = self.cell(q);
        let mut best = cap * cap;
        // Points in ring r (Chebyshev bucket distance r from q's bucket, which may lie
        // outside the grid) are more than (r - 1) buckets away, so once the best distance is
        // within that, or beyond the cap, the search is over.
        let reach = (cap / BUCKET_PX).ceil() as i32 + 1;
        for r in 0..=reach {
            let bound = (r - 1).max(0) as f32 * BUCKET_PX;
            if bound * bound >= best {
                break;
            }
            self.search_ring(q, (qx, qy), r, &mut best);
        }
        best.sqrt().min(cap)
    }

    fn search_ring(&self, q: Vec2, (qx, qy): (i32, i32), r: i32, best: &mut f32) {
        let y_range = (qy - r).max(0)..=(qy + r).min(self.rows - 1);
        for cy in y_range {
            let on_edge_row = (cy - qy).abs() == r;
            let step = if on_edge_row { 1 } else { (2 * r).max(1) };
            let mut cx = qx - r;
            while cx <= qx + r {
                if (0..self.cols).contains(&cx) {
                    self.search_bucket(q, (cy * self.cols + cx) as usize, best);
                }
                cx += step;
            }
        }
    }

    fn search_bucket(&self, q: Vec2, k: usize, best: &mut f32) {
        let range = self.starts[k] as usize..self.starts[k + 1] as usize;
        for &p in &self.points[range] {
            *best = best.min(p.distance_squared(q));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force nearest distance, capped.
    fn nearest_brute(q: Vec2, points: &[Vec2], cap: f32) -> f32 {
        points.iter().map(|p| p.distance(q)).fold(cap, f32::min)
    }

    #[test]
    fn buckets_find_the_same_nearest_point_as_brute_force() {
        let mut seed = 12345u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1 << 24) as f32
        };
        let points: Vec<Vec2> = (0..400)
            .map(|_| Vec2::new(next() * 300.0, next() * 120.0))
            .collect();
        let buckets = Buckets::new(&points);
        for _ in 0..2000 {
            let q = Vec2::new(next() * 400.0 - 50.0, next() * 220.0 - 50.0);
            let fast = buckets.nearest(q, 32.0);
            let slow = nearest_brute(q, &points, 32.0);
            assert!((fast - slow).abs() < 1e-4, "{q}: {fast} vs {slow}");
        }
    }

    #[test]
    fn crossings_interpolate_linearly() {
        // One row: inside, inside, outside: the crossing sits where -1 -> 3 passes zero.
        let d = [-2.0, -1.0, 3.0];
        let c = zero_crossings(3, 1, &d);
        assert_eq!(c, vec![Vec2::new(1.75, 0.5)]);
        // Zero counts as outside.
        assert_eq!(
            zero_crossings(2, 1, &[-1.0, 0.0]),
            vec![Vec2::new(1.5, 0.5)]
        );
        assert!(zero_crossings(2, 2, &[1.0, 2.0, 0.0, 5.0]).is_empty());
    }
}
