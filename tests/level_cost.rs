//! What one evaluation of a level costs is known when it is loaded, and a level past the
//! budget (`GraphLimits::max_eval_work`) is refused there, with its cost and the limit named,
//! whatever shape the cost takes: wide sums, deep products, long polygons and height
//! profiles, stacked noise, imported expressions. Each of these shapes passed every other
//! limit (nodes, depth, node-cost estimate, points) and then made every query crawl.

use craterfield::field2d::import::Expression;
use craterfield::field2d::{GraphLimits, Level, LevelError, MAX_EVAL_WORK};

fn level_with(root: &str, nodes: &str) -> String {
    format!(
        r#"Level(
    name: "costly",
    bounds: (min: (0.0, 0.0), max: (1024.0, 512.0)),
    materials: [(name: "rock", color: (1, 2, 3))],
    root: {root},
    nodes: {{{nodes}}},
)"#
    )
}

/// A balanced binary tree of `op` over `leaves` (depth grows with the log of their count).
fn tree(op: &str, mut leaves: Vec<String>) -> String {
    while leaves.len() > 1 {
        leaves = leaves
            .chunks(2)
            .map(|pair| match pair {
                [a, b] => format!("{op}({a}, {b})"),
                [a] => a.clone(),
                _ => unreachable!(),
            })
            .collect();
    }
    leaves.pop().expect("at least one leaf")
}

/// The ground as the surface `y = 200 + scale * expr`, so the level has solid and air.
fn ground_plus(expr: &str) -> String {
    format!(
        "Intersection([HalfPlane(point: (0.0, 200.0), normal: (0.0, 1.0)), \
         Add(Sub(Y, Const(300.0)), Mul(Const(0.00001), {expr}))])"
    )
}

/// The terms `Mul(X, Const(c_i))`, named `t0..`, with `x` the shared query coordinate.
fn named_terms(count: usize) -> String {
    let mut nodes = String::from("\"x\": X");
    for i in 0..count {
        nodes += &format!(
            ",\n\"t{i}\": Mul(Ref(\"x\"), Const({}))",
            0.001 + i as f64 * 1e-6
        );
    }
    nodes
}

/// The cost a refusal names, after checking the message names it and the limit.
fn refused_cost(text: &str) -> u64 {
    let started = std::time::Instant::now();
    let result = Level::from_ron(text);
    let elapsed = started.elapsed();
    match result {
        Err(e @ LevelError::TooCostly { work, limit, .. }) => {
            let msg = e.to_string();
            println!("refused in {elapsed:.2?}: {msg}");
            assert_eq!(limit, MAX_EVAL_WORK);
            assert!(work > limit, "{msg}");
            for part in [work.to_string(), limit.to_string(), "max_eval_work".into()] {
                assert!(msg.contains(&part), "{msg:?} should name {part}");
            }
            work
        }
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(level) => panic!(
            "accepted, at {:?} per evaluation",
            level.graph().eval_cost()
        ),
    }
}

fn accepted_work(text: &str) -> u64 {
    let level = Level::from_ron(text).unwrap_or_else(|e| panic!("refused: {e}"));
    let cost = level.graph().eval_cost();
    assert!(cost.work <= MAX_EVAL_WORK);
    cost.work
}

/// The shape of the level that stalled the demo: an `Add` of 24,000 `Mul(X, Const)` term
/// uses, 6,000 distinct terms summed in 8 named blocks that the root adds 4 times over
/// (about 330 KB, 18,000 nodes: every other limit holds).
#[test]
fn a_wide_sum_of_24000_terms_is_refused_naming_its_cost() {
    let blocks: Vec<String> = (0..8)
        .map(|b| {
            let terms = (0..750)
                .map(|k| format!("Ref(\"t{}\")", b * 750 + k))
                .collect();
            format!(",\n\"b{b}\": {}", tree("Add", terms))
        })
        .collect();
    let uses = (0..4)
        .flat_map(|_| (0..8).map(|b| format!("Ref(\"b{b}\")")))
        .collect();
    let nodes = named_terms(6000) + &blocks.concat();
    let text = level_with(&ground_plus(&tree("Add", uses)), &nodes);
    println!("{} KB of level text", text.len() / 1024);
    let work = refused_cost(&text);
    // Every distinct term is two instructions (a product by an immediate, a sum): the cost
    // is the tape's, not the 24,000 uses of the tree.
    assert!((12_000..12_100).contains(&work), "{work}");
}

#[test]
fn wide_sums_cost_their_terms() {
    let sum = |n: usize| {
        let terms = (0..n).map(|i| format!("Ref(\"t{i}\")")).collect();
        level_with(&ground_plus(&tree("Add", terms)), &named_terms(n))
    };
    let small = accepted_work(&sum(1000));
    assert!((2000..2100).contains(&small), "{small}");
    refused_cost(&sum(5000));
}

