//! The 2D WGSL emitter: every emitted module validates with naga, snapshots of the example
//! levels, culling decisions and keys, and the shader cache.

mod common;
mod emit_support;

use std::path::{Path, PathBuf};

use common::Rng;
use craterfield::emit::{Fate, TerrainEmitter};
use craterfield::field2d::{Aabb, Graph};
#[cfg(feature = "gpu")]
use craterfield::gpu::PipelineCache;
use craterfield::wgsl::f32_literal;
use emit_support::{every_variant_graph, example_levels, islands_graph, prospero_graph};
use glam::Vec2;
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

/// Every module-scope name except `base_sample` starts with `em_`, and `base_sample` has the
/// contract's signature.
fn check_names(name: &str, module: &naga::Module) {
    let mut base_sample = 0;
    for (_, f) in module.functions.iter() {
        let fname = f.name.as_deref().unwrap_or("");
        if fname == "base_sample" {
            base_sample += 1;
            assert_eq!(f.arguments.len(), 1, "{name}: base_sample takes one point");
            let arg = &module.types[f.arguments[0].ty].inner;
            let ret = &module.types[f.result.as_ref().expect("base_sample returns").ty].inner;
            assert!(
                matches!(arg, naga::TypeInner::Vector { size: naga::VectorSize::Bi, scalar } if *scalar == naga::Scalar::F32),
                "{name}: base_sample takes vec2<f32>, got {arg:?}"
            );
            assert!(
                matches!(ret, naga::TypeInner::Vector { size: naga::VectorSize::Quad, scalar } if *scalar == naga::Scalar::F32),
                "{name}: base_sample returns vec4<f32>, got {ret:?}"
            );
        } else {
            assert!(
                fname.starts_with("em_"),
                "{name}: function `{fname}` is not prefixed"
            );
        }
    }
    assert_eq!(base_sample, 1, "{name}: defines base_sample once");
    for (_, c) in module.constants.iter() {
        let cname = c.name.as_deref().unwrap_or("");
        assert!(
            cname.starts_with("em_"),
            "{name}: constant `{cname}` is not prefixed"
        );
    }
    for (_, g) in module.global_variables.iter() {
        let gname = g.name.as_deref().unwrap_or("");
        assert!(
            gname.starts_with("em_"),
            "{name}: variable `{gname}` is not prefixed"
        );
        assert!(g.binding.is_none(), "{name}: `{gname}` is a binding");
    }
    assert!(module.entry_points.is_empty(), "{name}: has an entry point");
    for (_, t) in module.types.iter() {
        if let Some(tname) = &t.name {
            assert!(
                tname.starts_with("em_"),
                "{name}: type `{tname}` is not prefixed"
            );
        }
    }
}

fn emit_and_validate(name: &str, emitter: &TerrainEmitter, view: Option<Aabb>) -> String {
    let plan = emitter.plan(view, 32.0);
    let text = emitter.emit(&plan);
    let module = validate(name, &text);
    check_names(name, &module);
    text
}

#[test]
fn literals_round_trip_bit_for_bit_through_naga() {
    let mut values = vec![
        0.0,
        -0.0,
        1.0,
        -1.5,
        0.1,
        1.0 / 3.0,
        16_777_216.0,
        16_777_217.0,
        std::f32::consts::PI,
        f32::EPSILON,
        f32::MIN_POSITIVE,
        f32::MAX,
        -f32::MAX,
        1.0e20,
        1.0e-7,
        123_456.79,
    ];
    let mut rng = Rng(7);
    while values.len() < 3000 {
        // Random bit patterns: every exponent, both signs, subnormals excluded (GPUs may flush
        // them; the emitter never relies on one).
        let bits = (rng.unit() * 65536.0) as u32 | (((rng.unit() * 65536.0) as u32) << 16);
        let v = f32::from_bits(bits);
        if v.is_finite() && (v == 0.0 || v.is_normal()) {
            values.push(v);
        }
    }
    let text: String = values
        .iter()
        .enumerate()
        .map(|(i, v)| format!("const em_v{i}: f32 = {};\n", f32_literal(*v).unwrap()))
        .collect();
    let module = validate("literals", &text);
    let mut checked = 0;
    for (_, c) in module.constants.iter() {
        let i: usize = c.name.as_ref().unwrap()["em_v".len()..].parse().unwrap();
        match module.global_expressions[c.init] {
            naga::Expression::Literal(naga::Literal::F32(got)) => {
                assert_eq!(
                    got.to_bits(),
                    values[i].to_bits(),
                    "{} reads back as {got}",
                    f32_literal(values[i]).unwrap()
                );
                checked += 1;
            }
            ref other => panic!("constant {i} is not folded to a literal: {other:?}"),
        }
    }
    assert_eq!(checked, values.len());
}

