//! The scenes of `craterfield bench fidelity`: terrains built to stress the reduced-scale
//! pipeline (thin solid lines, thin gaps, small islands, sharp corners, the prospero
//! expression, the default level as built and after a barrage), each with its camera and
//! the thin features it declares analytically for the recall measurement.
//!
//! The synthetic scenes are 1024 x 1024 world units seen at one unit per pixel. Every
//! terrain's band is [`BAND_TEXELS`] texels of the coarsest scale (1/32), so distances are
//! not clamped near surfaces at any scale measured.

use std::collections::BTreeMap;
use std::f32::consts::PI;
use std::path::Path;

use craterfield::field2d::import::graph_from_vm;
use craterfield::field2d::{Graph, Level, Terrain, TerrainOptions};
use craterfield::field2d::{Node, P2};
use craterfield::render2d::Camera;
use craterfield::render2d::fidelity::{Feature, FeatureKind};
use glam::Vec2;

use crate::barrage;

/// Band of every scene's terrain, in texels of the coarsest scale (1/32).
pub(crate) const BAND_TEXELS: f32 = 3.0;
/// Divisor of the coarsest scale measured.
const COARSEST_DIVISOR: f32 = 32.0;
/// Side of the synthetic scenes, world units and pixels.
const SIDE: f32 = 1024.0;
/// Widths of the thin lines and gaps, pixels.
const WIDTHS: [f32; 8] = [0.5, 1.0, 2.0, 3.0, 4.0, 8.0, 16.0, 32.0];
/// Angles of the thin lines and gaps: 0 to 170 degrees in 10-degree steps.
const ANGLE_STEPS: usize = 18;
/// Explosions fired into the default level.
const LEVEL_EXPLOSIONS: usize = 5_000;

/// The scenes in the order the bench runs them.
pub(crate) const NAMES: [&str; 8] = [
    "thin-lines",
    "thin-gaps",
    "islands",
    "corners",
    "prospero",
    "level-intact",
    "level",
    "level-reseeded",
];

/// A terrain, its view and its declared features (pixel coordinates of the camera).
pub(crate) struct Scene {
    /// Name as the bench prints it.
    pub name: &'static str,
    /// The terrain.
    pub terrain: Terrain<Graph>,
    /// The view measured.
    pub camera: Camera,
    /// Colours of the terrain's materials.
    pub palette: Vec<[u8; 3]>,
    /// Thin features whose recall is measured.
    pub features: Vec<Feature>,
}

/// Builds the scene called `name` (one of [`NAMES`]); `prospero` is the expression file,
/// `seed` the level barrage's seed.
pub(crate) fn build(name: &str, prospero: &Path, seed: u64) -> Result<Scene, String> {
    match name {
        "thin-lines" => thin_lines(),
        "thin-gaps" => thin_gaps(),
        "islands" => islands(),
        "corners" => corners(),
        "prospero" => prospero_scene(prospero),
        "level-intact" => level_scene("level-intact", 0, seed),
        "level" => level_scene("level", LEVEL_EXPLOSIONS, seed),
        "level-reseeded" => level_scene("level-reseeded", LEVEL_EXPLOSIONS, seed),
        other => Err(format!("unknown fidelity scene {other:?}")),
    }
}

/// A feature in world coordinates, before the camera maps it to pixels.
struct WorldFeature {
    kind: FeatureKind,
    line: Vec<Vec2>,
    width: f32,
}

fn to_pixels(camera: &Camera, features: &[WorldFeature]) -> Vec<Feature> {
    features
        .iter()
        .map(|f| Feature {
            kind: f.kind,
            centre_line: f.line.iter().map(|&p| camera.world_to_pixel(p)).collect(),
            width_px: f.width / camera.units_per_pixel,
        })
        .collect()
}

fn p2(v: Vec2) -> P2 {
    [v.x, v.y]
}

