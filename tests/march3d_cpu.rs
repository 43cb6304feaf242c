//! The CPU sphere tracer against geometry, against itself across instruction sets, thread
//! counts and tile sizes, and its counting mode, over-relaxation and input errors.

use craterfield::backend::Backend;
use craterfield::march3d::cpu::{self, Rendered, TraceError, TraceOptions};
use craterfield::march3d::plan3d::{
    AoMode, Camera3d, Fbm, Guard, Hash, Lift, March, Material, Node, PaperShading, Plan,
    PointLight, Prim, PrimKind, Shading, ShadowMode, Shape, Sphere, TerrainPlan, WorldShading,
};
use craterfield::march3d::scene::rotation_degrees;
use craterfield::march3d::simd;
use glam::Vec3;

fn paper_march() -> March {
    March {
        max_steps: 3000,
        hit: 5e-6,
        hit_per_t: 0.0,
        far: f32::INFINITY,
        escape: 100.0,
        step_factor: 1.0,
        ray_offset: 1e-3,
        normal_eps: 1e-4,
        relax: 1.0,
    }
}

fn paper_shading(lights: Vec<PointLight>, shadow_k: Option<f32>) -> Shading {
    Shading::Paper(PaperShading {
        lights,
        shininess: 15.0,
        specular: 0.2,
        ambient: 0.01,
        bounces: 3,
        reflection_scale: 0.1,
        shadow_k,
        fog: 7e-6,
        gamma: 0.4545,
    })
}

fn mat(r: f32, g: f32, b: f32, reflectivity: f32) -> Material {
    Material {
        colour: Vec3::new(r, g, b),
        reflectivity,
    }
}

fn node(material: u32, prim: Prim, bound: Sphere) -> Node {
    Node {
        material,
        lift: Lift::None,
        guard: None,
        shape: Shape::Prim(prim),
        bound,
        cost: 1,
    }
}

fn sphere(c: Vec3, r: f32) -> Sphere {
    Sphere {
        centre: c,
        radius: r,
    }
}

fn camera(fov: f32) -> Camera3d {
    Camera3d::looking(Vec3::ZERO, Vec3::Z, Vec3::Y, fov).unwrap()
}

/// The reference paper's scene0.
fn scene0() -> (Plan, Camera3d) {
    let at = |x, y, z| Vec3::new(x, y, z);
    let plane = Prim::at(
        Vec3::ZERO,
        PrimKind::Plane {
            normal: Vec3::Y,
            offset: -3.0,
        },
    );
    let boxed = Prim {
        centre: at(-4.0, -1.5, 15.0),
        rotation: Some(rotation_degrees(at(1.779_426_2, -1.154_797_4, -12.037_571)).transpose()),
        kind: PrimKind::Box {
            half: at(0.25, 0.5, 1.0),
        },
    };
    let nodes = vec![
        node(0, plane, sphere(Vec3::ZERO, f32::INFINITY)),
        node(1, boxed, sphere(at(-4.0, -1.5, 15.0), 1.2)),
        node(
            2,
            Prim::at(at(0.0, 0.0, 20.0), PrimKind::Sphere { r: 3.0 }),
            sphere(at(0.0, 0.0, 20.0), 3.0),
        ),
        node(
            1,
            Prim::at(
                at(1.5, -1.5, 12.0),
                PrimKind::CappedCone {
                    h: 1.0,
                    r1: 1.0,
                    r2: 0.5,
                },
            ),
            sphere(at(1.5, -1.5, 12.0), 1.5),
        ),
        node(
            3,
            Prim::at(
                at(4.0, -1.5, 15.0),
                PrimKind::Torus {
                    major: 1.0,
                    minor: 0.5,
                },
            ),
            sphere(at(4.0, -1.5, 15.0), 1.5),
        ),
        node(
            4,
            Prim::at(at(-1.5, -1.5, 12.0), PrimKind::Octahedron { s: 1.0 }),
            sphere(at(-1.5, -1.5, 12.0), 1.0),
        ),
    ];
    let plan = Plan {
        key: 0,
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
            vec![PointLight {
                position: at(0.0, 100.0, 0.0),
                emission: 200.0,
            }],
            Some(3.0),
        ),
        material_ids: true,
        hash: Hash::DotFract,
    };
    (plan, camera(30.0))
}

