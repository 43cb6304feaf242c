//! WGSL code generation for a planned 2D level graph.
//!
//! Nodes evaluated at the same query point share one *context*: a function
//! `em_c<id>(px, py) -> vec4<f32>` (point coordinates as dual numbers in, dual distance and
//! material out) whose body is straight-line `let`s, one per node, children before parents,
//! so a node shared inside the DAG is computed once. Domain operators (translate, rotate,
//! scale, mirror, repeat) move the query point: their child starts a context of its own,
//! called with the moved point. Polygons, height profiles and repetitions get a module-scope
//! function each (their loops index constant arrays held in private variables, which every
//! backend can index at run time). Materials that are known when emitting are folded into
//! constants, so only unions of differently painted children select a material at run time.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use glam::Vec2;

use craterfield_field::Axis;
use craterfield_field::{Graph, NodeId, Op, Repeat};

use super::cull::{Fate, op_children};
use super::helpers2d::used_helpers;
use craterfield_wgsl::{f32_expr, i32_literal, vec2_expr};

/// Material of a node's result: known when emitting, or a WGSL `f32` expression.
#[derive(Clone, Debug, PartialEq)]
enum Mat {
    Known(u16),
    Runtime(String),
}

impl Mat {
    fn text(&self) -> String {
        match self {
            Mat::Known(m) => f32_expr(f32::from(*m)),
            Mat::Runtime(e) => e.clone(),
        }
    }
}

/// Which operand's material a fold keeps.
#[derive(Clone, Copy, PartialEq)]
enum FoldMaterial {
    /// The operand with the smaller value (ties: the later one), as `Union` does.
    Winner,
    /// The first operand's.
    First,
}

/// Statements a GPU compiler sees once it has inlined every call of the module rooted at
/// the graph's root: each context's own nodes plus, per call site of a context, that
/// context's inlined size. The text shares a node used at several moved points (each a
/// separate call), but a driver that inlines calls copies it once per call site, so a DAG
/// whose shared nodes are called from several places grows exponentially there.
pub(crate) fn inlined_statements(graph: &Graph, fates: &[Fate]) -> u64 {
    let module = Module {
        graph,
        fates,
        items: BTreeMap::new(),
        context_material: BTreeMap::new(),
    };
    let mut inlined: BTreeMap<u32, u64> = BTreeMap::new();
    // Ascending: every context only calls contexts of lower ids (see `emit_module`).
    for root in context_roots(graph, fates) {
        let mut total = 0u64;
        for id in module.members(root) {
            total = total.saturating_add(1);
            let op = &graph.ops()[id as usize];
            if fates[id as usize] == Fate::Far {
                continue;
            }
            if let Some(child) = domain_child(op) {
                let callee = inlined.get(&child.0).copied().unwrap_or(1);
                total = total.saturating_add(callee);
            }
        }
        inlined.insert(root, total);
    }
    inlined.get(&graph.root().0).copied().unwrap_or(1)
}

/// The whole module for `graph` under `fates`.
pub(crate) fn emit_module(graph: &Graph, fates: &[Fate], key: u64, fingerprint: u64) -> String {
    let mut module = Module {
        graph,
        fates,
        items: BTreeMap::new(),
        context_material: BTreeMap::new(),
    };
    let mut functions = String::new();
    // A context's root has a lower id than every domain operator calling it, and each
    // context only calls contexts of lower ids: ascending order emits callees first.
    for root in context_roots(graph, fates) {
        functions.push_str(&module.context(root));
    }
    let root = graph.root().0;
    let _ = write!(
        functions,
        "fn base_sample(p: vec2<f32>) -> vec4<f32> {{\n    \
         return em_c{root}(vec3<f32>(p.x, 1.0, 0.0), vec3<f32>(p.y, 0.0, 1.0));\n}}\n"
    );
    let items: String = module.items.values().map(String::as_str).collect();
    let body = format!("{items}{functions}");
    format!(
        "// Emitted by craterfield from a level graph: do not edit.\n\
         // graph fingerprint {fingerprint:016x}, plan key {key:016x}.\n\
         // base_sample(p) = (distance, d/dx, d/dy, material) of the terrain graph at p.\n\n\
         {}\n{body}",
        used_helpers(&body)
    )
}

