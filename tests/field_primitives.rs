//! Every primitive against brute force: the distance to a densely sampled boundary (or, for
//! thick curves, to a densely sampled centre line), and an independent inside test.

mod common;

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use common::Rng;
use craterfield::field2d::{Exactness, Graph, Node, Sdf};
use glam::{DVec2, Vec2};

fn compile(node: Node) -> Graph {
    Graph::compile(&node, &BTreeMap::new()).expect("valid node")
}

fn circle_points(c: DVec2, r: f64, n: usize) -> Vec<DVec2> {
    (0..n)
        .map(|i| c + r * DVec2::from_angle(TAU * i as f64 / n as f64))
        .collect()
}

fn segment_points(a: DVec2, b: DVec2, step: f64) -> Vec<DVec2> {
    let n = ((b - a).length() / step).ceil().max(1.0) as usize;
    (0..=n).map(|i| a.lerp(b, i as f64 / n as f64)).collect()
}

fn polyline(pts: &[DVec2], closed: bool, step: f64) -> Vec<DVec2> {
    let mut out = Vec::new();
    let n = pts.len();
    let edges = if closed { n } else { n - 1 };
    for i in 0..edges {
        out.extend(segment_points(pts[i], pts[(i + 1) % n], step));
    }
    out
}

fn nearest(samples: &[DVec2], p: DVec2) -> f64 {
    samples
        .iter()
        .map(|s| s.distance(p))
        .fold(f64::INFINITY, f64::min)
}