/// The reference paper's Mandelbulb scene.
fn mandelbulb() -> (Plan, Camera3d) {
    let centre = Vec3::new(0.0, 0.0, 6.0);
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
            centre,
            iterations: 4,
            bailout: 256.0,
            derivative: 1.5,
        },
        bound: sphere(centre, 1.25),
        cost: 1,
    };
    let plan = Plan {
        key: 0,
        march: paper_march(),
        terrain: None,
        early_out: None,
        nodes: vec![node(0, plane, sphere(Vec3::ZERO, f32::INFINITY)), bulb],
        materials: vec![mat(1.0, 1.0, 1.0, 0.0), mat(0.0, 0.1, 0.6, 0.0)],
        shading: paper_shading(
            vec![PointLight {
                position: Vec3::new(0.0, 5.0, -10.0),
                emission: 70.0,
            }],
            Some(3.0),
        ),
        material_ids: true,
        hash: Hash::DotFract,
    };
    (plan, camera(25.0))
}

/// A small outdoor world exercising the terrain and every node kind.
fn world() -> (Plan, Camera3d) {
    let fbm = Fbm {
        base: 0.0,
        amplitude: 1.5,
        frequency: 0.15,
        lacunarity: 2.0,
        gain: 0.5,
        octaves: 4,
        rotation: 0.6,
    };
    let ground = |x: f32, z: f32| fbm.height(Hash::DotFract, x, z).0;
    let tree_at = Vec3::new(-2.0, 0.0, 12.0);
    let tree = Node {
        material: 1,
        lift: Lift::Ground {
            x: tree_at.x,
            z: tree_at.z,
        },
        guard: Some(Guard {
            centre: tree_at + Vec3::new(0.0, 1.5, 0.0),
            half: Vec3::new(1.2, 1.6, 1.2),
            margin: 0.3,
        }),
        shape: Shape::Blend {
            k: 0.4,
            parts: vec![
                Prim::at(
                    tree_at + Vec3::new(0.0, 0.8, 0.0),
                    PrimKind::Cylinder { r: 0.15, h: 0.8 },
                ),
                Prim::at(
                    tree_at + Vec3::new(0.0, 2.0, 0.0),
                    PrimKind::Ellipsoid {
                        r: Vec3::new(1.0, 0.9, 1.0),
                    },
                ),
                Prim::at(
                    tree_at + Vec3::new(0.3, 2.6, 0.0),
                    PrimKind::Sphere { r: 0.5 },
                ),
            ],
        },
        bound: sphere(tree_at + Vec3::new(0.0, 1.5 + ground(-2.0, 12.0), 0.0), 2.2),
        cost: 3,
    };
    let rock_at = Vec3::new(2.5, ground(2.5, 10.0), 10.0);
    let rock = Node {
        material: 2,
        lift: Lift::None,
        guard: None,
        shape: Shape::Displaced {
            prim: Prim::at(
                rock_at,
                PrimKind::RoundBox {
                    half: Vec3::new(0.6, 0.4, 0.5),
                    r: 0.1,
                },
            ),
            amp: 0.15,
            freq: 3.0,
        },
        bound: sphere(rock_at, 1.0),
        cost: 1,
    };
    let rows_at = Vec3::new(5.0, 0.0, 14.0);
    let rows = Node {
        material: 3,
        lift: Lift::Baked(ground(5.0, 14.0)),
        guard: None,
        shape: Shape::Rows {
            part: Prim::at(
                rows_at,
                PrimKind::Capsule {
                    a: Vec3::new(0.0, 0.3, 0.0),
                    b: Vec3::new(3.0, 0.3, 0.0),
                    r: 0.2,
                },
            ),
            spacing: 1.2,
            count: 4,
            nearest: true,
        },
        bound: sphere(rows_at + Vec3::new(1.5, ground(5.0, 14.0), 1.8), 3.0),
        cost: 2,
    };
    let hut_at = Vec3::new(-5.0, ground(-5.0, 18.0), 18.0);
    let hut = node(
        2,
        Prim::at(
            hut_at,
            PrimKind::Box {
                half: Vec3::new(1.0, 1.0, 1.0),
            },
        ),
        sphere(hut_at, 1.8),
    );
    let plan = Plan {
        key: 0,
        march: March {
            max_steps: 400,
            hit: 1e-3,
            hit_per_t: 1e-3,
            far: 80.0,
            escape: 200.0,
            step_factor: 1.0,
            ray_offset: 2e-2,
            normal_eps: 1e-3,
            relax: 1.0,
        },
        terrain: Some(TerrainPlan {
            fbm,
            material: 0,
            step_scale: fbm.step_scale(),
            analytic_normal: true,
        }),
        early_out: Some(8.0),
        nodes: vec![tree, rock, rows, hut],
        materials: vec![
            mat(0.3, 0.5, 0.2, 0.0),
            mat(0.1, 0.4, 0.1, 0.0),
            mat(0.4, 0.4, 0.4, 0.0),
            mat(0.5, 0.3, 0.1, 0.0),
        ],
        shading: Shading::World(WorldShading {
            sun: Vec3::new(0.4, 0.7, -0.3).normalize(),
            sun_colour: Vec3::new(1.2, 1.1, 0.9),
            sky: [Vec3::new(0.7, 0.8, 0.9), Vec3::new(0.3, 0.5, 0.9)],
            ao: AoMode::Adaptive {
                near: 5,
                far: 3,
                near_distance: 12.0,
            },
            shadow: ShadowMode::TerrainAndBounds {
                steps: 4,
                spacing: 0.5,
            },
            fog: 0.02,
            gamma: 0.4545,
        }),
        material_ids: true,
        hash: Hash::DotFract,
    };
    let cam = Camera3d::looking(
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::new(0.0, -0.2, 1.0),
        Vec3::Y,
        50.0,
    )
    .unwrap();
    (plan, cam)
}

