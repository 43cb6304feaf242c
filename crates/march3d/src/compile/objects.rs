//! Scene objects as plan nodes: the geometry of trees, rocks, vineyard rows and huts in
//! node-local coordinates (ground at y = 0 under the anchor), their simplified forms with
//! how far each may move the surface, and the bounds the emitter culls and guards with.

use glam::Vec3;

use crate::plan3d::{Guard, Lift, Node, Prim, PrimKind, Shape, Sphere};
use crate::scene::{Object, Scene, rotation_degrees};

/// The nodes of one object at one level of detail, before lifting onto the terrain.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Parts {
    /// Nodes with `Lift::None` and node-local y (ground at 0 for grounded objects).
    pub nodes: Vec<Node>,
}

/// One scene object ready for emission.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Prepared {
    /// Where the object stands, `(x, z)`, when it sits on the ground.
    pub anchor: Option<(f32, f32)>,
    /// Full detail.
    pub full: Parts,
    /// Simplified forms, finest first (level 1 is `lods[0]`).
    pub lods: Vec<Lod>,
    /// Sphere around the object (node-local y).
    pub bound: Sphere,
}

/// A simplified form of an object and its error: no point of its surface lies farther than
/// `error` (world units) from the full form's surface, nor the other way round. The emitter
/// uses a form only where that error covers at most a fraction of a pixel.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Lod {
    pub parts: Parts,
    pub error: f32,
}

/// Bounding sphere of a primitive about its placed centre (rotation does not change it).
pub(crate) fn prim_bound(p: &Prim) -> Sphere {
    let (centre, radius) = match p.kind {
        PrimKind::Sphere { r } => (Vec3::ZERO, r),
        PrimKind::Box { half } | PrimKind::RoundBox { half, .. } => (Vec3::ZERO, half.length()),
        PrimKind::Capsule { a, b, r } => ((a + b) * 0.5, (b - a).length() * 0.5 + r),
        PrimKind::Torus { major, minor } => (Vec3::ZERO, major + minor),
        PrimKind::Cylinder { r, h } => (Vec3::ZERO, (r * r + h * h).sqrt()),
        PrimKind::CappedCone { h, r1, r2 } => (Vec3::ZERO, (r1.max(r2).powi(2) + h * h).sqrt()),
        PrimKind::Octahedron { s } => (Vec3::ZERO, s),
        PrimKind::Ellipsoid { r } => (Vec3::ZERO, r.max_element()),
        PrimKind::Plane { .. } => (Vec3::ZERO, f32::INFINITY),
    };
    // The local centre offset (capsule) is rotated with the primitive.
    let offset = match p.rotation {
        Some(m) => m.transpose() * centre,
        None => centre,
    };
    Sphere {
        centre: p.centre + offset,
        radius,
    }
}

/// The smallest sphere around both (enough for bounds; not the minimal enclosing sphere of
/// a set).
pub(crate) fn merge(a: Sphere, b: Sphere) -> Sphere {
    if !a.radius.is_finite() || !b.radius.is_finite() {
        return Sphere {
            centre: a.centre,
            radius: f32::INFINITY,
        };
    }
    let d = (b.centre - a.centre).length();
    if d + b.radius <= a.radius {
        return a;
    }
    if d + a.radius <= b.radius {
        return b;
    }
    let radius = (d + a.radius + b.radius) * 0.5;
    let dir = (b.centre - a.centre) / d;
    Sphere {
        centre: a.centre + dir * (radius - a.radius),
        radius,
    }
}

fn merge_all(spheres: impl IntoIterator<Item = Sphere>) -> Sphere {
    spheres
        .into_iter()
        .reduce(merge)
        .expect("at least one sphere")
}

fn node(material: u32, shape: Shape, bound: Sphere, cost: u32) -> Node {
    Node {
        material,
        lift: Lift::None,
        guard: None,
        shape,
        bound,
        cost,
    }
}

fn prim_node(material: u32, prim: Prim) -> Node {
    node(material, Shape::Prim(prim), prim_bound(&prim), 1)
}

/// A guard box around `bound` with a margin that keeps near steps exact.
pub(crate) fn guard_for(bound: &Sphere) -> Option<Guard> {
    if !bound.radius.is_finite() {
        return None;
    }
    Some(Guard {
        centre: bound.centre,
        half: Vec3::splat(bound.radius),
        margin: (0.25 * bound.radius).max(0.05),
    })
}

