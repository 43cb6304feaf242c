//! A plan compiled once per frame for the CPU tracer: every node's primitive, guard, lift
//! and shape turned into the lane-ready constants that `map` reads (rotation matrices in
//! row order, reciprocals, blend factors).

use glam::{Mat3, Vec2, Vec3};

use crate::noise::FbmLanes;
use crate::plan3d::{
    Guard, Hash, Lift, Node, Plan, Prim, PrimKind, Shape, Sphere, VALUE_NOISE3_SLOPE,
};

/// A primitive with its per-frame constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PrimC {
    pub(super) centre: Vec3,
    pub(super) rot: Option<[f32; 9]>,
    pub(super) kind: PrimK,
}

#[derive(Clone, Copy, Debug)]
pub(super) enum PrimK {
    Sphere {
        r: f32,
    },
    Box {
        half: Vec3,
    },
    RoundBox {
        inner: Vec3,
        r: f32,
    },
    Capsule {
        a: Vec3,
        ba: Vec3,
        inv_baba: f32,
        r: f32,
    },
    Torus {
        major: f32,
        minor: f32,
    },
    Cylinder {
        r: f32,
        h: f32,
    },
    CappedCone {
        h: f32,
        r1: f32,
        r2: f32,
        k2: Vec2,
        inv_k2k2: f32,
    },
    Octahedron {
        s: f32,
    },
    Ellipsoid {
        inv_r: Vec3,
        inv_r2: Vec3,
    },
    /// `p.y - offset` (an up-facing plane, the common case).
    PlaneY {
        offset: f32,
    },
    Plane {
        normal: Vec3,
        offset: f32,
    },
}

/// A node's geometry with its per-frame constants.
#[derive(Clone, Debug)]
pub(super) enum ShapeC {
    Prim(PrimC),
    Blend {
        inv_k: f32,
        k_quarter: f32,
        parts: Vec<PrimC>,
    },
    Displaced {
        prim: PrimC,
        amp: f32,
        freq: f32,
        scale: f32,
    },
    Rows {
        part: PrimC,
        spacing: f32,
        inv_spacing: f32,
        count: u32,
        nearest: bool,
    },
    Mandelbulb {
        centre: Vec3,
        iterations: u32,
        bailout: f32,
        derivative: f32,
    },
}

/// A node ready to evaluate.
#[derive(Clone, Debug)]
pub(crate) struct NodeC {
    pub(super) material: i32,
    /// The height subtracted from `p.y` (0 for `Lift::None`).
    pub(super) lift: f32,
    /// Whether the lift is the terrain height computed at evaluation time (counted as an
    /// SDF evaluation; the value is the same every call, so it is computed once per frame).
    pub(super) ground: bool,
    pub(super) guard: Option<Guard>,
    pub(super) shape: ShapeC,
    /// Whether the node is one of [`SceneConstants::planes`] (left out of the distance to
    /// everything else that the march's plane landing compares with).
    pub(super) plane: bool,
    /// A lower bound on the node's distance far from it.
    pub(super) far: Option<FarBound>,
}

/// Far from a node, a lower bound on its distance: at `r = |q - centre| >= sqrt(radius2)`
/// it is at least `max(slope * r + offset)` over `lines`. Where a node evaluated before it
/// is nearer than that, the node cannot be the nearest, and evaluating it would change no
/// bit of the scene distance or the material: `map` skips it (unless its caller asks for
/// the distance without the planes, which it is part of).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FarBound {
    pub(super) centre: Vec3,
    pub(super) radius2: f32,
    /// `(slope, offset)` pairs.
    pub(super) lines: [(f32, f32); 4],
}

