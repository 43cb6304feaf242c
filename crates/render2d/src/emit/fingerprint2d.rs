//! A stable 64-bit fingerprint of a compiled level graph's content: every operation's kind,
//! the bits of its constants and its children, and the root. Two graphs with the same
//! fingerprint emit the same WGSL for the same plan.

use glam::Vec2;

use craterfield_field::Axis;
use craterfield_field::{Graph, Op};

use super::cull::op_children;
use craterfield_wgsl::fnv::Fnv64;

/// The fingerprint of `graph`.
pub(crate) fn fingerprint(graph: &Graph) -> u64 {
    let mut h = Fnv64::new();
    h.bytes(b"craterfield-graph2d-v1")
        .u32(graph.ops().len() as u32);
    for op in graph.ops() {
        h.u32(op_tag(op));
        hash_constants(&mut h, op);
        let children = op_children(op);
        h.u32(children.len() as u32);
        for c in children {
            h.u32(c.0);
        }
    }
    h.u32(graph.root().0);
    h.finish()
}

/// A distinct number per operation kind.
fn op_tag(op: &Op) -> u32 {
    match op {
        Op::Circle { .. } => 1,
        Op::Box { .. } => 2,
        Op::RoundedBox { .. } => 3,
        Op::OrientedBox { .. } => 4,
        Op::Capsule { .. } => 5,
        Op::Polygon { .. } => 6,
        Op::Ellipse { .. } => 7,
        Op::Ring { .. } => 8,
        Op::Arc { .. } => 9,
        Op::HalfPlane { .. } => 10,
        Op::Height { .. } => 11,
        Op::Union(_) => 12,
        Op::Intersection(_) => 13,
        Op::Subtract(..) => 14,
        Op::SmoothUnion(..) => 15,
        Op::SmoothIntersection(..) => 16,
        Op::SmoothSubtract(..) => 17,
        Op::Round(..) => 18,
        Op::Onion(..) => 19,
        Op::Translate(..) => 20,
        Op::Rotate { .. } => 21,
        Op::Scale { .. } => 22,
        Op::Mirror { .. } => 23,
        Op::Repeat(_) => 24,
        Op::Noise { .. } => 25,
        Op::Wave { .. } => 26,
        Op::Material(..) => 27,
        Op::X => 28,
        Op::Y => 29,
        Op::Const(_) => 30,
        Op::Add(..) => 31,
        Op::Sub(..) => 32,
        Op::Mul(..) => 33,
        Op::Neg(_) => 34,
        Op::Square(_) => 35,
        Op::Sqrt(_) => 36,
    }
}

fn floats(h: &mut Fnv64, values: &[f32]) {
    h.u32(values.len() as u32);
    for &v in values {
        h.f32(v);
    }
}

fn points(h: &mut Fnv64, values: &[Vec2]) {
    h.u32(values.len() as u32);
    for v in values {
        h.f32(v.x).f32(v.y);
    }
}

/// Every constant the emitted code bakes in (children are hashed by the caller).
fn hash_constants(h: &mut Fnv64, op: &Op) {
    match op {
        Op::Circle { c, r } => floats(h, &[c.x, c.y, *r]),
        Op::Box { c, h: half } => floats(h, &[c.x, c.y, half.x, half.y]),
        Op::RoundedBox { c, inner, r } => floats(h, &[c.x, c.y, inner.x, inner.y, *r]),
        Op::OrientedBox { mid, dir, half } => {
            floats(h, &[mid.x, mid.y, dir.x, dir.y, half.x, half.y]);
        }
        Op::Capsule { a, ba, inv_ba2, r } => floats(h, &[a.x, a.y, ba.x, ba.y, *inv_ba2, *r]),
        Op::Polygon { pts, inv_e2 } => {
            points(h, pts);
            floats(h, inv_e2);
        }
        Op::Ellipse { c, radii } => floats(h, &[c.x, c.y, radii.x, radii.y]),
        Op::Ring { c, r, half_width } => floats(h, &[c.x, c.y, *r, *half_width]),
        Op::Arc { c, rot, sc, ra, rb } => {
            floats(h, &[c.x, c.y, rot.x, rot.y, sc.x, sc.y, *ra, *rb]);
        }
        Op::HalfPlane { n, offset } => floats(h, &[n.x, n.y, *offset]),
        Op::Height { pts, dx, inv_e2 } => {
            points(h, pts);
            floats(h, &[*dx]);
            floats(h, inv_e2);
        }
        Op::SmoothUnion(k, _) | Op::SmoothIntersection(k, _) | Op::SmoothSubtract(k, ..) => {
            floats(h, &[*k]);
        }
        Op::Round(v, _) | Op::Onion(v, _) | Op::Const(v) => floats(h, &[*v]),
        Op::Translate(t, _) => floats(h, &[t.x, t.y]),
        Op::Rotate { cos, sin, .. } => floats(h, &[*cos, *sin]),
        Op::Scale { factor, inv, .. } => floats(h, &[*factor, *inv]),
        Op::Mirror { axis, at, .. } => {
            h.u32(match axis {
                Axis::X => 0,
                Axis::Y => 1,
            });
            floats(h, &[*at]);
        }
        Op::Repeat(r) => {
            floats(
                h,
                &[
                    r.period.x,
                    r.period.y,
                    r.guard_c.x,
                    r.guard_c.y,
                    r.guard_h.x,
                    r.guard_h.y,
                    r.cap,
                    r.all_min.x,
                    r.all_min.y,
                    r.all_max.x,
                    r.all_max.y,
                ],
            );
            for v in [r.lo[0], r.lo[1], r.hi[0], r.hi[1]] {
                h.u32(v as u32);
            }
        }
        Op::Noise {
            amplitude,
            inv_wavelength,
            seed,
            ..
        } => {
            floats(h, &[*amplitude, *inv_wavelength]);
            h.u32(*seed);
        }
        Op::Wave {
            amplitude,
            k,
            phase,
            ..
        } => floats(h, &[*amplitude, k.x, k.y, *phase]),
        Op::Material(m, _) => {
            h.u32(u32::from(*m));
        }
        Op::Union(_)
        | Op::Intersection(_)
        | Op::Subtract(..)
        | Op::X
        | Op::Y
        | Op::Add(..)
        | Op::Sub(..)
        | Op::Mul(..)
        | Op::Neg(_)
        | Op::Square(_)
        | Op::Sqrt(_) => {}
    }
}
