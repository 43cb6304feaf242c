//! The evaluator conformance suite: every backend this machine has, against the scalar
//! reference walker, bit for bit (NaNs compare equal whatever their payload: the contract
//! rejects NaN at the boundary, and payloads are not specified by IEEE-754).
//!
//! Covered: every instruction (a test fails if an instruction is never exercised), random
//! graphs over every node kind, adversarial points (signed zeros, denormals, huge and tiny
//! coordinates, points exactly on boundaries and on lattice and repetition edges), region
//! specialization against the whole tape, and terrains with events on cell edges through
//! the single-point and batch paths.

mod common;

use std::collections::BTreeSet;

use common::Rng;
use craterfield::backend::Backend;
use craterfield::field2d::tape::{Op, Outputs, Program};
use craterfield::field2d::{Event, Graph, Level, Node, Sample, Sdf, TerrainOptions};
use glam::Vec2;

fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn same_sample(a: &Sample, b: &Sample) -> bool {
    same(a.distance, b.distance)
        && same(a.gradient.x, b.gradient.x)
        && same(a.gradient.y, b.gradient.y)
        && a.material == b.material
}

/// Adversarial coordinates mixed into every point set.
fn adversarial() -> Vec<Vec2> {
    let specials = [
        0.0,
        -0.0,
        1e-40,
        -1e-40,
        1e-30,
        -1e-30,
        0.5,
        -0.5,
        1.0,
        -1.0,
        0.25,
        0.75,
        2.0,
        10.0,
        -10.0,
        32.0,
        64.0,
        100.0,
        1e6,
        -1e6,
        3e38,
        -3e38,
        f32::MAX,
        f32::MIN_POSITIVE,
    ];
    let mut out = Vec::new();
    for &x in &specials {
        for &y in &specials {
            out.push(Vec2::new(x, y));
        }
    }
    out
}

/// Checks a program's tapes (plain and fused) on every backend against the graph.
fn check_graph(
    graph: &Graph,
    program: &Program,
    points: &[Vec2],
    seen: &mut BTreeSet<Op>,
    what: &str,
) {
    let want_d: Vec<f32> = points.iter().map(|&p| graph.distance(p)).collect();
    let want_s: Vec<Sample> = points.iter().map(|&p| graph.sample(p)).collect();
    for prog in [program.clone(), program.fuse()] {
        let tv = prog.tape(Outputs::Value);
        let tm = prog.tape(Outputs::ValueMaterial);
        seen.extend(tv.instrs().iter().map(|i| i.op));
        seen.extend(tm.instrs().iter().map(|i| i.op));
        for b in Backend::available() {
            let mut d = vec![0.0; points.len()];
            tv.distances(points, &mut d, b).unwrap();
            let mut s = vec![want_s[0]; points.len()];
            tm.samples(points, &mut s, b).unwrap();
            for (k, p) in points.iter().enumerate() {
                assert!(
                    same(d[k], want_d[k]),
                    "{what}: {b} distance at {p:?}: {} != reference {}",
                    d[k],
                    want_d[k]
                );
                assert!(
                    same_sample(&s[k], &want_s[k]),
                    "{what}: {b} sample at {p:?}: {:?} != reference {:?}",
                    s[k],
                    want_s[k]
                );
            }
        }
    }
}

fn points_around(r: &mut Rng, radius: f32, n: usize) -> Vec<Vec2> {
    let mut pts: Vec<Vec2> = (0..n).map(|_| Vec2::from(r.square_point(radius))).collect();
    // Integer and half-integer lattice points: where floors, cells and repetitions flip.
    for i in -8..=8 {
        for j in -8..=8 {
            pts.push(Vec2::new(i as f32 * 12.5, j as f32 * 7.25));
        }
    }
    pts.extend(adversarial());
    pts
}

// ---- random graphs ----------------------------------------------------------------------

