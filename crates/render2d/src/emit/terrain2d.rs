//! The 2D terrain emitter: a compiled level graph to the WGSL function
//!
//! ```wgsl
//! fn base_sample(p: vec2<f32>) -> vec4<f32>   // (distance, d/dx, d/dy, f32(material))
//! ```
//!
//! the same as [`Sdf::sample`](craterfield_field::Sdf::sample) of the graph's root, unclamped.
//! The text is a module fragment (no entry points, no bindings); every other name it defines
//! at module scope starts with `em_`. Constants are baked in as exact literals. The GPU may
//! fuse multiply-adds and its division and square root are not always correctly rounded,
//! so results agree with the CPU to a few ulps, not bit for bit.
//!
//! [`TerrainEmitter::plan`] culls the graph to a view ([`super::cull`]);
//! [`TerrainEmitter::emit`] writes the module for a plan, deterministically: the same plan
//! gives byte-identical text, and [`CullPlan::key`] names that text for a
//! `gpu::PipelineCache`.

use craterfield_field::{Aabb, Graph};

use super::codegen2d::{emit_module, inlined_statements};
use super::cull::{self, CullPlan, GraphFacts};
use super::fingerprint2d::fingerprint;
use craterfield_wgsl::{EmitError, ShaderBudget};

/// Emits WGSL for one compiled level graph.
#[derive(Clone, Debug)]
pub struct TerrainEmitter {
    graph: Graph,
    deficits: Vec<Option<f32>>,
    fingerprint: u64,
    reachable: usize,
}

impl TerrainEmitter {
    /// An emitter for `graph` (copied), with its fingerprint computed once.
    pub fn new(graph: &Graph) -> TerrainEmitter {
        TerrainEmitter {
            graph: graph.clone(),
            deficits: cull::box_deficits(graph),
            fingerprint: fingerprint(graph),
            reachable: cull::reachable_count(graph),
        }
    }

    /// The graph this emitter writes.
    pub fn graph(&self) -> &Graph {
        &self.graph
    }

    /// Stable 64-bit hash of the graph's content (operations, constants' bits, structure).
    pub fn fingerprint(&self) -> u64 {
        self.fingerprint
    }

    /// The plan for an SDF pass covering the world rectangle `view` whose results are clamped
    /// to `[-band, band]`; `None` keeps everything. A view that is empty or not finite, or a
    /// band that is negative or not finite, also keeps everything (always correct).
    pub fn plan(&self, view: Option<Aabb>, band: f32) -> CullPlan {
        let facts = GraphFacts {
            graph: &self.graph,
            deficits: &self.deficits,
            fingerprint: self.fingerprint,
            reachable: self.reachable,
        };
        cull::plan(&facts, view, band)
    }

    /// Statements of the module for `plan` once a GPU compiler has inlined every call
    /// (each call site of a shared context copies it).
    pub fn inlined_statements(&self, plan: &CullPlan) -> u64 {
        if plan.fingerprint != self.fingerprint || plan.fates.len() != self.graph.ops().len() {
            return inlined_statements(&self.graph, &self.plan(None, 0.0).fates);
        }
        inlined_statements(&self.graph, &plan.fates)
    }

    /// [`TerrainEmitter::emit`], refusing a module past `budget` (what a renderer hands
    /// a driver goes through this). The inlined size is checked before any text is
    /// written.
    pub fn emit_within(&self, plan: &CullPlan, budget: &ShaderBudget) -> Result<String, EmitError> {
        budget.check_inlined(self.inlined_statements(plan))?;
        let text = self.emit(plan);
        budget.check_text(&text)?;
        Ok(text)
    }

    /// The WGSL module fragment for `plan`. A plan made for another graph (its fingerprint
    /// differs) is not applied: the unculled module is written, which is right for this one.
    /// Nothing is checked: see [`TerrainEmitter::emit_within`].
    pub fn emit(&self, plan: &CullPlan) -> String {
        if plan.fingerprint != self.fingerprint || plan.fates.len() != self.graph.ops().len() {
            let own = self.plan(None, 0.0);
            return emit_module(&self.graph, &own.fates, own.key, self.fingerprint);
        }
        emit_module(&self.graph, &plan.fates, plan.key, self.fingerprint)
    }
}