/// The 1024 x 1024 synthetic scene made of `root` with its features.
fn synthetic(name: &'static str, root: Node, features: &[WorldFeature]) -> Result<Scene, String> {
    let camera = Camera::fit(Vec2::ZERO, Vec2::splat(SIDE), SIDE as u32);
    let options = TerrainOptions {
        band: BAND_TEXELS * COARSEST_DIVISOR * camera.units_per_pixel,
        material_count: 1,
        ..TerrainOptions::default()
    };
    let terrain = terrain(&root, Vec2::ZERO, Vec2::splat(SIDE), options)?;
    Ok(Scene {
        name,
        terrain,
        camera,
        palette: vec![[124, 86, 52]],
        features: to_pixels(&camera, features),
    })
}

fn terrain(
    root: &Node,
    min: Vec2,
    max: Vec2,
    options: TerrainOptions,
) -> Result<Terrain<Graph>, String> {
    let graph = Graph::compile(root, &BTreeMap::new()).map_err(|e| e.to_string())?;
    Terrain::new(graph, min, max, options).map_err(|e| e.to_string())
}

/// Centres of a `cols x rows` grid of cells over the synthetic scene, row by row, nudged
/// by a sub-pixel offset that differs from cell to cell so that features meet the pixel
/// and texel grids at every phase.
fn grid_centres(cols: usize, rows: usize) -> Vec<Vec2> {
    let cell = Vec2::new(SIDE / cols as f32, SIDE / rows as f32);
    (0..rows * cols)
        .map(|i| {
            let (c, r) = (i % cols, i / cols);
            let phase = Vec2::new((i as f32 * 0.618).fract(), (i as f32 * 0.382).fract());
            Vec2::new(c as f32 + 0.5, r as f32 + 0.5) * cell + phase
        })
        .collect()
}

/// The 144 line placements shared by the thin lines and the thin gaps: every width at every
/// angle, each `(centre, direction, width)`.
fn line_placements() -> Vec<(Vec2, Vec2, f32)> {
    let centres = grid_centres(12, 12);
    (0..WIDTHS.len() * ANGLE_STEPS)
        .map(|i| {
            let width = WIDTHS[i % WIDTHS.len()];
            let degrees = (i / WIDTHS.len()) as f32 * 180.0 / ANGLE_STEPS as f32;
            let dir = Vec2::from_angle(degrees.to_radians());
            (centres[i], dir, width)
        })
        .collect()
}

/// Length of every thin line or gap, world units.
const LINE_LENGTH: f32 = 52.0;

/// Oriented boxes for the placements, and their centre lines (2 units short of the ends)
/// as features of `kind`.
fn lines(kind: FeatureKind) -> (Vec<Node>, Vec<WorldFeature>) {
    let half = LINE_LENGTH / 2.0;
    line_placements()
        .into_iter()
        .map(|(c, dir, width)| {
            let node = Node::OrientedBox {
                a: p2(c - dir * half),
                b: p2(c + dir * half),
                thickness: width,
            };
            let feature = WorldFeature {
                kind,
                line: vec![c - dir * (half - 2.0), c + dir * (half - 2.0)],
                width,
            };
            (node, feature)
        })
        .unzip()
}

/// Thin solid lines 0.5 to 32 px wide at 18 angles, in air.
fn thin_lines() -> Result<Scene, String> {
    let (nodes, features) = lines(FeatureKind::Solid);
    synthetic("thin-lines", Node::Union(nodes), &features)
}

/// A block covering the view, bigger than it on every side (no outer edge in view).
fn block() -> Node {
    Node::Box {
        center: [SIDE / 2.0, SIDE / 2.0],
        half_size: [SIDE * 0.6, SIDE * 0.6],
    }
}

/// The same lines cut as gaps into a solid block.
fn thin_gaps() -> Result<Scene, String> {
    let (cuts, features) = lines(FeatureKind::Gap);
    let root = Node::Subtract {
        base: Box::new(block()),
        cut: Box::new(Node::Union(cuts)),
    };
    synthetic("thin-gaps", root, &features)
}

/// Island radii (discs) and half-sizes (boxes), world units.
const ISLAND_SIZES: [f32; 9] = [0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0];

