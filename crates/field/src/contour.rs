//! Marching squares: the zero set of a field inside a rectangle, as closed polylines.
//!
//! # Conventions
//!
//! * **Grid.** The region is split into `nx × ny` equal cells, `nx = ceil(width / spacing)`
//!   (at least 1), so the effective cell size ([`Contours::cell_size`]) is at most the
//!   requested spacing and the outermost samples lie exactly on the region's edges. The field
//!   is sampled once per grid point; a point is *solid* when its distance is `< 0` (zero, NaN
//!   and `+inf` count as air).
//! * **Region edges.** Everything outside the rectangle is treated as air, so every contour is
//!   **closed**: where solid reaches the edge of the region, the contour runs along the edge
//!   (through the outermost samples). The enclosed area is therefore the solid area clipped
//!   to the region.
//! * **Orientation.** Contours are oriented with solid on their left: counter-clockwise
//!   around solid (positive [`Contour::signed_area`]) and clockwise around holes (negative).
//!   [`Contours::area`] is the sum of the signed areas. A contour's last point connects back
//!   to its first; the first point is not repeated.
//! * **Saddles.** A cell whose diagonal corners agree but whose neighbouring corners differ is
//!   resolved by sampling the field at the cell centre: a solid centre joins the two solid
//!   corners, an air centre separates them.
//! * **Vertices.** Each vertex lies on one grid edge, strictly inside it (never on a sample
//!   point except where a contour runs along the region's edge), at the linear interpolation
//!   of the two samples, then refined by safeguarded Newton steps along that edge (using the
//!   field's gradient, falling back to false position when a step would leave the bracket).
//!   Because vertices never leave their grid edge, unsimplified contours neither cross
//!   themselves nor each other.
//! * **Simplification** (optional, Douglas–Peucker) can make contours cross; loops that
//!   collapse below three points are dropped.
//! * **Order.** Contours come out in the row-major order (bottom row first, left to right) of
//!   the grid edge holding their first vertex; the output is a deterministic function of the
//!   field, the region and the options.

use glam::Vec2;
use thiserror::Error;

use super::aabb::Aabb;
use super::sdf::Sdf;

/// Most grid samples one extraction may take (`(nx + 1) * (ny + 1)`).
pub const MAX_CONTOUR_SAMPLES: u64 = 1 << 26;

/// Refinement iterations above this are treated as this many (Newton has long converged).
pub const MAX_REFINE_ITERATIONS: u32 = 16;

/// How contours are extracted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContourOptions {
    /// Largest grid cell size in world units (finite, > 0). Features thinner than about one
    /// cell may be missed.
    pub spacing: f32,
    /// Newton steps that move each vertex along its grid edge onto the zero set (0 = plain
    /// linear interpolation; default 2; capped at [`MAX_REFINE_ITERATIONS`]).
    pub refine_iterations: u32,
    /// Douglas–Peucker tolerance in world units (0 = off; finite, >= 0).
    pub simplify_tolerance: f32,
}

impl Default for ContourOptions {
    fn default() -> Self {
        ContourOptions {
            spacing: 1.0,
            refine_iterations: 2,
            simplify_tolerance: 0.0,
        }
    }
}

/// One closed contour, oriented with solid on its left (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    /// The vertices in order; the last connects back to the first (not repeated). At least 3.
    pub points: Vec<Vec2>,
}

impl Contour {
    /// Shoelace area: positive around solid (counter-clockwise), negative around holes.
    pub fn signed_area(&self) -> f64 {
        signed_area(&self.points)
    }

    /// True when the contour bounds a hole (clockwise, negative signed area).
    pub fn is_hole(&self) -> bool {
        self.signed_area() < 0.0
    }

    /// The contour's edges as point pairs, including the closing edge.
    pub fn segments(&self) -> impl Iterator<Item = (Vec2, Vec2)> + '_ {
        let n = self.points.len();
        (0..n).map(move |i| (self.points[i], self.points[(i + 1) % n]))
    }
}

/// The contours of a field in a region.
#[derive(Clone, Debug, PartialEq)]
pub struct Contours {
    /// Closed contours in deterministic row-major order.
    pub loops: Vec<Contour>,
    /// The region that was scanned.
    pub region: Aabb,
    /// The effective cell size used (at most the requested spacing on each axis).
    pub cell_size: Vec2,
}

