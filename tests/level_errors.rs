//! Bad level files: every error case is reported with a message that names the problem and
//! where it is, and no input makes the loader panic.

use std::collections::BTreeMap;

use craterfield::field2d::{Graph, GraphLimits, Level, LevelError, Node};
use proptest::prelude::*;

fn level_with(root: &str, extra: &str) -> String {
    format!(
        r#"Level(
    name: "t",
    bounds: (min: (0.0, 0.0), max: (1024.0, 512.0)),
    materials: [(name: "soil", color: (1, 2, 3))],
    root: {root},
    {extra}
)"#
    )
}

fn error_of(text: &str) -> String {
    match Level::from_ron(text) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn assert_mentions(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "message {msg:?} should mention {p:?}");
    }
}

#[test]
fn shipped_levels_are_valid() {
    let default = Level::default_level();
    assert_eq!(default.name(), "Default");
    for entry in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/levels")).unwrap() {
        let path = entry.unwrap().path();
        let level = Level::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(level.graph().node_count() > 3);
    }
}

#[test]
fn unknown_node_kind() {
    let msg = error_of(&level_with("Blob(radius: 3.0)", ""));
    assert_mentions(&msg, &["Blob"]);
}

#[test]
fn non_finite_and_negative_sizes() {
    let msg = error_of(&level_with("Circle(center: (1.0, 2.0), radius: NaN)", ""));
    assert_mentions(&msg, &["root.Circle.radius", "finite", "NaN"]);
    let msg = error_of(&level_with(
        "Union([Circle(radius: 1.0), Box(half_size: (inf, 1.0))])",
        "",
    ));
    assert_mentions(&msg, &["root.Union[1].Box.half_size.x", "finite"]);
    let msg = error_of(&level_with("Ring(radius: 5.0, width: -1.0)", ""));
    assert_mentions(&msg, &["root.Ring.width", "positive", "-1"]);
    let msg = error_of(&level_with("Circle(radius: 1e30)", ""));
    assert_mentions(&msg, &["root.Circle.radius", "absurdly large"]);
    let msg = error_of(&level_with(
        "RoundedBox(half_size: (2.0, 3.0), radius: 2.5)",
        "",
    ));
    assert_mentions(&msg, &["RoundedBox.radius", "larger than"]);
}

#[test]
fn degenerate_shapes() {
    let msg = error_of(&level_with(
        "Polygon(points: [(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)])",
        "",
    ));
    assert_mentions(&msg, &["root.Polygon.points", "zero area"]);
    let msg = error_of(&level_with(
        "Polygon(points: [(0.0, 0.0), (4.0, 4.0), (4.0, 0.0), (0.0, 4.0), (-1.0, 2.0)])",
        "",
    ));
    assert_mentions(&msg, &["root.Polygon.points", "not simple"]);
    let msg = error_of(&level_with("Polygon(points: [(0.0, 0.0), (1.0, 0.0)])", ""));
    assert_mentions(&msg, &["at least 3 vertices"]);
    let msg = error_of(&level_with(
        "Triangle(a: (1.0, 1.0), b: (1.0, 1.0), c: (3.0, 0.0))",
        "",
    ));
    assert_mentions(&msg, &["root.Triangle.points", "coincide"]);
    let msg = error_of(&level_with(
        "OrientedBox(a: (1.0, 1.0), b: (1.0, 1.0), thickness: 2.0)",
        "",
    ));
    assert_mentions(&msg, &["OrientedBox", "coincide"]);
    let msg = error_of(&level_with("HalfPlane(normal: (0.0, 0.0))", ""));
    assert_mentions(&msg, &["HalfPlane.normal", "zero vector"]);
    let msg = error_of(&level_with("Union([])", ""));
    assert_mentions(&msg, &["root.Union", "at least one child"]);
    let msg = error_of(&level_with(
        "Repeat(period: (4.0, 0.0), node: Circle(radius: 3.0))",
        "",
    ));
    assert_mentions(&msg, &["root.Repeat.node", "do not fit in one period"]);
}

