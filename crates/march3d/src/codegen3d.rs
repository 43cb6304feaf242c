//! WGSL code generation for a 3D [`Plan`]: one complete compute module that renders the
//! plan exactly as `march3d::plan` specifies.
//!
//! Everything the plan decides is baked into the text: the march settings and shading
//! parameters become constants, the terrain's FBM a function with literal coefficients, and
//! each node a straight-line function (lift, guard, shape) with its coordinates as exact
//! literals. Only the camera and the image size come from the `MarchFrame` uniform. The
//! hand-written half (`shaders/march3d.wgsl`: primitives, noise, the march, normals,
//! shadows, shading) is appended; it refers to the emitted `em_` names.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::plan3d::{
    AoMode, EARLY_OUT_MARGIN, Guard, Hash, Lift, MAX_OCTAVES, Node, Plan, PlanError, Prim,
    PrimKind, SKY, Shading, ShadowMode, Shape, TerrainPlan,
};
use craterfield_wgsl::ShaderBudget;
use craterfield_wgsl::{NONFINITE_HELPER, f32_expr, f32_literal, u32_literal};
use glam::{Mat3, Vec3};

/// The hand-written half of the module.
pub const MARCH3D_WGSL: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/march3d.wgsl"));

/// The complete WGSL compute module rendering `plan` (entry point `main`, workgroup 8x8,
/// bindings: 0 the `MarchFrame` uniform, 1 an `rgba8unorm` storage texture).
pub fn march_wgsl(plan: &Plan) -> Result<String, PlanError> {
    plan.validate()?;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// Emitted by craterfield::emit::codegen3d for plan key {:#018x}.",
        plan.key
    );
    out.push_str(NONFINITE_HELPER);
    out.push_str(&constants(plan));
    out.push_str(&hashes(plan.hash));
    out.push_str(&height_fn(plan.terrain.as_ref()));
    for (i, node) in plan.nodes.iter().enumerate() {
        out.push_str(&node_fn(i, node));
    }
    out.push_str(&map_fns(plan));
    out.push_str(&material_fn(plan));
    out.push_str(&lights_fn(plan));
    out.push_str(&bounds_shadow_fn(plan));
    out.push_str(&ao_taps_fn(plan));
    out.push('\n');
    out.push_str(MARCH3D_WGSL);
    Ok(out)
}

/// What a plan's module may cost the GPU compiler that receives it: 1 MiB of text (as
/// for 2D) and 150,000 statements once every call from `main` is inlined
/// ([`march_inlined_statements`]).
///
/// Counted on the builtin scenes at 16:9, in statements: sparse 8,140 with every
/// optimization and 54,303 naive; forest 29,472 and 422,823. Naive with the portable hash,
/// as the GPU tests compare it, is 74,559 for sparse and 575,559 for forest. In a naive
/// plan every node computes the terrain's height, the normals take central differences, and
/// `main` inlines the scene distance about 15 times. That makes naive forest 14 to 20 times
/// forest. On an NVIDIA H200 (Vulkan) the GPU tests compiled and rendered naive sparse
/// (54,303), then stopped at naive forest for over 150 s, most likely in the driver's
/// compiler; the same driver took about 6 s for prospero's 6,603 statements (a 2D module).
/// The limit is twice the largest plan the tests render on a GPU (naive sparse, portable
/// hash) and well under naive forest. It also refuses forest without constant baking
/// (260,712).
pub const MARCH3D_BUDGET: ShaderBudget = ShaderBudget {
    max_bytes: 1 << 20,
    max_inlined_statements: 150_000,
};

/// Statements of `plan`'s emitted `module` ([`march_wgsl`]) once a GPU compiler has inlined
/// every call from the entry point `main`: [`inlined_statements`] with the shading model the
/// plan does not use left out (`main` branches on the constant `em_paper`, and every
/// compiler drops the constant-false side).
pub fn march_inlined_statements(plan: &Plan, module: &str) -> u64 {
    let unused = match plan.shading {
        Shading::Paper(_) => "world_shade",
        Shading::World(_) => "paper_shade",
    };
    inlined_statements(module, "main", &[unused])
}