fn random_primitive(r: &mut Rng) -> Node {
    let size = |r: &mut Rng| r.range(1.0, 40.0);
    match r.below(13) {
        0 => Node::Circle {
            center: r.square_point(60.0),
            radius: size(r),
        },
        1 => Node::Box {
            center: r.square_point(60.0),
            half_size: [size(r), size(r)],
        },
        2 => {
            let h = [size(r), size(r)];
            Node::RoundedBox {
                center: r.square_point(60.0),
                half_size: h,
                radius: r.range(0.0, h[0].min(h[1])),
            }
        }
        3 => Node::OrientedBox {
            a: r.square_point(60.0),
            b: r.square_point(60.0),
            thickness: r.range(0.5, 10.0),
        },
        4 => Node::Capsule {
            a: r.square_point(60.0),
            b: r.square_point(60.0),
            radius: size(r),
        },
        5 => {
            // A convex polygon: sorted angles around a centre.
            let n = 3 + r.below(6) as usize;
            let c = r.square_point(40.0);
            let mut angles: Vec<f32> = (0..n)
                .map(|_| r.range(0.0, std::f32::consts::TAU))
                .collect();
            angles.sort_by(f32::total_cmp);
            let rad = size(r);
            let points = angles
                .iter()
                .map(|a| [c[0] + rad * a.cos(), c[1] + rad * a.sin()])
                .collect();
            Node::Polygon { points }
        }
        6 => {
            let a = size(r);
            Node::Ellipse {
                center: r.square_point(60.0),
                radii: [a, a * r.range(0.2, 5.0)],
            }
        }
        7 => Node::Ring {
            center: r.square_point(60.0),
            radius: size(r),
            width: r.range(0.5, 8.0),
        },
        8 => Node::Arc {
            center: r.square_point(60.0),
            radius: size(r),
            width: r.range(0.5, 8.0),
            aperture: r.range(1.0, 180.0),
            rotation: r.range(-360.0, 360.0),
        },
        9 => Node::HalfPlane {
            point: r.square_point(60.0),
            normal: r.square_point(1.0),
        },
        10 => {
            let n = 2 + r.below(30) as usize;
            Node::HeightProfile {
                x0: r.range(-100.0, 0.0),
                dx: r.range(1.0, 20.0),
                heights: (0..n).map(|_| r.range(-50.0, 50.0)).collect(),
            }
        }
        11 => Node::Triangle {
            a: r.square_point(60.0),
            b: r.square_point(60.0),
            c: r.square_point(60.0),
        },
        _ => match r.below(3) {
            0 => Node::X,
            1 => Node::Y,
            _ => Node::Const(r.range(-50.0, 50.0)),
        },
    }
}

fn random_node(r: &mut Rng, depth: u32) -> Node {
    if depth == 0 || r.below(10) < 3 {
        return random_primitive(r);
    }
    let d = depth - 1;
    let child = |r: &mut Rng| Box::new(random_node(r, d));
    let kids = |r: &mut Rng| (0..2 + r.below(3)).map(|_| random_node(r, d)).collect();
    match r.below(25) {
        0 => Node::Union(kids(r)),
        1 => Node::Intersection(kids(r)),
        2 => Node::Subtract {
            base: child(r),
            cut: child(r),
        },
        3 => Node::SmoothUnion {
            k: r.range(0.5, 20.0),
            nodes: kids(r),
        },
        4 => Node::SmoothIntersection {
            k: r.range(0.5, 20.0),
            nodes: kids(r),
        },
        5 => Node::SmoothSubtract {
            k: r.range(0.5, 20.0),
            base: child(r),
            cut: child(r),
        },
        6 => Node::Round {
            radius: r.range(0.0, 5.0),
            node: child(r),
        },
        7 => Node::Onion {
            width: r.range(0.5, 5.0),
            node: child(r),
        },
        8 => Node::Translate {
            offset: r.square_point(50.0),
            node: child(r),
        },
        9 => Node::Rotate {
            degrees: r.range(-360.0, 360.0),
            node: child(r),
        },
        10 => Node::Scale {
            factor: r.range(0.25, 4.0),
            node: child(r),
        },
        11 => Node::Mirror {
            axis: if r.below(2) == 0 {
                craterfield::field2d::Axis::X
            } else {
                craterfield::field2d::Axis::Y
            },
            at: r.range(-20.0, 20.0),
            node: child(r),
        },
        12 | 13 => {
            // A small child that fits its period.
            let rad = r.range(1.0, 8.0);
            let inner = Node::Circle {
                center: [r.range(-2.0, 2.0), r.range(-2.0, 2.0)],
                radius: rad,
            };
            let inner = if r.below(2) == 0 {
                Node::Union(vec![
                    inner,
                    Node::Box {
                        center: [0.0, 0.0],
                        half_size: [rad * 0.5, rad],
                    },
                ])
            } else {
                inner
            };
            let period = [
                if r.below(3) == 0 {
                    0.0
                } else {
                    2.0 * rad + r.range(5.0, 30.0)
                },
                if r.below(3) == 0 {
                    0.0
                } else {
                    2.0 * rad + r.range(5.0, 30.0)
                },
            ];
            let period = if period == [0.0, 0.0] {
                [2.0 * rad + 10.0, 0.0]
            } else {
                period
            };
            if r.below(2) == 0 {
                Node::Repeat {
                    period,
                    node: Box::new(inner),
                }
            } else {
                Node::RepeatFinite {
                    period,
                    count: [
                        if period[0] > 0.0 {
                            1 + r.below(5) as u32
                        } else {
                            1
                        },
                        if period[1] > 0.0 {
                            1 + r.below(5) as u32
                        } else {
                            1
                        },
                    ],
                    node: Box::new(inner),
                }
            }
        }
        14 => Node::DisplaceNoise {
            amplitude: r.range(0.0, 6.0),
            wavelength: r.range(5.0, 60.0),
            seed: r.next() as u32,
            node: child(r),
        },
        15 => Node::DisplaceWave {
            amplitude: r.range(0.0, 6.0),
            wavelength: r.range(5.0, 60.0),
            direction: r.range(-180.0, 180.0),
            phase: r.range(-1.0, 1.0),
            node: child(r),
        },
        16 | 17 => Node::Material {
            id: r.below(5) as u16,
            node: child(r),
        },
        18 => Node::Add(child(r), child(r)),
        19 => Node::Sub(child(r), child(r)),
        20 => Node::Mul(child(r), child(r)),
        21 => Node::Neg(child(r)),
        22 => Node::Square(child(r)),
        23 => Node::Sqrt(child(r)),
        _ => Node::Union(kids(r)),
    }
}

