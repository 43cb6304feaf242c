//! The one validator of a [`Plan`]: what the WGSL code generator and the CPU tracer both
//! need of it. A plan built by `march3d::compile` always passes; a plan built or edited by
//! hand gets a path-named error instead of a shader that misbehaves or a tracer that hangs.

use glam::Vec3;
use thiserror::Error;

use super::{
    AoMode, Lift, MAX_BOUNCES, MAX_MANDELBULB_ITERATIONS, MAX_OCTAVES, Node, Plan, Prim, PrimKind,
    Shading, ShadowMode, Shape, TerrainPlan,
};

/// Why a plan cannot be rendered.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum PlanError {
    /// A value that must be finite is not (only `far`, `escape`, bound radii and guard
    /// margins may be `+inf`; a negative bound radius is reported here too).
    #[error("plan value {what} is {value}, not a finite (or allowed infinite) value")]
    NonFinite {
        /// Which value.
        what: String,
        /// The value.
        value: f32,
    },
    /// A node or the terrain names a material the plan does not have.
    #[error("{what} uses material {index}, but the plan has {count} materials")]
    Material {
        /// Which part of the plan.
        what: String,
        /// The index used.
        index: u32,
        /// Materials in the plan.
        count: usize,
    },
    /// A count outside its documented range.
    #[error("plan value {what} is {value}: {expected}")]
    Range {
        /// Which value.
        what: String,
        /// The value.
        value: u64,
        /// What it should be.
        expected: &'static str,
    },
    /// A finite number outside its documented range.
    #[error("plan value {what} is {value}: it must be {expected}")]
    Invalid {
        /// Which value.
        what: String,
        /// The value.
        value: f32,
        /// What it should be.
        expected: &'static str,
    },
}

impl Plan {
    /// Checks what both renderers need of the plan: finite numbers (`far`, `escape` and
    /// bound radii may be `+inf`, a guard's margin too), positive steps and scales, material
    /// indices in range, and counts (octaves, rows, iterations, bounces) in range. The GPU
    /// code generator and the CPU tracer both refuse a plan this refuses, with this error.
    pub fn validate(&self) -> Result<(), PlanError> {
        check_plan(self)
    }
}

fn check_plan(plan: &Plan) -> Result<(), PlanError> {
    let m = &plan.march;
    for (what, v) in [
        ("march.hit", m.hit),
        ("march.hit_per_t", m.hit_per_t),
        ("march.step_factor", m.step_factor),
        ("march.ray_offset", m.ray_offset),
        ("march.normal_eps", m.normal_eps),
        ("march.relax", m.relax),
    ] {
        finite(what, v)?;
    }
    for (what, v) in [("march.far", m.far), ("march.escape", m.escape)] {
        if v.is_nan() || v == f32::NEG_INFINITY {
            return Err(PlanError::NonFinite {
                what: what.into(),
                value: v,
            });
        }
    }
    positive("march.step_factor", m.step_factor)?;
    positive("march.normal_eps", m.normal_eps)?;
    // `escape` may be `+inf` (never escape), but not zero or negative.
    if m.escape <= 0.0 {
        return Err(PlanError::Invalid {
            what: "march.escape".into(),
            value: m.escape,
            expected: "positive",
        });
    }
    if m.relax < 1.0 {
        return Err(PlanError::Invalid {
            what: "march.relax".into(),
            value: m.relax,
            expected: "at least 1",
        });
    }
    if let Some(top) = plan.early_out {
        finite("early_out", top)?;
    }
    let count = plan.materials.len();
    for (i, mat) in plan.materials.iter().enumerate() {
        finite_vec(&format!("materials[{i}].colour"), mat.colour)?;
        finite(&format!("materials[{i}].reflectivity"), mat.reflectivity)?;
    }
    if let Some(t) = &plan.terrain {
        check_terrain(t, count)?;
    }
    for (i, node) in plan.nodes.iter().enumerate() {
        check_node(i, node, count)?;
    }
    check_shading(&plan.shading)
}