fn mat(scene: &Scene, name: &str) -> u32 {
    // Names were checked by `Scene::validate`.
    scene.material_index(name).unwrap_or(0)
}

/// Prepares one validated object.
pub(crate) fn prepare(scene: &Scene, object: &Object) -> Prepared {
    match object {
        Object::Shape {
            shape,
            at,
            rotate,
            material,
            on_ground,
        } => shape_object(mat(scene, material), *shape, *at, *rotate, *on_ground),
        Object::Tree {
            at,
            height,
            trunk,
            leaves,
        } => tree(*at, *height, mat(scene, trunk), mat(scene, leaves)),
        Object::Rock {
            at,
            radius,
            roughness,
            material,
        } => rock(*at, *radius, *roughness, mat(scene, material)),
        Object::VineRows {
            at,
            rows,
            spacing,
            length,
            material,
        } => vine_rows(*at, *rows, *spacing, *length, mat(scene, material)),
        Object::Hut { at, size, material } => hut(*at, *size, mat(scene, material)),
        Object::Mandelbulb {
            at,
            iterations,
            bailout,
            derivative,
            material,
        } => {
            let bound = Sphere {
                centre: *at,
                radius: 1.25,
            };
            let shape = Shape::Mandelbulb {
                centre: *at,
                iterations: *iterations,
                bailout: *bailout,
                derivative: *derivative,
            };
            Prepared {
                anchor: None,
                full: Parts {
                    nodes: vec![node(mat(scene, material), shape, bound, 1)],
                },
                lods: Vec::new(),
                bound,
            }
        }
    }
}

fn shape_object(material: u32, kind: PrimKind, at: Vec3, rotate: Vec3, ground: bool) -> Prepared {
    let kind = match kind {
        PrimKind::Plane { normal, offset } => PrimKind::Plane {
            normal: normal.normalize(),
            offset: offset / normal.length(),
        },
        k => k,
    };
    let rotation = (rotate != Vec3::ZERO).then(|| rotation_degrees(rotate).transpose());
    let prim = Prim {
        centre: at,
        rotation,
        kind,
    };
    let n = prim_node(material, prim);
    let bound = n.bound;
    Prepared {
        anchor: ground.then_some((at.x, at.z)),
        full: Parts { nodes: vec![n] },
        lods: Vec::new(),
        bound,
    }
}

/// How far a simplified tree (crown of three blended masses, no branches) may move its
/// surface, as a fraction of its height (the test samples 0.024).
const TREE_CROWN_ERROR: f32 = 0.035;

fn tree((x, z): (f32, f32), h: f32, trunk: u32, leaves: u32) -> Prepared {
    let at = |dx: f32, dy: f32, dz: f32| Vec3::new(x + dx * h, dy * h, z + dz * h);
    let trunk_prim = Prim::at(
        Vec3::new(x, 0.0, z),
        PrimKind::Capsule {
            a: Vec3::new(0.0, -0.3, 0.0),
            b: Vec3::new(0.0, 0.55 * h, 0.0),
            r: 0.05 * h,
        },
    );
    let crown_parts = vec![
        Prim::at(
            Vec3::ZERO,
            PrimKind::Capsule {
                a: at(0.0, 0.4, 0.0),
                b: at(0.18, 0.62, 0.05),
                r: 0.025 * h,
            },
        ),
        Prim::at(
            Vec3::ZERO,
            PrimKind::Capsule {
                a: at(0.0, 0.45, 0.0),
                b: at(-0.15, 0.66, -0.08),
                r: 0.025 * h,
            },
        ),
        Prim::at(
            at(0.0, 0.74, 0.0),
            PrimKind::Ellipsoid {
                r: Vec3::new(0.26, 0.22, 0.26) * h,
            },
        ),
        Prim::at(at(0.15, 0.62, 0.06), PrimKind::Sphere { r: 0.16 * h }),
        Prim::at(at(-0.13, 0.64, -0.08), PrimKind::Sphere { r: 0.15 * h }),
    ];
    let k = 0.06 * h;
    let crown_bound = inflate(merge_all(crown_parts.iter().map(prim_bound)), k * 0.25);
    let crown = node(
        leaves,
        Shape::Blend {
            k,
            parts: crown_parts,
        },
        crown_bound,
        5,
    );
    let trunk_node = prim_node(trunk, trunk_prim);
    let bound = merge(trunk_node.bound, crown_bound);
    // The simplified tree keeps the trunk and blends only the crown's three masses: the
    // branches hide inside them but for stubs the trunk covers. Its error was measured by
    // sampling both surfaces (see the tests) and rounded up.
    let masses = match &crown.shape {
        Shape::Blend { parts, .. } => parts[2..].to_vec(),
        _ => unreachable!("a tree crown is a blend"),
    };
    let simple_crown = node(leaves, Shape::Blend { k, parts: masses }, crown_bound, 3);
    Prepared {
        anchor: Some((x, z)),
        lods: vec![Lod {
            parts: Parts {
                nodes: vec![trunk_node.clone(), simple_crown],
            },
            error: TREE_CROWN_ERROR * h,
        }],
        full: Parts {
            nodes: vec![trunk_node, crown],
        },
        bound,
    }
}