fn random_graph(r: &mut Rng) -> Graph {
    loop {
        let node = random_node(r, 4);
        if let Ok(g) = Graph::compile(&node, &Default::default()) {
            return g;
        }
    }
}

// ---- tests ------------------------------------------------------------------------------

/// Every node kind, alone and combined, on every backend; every instruction is exercised.
#[test]
fn random_graphs_match_the_reference_on_every_backend() {
    let mut r = Rng(0x5eed_0001);
    let mut seen = BTreeSet::new();
    for case in 0..300 {
        let g = random_graph(&mut r);
        let pts = points_around(&mut r, 150.0, 300);
        check_graph(
            &g,
            &g.program(),
            &pts,
            &mut seen,
            &format!("random graph {case}"),
        );
    }
    // The example levels and the prospero expression cover the rest.
    for level in example_levels() {
        let pts = points_around(&mut r, 4000.0, 2000);
        check_graph(
            level.graph(),
            &level.graph().program(),
            &pts,
            &mut seen,
            level.name(),
        );
    }
    let (pg, pts) = prospero_subset();
    check_graph(&pg, &pg.program(), &pts, &mut seen, "prospero");
    // Every superinstruction, from expressions made for it.
    let c = |v: f32| Box::new(Node::Const(v));
    let (x, y) = (|| Box::new(Node::X), || Box::new(Node::Y));
    for (combine, name) in [(true, "max"), (false, "min")] {
        let operands = vec![
            Node::Add(y(), c(3.5)),
            Node::Add(c(-2.0), y()),
            Node::Sub(y(), c(1.25)),
            Node::Sub(c(4.0), y()),
            Node::Sub(y(), x()),
            Node::Neg(y()),
        ];
        for operand in operands {
            let nodes = vec![Node::X, operand, Node::Square(y()), Node::Y];
            let node = if combine {
                Node::Intersection(nodes)
            } else {
                Node::Union(nodes)
            };
            let g = Graph::compile(&node, &Default::default()).unwrap();
            let pts = points_around(&mut r, 20.0, 200);
            check_graph(&g, &g.program(), &pts, &mut seen, name);
        }
    }
    let missing: Vec<Op> = Op::ALL
        .iter()
        .copied()
        .filter(|o| !seen.contains(o))
        .collect();
    assert!(
        missing.is_empty(),
        "instructions never exercised: {missing:?}"
    );
}

