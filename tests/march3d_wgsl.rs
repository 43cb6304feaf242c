//! The 3D WGSL emitter: every plan's module parses and validates with naga, bad plans are
//! errors, the baked literals are exact, and snapshots of the builtin scenes' modules.

mod march3d_plans;

use std::path::{Path, PathBuf};

use craterfield::march3d::Plan;
use craterfield::march3d::codegen3d::{MARCH3D_WGSL, march_wgsl};
use craterfield::march3d::compile::{CompileOptions, Optimization, emit};
use craterfield::march3d::plan3d::{Lift, PlanError, Shape};
use craterfield::march3d::scene::{BUILTIN, Lighting, Scene};
use march3d_plans::{WorldSwitches, all_plans, scene0, world};
use naga::valid::{Capabilities, ValidationFlags, Validator};

/// Parse and validate WGSL with naga, failing with the located error.
fn validate(name: &str, text: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(text)
        .unwrap_or_else(|e| panic!("{name}: WGSL does not parse:\n{}", e.emit_to_string(text)));
    Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .unwrap_or_else(|e| {
            panic!(
                "{name}: WGSL does not validate:\n{}",
                e.emit_to_string(text)
            )
        });
    module
}

#[test]
fn every_hand_built_plan_validates() {
    for (name, plan, _) in all_plans() {
        let text = march_wgsl(&plan).unwrap_or_else(|e| panic!("{name}: {e}"));
        let module = validate(&name, &text);
        let entry = module
            .entry_points
            .iter()
            .find(|e| e.name == "main")
            .unwrap_or_else(|| panic!("{name}: no entry point `main`"));
        assert_eq!(entry.stage, naga::ShaderStage::Compute, "{name}");
        assert_eq!(entry.workgroup_size, [8, 8, 1], "{name}");
        // One straight-line function per node.
        for i in 0..plan.nodes.len() {
            let fname = format!("em_node{i}");
            assert!(
                module
                    .functions
                    .iter()
                    .any(|(_, f)| f.name.as_deref() == Some(fname.as_str())),
                "{name}: no {fname}"
            );
        }
    }
}

#[test]
fn every_variant_of_each_node_kind_validates() {
    // Rows without nearest repetition, blends with a tiny k, zero-length capsules, lifted by
    // the terrain computed in the shader, without terrain at all. (A blend with k = 0 would
    // divide by zero in both renderers: the one validator refuses it.)
    let mut plan = world(WorldSwitches {
        optimized: false,
        relax: 1.0,
    });
    let mut sharp = plan.clone();
    for node in &mut sharp.nodes {
        if let Shape::Blend { k, .. } = &mut node.shape {
            *k = 0.0;
        }
    }
    assert!(matches!(march_wgsl(&sharp), Err(PlanError::Invalid { .. })));
    for node in &mut plan.nodes {
        match &mut node.shape {
            Shape::Blend { k, .. } => *k = 1e-6,
            Shape::Rows { part, .. } => {
                if let craterfield::march3d::plan3d::PrimKind::Capsule { a, b, .. } = &mut part.kind
                {
                    *b = *a;
                }
            }
            _ => {}
        }
    }
    validate("tiny k, point capsule", &march_wgsl(&plan).unwrap());
    plan.terrain = None;
    plan.early_out = None;
    for node in &mut plan.nodes {
        node.lift = Lift::None;
    }
    validate("no terrain", &march_wgsl(&plan).unwrap());
    plan.nodes.clear();
    validate("no nodes", &march_wgsl(&plan).unwrap());
}

#[test]
fn bad_plans_are_errors_not_shaders() {
    let mut plan = scene0();
    plan.march.hit = f32::NAN;
    assert!(matches!(
        march_wgsl(&plan),
        Err(PlanError::NonFinite { .. })
    ));
    let mut plan = scene0();
    plan.march.escape = f32::NEG_INFINITY;
    assert!(matches!(
        march_wgsl(&plan),
        Err(PlanError::NonFinite { .. })
    ));
    let mut plan = scene0();
    plan.nodes[1].material = 99;
    let err = march_wgsl(&plan).unwrap_err();
    assert!(
        matches!(
            err,
            PlanError::Material {
                index: 99,
                count: 5,
                ..
            }
        ),
        "{err}"
    );
    let mut plan = world(WorldSwitches {
        optimized: true,
        relax: 1.0,
    });
    if let Some(t) = &mut plan.terrain {
        t.fbm.octaves = 0;
    }
    assert!(matches!(march_wgsl(&plan), Err(PlanError::Range { .. })));
    if let Some(t) = &mut plan.terrain {
        t.fbm.octaves = 4;
        t.fbm.frequency = 0.0;
    }
    let err = march_wgsl(&plan).unwrap_err();
    assert!(
        matches!(&err, PlanError::Invalid { what, .. } if what == "terrain.frequency"),
        "{err}"
    );
    // An infinite escape distance is allowed, a zero one is not.
    let mut plan = scene0();
    plan.march.escape = f32::INFINITY;
    assert!(march_wgsl(&plan).is_ok());
    plan.march.escape = 0.0;
    assert!(matches!(march_wgsl(&plan), Err(PlanError::Invalid { .. })));
    // The paper's unbounded far plane is allowed.
    let plan = scene0();
    assert!(plan.march.far.is_infinite());
    assert!(march_wgsl(&plan).is_ok());
}