#[test]
fn every_example_level_emits_a_valid_module() {
    for (name, graph, bounds) in example_levels() {
        let emitter = TerrainEmitter::new(&graph);
        let full = emit_and_validate(&name, &emitter, None);
        let culled = emit_and_validate(&format!("{name} culled"), &emitter, Some(bounds));
        assert!(full.contains("fn base_sample(p: vec2<f32>) -> vec4<f32>"));
        assert!(culled.len() <= full.len());
    }
}

#[test]
fn the_every_variant_graph_emits_a_valid_module() {
    let graph = every_variant_graph();
    let emitter = TerrainEmitter::new(&graph);
    let text = emit_and_validate("every variant", &emitter, None);
    // Every primitive and operator family shows up in the text.
    for needle in [
        "em_circle(",
        "em_aabox(",
        "em_obox(",
        "em_capsule(",
        "em_poly",
        "em_ellipse(",
        "em_ring(",
        "em_arc(",
        "em_hp",
        "em_smin(",
        "em_smax(",
        "em_noise(",
        "em_wave(",
        "em_rep",
        "em_sqrt(",
        "em_mul(",
    ] {
        assert!(
            text.contains(needle),
            "no {needle} in the every-variant module"
        );
    }
    emit_and_validate(
        "every variant culled",
        &emitter,
        Some(Aabb::new(Vec2::new(-200.0, 0.0), Vec2::new(0.0, 200.0))),
    );
}

#[test]
fn the_prospero_expression_emits_a_valid_module() {
    let Some(graph) = prospero_graph() else {
        return;
    };
    let emitter = TerrainEmitter::new(&graph);
    let started = std::time::Instant::now();
    let text = emit_and_validate("prospero", &emitter, None);
    let elapsed = started.elapsed();
    // Node values are `let dN = ...`; n-ary unions add one `let dN_i` per fold step.
    let mut names: Vec<&str> = text
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("let d"))
        .filter_map(|l| l.split(' ').next())
        .collect();
    let lets = names.len();
    let node_lets = names.iter().filter(|n| !n.contains('_')).count();
    println!(
        "prospero: {} nodes, {lets} lets ({node_lets} node values), {} bytes of WGSL, \
         emitted and validated in {elapsed:.2?}",
        graph.node_count(),
        text.len(),
    );
    names.sort_unstable();
    names.dedup();
    // One `let` per node: the DAG's shared values are computed once, not per use.
    assert_eq!(names.len(), lets, "a value is defined twice");
    assert_eq!(node_lets, graph.node_count());
    assert!(text.len() < 64 * lets, "{} bytes", text.len());
}

#[test]
fn emission_is_deterministic() {
    for (name, graph, bounds) in example_levels() {
        let a = TerrainEmitter::new(&graph);
        let b = TerrainEmitter::new(&graph.clone());
        assert_eq!(a.fingerprint(), b.fingerprint(), "{name}");
        let (pa, pb) = (a.plan(Some(bounds), 32.0), b.plan(Some(bounds), 32.0));
        assert_eq!(pa.key, pb.key, "{name}");
        assert_eq!(a.emit(&pa), b.emit(&pb), "{name}");
        assert_eq!(a.emit(&pa), a.emit(&pa), "{name}");
    }
    let fingerprints: Vec<u64> = example_levels()
        .iter()
        .map(|(_, g, _)| TerrainEmitter::new(g).fingerprint())
        .collect();
    assert_ne!(fingerprints[0], fingerprints[1]);
    assert_ne!(fingerprints[1], fingerprints[2]);
}