/// Roots of all contexts: the graph root and the child of every evaluated domain operator.
fn context_roots(graph: &Graph, fates: &[Fate]) -> BTreeSet<u32> {
    let mut roots = BTreeSet::from([graph.root().0]);
    for (i, op) in graph.ops().iter().enumerate() {
        if fates[i] == Fate::Unreached || fates[i] == Fate::Far {
            continue;
        }
        if let Some(child) = domain_child(op) {
            roots.insert(child.0);
        }
    }
    roots
}

/// The child of a domain operator (evaluated at a moved point), or `None`.
fn domain_child(op: &Op) -> Option<NodeId> {
    match op {
        Op::Translate(_, c) => Some(*c),
        Op::Rotate { child, .. } | Op::Scale { child, .. } | Op::Mirror { child, .. } => {
            Some(*child)
        }
        Op::Repeat(r) => Some(r.child),
        _ => None,
    }
}

struct Module<'a> {
    graph: &'a Graph,
    fates: &'a [Fate],
    /// Module-scope functions and arrays of single nodes, by node id.
    items: BTreeMap<u32, String>,
    /// The material each emitted context returns, where known when emitting.
    context_material: BTreeMap<u32, Option<u16>>,
}

impl Module<'_> {
    /// The function of the context rooted at `root`.
    fn context(&mut self, root: u32) -> String {
        let mut body = Body {
            lines: String::new(),
            mats: BTreeMap::new(),
        };
        for id in self.members(root) {
            let mat = self.node(&mut body, id);
            body.mats.insert(id, mat);
        }
        let mat = body.mats[&root].clone();
        let known = match mat {
            Mat::Known(m) => Some(m),
            Mat::Runtime(_) => None,
        };
        self.context_material.insert(root, known);
        format!(
            "fn em_c{root}(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {{\n{}    return vec4<f32>(d{root}, {});\n}}\n\n",
            body.lines,
            mat.text()
        )
    }

    /// Nodes of the context rooted at `root`, ascending (children before parents).
    fn members(&self, root: u32) -> BTreeSet<u32> {
        let mut seen = BTreeSet::new();
        let mut stack = vec![root];
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            let fate = &self.fates[id as usize];
            let op = &self.graph.ops()[id as usize];
            if *fate == Fate::Far || domain_child(op).is_some() {
                continue;
            }
            for (j, child) in op_children(op).into_iter().enumerate() {
                if !fate.drops(j) {
                    stack.push(child.0);
                }
            }
        }
        seen
    }

    /// Emit node `id` into `body`; returns its material.
    fn node(&mut self, body: &mut Body, id: u32) -> Mat {
        if self.fates[id as usize] == Fate::Far {
            body.let_d(id, "em_far".into());
            return Mat::Known(0);
        }
        let op = &self.graph.ops()[id as usize];
        if let Some(mat) = self.primitive(body, id, op) {
            return mat;
        }
        if let Some(mat) = self.domain(body, id, op) {
            return mat;
        }
        self.combination(body, id, op)
    }

    /// Primitives and expression leaves: material 0.
    fn primitive(&mut self, body: &mut Body, id: u32, op: &Op) -> Option<Mat> {
        let f = f32_expr;
        let v = vec2_expr;
        let expr = match op {
            Op::Circle { c, r } => format!("em_circle(px, py, {}, {})", v(*c), f(*r)),
            Op::Box { c, h } => format!("em_aabox(px, py, {}, {})", v(*c), v(*h)),
            Op::RoundedBox { c, inner, r } => format!(
                "em_off(em_aabox(px, py, {}, {}), {})",
                v(*c),
                v(*inner),
                f(-r)
            ),
            Op::OrientedBox { mid, dir, half } => {
                format!("em_obox(px, py, {}, {}, {})", v(*mid), v(*dir), v(*half))
            }
            Op::Capsule { a, ba, inv_ba2, r } => format!(
                "em_capsule(px, py, {}, {}, {}, {})",
                v(*a),
                v(*ba),
                f(*inv_ba2),
                f(*r)
            ),
            Op::Polygon { pts, inv_e2 } => {
                self.items.insert(id, polygon_item(id, pts, inv_e2));
                format!("em_poly{id}(px, py)")
            }
            Op::Ellipse { c, radii } => format!("em_ellipse(px, py, {}, {})", v(*c), v(*radii)),
            Op::Ring { c, r, half_width } => {
                format!("em_ring(px, py, {}, {}, {})", v(*c), f(*r), f(*half_width))
            }
            Op::Arc { c, rot, sc, ra, rb } => format!(
                "em_arc(px, py, {}, {}, {}, {}, {}, {})",
                v(*c),
                v(*rot),
                v(*sc),
                v(*sc * *ra),
                f(*ra),
                f(*rb)
            ),
            Op::HalfPlane { n, offset } => {
                format!("em_off(px * {} + py * {}, {})", f(n.x), f(n.y), f(-offset))
            }
            Op::Height { pts, dx, inv_e2 } => {
                self.items.insert(id, height_item(id, pts, *dx, inv_e2));
                format!("em_hp{id}(px, py)")
            }
            Op::X => "px".into(),
            Op::Y => "py".into(),
            Op::Const(c) => format!("vec3<f32>({}, 0.0, 0.0)", f(*c)),
            _ => return None,
        };
        body.let_d(id, expr);
        Some(Mat::Known(0))
    }

    /// Domain operators: call the child's context at the moved point.
    fn domain(&mut self, body: &mut Body, id: u32, op: &Op) -> Option<Mat> {
        let f = f32_expr;
        let (child, call, factor) = match op {
            Op::Translate(t, c) => (
                *c,
                format!("em_off(px, {}), em_off(py, {})", f(-t.x), f(-t.y)),
                None,
            ),
            Op::Rotate { cos, sin, child } => (
                *child,
                format!(
                    "px * {c} + py * {s}, py * {c} - px * {s}",
                    c = f(*cos),
                    s = f(*sin)
                ),
                None,
            ),
            Op::Scale { factor, inv, child } => (
                *child,
                format!("px * {i}, py * {i}", i = f(*inv)),
                Some(*factor),
            ),
            Op::Mirror { axis, at, child } => {
                let fold = |v: &str| format!("em_off(em_abs(em_off({v}, {})), {})", f(-at), f(*at));
                let args = match axis {
                    Axis::X => format!("{}, py", fold("px")),
                    Axis::Y => format!("px, {}", fold("py")),
                };
                (*child, args, None)
            }
            Op::Repeat(r) => {
                self.items.insert(id, repeat_item(id, r));
                let _ = writeln!(body.lines, "    let r{id} = em_rep{id}(px, py);");
                body.let_d(id, format!("r{id}.xyz"));
                // Instances that win carry the child's material; the cap carries 0.
                return Some(match self.context_material.get(&r.child.0) {
                    Some(Some(0)) => Mat::Known(0),
                    _ => Mat::Runtime(format!("r{id}.w")),
                });
            }
            _ => return None,
        };
        let _ = writeln!(body.lines, "    let r{id} = em_c{}({call});", child.0);
        let value = match factor {
            Some(s) => format!("r{id}.xyz * {}", f(s)),
            None => format!("r{id}.xyz"),
        };
        body.let_d(id, value);
        Some(match self.context_material.get(&child.0) {
            Some(Some(m)) => Mat::Known(*m),
            _ => Mat::Runtime(format!("r{id}.w")),
        })
    }

    /// Booleans, shape operators, displacements, material and arithmetic.
    fn combination(&mut self, body: &mut Body, id: u32, op: &Op) -> Mat {
        let f = f32_expr;
        let fate = &self.fates[id as usize];
        let d = |c: &NodeId| format!("d{}", c.0);
        let first = |body: &Body, c: &NodeId| body.mats[&c.0].clone();
        let kept = |ids: &[NodeId]| -> Vec<NodeId> {
            ids.iter()
                .enumerate()
                .filter(|(j, _)| !fate.drops(*j))
                .map(|(_, c)| *c)
                .collect()
        };
        let (expr, mat) = match op {
            Op::Union(ids) => {
                return body.fold(id, &kept(ids), FoldMaterial::Winner, |a, b| {
                    format!("em_min({a}, {b})")
                });
            }
            Op::SmoothUnion(k, ids) => {
                let (k, q) = (f(*k), f(k * 0.25));
                return body.fold(id, &kept(ids), FoldMaterial::Winner, |a, b| {
                    format!("em_smin({a}, {b}, {k}, {q})")
                });
            }
            Op::Intersection(ids) => {
                return body.fold(id, ids, FoldMaterial::First, |a, b| {
                    format!("em_max({a}, {b})")
                });
            }
            Op::SmoothIntersection(k, ids) => {
                let (k, q) = (f(*k), f(k * 0.25));
                return body.fold(id, ids, FoldMaterial::First, |a, b| {
                    format!("em_smax({a}, {b}, {k}, {q})")
                });
            }
            Op::Subtract(a, _) | Op::SmoothSubtract(_, a, _) if fate.drops(1) => {
                (d(a), first(body, a))
            }
            Op::Subtract(a, b) => (format!("em_max({}, -{})", d(a), d(b)), first(body, a)),
            Op::SmoothSubtract(k, a, b) => (
                format!("em_smax({}, -{}, {}, {})", d(a), d(b), f(*k), f(k * 0.25)),
                first(body, a),
            ),
            Op::Round(r, c) => (format!("em_off({}, {})", d(c), f(-r)), first(body, c)),
            Op::Onion(w, c) => (
                format!("em_off(em_abs({}), {})", d(c), f(-w)),
                first(body, c),
            ),
            Op::Noise {
                amplitude,
                inv_wavelength,
                seed,
                child,
            } => (
                format!(
                    "{} + em_noise(px * {i}, py * {i}, {seed}u) * {}",
                    d(child),
                    f(*amplitude),
                    i = f(*inv_wavelength)
                ),
                first(body, child),
            ),
            Op::Wave {
                amplitude,
                k,
                phase,
                child,
            } => (
                format!(
                    "{} + em_wave(em_off(px * {} + py * {}, {})) * {}",
                    d(child),
                    f(k.x),
                    f(k.y),
                    f(*phase),
                    f(*amplitude)
                ),
                first(body, child),
            ),
            Op::Material(m, c) => (d(c), Mat::Known(*m)),
            Op::Add(a, b) => (format!("{} + {}", d(a), d(b)), first(body, a)),
            Op::Sub(a, b) => (format!("{} - {}", d(a), d(b)), first(body, a)),
            Op::Mul(a, b) => (format!("em_mul({}, {})", d(a), d(b)), first(body, a)),
            Op::Neg(a) => (format!("-{}", d(a)), first(body, a)),
            Op::Square(a) => (format!("em_mul({0}, {0})", d(a)), first(body, a)),
            Op::Sqrt(a) => (format!("em_sqrt({})", d(a)), first(body, a)),
            // Primitives and domain operators are handled before.
            _ => ("em_far".into(), Mat::Known(0)),
        };
        body.let_d(id, expr);
        mat
    }
}