/// The world with the other shading switches: full soft shadows, fixed AO, central
/// differences on the terrain, materials found after the march, the Sin hash.
fn world_alt() -> (Plan, Camera3d) {
    let (mut plan, cam) = world();
    if let Shading::World(w) = &mut plan.shading {
        w.shadow = ShadowMode::Full { steps: 48, k: 8.0 };
        w.ao = AoMode::Fixed(4);
    }
    if let Some(t) = &mut plan.terrain {
        t.analytic_normal = false;
    }
    plan.material_ids = false;
    plan.hash = Hash::Sin;
    (plan, cam)
}

fn opts(backend: Backend, threads: usize, tile: u32) -> TraceOptions {
    TraceOptions {
        threads,
        backend: Some(backend),
        tile,
    }
}

fn draw(scene: &(Plan, Camera3d), o: &TraceOptions) -> Rendered {
    cpu::render(&scene.0, &scene.1, 64, 36, o).unwrap()
}

/// Pixels whose channels differ by more than `levels`, and the largest difference.
fn differing(a: &Rendered, b: &Rendered, levels: u8) -> (usize, u8) {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let mut n = 0;
    let mut worst = 0;
    for (pa, pb) in a.rgba.chunks(4).zip(b.rgba.chunks(4)) {
        let d = pa
            .iter()
            .zip(pb)
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap();
        worst = worst.max(d);
        n += usize::from(d > levels);
    }
    (n, worst)
}