// ---- snapshots ------------------------------------------------------------------------

fn snapshot_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders/emitted")
}

/// Compare `text` with the committed snapshot, or rewrite it when asked to.
fn check_snapshot(file: &str, text: &str) {
    let path = snapshot_dir().join(file);
    if std::env::var("CRATERFIELD_UPDATE_SNAPSHOTS").as_deref() == Ok("1") {
        std::fs::create_dir_all(snapshot_dir()).unwrap();
        std::fs::write(&path, text).unwrap();
        println!("updated snapshot {}", path.display());
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "no snapshot {} ({e}); run with CRATERFIELD_UPDATE_SNAPSHOTS=1 to write it",
            path.display()
        )
    });
    if committed != text {
        let line = committed
            .lines()
            .zip(text.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| committed.lines().count().min(text.lines().count()));
        panic!(
            "emitted WGSL differs from the snapshot {} (first at line {}: {:?} now {:?}); \
             if the change is intended, run `CRATERFIELD_UPDATE_SNAPSHOTS=1 cargo test -p \
             craterfield --test emit_wgsl snapshots` and review the diff",
            path.display(),
            line + 1,
            committed.lines().nth(line).unwrap_or("<end>"),
            text.lines().nth(line).unwrap_or("<end>")
        );
    }
}

#[test]
fn snapshots_of_the_example_levels_match() {
    for (name, graph, _) in example_levels() {
        let emitter = TerrainEmitter::new(&graph);
        check_snapshot(
            &format!("{name}.wgsl"),
            &emitter.emit(&emitter.plan(None, 32.0)),
        );
        if name == "default" {
            let view = Aabb::new(Vec2::ZERO, Vec2::new(1920.0, 1080.0));
            let plan = emitter.plan(Some(view), 32.0);
            assert!(
                plan.culled > 0,
                "the 1080p view culls part of the default level"
            );
            check_snapshot("default_view_1920x1080.wgsl", &emitter.emit(&plan));
        }
    }
}

// ---- culling --------------------------------------------------------------------------

fn island_view(x: f32) -> Aabb {
    Aabb::new(Vec2::new(x - 200.0, 400.0), Vec2::new(x + 200.0, 650.0))
}

#[test]
fn views_over_different_islands_get_different_keys_and_fewer_nodes() {
    let graph = islands_graph();
    let emitter = TerrainEmitter::new(&graph);
    let all = emitter.plan(None, 32.0);
    assert_eq!(all.culled, 0);
    assert_eq!(all.kept, graph.node_count());
    let mut keys = Vec::new();
    for i in 0..4 {
        let plan = emitter.plan(Some(island_view(500.0 + 1000.0 * i as f32)), 32.0);
        assert!(
            plan.kept < all.kept,
            "island {i}: kept {} of {}",
            plan.kept,
            all.kept
        );
        assert_eq!(plan.kept + plan.culled, all.kept);
        // The other three islands go, with everything under them.
        assert_eq!(plan.culled_children(&graph).len(), 3, "island {i}");
        let text = emitter.emit(&plan);
        validate(&format!("island {i}"), &text);
        assert!(text.len() < emitter.emit(&all).len());
        keys.push(plan.key);
    }
    keys.push(all.key);
    let mut unique = keys.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), keys.len(), "keys {keys:x?}");
}

