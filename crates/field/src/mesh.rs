//! Triangle meshes of the solid terrain: a constrained Delaunay triangulation of the
//! extracted contours, keeping the triangles inside them.
//!
//! # Method
//!
//! 1. Contours are extracted with [`extract_contours`] (closed, solid on the left; see
//!    [`crate::contour`]).
//! 2. Every contour vertex is inserted into a spade [`ConstrainedDelaunayTriangulation`]
//!    (in `f64`; exactly equal points merge into one vertex; coordinates with magnitude below
//!    `1e-30` are snapped to 0 because spade rejects tiny non-zero values), then every contour
//!    edge is added as a constraint.
//! 3. A triangle is kept when its centroid is inside the contours by the even-odd rule, so
//!    the mesh covers exactly the contour-enclosed area when every constraint went in.
//!
//! # Conflicts
//!
//! Unsimplified contours never cross, so all constraints go in. Simplified contours (or
//! near-coincident points merged by rounding) can cross; a constraint edge that would cross
//! an earlier one is **skipped** (first come, first kept, in contour order) and counted in
//! [`TerrainMesh::skipped_constraints`]. The centroid rule still classifies every triangle,
//! so the mesh stays valid but may deviate from the contours near a skipped edge. Nothing
//! here panics on any input; spade's insertion errors become [`MeshError::Insertion`].

use glam::Vec2;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};
use thiserror::Error;

use super::aabb::Aabb;
use super::contour::{ContourError, ContourOptions, Contours, crosses_ray, extract_contours};
use super::sdf::Sdf;

/// A triangle mesh of solid terrain.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TerrainMesh {
    /// Vertex positions (only those used by a triangle), in order of first use.
    pub vertices: Vec<Vec2>,
    /// Triangles as indices into `vertices`, counter-clockwise (y up), none degenerate.
    pub triangles: Vec<[u32; 3]>,
    /// Contour edges that could not be inserted because they crossed an earlier one (0 for
    /// unsimplified contours).
    pub skipped_constraints: usize,
}

impl TerrainMesh {
    /// Total area of the triangles.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .filter_map(|i| self.triangle(i))
            .map(|[a, b, c]| 0.5 * cross(a, b, c))
            .sum()
    }

    /// The corners of triangle `i` (`None` when out of range).
    pub fn triangle(&self, i: usize) -> Option<[Vec2; 3]> {
        let t = self.triangles.get(i)?;
        let v = |k: usize| self.vertices.get(t[k] as usize).copied();
        Some([v(0)?, v(1)?, v(2)?])
    }

    /// The centroid of each triangle, in triangle order.
    pub fn centroids(&self) -> impl Iterator<Item = Vec2> + '_ {
        (0..self.triangles.len())
            .filter_map(|i| self.triangle(i))
            .map(|[a, b, c]| (a + b + c) / 3.0)
    }
}

/// Twice the signed area of `a b c`, in `f64`.
fn cross(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let (ax, ay) = (f64::from(a.x), f64::from(a.y));
    let (bx, by) = (f64::from(b.x), f64::from(b.y));
    let (cx, cy) = (f64::from(c.x), f64::from(c.y));
    (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
}

/// Why a mesh could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MeshError {
    /// Contour extraction failed (bad region or options).
    #[error(transparent)]
    Contour(#[from] ContourError),
    /// spade refused a vertex.
    #[error("cannot triangulate contour vertex {point}: {reason}")]
    Insertion {
        /// The vertex.
        point: Vec2,
        /// spade's reason.
        reason: String,
    },
}

/// Triangulate the solid part of `field` inside `region` (contours as [`extract_contours`]
/// with `opts`, then [`mesh_contours`]).
///
/// ```
/// use std::collections::BTreeMap;
/// use craterfield_field::{Aabb, Graph, Node};
/// use craterfield_field::contour::ContourOptions;
/// use craterfield_field::mesh::mesh_solid;
/// let slab = Graph::compile(&Node::Box { center: [0.25, 0.25], half_size: [4.0, 2.0] }, &BTreeMap::new())?;
/// let region = Aabb::new(glam::Vec2::splat(-8.0), glam::Vec2::splat(8.0));
/// let opts = ContourOptions { spacing: 0.5, ..ContourOptions::default() };
/// let mesh = mesh_solid(&slab, region, &opts)?;
/// // Marching squares cuts the box's corners slightly.
/// assert!((mesh.area() - 32.0).abs() < 0.2);
/// assert_eq!(mesh.skipped_constraints, 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn mesh_solid<F: Sdf>(
    field: &F,
    region: Aabb,
    opts: &ContourOptions,
) -> Result<TerrainMesh, MeshError> {
    let contours = extract_contours(field, region, opts)?;
    mesh_contours(&contours)
}