fn point_in_polygon(pts: &[DVec2], p: DVec2) -> bool {
    let mut inside = false;
    let n = pts.len();
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

/// Checks `|d|` against the brute-force distance and the sign against `inside`.
fn check(
    name: &str,
    node: Node,
    window: (DVec2, DVec2),
    brute: impl Fn(DVec2) -> f64,
    inside: impl Fn(DVec2) -> bool,
    tol: f64,
) {
    let g = compile(node);
    assert_eq!(
        g.root_info().exactness,
        Exactness::Exact,
        "{name} is reported exact"
    );
    let mut rng = Rng(name.len() as u64 * 7919);
    let mut worst = 0.0f64;
    for _ in 0..600 {
        let p = DVec2::new(
            rng.range_f64(window.0.x, window.1.x),
            rng.range_f64(window.0.y, window.1.y),
        );
        let d = g.distance(p.as_vec2()) as f64;
        let b = brute(p);
        if b < tol {
            continue; // too close to the boundary to judge the sign
        }
        let err = (d.abs() - b).abs();
        worst = worst.max(err);
        assert!(
            err <= tol + 1e-5 * b,
            "{name} at {p}: field {d}, brute force {b}"
        );
        assert_eq!(d < 0.0, inside(p), "{name} at {p}: sign of {d} is wrong");
    }
    assert!(worst.is_finite(), "{name}: no point was checked");
}

const STEP: f64 = 0.02;
const TOL: f64 = 0.02;

#[test]
fn circle() {
    let c = DVec2::new(3.0, -2.0);
    let boundary = circle_points(c, 7.5, 4000);
    let node = Node::Circle {
        center: [3.0, -2.0],
        radius: 7.5,
    };
    check(
        "circle",
        node,
        (DVec2::splat(-20.0), DVec2::splat(20.0)),
        |p| nearest(&boundary, p),
        |p| p.distance(c) < 7.5,
        TOL,
    );
}

#[test]
fn boxes_plain_rounded_oriented() {
    let corners = [
        DVec2::new(-4.0, -1.0),
        DVec2::new(6.0, -1.0),
        DVec2::new(6.0, 5.0),
        DVec2::new(-4.0, 5.0),
    ];
    let boundary = polyline(&corners, true, STEP);
    let node = Node::Box {
        center: [1.0, 2.0],
        half_size: [5.0, 3.0],
    };
    let inside = |p: DVec2| p.x > -4.0 && p.x < 6.0 && p.y > -1.0 && p.y < 5.0;
    check(
        "box",
        node,
        (DVec2::splat(-15.0), DVec2::splat(15.0)),
        |p| nearest(&boundary, p),
        inside,
        TOL,
    );

    // Rounded: the inner box's boundary offset by r, i.e. distance to the inner box minus r.
    let inner = [
        DVec2::new(-3.0, 0.0),
        DVec2::new(5.0, 0.0),
        DVec2::new(5.0, 4.0),
        DVec2::new(-3.0, 4.0),
    ];
    let inner_boundary = polyline(&inner, true, STEP);
    let inner_inside = |p: DVec2| point_in_polygon(&inner, p);
    let rounded_brute = |p: DVec2| {
        let d = nearest(&inner_boundary, p);
        if inner_inside(p) {
            d + 1.0
        } else {
            (d - 1.0).abs()
        }
    };
    let node = Node::RoundedBox {
        center: [1.0, 2.0],
        half_size: [5.0, 3.0],
        radius: 1.0,
    };
    let inside = |p: DVec2| inner_inside(p) || nearest(&inner_boundary, p) < 1.0;
    check(
        "rounded box",
        node,
        (DVec2::splat(-15.0), DVec2::splat(15.0)),
        rounded_brute,
        inside,
        TOL,
    );

    let (a, b) = (DVec2::new(-5.0, -3.0), DVec2::new(7.0, 4.0));
    let dir = (b - a).normalize();
    let n = dir.perp() * 1.5;
    let quad = [a - n, b - n, b + n, a + n];
    let boundary = polyline(&quad, true, STEP);
    let node = Node::OrientedBox {
        a: [-5.0, -3.0],
        b: [7.0, 4.0],
        thickness: 3.0,
    };
    check(
        "oriented box",
        node,
        (DVec2::splat(-15.0), DVec2::splat(15.0)),
        |p| nearest(&boundary, p),
        |p| point_in_polygon(&quad, p),
        TOL,
    );
}

#[test]
fn capsule_ring_arc_as_thick_curves() {
    let centre = segment_points(DVec2::new(-6.0, 1.0), DVec2::new(5.0, -3.0), 0.005);
    let node = Node::Capsule {
        a: [-6.0, 1.0],
        b: [5.0, -3.0],
        radius: 2.0,
    };
    let brute = |p: DVec2| (nearest(&centre, p) - 2.0).abs();
    check(
        "capsule",
        node,
        (DVec2::splat(-12.0), DVec2::splat(12.0)),
        brute,
        |p| nearest(&centre, p) < 2.0,
        TOL,
    );

    let c = DVec2::new(1.0, 1.0);
    let node = Node::Ring {
        center: [1.0, 1.0],
        radius: 6.0,
        width: 2.0,
    };
    let brute = |p: DVec2| ((p.distance(c) - 6.0).abs() - 1.0).abs();
    check(
        "ring",
        node,
        (DVec2::splat(-10.0), DVec2::splat(12.0)),
        brute,
        |p| (p.distance(c) - 6.0).abs() < 1.0,
        TOL,
    );

    // Arc of radius 8 around the origin, half-aperture 60 degrees about +y rotated by 30
    // degrees counter-clockwise, width 2.
    let mid = 90.0f64.to_radians() + 30.0f64.to_radians();
    let ap = 60.0f64.to_radians();
    let centre: Vec<DVec2> = (0..=6000)
        .map(|i| 8.0 * DVec2::from_angle(mid - ap + 2.0 * ap * i as f64 / 6000.0))
        .collect();
    let node = Node::Arc {
        center: [0.0, 0.0],
        radius: 8.0,
        width: 2.0,
        aperture: 60.0,
        rotation: 30.0,
    };
    let brute = |p: DVec2| (nearest(&centre, p) - 1.0).abs();
    check(
        "arc",
        node,
        (DVec2::splat(-12.0), DVec2::splat(12.0)),
        brute,
        |p| nearest(&centre, p) < 1.0,
        0.03,
    );
}

#[test]
fn triangle_and_polygons_of_either_winding() {
    let tri = [
        DVec2::new(-5.0, -4.0),
        DVec2::new(6.0, -2.0),
        DVec2::new(0.0, 7.0),
    ];
    let boundary = polyline(&tri, true, STEP);
    let node = Node::Triangle {
        a: [-5.0, -4.0],
        b: [6.0, -2.0],
        c: [0.0, 7.0],
    };
    check(
        "triangle",
        node,
        (DVec2::splat(-12.0), DVec2::splat(12.0)),
        |p| nearest(&boundary, p),
        |p| point_in_polygon(&tri, p),
        TOL,
    );

    // A concave polygon (a "C"), in both windings.
    let c_shape = [
        (-6.0, -6.0),
        (6.0, -6.0),
        (6.0, -3.0),
        (-2.0, -3.0),
        (-2.0, 3.0),
        (6.0, 3.0),
        (6.0, 6.0),
        (-6.0, 6.0),
    ];
    for (name, pts) in [
        ("polygon ccw", c_shape.to_vec()),
        ("polygon cw", c_shape.iter().rev().copied().collect()),
    ] {
        let dpts: Vec<DVec2> = pts.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
        let boundary = polyline(&dpts, true, STEP);
        let node = Node::Polygon {
            points: pts.iter().map(|&(x, y)| [x as f32, y as f32]).collect(),
        };
        check(
            name,
            node,
            (DVec2::splat(-12.0), DVec2::splat(12.0)),
            |p| nearest(&boundary, p),
            |p| point_in_polygon(&dpts, p),
            TOL,
        );
    }
}

#[test]
fn ellipse_is_exact_up_to_the_solver_tolerance() {
    for (rx, ry) in [(9.0, 3.0), (2.0, 7.0), (5.0, 5.0), (20.0, 1.0)] {
        let c = DVec2::new(-1.0, 2.0);
        let boundary: Vec<DVec2> = (0..20000)
            .map(|i| c + DVec2::new(rx, ry) * DVec2::from_angle(TAU * i as f64 / 20000.0))
            .collect();
        let node = Node::Ellipse {
            center: [-1.0, 2.0],
            radii: [rx as f32, ry as f32],
        };
        let inside = |p: DVec2| ((p - c) / DVec2::new(rx, ry)).length_squared() < 1.0;
        let name = format!("ellipse {rx}x{ry}");
        check(
            &name,
            node,
            (DVec2::splat(-25.0), DVec2::splat(25.0)),
            |p| nearest(&boundary, p),
            inside,
            0.03,
        );
    }
}

#[test]
fn half_plane_and_height_profile() {
    let node = Node::HalfPlane {
        point: [1.0, 2.0],
        normal: [3.0, 4.0],
    };
    let n = DVec2::new(0.6, 0.8);
    let brute = |p: DVec2| (p - DVec2::new(1.0, 2.0)).dot(n).abs();
    check(
        "half-plane",
        node,
        (DVec2::splat(-20.0), DVec2::splat(20.0)),
        brute,
        |p| (p - DVec2::new(1.0, 2.0)).dot(n) < 0.0,
        1e-3,
    );

    let heights = [3.0, 5.0, -1.0, 2.0, 2.5, 8.0, 0.0];
    let pts: Vec<DVec2> = heights
        .iter()
        .enumerate()
        .map(|(i, &h)| DVec2::new(-6.0 + 2.0 * i as f64, h))
        .collect();
    let mut line = vec![DVec2::new(-200.0, 3.0)];
    line.extend(&pts);
    line.push(DVec2::new(200.0, 0.0));
    let boundary = polyline(&line, false, 0.01);
    let ground = |x: f64| {
        if x <= -6.0 {
            return 3.0;
        }
        if x >= 6.0 {
            return 0.0;
        }
        let i = ((x + 6.0) / 2.0).floor() as usize;
        let t = (x - pts[i].x) / 2.0;
        pts[i].y + (pts[i + 1].y - pts[i].y) * t
    };
    let node = Node::HeightProfile {
        x0: -6.0,
        dx: 2.0,
        heights: heights.iter().map(|&h| h as f32).collect(),
    };
    check(
        "height profile",
        node,
        (DVec2::new(-15.0, -10.0), DVec2::new(15.0, 15.0)),
        |p| nearest(&boundary, p),
        |p| p.y < ground(p.x),
        0.01,
    );
}

/// The true distance to the zero set of a field, by brute force: zero crossings on a fine
/// raster (with linear interpolation) and the nearest of them.
fn raster_boundary(g: &Graph, lo: Vec2, hi: Vec2, step: f32) -> Vec<DVec2> {
    let nx = ((hi.x - lo.x) / step) as usize;
    let ny = ((hi.y - lo.y) / step) as usize;
    let at = |i: usize, j: usize| lo + Vec2::new(i as f32, j as f32) * step;
    let mut out = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let p = at(i, j);
            let d = g.distance(p);
            for q in [at(i + 1, j), at(i, j + 1)] {
                let e = g.distance(q);
                if (d < 0.0) != (e < 0.0) {
                    let t = d / (d - e);
                    out.push(p.as_dvec2().lerp(q.as_dvec2(), t as f64));
                }
            }
        }
    }
    out
}