/// Small discs and rotated boxes, radius 0.5 to 8, in air.
fn islands() -> Result<Scene, String> {
    let (nodes, features): (Vec<Node>, Vec<WorldFeature>) = grid_centres(12, 12)
        .into_iter()
        .enumerate()
        .map(|(i, c)| {
            let r = ISLAND_SIZES[i % ISLAND_SIZES.len()];
            let node = if (i / ISLAND_SIZES.len()).is_multiple_of(2) {
                Node::Circle {
                    center: p2(c),
                    radius: r,
                }
            } else {
                Node::Translate {
                    offset: p2(c),
                    node: Box::new(Node::Rotate {
                        degrees: i as f32 * 17.0,
                        node: Box::new(Node::Box {
                            center: [0.0, 0.0],
                            half_size: [r, r],
                        }),
                    }),
                }
            };
            // The centre, widened to a bar through the inscribed circle for larger islands.
            let reach = (r - 1.0).max(0.0);
            let feature = WorldFeature {
                kind: FeatureKind::Solid,
                line: vec![c - Vec2::X * reach, c + Vec2::X * reach],
                width: 2.0 * r,
            };
            (node, feature)
        })
        .unzip();
    synthetic("islands", Node::Union(nodes), &features)
}

/// A convex corner of a shape: its vertex, the unit direction into the shape along the
/// bisector, and its angle in radians.
struct Tip {
    vertex: Vec2,
    inward: Vec2,
    angle: f32,
}

impl Tip {
    /// The tip's centre line from where the shape (or notch) is 2 units wide to where it is
    /// 5 units wide: a feature at least 2 wide whose presence says the tip was kept to
    /// within a couple of pixels of its point.
    fn feature(&self, kind: FeatureKind) -> WorldFeature {
        let at_width = |w: f32| self.vertex + self.inward * (w / 2.0 / (self.angle / 2.0).tan());
        WorldFeature {
            kind,
            line: vec![at_width(2.0), at_width(5.0)],
            width: 2.0,
        }
    }
}

/// A polygon's vertices with the tips of its convex corners sharper than `max_angle`
/// (counter-clockwise vertices).
fn tips(points: &[Vec2], max_angle: f32) -> Vec<Tip> {
    let n = points.len();
    (0..n)
        .filter_map(|i| {
            let (prev, v, next) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            let (a, b) = ((prev - v).normalize(), (next - v).normalize());
            let convex = (v - prev).perp_dot(next - v) > 0.0;
            let angle = a.angle_to(b).abs();
            (convex && angle <= max_angle + 1e-4).then(|| Tip {
                vertex: v,
                inward: (a + b).normalize(),
                angle,
            })
        })
        .collect()
}

/// An isosceles triangle with tip angle `degrees` at `tip`, pointing along `dir`, with
/// sides `side` long, counter-clockwise.
fn triangle(tip: Vec2, dir: Vec2, degrees: f32, side: f32) -> Vec<Vec2> {
    let half = degrees.to_radians() / 2.0;
    let base = tip - dir * (side * half.cos());
    let half_base = side * half.sin();
    vec![
        tip,
        base + dir.perp() * half_base,
        base - dir.perp() * half_base,
    ]
}

/// A square centred at `c` with half side `h`, rotated by `degrees`, counter-clockwise.
fn square(c: Vec2, h: f32, degrees: f32) -> Vec<Vec2> {
    let rot = Vec2::from_angle(degrees.to_radians());
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .into_iter()
        .map(|(x, y)| c + rot.rotate(Vec2::new(x, y) * h))
        .collect()
}

/// A star with `points` points of radius `outer` and notches at radius `inner`,
/// counter-clockwise.
fn star(c: Vec2, points: usize, outer: f32, inner: f32, degrees: f32) -> Vec<Vec2> {
    (0..2 * points)
        .map(|i| {
            let r = if i.is_multiple_of(2) { outer } else { inner };
            let a = degrees.to_radians() + i as f32 * PI / points as f32;
            c + Vec2::from_angle(a) * r
        })
        .collect()
}

