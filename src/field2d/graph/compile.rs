//! The level compiler: a node tree (with named references) to a [`Graph`], validating every
//! value and computing each node's facts (exactness, Lipschitz bound, bounds, cost). Every
//! error names the node path of the first problem.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use glam::Vec2;

use super::{Exactness, Graph, GraphLimits, NodeId, NodeInfo, Op, Repeat};
use crate::det::math::{self, TAU, sin_cos_deg};
use crate::field2d::aabb::Aabb;
use crate::field2d::error::LevelError;
use crate::field2d::node::{Axis, Node, P2};
use crate::field2d::noise::NOISE_LIPSCHITZ;

impl Graph {
    /// Compile `root`, resolving `Ref`s against `named`, with the default limits.
    pub fn compile(root: &Node, named: &BTreeMap<String, Node>) -> Result<Graph, LevelError> {
        Graph::compile_with_limits(root, named, GraphLimits::default())
    }

    /// Compile with explicit limits.
    pub fn compile_with_limits(
        root: &Node,
        named: &BTreeMap<String, Node>,
        limits: GraphLimits,
    ) -> Result<Graph, LevelError> {
        let mut c = Compiler {
            ops: Vec::new(),
            info: Vec::new(),
            named,
            memo: BTreeMap::new(),
            stack: Vec::new(),
            limits,
        };
        let root = c.node(root, "root", 0)?;
        let cost = c.info[root.0 as usize].cost;
        if cost > limits.max_cost {
            return Err(LevelError::Limit {
                path: "root".into(),
                what: "evaluation cost",
                limit: limits.max_cost,
            });
        }
        Ok(Graph {
            ops: c.ops,
            info: c.info,
            root,
            program: OnceLock::new(),
        })
    }
}

struct Compiler<'a> {
    ops: Vec<Op>,
    info: Vec<NodeInfo>,
    named: &'a BTreeMap<String, Node>,
    memo: BTreeMap<String, NodeId>,
    stack: Vec<String>,
    limits: GraphLimits,
}

fn invalid(path: &str, field: &str, reason: String) -> LevelError {
    LevelError::Invalid {
        path: format!("{path}.{field}"),
        reason,
    }
}