fn example_levels() -> Vec<Level> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/levels");
    ["default", "skyrealm", "caverns"]
        .iter()
        .map(|n| Level::load(std::path::Path::new(&format!("{dir}/{n}.ron"))).unwrap())
        .collect()
}

fn prospero_text() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/prospero.vm");
    std::fs::read_to_string(path).expect("the vendored test input tests/data/prospero.vm")
}

/// The prospero graph and a spread of its pixels (the full image is the benchmark's job).
fn prospero_subset() -> (Graph, Vec<Vec2>) {
    let g = craterfield::field2d::import::graph_from_vm(&prospero_text()).unwrap();
    let mut pts = Vec::new();
    for j in (0..1024).step_by(37) {
        for i in (0..1024).step_by(29) {
            pts.push(Vec2::new(
                (i as f32 + 0.5) / 512.0 - 1.0,
                1.0 - (j as f32 + 0.5) / 512.0,
            ));
        }
    }
    pts.extend(adversarial());
    (g, pts)
}

/// A specialized program computes the whole program's bits everywhere in its box.
#[test]
fn specialization_is_bit_identical_inside_its_box() {
    let mut r = Rng(0x5eed_0002);
    let mut pruned = 0usize;
    let mut total = 0usize;
    let mut cases: Vec<(Graph, f32)> = (0..150).map(|_| (random_graph(&mut r), 100.0)).collect();
    for l in example_levels() {
        cases.push((l.graph().clone(), 2000.0));
    }
    for (g, extent) in &cases {
        let full = g.program();
        for _ in 0..6 {
            let c = Vec2::new(r.range(-extent, *extent), r.range(-extent, *extent));
            let h = Vec2::new(r.range(0.5, extent / 10.0), r.range(0.5, extent / 10.0));
            let (min, max) = (c - h, c + h);
            let spec = full.specialize(min, max);
            total += full.len();
            pruned += full.len() - spec.len().min(full.len());
            let mut pts: Vec<Vec2> = (0..200)
                .map(|_| Vec2::new(r.range(min.x, max.x), r.range(min.y, max.y)))
                .collect();
            pts.extend([
                min,
                max,
                Vec2::new(min.x, max.y),
                Vec2::new(max.x, min.y),
                c,
            ]);
            for prog in [spec.clone(), spec.fuse()] {
                let (tv, tm) = (prog.tape(Outputs::Value), prog.tape(Outputs::ValueMaterial));
                let (fv, fm) = (full.tape(Outputs::Value), full.tape(Outputs::ValueMaterial));
                for b in Backend::available() {
                    let mut d = vec![0.0; pts.len()];
                    let mut e = vec![0.0; pts.len()];
                    tv.distances(&pts, &mut d, b).unwrap();
                    fv.distances(&pts, &mut e, b).unwrap();
                    let mut s = vec![
                        Sample {
                            distance: 0.0,
                            gradient: Vec2::ZERO,
                            material: 0
                        };
                        pts.len()
                    ];
                    let mut t = s.clone();
                    tm.samples(&pts, &mut s, b).unwrap();
                    fm.samples(&pts, &mut t, b).unwrap();
                    for k in 0..pts.len() {
                        assert!(
                            same(d[k], e[k]),
                            "{b} at {:?} in {min}..{max}: {} != {}",
                            pts[k],
                            d[k],
                            e[k]
                        );
                        assert!(
                            same_sample(&s[k], &t[k]),
                            "{b} at {:?}: {:?} != {:?}",
                            pts[k],
                            s[k],
                            t[k]
                        );
                    }
                }
            }
        }
    }
    // It must also do something: a good share of instructions is dropped on small boxes.
    assert!(
        pruned * 4 > total,
        "specialization dropped only {pruned} of {total} instructions"
    );
}