/// Statements of a WGSL `module` once a GPU compiler has inlined every call reachable from
/// the function `entry`: each function's `;` plus, at every call site, its callee's inlined
/// count (functions named in `dropped` count nothing). Comments are skipped. A loop's body
/// counts once, although a compiler that unrolls it compiles more; that is what the budget's
/// margin is for. An `entry` the module does not define counts 0.
///
/// The 2D emitter counts its modules from the level graph before writing any text
/// (`TerrainEmitter::inlined_statements`); a 3D module's size comes from the hand-written
/// half as much as from the plan, so it is counted from the text.
pub fn inlined_statements(module: &str, entry: &str, dropped: &[&str]) -> u64 {
    let code = strip_comments(module);
    let functions = function_bodies(&code);
    let mut memo: HashMap<&str, u64> = dropped.iter().map(|&name| (name, 0)).collect();
    inlined_size(entry, &functions, &mut memo)
}

/// `module` with every `//` line comment and `/* */` block comment (which nest in WGSL)
/// replaced by a space, so a comment naming a function is not a call and its `;` no
/// statement.
fn strip_comments(module: &str) -> String {
    let mut out = String::with_capacity(module.len());
    let mut rest = module;
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix("//") {
            rest = after.find('\n').map_or("", |end| &after[end..]);
            out.push(' ');
        } else if rest.starts_with("/*") {
            let mut depth = 0usize;
            let mut end = rest.len();
            let bytes = rest.as_bytes();
            let mut i = 0;
            while i + 1 < bytes.len() {
                match &bytes[i..i + 2] {
                    b"/*" => {
                        depth += 1;
                        i += 2;
                    }
                    b"*/" => {
                        depth -= 1;
                        i += 2;
                        if depth == 0 {
                            end = i;
                            break;
                        }
                    }
                    _ => i += 1,
                }
            }
            rest = &rest[end..];
            out.push(' ');
        } else {
            let next = rest.find('/').map_or(rest.len(), |i| i.max(1));
            out.push_str(&rest[..next]);
            rest = &rest[next..];
        }
    }
    out
}

fn is_ident_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// Every function of comment-free WGSL `code`: its name and its body, braces included.
fn function_bodies(code: &str) -> HashMap<&str, &str> {
    let mut bodies = HashMap::new();
    let mut at = 0;
    while let Some(found) = code[at..].find("fn ") {
        let start = at + found;
        at = start + 3;
        // `fn` as a whole word: `main_fn ` does not start a function.
        if code[..start].chars().next_back().is_some_and(is_ident_char) {
            continue;
        }
        let head = code[at..].trim_start();
        let name_len = head.find(|c| !is_ident_char(c)).unwrap_or(head.len());
        let name = &head[..name_len];
        let Some(open) = code[at..].find('{').map(|i| at + i) else {
            break;
        };
        let mut depth = 0usize;
        let mut close = code.len();
        for (i, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        close = open + i + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        if !name.is_empty() {
            bodies.insert(name, &code[open..close]);
        }
        at = close;
    }
    bodies
}

/// [`inlined_statements`] of the function `name`, memoized. WGSL has no recursion; a cycle
/// (an invalid module) counts its repeated call once rather than looping.
fn inlined_size<'a>(
    name: &'a str,
    functions: &HashMap<&'a str, &'a str>,
    memo: &mut HashMap<&'a str, u64>,
) -> u64 {
    if let Some(&n) = memo.get(name) {
        return n;
    }
    let Some(body) = functions.get(name).copied() else {
        return 0;
    };
    memo.insert(name, 0);
    let mut total = body.matches(';').count() as u64;
    let mut word = None;
    for (i, c) in body.char_indices() {
        match (is_ident_char(c), word) {
            (true, None) => word = Some(i),
            (false, Some(start)) => {
                word = None;
                let callee = &body[start..i];
                let called = body[i..].trim_start().starts_with('(');
                if called && functions.contains_key(callee) {
                    total = total.saturating_add(inlined_size(callee, functions, memo));
                }
            }
            _ => {}
        }
    }
    memo.insert(name, total);
    total
}