impl Compiler<'_> {
    fn push(&mut self, op: Op, info: NodeInfo, path: &str) -> Result<NodeId, LevelError> {
        if self.ops.len() >= self.limits.max_nodes {
            return Err(LevelError::Limit {
                path: path.into(),
                what: "node count",
                limit: self.limits.max_nodes as u64,
            });
        }
        if info.cost > self.limits.max_cost {
            return Err(LevelError::Limit {
                path: path.into(),
                what: "evaluation cost",
                limit: self.limits.max_cost,
            });
        }
        self.ops.push(op);
        self.info.push(info);
        Ok(NodeId(self.ops.len() as u32 - 1))
    }

    fn info_of(&self, id: NodeId) -> NodeInfo {
        self.info[id.0 as usize]
    }

    fn num(&self, path: &str, field: &str, v: f32) -> Result<f32, LevelError> {
        if !v.is_finite() {
            return Err(invalid(
                path,
                field,
                format!("must be a finite number, got {v}"),
            ));
        }
        if v.abs() > self.limits.max_coordinate {
            return Err(invalid(
                path,
                field,
                format!(
                    "{v} is absurdly large (limit ±{})",
                    self.limits.max_coordinate
                ),
            ));
        }
        Ok(v)
    }

    fn positive(&self, path: &str, field: &str, v: f32) -> Result<f32, LevelError> {
        let v = self.num(path, field, v)?;
        if v <= 0.0 {
            return Err(invalid(path, field, format!("must be positive, got {v}")));
        }
        Ok(v)
    }

    fn non_negative(&self, path: &str, field: &str, v: f32) -> Result<f32, LevelError> {
        let v = self.num(path, field, v)?;
        if v < 0.0 {
            return Err(invalid(
                path,
                field,
                format!("must not be negative, got {v}"),
            ));
        }
        Ok(v)
    }

    fn point(&self, path: &str, field: &str, v: P2) -> Result<Vec2, LevelError> {
        Ok(Vec2::new(
            self.num(path, &format!("{field}.x"), v[0])?,
            self.num(path, &format!("{field}.y"), v[1])?,
        ))
    }

    fn primitive(op: Op, bounds: Aabb, cost: u64) -> (Op, NodeInfo) {
        (
            op,
            NodeInfo {
                exactness: Exactness::Exact,
                lipschitz: 1.0,
                bounds,
                cost,
            },
        )
    }

    fn node(&mut self, node: &Node, path: &str, depth: usize) -> Result<NodeId, LevelError> {
        if depth > self.limits.max_depth {
            return Err(LevelError::Limit {
                path: path.into(),
                what: "nesting depth",
                limit: self.limits.max_depth as u64,
            });
        }
        let path = if let Node::Ref(_) = node {
            path.to_string()
        } else {
            format!("{path}.{}", node.kind())
        };
        let path = path.as_str();
        if let Node::Ref(name) = node {
            return self.reference(name, path, depth);
        }
        let (op, info) = match node {
            Node::Circle { center, radius } => {
                let c = self.point(path, "center", *center)?;
                let r = self.positive(path, "radius", *radius)?;
                Self::primitive(Op::Circle { c, r }, Aabb::centered(c, Vec2::splat(r)), 1)
            }
            Node::Box { center, half_size } => {
                let c = self.point(path, "center", *center)?;
                let h = self.point(path, "half_size", *half_size)?;
                self.positive(path, "half_size.x", h.x)?;
                self.positive(path, "half_size.y", h.y)?;
                Self::primitive(Op::Box { c, h }, Aabb::centered(c, h), 1)
            }
            Node::RoundedBox {
                center,
                half_size,
                radius,
            } => {
                let c = self.point(path, "center", *center)?;
                let h = self.point(path, "half_size", *half_size)?;
                self.positive(path, "half_size.x", h.x)?;
                self.positive(path, "half_size.y", h.y)?;
                let r = self.non_negative(path, "radius", *radius)?;
                if r > h.x.min(h.y) {
                    return Err(invalid(
                        path,
                        "radius",
                        format!(
                            "{r} is larger than the smaller half extent {}",
                            h.x.min(h.y)
                        ),
                    ));
                }
                Self::primitive(
                    Op::RoundedBox {
                        c,
                        inner: h - Vec2::splat(r),
                        r,
                    },
                    Aabb::centered(c, h),
                    1,
                )
            }
            Node::OrientedBox { a, b, thickness } => {
                let a = self.point(path, "a", *a)?;
                let b = self.point(path, "b", *b)?;
                let th = self.positive(path, "thickness", *thickness)?;
                let len = (b - a).length();
                if len.is_nan() || len <= 0.0 {
                    return Err(invalid(path, "b", "is degenerate: a and b coincide".into()));
                }
                let dir = (b - a) / len;
                let half = Vec2::new(len * 0.5, th * 0.5);
                let mid = (a + b) * 0.5;
                let bounds = Aabb::of_points([a, b]).expand(th * 0.5);
                Self::primitive(Op::OrientedBox { mid, dir, half }, bounds, 1)
            }
            Node::Capsule { a, b, radius } => {
                let a = self.point(path, "a", *a)?;
                let b = self.point(path, "b", *b)?;
                let r = self.positive(path, "radius", *radius)?;
                let ba = b - a;
                let l2 = ba.dot(ba);
                let inv_ba2 = if l2 > 0.0 { 1.0 / l2 } else { 0.0 };
                Self::primitive(
                    Op::Capsule { a, ba, inv_ba2, r },
                    Aabb::of_points([a, b]).expand(r),
                    1,
                )
            }
            Node::Triangle { a, b, c } => {
                let pts = self.polygon_points(path, &[*a, *b, *c])?;
                self.polygon(pts)
            }
            Node::Polygon { points } => {
                let pts = self.polygon_points(path, points)?;
                self.polygon(pts)
            }
            Node::Ellipse { center, radii } => {
                let c = self.point(path, "center", *center)?;
                let r = self.point(path, "radii", *radii)?;
                self.positive(path, "radii.x", r.x)?;
                self.positive(path, "radii.y", r.y)?;
                if r.x.max(r.y) > 100.0 * r.x.min(r.y) {
                    return Err(invalid(
                        path,
                        "radii",
                        format!("axis ratio of {r} exceeds 100 (use a capsule or box)"),
                    ));
                }
                Self::primitive(Op::Ellipse { c, radii: r }, Aabb::centered(c, r), 3)
            }
            Node::Ring {
                center,
                radius,
                width,
            } => {
                let c = self.point(path, "center", *center)?;
                let r = self.positive(path, "radius", *radius)?;
                let w = self.positive(path, "width", *width)?;
                Self::primitive(
                    Op::Ring {
                        c,
                        r,
                        half_width: w * 0.5,
                    },
                    Aabb::centered(c, Vec2::splat(r + w * 0.5)),
                    1,
                )
            }
            Node::Arc {
                center,
                radius,
                width,
                aperture,
                rotation,
            } => {
                let c = self.point(path, "center", *center)?;
                let ra = self.positive(path, "radius", *radius)?;
                let w = self.positive(path, "width", *width)?;
                let ap = self.positive(path, "aperture", *aperture)?;
                if ap > 180.0 {
                    return Err(invalid(
                        path,
                        "aperture",
                        format!("must be at most 180 degrees, got {ap}"),
                    ));
                }
                let rot = self.num(path, "rotation", *rotation)?;
                let (s, co) = sin_cos_deg(ap);
                let (rs, rc) = sin_cos_deg(rot);
                let bounds = Aabb::centered(c, Vec2::splat(ra + w * 0.5));
                Self::primitive(
                    Op::Arc {
                        c,
                        rot: Vec2::new(rc, rs),
                        sc: Vec2::new(s, co),
                        ra,
                        rb: w * 0.5,
                    },
                    bounds,
                    1,
                )
            }
            Node::HalfPlane { point, normal } => {
                let p = self.point(path, "point", *point)?;
                let n = self.point(path, "normal", *normal)?;
                let len = n.length();
                if len.is_nan() || len <= 0.0 {
                    return Err(invalid(
                        path,
                        "normal",
                        "must not be the zero vector".into(),
                    ));
                }
                let n = n / len;
                let bounds = half_plane_bounds(n, p);
                Self::primitive(
                    Op::HalfPlane {
                        n,
                        offset: p.dot(n),
                    },
                    bounds,
                    1,
                )
            }
            Node::HeightProfile { x0, dx, heights } => {
                let x0 = self.num(path, "x0", *x0)?;
                let dx = self.positive(path, "dx", *dx)?;
                if heights.len() < 2 {
                    return Err(invalid(
                        path,
                        "heights",
                        format!("needs at least 2 samples, got {}", heights.len()),
                    ));
                }
                if heights.len() > self.limits.max_points {
                    return Err(invalid(
                        path,
                        "heights",
                        format!(
                            "{} samples exceed the limit of {}",
                            heights.len(),
                            self.limits.max_points
                        ),
                    ));
                }
                let mut pts = Vec::with_capacity(heights.len());
                for (i, &h) in heights.iter().enumerate() {
                    let y = self.num(path, &format!("heights[{i}]"), h)?;
                    pts.push(Vec2::new(x0 + dx * i as f32, y));
                }
                let last_x = pts[pts.len() - 1].x;
                self.num(path, "dx", last_x)?;
                let inv_e2: Vec<f32> = pts
                    .windows(2)
                    .map(|w| 1.0 / (w[1] - w[0]).length_squared())
                    .collect();
                let top = pts.iter().fold(f32::NEG_INFINITY, |m, p| math::max(m, p.y));
                let bounds = Aabb::new(
                    Vec2::new(f32::NEG_INFINITY, f32::NEG_INFINITY),
                    Vec2::new(f32::INFINITY, top),
                );
                Self::primitive(Op::Height { pts, dx, inv_e2 }, bounds, 8)
            }
            Node::Union(nodes) | Node::Intersection(nodes) => {
                let union = matches!(node, Node::Union(_));
                let ids = self.children(nodes, path, depth)?;
                let infos: Vec<NodeInfo> = ids.iter().map(|&i| self.info_of(i)).collect();
                let bounds = if union {
                    infos.iter().fold(Aabb::EMPTY, |b, i| b.union(&i.bounds))
                } else {
                    infos
                        .iter()
                        .fold(Aabb::EVERYTHING, |b, i| b.intersection(&i.bounds))
                };
                let info = combine(&infos, bounds, 0.0);
                (
                    if union {
                        Op::Union(ids)
                    } else {
                        Op::Intersection(ids)
                    },
                    info,
                )
            }
            Node::SmoothUnion { k, nodes } | Node::SmoothIntersection { k, nodes } => {
                let union = matches!(node, Node::SmoothUnion { .. });
                let k = self.positive(path, "k", *k)?;
                let ids = self.children(nodes, path, depth)?;
                let infos: Vec<NodeInfo> = ids.iter().map(|&i| self.info_of(i)).collect();
                let bounds = if union {
                    infos
                        .iter()
                        .fold(Aabb::EMPTY, |b, i| b.union(&i.bounds))
                        .expand(k * 0.25)
                } else {
                    infos
                        .iter()
                        .fold(Aabb::EVERYTHING, |b, i| b.intersection(&i.bounds))
                };
                let mut info = combine(&infos, bounds, 0.0);
                info.exactness = Exactness::Bound;
                (
                    if union {
                        Op::SmoothUnion(k, ids)
                    } else {
                        Op::SmoothIntersection(k, ids)
                    },
                    info,
                )
            }
            Node::Subtract { base, cut } | Node::SmoothSubtract { base, cut, .. } => {
                let k = match node {
                    Node::SmoothSubtract { k, .. } => Some(self.positive(path, "k", *k)?),
                    _ => None,
                };
                let a = self.node(base, &format!("{path}.base"), depth + 1)?;
                let b = self.node(cut, &format!("{path}.cut"), depth + 1)?;
                let (ia, ib) = (self.info_of(a), self.info_of(b));
                let mut info = combine(&[ia, ib], ia.bounds, 0.0);
                info.exactness = Exactness::Bound;
                (
                    match k {
                        Some(k) => Op::SmoothSubtract(k, a, b),
                        None => Op::Subtract(a, b),
                    },
                    info,
                )
            }
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
            Node::X | Node::Y | Node::Const(_) => self.expression_leaf(node, path)?,
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => {
                let ia = self.node(a, &format!("{path}[0]"), depth + 1)?;
                let ib = self.node(b, &format!("{path}[1]"), depth + 1)?;
                let (fa, fb) = (self.info_of(ia), self.info_of(ib));
                let lipschitz = match node {
                    Node::Mul(..) => mul_lipschitz(&self.ops, ia, fa, ib, fb),
                    _ => fa.lipschitz + fb.lipschitz,
                };
                let op = match node {
                    Node::Add(..) => Op::Add(ia, ib),
                    Node::Sub(..) => Op::Sub(ia, ib),
                    _ => Op::Mul(ia, ib),
                };
                (op, expression_info(lipschitz, fa.cost + fb.cost + 1))
            }
            Node::Neg(a) | Node::Square(a) | Node::Sqrt(a) => {
                let ia = self.node(a, &format!("{path}[0]"), depth + 1)?;
                let fa = self.info_of(ia);
                let (op, lipschitz) = match node {
                    Node::Neg(_) => (Op::Neg(ia), fa.lipschitz),
                    Node::Square(_) => (Op::Square(ia), square_lipschitz(fa)),
                    _ => (Op::Sqrt(ia), sqrt_lipschitz(&self.ops, &self.info, ia)),
                };
                (op, expression_info(lipschitz, fa.cost + 1))
            }
            Node::Ref(_) => unreachable!("references are resolved above"),
        };
        self.push(op, info, path)
    }

    fn expression_leaf(&self, node: &Node, path: &str) -> Result<(Op, NodeInfo), LevelError> {
        Ok(match node {
            Node::X => (Op::X, expression_info(1.0, 1)),
            Node::Y => (Op::Y, expression_info(1.0, 1)),
            Node::Const(c) => {
                // Constants of expressions are not coordinates: only finiteness is required.
                if !c.is_finite() {
                    return Err(LevelError::Invalid {
                        path: path.into(),
                        reason: format!("must be a finite number, got {c}"),
                    });
                }
                (Op::Const(*c), expression_info(0.0, 1))
            }
            _ => unreachable!("only called for expression leaves"),
        })
    }

    fn reference(&mut self, name: &str, path: &str, depth: usize) -> Result<NodeId, LevelError> {
        if let Some(&id) = self.memo.get(name) {
            return Ok(id);
        }
        if let Some(pos) = self.stack.iter().position(|n| n == name) {
            let mut cycle: Vec<&str> = self.stack[pos..].iter().map(String::as_str).collect();
            cycle.push(name);
            return Err(LevelError::Cycle {
                path: path.into(),
                cycle: cycle.join(" -> "),
            });
        }
        let Some(target) = self.named.get(name) else {
            let known: Vec<&str> = self.named.keys().map(String::as_str).collect();
            return Err(LevelError::UnknownRef {
                path: path.into(),
                name: name.into(),
                known: known.join(", "),
            });
        };
        self.stack.push(name.to_string());
        let id = self.node(target, &format!("nodes[\"{name}\"]"), depth + 1);
        self.stack.pop();
        let id = id?;
        self.memo.insert(name.to_string(), id);
        Ok(id)
    }

    fn child(
        &mut self,
        child: &Node,
        path: &str,
        depth: usize,
    ) -> Result<(NodeId, NodeInfo), LevelError> {
        let id = self.node(child, &format!("{path}.node"), depth + 1)?;
        Ok((id, self.info_of(id)))
    }

    fn children(
        &mut self,
        nodes: &[Node],
        path: &str,
        depth: usize,
    ) -> Result<Vec<NodeId>, LevelError> {
        if nodes.is_empty() {
            return Err(LevelError::Invalid {
                path: path.into(),
                reason: "needs at least one child".into(),
            });
        }
        nodes
            .iter()
            .enumerate()
            .map(|(i, n)| self.node(n, &format!("{path}[{i}]"), depth + 1))
            .collect()
    }

    fn polygon_points(&self, path: &str, points: &[P2]) -> Result<Vec<Vec2>, LevelError> {
        if points.len() < 3 {
            return Err(invalid(
                path,
                "points",
                format!("needs at least 3 vertices, got {}", points.len()),
            ));
        }
        if points.len() > self.limits.max_points {
            return Err(invalid(
                path,
                "points",
                format!(
                    "{} vertices exceed the limit of {}",
                    points.len(),
                    self.limits.max_points
                ),
            ));
        }
        let pts = points
            .iter()
            .enumerate()
            .map(|(i, p)| self.point(path, &format!("points[{i}]"), *p))
            .collect::<Result<Vec<_>, _>>()?;
        check_simple_polygon(&pts).map_err(|reason| invalid(path, "points", reason))?;
        Ok(pts)
    }

    fn polygon(&self, pts: Vec<Vec2>) -> (Op, NodeInfo) {
        let n = pts.len();
        let inv_e2 = (0..n)
            .map(|i| {
                let e = pts[(i + n - 1) % n] - pts[i];
                1.0 / e.length_squared()
            })
            .collect();
        let bounds = Aabb::of_points(pts.iter().copied());
        let cost = 1 + n as u64 / 4;
        Self::primitive(Op::Polygon { pts, inv_e2 }, bounds, cost)
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

/// Facts of an arithmetic expression node: a bound whose box is the whole plane.
fn expression_info(lipschitz: f32, cost: u64) -> NodeInfo {
    NodeInfo {
        exactness: Exactness::Bound,
        lipschitz,
        bounds: Aabb::EVERYTHING,
        cost,
    }
}

/// `|grad (a b)| <= |c| L` when one factor is the constant `c`; unbounded otherwise.
fn mul_lipschitz(ops: &[Op], ia: NodeId, fa: NodeInfo, ib: NodeId, fb: NodeInfo) -> f32 {
    let constant = |id: NodeId| match ops.get(id.0 as usize) {
        Some(Op::Const(c)) => Some(c.abs()),
        _ => None,
    };
    match (constant(ia), constant(ib)) {
        (Some(c), _) => c * fb.lipschitz,
        (_, Some(c)) => c * fa.lipschitz,
        _ if fa.lipschitz == 0.0 && fb.lipschitz == 0.0 => 0.0,
        _ => f32::INFINITY,
    }
}

/// A square has no global Lipschitz bound unless its argument is constant.
fn square_lipschitz(fa: NodeInfo) -> f32 {
    if fa.lipschitz == 0.0 {
        0.0
    } else {
        f32::INFINITY
    }
}

/// `sqrt(a² + b²)` is the norm of `(a, b)`: by Cauchy-Schwarz its gradient is at most
/// `sqrt(La² + Lb²)`. Any other square root has no global bound (its slope is unbounded
/// near zero) unless its argument is constant.
fn sqrt_lipschitz(ops: &[Op], info: &[NodeInfo], ia: NodeId) -> f32 {
    let at = |id: NodeId| ops.get(id.0 as usize);
    let lip = |id: NodeId| {
        info.get(id.0 as usize)
            .map_or(f32::INFINITY, |i| i.lipschitz)
    };
    if lip(ia) == 0.0 {
        return 0.0;
    }
    // (No let-chains: the deterministic core also builds with older cross toolchains.)
    match at(ia) {
        Some(Op::Add(s, t)) => match (at(*s), at(*t)) {
            (Some(Op::Square(a)), Some(Op::Square(b))) => {
                let (la, lb) = (lip(*a), lip(*b));
                (la * la + lb * lb).sqrt() * 1.000_001
            }
            _ => f32::INFINITY,
        },
        _ => f32::INFINITY,
    }
}

/// Info of an n-ary min/max combination.
fn combine(infos: &[NodeInfo], bounds: Aabb, extra_lipschitz: f32) -> NodeInfo {
    let exactness = if infos.len() == 1 {
        infos[0].exactness
    } else {
        Exactness::Bound
    };
    let lipschitz = infos.iter().fold(0.0f32, |m, i| math::max(m, i.lipschitz)) + extra_lipschitz;
    let cost = infos.iter().map(|i| i.cost).sum::<u64>() + infos.len() as u64;
    NodeInfo {
        exactness,
        lipschitz,
        bounds,
        cost,
    }
}

fn half_plane_bounds(n: Vec2, p: Vec2) -> Aabb {
    let mut b = Aabb::EVERYTHING;
    // Solid is dot(q - p, n) < 0; only axis-aligned normals give a finite side.
    if n.y == 0.0 {
        if n.x > 0.0 {
            b.max.x = p.x
        } else {
            b.min.x = p.x
        }
    } else if n.x == 0.0 {
        if n.y > 0.0 {
            b.max.y = p.y
        } else {
            b.min.y = p.y
        }
    }
    b
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

/// Checks that a polygon has non-zero area, no repeated consecutive vertices and no
/// intersecting non-adjacent edges (O(n²); the vertex count is limited).
fn check_simple_polygon(pts: &[Vec2]) -> Result<(), String> {
    let n = pts.len();
    for i in 0..n {
        if pts[i] == pts[(i + 1) % n] {
            return Err(format!(
                "degenerate polygon: vertices {i} and {} coincide at {}",
                (i + 1) % n,
                pts[i]
            ));
        }
    }
    let area2: f64 = (0..n)
        .map(|i| {
            let (a, b) = (pts[i].as_dvec2(), pts[(i + 1) % n].as_dvec2());
            a.x * b.y - b.x * a.y
        })
        .sum();
    if area2.abs() < 1e-9 {
        return Err("degenerate polygon: zero area".into());
    }
    if n > 4 {
        for i in 0..n {
            for j in i + 2..n {
                if i == 0 && j == n - 1 {
                    continue;
                }
                if segments_intersect(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n]) {
                    return Err(format!("polygon is not simple: edge {i} crosses edge {j}"));
                }
            }
        }
    } else if n == 4
        && (segments_intersect(pts[0], pts[1], pts[2], pts[3])
            || segments_intersect(pts[1], pts[2], pts[3], pts[0]))
    {
        return Err("polygon is not simple: its edges cross".into());
    }
    Ok(())
}

fn segments_intersect(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> bool {
    let (a, b, c, d) = (a.as_dvec2(), b.as_dvec2(), c.as_dvec2(), d.as_dvec2());
    let orient = |p: glam::DVec2, q: glam::DVec2, r: glam::DVec2| (q - p).perp_dot(r - p);
    let (o1, o2, o3, o4) = (
        orient(a, b, c),
        orient(a, b, d),
        orient(c, d, a),
        orient(c, d, b),
    );
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return true;
    }
    let on = |p: glam::DVec2, q: glam::DVec2, r: glam::DVec2, o: f64| {
        o == 0.0
            && r.x >= p.x.min(q.x)
            && r.x <= p.x.max(q.x)
            && r.y >= p.y.min(q.y)
            && r.y <= p.y.max(q.y)
    };
    on(a, b, c, o1) || on(a, b, d, o2) || on(c, d, a, o3) || on(c, d, b, o4)
}