/// The lines of one context function and the materials of its nodes so far.
struct Body {
    lines: String,
    mats: BTreeMap<u32, Mat>,
}

impl Body {
    fn let_d(&mut self, id: u32, expr: String) {
        let _ = writeln!(self.lines, "    let d{id} = {expr};");
    }

    /// Left fold of `ids` with `combine`, as the CPU's `fold`: one `let` per step.
    fn fold(
        &mut self,
        id: u32,
        ids: &[NodeId],
        material: FoldMaterial,
        combine: impl Fn(&str, &str) -> String,
    ) -> Mat {
        let Some((first, rest)) = ids.split_first() else {
            // Every child dropped is planned as far; an empty list never reaches here.
            self.let_d(id, "em_far".into());
            return Mat::Known(0);
        };
        let mut acc = format!("d{}", first.0);
        let mut mat = self.mats[&first.0].clone();
        if rest.is_empty() {
            self.let_d(id, acc);
            return mat;
        }
        for (step, next) in rest.iter().enumerate() {
            let last = step + 1 == rest.len();
            let name = if last {
                format!("d{id}")
            } else {
                format!("d{id}_{step}")
            };
            let next_d = format!("d{}", next.0);
            let _ = writeln!(self.lines, "    let {name} = {};", combine(&acc, &next_d));
            let next_mat = self.mats[&next.0].clone();
            if material == FoldMaterial::Winner && next_mat != mat {
                let m_name = format!("m{}", &name[1..]);
                let _ = writeln!(
                    self.lines,
                    "    let {m_name} = select({}, {}, {acc}.x < {next_d}.x);",
                    next_mat.text(),
                    mat.text()
                );
                mat = Mat::Runtime(m_name);
            }
            acc = name;
        }
        mat
    }
}