/// A literal of a value [`Plan::validate`] has proven finite.
fn lit(v: f32) -> String {
    f32_expr(v)
}

/// A constant's literal where `+inf` is allowed (`far`, `escape`): WGSL constants cannot be
/// infinite, and the largest finite `f32` answers every `x > limit` test the same for
/// finite `x`.
fn limit_lit(v: f32) -> String {
    f32_literal(v).unwrap_or_else(|_| f32_expr(f32::MAX))
}

fn vec3_lit(v: Vec3) -> String {
    format!("vec3<f32>({}, {}, {})", lit(v.x), lit(v.y), lit(v.z))
}

fn mat3_lit(m: &Mat3) -> String {
    // Both glam and WGSL store columns: the constructor takes them in order.
    let c = m.to_cols_array();
    let parts: Vec<String> = c.iter().map(|v| lit(*v)).collect();
    format!("mat3x3<f32>({})", parts.join(", "))
}

fn bool_lit(b: bool) -> &'static str {
    if b { "true" } else { "false" }
}

/// Every `em_` constant the hand-written half reads. Parameters of the shading model not in
/// use get neutral values (the branches that read them are compiled out).
fn constants(plan: &Plan) -> String {
    let m = &plan.march;
    let mut c: Vec<(&str, &str, String)> = vec![
        ("em_max_steps", "u32", u32_literal(m.max_steps)),
        ("em_hit", "f32", lit(m.hit)),
        ("em_hit_per_t", "f32", lit(m.hit_per_t)),
        ("em_far", "f32", limit_lit(m.far)),
        ("em_escape", "f32", limit_lit(m.escape)),
        ("em_step_factor", "f32", lit(m.step_factor)),
        ("em_ray_offset", "f32", lit(m.ray_offset)),
        ("em_normal_eps", "f32", lit(m.normal_eps)),
        ("em_relax", "f32", lit(m.relax)),
        (
            "em_material_ids",
            "bool",
            bool_lit(plan.material_ids).into(),
        ),
        (
            "em_has_terrain",
            "bool",
            bool_lit(plan.terrain.is_some()).into(),
        ),
        (
            "em_terrain_material",
            "u32",
            u32_literal(plan.terrain.map_or(SKY, |t| t.material)),
        ),
        (
            "em_analytic_normal",
            "bool",
            bool_lit(plan.terrain.is_some_and(|t| t.analytic_normal)).into(),
        ),
        (
            "em_terrain_top",
            "f32",
            lit(plan.terrain.map_or(0.0, |t| t.fbm.top())),
        ),
    ];
    c.extend(shading_constants(&plan.shading));
    let mut out = String::new();
    for (name, ty, value) in c {
        let _ = writeln!(out, "const {name}: {ty} = {value};");
    }
    out
}

