//! Mode `refine` on the GPU: the bind group layouts, pipelines and bind groups of its
//! passes (`shaders/refine_*.wgsl`), which `RefineTargets::encode` records and
//! `TerrainRenderer` draws.

use super::RenderError;
use super::pipelines::{buffer, buffer_entry, compute_pipeline, fullscreen_pipeline, layout};
use super::pipelines::{texture_entry, uniform_entry};
use super::refine::RefineTargets;
use super::shaders;

/// What the refine bind groups read from the renderer besides the refine targets.
pub(super) struct RefineResources<'a> {
    /// The frame uniform.
    pub(super) frame: &'a wgpu::Buffer,
    /// The palette uniform.
    pub(super) palette: &'a wgpu::Buffer,
    /// The cell proofs (`ProofMirror::buffer`).
    pub(super) proofs: &'a wgpu::Buffer,
    /// Pass 1's texels.
    pub(super) texels: &'a wgpu::TextureView,
}

/// The refine passes that read the field: corner samples, event signs and the exact pass.
pub(super) struct RefineFieldPipelines {
    pub(super) corners: wgpu::ComputePipeline,
    pub(super) signs: wgpu::ComputePipeline,
    pub(super) exact: wgpu::ComputePipeline,
}

/// The refine passes that do not depend on the level.
pub(super) struct RefinePipelines {
    pub(super) classify: wgpu::ComputePipeline,
    pub(super) open: wgpu::ComputePipeline,
    pub(super) corner_args: wgpu::ComputePipeline,
    pub(super) blocks: wgpu::ComputePipeline,
    pub(super) args: wgpu::ComputePipeline,
    pub(super) draw: wgpu::RenderPipeline,
}

/// Bind group layouts of the refine passes (bindings as in `shaders/refine_*.wgsl`).
pub(super) struct RefineLayouts {
    /// Group 0 of `cs_classify` and `cs_blocks`.
    pub(super) classify: wgpu::BindGroupLayout,
    /// Group 1 of `cs_corners` (group 0 is the field's).
    pub(super) corners: wgpu::BindGroupLayout,
    /// Group 1 of `cs_signs` (group 0 is the field's).
    pub(super) signs: wgpu::BindGroupLayout,
    /// Group 0 of `fs_refine`.
    pub(super) draw: wgpu::BindGroupLayout,
    /// Group 1 of the exact pass (group 0 is the field's).
    pub(super) exact: wgpu::BindGroupLayout,
}

/// The bind groups of the refine passes for one set of targets.
pub(super) struct RefineBinds {
    pub(super) classify: wgpu::BindGroup,
    pub(super) corners: wgpu::BindGroup,
    pub(super) signs: wgpu::BindGroup,
    pub(super) draw: wgpu::BindGroup,
    pub(super) exact: wgpu::BindGroup,
}

impl RefineLayouts {
    pub(super) fn new(device: &wgpu::Device) -> RefineLayouts {
        let compute = wgpu::ShaderStages::COMPUTE;
        let fragment = wgpu::ShaderStages::FRAGMENT;
        RefineLayouts {
            classify: layout(
                device,
                "craterfield refine classify",
                &[
                    uniform_entry(0),
                    texture_entry(1),
                    buffer_entry(2, compute, true),
                    buffer_entry(3, compute, false),
                    buffer_entry(4, compute, true),
                    buffer_entry(5, compute, false),
                    buffer_entry(6, compute, false),
                ],
            ),
            corners: layout(
                device,
                "craterfield refine corners",
                &[
                    buffer_entry(0, compute, true),
                    buffer_entry(1, compute, false),
                ],
            ),
            signs: layout(
                device,
                "craterfield refine signs",
                &[
                    buffer_entry(0, compute, true),
                    buffer_entry(1, compute, false),
                ],
            ),
            draw: layout(
                device,
                "craterfield refine draw",
                &[
                    uniform_entry(0),
                    buffer_entry(2, fragment, true),
                    buffer_entry(3, fragment, true),
                    buffer_entry(4, fragment, true),
                    buffer_entry(5, fragment, true),
                    uniform_entry(7),
                ],
            ),
            exact: layout(
                device,
                "craterfield refine exact",
                &[
                    buffer_entry(0, compute, true),
                    buffer_entry(1, compute, true),
                    buffer_entry(2, compute, false),
                ],
            ),
        }
    }
}

