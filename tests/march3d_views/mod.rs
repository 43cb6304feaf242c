//! The views and checks that both 3D renderers are held to, shared by the CPU tracer's
//! tests (`march3d_fidelity`) and the GPU raymarcher's (`march3d_gpu`): the reference
//! renderer's own pictures of the paper scenes, LOD on against LOD off, and grazing cameras
//! over the terrain that must never show sky below the horizon.
#![allow(dead_code)]

use std::path::PathBuf;

use craterfield::march3d::Camera3d;
use craterfield::march3d::compile::{CompileOptions, Optimization, emit};
use craterfield::march3d::plan3d::{Hash, Plan, Shading};
use craterfield::march3d::scene::{BUILTIN, Lighting, Scene};
use craterfield::visdiff::{DiffOptions, DiffReport, compare, load_png};
use glam::Vec3;
use image::RgbaImage;

/// The size of the reference renderer's pictures.
pub(crate) const REFERENCE_SIZE: (u32, u32) = (1280, 720);

/// The largest FLIP of a paper scene against the reference renderer's picture.
pub(crate) const REFERENCE_MAX_FLIP: f64 = 0.02;

/// The size of the LOD and grazing renders.
pub(crate) const VIEW_SIZE: (u32, u32) = (320, 180);

/// At most this fraction of pixels may differ by more than [`LOD_LEVELS`] between LOD on
/// and off.
pub(crate) const LOD_MAX_FRACTION: f64 = 0.001;
/// See [`LOD_MAX_FRACTION`].
pub(crate) const LOD_LEVELS: u8 = 8;

/// The paper scenes.
pub(crate) const PAPER_SCENES: [&str; 2] = ["scene0", "mandelbulb"];

