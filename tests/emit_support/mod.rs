//! Graphs and checks shared by the shader emitter tests (`emit_wgsl`, `emit_gpu`).
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use craterfield::field2d::import::graph_from_vm;
use craterfield::field2d::{Aabb, Axis, Graph, Level, Node};
use glam::Vec2;

/// The example levels: (file stem, graph, world bounds).
pub(crate) fn example_levels() -> Vec<(String, Graph, Aabb)> {
    ["default", "caverns", "skyrealm"]
        .iter()
        .map(|name| {
            let path = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("levels")
                .join(format!("{name}.ron"));
            let level = Level::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            (name.to_string(), level.graph().clone(), level.bounds())
        })
        .collect()
}

/// Where the prospero expression is looked for: `CRATERFIELD_PROSPERO`, else the vendored copy
/// under `tests/data`.
pub(crate) fn prospero_path() -> PathBuf {
    std::env::var_os("CRATERFIELD_PROSPERO")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/prospero.vm"))
}

/// The prospero expression as a graph, or `None` (reported as skipped, an error under CI)
/// when the file is not there.
pub(crate) fn prospero_graph() -> Option<Graph> {
    let path = prospero_path();
    match std::fs::read_to_string(&path) {
        Ok(text) => Some(graph_from_vm(&text).expect("prospero.vm imports")),
        Err(e) => {
            assert!(
                std::env::var_os("CI").is_none(),
                "prospero.vm is required under CI: {}: {e}",
                path.display()
            );
            println!("SKIPPED: prospero.vm not found at {}: {e}", path.display());
            None
        }
    }
}

fn p(x: f32, y: f32) -> [f32; 2] {
    [x, y]
}

fn circle(x: f32, y: f32, r: f32) -> Node {
    Node::Circle {
        center: p(x, y),
        radius: r,
    }
}

fn rect(x: f32, y: f32, hx: f32, hy: f32) -> Node {
    Node::Box {
        center: p(x, y),
        half_size: p(hx, hy),
    }
}

fn paint(id: u16, node: Node) -> Node {
    Node::Material {
        id,
        node: Box::new(node),
    }
}

fn at(x: f32, y: f32, node: Node) -> Node {
    Node::Translate {
        offset: p(x, y),
        node: Box::new(node),
    }
}

/// The arithmetic circle `sqrt((x - cx)² + (y - cy)²) * 1 - r`, negated twice.
fn expression_circle(cx: f32, cy: f32, r: f32) -> Node {
    let dx = Node::Sub(Box::new(Node::X), Box::new(Node::Const(cx)));
    let dy = Node::Sub(Box::new(Node::Y), Box::new(Node::Const(cy)));
    let len = Node::Sqrt(Box::new(Node::Add(
        Box::new(Node::Square(Box::new(dx))),
        Box::new(Node::Square(Box::new(dy))),
    )));
    let scaled = Node::Mul(Box::new(Node::Const(1.0)), Box::new(len));
    Node::Neg(Box::new(Node::Neg(Box::new(Node::Sub(
        Box::new(scaled),
        Box::new(Node::Const(r)),
    )))))
}

/// Primitives, one per variant, laid out on a grid in [-200, 200]².
fn primitives() -> Vec<Node> {
    vec![
        paint(1, circle(-160.0, 160.0, 25.0)),
        rect(-100.0, 160.0, 20.0, 12.0),
        Node::RoundedBox {
            center: p(-40.0, 160.0),
            half_size: p(22.0, 15.0),
            radius: 5.0,
        },
        Node::OrientedBox {
            a: p(5.0, 140.0),
            b: p(45.0, 180.0),
            thickness: 10.0,
        },
        paint(
            2,
            Node::Capsule {
                a: p(70.0, 145.0),
                b: p(110.0, 175.0),
                radius: 8.0,
            },
        ),
        Node::Triangle {
            a: p(130.0, 140.0),
            b: p(175.0, 140.0),
            c: p(150.0, 185.0),
        },
        // Concave, clockwise.
        Node::Polygon {
            points: vec![
                p(-185.0, 60.0),
                p(-185.0, 100.0),
                p(-135.0, 100.0),
                p(-150.0, 80.0),
                p(-135.0, 60.0),
            ],
        },
        Node::Ellipse {
            center: p(-90.0, 80.0),
            radii: p(30.0, 12.0),
        },
        Node::Ring {
            center: p(-30.0, 80.0),
            radius: 20.0,
            width: 4.0,
        },
        Node::Arc {
            center: p(30.0, 75.0),
            radius: 22.0,
            width: 5.0,
            aperture: 60.0,
            rotation: 30.0,
        },
        Node::Intersection(vec![
            Node::HalfPlane {
                point: p(90.0, 80.0),
                normal: p(1.0, 1.0),
            },
            rect(90.0, 80.0, 22.0, 22.0),
        ]),
        Node::HeightProfile {
            x0: -120.0,
            dx: 20.0,
            heights: vec![
                -175.0, -160.0, -168.0, -150.0, -171.0, -158.0, -162.0, -149.0, -170.0, -166.0,
                -155.0, -172.0, -160.0,
            ],
        },
    ]
}