fn scenes() -> Vec<(&'static str, (Plan, Camera3d))> {
    vec![
        ("scene0", scene0()),
        ("mandelbulb", mandelbulb()),
        ("world", world()),
        ("world_alt", world_alt()),
    ]
}

/// Not black everywhere, not one colour: the picture has content.
fn assert_has_content(img: &Rendered, name: &str) {
    let first = &img.rgba[..4];
    assert!(
        img.rgba.chunks(4).any(|px| px != first),
        "{name}: a flat image"
    );
    assert!(img.rgba.chunks(4).all(|px| px[3] == 255), "{name}: alpha");
}

#[test]
fn every_available_isa_draws_the_scalar_image() {
    for (name, scene) in scenes() {
        let reference = draw(&scene, &opts(Backend::Scalar, 1, 16));
        assert_has_content(&reference, name);
        for isa in [Backend::Avx2, Backend::Avx512, Backend::Neon] {
            if !isa.is_available() {
                continue;
            }
            let img = draw(&scene, &opts(isa, 1, 16));
            let (n, worst) = differing(&reference, &img, 3);
            let pixels = (img.width * img.height) as usize;
            assert!(
                n * 100 < pixels,
                "{name} on {isa}: {n} of {pixels} pixels differ by more than 3 levels (worst {worst})"
            );
        }
    }
}

#[test]
fn threads_and_tiles_do_not_change_the_image() {
    for (name, scene) in scenes() {
        let isa = simd::best();
        let one = draw(&scene, &opts(isa, 1, 32));
        assert_eq!(one, draw(&scene, &opts(isa, 2, 32)), "{name}: threads");
        assert_eq!(one, draw(&scene, &opts(isa, 3, 5)), "{name}: tiles");
    }
}

#[test]
fn a_sphere_covers_the_pixels_whose_rays_meet_it() {
    let centre = Vec3::new(0.7, -0.4, 20.0);
    let radius = 3.0;
    let plan = Plan {
        key: 0,
        march: paper_march(),
        terrain: None,
        early_out: None,
        nodes: vec![node(
            0,
            Prim::at(centre, PrimKind::Sphere { r: radius }),
            sphere(centre, radius),
        )],
        materials: vec![mat(1.0, 1.0, 1.0, 0.0)],
        shading: Shading::Paper(PaperShading {
            lights: vec![],
            shininess: 15.0,
            specular: 0.0,
            ambient: 0.5,
            bounces: 0,
            reflection_scale: 0.1,
            shadow_k: None,
            fog: 0.0,
            gamma: 1.0,
        }),
        material_ids: true,
        hash: Hash::DotFract,
    };
    let cam = camera(30.0);
    let (w, h) = (96, 64);
    for isa in [Backend::Scalar, simd::best()] {
        let img = cpu::render(&plan, &cam, w, h, &opts(isa, 1, 16)).unwrap();
        let mut hits = 0;
        for j in 0..h {
            for i in 0..w {
                let dir = cam.ray(i, j, w, h);
                // Distance of the sphere's centre from the ray's line.
                let along = centre.dot(dir);
                let miss_by = (centre - dir * along).length() - radius;
                let px = &img.rgba[((j * w + i) * 4) as usize..][..4];
                // Half a pixel's angular size at the sphere's distance is about 0.05.
                if miss_by < -0.1 {
                    // Ambient 0.5: 127.5 levels, truncated as the reference renderer does.
                    assert_eq!(px, [127, 127, 127, 255], "{isa}: ({i}, {j}) should hit");
                    hits += 1;
                } else if miss_by > 0.1 {
                    assert_eq!(px, [0, 0, 0, 255], "{isa}: ({i}, {j}) should miss");
                }
            }
        }
        assert!(hits > 200, "{hits}");
    }
}

