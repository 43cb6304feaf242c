//! Hand-built 3D plans for the WGSL and GPU tests: the reference paper's two scenes, and
//! small worlds that between them use every node kind, lift, guard, hash, normal, AO and
//! shadow mode of `march3d::plan`.
#![allow(dead_code)]

use craterfield::march3d::Camera3d;
use craterfield::march3d::plan3d::{
    AoMode, Fbm, Guard, Hash, Lift, March, Material, Node, PaperShading, Plan, PointLight, Prim,
    PrimKind, Shading, ShadowMode, Shape, Sphere, TerrainPlan, WorldShading,
};
use craterfield::march3d::scene::rotation_degrees;
use glam::Vec3;

/// The reference implementation's march settings.
pub(crate) fn paper_march() -> March {
    March {
        max_steps: 3000,
        hit: 5.0e-6,
        hit_per_t: 0.0,
        far: f32::INFINITY,
        escape: 100.0,
        step_factor: 1.0,
        ray_offset: 1.0e-3,
        normal_eps: 1.0e-4,
        relax: 1.0,
    }
}

fn paper_shading(light: PointLight, shadows: bool) -> Shading {
    Shading::Paper(PaperShading {
        lights: vec![light],
        shininess: 15.0,
        specular: 0.2,
        ambient: 0.01,
        bounces: 3,
        reflection_scale: 0.1,
        shadow_k: shadows.then_some(3.0),
        fog: 7.0e-6,
        gamma: 0.4545,
    })
}

fn node(material: u32, prim: Prim, radius: f32) -> Node {
    Node {
        material,
        lift: Lift::None,
        guard: None,
        shape: Shape::Prim(prim),
        bound: Sphere {
            centre: prim.centre,
            radius,
        },
        cost: 1,
    }
}

fn mat(r: f32, g: f32, b: f32, reflectivity: f32) -> Material {
    Material {
        colour: Vec3::new(r, g, b),
        reflectivity,
    }
}

/// The paper's scene0 camera: origin, looking +z, fov 30.
pub(crate) fn scene0_camera() -> Camera3d {
    Camera3d::looking(Vec3::ZERO, Vec3::Z, Vec3::Y, 30.0).expect("camera")
}

/// The paper's Mandelbulb camera: origin, looking +z, fov 25.
pub(crate) fn mandelbulb_camera() -> Camera3d {
    Camera3d::looking(Vec3::ZERO, Vec3::Z, Vec3::Y, 25.0).expect("camera")
}

/// The paper's scene0 (issue 6): plane, rotated box, reflective sphere, capped cone, torus,
/// octahedron, one light, soft shadows.
pub(crate) fn scene0() -> Plan {
    let plane = Prim::at(
        Vec3::ZERO,
        PrimKind::Plane {
            normal: Vec3::Y,
            offset: -3.0,
        },
    );
    let mut boxed = Prim::at(
        Vec3::new(-4.0, -1.5, 15.0),
        PrimKind::Box {
            half: Vec3::new(0.25, 0.5, 1.0),
        },
    );
    boxed.rotation =
        Some(rotation_degrees(Vec3::new(1.779_426_2, -1.154_797_4, -12.037_571)).transpose());
    let nodes = vec![
        node(0, plane, 1.0e4),
        node(1, boxed, 1.2),
        node(
            2,
            Prim::at(Vec3::new(0.0, 0.0, 20.0), PrimKind::Sphere { r: 3.0 }),
            3.0,
        ),
        node(
            1,
            Prim::at(
                Vec3::new(1.5, -1.5, 12.0),
                PrimKind::CappedCone {
                    h: 1.0,
                    r1: 1.0,
                    r2: 0.5,
                },
            ),
            1.5,
        ),
        node(
            3,
            Prim::at(
                Vec3::new(4.0, -1.5, 15.0),
                PrimKind::Torus {
                    major: 1.0,
                    minor: 0.5,
                },
            ),
            1.5,
        ),
        node(
            4,
            Prim::at(Vec3::new(-1.5, -1.5, 12.0), PrimKind::Octahedron { s: 1.0 }),
            1.0,
        ),
    ];
    Plan {
        key: 0x5ce0,
        march: paper_march(),
        terrain: None,
        early_out: None,
        nodes,
        materials: vec![
            mat(1.0, 1.0, 1.0, 0.0),
            mat(0.0, 0.1, 0.6, 0.0),
            mat(0.3, 0.0, 0.0, 0.5),
            mat(0.5, 0.5, 0.0, 0.0),
            mat(0.0, 0.6, 0.1, 0.0),
        ],
        shading: paper_shading(
            PointLight {
                position: Vec3::new(0.0, 100.0, 0.0),
                emission: 200.0,
            },
            true,
        ),
        material_ids: true,
        hash: Hash::DotFract,
    }
}

