//! WGSL text shared by craterfield's shader emitters (the 2D terrain emitter of
//! `craterfield-render2d` and the 3D plan's code generator of `craterfield-march3d`): exact
//! number literals and module-scope names ([`literal`]), the stable hash behind fingerprints and
//! pipeline keys ([`fnv`]), and the budget an emitted module must fit ([`ShaderBudget`]).
//!
//! Plain text generation: no GPU types and no craterfield dependency, so that both emitters
//! build without `wgpu` and neither depends on the other.

#![forbid(unsafe_code)]

mod budget;
pub mod fnv;
pub mod literal;

pub use budget::{EmitError, ShaderBudget};
pub use literal::{
    NONFINITE_FN, NONFINITE_HELPER, PREFIX, WgslError, f32_expr, f32_literal, i32_literal,
    is_identifier, module_name, u32_literal, vec2_expr,
};