#[test]
fn counting_mode_counts_and_draws_the_scalar_image() {
    for (name, scene) in scenes() {
        let (img, stats) = cpu::render_counted(&scene.0, &scene.1, 64, 36, 2).unwrap();
        assert_eq!(img, draw(&scene, &opts(Backend::Scalar, 1, 16)), "{name}");
        assert_eq!(stats.pixels, 64 * 36);
        assert!(stats.steps > stats.pixels, "{name}: {stats:?}");
        assert!(stats.sdf_evals >= stats.steps, "{name}: {stats:?}");
        assert!(stats.flops > stats.sdf_evals, "{name}: {stats:?}");
        // Every ray takes at most max_steps: primary, up to `bounces` reflections, and a
        // shadow ray per light per hit.
        let (rays, max) = match &scene.0.shading {
            Shading::Paper(s) => (
                (1 + s.bounces as u64) * (1 + s.lights.len() as u64),
                scene.0.march.max_steps as u64,
            ),
            Shading::World(_) => (2, scene.0.march.max_steps as u64),
        };
        assert!(
            stats.steps <= stats.pixels * rays * max,
            "{name}: {stats:?}"
        );
        // The same counts whatever the thread count.
        let (_, again) = cpu::render_counted(&scene.0, &scene.1, 64, 36, 1).unwrap();
        assert_eq!(stats, again, "{name}");
    }
}

#[test]
fn a_primary_ray_takes_at_most_max_steps() {
    // A ray grazing a plane creeps along it: the step limit ends it.
    let (mut plan, cam) = scene0();
    plan.march.max_steps = 40;
    plan.shading = paper_shading(vec![], None);
    if let Shading::Paper(s) = &mut plan.shading {
        s.bounces = 0;
    }
    for j in [0, 20, 35] {
        let c = Camera3d {
            tan_half_fov: cam.tan_half_fov * (1.0 + j as f32 * 0.01),
            ..cam
        };
        let (_, stats) = cpu::render_counted(&plan, &c, 1, 1, 1).unwrap();
        assert!(stats.steps >= 1 && stats.steps <= 40, "{stats:?}");
    }
    let (_, stats) = cpu::render_counted(&plan, &cam, 64, 36, 1).unwrap();
    assert!(stats.steps <= 64 * 36 * 40);
    // Some rays of the plane's horizon do run out of steps.
    assert!(stats.steps > 64 * 36 * 10, "{stats:?}");
}

#[test]
fn over_relaxation_keeps_the_image_with_fewer_steps() {
    for (name, scene) in [("scene0", scene0()), ("world", world())] {
        let (plain, s1) = cpu::render_counted(&scene.0, &scene.1, 64, 36, 1).unwrap();
        let mut relaxed = scene.0.clone();
        relaxed.march.relax = 1.6;
        let (img, s2) = cpu::render_counted(&relaxed, &scene.1, 64, 36, 1).unwrap();
        assert!(
            s2.steps < s1.steps,
            "{name}: {} steps relaxed vs {} plain",
            s2.steps,
            s1.steps
        );
        // Rays grazing the terrain near the horizon are sensitive to where the steps
        // land: a few of them may change.
        let (n, worst) = differing(&plain, &img, 8);
        assert!(
            n * 20 < 64 * 36,
            "{name}: {n} pixels differ (worst {worst})"
        );
    }
}

#[test]
fn materials_found_after_the_march_equal_tracked_ones() {
    let (plan, cam) = scene0();
    let mut untracked = plan.clone();
    untracked.material_ids = false;
    let o = opts(simd::best(), 1, 16);
    let a = cpu::render(&plan, &cam, 64, 36, &o).unwrap();
    let b = cpu::render(&untracked, &cam, 64, 36, &o).unwrap();
    assert_eq!(a, b);
    let (_, sa) = cpu::render_counted(&plan, &cam, 64, 36, 1).unwrap();
    let (_, sb) = cpu::render_counted(&untracked, &cam, 64, 36, 1).unwrap();
    assert!(sb.sdf_evals > sa.sdf_evals, "{sa:?} {sb:?}");
}