/// One vertex record per line: `vec3<f32>(x, y, w)`.
fn vec3_rows(rows: impl Iterator<Item = (Vec2, f32)>) -> String {
    rows.map(|(p, w)| {
        format!(
            "    vec3<f32>({}, {}, {}),\n",
            f32_expr(p.x),
            f32_expr(p.y),
            f32_expr(w)
        )
    })
    .collect()
}

/// `primitives::polygon` for one polygon: vertices with `inv_e2` of the edge ending at each.
fn polygon_item(id: u32, pts: &[Vec2], inv_e2: &[f32]) -> String {
    let n = pts.len();
    let rows = vec3_rows(pts.iter().copied().zip(inv_e2.iter().copied()));
    format!(
        "var<private> em_poly{id}_v: array<vec3<f32>, {n}> = array<vec3<f32>, {n}>(\n{rows});\n\n\
         fn em_poly{id}(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {{\n    \
         let first = em_poly{id}_v[0];\n    \
         var d2 = em_len2(em_off(px, -first.x), em_off(py, -first.y));\n    \
         var inside = false;\n    \
         var j = {last}u;\n    \
         for (var i = 0u; i < {n}u; i++) {{\n        \
         let vi = em_poly{id}_v[i];\n        \
         let vj = em_poly{id}_v[j];\n        \
         let e = vj.xy - vi.xy;\n        \
         let wx = em_off(px, -vi.x);\n        \
         let wy = em_off(py, -vi.y);\n        \
         d2 = em_min(d2, em_seg2(wx, wy, e, vi.z));\n        \
         // Crossing parity, so the winding does not matter.\n        \
         let c1 = py.x >= vi.y;\n        \
         let c2 = py.x < vj.y;\n        \
         let c3 = e.x * wy.x > e.y * wx.x;\n        \
         if ((c1 && c2 && c3) || (!c1 && !c2 && !c3)) {{\n            \
         inside = !inside;\n        \
         }}\n        \
         j = i;\n    \
         }}\n    \
         let d = em_sqrt(d2);\n    \
         return select(d, -d, inside);\n\
         }}\n\n",
        last = n - 1
    )
}