#[test]
fn bounds_never_exceed_the_true_distance() {
    let circle = |x: f32, y: f32, r: f32| Node::Circle {
        center: [x, y],
        radius: r,
    };
    let boxn = |x: f32, y: f32, w: f32, h: f32| Node::Box {
        center: [x, y],
        half_size: [w, h],
    };
    let cases: Vec<(&str, Node)> = vec![
        (
            "union",
            Node::Union(vec![circle(-3.0, 0.0, 4.0), boxn(4.0, 1.0, 3.0, 2.0)]),
        ),
        (
            "intersection",
            Node::Intersection(vec![circle(0.0, 0.0, 6.0), boxn(3.0, 0.0, 4.0, 4.0)]),
        ),
        (
            "subtract",
            Node::Subtract {
                base: Box::new(boxn(0.0, 0.0, 8.0, 5.0)),
                cut: Box::new(circle(2.0, 1.0, 3.0)),
            },
        ),
        (
            "smooth union",
            Node::SmoothUnion {
                k: 3.0,
                nodes: vec![circle(-3.0, 0.0, 4.0), circle(4.0, 0.0, 3.0)],
            },
        ),
        (
            "smooth intersection",
            Node::SmoothIntersection {
                k: 2.0,
                nodes: vec![circle(0.0, 0.0, 6.0), boxn(3.0, 0.0, 4.0, 4.0)],
            },
        ),
        (
            "smooth subtract",
            Node::SmoothSubtract {
                k: 2.0,
                base: Box::new(boxn(0.0, 0.0, 8.0, 5.0)),
                cut: Box::new(circle(2.0, 1.0, 3.0)),
            },
        ),
        (
            "round",
            Node::Round {
                radius: 1.5,
                node: Box::new(Node::Triangle {
                    a: [-5.0, -4.0],
                    b: [6.0, -2.0],
                    c: [0.0, 5.0],
                }),
            },
        ),
        (
            "onion",
            Node::Onion {
                width: 0.7,
                node: Box::new(boxn(0.0, 0.0, 5.0, 3.0)),
            },
        ),
        (
            "mirror",
            Node::Mirror {
                axis: craterfield::field2d::Axis::X,
                at: 1.0,
                node: Box::new(circle(4.0, 0.0, 2.0)),
            },
        ),
        (
            "repeat",
            Node::Repeat {
                period: [6.0, 0.0],
                node: Box::new(circle(0.0, 0.0, 1.5)),
            },
        ),
        (
            "repeat finite",
            Node::RepeatFinite {
                period: [5.0, 4.0],
                count: [3, 2],
                node: Box::new(boxn(0.0, 0.0, 1.0, 0.5)),
            },
        ),
        (
            "displace noise",
            Node::DisplaceNoise {
                amplitude: 0.8,
                wavelength: 3.0,
                seed: 5,
                node: Box::new(circle(0.0, 0.0, 6.0)),
            },
        ),
        (
            "displace wave",
            Node::DisplaceWave {
                amplitude: 0.5,
                wavelength: 4.0,
                direction: 20.0,
                phase: 0.1,
                node: Box::new(boxn(0.0, 0.0, 6.0, 4.0)),
            },
        ),
    ];
    for (name, node) in cases {
        let g = compile(node);
        let (lo, hi) = (Vec2::splat(-14.0), Vec2::splat(14.0));
        let boundary = raster_boundary(&g, lo, hi, 0.02);
        assert!(!boundary.is_empty(), "{name}: no boundary found");
        let mut rng = Rng(name.len() as u64 + 17);
        for _ in 0..300 {
            let p = DVec2::new(rng.range_f64(-10.0, 10.0), rng.range_f64(-10.0, 10.0));
            let d = g.distance(p.as_vec2()) as f64;
            let truth = nearest(&boundary, p);
            let l = g.lipschitz() as f64;
            assert!(
                d.abs() / l <= truth + 0.03,
                "{name} at {p}: |{d}| / {l} exceeds the true distance {truth}"
            );
        }
    }
}
