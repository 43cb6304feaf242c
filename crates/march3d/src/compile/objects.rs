//! Scene objects as plan nodes: the geometry of trees, rocks, vineyard rows and huts in
//! node-local coordinates (ground at y = 0 under the anchor), their far-distance
//! simplifications, and the bounds the emitter culls and guards with.

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
    /// The simplified form far away, when there is one.
    pub far: Option<Parts>,
    /// Sphere around the object (node-local y).
    pub bound: Sphere,
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
            };
            Prepared {
                anchor: None,
                full: Parts {
                    nodes: vec![node(mat(scene, material), shape, bound, 1)],
                },
                far: None,
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
        far: None,
        bound,
    }
}

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
    let far = prim_node(
        leaves,
        Prim::at(at(0.0, 0.68, 0.0), PrimKind::Sphere { r: 0.3 * h }),
    );
    Prepared {
        anchor: Some((x, z)),
        full: Parts {
            nodes: vec![trunk_node, crown],
        },
        far: Some(Parts { nodes: vec![far] }),
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
        far: Some(Parts {
            nodes: vec![prim_node(material, base)],
        }),
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
        far: None,
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
        far: None,
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

    #[test]
    fn a_tree_is_six_primitives_and_one_far_away() {
        let p = tree((0.0, 0.0), 6.0, 0, 1);
        let cost: u32 = p.full.nodes.iter().map(|n| n.cost).sum();
        assert_eq!(cost, 6);
        assert_eq!(p.far.unwrap().nodes.len(), 1);
    }
}
