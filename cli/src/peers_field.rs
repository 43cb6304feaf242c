//! The polygon peers of `bench field --peers` (feature `peers`): the terrain a game would
//! otherwise keep, as polygons cut by i_overlay, queried through a uniform edge grid and
//! through parry2d's `Polyline`. Benchmark baselines only: the library never depends on them.
//!
//! * Inserts: each explosion is a 32-gon subtracted with i_overlay's integer overlay
//!   (coordinates at 1/16 unit), either per 256-unit chunk it touches (how games keep
//!   polygon terrain fast) or from the whole level's shapes.
//! * Distance: a uniform grid of 32-unit cells, each listing the edges within [`CLAMP`] of
//!   it; the distance is the nearest listed edge's, clamped at [`CLAMP`], signed by the
//!   side of that edge (contours are counter-clockwise around solid) or, in a cell with no
//!   edges, by the cell's inside flag. Gradients come from the nearest point.
//! * parry2d: one `Polyline` of every edge; unsigned distance, ray casts and circle casts.

use glam::Vec2;
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::Overlay;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;
use parry2d::math::Pose;
use parry2d::query::{PointQuery, Ray, RayCast, ShapeCastOptions, cast_shapes};
use parry2d::shape::{Ball, Polyline};

use crate::field_scene::{self, BOXES, HEIGHT, ISLANDS, WIDTH};

/// Integer units per world unit.
const SCALE: f32 = 16.0;
/// Side of an insert chunk, world units.
const CHUNK: f32 = 256.0;
/// Sides of an explosion polygon (and of an island's).
const SIDES: usize = 32;
/// Side of an edge-grid cell, world units.
const CELL: f32 = 32.0;
/// Distances are clamped here (as craterfield's band clamps them).
pub(crate) const CLAMP: f32 = 64.0;

type Contour = Vec<IntPoint>;
type Shape = Vec<Contour>;

fn int(p: Vec2) -> IntPoint {
    IntPoint::new((p.x * SCALE).round() as i32, (p.y * SCALE).round() as i32)
}

fn world(p: IntPoint) -> Vec2 {
    Vec2::new(p.x as f32 / SCALE, p.y as f32 / SCALE)
}

fn polygon(points: impl IntoIterator<Item = Vec2>) -> Contour {
    points.into_iter().map(int).collect()
}

fn ngon(c: Vec2, r: f32) -> Contour {
    polygon(
        (0..SIDES)
            .map(|i| c + Vec2::from_angle(i as f32 * std::f32::consts::TAU / SIDES as f32) * r),
    )
}

fn rect(min: Vec2, max: Vec2) -> Contour {
    polygon([min, Vec2::new(max.x, min.y), max, Vec2::new(min.x, max.y)])
}

/// The level's solid set as counter-clockwise shapes.
fn level_shapes() -> Vec<Shape> {
    let mut ground = vec![Vec2::new(0.0, 0.0), Vec2::new(WIDTH, 0.0)];
    ground.extend(field_scene::ground_samples().into_iter().rev());
    let mut shapes = vec![vec![polygon(ground)]];
    shapes.extend(ISLANDS.iter().map(|&(c, r)| vec![ngon(c, r)]));
    shapes.extend(BOXES.iter().map(|&(c, h)| vec![rect(c - h, c + h)]));
    shapes
}

/// Polygon terrain cut into chunks (one chunk covering the level: the whole-level peer).
pub(crate) struct PolygonTerrain {
    chunks: Vec<Chunk>,
}

struct Chunk {
    min: Vec2,
    max: Vec2,
    shapes: Vec<Shape>,
}

