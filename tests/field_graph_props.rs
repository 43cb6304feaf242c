//! Properties of every node: analytic gradients match finite differences, exact nodes have
//! unit gradients, Lipschitz bounds hold on random point pairs, and the distance-only and
//! distance+gradient paths agree bit for bit. Run on the default level's nodes and on random
//! graphs.

use std::collections::BTreeMap;

use craterfield::field2d::{Exactness, Graph, Level, Node, NodeId};
use glam::Vec2;
use proptest::prelude::*;

fn arb_point(r: f32) -> impl Strategy<Value = [f32; 2]> {
    [-r..r, -r..r]
}

fn arb_leaf() -> impl Strategy<Value = Node> {
    prop_oneof![
        (arb_point(20.0), 0.5f32..15.0)
            .prop_map(|(center, radius)| Node::Circle { center, radius }),
        (arb_point(20.0), [0.5f32..10.0, 0.5f32..10.0])
            .prop_map(|(center, half_size)| Node::Box { center, half_size }),
        (arb_point(20.0), [1.0f32..10.0, 1.0f32..10.0], 0.0f32..1.0).prop_map(
            |(center, half_size, r)| Node::RoundedBox {
                center,
                half_size,
                radius: r
            }
        ),
        (arb_point(20.0), arb_point(20.0), 0.2f32..6.0)
            .prop_map(|(a, b, thickness)| Node::OrientedBox { a, b, thickness }),
        (arb_point(20.0), arb_point(20.0), 0.2f32..6.0).prop_map(|(a, b, radius)| Node::Capsule {
            a,
            b,
            radius
        }),
        (arb_point(20.0), arb_point(20.0), arb_point(20.0)).prop_map(|(a, b, c)| Node::Triangle {
            a,
            b,
            c
        }),
        (arb_point(20.0), [1.0f32..12.0, 1.0f32..12.0])
            .prop_map(|(center, radii)| Node::Ellipse { center, radii }),
        (arb_point(20.0), 1.0f32..12.0, 0.2f32..4.0).prop_map(|(center, radius, width)| {
            Node::Ring {
                center,
                radius,
                width,
            }
        }),
        (
            arb_point(20.0),
            1.0f32..12.0,
            0.2f32..4.0,
            5.0f32..180.0,
            -180.0f32..180.0
        )
            .prop_map(|(center, radius, width, aperture, rotation)| Node::Arc {
                center,
                radius,
                width,
                aperture,
                rotation
            }),
        (arb_point(20.0), arb_point(1.0))
            .prop_map(|(point, normal)| Node::HalfPlane { point, normal }),
        (
            -20.0f32..0.0,
            0.5f32..5.0,
            proptest::collection::vec(-10.0f32..10.0, 2..12)
        )
            .prop_map(|(x0, dx, heights)| Node::HeightProfile { x0, dx, heights }),
    ]
}