/// Single points, batches on every backend, and the brute force agree on a terrain with
/// events centred exactly on cell edges and corners, rims, fills and growing events.
#[test]
fn terrain_batches_match_single_points_and_brute_force() {
    let level = Level::default_level();
    let mut t = level.terrain().unwrap();
    let cell = t.options().cell_size;
    let mut r = Rng(0x5eed_0003);
    for i in 0..2500u32 {
        let c = if i % 3 == 0 {
            // On a cell edge or corner.
            Vec2::new(
                (r.below(60) as f32) * cell,
                (r.below(25) as f32) * cell + if i % 2 == 0 { 0.0 } else { cell * 0.5 },
            )
        } else {
            Vec2::new(r.range(0.0, 3840.0), r.range(150.0, 1300.0))
        };
        let radius = r.range(2.0, 70.0);
        let mut e = if i % 6 == 0 {
            Event::fill(c, radius, (i % 5) as u16).unwrap()
        } else {
            Event::carve(c, radius).unwrap()
        };
        if i % 4 == 0 {
            e = e.with_rim(r.range(0.5, 12.0)).unwrap();
        }
        if i % 9 == 0 {
            e = e.with_growth(10).at_tick(i / 100);
        }
        t.apply(e).unwrap();
    }
    t.set_tick(20).unwrap();
    let mut pts: Vec<Vec2> = (0..30_000)
        .map(|_| Vec2::new(r.range(-700.0, 4540.0), r.range(-700.0, 2300.0)))
        .collect();
    for i in 0..61 {
        for j in 0..26 {
            pts.push(Vec2::new(i as f32 * cell, j as f32 * cell));
        }
    }
    // Around the grid in its halo of coarse tiles, across the halo's edge (8,192 units
    // past the grid) and beyond it, where the whole program answers.
    for k in 0..720 {
        let reach = [900.0, 3000.0, 8100.0, 8300.0, 9000.0, 40_000.0][k % 6];
        let dir = Vec2::from_angle(k as f32 * 0.0087);
        pts.push(Vec2::new(1900.0, 650.0) + dir * (1900.0 + reach));
    }
    pts.extend([Vec2::new(f32::NAN, 3.0), Vec2::new(1.0, f32::NAN)]);
    let single_d: Vec<f32> = pts.iter().map(|&p| t.distance(p)).collect();
    let single_s: Vec<Sample> = pts.iter().map(|&p| t.sample(p)).collect();
    let every_seventh_and_the_far_ring = (0..pts.len()).filter(|k| k % 7 == 0 || *k >= 30_000);
    for (k, p) in every_seventh_and_the_far_ring.map(|k| (k, pts[k])) {
        if t.cell_state(p).and_then(|s| s.brick()).is_none() {
            assert!(same(single_d[k], t.distance_brute_force(p)), "at {p}");
            assert!(
                same_sample(&single_s[k], &t.sample_brute_force(p)),
                "at {p}"
            );
        }
    }
    for b in Backend::available() {
        t.set_backend(b).unwrap();
        let mut d = vec![0.0; pts.len()];
        t.distances(&pts, &mut d).unwrap();
        let mut s = vec![single_s[0]; pts.len()];
        t.samples(&pts, &mut s).unwrap();
        for k in 0..pts.len() {
            assert!(
                same(d[k], single_d[k]),
                "{b} at {}: {} != {}",
                pts[k],
                d[k],
                single_d[k]
            );
            assert!(
                same_sample(&s[k], &single_s[k]),
                "{b} at {}: {:?} != {:?}",
                pts[k],
                s[k],
                single_s[k]
            );
        }
        // Small batches take the other grouping path.
        let few = &pts[..50];
        let mut d = vec![0.0; few.len()];
        t.distances(few, &mut d).unwrap();
        assert!(d.iter().zip(&single_d).all(|(a, b)| same(*a, *b)));
    }
}

/// Heavy destruction: bricks everywhere the grid overflowed, batches still match single
/// points, and specialization on or off changes nothing.
#[test]
fn terrain_with_bricks_matches_across_paths() {
    let level = Level::default_level();
    let o = TerrainOptions {
        cell_cap: 6,
        ..level.terrain_options()
    };
    let b = level.bounds();
    let mut t = craterfield::field2d::Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap();
    let mut r = Rng(0x5eed_0004);
    for i in 0..3000 {
        let c = Vec2::new(r.range(1000.0, 1600.0), r.range(300.0, 800.0));
        let e = if i % 5 == 0 {
            Event::fill(c, r.range(2.0, 15.0), 4).unwrap()
        } else {
            Event::carve(c, r.range(2.0, 25.0)).unwrap()
        };
        t.apply(e).unwrap();
    }
    assert!(t.stats().bricks > 0, "the test needs bricks");
    let pts: Vec<Vec2> = (0..20_000)
        .map(|_| Vec2::new(r.range(900.0, 1700.0), r.range(200.0, 900.0)))
        .collect();
    let single: Vec<Sample> = pts.iter().map(|&p| t.sample(p)).collect();
    for spec in [true, false] {
        t.set_specialize(spec);
        for b in Backend::available() {
            t.set_backend(b).unwrap();
            let mut s = vec![single[0]; pts.len()];
            t.samples(&pts, &mut s).unwrap();
            let mut d = vec![0.0; pts.len()];
            t.distances(&pts, &mut d).unwrap();
            for k in 0..pts.len() {
                assert!(
                    same_sample(&s[k], &single[k]),
                    "{b} spec {spec} at {}",
                    pts[k]
                );
                assert!(
                    same(d[k], single[k].distance),
                    "{b} spec {spec} at {}",
                    pts[k]
                );
            }
        }
    }
}