impl PolygonTerrain {
    /// The level in `side`-unit chunks; `None` keeps it whole.
    pub(crate) fn new(chunked: bool) -> PolygonTerrain {
        let side = if chunked { CHUNK } else { WIDTH.max(HEIGHT) };
        let all = level_shapes();
        let (nx, ny) = (
            (WIDTH / side).ceil() as usize,
            (HEIGHT / side).ceil() as usize,
        );
        let mut chunks = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let min = Vec2::new(i as f32 * side, j as f32 * side);
                let max = (min + Vec2::splat(side)).min(Vec2::new(WIDTH, HEIGHT));
                let shapes = Overlay::from_subj_and_clip(&all, &[vec![rect(min, max)]])
                    .overlay(OverlayRule::Intersect, FillRule::NonZero);
                chunks.push(Chunk { min, max, shapes });
            }
        }
        PolygonTerrain { chunks }
    }

    /// Subtracts a disc from every chunk it touches.
    pub(crate) fn carve(&mut self, center: Vec2, radius: f32) {
        let hole = vec![ngon(center, radius)];
        let (lo, hi) = (center - Vec2::splat(radius), center + Vec2::splat(radius));
        for chunk in &mut self.chunks {
            let touches = lo.x < chunk.max.x
                && hi.x > chunk.min.x
                && lo.y < chunk.max.y
                && hi.y > chunk.min.y;
            if touches && !chunk.shapes.is_empty() {
                chunk.shapes =
                    Overlay::from_subj_and_clip(&chunk.shapes, std::slice::from_ref(&hole))
                        .overlay(OverlayRule::Difference, FillRule::NonZero);
            }
        }
    }

    /// Every boundary edge in world units (chunk seams included when chunked).
    pub(crate) fn edges(&self) -> Vec<[Vec2; 2]> {
        let mut edges = Vec::new();
        for contour in self.chunks.iter().flat_map(|c| c.shapes.iter().flatten()) {
            for (k, &a) in contour.iter().enumerate() {
                let b = contour[(k + 1) % contour.len()];
                edges.push([world(a), world(b)]);
            }
        }
        edges
    }
}

/// A uniform grid of edges: signed distance clamped at [`CLAMP`].
pub(crate) struct EdgeGrid {
    nx: usize,
    ny: usize,
    /// Per cell: the range of `lists` it owns.
    spans: Vec<(u32, u32)>,
    lists: Vec<u32>,
    edges: Vec<[Vec2; 2]>,
    /// Per cell with no edges: whether it is solid.
    inside: Vec<bool>,
}

impl EdgeGrid {
    pub(crate) fn new(edges: Vec<[Vec2; 2]>) -> EdgeGrid {
        let (nx, ny) = (
            (WIDTH / CELL).ceil() as usize,
            (HEIGHT / CELL).ceil() as usize,
        );
        let mut per_cell: Vec<Vec<u32>> = vec![Vec::new(); nx * ny];
        for (k, e) in edges.iter().enumerate() {
            let lo = (e[0].min(e[1]) - Vec2::splat(CLAMP)) / CELL;
            let hi = (e[0].max(e[1]) + Vec2::splat(CLAMP)) / CELL;
            let (i0, j0) = (lo.x.max(0.0) as usize, lo.y.max(0.0) as usize);
            let (i1, j1) = ((hi.x as usize).min(nx - 1), (hi.y as usize).min(ny - 1));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    per_cell[j * nx + i].push(k as u32);
                }
            }
        }
        let mut spans = Vec::with_capacity(nx * ny);
        let mut lists = Vec::new();
        for list in &per_cell {
            spans.push((lists.len() as u32, (lists.len() + list.len()) as u32));
            lists.extend_from_slice(list);
        }
        let inside = (0..nx * ny)
            .map(|c| {
                let centre = Vec2::new((c % nx) as f32 + 0.5, (c / nx) as f32 + 0.5) * CELL;
                crossings(&edges, centre) % 2 == 1
            })
            .collect();
        EdgeGrid {
            nx,
            ny,
            spans,
            lists,
            edges,
            inside,
        }
    }

    fn cell(&self, p: Vec2) -> usize {
        let i = ((p.x / CELL) as usize).min(self.nx - 1);
        let j = ((p.y / CELL) as usize).min(self.ny - 1);
        j * self.nx + i
    }

    /// The signed distance and the gradient at `p` (a point of the level).
    #[inline]
    pub(crate) fn sample(&self, p: Vec2) -> (f32, Vec2) {
        let cell = self.cell(p);
        let (a, b) = self.spans[cell];
        // (squared distance, nearest point, side of that edge, distance to the edge's line)
        let mut best = (CLAMP * CLAMP, Vec2::ZERO, 0.0f32, 0.0f32);
        for &k in &self.lists[a as usize..b as usize] {
            let [s, t] = self.edges[k as usize];
            let d = t - s;
            let h = ((p - s).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            let q = s + d * h;
            let d2 = (p - q).length_squared();
            let side = d.perp_dot(p - s);
            let off_line = side.abs() / d.length();
            // Where two edges meet at the nearest point (a vertex), the side of the one whose
            // line the point is farther from is the true side (the other's line may cut the
            // corner's wedge).
            let tie = d2 <= best.0 * (1.0 + 1e-5) && d2 >= best.0 * (1.0 - 1e-5);
            if d2 < best.0 * (1.0 - 1e-5) || (tie && off_line > best.3) {
                best = (d2, q, side, off_line);
            }
        }
        let (d2, q, side, _) = best;
        if d2 >= CLAMP * CLAMP {
            let sign = if self.inside[cell] { -1.0 } else { 1.0 };
            return (sign * CLAMP, Vec2::ZERO);
        }
        let d = d2.sqrt();
        // Counter-clockwise around solid: solid is to the left of each edge.
        let sign = if side > 0.0 { -1.0 } else { 1.0 };
        let grad = if d > 0.0 {
            (p - q) / d * sign
        } else {
            Vec2::ZERO
        };
        (sign * d, grad)
    }

    /// The signed distance at `p`.
    #[inline]
    pub(crate) fn distance(&self, p: Vec2) -> f32 {
        self.sample(p).0
    }
}