fn arb_graph() -> impl Strategy<Value = Node> {
    arb_leaf().prop_recursive(5, 40, 4, |inner| {
        let b = move || inner.clone().prop_map(Box::new);
        prop_oneof![
            proptest::collection::vec(b().prop_map(|n| *n), 1..4).prop_map(Node::Union),
            proptest::collection::vec(b().prop_map(|n| *n), 1..3).prop_map(Node::Intersection),
            (b(), b()).prop_map(|(base, cut)| Node::Subtract { base, cut }),
            (
                0.5f32..5.0,
                proptest::collection::vec(b().prop_map(|n| *n), 1..3)
            )
                .prop_map(|(k, nodes)| Node::SmoothUnion { k, nodes }),
            (
                0.5f32..5.0,
                proptest::collection::vec(b().prop_map(|n| *n), 1..3)
            )
                .prop_map(|(k, nodes)| Node::SmoothIntersection { k, nodes }),
            (0.5f32..5.0, b(), b()).prop_map(|(k, base, cut)| Node::SmoothSubtract {
                k,
                base,
                cut
            }),
            (0.0f32..3.0, b()).prop_map(|(radius, node)| Node::Round { radius, node }),
            (0.1f32..2.0, b()).prop_map(|(width, node)| Node::Onion { width, node }),
            (arb_point(10.0), b()).prop_map(|(offset, node)| Node::Translate { offset, node }),
            (-360.0f32..360.0, b()).prop_map(|(degrees, node)| Node::Rotate { degrees, node }),
            (0.25f32..4.0, b()).prop_map(|(factor, node)| Node::Scale { factor, node }),
            (
                prop_oneof![
                    Just(craterfield::field2d::Axis::X),
                    Just(craterfield::field2d::Axis::Y)
                ],
                -5.0f32..5.0,
                b()
            )
                .prop_map(|(axis, at, node)| Node::Mirror { axis, at, node }),
            (0.0f32..3.0, 2.0f32..20.0, any::<u32>(), b()).prop_map(
                |(amplitude, wavelength, seed, node)| Node::DisplaceNoise {
                    amplitude,
                    wavelength,
                    seed,
                    node
                }
            ),
            (0.0f32..2.0, 3.0f32..30.0, -180.0f32..180.0, b()).prop_map(
                |(amplitude, wavelength, direction, node)| Node::DisplaceWave {
                    amplitude,
                    wavelength,
                    direction,
                    phase: 0.0,
                    node
                }
            ),
            // Repetition needs the child to fit a period: a small circle in a big period.
            (0.5f32..3.0, 8.0f32..20.0, 1u32..5).prop_map(|(r, period, n)| Node::RepeatFinite {
                period: [period, 0.0],
                count: [n, 1],
                node: Box::new(Node::Circle {
                    center: [0.0, 0.0],
                    radius: r
                }),
            }),
            (0.5f32..3.0, 8.0f32..20.0).prop_map(|(r, period)| Node::Repeat {
                period: [period, period],
                node: Box::new(Node::Capsule {
                    a: [-1.0, 0.0],
                    b: [1.0, 1.0],
                    radius: r
                }),
            }),
        ]
    })
}

/// Central difference gradient, where the field is smooth enough around `p` for it to mean
/// something: two step sizes must agree, and so must the one-sided differences on either
/// side of `p` (within `kink`). A kink at `p` itself passes the first test (every central
/// difference straddling it gives the mean of the slopes on its two sides) but not the
/// second.
fn finite_difference(f: impl Fn(Vec2) -> f32, p: Vec2, h: f32, kink: f32) -> Option<Vec2> {
    let at = |q: Vec2| f(q) as f64;
    let grad = |h: f32| {
        let dx = (at(p + Vec2::X * h) - at(p - Vec2::X * h)) / (2.0 * h as f64);
        let dy = (at(p + Vec2::Y * h) - at(p - Vec2::Y * h)) / (2.0 * h as f64);
        Vec2::new(dx as f32, dy as f32)
    };
    let one_sided = |h: f32| {
        let dx = (at(p + Vec2::X * h) - at(p)) / h as f64;
        let dy = (at(p + Vec2::Y * h) - at(p)) / h as f64;
        Vec2::new(dx as f32, dy as f32)
    };
    let (a, b) = (grad(h), grad(h * 0.5));
    let (ahead, behind) = (one_sided(h * 0.5), one_sided(-h * 0.5));
    ((a - b).length() < 2e-3 && (ahead - behind).length() < kink).then_some(b)
}