impl Contours {
    /// Enclosed solid area: the sum of the contours' signed areas.
    pub fn area(&self) -> f64 {
        self.loops.iter().map(Contour::signed_area).sum()
    }

    /// Total number of vertices over all contours.
    pub fn vertex_count(&self) -> usize {
        self.loops.iter().map(|l| l.points.len()).sum()
    }

    /// Whether `p` is enclosed by the contours (even-odd rule; one pass over every edge, so
    /// meant for tests and occasional queries).
    pub fn contains(&self, p: Vec2) -> bool {
        let (px, py) = (f64::from(p.x), f64::from(p.y));
        let mut inside = false;
        for c in &self.loops {
            for (a, b) in c.segments() {
                if crosses_ray(a, b, px, py) {
                    inside = !inside;
                }
            }
        }
        inside
    }
}

/// Whether the segment `a`-`b` crosses the ray from `(px, py)` towards `+x` (half-open in y,
/// so a vertex on the ray is counted once).
pub(crate) fn crosses_ray(a: Vec2, b: Vec2, px: f64, py: f64) -> bool {
    let (ax, ay, bx, by) = (
        f64::from(a.x),
        f64::from(a.y),
        f64::from(b.x),
        f64::from(b.y),
    );
    if (ay > py) == (by > py) {
        return false;
    }
    let x = ax + (py - ay) * (bx - ax) / (by - ay);
    x > px
}

fn signed_area(points: &[Vec2]) -> f64 {
    let n = points.len();
    if n < 3 {
        return 0.0;
    }
    let mut sum = 0.0f64;
    for i in 0..n {
        let a = points[i];
        let b = points[(i + 1) % n];
        sum += f64::from(a.x) * f64::from(b.y) - f64::from(b.x) * f64::from(a.y);
    }
    0.5 * sum
}

/// Why contours could not be extracted.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ContourError {
    /// The region has an infinite or NaN bound (or its size overflows).
    #[error("region must be finite, got min {min} max {max}")]
    NonFiniteRegion {
        /// Lower corner.
        min: Vec2,
        /// Upper corner.
        max: Vec2,
    },
    /// The region is empty or has zero width or height.
    #[error("region must have min < max on both axes, got min {min} max {max}")]
    EmptyRegion {
        /// Lower corner.
        min: Vec2,
        /// Upper corner.
        max: Vec2,
    },
    /// The spacing is zero, negative, infinite or NaN.
    #[error("spacing must be finite and > 0, got {spacing}")]
    InvalidSpacing {
        /// The spacing given.
        spacing: f32,
    },
    /// The simplification tolerance is negative, infinite or NaN.
    #[error("simplify_tolerance must be finite and >= 0, got {tolerance}")]
    InvalidSimplifyTolerance {
        /// The tolerance given.
        tolerance: f32,
    },
    /// The region at this spacing needs more samples than [`MAX_CONTOUR_SAMPLES`].
    #[error(
        "region {width} x {height} at spacing {spacing} needs {samples} samples, over the limit of {limit}; use a larger spacing or a smaller region"
    )]
    TooManySamples {
        /// Region width.
        width: f32,
        /// Region height.
        height: f32,
        /// The spacing given.
        spacing: f32,
        /// Samples needed (saturating).
        samples: u64,
        /// The limit.
        limit: u64,
    },
}

const NONE: u32 = u32::MAX;