/// `primitives::height_profile` for one profile: only the segments within reach of the
/// query point are visited, as on the CPU.
fn height_item(id: u32, pts: &[Vec2], dx: f32, inv_e2: &[f32]) -> String {
    let n = pts.len();
    let (first, last) = (pts[0], pts[n - 1]);
    let rows = vec3_rows(
        pts.iter()
            .copied()
            .zip(inv_e2.iter().copied().chain(std::iter::once(0.0))),
    );
    let f = f32_expr;
    let (x0, y0, xl, yl) = (f(first.x), f(first.y), f(last.x), f(last.y));
    let (dx, segments) = (f(dx), n - 1);
    format!(
        "var<private> em_hp{id}_v: array<vec3<f32>, {n}> = array<vec3<f32>, {n}>(\n{rows});\n\n\
         fn em_hp{id}(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {{\n    \
         let x = px.x;\n    \
         let y = py.x;\n    \
         // At or left of the first sample (and for NaN) the ground is the first height.\n    \
         var ground = {y0};\n    \
         if (x >= {xl}) {{\n        \
         ground = {yl};\n    \
         }} else if (x > {x0}) {{\n        \
         let s = em_hp_index(x, {x0}, {dx}, {segments}u);\n        \
         let a = em_hp{id}_v[s];\n        \
         let b = em_hp{id}_v[s + 1u];\n        \
         ground = a.y + (b.y - a.y) * ((x - a.x) / (b.x - a.x));\n    \
         }}\n    \
         let reach = abs(y - ground);\n    \
         // The largest finite f32 stands in for the CPU's infinity: every segment is nearer.\n    \
         var d2 = vec3<f32>({max}, 0.0, 0.0);\n    \
         if (x < {x0}) {{\n        \
         let dy = em_off(py, {ny0});\n        \
         d2 = em_mul(dy, dy);\n    \
         }}\n    \
         if (x > {xl}) {{\n        \
         let dy = em_off(py, {nyl});\n        \
         d2 = em_min(d2, em_mul(dy, dy));\n    \
         }}\n    \
         let lo0 = em_hp_index(x - reach, {x0}, {dx}, {segments}u);\n    \
         let lo = select(lo0 - 1u, 0u, lo0 == 0u);\n    \
         let hi = min(em_hp_index(x + reach, {x0}, {dx}, {segments}u) + 1u, {last_segment}u);\n    \
         for (var s = lo; s <= hi; s++) {{\n        \
         let a = em_hp{id}_v[s];\n        \
         let b = em_hp{id}_v[s + 1u];\n        \
         d2 = em_min(d2, em_seg2(em_off(px, -a.x), em_off(py, -a.y), b.xy - a.xy, a.z));\n    \
         }}\n    \
         let d = em_sqrt(d2);\n    \
         return select(d, -d, y < ground);\n\
         }}\n\n",
        max = f(f32::MAX),
        ny0 = f(-first.y),
        nyl = f(-last.y),
        last_segment = segments - 1,
    )
}