/// Booleans and shape operators.
fn operators() -> Vec<Node> {
    vec![
        paint(
            3,
            Node::Subtract {
                base: Box::new(rect(160.0, 80.0, 22.0, 22.0)),
                cut: Box::new(circle(170.0, 90.0, 11.0)),
            },
        ),
        Node::SmoothUnion {
            k: 10.0,
            nodes: vec![
                paint(1, circle(-170.0, 0.0, 15.0)),
                circle(-145.0, 0.0, 12.0),
                rect(-155.0, -18.0, 20.0, 5.0),
            ],
        },
        Node::SmoothIntersection {
            k: 8.0,
            nodes: vec![circle(-90.0, 0.0, 24.0), rect(-80.0, 0.0, 16.0, 26.0)],
        },
        Node::SmoothSubtract {
            k: 6.0,
            base: Box::new(rect(-30.0, 0.0, 20.0, 18.0)),
            cut: Box::new(circle(-20.0, 10.0, 10.0)),
        },
        Node::Round {
            radius: 4.0,
            node: Box::new(Node::Triangle {
                a: p(10.0, -15.0),
                b: p(45.0, -15.0),
                c: p(25.0, 20.0),
            }),
        },
        Node::Onion {
            width: 3.0,
            node: Box::new(circle(90.0, 0.0, 18.0)),
        },
        at(
            150.0,
            0.0,
            Node::Rotate {
                degrees: 30.0,
                node: Box::new(Node::Scale {
                    factor: 1.5,
                    node: Box::new(paint(2, rect(0.0, 0.0, 12.0, 6.0))),
                }),
            },
        ),
    ]
}

/// Domain repetition, mirrors, displacements, references and expressions.
fn domain_and_more() -> Vec<Node> {
    vec![
        Node::Mirror {
            axis: Axis::X,
            at: -140.0,
            node: Box::new(circle(-125.0, -70.0, 9.0)),
        },
        Node::Mirror {
            axis: Axis::Y,
            at: -70.0,
            node: Box::new(rect(-80.0, -58.0, 12.0, 5.0)),
        },
        // An infinite lattice of discs, cut to a box.
        Node::Intersection(vec![
            Node::Repeat {
                period: p(16.0, 16.0),
                node: Box::new(circle(0.0, 0.0, 5.0)),
            },
            rect(-20.0, -70.0, 25.0, 18.0),
        ]),
        at(
            40.0,
            -70.0,
            paint(
                1,
                Node::RepeatFinite {
                    period: p(22.0, 0.0),
                    count: [4, 1],
                    node: Box::new(circle(0.0, 0.0, 7.0)),
                },
            ),
        ),
        at(
            140.0,
            -90.0,
            Node::RepeatFinite {
                period: p(0.0, 14.0),
                count: [1, 3],
                node: Box::new(rect(0.0, 0.0, 9.0, 4.0)),
            },
        ),
        Node::DisplaceNoise {
            amplitude: 4.0,
            wavelength: 15.0,
            seed: 3,
            node: Box::new(circle(-160.0, -120.0, 20.0)),
        },
        Node::DisplaceWave {
            amplitude: 3.0,
            wavelength: 20.0,
            direction: 45.0,
            phase: 0.1,
            node: Box::new(rect(-95.0, -120.0, 28.0, 16.0)),
        },
        at(-30.0, -120.0, Node::Ref("gem".into())),
        at(10.0, -120.0, Node::Ref("gem".into())),
        paint(4, expression_circle(70.0, -120.0, 16.0)),
    ]
}

/// A graph with every `Node` variant (and `Triangle`, `Ref` resolved), materials 0-4.
pub(crate) fn every_variant_graph() -> Graph {
    let mut nodes = primitives();
    nodes.extend(operators());
    nodes.extend(domain_and_more());
    let named = BTreeMap::from([(
        "gem".to_string(),
        paint(
            2,
            Node::Rotate {
                degrees: 45.0,
                node: Box::new(rect(0.0, 0.0, 8.0, 8.0)),
            },
        ),
    )]);
    Graph::compile(&Node::Union(nodes), &named).expect("the every-variant graph compiles")
}

/// The region the every-variant graph is laid out in.
pub(crate) fn every_variant_bounds() -> Aabb {
    Aabb::new(Vec2::splat(-200.0), Vec2::splat(200.0))
}

/// Islands 1000 units apart along x, each a small union of its own.
pub(crate) fn islands_graph() -> Graph {
    let island = |x: f32, m: u16| {
        paint(
            m,
            Node::Union(vec![
                Node::Ellipse {
                    center: p(x, 500.0),
                    radii: p(160.0, 40.0),
                },
                circle(x - 60.0, 540.0, 30.0),
                Node::SmoothUnion {
                    k: 20.0,
                    nodes: vec![circle(x + 50.0, 545.0, 25.0), circle(x + 80.0, 540.0, 20.0)],
                },
            ]),
        )
    };
    let root = Node::Union(
        (0..4)
            .map(|i| island(500.0 + 1000.0 * i as f32, i))
            .collect(),
    );
    Graph::compile(&root, &BTreeMap::new()).expect("the islands compile")
}