/// Extract the closed contours of `field`'s zero set inside `region` (see the module docs for
/// the grid, edge, orientation and saddle conventions).
///
/// ```
/// use std::collections::BTreeMap;
/// use craterfield_field::{Aabb, Graph, Node};
/// use craterfield_field::contour::{extract_contours, ContourOptions};
/// let disc = Graph::compile(&Node::Circle { center: [0.0, 0.0], radius: 10.0 }, &BTreeMap::new())?;
/// let region = Aabb::new(glam::Vec2::splat(-16.0), glam::Vec2::splat(16.0));
/// let contours = extract_contours(&disc, region, &ContourOptions::default())?;
/// assert_eq!(contours.loops.len(), 1);
/// let exact = std::f64::consts::PI * 100.0;
/// assert!(contours.area() > 0.0); // counter-clockwise around solid
/// assert!((contours.area() - exact).abs() < 0.005 * exact);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn extract_contours<F: Sdf>(
    field: &F,
    region: Aabb,
    opts: &ContourOptions,
) -> Result<Contours, ContourError> {
    let grid = Grid::new(region, opts)?;
    let iters = opts.refine_iterations.min(MAX_REFINE_ITERATIONS);
    let mut builder = Builder {
        field,
        grid: &grid,
        iters,
        positions: Vec::new(),
        next: Vec::new(),
    };
    builder.scan();
    let Builder {
        positions, next, ..
    } = builder;
    let mut loops = chain(&positions, &next);
    if opts.simplify_tolerance > 0.0 {
        loops = loops
            .into_iter()
            .map(|pts| simplify_closed(&pts, opts.simplify_tolerance))
            .filter(|pts| pts.len() >= 3)
            .collect();
    }
    Ok(Contours {
        loops: loops.into_iter().map(|points| Contour { points }).collect(),
        region,
        cell_size: grid.cell_size,
    })
}

/// The validated sample grid. Extended indices add one ring of air "pad" samples around the
/// region: extended column `I` is region column `I - 1`, and `I = 0`, `I = nx + 2` are pads.
struct Grid {
    xs: Vec<f32>,
    ys: Vec<f32>,
    cell_size: Vec2,
}

impl Grid {
    fn new(region: Aabb, opts: &ContourOptions) -> Result<Grid, ContourError> {
        let (min, max) = (region.min, region.max);
        let spacing = opts.spacing;
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(ContourError::InvalidSpacing { spacing });
        }
        let tol = opts.simplify_tolerance;
        if !(tol.is_finite() && tol >= 0.0) {
            return Err(ContourError::InvalidSimplifyTolerance { tolerance: tol });
        }
        if !region.is_finite() {
            return Err(ContourError::NonFiniteRegion { min, max });
        }
        if !(min.x < max.x && min.y < max.y) {
            return Err(ContourError::EmptyRegion { min, max });
        }
        let size = max - min;
        if !size.is_finite() {
            return Err(ContourError::NonFiniteRegion { min, max });
        }
        let w = f64::from(max.x) - f64::from(min.x);
        let h = f64::from(max.y) - f64::from(min.y);
        let s = f64::from(spacing);
        let nx = (w / s).ceil().max(1.0);
        let ny = (h / s).ceil().max(1.0);
        let samples = (nx + 1.0) * (ny + 1.0);
        if samples.is_nan() || samples > MAX_CONTOUR_SAMPLES as f64 {
            return Err(ContourError::TooManySamples {
                width: size.x,
                height: size.y,
                spacing,
                // Saturating conversion; the comparison above rules out NaN being small.
                samples: samples as u64,
                limit: MAX_CONTOUR_SAMPLES,
            });
        }
        let (nx, ny) = (nx as usize, ny as usize);
        let axis = |lo: f32, len: f64, n: usize| -> Vec<f32> {
            (0..=n)
                .map(|i| {
                    if i == n {
                        // The last sample is exactly the upper bound.
                        (f64::from(lo) + len) as f32
                    } else {
                        (f64::from(lo) + len * (i as f64 / n as f64)) as f32
                    }
                })
                .collect()
        };
        let xs = axis(min.x, w, nx);
        let ys = axis(min.y, h, ny);
        let cell_size = Vec2::new((w / nx as f64) as f32, (h / ny as f64) as f32);
        Ok(Grid { xs, ys, cell_size })
    }

    /// Cells along x in extended indices (`nx + 2`).
    fn ext_cells_x(&self) -> usize {
        self.xs.len() + 1
    }

    /// Cells along y in extended indices (`ny + 2`).
    fn ext_cells_y(&self) -> usize {
        self.ys.len() + 1
    }

    fn x(&self, ext: usize) -> f32 {
        self.xs[ext.saturating_sub(1).min(self.xs.len() - 1)]
    }

    fn y(&self, ext: usize) -> f32 {
        self.ys[ext.saturating_sub(1).min(self.ys.len() - 1)]
    }

    fn is_pad_x(&self, ext: usize) -> bool {
        ext == 0 || ext > self.xs.len()
    }

    fn is_pad_y(&self, ext: usize) -> bool {
        ext == 0 || ext > self.ys.len()
    }
}