/// `eval::repeat` for one repetition: the 3x3 (or 3x1) neighbourhood of the nearest
/// instance, each guarded by its box, capped by the box of all instances.
fn repeat_item(id: u32, r: &Repeat) -> String {
    let f = f32_expr;
    let child = r.child.0;
    let mut text = format!("fn em_rep{id}(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {{\n");
    let axes = [("x", "px", 0usize), ("y", "py", 1usize)];
    for (name, p, a) in axes {
        if r.period[a] > 0.0 {
            let (lo, hi) = (i32_literal(r.lo[a]), i32_literal(r.hi[a]));
            let _ = write!(
                text,
                "    let k{name} = clamp(em_sat_i32(floor({p}.x / {} + 0.5)), {lo}, {hi});\n    \
                 let {name}0 = max(k{name} - 1, {lo});\n    \
                 let {name}1 = min(k{name} + 1, {hi});\n",
                f(r.period[a])
            );
        }
    }
    let axis = |p: &str, a: usize| {
        let zero = "vec3<f32>(0.0)".to_string();
        let (lo, hi) = (r.all_min[a], r.all_max[a]);
        if !lo.is_finite() && !hi.is_finite() {
            // max(max(0, 0), 0): a constant zero on an axis unbounded both ways.
            return zero;
        }
        let below = if lo.is_finite() {
            format!("vec3<f32>({}, 0.0, 0.0) - {p}", f(lo))
        } else {
            zero.clone()
        };
        let above = if hi.is_finite() {
            format!("em_off({p}, {})", f(-hi))
        } else {
            zero.clone()
        };
        format!("em_max(em_max({below}, {above}), {zero})")
    };
    let _ = writeln!(
        text,
        "    var best = vec4<f32>(em_max(vec3<f32>({}, 0.0, 0.0), em_len({}, {})), 0.0);",
        f(r.cap),
        axis("px", 0),
        axis("py", 1)
    );
    let (rx, ry) = (r.period.x > 0.0, r.period.y > 0.0);
    let mut indent = String::from("    ");
    for (name, repeated) in [("y", ry), ("x", rx)] {
        if repeated {
            let _ = writeln!(
                text,
                "{indent}for (var i{name} = {name}0; i{name} <= {name}1; i{name}++) {{"
            );
            indent.push_str("    ");
        }
    }
    let moved = |p: &str, name: &str, a: usize, repeated: bool| {
        if repeated {
            format!("em_off({p}, -(f32(i{name}) * {}))", f(r.period[a]))
        } else {
            p.to_string()
        }
    };
    let guard = match (rx, ry) {
        (true, true) => format!(
            "em_aabox(qx, qy, {}, {})",
            vec2_expr(r.guard_c),
            vec2_expr(r.guard_h)
        ),
        (true, false) => format!(
            "em_off(em_abs(em_off(qx, {})), {})",
            f(-r.guard_c.x),
            f(-r.guard_h.x)
        ),
        _ => format!(
            "em_off(em_abs(em_off(qy, {})), {})",
            f(-r.guard_c.y),
            f(-r.guard_h.y)
        ),
    };
    let _ = write!(
        text,
        "{indent}let qx = {};\n\
         {indent}let qy = {};\n\
         {indent}let r = em_c{child}(qx, qy);\n\
         {indent}let g = em_max(r.xyz, {guard});\n\
         {indent}if (g.x < best.x) {{\n\
         {indent}    best = vec4<f32>(g, r.w);\n\
         {indent}}}\n",
        moved("px", "x", 0, rx),
        moved("py", "y", 1, ry)
    );
    for repeated in [rx, ry] {
        if repeated {
            indent.truncate(indent.len() - 4);
            let _ = writeln!(text, "{indent}}}");
        }
    }
    text.push_str("    return best;\n}\n\n");
    text
}
