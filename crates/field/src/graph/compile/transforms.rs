//! Lowering the operators with one child: offsets (round, onion), placements (translate,
//! rotate, scale, mirror, repeat), displacements and material tags. Each keeps or loosens
//! the child's facts as the operator allows.

use glam::Vec2;

use super::{Compiler, invalid};
use crate::aabb::Aabb;
use crate::error::LevelError;
use crate::graph::{Exactness, NodeInfo, Op, Repeat};
use crate::node::{Axis, Node, P2};
use crate::noise::NOISE_LIPSCHITZ;
use craterfield_core::det::math::{self, TAU, sin_cos_deg};

impl Compiler<'_> {
    /// The one-child operator `node` lowered, or `None` when it is not one.
    pub(super) fn transform(
        &mut self,
        node: &Node,
        path: &str,
        depth: usize,
    ) -> Result<Option<(Op, NodeInfo)>, LevelError> {
        Ok(Some(match node {
            Node::Round {
                radius,
                node: child,
            } => {
                let r = self.non_negative(path, "radius", *radius)?;
                let (id, ci) = self.child(child, path, depth)?;
                (
                    Op::Round(r, id),
                    NodeInfo {
                        exactness: Exactness::Bound,
                        bounds: ci.bounds.expand(r),
                        cost: ci.cost + 1,
                        ..ci
                    },
                )
            }
            Node::Onion { width, node: child } => {
                let w = self.positive(path, "width", *width)?;
                let (id, ci) = self.child(child, path, depth)?;
                (
                    Op::Onion(w, id),
                    NodeInfo {
                        exactness: Exactness::Bound,
                        bounds: ci.bounds.expand(w),
                        cost: ci.cost + 1,
                        ..ci
                    },
                )
            }
            Node::Translate {
                offset,
                node: child,
            } => {
                let t = self.point(path, "offset", *offset)?;
                let (id, ci) = self.child(child, path, depth)?;
                (
                    Op::Translate(t, id),
                    NodeInfo {
                        bounds: ci.bounds.translate(t),
                        cost: ci.cost + 1,
                        ..ci
                    },
                )
            }
            Node::Rotate {
                degrees,
                node: child,
            } => {
                let deg = self.num(path, "degrees", *degrees)?;
                let (sin, cos) = sin_cos_deg(deg);
                let (id, ci) = self.child(child, path, depth)?;
                (
                    Op::Rotate {
                        cos,
                        sin,
                        child: id,
                    },
                    NodeInfo {
                        bounds: ci.bounds.rotate(cos, sin),
                        cost: ci.cost + 1,
                        ..ci
                    },
                )
            }
            Node::Scale {
                factor,
                node: child,
            } => {
                let s = self.positive(path, "factor", *factor)?;
                if !(1e-4..=1e4).contains(&s) {
                    return Err(invalid(
                        path,
                        "factor",
                        format!("{s} is outside 1e-4 ..= 1e4"),
                    ));
                }
                let (id, ci) = self.child(child, path, depth)?;
                (
                    Op::Scale {
                        factor: s,
                        inv: 1.0 / s,
                        child: id,
                    },
                    NodeInfo {
                        bounds: ci.bounds.scale(s),
                        cost: ci.cost + 1,
                        ..ci
                    },
                )
            }
            Node::Mirror {
                axis,
                at,
                node: child,
            } => {
                let at = self.num(path, "at", *at)?;
                let (id, ci) = self.child(child, path, depth)?;
                let bounds = mirror_bounds(ci.bounds, *axis, at);
                (
                    Op::Mirror {
                        axis: *axis,
                        at,
                        child: id,
                    },
                    NodeInfo {
                        exactness: Exactness::Bound,
                        bounds,
                        cost: ci.cost + 1,
                        ..ci
                    },
                )
            }
            Node::Repeat {
                period,
                node: child,
            } => self.repeat(path, *period, None, child, depth)?,
            Node::RepeatFinite {
                period,
                count,
                node: child,
            } => self.repeat(path, *period, Some(*count), child, depth)?,
            Node::DisplaceNoise {
                amplitude,
                wavelength,
                seed,
                node: child,
            } => {
                let amp = self.non_negative(path, "amplitude", *amplitude)?;
                let wl = self.positive(path, "wavelength", *wavelength)?;
                let (id, ci) = self.child(child, path, depth)?;
                let inv = 1.0 / wl;
                let info = NodeInfo {
                    exactness: Exactness::Bound,
                    lipschitz: ci.lipschitz + amp * inv * NOISE_LIPSCHITZ,
                    bounds: ci.bounds.expand(amp),
                    cost: ci.cost + 2,
                };
                (
                    Op::Noise {
                        amplitude: amp,
                        inv_wavelength: inv,
                        seed: *seed,
                        child: id,
                    },
                    info,
                )
            }
            Node::DisplaceWave {
                amplitude,
                wavelength,
                direction,
                phase,
                node: child,
            } => {
                let amp = self.non_negative(path, "amplitude", *amplitude)?;
                let wl = self.positive(path, "wavelength", *wavelength)?;
                let dir = self.num(path, "direction", *direction)?;
                let phase = self.num(path, "phase", *phase)?;
                let (s, c) = sin_cos_deg(dir);
                let (id, ci) = self.child(child, path, depth)?;
                let info = NodeInfo {
                    exactness: Exactness::Bound,
                    // |∇ sin(2π t)| = 2π |∇t| and |∇t| = |dir| / wavelength (|dir| <= 1 + 1e-6).
                    lipschitz: ci.lipschitz + amp * TAU * 1.000_001 / wl,
                    bounds: ci.bounds.expand(amp),
                    cost: ci.cost + 2,
                };
                (
                    Op::Wave {
                        amplitude: amp,
                        k: Vec2::new(c, s) / wl,
                        phase,
                        child: id,
                    },
                    info,
                )
            }
            Node::Material {
                id: mat,
                node: child,
            } => {
                let (id, ci) = self.child(child, path, depth)?;
                (
                    Op::Material(*mat, id),
                    NodeInfo {
                        cost: ci.cost + 1,
                        ..ci
                    },
                )
            }
            _ => return Ok(None),
        }))
    }

    fn repeat(
        &mut self,
        path: &str,
        period: P2,
        count: Option<[u32; 2]>,
        child: &Node,
        depth: usize,
    ) -> Result<(Op, NodeInfo), LevelError> {
        let period = self.point(path, "period", period)?;
        for (axis, v) in [("x", period.x), ("y", period.y)] {
            if v < 0.0 {
                return Err(invalid(
                    path,
                    &format!("period.{axis}"),
                    format!("must not be negative, got {v}"),
                ));
            }
        }
        if period.x == 0.0 && period.y == 0.0 {
            return Err(invalid(
                path,
                "period",
                "must be positive on at least one axis".into(),
            ));
        }
        let (lo, hi) = match count {
            None => ([i32::MIN / 2; 2], [i32::MAX / 2; 2]),
            Some(c) => {
                for (axis, n, p) in [("x", c[0], period.x), ("y", c[1], period.y)] {
                    if n == 0 || n > 4096 {
                        return Err(invalid(
                            path,
                            &format!("count.{axis}"),
                            format!("must be in 1..=4096, got {n}"),
                        ));
                    }
                    if p == 0.0 && n != 1 {
                        return Err(invalid(
                            path,
                            &format!("count.{axis}"),
                            format!("must be 1 on an axis with period 0, got {n}"),
                        ));
                    }
                }
                ([0, 0], [c[0] as i32 - 1, c[1] as i32 - 1])
            }
        };
        let (id, ci) = self.child(child, path, depth)?;
        let b = ci.bounds;
        let mut guard_c = Vec2::ZERO;
        let mut guard_h = Vec2::ZERO;
        let mut cap = f32::INFINITY;
        for (axis, p, bmin, bmax, gi) in [
            ("x", period.x, b.min.x, b.max.x, 0),
            ("y", period.y, b.min.y, b.max.y, 1),
        ] {
            if p == 0.0 {
                continue;
            }
            if b.is_empty() || !(bmin >= -p * 0.5 && bmax <= p * 0.5) {
                return Err(invalid(
                    path,
                    "node",
                    format!(
                        "the child's bounds {bmin} ..= {bmax} on {axis} do not fit in one period [-{}, {}] around the origin",
                        p * 0.5,
                        p * 0.5
                    ),
                ));
            }
            guard_c[gi] = (bmin + bmax) * 0.5;
            guard_h[gi] = (bmax - bmin) * 0.5;
            cap = math::min(cap, p * 0.5);
        }
        let mut bounds = b;
        for axis in 0..2 {
            if period[axis] > 0.0 {
                if count.is_none() {
                    bounds.min[axis] = f32::NEG_INFINITY;
                    bounds.max[axis] = f32::INFINITY;
                } else {
                    bounds.max[axis] += period[axis] * hi[axis] as f32;
                }
            }
        }
        let instances: u64 = (0..2)
            .map(|a| if period[a] > 0.0 { 3 } else { 1 })
            .product();
        let info = NodeInfo {
            exactness: Exactness::Bound,
            lipschitz: math::max(ci.lipschitz, 1.0),
            bounds,
            cost: instances * (ci.cost + 1),
        };
        let (all_min, all_max) = (bounds.min, bounds.max);
        Ok((
            Op::Repeat(Box::new(Repeat {
                period,
                lo,
                hi,
                guard_c,
                guard_h,
                cap,
                all_min,
                all_max,
                child: id,
            })),
            info,
        ))
    }
}

fn mirror_bounds(b: Aabb, axis: Axis, at: f32) -> Aabb {
    let i = match axis {
        Axis::X => 0,
        Axis::Y => 1,
    };
    let hi = b.max[i];
    if b.is_empty() || hi < at {
        return Aabb::EMPTY;
    }
    let mut out = b;
    out.min[i] = 2.0 * at - hi;
    out
}