/// One sample of the extended grid.
#[derive(Clone, Copy)]
struct GridSample {
    pos: Vec2,
    value: f32,
    pad: bool,
}

impl GridSample {
    fn solid(&self) -> bool {
        self.value < 0.0
    }
}

struct Builder<'a, F> {
    field: &'a F,
    grid: &'a Grid,
    iters: u32,
    positions: Vec<Vec2>,
    /// `next[v]`: the vertex after `v` along its contour.
    next: Vec<u32>,
}

impl<F: Sdf> Builder<'_, F> {
    fn sample_row(&self, ext_j: usize) -> Vec<GridSample> {
        let g = self.grid;
        let pad_row = g.is_pad_y(ext_j);
        let y = g.y(ext_j);
        (0..=g.ext_cells_x())
            .map(|ext_i| {
                let pos = Vec2::new(g.x(ext_i), y);
                let pad = pad_row || g.is_pad_x(ext_i);
                let value = if pad {
                    f32::INFINITY
                } else {
                    self.field.distance(pos)
                };
                GridSample { pos, value, pad }
            })
            .collect()
    }

    /// The vertex on the grid edge `a`-`b`, if the edge crosses the contour.
    fn edge_vertex(&mut self, a: GridSample, b: GridSample) -> u32 {
        if a.solid() == b.solid() {
            return NONE;
        }
        let (s, o) = if a.solid() { (a, b) } else { (b, a) };
        let pos = if o.pad {
            // Outside the region is air: the contour runs through the last solid sample.
            s.pos
        } else {
            self.refine(s, o)
        };
        let id = self.positions.len() as u32;
        self.positions.push(pos);
        self.next.push(NONE);
        id
    }

    /// The zero crossing between solid sample `s` and air sample `o`, strictly inside the
    /// edge.
    fn refine(&self, s: GridSample, o: GridSample) -> Vec2 {
        let dir = o.pos - s.pos;
        let len = dir.length();
        // Keep the vertex off both sample points (by more than float rounding), so vertices
        // on different edges never coincide and saddle segments never touch.
        let scale = s.pos.abs().max(o.pos.abs()).max_element();
        let eps = (1e-4f32).max(16.0 * f32::EPSILON * scale / len.max(f32::MIN_POSITIVE));
        let eps = eps.min(0.25);
        let (mut lo, mut dlo) = (0.0f32, s.value);
        let (mut hi, mut dhi) = (1.0f32, o.value);
        let mut t = if dhi.is_finite() {
            dlo / (dlo - dhi)
        } else {
            0.5
        };
        if !t.is_finite() {
            t = 0.5;
        }
        for _ in 0..self.iters {
            let smp = self.field.sample(s.pos + dir * t);
            let d = smp.distance;
            if d.is_nan() {
                break;
            }
            if d < 0.0 {
                (lo, dlo) = (t, d);
            } else {
                (hi, dhi) = (t, d);
            }
            if d == 0.0 {
                break;
            }
            let slope = smp.gradient.dot(dir);
            let newton = t - d / slope;
            t = if newton > lo && newton < hi {
                newton
            } else if dhi.is_finite() && dhi > dlo {
                lo + (hi - lo) * (-dlo / (dhi - dlo))
            } else {
                0.5 * (lo + hi)
            };
            if !t.is_finite() {
                t = 0.5 * (lo + hi);
            }
        }
        let t = t.clamp(eps, 1.0 - eps);
        s.pos + dir * t
    }

    fn scan(&mut self) {
        let g = self.grid;
        let cells_x = g.ext_cells_x();
        let mut bottom = self.sample_row(0);
        // Row 0 is all pads: no horizontal crossings.
        let mut h_bottom = vec![NONE; cells_x];
        for ext_j in 0..g.ext_cells_y() {
            let top = self.sample_row(ext_j + 1);
            let h_top: Vec<u32> = (0..cells_x)
                .map(|i| self.edge_vertex(top[i], top[i + 1]))
                .collect();
            let vert: Vec<u32> = (0..=cells_x)
                .map(|i| self.edge_vertex(bottom[i], top[i]))
                .collect();
            for i in 0..cells_x {
                let corners = [bottom[i], bottom[i + 1], top[i + 1], top[i]];
                // Edges counter-clockwise: bottom, right, top, left.
                let edges = [h_bottom[i], vert[i + 1], h_top[i], vert[i]];
                self.cell(corners, edges);
            }
            bottom = top;
            h_bottom = h_top;
        }
    }

    /// Link the segments of one cell. Corners and edges are counter-clockwise from the
    /// bottom-left corner; edge `k` joins corners `k` and `k + 1`.
    fn cell(&mut self, corners: [GridSample; 4], edges: [u32; 4]) {
        let solid = corners.map(|c| c.solid());
        let mask = solid
            .iter()
            .enumerate()
            .fold(0u8, |m, (k, &s)| m | (u8::from(s) << k));
        if mask == 0 || mask == 15 {
            return;
        }
        // Edge k is an exit (solid -> air walking counter-clockwise) when corner k is solid.
        // A segment goes from an exit edge to an entry edge, so solid lies on its left.
        if mask == 0b0101 || mask == 0b1010 {
            let centre = (corners[0].pos + corners[2].pos) * 0.5;
            let joined = self.field.distance(centre) < 0.0;
            for k in 0..4 {
                if solid[k] {
                    let entry = if joined { (k + 1) % 4 } else { (k + 3) % 4 };
                    self.link(edges[k], edges[entry]);
                }
            }
            return;
        }
        let mut exit = None;
        let mut entry = None;
        for k in 0..4 {
            if solid[k] != solid[(k + 1) % 4] {
                if solid[k] {
                    exit = Some(k);
                } else {
                    entry = Some(k);
                }
            }
        }
        if let (Some(x), Some(n)) = (exit, entry) {
            self.link(edges[x], edges[n]);
        }
    }

    fn link(&mut self, from: u32, to: u32) {
        if let Some(slot) = self.next.get_mut(from as usize) {
            *slot = to;
        }
    }
}