fn shading_constants(shading: &Shading) -> Vec<(&'static str, &'static str, String)> {
    let zero = || lit(0.0);
    let zero3 = || vec3_lit(Vec3::ZERO);
    match shading {
        Shading::Paper(s) => vec![
            ("em_paper", "bool", "true".into()),
            ("em_ambient", "f32", lit(s.ambient)),
            ("em_specular", "f32", lit(s.specular)),
            ("em_shininess", "f32", lit(s.shininess)),
            ("em_fog", "f32", lit(s.fog)),
            ("em_gamma", "f32", lit(s.gamma)),
            ("em_bounces", "u32", u32_literal(s.bounces)),
            ("em_reflection_scale", "f32", lit(s.reflection_scale)),
            (
                "em_paper_shadows",
                "bool",
                bool_lit(s.shadow_k.is_some()).into(),
            ),
            ("em_shadow_k", "f32", lit(s.shadow_k.unwrap_or(0.0))),
            ("em_sky0", "vec3<f32>", zero3()),
            ("em_sky1", "vec3<f32>", zero3()),
            ("em_sun", "vec3<f32>", zero3()),
            ("em_sun_colour", "vec3<f32>", zero3()),
            ("em_full_shadow", "bool", "false".into()),
            ("em_shadow_steps", "u32", u32_literal(0)),
            ("em_shadow_spacing", "f32", zero()),
        ],
        Shading::World(w) => {
            let (full, steps, k, spacing) = match w.shadow {
                ShadowMode::Full { steps, k } => (true, steps, k, 0.0),
                ShadowMode::TerrainAndBounds { steps, spacing } => (false, steps, 0.0, spacing),
            };
            vec![
                ("em_paper", "bool", "false".into()),
                ("em_ambient", "f32", zero()),
                ("em_specular", "f32", zero()),
                ("em_shininess", "f32", zero()),
                ("em_fog", "f32", lit(w.fog)),
                ("em_gamma", "f32", lit(w.gamma)),
                ("em_bounces", "u32", u32_literal(0)),
                ("em_reflection_scale", "f32", zero()),
                ("em_paper_shadows", "bool", "false".into()),
                ("em_shadow_k", "f32", lit(k)),
                ("em_sky0", "vec3<f32>", vec3_lit(w.sky[0])),
                ("em_sky1", "vec3<f32>", vec3_lit(w.sky[1])),
                ("em_sun", "vec3<f32>", vec3_lit(w.sun)),
                ("em_sun_colour", "vec3<f32>", vec3_lit(w.sun_colour)),
                ("em_full_shadow", "bool", bool_lit(full).into()),
                ("em_shadow_steps", "u32", u32_literal(steps)),
                ("em_shadow_spacing", "f32", lit(spacing)),
            ]
        }
    }
}

fn hashes(hash: Hash) -> String {
    let (h2, h3) = match hash {
        Hash::DotFract => ("hash2_dot_fract", "hash3_dot_fract"),
        Hash::Sin => ("hash2_sin", "hash3_sin"),
    };
    format!(
        "fn em_hash2(q: vec2<f32>) -> f32 {{\n    return {h2}(q);\n}}\n\
         fn em_hash3(q: vec3<f32>) -> f32 {{\n    return {h3}(q);\n}}\n"
    )
}

/// `em_height(xz) -> (h, dh/dx, dh/dz)`: `Fbm::height` unrolled over its octaves. Each
/// octave's weight `amplitude * gain^o` and its `amplitude * gain^o * J_o^T` (with `J_o =
/// frequency * (lacunarity R)^o`) are computed in `f64` here and baked as `f32` literals, as
/// the CPU tracer does, so both sum the same rounded coefficients.
fn height_fn(terrain: Option<&TerrainPlan>) -> String {
    let Some(t) = terrain else {
        return "// No terrain: objects stand on y = 0 (never called for the terrain).\n\
                fn em_height(x: vec2<f32>) -> vec3<f32> {\n    return vec3<f32>(0.0);\n}\n"
            .into();
    };
    let f = &t.fbm;
    let octaves = f.octaves.clamp(1, MAX_OCTAVES) as usize;
    let (sin, cos) = f64::from(f.rotation).sin_cos();
    let lac = f64::from(f.lacunarity);
    let (a, b) = (lac * cos, lac * sin);
    let (al, bl) = (lit(a as f32), lit(b as f32));
    let mut j = [f64::from(f.frequency), 0.0, 0.0, f64::from(f.frequency)];
    let mut w = f64::from(f.amplitude);
    let mut out = String::from("fn em_height(x: vec2<f32>) -> vec3<f32> {\n");
    let _ = writeln!(out, "    var q = x * {};", lit(f.frequency));
    let _ = writeln!(out, "    var h = {};", lit(f.base));
    out.push_str("    var g = vec2<f32>(0.0);\n    var n: vec3<f32>;\n");
    for o in 0..octaves {
        let jt = [w * j[0], w * j[2], w * j[1], w * j[3]].map(|v| lit(v as f32));
        let _ = writeln!(out, "    n = noise2(q);");
        let _ = writeln!(out, "    h += {} * n.x;", lit(w as f32));
        let _ = writeln!(
            out,
            "    g += vec2<f32>({} * n.y + {} * n.z, {} * n.y + {} * n.z);",
            jt[0], jt[1], jt[2], jt[3]
        );
        if o + 1 < octaves {
            let _ = writeln!(
                out,
                "    q = vec2<f32>({al} * q.x - {bl} * q.y, {bl} * q.x + {al} * q.y);"
            );
        }
        j = [
            a * j[0] - b * j[2],
            a * j[1] - b * j[3],
            b * j[0] + a * j[2],
            b * j[1] + a * j[3],
        ];
        w *= f64::from(f.gain);
    }
    out.push_str("    return vec3<f32>(h, g);\n}\n");
    out
}

