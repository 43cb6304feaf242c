//! Mode refine's share of [`TerrainRenderer`](super::TerrainRenderer): the cell proofs
//! mirrored from the terrain, the level-independent refine passes (compiled on first use),
//! the per-frame targets sized to the camera, and what the mode records in place of the
//! other modes' passes 2 and 3. The renderer holds one and calls into it only in mode
//! refine, so its own `prepare`, `encode_prepasses` and `draw` read as the pipeline of
//! every mode.

use craterfield_field::{Graph, Terrain};

use super::refine::{ClassifyPasses, ProofMirror, RefineTargets, STORAGE_BUFFERS_NEEDED};
use super::refine_passes::{
    RefineBinds, RefineFieldPipelines, RefineLayouts, RefinePipelines, RefineResources,
};
use super::{RenderError, Unsupported};
use crate::camera::Camera;
use crate::lattice::Lattice;
use crate::twin::RefineStats;

/// Invocations per workgroup the refine compute passes use.
const INVOCATIONS_NEEDED: u32 = 64;

/// The refine passes' state across frames.
pub(super) struct RefineMode {
    proofs: ProofMirror,
    pipelines: Option<RefinePipelines>,
    targets: Option<RefineTargets>,
}

/// What [`RefineMode::ensure`] needs of the renderer.
pub(super) struct RefineDevice<'a> {
    pub(super) device: &'a wgpu::Device,
    pub(super) queue: &'a wgpu::Queue,
    pub(super) layouts: &'a RefineLayouts,
    pub(super) format: wgpu::TextureFormat,
}

impl RefineMode {
    pub(super) fn new(device: &wgpu::Device) -> RefineMode {
        RefineMode {
            proofs: ProofMirror::new(device),
            pipelines: None,
            targets: None,
        }
    }

    /// Refuses mode refine on a device whose limits its passes exceed.
    pub(super) fn check_limits(device: &wgpu::Device) -> Result<(), RenderError> {
        let limits = device.limits();
        let have = limits.max_storage_buffers_per_shader_stage;
        if have < STORAGE_BUFFERS_NEEDED {
            return Err(RenderError::Unsupported {
                what: Unsupported::StorageBuffers {
                    have,
                    needed: STORAGE_BUFFERS_NEEDED,
                },
            });
        }
        let invocations = limits.max_compute_invocations_per_workgroup;
        if invocations < INVOCATIONS_NEEDED {
            return Err(RenderError::Unsupported {
                what: Unsupported::ComputeInvocations {
                    have: invocations,
                    needed: INVOCATIONS_NEEDED,
                },
            });
        }
        Ok(())
    }

    /// Compiles the level-independent refine passes once, syncs the cell proofs and sizes
    /// the per-frame buffers for the camera. `Ok(true)` when a buffer the bind groups
    /// reference was replaced, so they must be made again.
    pub(super) fn ensure(
        &mut self,
        gpu: RefineDevice<'_>,
        terrain: &Terrain<Graph>,
        fingerprint: u64,
        camera: &Camera,
    ) -> Result<bool, RenderError> {
        if self.pipelines.is_none() {
            self.pipelines = Some(RefinePipelines::new(gpu.device, gpu.layouts, gpu.format)?);
        }
        let mut rebind = self
            .proofs
            .sync(gpu.device, gpu.queue, terrain, fingerprint)?;
        let fits = self
            .targets
            .as_ref()
            .is_some_and(|t| t.fits(camera.width, camera.height));
        if !fits {
            self.targets = Some(RefineTargets::new(gpu.device, camera.width, camera.height)?);
            rebind = true;
        }
        Ok(rebind)
    }

    /// What the last frame submitted did (waits for the device).
    pub(super) async fn stats(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        lattice: &Lattice,
        camera: &Camera,
    ) -> Result<RefineStats, RenderError> {
        let targets = self.targets.as_ref().ok_or(RenderError::NotPrepared)?;
        targets
            .stats(
                device,
                queue,
                u64::from(lattice.cols) * u64::from(lattice.rows),
                u64::from(camera.width) * u64::from(camera.height),
            )
            .await
    }

    /// The mode's bind groups over the renderer's shared resources (`None` until
    /// [`RefineMode::ensure`] ran).
    pub(super) fn binds(
        &self,
        device: &wgpu::Device,
        layouts: &RefineLayouts,
        frame: &wgpu::Buffer,
        palette: &wgpu::Buffer,
        texels: &wgpu::TextureView,
    ) -> Option<RefineBinds> {
        self.pipelines.as_ref()?;
        let targets = self.targets.as_ref()?;
        Some(RefineBinds::new(
            device,
            layouts,
            targets,
            RefineResources {
                frame,
                palette,
                proofs: self.proofs.buffer(),
                texels,
            },
        ))
    }

    /// The refine classification after pass 1 (mode refine needs no pass 2): `own` are the
    /// level's refine pipelines, `field_bind` pass 1's bind group.
    pub(super) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        own: Option<&RefineFieldPipelines>,
        binds: Option<&RefineBinds>,
        field_bind: &wgpu::BindGroup,
    ) -> Result<(), RenderError> {
        let (Some(shared), Some(own), Some(binds), Some(targets)) =
            (&self.pipelines, own, binds, &self.targets)
        else {
            return Err(RenderError::NotPrepared);
        };
        targets.encode(
            encoder,
            ClassifyPasses {
                classify: &shared.classify,
                open: &shared.open,
                corner_args: &shared.corner_args,
                corners: &own.corners,
                blocks: &shared.blocks,
                signs: &own.signs,
                args: &shared.args,
                exact: &own.exact,
                classify_bind: &binds.classify,
                field_bind,
                corners_bind: &binds.corners,
                signs_bind: &binds.signs,
                exact_bind: &binds.exact,
            },
        );
        Ok(())
    }

    /// Pass 3 of mode refine: the proven blocks drawn, the exact ones copied.
    pub(super) fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        binds: Option<&RefineBinds>,
    ) -> Result<(), RenderError> {
        let (Some(shared), Some(binds)) = (&self.pipelines, binds) else {
            return Err(RenderError::NotPrepared);
        };
        pass.set_pipeline(&shared.draw);
        pass.set_bind_group(0, &binds.draw, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}