fn finite(what: &str, value: f32) -> Result<(), PlanError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(PlanError::NonFinite {
            what: what.into(),
            value,
        })
    }
}

fn not_nan(what: &str, value: f32) -> Result<(), PlanError> {
    if value.is_nan() {
        Err(PlanError::NonFinite {
            what: what.into(),
            value,
        })
    } else {
        Ok(())
    }
}

fn positive(what: &str, value: f32) -> Result<(), PlanError> {
    finite(what, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(PlanError::Invalid {
            what: what.into(),
            value,
            expected: "positive",
        })
    }
}

fn finite_vec(what: &str, v: Vec3) -> Result<(), PlanError> {
    for (axis, c) in ["x", "y", "z"].iter().zip(v.to_array()) {
        finite(&format!("{what}.{axis}"), c)?;
    }
    Ok(())
}

fn material_in_range(what: &str, index: u32, count: usize) -> Result<(), PlanError> {
    if (index as usize) < count {
        Ok(())
    } else {
        Err(PlanError::Material {
            what: what.into(),
            index,
            count,
        })
    }
}

fn check_terrain(t: &TerrainPlan, count: usize) -> Result<(), PlanError> {
    material_in_range("terrain", t.material, count)?;
    let f = &t.fbm;
    for (what, v) in [
        ("terrain.base", f.base),
        ("terrain.amplitude", f.amplitude),
        ("terrain.frequency", f.frequency),
        ("terrain.lacunarity", f.lacunarity),
        ("terrain.gain", f.gain),
        ("terrain.rotation", f.rotation),
        ("terrain.step_scale", t.step_scale),
    ] {
        finite(what, v)?;
    }
    if !(1..=MAX_OCTAVES).contains(&f.octaves) {
        return Err(PlanError::Range {
            what: "terrain.octaves".into(),
            value: f.octaves.into(),
            expected: "1..=12",
        });
    }
    positive("terrain.frequency", f.frequency)?;
    positive("terrain.lacunarity", f.lacunarity)?;
    positive("terrain.step_scale", t.step_scale)
}

fn check_prim(what: &str, p: &Prim) -> Result<(), PlanError> {
    finite_vec(&format!("{what}.centre"), p.centre)?;
    if let Some(r) = p.rotation {
        for (i, c) in r.to_cols_array().iter().enumerate() {
            finite(&format!("{what}.rotation[{i}]"), *c)?;
        }
    }
    let scalars: Vec<f32> = match p.kind {
        PrimKind::Sphere { r } => vec![r],
        PrimKind::Box { half } => half.to_array().to_vec(),
        PrimKind::RoundBox { half, r } => vec![half.x, half.y, half.z, r],
        PrimKind::Capsule { a, b, r } => vec![a.x, a.y, a.z, b.x, b.y, b.z, r],
        PrimKind::Torus { major, minor } => vec![major, minor],
        PrimKind::Cylinder { r, h } => vec![r, h],
        PrimKind::CappedCone { h, r1, r2 } => vec![h, r1, r2],
        PrimKind::Octahedron { s } => vec![s],
        PrimKind::Ellipsoid { r } => r.to_array().to_vec(),
        PrimKind::Plane { normal, offset } => vec![normal.x, normal.y, normal.z, offset],
    };
    for v in scalars {
        finite(&format!("{what}.kind"), v)?;
    }
    match p.kind {
        PrimKind::CappedCone { h, .. } => positive(&format!("{what}.kind.h"), h),
        PrimKind::Ellipsoid { r } => positive(&format!("{what}.kind.r"), r.min_element()),
        _ => Ok(()),
    }
}