/// The distance of `prim` at the node-local point named `p`.
fn prim_expr(prim: &Prim, p: &str) -> String {
    let moved = if prim.centre == Vec3::ZERO {
        p.to_string()
    } else {
        format!("({p} - {})", vec3_lit(prim.centre))
    };
    let local = match &prim.rotation {
        Some(r) => format!("({} * {moved})", mat3_lit(r)),
        None => moved,
    };
    match prim.kind {
        PrimKind::Sphere { r } => format!("sd_sphere({local}, {})", lit(r)),
        PrimKind::Box { half } => format!("sd_box({local}, {})", vec3_lit(half)),
        PrimKind::RoundBox { half, r } => {
            format!("sd_round_box({local}, {}, {})", vec3_lit(half), lit(r))
        }
        // A zero-length capsule is a sphere (the segment formula would divide by zero).
        PrimKind::Capsule { a, b, r } if a == b => {
            format!("sd_sphere({local} - {}, {})", vec3_lit(a), lit(r))
        }
        PrimKind::Capsule { a, b, r } => format!(
            "sd_capsule({local}, {}, {}, {})",
            vec3_lit(a),
            vec3_lit(b),
            lit(r)
        ),
        PrimKind::Torus { major, minor } => {
            format!("sd_torus({local}, {}, {})", lit(major), lit(minor))
        }
        PrimKind::Cylinder { r, h } => format!("sd_cylinder({local}, {}, {})", lit(r), lit(h)),
        PrimKind::CappedCone { h, r1, r2 } => format!(
            "sd_capped_cone({local}, {}, {}, {})",
            lit(h),
            lit(r1),
            lit(r2)
        ),
        PrimKind::Octahedron { s } => format!("sd_octahedron({local}, {})", lit(s)),
        PrimKind::Ellipsoid { r } => format!("sd_ellipsoid({local}, {})", vec3_lit(r)),
        PrimKind::Plane { normal, offset } => {
            format!("sd_plane({local}, {}, {})", vec3_lit(normal), lit(offset))
        }
    }
}

/// `fn em_node<i>(pw) -> f32`: lift, guard, then the shape, straight-line.
fn node_fn(i: usize, node: &Node) -> String {
    let mut out = format!("fn em_node{i}(pw: vec3<f32>) -> f32 {{\n");
    match node.lift {
        Lift::None => out.push_str("    let p = pw;\n"),
        Lift::Baked(y) => {
            let _ = writeln!(out, "    let p = pw - vec3<f32>(0.0, {}, 0.0);", lit(y));
        }
        Lift::Ground { x, z } => {
            let _ = writeln!(
                out,
                "    let p = pw - vec3<f32>(0.0, em_height(vec2<f32>({}, {})).x, 0.0);",
                lit(x),
                lit(z)
            );
        }
    }
    if let Some(g) = &node.guard {
        out.push_str(&guard_code(g));
    }
    out.push_str(&shape_code(&node.shape));
    out.push_str("}\n");
    out
}

fn guard_code(g: &Guard) -> String {
    format!(
        "    let db = guard_distance(p, {}, {});\n    if (db > {}) {{\n        return db;\n    }}\n",
        vec3_lit(g.centre),
        vec3_lit(g.half),
        lit(g.margin)
    )
}