#[test]
fn deep_products_are_refused() {
    // A product of 5,000 distinct factors `(x + c_i)`, thirteen levels deep.
    let factors = (0..5000)
        .map(|i| format!("Add(Ref(\"x\"), Const({}))", 1.0 + i as f64 * 1e-4))
        .collect();
    refused_cost(&level_with(&ground_plus(&tree("Mul", factors)), "\"x\": X"));
}

/// A star-shaped simple polygon of `n` vertices around (512, 256).
fn wavy_polygon(n: usize) -> String {
    let points: Vec<String> = (0..n)
        .map(|k| {
            let t = k as f64 / n as f64 * std::f64::consts::TAU;
            let r = 150.0 + 20.0 * (t * 40.0).sin();
            format!("({:.3}, {:.3})", 512.0 + r * t.cos(), 256.0 + r * t.sin())
        })
        .collect();
    format!("Polygon(points: [{}])", points.join(", "))
}

#[test]
fn long_polygons_cost_every_edge() {
    let small = accepted_work(&level_with(&wavy_polygon(2000), ""));
    assert!(small >= 2000, "{small}");
    let work = refused_cost(&level_with(&wavy_polygon(10_000), ""));
    assert!(work >= 10_000, "{work}");
}

#[test]
fn long_height_profiles_cost_every_segment() {
    let profile = |n: usize| {
        let heights: Vec<String> = (0..n)
            .map(|i| format!("{:.2}", 200.0 + 40.0 * (i as f64 * 0.01).sin()))
            .collect();
        format!(
            "HeightProfile(x0: 0.0, dx: {}, heights: [{}])",
            1024.0 / (n - 1) as f64,
            heights.join(", ")
        )
    };
    let small = accepted_work(&level_with(&profile(1500), ""));
    assert!(small >= 1500, "{small}");
    let work = refused_cost(&level_with(&profile(10_000), ""));
    assert!(work >= 10_000, "{work}");
}

#[test]
fn stacked_noise_is_refused() {
    // Noise displacements of many seeds over one circle each: octaves laid side by side.
    let noisy = |n: usize| {
        let parts: Vec<String> = (0..n)
            .map(|i| {
                format!(
                    "DisplaceNoise(amplitude: 4.0, wavelength: {}, seed: {i}, node: \
                     Circle(center: ({}, 200.0), radius: 30.0))",
                    20.0 + i as f64 * 0.01,
                    (i % 900) as f64 + 50.0
                )
            })
            .collect();
        level_with(&format!("Union([{}])", parts.join(", ")), "")
    };
    accepted_work(&noisy(100));
    refused_cost(&noisy(1000));
}

#[test]
fn imported_expressions_are_held_to_the_same_budget() {
    // prospero (7,866 operations) stays well inside.
    let prospero = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/prospero.vm"
    ))
    .expect("tests/data/prospero.vm");
    let graph = Expression::parse(&prospero).unwrap().graph().unwrap();
    let cost = graph.eval_cost();
    println!("prospero: {cost:?}");
    assert!(cost.work * 2 <= MAX_EVAL_WORK, "{cost:?}");
    // A sum of 6,000 products in the same text format, added pairwise (thirteen deep), is
    // refused, naming its cost.
    let mut text = String::from("_x var-x\n");
    let mut level: Vec<String> = (0..6000)
        .map(|i| {
            text += &format!(
                "_c{i} const {}\n_m{i} mul _x _c{i}\n",
                1.0 + i as f64 * 1e-4
            );
            format!("_m{i}")
        })
        .collect();
    let mut next = 0;
    while level.len() > 1 {
        level = level
            .chunks(2)
            .map(|pair| match pair {
                [a, b] => {
                    next += 1;
                    text += &format!("_s{next} add {a} {b}\n");
                    format!("_s{next}")
                }
                [a] => a.clone(),
                _ => unreachable!(),
            })
            .collect();
    }
    match Expression::parse(&text).unwrap().graph() {
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.contains("max_eval_work"), "{msg}");
        }
        Ok(g) => panic!("accepted at {:?}", g.eval_cost()),
    }
}

#[test]
fn the_budget_is_a_limit_callers_can_raise() {
    let terms = (0..5000).map(|i| format!("Ref(\"t{i}\")")).collect();
    let text = level_with(&ground_plus(&tree("Add", terms)), &named_terms(5000));
    refused_cost(&text);
    let parsed: craterfield::field2d::LevelFile = ron::from_str(&text).unwrap();
    let limits = GraphLimits {
        max_eval_work: 20_000,
        ..GraphLimits::default()
    };
    let graph =
        craterfield::field2d::Graph::compile_with_limits(&parsed.root, &parsed.nodes, limits)
            .unwrap();
    assert!(graph.eval_cost().work > MAX_EVAL_WORK);
}

#[test]
fn shipped_levels_cost_little() {
    for entry in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/levels")).unwrap() {
        let path = entry.unwrap().path();
        let level = Level::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let cost = level.graph().eval_cost();
        println!("{}: {cost:?}", path.display());
        assert!(cost.work * 16 <= MAX_EVAL_WORK, "{}", path.display());
    }
}
