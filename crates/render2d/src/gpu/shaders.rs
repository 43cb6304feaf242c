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

/// Mode refine: block grid, classes and counters.
pub const REFINE_COMMON: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/refine_common.wgsl"
));
/// Mode refine: the block proof.
pub const REFINE_PROOF: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/refine_proof.wgsl"
));
/// Mode refine: classification levels 0 and 1.
pub const REFINE_CLASSIFY: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/refine_classify.wgsl"
));
/// Mode refine: exact samples at the open blocks' corners.
pub const REFINE_CORNERS: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/refine_corners.wgsl"
));
/// Mode refine: the event-sign proof of the blocks the distance bounds left open.
pub const REFINE_SIGNS: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/refine_signs.wgsl"
));
/// Mode refine: the proven blocks drawn.
pub const REFINE_DRAW: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/refine_draw.wgsl"
));
/// Mode refine: the exact pass over the listed blocks.
pub const REFINE_EXACT: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/shaders/refine_exact.wgsl"
));

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

/// Mode refine, classification (`cs_classify`, `cs_blocks`, `cs_args`).
pub fn refine_classify_module() -> String {
    join(&[COMMON, REFINE_COMMON, REFINE_PROOF, REFINE_CLASSIFY])
}

/// Mode refine, the corner samples over the emitted base field (`cs_corners`).
pub fn refine_corners_module(base_field: &str) -> String {
    join(&[COMMON, base_field, FIELD, REFINE_COMMON, REFINE_CORNERS])
}

/// Mode refine, the event signs over the emitted base field's event lists (`cs_signs`).
pub fn refine_signs_module(base_field: &str) -> String {
    join(&[
        COMMON,
        base_field,
        FIELD,
        REFINE_COMMON,
        REFINE_PROOF,
        REFINE_SIGNS,
    ])
}

/// Mode refine, the proven blocks (`fs_refine`).
pub fn refine_draw_module() -> String {
    join(&[COMMON, SHADE, REFINE_COMMON, REFINE_PROOF, REFINE_DRAW])
}

/// Mode refine, the exact pass over the emitted base field (`cs_exact`).
pub fn refine_exact_module(base_field: &str) -> String {
    join(&[
        COMMON,
        base_field,
        FIELD,
        SHADE,
        REFINE_COMMON,
        REFINE_EXACT,
    ])
}