#[test]
fn panning_within_the_same_visible_set_keeps_the_key() {
    let graph = islands_graph();
    let emitter = TerrainEmitter::new(&graph);
    let base = emitter.plan(Some(island_view(500.0)), 32.0);
    for (dx, dy) in [(3.0, 2.0), (-40.0, 10.0), (60.0, -25.0)] {
        let moved = island_view(500.0);
        let view = Aabb::new(moved.min + Vec2::new(dx, dy), moved.max + Vec2::new(dx, dy));
        let plan = emitter.plan(Some(view), 32.0);
        assert_eq!(plan.key, base.key, "pan by ({dx}, {dy})");
        assert_eq!(emitter.emit(&plan), emitter.emit(&base));
    }
    // Panning until the next island is within the band changes the visible set.
    let wide = Aabb::new(Vec2::new(300.0, 400.0), Vec2::new(1320.0, 650.0));
    assert_ne!(emitter.plan(Some(wide), 32.0).key, base.key);
}

#[test]
fn culled_children_are_beyond_the_band_at_every_view_point() {
    let graph = islands_graph();
    let emitter = TerrainEmitter::new(&graph);
    let band = 32.0;
    let mut rng = Rng(11);
    let mut checked = 0;
    for x in [500.0, 1500.0, 2500.0, 3500.0] {
        let view = island_view(x);
        let plan = emitter.plan(Some(view), band);
        for culled in plan.culled_children(&graph) {
            let info = graph.info(culled.child).unwrap();
            let margin = band * info.lipschitz.max(1.0);
            for _ in 0..500 {
                let p = rng.point_in(&view);
                let value = graph.node_distance(culled.child, p);
                let gap = (p - p.clamp(info.bounds.min, info.bounds.max)).length();
                // What culling relies on: the box is beyond the margin, and the child's value
                // there is above the band, so min(kept, child) clamps to the same value.
                assert!(gap > margin, "{culled:?} at {p}: box {gap} from the point");
                assert!(value > band, "{culled:?} at {p}: value {value}");
                checked += 1;
            }
        }
    }
    assert!(checked >= 4 * 3 * 500, "{checked} checks");
}

#[test]
fn a_view_over_nothing_culls_everything_to_the_far_constant() {
    let graph = islands_graph();
    let emitter = TerrainEmitter::new(&graph);
    let plan = emitter.plan(Some(Aabb::new(Vec2::ZERO, Vec2::new(200.0, 100.0))), 32.0);
    assert_eq!(plan.fate(graph.root()), Some(&Fate::Far));
    assert_eq!(plan.far_nodes(), vec![graph.root()]);
    assert_eq!(plan.kept, 1);
    let text = emitter.emit(&plan);
    validate("nothing", &text);
    assert!(text.contains("em_far"));
}

#[test]
fn unusable_views_and_bands_keep_everything() {
    let graph = islands_graph();
    let emitter = TerrainEmitter::new(&graph);
    let all = emitter.plan(None, 32.0);
    let nan = Aabb::new(Vec2::new(f32::NAN, 0.0), Vec2::new(10.0, 10.0));
    let inverted = Aabb::new(Vec2::new(10.0, 10.0), Vec2::ZERO);
    let view = island_view(500.0);
    for (what, plan) in [
        ("NaN view", emitter.plan(Some(nan), 32.0)),
        ("empty view", emitter.plan(Some(inverted), 32.0)),
        ("infinite view", emitter.plan(Some(Aabb::EVERYTHING), 32.0)),
        ("NaN band", emitter.plan(Some(view), f32::NAN)),
        ("negative band", emitter.plan(Some(view), -1.0)),
        ("infinite band", emitter.plan(Some(view), f32::INFINITY)),
    ] {
        assert_eq!(plan.key, all.key, "{what}");
        assert_eq!(plan.culled, 0, "{what}");
    }
}

#[test]
fn a_plan_from_another_graph_is_not_applied() {
    let islands = TerrainEmitter::new(&islands_graph());
    let every = TerrainEmitter::new(&every_variant_graph());
    let foreign = islands.plan(Some(island_view(500.0)), 32.0);
    let own = every.plan(None, 32.0);
    assert_eq!(every.emit(&foreign), every.emit(&own));
}