fn snap(v: f32) -> f64 {
    if v.abs() < 1e-30 { 0.0 } else { f64::from(v) }
}

/// Triangulate the area enclosed by `contours` (even-odd rule; see the module docs for how
/// crossing contour edges are handled).
pub fn mesh_contours(contours: &Contours) -> Result<TerrainMesh, MeshError> {
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut handles = Vec::with_capacity(contours.loops.len());
    for l in &contours.loops {
        let mut hs = Vec::with_capacity(l.points.len());
        for &p in &l.points {
            let h = cdt.insert(Point2::new(snap(p.x), snap(p.y))).map_err(|e| {
                MeshError::Insertion {
                    point: p,
                    reason: format!("{e:?}"),
                }
            })?;
            hs.push(h);
        }
        handles.push(hs);
    }
    let mut skipped = 0usize;
    for hs in &handles {
        let n = hs.len();
        for i in 0..n {
            let (a, b) = (hs[i], hs[(i + 1) % n]);
            if a != b && cdt.try_add_constraint(a, b).is_empty() {
                skipped += 1;
            }
        }
    }

    let index = EvenOdd::new(contours);
    let mut remap = vec![u32::MAX; cdt.num_vertices()];
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for face in cdt.inner_faces() {
        let vs = face.vertices();
        let pos = vs.map(|v| {
            let p = v.position();
            Vec2::new(p.x as f32, p.y as f32)
        });
        let area2 = cross(pos[0], pos[1], pos[2]);
        let scale = (pos[1] - pos[0])
            .length_squared()
            .max((pos[2] - pos[0]).length_squared());
        if area2.is_nan() || area2 <= 1e-12 * f64::from(scale) {
            continue;
        }
        let centroid = (pos[0] + pos[1] + pos[2]) / 3.0;
        if !index.contains(centroid) {
            continue;
        }
        let mut tri = [0u32; 3];
        for (k, v) in vs.iter().enumerate() {
            let slot = &mut remap[v.fix().index()];
            if *slot == u32::MAX {
                *slot = vertices.len() as u32;
                vertices.push(pos[k]);
            }
            tri[k] = *slot;
        }
        triangles.push(tri);
    }
    Ok(TerrainMesh {
        vertices,
        triangles,
        skipped_constraints: skipped,
    })
}

/// Even-odd point-in-contours test with the edges bucketed into horizontal bands, so one
/// query reads only the edges spanning its band.
struct EvenOdd {
    y0: f64,
    band_height: f64,
    /// Per band, the edges whose y range overlaps it.
    bands: Vec<Vec<(Vec2, Vec2)>>,
}