fn shape_code(shape: &Shape) -> String {
    match shape {
        Shape::Prim(prim) => format!("    return {};\n", prim_expr(prim, "p")),
        Shape::Blend { k, parts } => blend_code(*k, parts),
        Shape::Displaced { prim, amp, freq } => {
            let scale = 1.0 / (1.0 + amp * freq * crate::plan3d::VALUE_NOISE3_SLOPE);
            format!(
                "    return ({} + {} * (noise3(p * {}) - 0.5)) * {};\n",
                prim_expr(prim, "p"),
                lit(*amp),
                lit(*freq),
                lit(scale)
            )
        }
        Shape::Rows {
            part,
            spacing,
            count,
            nearest,
        } => rows_code(part, *spacing, *count, *nearest),
        Shape::Mandelbulb {
            centre,
            iterations,
            bailout,
            derivative,
        } => format!(
            "    return sd_mandelbulb(p, {}, {}, {}, {});\n",
            vec3_lit(*centre),
            u32_literal(*iterations),
            lit(*bailout),
            lit(*derivative)
        ),
    }
}

fn blend_code(k: f32, parts: &[Prim]) -> String {
    let Some((first, rest)) = parts.split_first() else {
        // No parts: nothing there.
        return format!("    return {};\n", f32_expr(f32::INFINITY));
    };
    let mut out = format!("    var d = {};\n", prim_expr(first, "p"));
    for part in rest {
        // With k = 0 the smooth minimum is the plain minimum (its formula would divide 0 by 0).
        if k > 0.0 {
            let _ = writeln!(
                out,
                "    d = smin(d, {}, {});",
                prim_expr(part, "p"),
                lit(k)
            );
        } else {
            let _ = writeln!(out, "    d = min(d, {});", prim_expr(part, "p"));
        }
    }
    out.push_str("    return d;\n");
    out
}

fn rows_code(part: &Prim, spacing: f32, count: u32, nearest: bool) -> String {
    let sp = lit(spacing);
    let row = |index: &str| prim_expr(part, &format!("(p - vec3<f32>(0.0, 0.0, {index} * {sp}))"));
    let last = lit((count - 1) as f32);
    if nearest {
        let mut out = format!("    let z = p.z - {};\n", lit(part.centre.z));
        let _ = writeln!(out, "    let c = clamp(round(z / {sp}), 0.0, {last});");
        let _ = writeln!(out, "    var d = {};", row("c"));
        let _ = writeln!(out, "    let nb = c + sign(z - c * {sp});");
        let _ = writeln!(
            out,
            "    if (nb != c && nb >= 0.0 && nb <= {last}) {{\n        let dn = {};\n        if (dn < d) {{\n            d = dn;\n        }}\n    }}",
            row("nb")
        );
        out.push_str("    return d;\n");
        out
    } else {
        let mut out = format!("    var d = {};\n", row("0.0"));
        let _ = writeln!(
            out,
            "    for (var i = 1u; i < {}; i++) {{\n        let dn = {};\n        if (dn < d) {{\n            d = dn;\n        }}\n    }}",
            u32_literal(count),
            row("f32(i)")
        );
        out.push_str("    return d;\n");
        out
    }
}

/// `em_map` (distance and material) and `em_dist` (distance only), the scene distance of
/// the plan's module doc.
fn map_fns(plan: &Plan) -> String {
    let mut out = String::new();
    for (name, ret, with_material) in [("em_map", "MapHit", true), ("em_dist", "f32", false)] {
        let _ = writeln!(out, "fn {name}(p: vec3<f32>) -> {ret} {{");
        let _ = writeln!(out, "    var d = {};", f32_expr(f32::INFINITY));
        out.push_str("    var m = SKY;\n");
        if let Some(t) = &plan.terrain {
            let _ = writeln!(
                out,
                "    d = (p.y - em_height(p.xz).x) * {};\n    m = {};",
                lit(t.step_scale),
                u32_literal(t.material)
            );
        }
        let result = if with_material { "MapHit(d, m)" } else { "d" };
        if let Some(top) = plan.early_out {
            let _ = writeln!(
                out,
                "    if (p.y > {above}) {{\n        let e = p.y - {top};\n        if (e < d) {{\n            d = e;\n            m = SKY;\n        }}\n        return {result};\n    }}",
                top = lit(top),
                above = lit(top + EARLY_OUT_MARGIN)
            );
        }
        for (i, node) in plan.nodes.iter().enumerate() {
            let _ = writeln!(
                out,
                "    let d{i} = em_node{i}(p);\n    if (d{i} < d) {{\n        d = d{i};\n        m = {};\n    }}",
                u32_literal(node.material)
            );
        }
        let _ = writeln!(out, "    return {result};\n}}");
    }
    out
}