impl FarBound {
    /// The Mandelbulb's, where its parameters allow one. At `r = |c| >= 2` the first power
    /// step escapes past any bailout under `(2^8 - 2)^2`, so the estimate is `0.5 |w| ln|w|
    /// / (8 d r^7 + 1)` with `|w| >= r^8 - r`, which is at least `K r ln r` with `K =
    /// 3.9633 / (8 d + 1/128)` (`d` the derivative seed; docs/march3d.md has the steps).
    /// That is convex, so at least each of its tangents, `K ((1 + ln a) r - a)` at `r = a`;
    /// nine tenths of `K` leaves room for every rounding of the f32 estimate (relative
    /// errors near 1e-5).
    pub(super) fn mandelbulb(
        centre: Vec3,
        iterations: u32,
        bailout: f32,
        derivative: f32,
    ) -> Option<Self> {
        // (NaN parameters fail these too.)
        let bounded = iterations > 0 && derivative > 0.0 && bailout < 64_516.0;
        if !bounded {
            return None;
        }
        let k = 0.9 * 3.9633 / (8.0 * derivative + 1.0 / 128.0);
        Some(FarBound {
            centre,
            radius2: 4.0,
            lines: [2.0f32, 4.0, 8.0, 16.0].map(|a| (k * (1.0 + a.ln()), -k * a)),
        })
    }
}

/// An unrotated, unguarded plane node of a scene without terrain: distance `dot(n, q) - c`.
/// The march lands on it in closed form when nothing else is nearer along the ray.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlaneC {
    pub(crate) n: Vec3,
    pub(crate) c: f32,
}

/// The terrain, prepared.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TerrainC {
    pub(crate) fbm: FbmLanes,
    pub(crate) material: i32,
    pub(crate) step_scale: f32,
    pub(crate) analytic_normal: bool,
    /// `Fbm::top`: no terrain lies above this height.
    pub(crate) top: f32,
}

/// Everything `map` needs, computed once per frame.
#[derive(Clone, Debug)]
pub(crate) struct SceneConstants {
    pub(crate) terrain: Option<TerrainC>,
    pub(crate) early_out: Option<f32>,
    pub(crate) nodes: Vec<NodeC>,
    pub(crate) material_ids: bool,
    pub(crate) hash: Hash,
    /// The planes the march may land on (none with a terrain or an early-out, whose
    /// distances are not a plain minimum over nodes).
    pub(crate) planes: Vec<PlaneC>,
    /// The bounding spheres of every other node, when they are all finite and there is no
    /// terrain: a ray that can meet none of them and no plane ahead has missed.
    pub(crate) bounds: Option<Vec<Sphere>>,
    /// Whether a node's distance is a long chain of dependent operations (the
    /// Mandelbulb's iteration, a square root and a division per step), where the ray
    /// streams march two registers at once (`Pack::STREAM_PAIRS`). Measured on AVX-512,
    /// one thread: pairs took the Mandelbulb from about 1.1 to 0.85 s, and made scene0's
    /// short primitives 1.5x slower (twice the live values for the same work).
    pub(crate) long_chains: bool,
}

impl PrimC {
    fn new(prim: &Prim) -> PrimC {
        let rot = prim.rotation.map(row_major);
        let kind = match prim.kind {
            PrimKind::Sphere { r } => PrimK::Sphere { r },
            PrimKind::Box { half } => PrimK::Box { half },
            PrimKind::RoundBox { half, r } => PrimK::RoundBox {
                inner: half - Vec3::splat(r),
                r,
            },
            PrimKind::Capsule { a, b, r } => {
                let ba = b - a;
                let baba = ba.dot(ba);
                PrimK::Capsule {
                    a,
                    ba,
                    inv_baba: if baba > 0.0 { 1.0 / baba } else { 0.0 },
                    r,
                }
            }
            PrimKind::Torus { major, minor } => PrimK::Torus { major, minor },
            PrimKind::Cylinder { r, h } => PrimK::Cylinder { r, h },
            PrimKind::CappedCone { h, r1, r2 } => {
                let k2 = Vec2::new(r2 - r1, 2.0 * h);
                PrimK::CappedCone {
                    h,
                    r1,
                    r2,
                    k2,
                    inv_k2k2: 1.0 / k2.dot(k2),
                }
            }
            PrimKind::Octahedron { s } => PrimK::Octahedron { s },
            PrimKind::Ellipsoid { r } => PrimK::Ellipsoid {
                inv_r: r.recip(),
                inv_r2: (r * r).recip(),
            },
            PrimKind::Plane { normal, offset } if normal == Vec3::Y && rot.is_none() => {
                // Fold the translation into the offset: no per-lane subtraction.
                return PrimC {
                    centre: Vec3::ZERO,
                    rot: None,
                    kind: PrimK::PlaneY {
                        offset: offset + prim.centre.y,
                    },
                };
            }
            PrimKind::Plane { normal, offset } => PrimK::Plane { normal, offset },
        };
        PrimC {
            centre: prim.centre,
            rot,
            kind,
        }
    }
}