/// The reference renderer's picture of paper scene `name` (vendored, see
/// `tests/data/README.md`).
pub(crate) fn reference_picture(name: &str) -> RgbaImage {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/march3d-reference")
        .join(format!("{name}.png"));
    load_png(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The plan of builtin scene `name` under `opts` for images of `size`.
pub(crate) fn plan(name: &str, opts: &CompileOptions, size: (u32, u32)) -> (Plan, Camera3d) {
    let scene = Scene::builtin(name).expect("builtin scene");
    let camera = scene.camera.camera().expect("builtin camera");
    (plan_at(&scene, &camera, opts, size), camera)
}

/// The plan of `scene` seen by `camera` under `opts` for images of `size`.
pub(crate) fn plan_at(
    scene: &Scene,
    camera: &Camera3d,
    opts: &CompileOptions,
    size: (u32, u32),
) -> Plan {
    let opts = CompileOptions {
        aspect: size.0 as f32 / size.1 as f32,
        height: size.1,
        ..opts.clone()
    };
    emit(scene, camera, &opts).expect("emit")
}

/// A scene's own preset: the paper's for the paper scenes, every optimization for worlds.
pub(crate) fn own_preset(scene: &Scene) -> CompileOptions {
    match scene.lighting {
        Lighting::Paper(_) => CompileOptions::paper(),
        Lighting::World(_) => CompileOptions::default(),
    }
}

/// Every builtin scene's plan with LOD on and off (each scene's own preset otherwise).
pub(crate) fn lod_pairs() -> Vec<(&'static str, [(Plan, Camera3d); 2])> {
    BUILTIN
        .iter()
        .map(|name| {
            let scene = Scene::builtin(name).expect("builtin scene");
            let own = own_preset(&scene);
            let on = CompileOptions {
                enabled: own
                    .enabled
                    .iter()
                    .copied()
                    .chain([Optimization::Lod])
                    .collect(),
                ..own.clone()
            };
            let off = on.without(Optimization::Lod);
            (
                *name,
                [plan(name, &on, VIEW_SIZE), plan(name, &off, VIEW_SIZE)],
            )
        })
        .collect()
}

/// The FLIP check of a render of paper scene `name` against the reference's picture.
pub(crate) fn against_reference(name: &str, rgba: Vec<u8>) -> DiffReport {
    let (w, h) = REFERENCE_SIZE;
    let ours = RgbaImage::from_raw(w, h, rgba).expect("image size");
    let options = DiffOptions {
        pixel_tolerance: 2,
        max_differing_fraction: 1.0,
        max_mean: 255.0,
        max_error: 255.0,
        max_percentile: 255.0,
        max_flip: REFERENCE_MAX_FLIP,
        ..DiffOptions::default()
    };
    compare(&reference_picture(name), &ours, &options).expect("comparable pictures")
}

/// The LOD check: the fraction of pixels more than [`LOD_LEVELS`] apart.
pub(crate) fn lod_difference(on: &RgbaImage, off: &RgbaImage) -> DiffReport {
    let options = DiffOptions {
        pixel_tolerance: LOD_LEVELS,
        max_differing_fraction: LOD_MAX_FRACTION,
        max_mean: 255.0,
        max_error: 255.0,
        max_percentile: 255.0,
        max_flip: f64::INFINITY,
        ..DiffOptions::default()
    };
    compare(off, on, &options).expect("comparable pictures")
}

/// Cameras that graze the terrain of a world scene: 1.5 units above the ground at points
/// around the scene's own camera, looking level (and slightly down) in four directions,
/// with the scene's field of view. Empty for scenes without terrain.
pub(crate) fn grazing_cameras(scene: &Scene) -> Vec<Camera3d> {
    let Some(terrain) = &scene.terrain else {
        return Vec::new();
    };
    let home = scene.camera.position;
    let mut out = Vec::new();
    for (k, offset) in [(0.0, 0.0), (30.0, 20.0), (-25.0, 40.0)].iter().enumerate() {
        let (x, z) = (home.x + offset.0, home.z + offset.1);
        let (ground, _) = terrain.fbm.height(Hash::DotFract, x, z);
        let eye = Vec3::new(x, ground + 1.5, z);
        for quarter in 0..4 {
            let a = (quarter as f32 + 0.3 * k as f32) * std::f32::consts::FRAC_PI_2;
            let pitch = if quarter % 2 == 0 { 0.0 } else { -0.04 };
            let forward = Vec3::new(a.sin(), pitch, a.cos());
            out.push(Camera3d::looking(eye, forward, Vec3::Y, scene.camera.fov).expect("camera"));
        }
    }
    out
}

/// Pixels of `img` (seen by `camera`) whose ray points below the horizon and that show the
/// sky: the sky's colour in that direction, within 2 levels. Such a ray can only meet the
/// ground, so every one is sky drawn through the terrain.
pub(crate) fn sky_below_horizon(img: &RgbaImage, camera: &Camera3d, plan: &Plan) -> usize {
    let Shading::World(w) = &plan.shading else {
        return 0;
    };
    let byte = |c: f32| (c.clamp(0.0, 1.0).powf(w.gamma) * 255.0 + 0.5).floor();
    let sky = [byte(w.sky[0].x), byte(w.sky[0].y), byte(w.sky[0].z)];
    let (width, height) = img.dimensions();
    let mut leaks = 0;
    for j in 0..height {
        for i in 0..width {
            if camera.ray(i, j, width, height).y >= 0.0 {
                continue;
            }
            let px = img.get_pixel(i, j).0;
            if (0..3).all(|c| (px[c] as f32 - sky[c]).abs() <= 2.0) {
                leaks += 1;
            }
        }
    }
    leaks
}

/// The world scenes (those with terrain) and their grazing cameras' plans.
pub(crate) fn grazing_views() -> Vec<(String, Plan, Camera3d)> {
    let mut out = Vec::new();
    for name in BUILTIN {
        let scene = Scene::builtin(name).expect("builtin scene");
        for (k, camera) in grazing_cameras(&scene).into_iter().enumerate() {
            let plan = plan_at(&scene, &camera, &own_preset(&scene), VIEW_SIZE);
            out.push((format!("{name}-grazing-{k}"), plan, camera));
        }
    }
    out
}