#[test]
fn references_unknown_and_cyclic() {
    let msg = error_of(&level_with(
        r#"Ref("nowhere")"#,
        r#"nodes: { "a": Circle(radius: 1.0) },"#,
    ));
    assert_mentions(&msg, &["unknown node reference", "nowhere", "a"]);
    let msg = error_of(&level_with(
        r#"Ref("a")"#,
        r#"nodes: { "a": Union([Circle(radius: 1.0), Ref("b")]), "b": Translate(offset: (1.0, 0.0), node: Ref("a")) },"#,
    ));
    assert_mentions(
        &msg,
        &[
            "reference cycle",
            "a -> b -> a",
            "nodes[\"b\"].Translate.node",
        ],
    );
}

#[test]
fn depth_and_node_count_limits() {
    let mut root = String::from("Circle(radius: 1.0)");
    for _ in 0..100 {
        root = format!("Translate(offset: (1.0, 0.0), node: {root})");
    }
    // The RON parser's own recursion limit or the graph's depth limit: either is reported.
    let msg = error_of(&level_with(&root, ""));
    assert!(
        msg.contains("nesting depth") || msg.contains("recursion"),
        "{msg}"
    );

    let node = Node::Union(
        (0..50)
            .map(|i| Node::Circle {
                center: [i as f32, 0.0],
                radius: 1.0,
            })
            .collect(),
    );
    let limits = GraphLimits {
        max_nodes: 20,
        ..GraphLimits::default()
    };
    let err = Graph::compile_with_limits(&node, &BTreeMap::new(), limits).unwrap_err();
    assert_mentions(&err.to_string(), &["node count", "20"]);

    let nested = (0..6).fold(
        Node::Circle {
            center: [0.0, 0.0],
            radius: 1.0,
        },
        |n, _| Node::RepeatFinite {
            period: [10.0, 10.0],
            count: [1, 1],
            node: Box::new(n),
        },
    );
    let err = Graph::compile_with_limits(
        &nested,
        &BTreeMap::new(),
        GraphLimits {
            max_cost: 10_000,
            ..GraphLimits::default()
        },
    )
    .unwrap_err();
    assert_mentions(&err.to_string(), &["evaluation cost"]);
}

#[test]
fn absurd_bounds_cells_materials_spawns() {
    let bad_bounds =
        level_with("Circle(radius: 1.0)", "").replace("max: (1024.0, 512.0)", "max: (1e9, 512.0)");
    assert_mentions(&error_of(&bad_bounds), &["bounds.max.x", "65536"]);
    let flat =
        level_with("Circle(radius: 1.0)", "").replace("max: (1024.0, 512.0)", "max: (1024.0, 0.0)");
    assert_mentions(&error_of(&flat), &["bounds", "at least 16 units"]);
    let cells = level_with("Circle(radius: 1.0)", "cell_size: 0.5,");
    assert_mentions(&error_of(&cells), &["cell_size", "0.5"]);
    let mat = level_with("Material(id: 4, node: Circle(radius: 1.0))", "");
    assert_mentions(
        &error_of(&mat),
        &["root.Material.id", "material 4", "palette of 1"],
    );
    let spawn = level_with("Circle(radius: 1.0)", "spawns: [(5.0, 5.0), (-5.0, 5.0)],");
    assert_mentions(
        &error_of(&spawn),
        &["spawns[1]", "outside the world bounds"],
    );
    let no_materials = level_with("Circle(radius: 1.0)", "")
        .replace(r#"[(name: "soil", color: (1, 2, 3))]"#, "[]");
    assert_mentions(&error_of(&no_materials), &["materials", "1 ..= 256"]);
}

#[test]
fn oversized_input_is_refused_before_parsing() {
    let big = " ".repeat(craterfield::field2d::MAX_LEVEL_BYTES + 1);
    assert!(matches!(
        Level::from_ron(&big),
        Err(LevelError::TooLarge { .. })
    ));
    let missing = Level::load(std::path::Path::new("/nonexistent/level.ron")).unwrap_err();
    assert_mentions(&missing.to_string(), &["/nonexistent/level.ron"]);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// Truncated or corrupted level text gives an error or a level, never a panic.
    #[test]
    fn mangled_levels_never_panic(cut in 0usize..6000, flips in proptest::collection::vec((0usize..6000, any::<u8>()), 0..4)) {
        let mut bytes = craterfield::field2d::DEFAULT_LEVEL_RON.as_bytes().to_vec();
        bytes.truncate(cut.min(bytes.len()));
        for (i, b) in flips {
            if i < bytes.len() {
                bytes[i] = b;
            }
        }
        let text = String::from_utf8_lossy(&bytes);
        let _ = Level::from_ron(&text);
    }
}

#[test]
fn levels_whose_explosion_grid_would_be_too_big_are_refused() {
    let huge = level_with("Circle(radius: 1.0)", "cell_size: 8.0,")
        .replace("max: (1024.0, 512.0)", "max: (60000.0, 30000.0)");
    let msg = error_of(&huge);
    assert!(msg.starts_with("cell_size:"), "{msg}");
}

/// A misspelt field anywhere in a level (top level, bounds, a material, a node of any
/// kind) is an error that names the field and its line, never a silent default.
#[test]
fn unknown_fields_are_errors_that_name_the_line() {
    let cases = [
        (
            level_with("Circle(radius: 3.0)", "cell_sise: 4.0,"),
            "cell_sise",
            6,
        ),
        (
            level_with(
                "Union([Circle(radius: 3.0), Circle(radius: 2.0, centre: (1.0, 1.0))])",
                "",
            ),
            "centre",
            5,
        ),
        (
            level_with(
                "Translate(offset: (1.0, 0.0), node: Box(half_size: (1.0, 1.0), angel: 0.5))",
                "",
            ),
            "angel",
            5,
        ),
        (
            r#"Level(
    name: "t",
    bounds: (min: (0.0, 0.0), max: (1024.0, 512.0), maxx: (1.0, 1.0)),
    materials: [(name: "soil", color: (1, 2, 3))],
    root: Circle(radius: 3.0),
)"#
            .to_string(),
            "maxx",
            3,
        ),
        (
            r#"Level(
    name: "t",
    bounds: (min: (0.0, 0.0), max: (1024.0, 512.0)),
    materials: [(name: "soil", colour: (1, 2, 3))],
    root: Circle(radius: 3.0),
)"#
            .to_string(),
            "colour",
            4,
        ),
        (
            level_with(
                "Ref(\"a\")",
                "nodes: { \"a\": Circle(radius: 3.0, radios: 1.0) },",
            ),
            "radios",
            6,
        ),
    ];
    for (text, field, line) in cases {
        let msg = error_of(&text);
        assert_mentions(&msg, &[field, &format!("{line}:")]);
    }
}