/// Walk the `next` links into loops, in vertex order; removes consecutive duplicate points
/// and drops loops with fewer than 3 points.
fn chain(positions: &[Vec2], next: &[u32]) -> Vec<Vec<Vec2>> {
    let mut visited = vec![false; positions.len()];
    let mut loops = Vec::new();
    for start in 0..positions.len() {
        if visited[start] {
            continue;
        }
        let mut pts: Vec<Vec2> = Vec::new();
        let mut cur = start;
        while !visited[cur] {
            visited[cur] = true;
            let p = positions[cur];
            if pts.last() != Some(&p) {
                pts.push(p);
            }
            match next.get(cur) {
                Some(&n) if (n as usize) < positions.len() => cur = n as usize,
                _ => break,
            }
        }
        while pts.len() > 1 && pts.first() == pts.last() {
            pts.pop();
        }
        if pts.len() >= 3 {
            loops.push(pts);
        }
    }
    loops
}

/// Distance from `p` to the segment `a`-`b`.
fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f64 {
    let (px, py) = (f64::from(p.x), f64::from(p.y));
    let (ax, ay) = (f64::from(a.x), f64::from(a.y));
    let (bx, by) = (f64::from(b.x), f64::from(b.y));
    let (dx, dy) = (bx - ax, by - ay);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((px - ax) * dx + (py - ay) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (ax + t * dx - px, ay + t * dy - py);
    (qx * qx + qy * qy).sqrt()
}

/// Douglas–Peucker on a closed polyline, anchored at the first point and the point farthest
/// from it.
fn simplify_closed(pts: &[Vec2], tol: f32) -> Vec<Vec2> {
    let n = pts.len();
    if n < 4 {
        return pts.to_vec();
    }
    let tol = f64::from(tol);
    let at = |i: usize| pts[i % n];
    let far = (1..n)
        .map(|i| (i, pts[0].distance_squared(pts[i])))
        .fold((1, -1.0f32), |best, c| if c.1 > best.1 { c } else { best })
        .0;
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[far] = true;
    let mut stack = vec![(0usize, far), (far, n)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (pa, pb) = (at(a), at(b));
        let mut best = (a, -1.0f64);
        for (i, &p) in pts.iter().enumerate().take(b).skip(a + 1) {
            let d = segment_distance(p, pa, pb);
            if d > best.1 {
                best = (i, d);
            }
        }
        if best.1 > tol {
            keep[best.0] = true;
            stack.push((best.0, b));
            stack.push((a, best.0));
        }
    }
    pts.iter()
        .zip(&keep)
        .filter_map(|(p, &k)| k.then_some(*p))
        .collect()
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;
    use std::f64::consts::PI;

    use super::*;
    use crate::{Graph, Level, Node};

    fn graph(node: Node) -> Graph {
        Graph::compile(&node, &BTreeMap::new()).expect("valid test node")
    }

    fn square(c: f32, h: f32) -> Aabb {
        Aabb::centered(Vec2::splat(c), Vec2::splat(h))
    }

    fn opts(spacing: f32) -> ContourOptions {
        ContourOptions {
            spacing,
            ..ContourOptions::default()
        }
    }

    #[test]
    fn circle_is_one_accurate_ccw_loop() {
        for center in [[0.0, 0.0], [0.37, -0.21]] {
            let g = graph(Node::Circle {
                center,
                radius: 10.0,
            });
            let c = extract_contours(&g, square(0.0, 16.0), &opts(1.0)).unwrap();
            assert_eq!(c.loops.len(), 1, "center {center:?}");
            let l = &c.loops[0];
            assert!(l.points.len() > 40);
            let cv = Vec2::from(center);
            for p in &l.points {
                let err = ((*p - cv).length() - 10.0).abs();
                assert!(err < 1e-3, "vertex {p} is {err} off the circle");
            }
            let exact = PI * 100.0;
            let area = l.signed_area();
            assert!(area > 0.0, "solid must be counter-clockwise");
            assert!(!l.is_hole());
            assert!(
                ((area - exact) / exact).abs() < 0.005,
                "area {area} vs {exact}"
            );
            assert!(c.contains(cv));
            assert!(!c.contains(Vec2::new(15.0, 15.0)));
        }
    }

    #[test]
    fn refinement_beats_linear_interpolation() {
        let g = graph(Node::Circle {
            center: [0.3, 0.1],
            radius: 10.0,
        });
        let max_err = |iters: u32| {
            let o = ContourOptions {
                spacing: 1.0,
                refine_iterations: iters,
                simplify_tolerance: 0.0,
            };
            let c = extract_contours(&g, square(0.0, 16.0), &o).unwrap();
            c.loops[0]
                .points
                .iter()
                .map(|p| ((*p - Vec2::new(0.3, 0.1)).length() - 10.0).abs())
                .fold(0.0f32, f32::max)
        };
        let (raw, refined) = (max_err(0), max_err(2));
        assert!(raw > 1e-3, "linear interpolation error {raw}");
        assert!(refined < 1e-4, "refined error {refined}");
    }

    #[test]
    fn ring_gives_outer_loop_and_opposite_hole() {
        let g = graph(Node::Ring {
            center: [0.0, 0.0],
            radius: 12.0,
            width: 6.0,
        });
        let c = extract_contours(&g, square(0.0, 20.0), &opts(1.0)).unwrap();
        assert_eq!(c.loops.len(), 2);
        let areas: Vec<f64> = c.loops.iter().map(Contour::signed_area).collect();
        assert_eq!(areas.iter().filter(|a| **a > 0.0).count(), 1);
        assert_eq!(areas.iter().filter(|a| **a < 0.0).count(), 1);
        let exact = PI * (15.0f64.powi(2) - 9.0f64.powi(2));
        assert!(((c.area() - exact) / exact).abs() < 0.005, "{}", c.area());
        assert!(!c.contains(Vec2::ZERO));
        assert!(c.contains(Vec2::new(12.0, 0.0)));
    }

    #[test]
    fn thin_bars_vanish_and_thick_bars_appear() {
        let bar = |thickness: f32| {
            graph(Node::OrientedBox {
                a: [-10.0, 0.9],
                b: [10.0, 0.9],
                thickness,
            })
        };
        let spacing = 2.0;
        // Thinner than a cell and between sample rows: no sample sees it.
        let thin = extract_contours(&bar(0.5), square(0.0, 16.0), &opts(spacing)).unwrap();
        assert!(thin.loops.is_empty(), "a bar between rows is not sampled");
        let thick =
            extract_contours(&bar(3.0 * spacing), square(0.0, 16.0), &opts(spacing)).unwrap();
        assert_eq!(thick.loops.len(), 1);
        let exact = 20.0 * 6.0;
        assert!(
            ((thick.area() - exact) / exact).abs() < 0.1,
            "{}",
            thick.area()
        );
    }

    #[test]
    fn two_circles_two_loops_in_scan_order() {
        let g = graph(Node::Union(vec![
            Node::Circle {
                center: [-8.0, 5.0],
                radius: 4.0,
            },
            Node::Circle {
                center: [8.0, -5.0],
                radius: 3.0,
            },
        ]));
        let c = extract_contours(&g, square(0.0, 16.0), &opts(0.5)).unwrap();
        assert_eq!(c.loops.len(), 2);
        // Row-major scan from the bottom: the lower circle comes first.
        assert!(c.loops[0].points[0].y < c.loops[1].points[0].y);
        assert!(c.loops.iter().all(|l| l.signed_area() > 0.0));
        let again = extract_contours(&g, square(0.0, 16.0), &opts(0.5)).unwrap();
        assert_eq!(c, again, "deterministic");
    }

    #[test]
    fn solid_touching_the_edge_is_closed_along_it() {
        // Ground below y = 0.3, region straddles it: the solid part is clipped to the region.
        let g = graph(Node::HalfPlane {
            point: [0.0, 0.3],
            normal: [0.0, 1.0],
        });
        let region = Aabb::new(Vec2::new(-5.0, -4.0), Vec2::new(5.0, 4.0));
        let c = extract_contours(&g, region, &opts(1.0)).unwrap();
        assert_eq!(c.loops.len(), 1);
        let exact = 10.0 * 4.3;
        assert!((c.area() - exact).abs() < 1e-3, "{}", c.area());
        for p in &c.loops[0].points {
            assert!(region.contains(*p), "{p} outside the region");
        }
        // Fully solid region: one loop, the region's boundary.
        let all = extract_contours(
            &g,
            Aabb::new(Vec2::splat(-3.0), Vec2::splat(-1.0)),
            &opts(0.5),
        )
        .unwrap();
        assert_eq!(all.loops.len(), 1);
        assert!((all.area() - 4.0).abs() < 1e-5);
        // Fully air: nothing.
        let none = extract_contours(
            &g,
            Aabb::new(Vec2::splat(1.0), Vec2::splat(3.0)),
            &opts(0.5),
        )
        .unwrap();
        assert!(none.loops.is_empty());
    }

    #[test]
    fn saddles_follow_the_centre_value() {
        // Two discs touching diagonally across one cell centre: at the centre the union is
        // solid, so the saddle joins them into one loop.
        let joined = graph(Node::Union(vec![
            Node::Box {
                center: [-1.0, -1.0],
                half_size: [1.2, 1.2],
            },
            Node::Box {
                center: [1.0, 1.0],
                half_size: [1.2, 1.2],
            },
        ]));
        let region = Aabb::new(Vec2::splat(-3.5), Vec2::splat(3.5));
        let c = extract_contours(&joined, region, &opts(1.0)).unwrap();
        assert_eq!(c.loops.len(), 1);
        let apart = graph(Node::Union(vec![
            Node::Box {
                center: [-1.0, -1.0],
                half_size: [0.8, 0.8],
            },
            Node::Box {
                center: [1.0, 1.0],
                half_size: [0.8, 0.8],
            },
        ]));
        let c = extract_contours(&apart, region, &opts(1.0)).unwrap();
        assert_eq!(c.loops.len(), 2);
    }

    #[test]
    fn simplification_reduces_points_within_tolerance() {
        let g = graph(Node::Circle {
            center: [0.0, 0.0],
            radius: 10.0,
        });
        let full = extract_contours(&g, square(0.0, 16.0), &opts(0.5)).unwrap();
        let o = ContourOptions {
            spacing: 0.5,
            refine_iterations: 2,
            simplify_tolerance: 0.05,
        };
        let simple = extract_contours(&g, square(0.0, 16.0), &o).unwrap();
        assert_eq!(simple.loops.len(), 1);
        assert!(simple.vertex_count() * 2 < full.vertex_count());
        for p in &simple.loops[0].points {
            assert!((p.length() - 10.0).abs() < 1e-3);
        }
        assert!((simple.area() - full.area()).abs() / full.area() < 0.005);
    }

    fn err(region: Aabb, o: ContourOptions) -> String {
        let g = graph(Node::Circle {
            center: [0.0, 0.0],
            radius: 1.0,
        });
        match extract_contours(&g, region, &o) {
            Ok(_) => panic!("expected an error for {region:?} {o:?}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn bad_arguments_are_named() {
        let r = square(0.0, 4.0);
        let m = err(r, opts(f32::NAN));
        assert!(m.contains("spacing") && m.contains("NaN"), "{m}");
        let m = err(r, opts(0.0));
        assert!(m.contains("spacing") && m.contains("got 0"), "{m}");
        let m = err(r, opts(-1.0));
        assert!(m.contains("spacing") && m.contains("-1"), "{m}");
        let m = err(r, opts(f32::INFINITY));
        assert!(m.contains("spacing") && m.contains("inf"), "{m}");
        let inverted = Aabb::new(Vec2::new(4.0, 0.0), Vec2::new(0.0, 4.0));
        let m = err(inverted, opts(1.0));
        assert!(m.contains("region") && m.contains("min < max"), "{m}");
        let m = err(Aabb::EMPTY, opts(1.0));
        assert!(m.contains("region") && m.contains("finite"), "{m}");
        let flat = Aabb::new(Vec2::new(0.0, 1.0), Vec2::new(4.0, 1.0));
        assert!(err(flat, opts(1.0)).contains("min < max"));
        let nan = Aabb::new(Vec2::new(f32::NAN, 0.0), Vec2::splat(1.0));
        assert!(err(nan, opts(1.0)).contains("finite"));
        let huge = Aabb::new(Vec2::splat(-3e38), Vec2::splat(3e38));
        assert!(err(huge, opts(1.0)).contains("finite"));
        let m = err(square(0.0, 100_000.0), opts(1.0));
        assert!(m.contains("samples") && m.contains("limit"), "{m}");
        let m = err(r, opts(1e-30));
        assert!(m.contains("samples"), "{m}");
        let m = err(
            r,
            ContourOptions {
                simplify_tolerance: -1.0,
                ..opts(1.0)
            },
        );
        assert!(m.contains("simplify_tolerance"), "{m}");
    }

    #[test]
    fn tiny_and_odd_regions() {
        let g = graph(Node::Circle {
            center: [0.0, 0.0],
            radius: 1.0,
        });
        // Region smaller than one cell: one cell, still closed.
        let c = extract_contours(&g, square(0.0, 0.1), &opts(5.0)).unwrap();
        assert_eq!(c.loops.len(), 1);
        assert!((c.area() - 0.04).abs() < 1e-6);
        // Non-integer cell counts: effective spacing shrinks.
        let r = Aabb::new(Vec2::new(-2.0, -2.0), Vec2::new(2.5, 2.2));
        let c = extract_contours(&g, r, &opts(0.7)).unwrap();
        assert!(c.cell_size.x <= 0.7 && c.cell_size.y <= 0.7);
        assert_eq!(c.loops.len(), 1);
    }

    #[test]
    fn default_level_window_extracts() {
        let level = Level::default_level();
        let region = Aabb::new(Vec2::new(1024.0, 256.0), Vec2::new(1536.0, 768.0));
        let c = extract_contours(level.graph(), region, &opts(2.0)).unwrap();
        assert!(!c.loops.is_empty());
        let area = c.area();
        assert!(area > 0.0 && area <= 512.0 * 512.0 + 1e-3, "{area}");
    }
}