/// The corner shapes centred around `origin`: triangles with tip angles 10 to 90 degrees,
/// four rotated squares and two stars.
fn corner_shapes(origin: Vec2) -> Vec<Vec<Vec2>> {
    let mut shapes: Vec<Vec<Vec2>> = (1..=9)
        .map(|k| {
            let c = origin + Vec2::new(-440.0 + 110.0 * (k - 1) as f32, 110.0);
            let dir = Vec2::from_angle((90.0 + 37.0 * k as f32).to_radians());
            triangle(c + dir * 30.0, dir, 10.0 * k as f32, 60.0)
        })
        .collect();
    for (k, degrees) in [0.0f32, 15.0, 30.0, 45.0].into_iter().enumerate() {
        let c = origin + Vec2::new(-420.0 + 130.0 * k as f32, -90.0);
        shapes.push(square(c + Vec2::new(0.3, 0.7), 35.0, degrees));
    }
    shapes.push(star(origin + Vec2::new(150.0, -90.0), 5, 50.0, 17.0, 90.0));
    shapes.push(star(origin + Vec2::new(340.0, -90.0), 8, 55.0, 30.0, 11.0));
    shapes
}

/// Sharp corners as solids in air (top half) and as notches in a block (bottom half).
fn corners() -> Result<Scene, String> {
    let max_tip = 90f32.to_radians();
    let mut features = Vec::new();
    let solids = corner_shapes(Vec2::new(512.0, 768.0));
    let holes = corner_shapes(Vec2::new(512.0, 256.0));
    let polygon = |points: &Vec<Vec2>| Node::Polygon {
        points: points.iter().map(|&p| p2(p)).collect(),
    };
    for shape in &solids {
        let shape_tips = tips(shape, max_tip);
        features.extend(shape_tips.iter().map(|t| t.feature(FeatureKind::Solid)));
    }
    for shape in &holes {
        let shape_tips = tips(shape, max_tip);
        features.extend(shape_tips.iter().map(|t| t.feature(FeatureKind::Gap)));
    }
    let lower_block = Node::Box {
        center: [SIDE / 2.0, SIDE * 0.25 - 100.0],
        half_size: [SIDE * 0.6, SIDE * 0.25 + 150.0],
    };
    let root = Node::Union(vec![
        Node::Union(solids.iter().map(polygon).collect()),
        Node::Subtract {
            base: Box::new(lower_block),
            cut: Box::new(Node::Union(holes.iter().map(polygon).collect())),
        },
    ]);
    synthetic("corners", root, &features)
}

