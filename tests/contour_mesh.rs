//! Contours and meshes of random and real fields: closed, non-crossing contours whose
//! enclosed area the mesh reproduces, deterministic, and no panics on odd options.
#![cfg(feature = "mesh")]

use std::collections::BTreeMap;

use craterfield::field2d::contour::{ContourOptions, Contours, extract_contours};
use craterfield::field2d::mesh::{mesh_contours, mesh_solid};
use craterfield::field2d::{Aabb, Graph, Level, Node, Sdf};
use glam::Vec2;
use proptest::prelude::*;

fn orient(a: Vec2, b: Vec2, c: Vec2) -> f64 {
    let (ax, ay) = (f64::from(a.x), f64::from(a.y));
    let (bx, by) = (f64::from(b.x), f64::from(b.y));
    let (cx, cy) = (f64::from(c.x), f64::from(c.y));
    (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
}

/// True when the closed segments `a`-`b` and `c`-`d` share a point.
fn segments_touch(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    let on = |p: Vec2, q: Vec2, r: Vec2, o: f64| {
        o == 0.0
            && r.x >= p.x.min(q.x)
            && r.x <= p.x.max(q.x)
            && r.y >= p.y.min(q.y)
            && r.y <= p.y.max(q.y)
    };
    on(a, b, c, o1) || on(a, b, d, o2) || on(c, d, a, o3) || on(c, d, b, o4)
}

/// Every pair of segments that are not neighbours along one loop is disjoint, and no point
/// repeats.
fn assert_simple(c: &Contours) {
    let segs: Vec<(usize, usize, Vec2, Vec2)> = c
        .loops
        .iter()
        .enumerate()
        .flat_map(|(li, l)| {
            let n = l.points.len();
            (0..n).map(move |i| (li, i, l.points[i], l.points[(i + 1) % n]))
        })
        .collect();
    for (x, &(la, ia, a, b)) in segs.iter().enumerate() {
        for &(lb, ib, p, q) in &segs[x + 1..] {
            if la == lb {
                let n = c.loops[la].points.len();
                if (ia + 1) % n == ib || (ib + 1) % n == ia {
                    continue;
                }
            }
            assert!(
                !segments_touch(a, b, p, q),
                "segments {a}-{b} (loop {la}) and {p}-{q} (loop {lb}) touch"
            );
        }
    }
}

fn circles(spec: &[(f32, f32, f32)], holes: &[(f32, f32, f32)]) -> Graph {
    let disc = |&(x, y, r): &(f32, f32, f32)| Node::Circle {
        center: [x, y],
        radius: r,
    };
    let base = Node::Union(spec.iter().map(disc).collect());
    let node = if holes.is_empty() {
        base
    } else {
        Node::Subtract {
            base: Box::new(base),
            cut: Box::new(Node::Union(holes.iter().map(disc).collect())),
        }
    };
    Graph::compile(&node, &BTreeMap::new()).expect("valid circles")
}

fn circle_strategy() -> impl Strategy<Value = (f32, f32, f32)> {
    (-14.0f32..14.0, -14.0f32..14.0, 0.3f32..7.0)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn random_blobs_contour_and_mesh_consistently(
        solids in prop::collection::vec(circle_strategy(), 1..5),
        holes in prop::collection::vec(circle_strategy(), 0..3),
        spacing in 0.4f32..2.0,
        refine in 0u32..4,
    ) {
        let g = circles(&solids, &holes);
        // The region cuts some blobs: they close along its edge.
        let region = Aabb::new(Vec2::new(-15.0, -12.0), Vec2::new(13.0, 15.0));
        let opts = ContourOptions { spacing, refine_iterations: refine, simplify_tolerance: 0.0 };
        let c = extract_contours(&g, region, &opts).unwrap();
        assert_simple(&c);
        for l in &c.loops {
            prop_assert!(l.points.len() >= 3);
            for p in &l.points {
                prop_assert!(region.contains(*p), "{} outside the region", p);
            }
        }
        let again = extract_contours(&g, region, &opts).unwrap();
        prop_assert_eq!(&c, &again);
        let m = mesh_contours(&c).unwrap();
        prop_assert_eq!(m.skipped_constraints, 0);
        let (ca, ma) = (c.area(), m.area());
        prop_assert!((ca - ma).abs() <= 1e-6 * ca.abs().max(1.0), "contours {} mesh {}", ca, ma);
        for i in 0..m.triangles.len() {
            let [a, b, t] = m.triangle(i).unwrap();
            prop_assert!(orient(a, b, t) > 0.0);
        }
        // Centroids are inside the field up to the contour's approximation error: a point
        // covered by the polygon lies in a cell with a solid corner, so within a cell
        // diagonal of solid (sharp concave corners between blobs are cut across).
        for p in m.centroids() {
            prop_assert!(g.distance(p) < std::f32::consts::SQRT_2 * spacing, "centroid {} at {}", p, g.distance(p));
        }
    }

    #[test]
    fn odd_options_never_panic(
        spacing in prop_oneof![Just(f32::NAN), Just(0.0f32), Just(-1.0f32), Just(f32::INFINITY), 1e-3f32..50.0],
        tol in prop_oneof![Just(f32::NAN), Just(-0.5f32), 0.0f32..3.0],
        refine in prop_oneof![Just(u32::MAX), 0u32..5],
        x0 in -20.0f32..20.0, y0 in -20.0f32..20.0, w in -5.0f32..40.0, h in -5.0f32..40.0,
    ) {
        let g = circles(&[(0.0, 0.0, 8.0), (6.0, 5.0, 3.0)], &[(1.0, -1.0, 2.0)]);
        let region = Aabb::new(Vec2::new(x0, y0), Vec2::new(x0 + w, y0 + h));
        let opts = ContourOptions { spacing, refine_iterations: refine, simplify_tolerance: tol };
        match mesh_solid(&g, region, &opts) {
            Ok(m) => {
                prop_assert!(m.area() >= 0.0);
                prop_assert!(m.triangles.iter().flatten().all(|&i| (i as usize) < m.vertices.len()));
            }
            Err(e) => prop_assert!(!e.to_string().is_empty()),
        }
    }
}

#[test]
fn default_level_window_at_unit_spacing() {
    let level = Level::default_level();
    // A window with thin bridges and spikes (1.5-3 units wide).
    let region = Aabb::new(Vec2::new(2048.0, 768.0), Vec2::new(2560.0, 1280.0));
    let opts = ContourOptions::default();
    let c = extract_contours(level.graph(), region, &opts).unwrap();
    assert!(!c.loops.is_empty());
    let m = mesh_contours(&c).unwrap();
    let (ca, ma) = (c.area(), m.area());
    assert!(ca > 0.0);
    assert!(((ma - ca) / ca).abs() < 0.01, "mesh {ma} vs contours {ca}");
    assert_eq!(m.skipped_constraints, 0);
    for p in m.centroids() {
        let d = level.graph().distance(p);
        assert!(d < 0.5, "centroid {p} at distance {d}");
    }
}

#[test]
fn default_level_window_simplified() {
    let level = Level::default_level();
    let region = Aabb::new(Vec2::new(0.0, 0.0), Vec2::new(512.0, 512.0));
    let opts = ContourOptions {
        spacing: 2.0,
        refine_iterations: 2,
        simplify_tolerance: 0.25,
    };
    let full = extract_contours(
        level.graph(),
        region,
        &ContourOptions {
            simplify_tolerance: 0.0,
            ..opts
        },
    )
    .unwrap();
    let c = extract_contours(level.graph(), region, &opts).unwrap();
    assert!(c.vertex_count() < full.vertex_count());
    let m = mesh_contours(&c).unwrap();
    let (ca, ma, fa) = (c.area(), m.area(), full.area());
    assert!(((ma - ca) / ca).abs() < 0.01, "mesh {ma} vs contours {ca}");
    assert!(
        ((ca - fa) / fa).abs() < 0.01,
        "simplified {ca} vs full {fa}"
    );
}