fn row_major(m: Mat3) -> [f32; 9] {
    let r = m.transpose().to_cols_array();
    [r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]]
}

impl SceneConstants {
    /// Compiles the plan's nodes and terrain (the plan must be valid).
    pub(super) fn new(plan: &Plan) -> SceneConstants {
        let terrain = plan.terrain.map(|t| TerrainC {
            fbm: FbmLanes::new(&t.fbm, plan.hash),
            material: t.material as i32,
            step_scale: t.step_scale,
            analytic_normal: t.analytic_normal,
            top: t.fbm.top(),
        });
        let mut nodes: Vec<NodeC> = plan.nodes.iter().map(|n| compile_node(plan, n)).collect();
        let mut planes = Vec::new();
        let mut bounds = None;
        if terrain.is_none() && plan.early_out.is_none() {
            let mut others = Vec::new();
            for (node, n) in nodes.iter_mut().zip(&plan.nodes) {
                if let Some(pl) = landing_plane(n) {
                    node.plane = true;
                    planes.push(pl);
                } else {
                    others.push(n.bound);
                }
            }
            bounds = others
                .iter()
                .all(|b| b.radius.is_finite())
                .then_some(others);
        }
        let long_chains = nodes
            .iter()
            .any(|n| matches!(n.shape, ShapeC::Mandelbulb { .. }));
        SceneConstants {
            terrain,
            early_out: plan.early_out,
            long_chains,
            nodes,
            material_ids: plan.material_ids,
            hash: plan.hash,
            planes,
            bounds,
        }
    }
}

/// The node as a plane the march may land on: a bare plane primitive (no rotation, lift or
/// guard).
fn landing_plane(node: &Node) -> Option<PlaneC> {
    match (&node.shape, node.lift, &node.guard) {
        (Shape::Prim(prim), Lift::None, None) if prim.rotation.is_none() => match prim.kind {
            PrimKind::Plane { normal, offset } => Some(PlaneC {
                n: normal,
                c: normal.dot(prim.centre) + offset,
            }),
            _ => None,
        },
        _ => None,
    }
}

fn compile_node(plan: &Plan, node: &Node) -> NodeC {
    let (lift, ground) = match node.lift {
        Lift::None => (0.0, false),
        Lift::Baked(y) => (y, false),
        Lift::Ground { x, z } => match &plan.terrain {
            Some(t) => (t.fbm.height(plan.hash, x, z).0, true),
            None => (0.0, true),
        },
    };
    let shape = match &node.shape {
        Shape::Prim(prim) => ShapeC::Prim(PrimC::new(prim)),
        Shape::Blend { k, parts } => ShapeC::Blend {
            inv_k: 1.0 / k,
            k_quarter: 0.25 * k,
            parts: parts.iter().map(PrimC::new).collect(),
        },
        Shape::Displaced { prim, amp, freq } => ShapeC::Displaced {
            prim: PrimC::new(prim),
            amp: *amp,
            freq: *freq,
            scale: 1.0 / (1.0 + amp * freq * VALUE_NOISE3_SLOPE),
        },
        Shape::Rows {
            part,
            spacing,
            count,
            nearest,
        } => ShapeC::Rows {
            part: PrimC::new(part),
            spacing: *spacing,
            inv_spacing: 1.0 / spacing,
            count: (*count).max(1),
            nearest: *nearest,
        },
        Shape::Mandelbulb {
            centre,
            iterations,
            bailout,
            derivative,
        } => ShapeC::Mandelbulb {
            centre: *centre,
            iterations: *iterations,
            bailout: *bailout,
            derivative: *derivative,
        },
    };
    let far = match &shape {
        ShapeC::Mandelbulb {
            centre,
            iterations,
            bailout,
            derivative,
        } if lift == 0.0 && !ground && node.guard.is_none() => {
            FarBound::mandelbulb(*centre, *iterations, *bailout, *derivative)
        }
        _ => None,
    };
    NodeC {
        material: node.material as i32,
        lift,
        ground,
        guard: node.guard,
        shape,
        plane: false,
        far,
    }
}