fn check_node(i: usize, node: &Node, count: usize) -> Result<(), PlanError> {
    let what = format!("nodes[{i}]");
    material_in_range(&what, node.material, count)?;
    match node.lift {
        Lift::None => {}
        Lift::Baked(y) => finite(&format!("{what}.lift"), y)?,
        Lift::Ground { x, z } => {
            finite(&format!("{what}.lift.x"), x)?;
            finite(&format!("{what}.lift.z"), z)?;
        }
    }
    if let Some(g) = &node.guard {
        finite_vec(&format!("{what}.guard.centre"), g.centre)?;
        finite_vec(&format!("{what}.guard.half"), g.half)?;
        not_nan(&format!("{what}.guard.margin"), g.margin)?;
    }
    finite_vec(&format!("{what}.bound.centre"), node.bound.centre)?;
    // An unbounded node (a plane) has an infinite bound radius.
    let radius = node.bound.radius;
    if radius.is_nan() || radius < 0.0 {
        return Err(PlanError::NonFinite {
            what: format!("{what}.bound.radius"),
            value: radius,
        });
    }
    match &node.shape {
        Shape::Prim(p) => check_prim(&what, p),
        Shape::Blend { k, parts } => {
            positive(&format!("{what}.k"), *k)?;
            if parts.is_empty() {
                return Err(PlanError::Range {
                    what: format!("{what}.parts"),
                    value: 0,
                    expected: "at least 1 part",
                });
            }
            parts.iter().try_for_each(|p| check_prim(&what, p))
        }
        Shape::Displaced { prim, amp, freq } => {
            finite(&format!("{what}.amp"), *amp)?;
            finite(&format!("{what}.freq"), *freq)?;
            check_prim(&what, prim)
        }
        Shape::Rows {
            part,
            spacing,
            count: rows,
            ..
        } => {
            positive(&format!("{what}.spacing"), *spacing)?;
            if *rows == 0 || *rows > i32::MAX as u32 {
                return Err(PlanError::Range {
                    what: format!("{what}.count"),
                    value: (*rows).into(),
                    expected: "at least 1 row",
                });
            }
            check_prim(&what, part)
        }
        Shape::Mandelbulb {
            centre,
            iterations,
            bailout,
            derivative,
        } => {
            finite(&format!("{what}.derivative"), *derivative)?;
            if *derivative <= 0.0 {
                return Err(PlanError::Invalid {
                    what: format!("{what}.derivative"),
                    value: *derivative,
                    expected: "positive",
                });
            }
            finite_vec(&format!("{what}.centre"), *centre)?;
            if *iterations > MAX_MANDELBULB_ITERATIONS {
                return Err(PlanError::Range {
                    what: format!("{what}.iterations"),
                    value: (*iterations).into(),
                    expected: "at most 64",
                });
            }
            finite(&format!("{what}.bailout"), *bailout)
        }
    }
}

fn check_shading(shading: &Shading) -> Result<(), PlanError> {
    match shading {
        Shading::Paper(s) => {
            if s.bounces > MAX_BOUNCES {
                return Err(PlanError::Range {
                    what: "bounces".into(),
                    value: s.bounces.into(),
                    expected: "at most 64",
                });
            }
            for (i, l) in s.lights.iter().enumerate() {
                finite_vec(&format!("lights[{i}].position"), l.position)?;
                finite(&format!("lights[{i}].emission"), l.emission)?;
            }
            for (what, v) in [
                ("shininess", s.shininess),
                ("specular", s.specular),
                ("ambient", s.ambient),
                ("reflection_scale", s.reflection_scale),
                ("fog", s.fog),
                ("gamma", s.gamma),
                ("shadow_k", s.shadow_k.unwrap_or(0.0)),
            ] {
                finite(what, v)?;
            }
        }
        Shading::World(w) => {
            finite_vec("sun", w.sun)?;
            finite_vec("sun_colour", w.sun_colour)?;
            finite_vec("sky[0]", w.sky[0])?;
            finite_vec("sky[1]", w.sky[1])?;
            finite("fog", w.fog)?;
            finite("gamma", w.gamma)?;
            if let AoMode::Adaptive { near_distance, .. } = w.ao {
                finite("ao.near_distance", near_distance)?;
            }
            match w.shadow {
                ShadowMode::Full { k, .. } => finite("shadow.k", k)?,
                ShadowMode::TerrainAndBounds { spacing, .. } => finite("shadow.spacing", spacing)?,
            }
        }
    }
    Ok(())
}