/// Every `f32` literal of the emitted text, in order.
fn f32_literals(text: &str) -> Vec<f32> {
    let mut out = Vec::new();
    for token in text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-')) {
        if let Some(num) = token.strip_suffix('f')
            && num
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit() || c == '-')
            && let Ok(v) = num.parse::<f32>()
        {
            out.push(v);
        }
    }
    out
}

#[test]
fn plan_values_are_baked_bit_for_bit() {
    let plan = scene0();
    let text = march_wgsl(&plan).unwrap();
    let literals = f32_literals(&text);
    let has = |v: f32| literals.iter().any(|l| l.to_bits() == v.to_bits());
    let rotation = plan.nodes[1].shape.clone();
    let Shape::Prim(boxed) = rotation else {
        panic!("scene0's box is a primitive")
    };
    for v in boxed.rotation.expect("rotated box").to_cols_array() {
        assert!(has(v), "rotation entry {v:?} is not baked exactly");
    }
    for v in [5.0e-6, 1.0e-3, 1.0e-4, 7.0e-6, 0.4545, 200.0, 100.0] {
        assert!(has(v), "{v:?} is not baked exactly");
    }
}

fn snapshot_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders/emitted")
}

fn check_snapshot(name: &str, text: &str) {
    let path = snapshot_dir().join(format!("march3d_{name}.wgsl"));
    if std::env::var("CRATERFIELD_UPDATE_SNAPSHOTS").as_deref() == Ok("1") {
        std::fs::create_dir_all(snapshot_dir()).unwrap();
        std::fs::write(&path, text).unwrap();
        println!("updated snapshot {}", path.display());
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "no snapshot {} ({e}); run with CRATERFIELD_UPDATE_SNAPSHOTS=1 to write it",
            path.display()
        )
    });
    if expected != text {
        let line = expected
            .lines()
            .zip(text.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| expected.lines().count().min(text.lines().count()));
        panic!(
            "{} differs from the emitted text at line {}; if the change is intended, run \
             `CRATERFIELD_UPDATE_SNAPSHOTS=1 cargo test -p craterfield --test march3d_wgsl \
             snapshots` and review the diff",
            path.display(),
            line + 1
        );
    }
}

/// The plan of a builtin scene for its own camera: the paper preset for the paper scenes,
/// every optimization for the worlds (or none, with `naive`).
fn builtin_plan(name: &str, naive: bool) -> Plan {
    let scene = Scene::builtin(name).unwrap();
    let camera = scene.camera.camera().unwrap();
    let opts = match (&scene.lighting, naive) {
        (Lighting::Paper(_), _) => CompileOptions::paper(),
        (Lighting::World(_), false) => CompileOptions::default(),
        (Lighting::World(_), true) => CompileOptions::naive(),
    };
    emit(&scene, &camera, &opts).unwrap()
}

#[test]
fn every_builtin_scene_validates_with_every_optimization_switched_off_in_turn() {
    for name in BUILTIN {
        for naive in [false, true] {
            let plan = builtin_plan(name, naive);
            validate(name, &march_wgsl(&plan).unwrap());
        }
        let scene = Scene::builtin(name).unwrap();
        let camera = scene.camera.camera().unwrap();
        for o in Optimization::ALL {
            let plan = emit(&scene, &camera, &CompileOptions::default().without(o)).unwrap();
            validate(
                &format!("{name} no-{}", o.name()),
                &march_wgsl(&plan).unwrap(),
            );
        }
    }
}

/// The snapshots hold only what the emitter generated: the module is that text followed by
/// the hand-written half (`shaders/march3d.wgsl`), which is checked here and not repeated in
/// every snapshot.
#[test]
fn snapshots_of_the_builtin_scenes_match() {
    for name in BUILTIN {
        let module = march_wgsl(&builtin_plan(name, false)).unwrap();
        let emitted = module
            .strip_suffix(MARCH3D_WGSL)
            .unwrap_or_else(|| panic!("{name}: the module does not end with shaders/march3d.wgsl"));
        check_snapshot(name, emitted);
    }
}