impl EvenOdd {
    fn new(contours: &Contours) -> EvenOdd {
        let all = || contours.loops.iter().flat_map(|l| l.points.iter());
        let (lo, hi) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(f64::from(p.y)), hi.max(f64::from(p.y)))
        });
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return EvenOdd {
                y0: 0.0,
                band_height: 1.0,
                bands: Vec::new(),
            };
        }
        let cell = f64::from(contours.cell_size.y).max((hi - lo) / 65_536.0);
        let count = (((hi - lo) / cell).ceil() as usize).max(1);
        let band_height = (hi - lo) / count as f64;
        let mut bands = vec![Vec::new(); count];
        let band_of = |y: f64| (((y - lo) / band_height).floor().max(0.0) as usize).min(count - 1);
        for l in &contours.loops {
            for (a, b) in l.segments() {
                let (ya, yb) = (f64::from(a.y), f64::from(b.y));
                for band in &mut bands[band_of(ya.min(yb))..=band_of(ya.max(yb))] {
                    band.push((a, b));
                }
            }
        }
        EvenOdd {
            y0: lo,
            band_height,
            bands,
        }
    }

    fn contains(&self, p: Vec2) -> bool {
        let (px, py) = (f64::from(p.x), f64::from(p.y));
        let k = (py - self.y0) / self.band_height;
        if !(k >= 0.0 && k < self.bands.len() as f64) {
            return false;
        }
        let band = &self.bands[k as usize];
        band.iter()
            .filter(|(a, b)| crosses_ray(*a, *b, px, py))
            .count()
            % 2
            == 1
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;
    use std::f64::consts::PI;

    use super::*;
    use crate::contour::Contour;
    use crate::{Graph, Level, Node};

    fn graph(node: Node) -> Graph {
        Graph::compile(&node, &BTreeMap::new()).expect("valid test node")
    }

    fn opts(spacing: f32) -> ContourOptions {
        ContourOptions {
            spacing,
            ..ContourOptions::default()
        }
    }

    fn region(h: f32) -> Aabb {
        Aabb::centered(Vec2::ZERO, Vec2::splat(h))
    }

    /// Area check, centroids inside (field distance below `eps`), no degenerate triangles,
    /// counter-clockwise triangles, valid indices.
    fn check(field: &Graph, mesh: &TerrainMesh, exact: f64, rel: f64, eps: f32) {
        assert!(!mesh.triangles.is_empty());
        assert_eq!(mesh.skipped_constraints, 0);
        let area = mesh.area();
        assert!(
            ((area - exact) / exact).abs() < rel,
            "mesh area {area} vs exact {exact}"
        );
        for i in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.triangle(i).expect("indices in range");
            assert!(cross(a, b, c) > 0.0, "triangle {i} degenerate or clockwise");
        }
        for c in mesh.centroids() {
            let d = field.distance(c);
            assert!(d < eps, "centroid {c} has distance {d}");
        }
    }

    #[test]
    fn box_mesh_matches_area() {
        let g = graph(Node::Box {
            center: [0.3, -0.2],
            half_size: [6.0, 3.5],
        });
        let mesh = mesh_solid(&g, region(10.0), &opts(1.0)).unwrap();
        check(&g, &mesh, 12.0 * 7.0, 0.01, 1e-3);
    }

    #[test]
    fn circle_mesh_matches_area() {
        let g = graph(Node::Circle {
            center: [0.1, 0.2],
            radius: 10.0,
        });
        let mesh = mesh_solid(&g, region(16.0), &opts(1.0)).unwrap();
        check(&g, &mesh, PI * 100.0, 0.01, 0.05);
        let c = extract_contours(&g, region(16.0), &opts(1.0)).unwrap();
        assert!((mesh.area() - c.area()).abs() < 1e-6 * c.area());
    }

    #[test]
    fn polygon_with_hole_matches_area() {
        let g = graph(Node::Subtract {
            base: Box::new(Node::Polygon {
                points: vec![[-12.0, -9.0], [13.0, -10.0], [11.0, 12.0], [-3.0, 8.0]],
            }),
            cut: Box::new(Node::Circle {
                center: [2.0, 0.0],
                radius: 4.0,
            }),
        });
        // Shoelace area of the quadrilateral.
        let q = [[-12.0, -9.0], [13.0, -10.0], [11.0, 12.0], [-3.0, 8.0]];
        let quad: f64 = (0..4)
            .map(|i| {
                let (a, b) = (q[i], q[(i + 1) % 4]);
                0.5 * (a[0] * b[1] - b[0] * a[1])
            })
            .sum();
        let exact = quad - PI * 16.0;
        let mesh = mesh_solid(&g, region(16.0), &opts(0.5)).unwrap();
        check(&g, &mesh, exact, 0.01, 0.05);
        let c = extract_contours(&g, region(16.0), &opts(0.5)).unwrap();
        assert_eq!(c.loops.len(), 2);
        assert_eq!(c.loops.iter().filter(|l| l.is_hole()).count(), 1);
        // No triangle covers the hole's centre.
        for i in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.triangle(i).unwrap();
            let p = Vec2::new(2.0, 0.0);
            let inside = cross(a, b, p) > 0.0 && cross(b, c, p) > 0.0 && cross(c, a, p) > 0.0;
            assert!(!inside, "triangle {i} covers the hole");
        }
    }

    #[test]
    fn simplified_contours_still_mesh() {
        let g = graph(Node::Ring {
            center: [0.0, 0.0],
            radius: 10.0,
            width: 4.0,
        });
        let o = ContourOptions {
            spacing: 0.5,
            refine_iterations: 2,
            simplify_tolerance: 0.02,
        };
        let mesh = mesh_solid(&g, region(16.0), &o).unwrap();
        let exact = PI * (12.0f64.powi(2) - 8.0f64.powi(2));
        check(&g, &mesh, exact, 0.01, 0.05);
    }

    #[test]
    fn crossing_constraints_are_skipped_not_panicking() {
        // Two hand-made loops that cross each other.
        let sq = |c: Vec2| Contour {
            points: vec![
                c + Vec2::new(-1.0, -1.0),
                c + Vec2::new(1.0, -1.0),
                c + Vec2::new(1.0, 1.0),
                c + Vec2::new(-1.0, 1.0),
            ],
        };
        let contours = Contours {
            loops: vec![sq(Vec2::ZERO), sq(Vec2::new(1.0, 0.5))],
            region: region(4.0),
            cell_size: Vec2::splat(1.0),
        };
        let mesh = mesh_contours(&contours).unwrap();
        assert!(mesh.skipped_constraints > 0);
        assert!(!mesh.triangles.is_empty());
        // Empty input gives an empty mesh.
        let empty = Contours {
            loops: Vec::new(),
            region: region(4.0),
            cell_size: Vec2::splat(1.0),
        };
        assert_eq!(mesh_contours(&empty).unwrap(), TerrainMesh::default());
    }

    #[test]
    fn bad_arguments_propagate() {
        let g = graph(Node::Circle {
            center: [0.0, 0.0],
            radius: 1.0,
        });
        let e = mesh_solid(&g, region(4.0), &opts(f32::NAN)).unwrap_err();
        assert!(matches!(e, MeshError::Contour(_)));
        assert!(e.to_string().contains("spacing"), "{e}");
    }

    #[test]
    fn default_level_window_mesh_matches_contours() {
        let level = Level::default_level();
        let region = Aabb::new(Vec2::new(1024.0, 256.0), Vec2::new(1536.0, 768.0));
        let o = opts(2.0);
        let contours = extract_contours(level.graph(), region, &o).unwrap();
        let mesh = mesh_contours(&contours).unwrap();
        let (ca, ma) = (contours.area(), mesh.area());
        assert!(ca > 0.0);
        assert!(((ma - ca) / ca).abs() < 0.01, "mesh {ma} vs contours {ca}");
        assert_eq!(mesh.skipped_constraints, 0);
        for i in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.triangle(i).unwrap();
            assert!(cross(a, b, c) > 0.0);
        }
    }
}