#[test]
fn culled_children_of_the_default_level_are_above_the_band_in_the_view() {
    // Its unions all sit in the world frame, so children are evaluated at world points.
    let (_, graph, _) = example_levels().remove(0);
    let emitter = TerrainEmitter::new(&graph);
    let view = Aabb::new(Vec2::ZERO, Vec2::new(1920.0, 1080.0));
    let plan = emitter.plan(Some(view), 32.0);
    let mut rng = Rng(5);
    for culled in plan.culled_children(&graph) {
        for _ in 0..300 {
            let p = rng.point_in(&view);
            let v = graph.node_distance(culled.child, p);
            assert!(v > 32.0, "{culled:?} at {p}: {v}");
        }
    }
}

// ---- cache ------------------------------------------------------------------------------

#[cfg(feature = "gpu")]
#[test]
fn the_cache_hits_on_an_unchanged_key_and_misses_on_a_change() {
    let graph = islands_graph();
    let emitter = TerrainEmitter::new(&graph);
    let mut cache: PipelineCache<String> = PipelineCache::new(4);
    let mut compiles = 0;
    let mut frame = |x: f32, cache: &mut PipelineCache<String>| {
        let plan = emitter.plan(Some(island_view(x)), 32.0);
        let (text, hit) = cache.get_or_insert_with(plan.key, || {
            compiles += 1;
            emitter.emit(&plan)
        });
        assert!(text.contains("base_sample"));
        hit
    };
    assert!(!frame(500.0, &mut cache));
    assert!(frame(505.0, &mut cache), "a small pan hits");
    assert!(frame(510.0, &mut cache));
    assert!(!frame(1500.0, &mut cache), "another island misses");
    assert!(frame(500.0, &mut cache), "coming back hits");
    assert_eq!((cache.hits(), cache.misses(), cache.len()), (3, 2, 2));
    assert_eq!(compiles, 2);
}

#[cfg(feature = "gpu")]
#[test]
fn the_cache_evicts_the_least_recently_used_beyond_its_capacity() {
    let mut cache: PipelineCache<u64> = PipelineCache::new(3);
    for key in 0..3 {
        cache.get_or_insert_with(key, || key * 10);
    }
    // Touch 0 so that 1 is now the oldest.
    assert_eq!(cache.get_or_insert_with(0, || unreachable!()), (&0, true));
    cache.get_or_insert_with(3, || 30);
    assert_eq!(cache.len(), 3);
    assert!(
        cache.peek(1).is_none(),
        "the least recently used is evicted"
    );
    assert_eq!(cache.peek(0), Some(&0));
    for key in 100..1100 {
        cache.get_or_insert_with(key, || key);
        assert!(cache.len() <= 3);
    }
    assert_eq!(cache.misses(), 4 + 1000);
    assert_eq!(cache.hits(), 1);
    let failed: Result<_, String> =
        cache.get_or_try_insert_with(7, || Err("driver says no".into()));
    assert_eq!(failed.unwrap_err(), "driver says no");
    assert!(cache.peek(7).is_none());
}

#[test]
fn graphs_with_the_same_content_share_a_fingerprint() {
    let a: Graph = islands_graph();
    let b: Graph = islands_graph();
    assert_eq!(
        TerrainEmitter::new(&a).fingerprint(),
        TerrainEmitter::new(&b).fingerprint()
    );
    assert_ne!(
        TerrainEmitter::new(&a).fingerprint(),
        TerrainEmitter::new(&every_variant_graph()).fingerprint()
    );
}

/// A chain of `depth` named nodes, each the union of `fanout` copies of the next one at
/// moved points (each copy a call of the next node's context): shared in the text, but
/// `fanout^depth` copies once a GPU compiler inlines the calls.
fn dag_level(fanout: usize, depth: usize) -> craterfield::field2d::Graph {
    let mut nodes = String::new();
    for i in 0..depth {
        let copies: Vec<String> = (0..fanout)
            .map(|k| {
                format!(
                    "Translate(offset: ({}.0, 0.0), node: Ref(\"n{}\"))",
                    k,
                    i + 1
                )
            })
            .collect();
        nodes += &format!("\"n{i}\": Union([{}]),\n", copies.join(", "));
    }
    nodes += &format!("\"n{depth}\": Circle(center: (500.0, 500.0), radius: 20.0),\n");
    let text = format!(
        "Level(name: \"dag\", bounds: (min: (0.0, 0.0), max: (1024.0, 1024.0)),\n\
         materials: [(name: \"soil\", color: (1, 2, 3))], root: Ref(\"n0\"), nodes: {{\n{nodes}}})"
    );
    graph_past_the_cost_limit(&text)
}