fn inflate(s: Sphere, by: f32) -> Sphere {
    Sphere {
        centre: s.centre,
        radius: s.radius + by,
    }
}

fn rock((x, z): (f32, f32), r: f32, roughness: f32, material: u32) -> Prepared {
    let base = Prim::at(
        Vec3::new(x, 0.3 * r, z),
        PrimKind::Ellipsoid {
            r: Vec3::new(1.2, 0.75, 1.0) * r,
        },
    );
    let amp = 2.0 * roughness * r;
    let bound = inflate(prim_bound(&base), amp * 0.5);
    let full = node(
        material,
        Shape::Displaced {
            prim: base,
            amp,
            freq: 1.6 / r,
        },
        bound,
        1,
    );
    Prepared {
        anchor: Some((x, z)),
        full: Parts { nodes: vec![full] },
        // The displacement moves the surface by at most amp / 2 either way.
        lods: vec![Lod {
            parts: Parts {
                nodes: vec![prim_node(material, base)],
            },
            error: amp * 0.5,
        }],
        bound,
    }
}

fn vine_rows((x, z): (f32, f32), rows: u32, spacing: f32, length: f32, material: u32) -> Prepared {
    let part = Prim::at(
        Vec3::new(x, 0.45, z),
        PrimKind::RoundBox {
            half: Vec3::new(length * 0.5, 0.85, 0.3),
            r: 0.25,
        },
    );
    let last = z + (rows - 1) as f32 * spacing;
    let half = Vec3::new(length * 0.5, 0.85, 0.3 + (last - z) * 0.5);
    let bound = Sphere {
        centre: Vec3::new(x, 0.45, (z + last) * 0.5),
        radius: half.length(),
    };
    let shape = |nearest| Shape::Rows {
        part,
        spacing,
        count: rows,
        nearest,
    };
    let full = node(material, shape(true), bound, rows);
    Prepared {
        anchor: Some((x, (z + last) * 0.5)),
        full: Parts { nodes: vec![full] },
        lods: Vec::new(),
        bound,
    }
}