/// How many edges a ray from `p` towards +x crosses.
fn crossings(edges: &[[Vec2; 2]], p: Vec2) -> usize {
    edges
        .iter()
        .filter(|[a, b]| {
            (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)
        })
        .count()
}

/// parry2d's polyline of the same edges.
pub(crate) struct ParryPolyline(Polyline);

impl ParryPolyline {
    pub(crate) fn new(edges: &[[Vec2; 2]]) -> ParryPolyline {
        let vertices = edges
            .iter()
            .flat_map(|e| e.iter().map(|p| parry2d::math::Vector::new(p.x, p.y)))
            .collect();
        let indices = (0..edges.len() as u32)
            .map(|k| [2 * k, 2 * k + 1])
            .collect();
        ParryPolyline(Polyline::new(vertices, Some(indices)))
    }

    /// The unsigned distance to the nearest edge.
    #[inline]
    pub(crate) fn distance(&self, p: Vec2) -> f32 {
        self.0
            .distance_to_local_point(parry2d::math::Vector::new(p.x, p.y), false)
    }

    /// How far a circle of `radius` moves from `origin` along the unit `dir` before it
    /// touches an edge, within `length`.
    pub(crate) fn sweep(&self, origin: Vec2, dir: Vec2, length: f32, radius: f32) -> Option<f32> {
        let options = ShapeCastOptions::with_max_time_of_impact(length);
        let ball = Ball::new(radius);
        let at = Pose::translation(origin.x, origin.y);
        let velocity = parry2d::math::Vector::new(dir.x, dir.y);
        let zero = parry2d::math::Vector::new(0.0, 0.0);
        let hit = cast_shapes(
            &at,
            velocity,
            &ball,
            &Pose::identity(),
            zero,
            &self.0,
            options,
        );
        hit.ok().flatten().map(|h| h.time_of_impact)
    }

    /// The distance along the ray to the first edge it meets, within `length`.
    #[inline]
    pub(crate) fn raycast(&self, origin: Vec2, dir: Vec2, length: f32) -> Option<f32> {
        let ray = Ray::new(
            parry2d::math::Vector::new(origin.x, origin.y),
            parry2d::math::Vector::new(dir.x, dir.y),
        );
        self.0.cast_local_ray(&ray, length, false)
    }
}