/// The prospero expression over [-1, 1]^2 at 1024 x 1024: a band and grid scaled to that
/// world.
fn prospero_scene(path: &Path) -> Result<Scene, String> {
    let text =
        craterfield::files::read_text(path, craterfield::field2d::import::MAX_VM_BYTES as u64)
            .map_err(|e| e.to_string())?;
    let graph = graph_from_vm(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let camera = Camera::fit(Vec2::splat(-1.0), Vec2::splat(1.0), SIDE as u32);
    let upp = camera.units_per_pixel;
    let options = TerrainOptions {
        cell_size: 64.0 * upp,
        band: BAND_TEXELS * COARSEST_DIVISOR * upp,
        max_event_radius: 16.0 * upp,
        max_rim: 0.0,
        material_count: 1,
        ..TerrainOptions::default()
    };
    let terrain = Terrain::new(graph, Vec2::splat(-1.0), Vec2::splat(1.0), options)
        .map_err(|e| e.to_string())?;
    Ok(Scene {
        name: "prospero",
        terrain,
        camera,
        palette: vec![[230, 230, 230]],
        features: Vec::new(),
    })
}

/// The default level after `explosions` explosions, seen at 1920 x 1080 over where the
/// bridges, the flat island's spikes, the overhang's stalactites and the thin ring were
/// built (a barrage of thousands of shells destroys most of them: the features that
/// survive count).
fn level_scene(name: &'static str, explosions: usize, seed: u64) -> Result<Scene, String> {
    let level = Level::default_level();
    let b = level.bounds();
    let options = TerrainOptions {
        band: BAND_TEXELS * COARSEST_DIVISOR,
        ..level.terrain_options()
    };
    let mut terrain =
        Terrain::new(level.graph().clone(), b.min, b.max, options).map_err(|e| e.to_string())?;
    barrage::fire(&level, &mut terrain, explosions, seed);
    let camera = Camera {
        center: Vec2::new(2460.0, 840.0),
        units_per_pixel: 1.0,
        width: 1920,
        height: 1080,
    };
    let features = to_pixels(&camera, &level_features());
    Ok(Scene {
        name,
        terrain,
        camera,
        palette: level.materials().iter().map(|m| m.color).collect(),
        features,
    })
}

/// Length of the pieces the level's long thin features are cut into: explosions break them,
/// and each surviving piece counts on its own.
const PIECE: f32 = 32.0;

/// The default level's thin solids: its three bridges (2, 1.5 and 3 wide) and the 3 wide
/// ring, in pieces.
fn level_features() -> Vec<WorldFeature> {
    let bridges = [
        ((1205.0, 1140.0), (1765.0, 1205.0), 2.0),
        ((2030.0, 1215.0), (2600.0, 1065.0), 1.5),
        ((2840.0, 585.0), (3300.0, 505.0), 3.0),
    ];
    let mut out = Vec::new();
    for (a, b, width) in bridges {
        let (a, b) = (Vec2::from(a), Vec2::from(b));
        let pieces = (a.distance(b) / PIECE).floor() as usize;
        for k in 0..pieces {
            let t = |s: f32| a.lerp(b, s / pieces as f32);
            out.push(WorldFeature {
                kind: FeatureKind::Solid,
                line: vec![t(k as f32 + 0.1), t(k as f32 + 0.9)],
                width,
            });
        }
    }
    let (centre, radius) = (Vec2::new(3350.0, 1180.0), 80.0);
    let arcs = (2.0 * PI * radius / PIECE).floor() as usize;
    for k in 0..arcs {
        let at = |s: f32| centre + Vec2::from_angle(s * 2.0 * PI / arcs as f32) * radius;
        let line = (0..=8)
            .map(|j| at(k as f32 + 0.1 + 0.1 * j as f32))
            .collect();
        out.push(WorldFeature {
            kind: FeatureKind::Solid,
            line,
            width: 3.0,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use craterfield::field2d::Sdf;

    #[test]
    fn declared_features_lie_on_their_shapes() {
        for name in ["thin-lines", "thin-gaps", "islands", "corners"] {
            let scene = build(name, Path::new("unused"), 1).unwrap();
            assert!(!scene.features.is_empty(), "{name}");
            for f in &scene.features {
                for &p in &f.centre_line {
                    let cam = &scene.camera;
                    let half = Vec2::new(cam.width as f32, cam.height as f32) / 2.0;
                    let world =
                        cam.center + (p - half) * Vec2::new(1.0, -1.0) * cam.units_per_pixel;
                    let d = scene.terrain.distance(world);
                    let on_side = match f.kind {
                        FeatureKind::Solid => d <= 0.0,
                        FeatureKind::Gap => d >= 0.0,
                    };
                    assert!(on_side, "{name}: {f:?} at {world}: d = {d}");
                }
            }
        }
    }

    #[test]
    fn every_width_and_angle_is_present_once() {
        let placements = line_placements();
        assert_eq!(placements.len(), 144);
        for w in WIDTHS {
            let n = placements.iter().filter(|p| p.2 == w).count();
            assert_eq!(n, ANGLE_STEPS, "width {w}");
        }
    }

    #[test]
    fn tips_of_a_triangle_and_a_star() {
        let t = triangle(Vec2::ZERO, Vec2::Y, 30.0, 50.0);
        assert!((t[1].distance(t[0]) - 50.0).abs() < 1e-4);
        // The 30-degree tip and the two 75-degree base corners.
        let found = tips(&t, 90f32.to_radians());
        assert_eq!(found.len(), 3);
        assert!((found[0].angle.to_degrees() - 30.0).abs() < 1e-3);
        assert!((found[0].inward - -Vec2::Y).length() < 1e-5);
        assert!((found[1].angle.to_degrees() - 75.0).abs() < 1e-3);
        assert_eq!(tips(&t, 60f32.to_radians()).len(), 1);
        let s = star(Vec2::ZERO, 5, 50.0, 17.0, 90.0);
        assert_eq!(tips(&s, 90f32.to_radians()).len(), 5);
    }
}