/// Checks one node; returns how many points had a finite-difference gradient to compare.
fn check_node(
    g: &Graph,
    id: NodeId,
    points: &[Vec2],
    pairs: &[(Vec2, Vec2)],
    h: f32,
) -> Result<usize, TestCaseError> {
    let info = *g.info(id).unwrap();
    let tolerance = 1e-2 * (1.0 + info.lipschitz);
    let mut checked = 0;
    for &p in points {
        let s = g.node_sample(id, p);
        let d = g.node_distance(id, p);
        prop_assert_eq!(
            s.distance.to_bits(),
            d.to_bits(),
            "sample and distance differ at {}",
            p
        );
        if d.abs() > 1e5 {
            continue;
        }
        if let Some(fd) = finite_difference(|q| g.node_distance(id, q), p, h, tolerance) {
            checked += 1;
            prop_assert!(
                (fd - s.gradient).length() < tolerance,
                "gradient {} vs differences {} at {}",
                s.gradient,
                fd,
                p
            );
            if info.exactness == Exactness::Exact && s.gradient != Vec2::ZERO {
                prop_assert!(
                    (s.gradient.length() - 1.0).abs() < 1e-3,
                    "|grad| = {} at {}",
                    s.gradient.length(),
                    p
                );
            }
        }
    }
    for &(a, b) in pairs {
        let (da, db) = (g.node_distance(id, a) as f64, g.node_distance(id, b) as f64);
        let bound = info.lipschitz as f64 * a.distance(b) as f64;
        prop_assert!(
            (da - db).abs() <= bound * (1.0 + 1e-4) + 2e-3,
            "Lipschitz {} violated: {} vs {} over {}",
            info.lipschitz,
            da,
            db,
            a.distance(b)
        );
    }
    Ok(checked)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, ..ProptestConfig::default() })]

    #[test]
    fn random_graphs_have_consistent_gradients_and_lipschitz_bounds(
        node in arb_graph(),
        points in proptest::collection::vec(arb_point(40.0), 24),
        pairs in proptest::collection::vec((arb_point(40.0), arb_point(40.0), 0.001f32..3.0), 24),
    ) {
        // Random triangles can be degenerate; the compiler rejects those (tested elsewhere).
        let Ok(g) = Graph::compile(&node, &BTreeMap::new()) else { return Ok(()) };
        let points: Vec<Vec2> = points.into_iter().map(Vec2::from).collect();
        let pairs: Vec<(Vec2, Vec2)> = pairs.into_iter().map(|(a, b, t)| {
            let a = Vec2::from(a);
            (a, a + (Vec2::from(b) - a).normalize_or_zero() * t)
        }).chain(points.iter().zip(points.iter().skip(1)).map(|(&a, &b)| (a, b))).collect();
        for id in g.node_ids() {
            check_node(&g, id, &points, &pairs, 0.02)?;
        }
    }
}

#[test]
fn default_level_nodes_have_consistent_gradients_and_lipschitz_bounds() {
    let level = Level::default_level();
    let g = level.graph();
    let b = level.bounds();
    let mut seed = 12345u64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut point = || b.min + (b.max - b.min) * Vec2::new(rnd(), rnd());
    let points: Vec<Vec2> = (0..300).map(|_| point()).collect();
    let pairs: Vec<(Vec2, Vec2)> = points
        .iter()
        .map(|&a| (a, a + Vec2::new(0.37, -0.81) * 2.5))
        .chain(points.windows(2).map(|w| (w[0], w[1])))
        .collect();
    let mut checked = 0;
    for id in g.node_ids() {
        // World-scale coordinates: a larger step keeps rounding out of the differences.
        checked += check_node(g, id, &points, &pairs, 0.25).unwrap();
    }
    // Most sample points are away from kinks, so most gradients were really compared.
    assert!(
        checked > g.node_count() * points.len() / 2,
        "only {checked} gradients compared"
    );
}

/// A repetition whose nearest copy is exactly as far as its cap (half the period) at the
/// point: the field has a kink there (the cap's flat side, the copy's slope on the other),
/// which central differences of any step average into half the copy's gradient.
#[test]
fn a_kink_at_the_point_is_not_compared() {
    let node = Node::Repeat {
        period: [15.95856, 15.95856],
        node: Box::new(Node::Capsule {
            a: [-1.0, 0.0],
            b: [1.0, 1.0],
            radius: 1.5399344,
        }),
    };
    let g = Graph::compile(&node, &BTreeMap::new()).unwrap();
    let p = Vec2::new(23.807491, 25.587177);
    for id in g.node_ids() {
        check_node(&g, id, &[p], &[], 0.02).unwrap();
    }
    let root = g.root();
    let f = |q: Vec2| g.node_distance(root, q);
    let cap = 15.95856f32 / 2.0;
    assert!(
        (f(p) - cap).abs() < 0.01,
        "the point is on the cap: {}",
        f(p)
    );
    assert!(finite_difference(f, p, 0.02, 1e-2).is_none());
}