fn hut((x, z): (f32, f32), s: f32, material: u32) -> Prepared {
    let walls = Prim::at(
        Vec3::new(x, 0.6 * s, z),
        PrimKind::Box {
            half: Vec3::new(s, 1.0 * s, s),
        },
    );
    let roof = Prim::at(
        Vec3::new(x, 2.0 * s, z),
        PrimKind::CappedCone {
            h: 0.5 * s,
            r1: 1.45 * s,
            r2: 0.1 * s,
        },
    );
    let k = 0.1 * s;
    let bound = inflate(merge(prim_bound(&walls), prim_bound(&roof)), k * 0.25);
    let full = node(
        material,
        Shape::Blend {
            k,
            parts: vec![walls, roof],
        },
        bound,
        2,
    );
    Prepared {
        anchor: Some((x, z)),
        full: Parts { nodes: vec![full] },
        lods: Vec::new(),
        bound,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merged_spheres_contain_both() {
        let a = Sphere {
            centre: Vec3::ZERO,
            radius: 1.0,
        };
        let b = Sphere {
            centre: Vec3::new(3.0, 0.0, 0.0),
            radius: 0.5,
        };
        let m = merge(a, b);
        for s in [a, b] {
            assert!((s.centre - m.centre).length() + s.radius <= m.radius + 1e-5);
        }
    }

    /// A plan of `nodes` alone, for distances.
    fn plan_of(nodes: &[Node]) -> crate::plan3d::Plan {
        use crate::plan3d::{Hash, March, Material, PaperShading, Plan, Shading};
        Plan {
            key: 0,
            march: March {
                max_steps: 1,
                hit: 1e-3,
                hit_per_t: 0.0,
                far: f32::INFINITY,
                escape: f32::INFINITY,
                step_factor: 1.0,
                ray_offset: 1e-3,
                normal_eps: 1e-3,
                relax: 1.0,
            },
            terrain: None,
            early_out: None,
            nodes: nodes.to_vec(),
            materials: vec![
                Material {
                    colour: Vec3::ONE,
                    reflectivity: 0.0,
                };
                2
            ],
            shading: Shading::Paper(PaperShading {
                lights: Vec::new(),
                shininess: 1.0,
                specular: 0.0,
                ambient: 1.0,
                bounces: 0,
                reflection_scale: 0.0,
                shadow_k: None,
                fog: 0.0,
                gamma: 1.0,
            }),
            material_ids: false,
            hash: Hash::DotFract,
        }
    }

    /// The largest distance from one surface to the other over sampled points near either:
    /// the surface error a simplified form claims to stay within.
    fn surface_error(a: &[Node], b: &[Node], bound: Sphere) -> f32 {
        let (pa, pb) = (plan_of(a), plan_of(b));
        let shell = 2e-3 * bound.radius;
        let mut seed = 0x9e37_79b9_u32;
        let mut unit = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            seed as f32 / u32::MAX as f32 * 2.0 - 1.0
        };
        let (mut worst, mut near) = (0.0f32, 0);
        for _ in 0..400_000 {
            let q = bound.centre + Vec3::new(unit(), unit(), unit()) * bound.radius;
            let (da, db) = (
                crate::cpu::distance_at(&pa, q),
                crate::cpu::distance_at(&pb, q),
            );
            if da.abs() < shell {
                worst = worst.max(db.abs());
                near += 1;
            }
            if db.abs() < shell {
                worst = worst.max(da.abs());
                near += 1;
            }
        }
        assert!(near > 1000, "only {near} samples near the surfaces");
        worst
    }

    #[test]
    fn simplified_forms_stay_within_their_error() {
        let h = 6.0;
        let t = tree((0.0, 0.0), h, 0, 1);
        let e = surface_error(&t.full.nodes, &t.lods[0].parts.nodes, t.bound);
        eprintln!("tree: surface error {e} (claimed {})", t.lods[0].error);
        assert!(e <= t.lods[0].error, "tree: {e} > {}", t.lods[0].error);
        // The claim is not loose either: the old one-sphere proxy is far outside it.
        let ball = [prim_node(
            1,
            Prim::at(
                Vec3::new(0.0, 0.68 * h, 0.0),
                PrimKind::Sphere { r: 0.3 * h },
            ),
        )];
        assert!(surface_error(&t.full.nodes, &ball, t.bound) > 4.0 * t.lods[0].error);
        let r = rock((0.0, 0.0), 1.0, 0.18, 0);
        let e = surface_error(&r.full.nodes, &r.lods[0].parts.nodes, r.bound);
        eprintln!("rock: surface error {e} (claimed {})", r.lods[0].error);
        assert!(e <= r.lods[0].error, "rock: {e} > {}", r.lods[0].error);
    }

    #[test]
    fn a_tree_is_six_primitives_and_four_simplified() {
        let p = tree((0.0, 0.0), 6.0, 0, 1);
        let cost = |parts: &Parts| parts.nodes.iter().map(|n| n.cost).sum::<u32>();
        assert_eq!(cost(&p.full), 6);
        let costs: Vec<u32> = p.lods.iter().map(|l| cost(&l.parts)).collect();
        assert_eq!(costs, [4]);
        // The simplified form keeps the trunk, and the crown its colour and bound.
        let simple = &p.lods[0].parts;
        assert_eq!(simple.nodes[0], p.full.nodes[0]);
        assert_eq!(simple.nodes[1].material, 1);
        assert_eq!(simple.nodes[1].bound, p.full.nodes[1].bound);
    }
}