#[test]
fn guards_and_the_early_out_save_work_without_changing_the_picture() {
    let (plan, cam) = world();
    let mut naive = plan.clone();
    naive.early_out = None;
    for n in &mut naive.nodes {
        n.guard = None;
    }
    let (a, sa) = cpu::render_counted(&plan, &cam, 64, 36, 1).unwrap();
    let (b, sb) = cpu::render_counted(&naive, &cam, 64, 36, 1).unwrap();
    assert!(sa.sdf_evals < sb.sdf_evals, "{sa:?} {sb:?}");
    // Only rays grazing the terrain, sensitive to where the steps land, may change.
    let (n, worst) = differing(&a, &b, 8);
    assert!(n * 20 < 64 * 36, "{n} pixels differ (worst {worst})");
}

#[test]
fn bad_sizes_and_values_are_errors() {
    let (plan, cam) = scene0();
    let o = TraceOptions::default();
    for (w, h) in [(0, 10), (10, 0), (16_385, 1), (8192, 8193)] {
        assert!(
            matches!(
                cpu::render(&plan, &cam, w, h, &o),
                Err(TraceError::BadSize { .. })
            ),
            "{w}x{h}"
        );
        assert!(cpu::render_counted(&plan, &cam, w, h, 1).is_err());
    }
    let nan_cam = Camera3d {
        position: Vec3::new(f32::NAN, 0.0, 0.0),
        ..cam
    };
    assert!(matches!(
        cpu::render(&plan, &nan_cam, 8, 8, &o),
        Err(TraceError::BadCamera(_))
    ));
    let fov_cam = Camera3d {
        tan_half_fov: f32::NAN,
        ..cam
    };
    assert!(matches!(
        cpu::render(&plan, &fov_cam, 8, 8, &o),
        Err(TraceError::BadCamera(_))
    ));
    let mut nan_plan = plan.clone();
    nan_plan.nodes[2].shape = Shape::Prim(Prim::at(
        Vec3::new(0.0, f32::NAN, 20.0),
        PrimKind::Sphere { r: 3.0 },
    ));
    assert!(matches!(
        cpu::render(&nan_plan, &cam, 8, 8, &o),
        Err(TraceError::BadPlan(_))
    ));
    let mut nan_march = plan.clone();
    nan_march.march.hit = f32::NAN;
    assert!(matches!(
        cpu::render(&nan_march, &cam, 8, 8, &o),
        Err(TraceError::BadPlan(_))
    ));
    let mut bad_material = plan.clone();
    bad_material.nodes[0].material = 99;
    assert!(matches!(
        cpu::render(&bad_material, &cam, 8, 8, &o),
        Err(TraceError::BadPlan(_))
    ));
    let tile0 = TraceOptions { tile: 0, ..o };
    assert!(matches!(
        cpu::render(&plan, &cam, 8, 8, &tile0),
        Err(TraceError::BadTile)
    ));
    for isa in Backend::ALL {
        if simd::check(isa).is_err() {
            assert!(matches!(
                cpu::render(&plan, &cam, 8, 8, &opts(isa, 1, 8)),
                Err(TraceError::Backend(_))
            ));
        }
    }
}

/// Seconds per frame of the paper's scenes at 1280x720 (run in release with `--ignored
/// --nocapture`; prints, asserts nothing about time).
#[test]
#[ignore]
fn time_paper_scenes() {
    let isa = simd::best();
    for (name, scene) in [("scene0", scene0()), ("mandelbulb", mandelbulb())] {
        for threads in [1, 2] {
            let mut best = f64::INFINITY;
            for _ in 0..3 {
                let t = std::time::Instant::now();
                let img =
                    cpu::render(&scene.0, &scene.1, 1280, 720, &opts(isa, threads, 32)).unwrap();
                best = best.min(t.elapsed().as_secs_f64());
                assert_eq!(img.rgba.len(), 1280 * 720 * 4);
            }
            println!("{name} {isa} threads {threads}: {best:.3} s");
        }
    }
}
