//! The WGSL of the passes: hand-written sources from `shaders/` plus the emitted base field,
//! assembled into one module per pipeline.

/// Uniforms, full-screen triangle and lattice helpers.
pub const COMMON: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/common.wgsl"));
/// The explosion grid and events over the emitted `base_sample`.
pub const FIELD: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/field.wgsl"));
/// Pass 1.
pub const SDF_PASS: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/sdf_pass.wgsl"
));
/// Pass 2.
pub const RECONSTRUCT: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/reconstruct.wgsl"
));
/// The shading formula.
pub const SHADE: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/shade.wgsl"));
/// Pass 3.
pub const UPSAMPLE: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/upsample.wgsl"
));
/// Full-resolution direct evaluation.
pub const DIRECT: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/direct.wgsl"));

fn join(parts: &[&str]) -> String {
    parts.join("\n")
}

/// Pass 1 over the emitted base field.
pub fn sdf_module(base_field: &str) -> String {
    join(&[COMMON, base_field, FIELD, SDF_PASS])
}

/// Full-resolution direct evaluation over the emitted base field.
pub fn direct_module(base_field: &str) -> String {
    join(&[COMMON, base_field, FIELD, SHADE, DIRECT])
}

/// Pass 2.
pub fn reconstruct_module() -> String {
    join(&[COMMON, RECONSTRUCT])
}

/// Pass 3.
pub fn upsample_module() -> String {
    join(&[COMMON, SHADE, UPSAMPLE])
}