/// The paper's Mandelbulb scene: plane y = -1.5 and a power-8 bulb at (0, 0, 6).
pub(crate) fn mandelbulb() -> Plan {
    let plane = Prim::at(
        Vec3::ZERO,
        PrimKind::Plane {
            normal: Vec3::Y,
            offset: -1.5,
        },
    );
    let bulb = Node {
        material: 1,
        lift: Lift::None,
        guard: None,
        shape: Shape::Mandelbulb {
            centre: Vec3::new(0.0, 0.0, 6.0),
            iterations: 4,
            bailout: 256.0,
            derivative: 1.5,
        },
        bound: Sphere {
            centre: Vec3::new(0.0, 0.0, 6.0),
            radius: 1.2,
        },
        cost: 1,
    };
    Plan {
        key: 0xb01b,
        march: paper_march(),
        terrain: None,
        early_out: None,
        nodes: vec![node(0, plane, 1.0e4), bulb],
        materials: vec![mat(1.0, 1.0, 1.0, 0.0), mat(0.0, 0.1, 0.6, 0.0)],
        shading: paper_shading(
            PointLight {
                position: Vec3::new(0.0, 5.0, -10.0),
                emission: 70.0,
            },
            true,
        ),
        material_ids: true,
        hash: Hash::DotFract,
    }
}

/// A camera over [`world`]: at (0, 4, -6) looking down the valley.
pub(crate) fn world_camera() -> Camera3d {
    Camera3d::looking(
        Vec3::new(0.0, 4.0, -6.0),
        Vec3::new(0.0, -0.25, 1.0),
        Vec3::Y,
        50.0,
    )
    .expect("camera")
}

/// Which shader-side switches a [`world`] plan uses.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorldSwitches {
    /// Guards, nearest rows, material IDs, adaptive AO, terrain shadow, dot-fract hash,
    /// analytic normal, baked lifts: all on (`true`) or all off.
    pub optimized: bool,
    /// Over-relaxation factor.
    pub relax: f32,
}

fn fbm() -> Fbm {
    Fbm {
        base: -1.0,
        amplitude: 1.6,
        frequency: 0.15,
        lacunarity: 2.0,
        gain: 0.45,
        octaves: 5,
        rotation: 0.6,
    }
}