impl RefinePipelines {
    /// The level-independent refine pipelines, drawing into `format`.
    pub(super) fn new(
        device: &wgpu::Device,
        l: &RefineLayouts,
        format: wgpu::TextureFormat,
    ) -> Result<RefinePipelines, RenderError> {
        let classify_src = shaders::refine_classify_module();
        Ok(RefinePipelines {
            classify: compute_pipeline(
                device,
                "craterfield refine classify",
                &classify_src,
                "cs_classify",
                &[&l.classify],
            )?,
            open: compute_pipeline(
                device,
                "craterfield refine classify",
                &classify_src,
                "cs_open",
                &[&l.classify],
            )?,
            corner_args: compute_pipeline(
                device,
                "craterfield refine classify",
                &classify_src,
                "cs_corner_args",
                &[&l.classify],
            )?,
            blocks: compute_pipeline(
                device,
                "craterfield refine classify",
                &classify_src,
                "cs_blocks",
                &[&l.classify],
            )?,
            args: compute_pipeline(
                device,
                "craterfield refine classify",
                &classify_src,
                "cs_args",
                &[&l.classify],
            )?,
            draw: fullscreen_pipeline(
                device,
                "craterfield refine draw",
                &shaders::refine_draw_module(),
                "fs_refine",
                &l.draw,
                format,
            )?,
        })
    }
}

impl RefineFieldPipelines {
    /// The refine pipelines over the emitted base field `base`, whose buffers `field` lays out
    /// (group 0).
    pub(super) fn new(
        device: &wgpu::Device,
        field: &wgpu::BindGroupLayout,
        l: &RefineLayouts,
        base: &str,
    ) -> Result<RefineFieldPipelines, RenderError> {
        Ok(RefineFieldPipelines {
            corners: compute_pipeline(
                device,
                "craterfield refine corners",
                &shaders::refine_corners_module(base),
                "cs_corners",
                &[field, &l.corners],
            )?,
            signs: compute_pipeline(
                device,
                "craterfield refine signs",
                &shaders::refine_signs_module(base),
                "cs_signs",
                &[field, &l.signs],
            )?,
            exact: compute_pipeline(
                device,
                "craterfield refine exact",
                &shaders::refine_exact_module(base),
                "cs_exact",
                &[field, &l.exact],
            )?,
        })
    }
}

impl RefineBinds {
    /// The bind groups of the refine passes over targets `t` and the renderer's resources.
    pub(super) fn new(
        device: &wgpu::Device,
        l: &RefineLayouts,
        t: &RefineTargets,
        r: RefineResources<'_>,
    ) -> RefineBinds {
        let group =
            |label: &str, layout: &wgpu::BindGroupLayout, entries: &[wgpu::BindGroupEntry]| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(label),
                    layout,
                    entries,
                })
            };
        let proofs = r.proofs;
        RefineBinds {
            classify: group(
                "craterfield refine classify",
                &l.classify,
                &[
                    buffer(0, r.frame),
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(r.texels),
                    },
                    buffer(2, proofs),
                    buffer(3, &t.blocks),
                    buffer(4, &t.corners),
                    buffer(5, &t.work),
                    buffer(6, &t.list),
                ],
            ),
            corners: group(
                "craterfield refine corners",
                &l.corners,
                &[buffer(0, &t.list), buffer(1, &t.corners)],
            ),
            signs: group(
                "craterfield refine signs",
                &l.signs,
                &[buffer(0, proofs), buffer(1, &t.blocks)],
            ),
            draw: group(
                "craterfield refine draw",
                &l.draw,
                &[
                    buffer(0, r.frame),
                    buffer(2, proofs),
                    buffer(3, &t.blocks),
                    buffer(4, &t.corners),
                    buffer(5, &t.colors),
                    buffer(7, r.palette),
                ],
            ),
            exact: group(
                "craterfield refine exact",
                &l.exact,
                &[buffer(0, &t.list), buffer(1, &t.work), buffer(2, &t.colors)],
            ),
        }
    }
}