/// The level's graph compiled without the evaluation-cost limit: a level loader refuses
/// these (their tapes cost too much), so the emitter's own budget is the last line here, as
/// it is for a caller that raises `GraphLimits::max_eval_work`.
fn graph_past_the_cost_limit(text: &str) -> craterfield::field2d::Graph {
    let file: craterfield::field2d::LevelFile = ron::from_str(text).unwrap();
    let limits = craterfield::field2d::GraphLimits {
        max_eval_work: u64::MAX,
        ..Default::default()
    };
    craterfield::field2d::Graph::compile_with_limits(&file.root, &file.nodes, limits).unwrap()
}

/// What the emitter hands a driver is bounded: DAG levels of several fan-outs and depths
/// that compile (within every level limit but the tape's cost) are refused once their
/// inlined size passes the budget, and so is a union too wide for the text budget; the
/// ones within it emit valid WGSL with an inlined size that matches the copies.
#[test]
fn shaders_past_the_budget_are_refused_before_a_driver_sees_them() {
    use craterfield::emit::{EmitError, ShaderBudget};
    let budget = ShaderBudget::default();
    for (fanout, depth, fits) in [
        (2, 6, true),
        (3, 4, true),
        (2, 15, false),
        (3, 9, false),
        (8, 5, false),
    ] {
        let graph = dag_level(fanout, depth);
        let emitter = TerrainEmitter::new(&graph);
        let plan = emitter.plan(None, 32.0);
        let inlined = emitter.inlined_statements(&plan);
        let copies = (fanout as u64).pow(depth as u32);
        assert!(inlined >= copies, "{fanout}^{depth}: {inlined} statements");
        match emitter.emit_within(&plan, &budget) {
            Ok(text) => {
                assert!(fits, "{fanout}^{depth} should be refused");
                validate(&format!("dag {fanout}^{depth}"), &text);
            }
            Err(EmitError::TooLarge { what, .. }) => {
                assert!(!fits, "{fanout}^{depth} should fit");
                assert_eq!(what, "inlined statements");
            }
        }
    }
    // 15,000 children of one union: within every level limit but the tape's cost, 1.5 MB
    // of text.
    let children: Vec<String> = (0..15_000)
        .map(|i| {
            format!(
                "Circle(center: ({}.0, {}.0), radius: 3.0)",
                i % 1000,
                i / 1000 * 60
            )
        })
        .collect();
    let text = format!(
        "Level(name: \"wide\", bounds: (min: (0.0, 0.0), max: (1024.0, 1024.0)),\n\
         materials: [(name: \"soil\", color: (1, 2, 3))], root: Union([{}]))",
        children.join(", ")
    );
    let graph = graph_past_the_cost_limit(&text);
    let emitter = TerrainEmitter::new(&graph);
    let e = emitter
        .emit_within(&emitter.plan(None, 32.0), &budget)
        .unwrap_err();
    assert!(
        matches!(
            e,
            EmitError::TooLarge {
                what: "text bytes",
                ..
            }
        ),
        "{e}"
    );
    // Every shipped level is far inside the budget.
    let prospero = prospero_graph().map(|g| ("prospero".to_string(), g));
    let levels = example_levels()
        .into_iter()
        .map(|(name, graph, _)| (name, graph));
    for (name, graph) in levels.chain(prospero) {
        let emitter = TerrainEmitter::new(&graph);
        let plan = emitter.plan(None, 32.0);
        eprintln!(
            "{name}: {} inlined statements, {} bytes",
            emitter.inlined_statements(&plan),
            emitter.emit(&plan).len()
        );

        emitter.emit_within(&plan, &budget).unwrap();
    }
}