/// A small outdoor world with terrain, a blended tree, a displaced rock, vineyard rows, a
/// capsule, a cylinder, an ellipsoid and a round box; `switches` pick the variants.
pub(crate) fn world(switches: WorldSwitches) -> Plan {
    let on = switches.optimized;
    let lift = |x: f32, z: f32, baked: f32| {
        if on {
            Lift::Baked(baked)
        } else {
            Lift::Ground { x, z }
        }
    };
    let guard = |centre: Vec3, half: Vec3| {
        on.then_some(Guard {
            centre,
            half,
            margin: 0.3,
        })
    };
    let tree = Node {
        material: 1,
        lift: lift(2.0, 8.0, -0.4),
        guard: guard(Vec3::new(2.0, 1.5, 8.0), Vec3::new(1.2, 1.6, 1.2)),
        shape: Shape::Blend {
            k: 0.3,
            parts: vec![
                Prim::at(
                    Vec3::new(2.0, 0.6, 8.0),
                    PrimKind::Cylinder { r: 0.15, h: 0.6 },
                ),
                Prim::at(Vec3::new(2.0, 1.6, 8.0), PrimKind::Sphere { r: 0.8 }),
                Prim::at(
                    Vec3::new(2.0, 2.3, 8.0),
                    PrimKind::Ellipsoid {
                        r: Vec3::new(0.6, 0.7, 0.6),
                    },
                ),
            ],
        },
        bound: Sphere {
            centre: Vec3::new(2.0, 1.1, 8.0),
            radius: 2.2,
        },
        cost: 3,
    };
    let rock = Node {
        material: 2,
        lift: lift(-2.5, 6.0, -0.5),
        guard: guard(Vec3::new(-2.5, 0.3, 6.0), Vec3::new(1.0, 0.8, 1.0)),
        shape: Shape::Displaced {
            prim: Prim::at(
                Vec3::new(-2.5, 0.3, 6.0),
                PrimKind::RoundBox {
                    half: Vec3::new(0.8, 0.5, 0.7),
                    r: 0.2,
                },
            ),
            amp: 0.25,
            freq: 2.0,
        },
        bound: Sphere {
            centre: Vec3::new(-2.5, -0.2, 6.0),
            radius: 1.5,
        },
        cost: 2,
    };
    let rows = Node {
        material: 3,
        lift: lift(-6.0, 10.0, -0.6),
        guard: None,
        shape: Shape::Rows {
            part: Prim::at(
                Vec3::new(-6.0, 0.4, 10.0),
                PrimKind::Capsule {
                    a: Vec3::new(-1.5, 0.0, 0.0),
                    b: Vec3::new(1.5, 0.0, 0.0),
                    r: 0.3,
                },
            ),
            spacing: 1.5,
            count: 5,
            nearest: on,
        },
        bound: Sphere {
            centre: Vec3::new(-6.0, -0.2, 13.0),
            radius: 4.5,
        },
        cost: 5,
    };
    let mut post = Prim::at(
        Vec3::new(5.0, 0.5, 12.0),
        PrimKind::RoundBox {
            half: Vec3::new(0.3, 0.9, 0.3),
            r: 0.1,
        },
    );
    post.rotation = Some(rotation_degrees(Vec3::new(0.0, 30.0, 10.0)).transpose());
    let post = Node {
        material: 4,
        lift: lift(5.0, 12.0, -0.5),
        guard: guard(Vec3::new(5.0, 0.5, 12.0), Vec3::new(0.7, 1.1, 0.7)),
        shape: Shape::Prim(post),
        bound: Sphere {
            centre: Vec3::new(5.0, 0.0, 12.0),
            radius: 1.3,
        },
        cost: 1,
    };
    Plan {
        key: if on { 0x3a11 } else { 0x3a00 },
        march: March {
            max_steps: 160,
            hit: 1.0e-3,
            hit_per_t: 1.5e-3,
            far: 60.0,
            escape: 1.0e4,
            step_factor: if on { 0.75 } else { 0.68 },
            ray_offset: 2.0e-2,
            normal_eps: 2.0e-3,
            relax: switches.relax,
        },
        terrain: Some(TerrainPlan {
            fbm: fbm(),
            material: 0,
            step_scale: if on { 0.8 } else { 1.0 },
            analytic_normal: on,
        }),
        early_out: on.then_some(3.5),
        nodes: vec![tree, rock, rows, post],
        materials: vec![
            mat(0.35, 0.45, 0.2, 0.0),
            mat(0.15, 0.4, 0.12, 0.0),
            mat(0.45, 0.42, 0.4, 0.0),
            mat(0.4, 0.25, 0.5, 0.0),
            mat(0.6, 0.35, 0.2, 0.0),
        ],
        shading: Shading::World(WorldShading {
            sun: Vec3::new(0.5, 0.6, -0.4).normalize(),
            sun_colour: Vec3::new(1.3, 1.2, 1.0),
            sky: [Vec3::new(0.75, 0.82, 0.9), Vec3::new(0.3, 0.5, 0.85)],
            ao: if on {
                AoMode::Adaptive {
                    near: 5,
                    far: 3,
                    near_distance: 10.0,
                }
            } else {
                AoMode::Fixed(5)
            },
            shadow: if on {
                ShadowMode::TerrainAndBounds {
                    steps: 4,
                    spacing: 1.0,
                }
            } else {
                ShadowMode::Full { steps: 64, k: 8.0 }
            },
            fog: 0.012,
            gamma: 0.4545,
        }),
        material_ids: on,
        hash: if on { Hash::DotFract } else { Hash::Sin },
    }
}

/// Every hand-built plan with a name and its camera.
pub(crate) fn all_plans() -> Vec<(String, Plan, Camera3d)> {
    let mut plans = vec![
        ("scene0".to_string(), scene0(), scene0_camera()),
        ("mandelbulb".to_string(), mandelbulb(), mandelbulb_camera()),
    ];
    for (name, optimized, relax) in [
        ("world-optimized", true, 1.0),
        ("world-naive", false, 1.0),
        ("world-relaxed", true, 1.6),
    ] {
        plans.push((
            name.to_string(),
            world(WorldSwitches { optimized, relax }),
            world_camera(),
        ));
    }
    plans
}