fn material_fn(plan: &Plan) -> String {
    let mut out = String::from("fn em_material(m: u32) -> Look {\n    switch m {\n");
    for (i, mat) in plan.materials.iter().enumerate() {
        let _ = writeln!(
            out,
            "        case {}: {{\n            return Look({}, {});\n        }}",
            u32_literal(i as u32),
            vec3_lit(mat.colour),
            lit(mat.reflectivity)
        );
    }
    out.push_str(
        "        default: {\n            return Look(vec3<f32>(0.0), 0.0);\n        }\n    }\n}\n",
    );
    out
}

/// `em_lights`: the paper's lights, one call each, summed in order.
fn lights_fn(plan: &Plan) -> String {
    let mut out = String::from(
        "fn em_lights(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> Lit {\n    var sum = Lit(0.0, 0.0);\n",
    );
    if let Shading::Paper(s) = &plan.shading {
        for l in &s.lights {
            let _ = writeln!(
                out,
                "    {{\n        let one = point_light(p, n, dir, {}, {});\n        sum.diffuse += one.diffuse;\n        sum.specular += one.specular;\n    }}",
                vec3_lit(l.position),
                lit(l.emission)
            );
        }
    }
    out.push_str("    return sum;\n}\n");
    out
}

/// `em_bounds_shadow(o)`: whether the sun ray from `o` meets a node's bounding sphere ahead.
/// One test per node, or-ed into one flag: written with an early `return` per node, a
/// forest's 132 tests lost the shadows of its last twenty nodes on lavapipe (2.5% of its
/// pixels off the CPU tracer's; 0.007% this way).
fn bounds_shadow_fn(plan: &Plan) -> String {
    let mut out =
        String::from("fn em_bounds_shadow(o: vec3<f32>) -> bool {\n    var meets = false;\n");
    let uses_bounds = matches!(
        &plan.shading,
        Shading::World(w) if matches!(w.shadow, ShadowMode::TerrainAndBounds { .. })
    );
    if uses_bounds {
        for node in &plan.nodes {
            let b = &node.bound;
            let _ = writeln!(
                out,
                "    {{\n        let oc = {} - o;\n        let b = dot(oc, em_sun);\n        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - {});\n    }}",
                vec3_lit(b.centre),
                lit(b.radius * b.radius)
            );
        }
    }
    out.push_str("    return meets;\n}\n");
    out
}

/// `em_ao_taps(p, n, t, m)`: the number of occlusion taps of a hit.
fn ao_taps_fn(plan: &Plan) -> String {
    let mut out =
        String::from("fn em_ao_taps(p: vec3<f32>, n: vec3<f32>, t: f32, m: u32) -> u32 {\n");
    match &plan.shading {
        Shading::Paper(_) => out.push_str("    return 0u;\n"),
        Shading::World(w) => match w.ao {
            AoMode::Fixed(taps) => {
                let _ = writeln!(out, "    return {};", u32_literal(taps));
            }
            AoMode::Adaptive {
                near,
                far,
                near_distance,
            } => {
                // Flat terrain lying above the eye: none.
                out.push_str(
                    "    if (em_has_terrain && m == em_terrain_material && n.y > 0.9 && p.y > frame.position.y) {\n        return 0u;\n    }\n",
                );
                let _ = writeln!(
                    out,
                    "    if (t < {}) {{\n        return {};\n    }}\n    return {};",
                    lit(near_distance),
                    u32_literal(near),
                    u32_literal(far)
                );
            }
        },
    }
    out.push_str("}\n");
    out
}