#[test]
fn batch_errors_are_reported_not_panics() {
    let level = Level::default_level();
    let t = level.terrain().unwrap();
    let e = t.distances(&[Vec2::ZERO; 3], &mut [0.0; 2]).unwrap_err();
    assert!(e.to_string().contains("2 slots for 3 points"), "{e}");
    let tape = level.graph().program().tape(Outputs::Value);
    let missing = Backend::ALL.iter().find(|b| !b.is_available());
    let missing = missing.expect("no machine has both NEON and SSE2");
    let e = tape
        .distances(&[Vec2::ZERO], &mut [0.0], *missing)
        .unwrap_err();
    assert!(e.to_string().contains("not available"), "{e}");
}

/// The specialized prospero render gives the brute force's image, pixel for pixel, with
/// any tiling and thread count, and skips most of the work.
#[test]
fn prospero_specialized_image_equals_brute_force() {
    use craterfield::field2d::tape::{ImageOptions, inside_image};
    let g = craterfield::field2d::import::graph_from_vm(&prospero_text()).unwrap();
    let program = g.program();
    let brute_opts = ImageOptions {
        size: 256,
        tiles: vec![],
        backend: Backend::widest(),
        ..ImageOptions::default()
    };
    let (brute, _) = inside_image(&program, &brute_opts).unwrap();
    let inside = brute.iter().filter(|b| **b).count();
    assert!(
        inside > 1000 && inside < 256 * 256 / 2,
        "{inside} inside pixels"
    );
    let cases = [
        (vec![64, 16, 4], 1, true),
        (vec![32, 8], 2, false),
        (vec![16], 1, true),
        (vec![128, 32, 16], 1, false),
    ];
    for (tiles, threads, leaf_bounds) in cases {
        let o = ImageOptions {
            tiles: tiles.clone(),
            threads,
            leaf_bounds,
            ..brute_opts.clone()
        };
        let (img, stats) = inside_image(&program, &o).unwrap();
        let diff = img.iter().zip(&brute).filter(|(a, b)| a != b).count();
        assert_eq!(diff, 0, "tiles {tiles:?}: {diff} pixels differ");
        assert!(
            stats.filled_tiles > 0 && stats.evaluated_pixels < 256 * 256,
            "tiles {tiles:?}: {stats:?}"
        );
    }
    let bad = ImageOptions {
        tiles: vec![100],
        ..brute_opts
    };
    assert!(
        inside_image(&program, &bad)
            .unwrap_err()
            .to_string()
            .contains("does not divide")
    );
}

/// Every choice of fusion patterns computes the unfused tape's bits.
#[test]
fn every_fusion_subset_is_bit_identical() {
    use craterfield::field2d::tape::FuseOptions;
    let (g, pts) = prospero_subset();
    let program = g.program();
    let plain = program.tape(Outputs::Value);
    let mut want = vec![0.0; pts.len()];
    plain.distances(&pts, &mut want, Backend::Scalar).unwrap();
    for bits in 0..8u8 {
        let o = FuseOptions {
            hypot: bits & 1 != 0,
            affine: bits & 2 != 0,
            chains: bits & 4 != 0,
        };
        let tape = program.fuse_with(o).tape(Outputs::Value);
        assert!(bits == 0 || tape.len() < plain.len(), "{o:?} fused nothing");
        for b in Backend::available() {
            let mut got = vec![0.0; pts.len()];
            tape.distances(&pts, &mut got, b).unwrap();
            for k in 0..pts.len() {
                assert!(same(got[k], want[k]), "{o:?} {b} at {}", pts[k]);
            }
        }
    }
}