/// A node name defined twice would keep only one definition: refused, naming the name
/// and the line.
#[test]
fn duplicate_node_names_are_errors() {
    let text = level_with(
        "Ref(\"hill\")",
        "nodes: {\n        \"hill\": Circle(radius: 3.0),\n        \"hill\": Circle(radius: 9.0),\n    },",
    );
    let msg = error_of(&text);
    assert_mentions(&msg, &["\"hill\"", "defined twice", "8:"]);
    // A field given twice in one node is refused the same way.
    let msg = error_of(&level_with("Circle(radius: 3.0, radius: 4.0)", ""));
    assert_mentions(&msg, &["duplicate field", "radius", "5:"]);
}

/// Parameters whose Lipschitz bound makes queries meaningless are refused wherever they
/// come from: a tiny noise or wave wavelength for its amplitude, a huge factor in an
/// expression, at the root or nested. Each names the node.
#[test]
fn parameters_that_make_queries_meaningless_are_refused() {
    for (root, path) in [
        (
            "DisplaceNoise(amplitude: 8.0, wavelength: 1e-30, node: Circle(radius: 50.0))",
            "root.DisplaceNoise",
        ),
        (
            "DisplaceNoise(amplitude: 1000.0, wavelength: 0.01, node: Circle(radius: 50.0))",
            "root.DisplaceNoise",
        ),
        (
            "DisplaceWave(amplitude: 100.0, wavelength: 1e-6, direction: 0.0, node: Circle(radius: 50.0))",
            "root.DisplaceWave",
        ),
        (
            "Union([Circle(radius: 5.0), Translate(offset: (1.0, 0.0), node: Mul(X, Const(1e8)))])",
            "root",
        ),
        ("Mul(X, Const(1e30))", "root"),
    ] {
        let msg = error_of(&level_with(root, ""));
        assert_mentions(&msg, &[path, "Lipschitz bound", "past the limit"]);
    }
    // Gentle ones compile.
    for root in [
        "DisplaceNoise(amplitude: 8.0, wavelength: 40.0, node: Circle(radius: 50.0))",
        "Mul(X, Const(3.0))",
    ] {
        Level::from_ron(&level_with(root, "")).unwrap();
    }
}
