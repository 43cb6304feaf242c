//! Mode `refine` on the GPU (`docs/render2d-pipeline.md`, "Refine on the GPU"): the
//! per-cell proof data mirrored from the terrain, the block, corner, work and exact-list
//! buffers of one frame size, and the passes that use them.
//!
//! After pass 1, one compute pass runs eight dispatches: `cs_classify` (level 0: every
//! `4 x 4` pixel block bounded from the texels around it), `cs_signs` (what the events of
//! the cells an open block touches force over it: sky and deep solid decided there, the
//! "solid" bound kept for level 1), `cs_open` (the blocks still open listed, each with the
//! corners it samples), `cs_corner_args` and `cs_corners` (exact samples at those corners,
//! an indirect dispatch over the list, so no invocation idles) and `cs_blocks` (level 1: those blocks bounded from their corner samples and
//! signs; the ones still open are appended to a list with an atomic counter); `cs_args`
//! turns the count into the workgroups of an indirect dispatch of `cs_exact`, which
//! evaluates and shades every pixel of the listed blocks as the direct pass does and stores
//! the colours by list slot. Pass 3 (`fs_refine`) draws the proven blocks and
//! copies the exact ones, so every pixel that no proof covers is the exact render's.

use super::grid_mirror::buffer_with;
use super::uniforms::{CORNER_DISPATCH_OFFSET, GpuBlockState, GpuCellProof, GpuWork, WORK_BYTES};
use super::{RenderError, Unsupported};
use crate::twin::{REFINE_BLOCK as BLOCK, RefineStats};
use craterfield_field::Sdf;
use craterfield_field::Terrain;
use craterfield_gpu::map_read_async;

/// Storage buffers one stage of the refine passes binds at most (`cs_exact`: the four of the
/// field, the list, work and colours; `cs_signs`: the field's, proofs and blocks).
pub(crate) const STORAGE_BUFFERS_NEEDED: u32 = 7;

/// Bytes of one cell proof record.
const RECORD: u64 = std::mem::size_of::<GpuCellProof>() as u64;

/// Bits of a block index in the open-block list (`OPEN_INDEX_BITS` of
/// `shaders/refine_common.wgsl`; the corner mask sits above them).
const OPEN_INDEX_BITS: u32 = 28;

/// Workgroup side of the refine compute entry points (`@workgroup_size(8, 8)`).
const WORKGROUP: u32 = 8;

/// The terrain's per-cell slope bounds and constant materials, then one record for the
/// points outside the grid, kept in step with the grid's cell revisions.
pub(crate) struct ProofMirror {
    buffer: wgpu::Buffer,
    records: Vec<GpuCellProof>,
    sent_revisions: Vec<u64>,
    /// Fingerprint of the base field and grid the records describe.
    identity: Option<(u64, (u32, u32))>,
}

impl ProofMirror {
    pub(crate) fn new(device: &wgpu::Device) -> ProofMirror {
        ProofMirror {
            buffer: proof_buffer(device, 1),
            records: Vec::new(),
            sent_revisions: Vec::new(),
            identity: None,
        }
    }

    pub(crate) fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Brings the records up to date with `terrain` (whose base field has content
    /// fingerprint `fingerprint`); `true` when the buffer was reallocated.
    pub(crate) fn sync<F: Sdf>(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        terrain: &Terrain<F>,
        fingerprint: u64,
    ) -> Result<bool, RenderError> {
        let grid = terrain.grid();
        let cells = grid.cell_count();
        let identity = (fingerprint, grid.dims());
        let reset = self.identity != Some(identity);
        if reset {
            let bytes = (cells as u64 + 1) * RECORD;
            craterfield_gpu::check_storage(device, "refine cell proofs (bytes)", bytes)?;
            self.buffer = proof_buffer(device, cells as u64 + 1);
            self.records = vec![GpuCellProof::default(); cells + 1];
            self.sent_revisions = vec![u64::MAX; cells];
            self.identity = Some(identity);
        }
        let dirty: Vec<usize> = grid.changed_since(&self.sent_revisions).collect();
        for &i in &dirty {
            self.records[i] = cell_proof(terrain, i);
            if let (Some(sent), Some(cell)) = (self.sent_revisions.get_mut(i), grid.cell(i)) {
                *sent = cell.revision();
            }
        }
        let outside = GpuCellProof::new(terrain.lipschitz(), 0.0, None, None);
        let outside_changed = self.records[cells] != outside;
        self.records[cells] = outside;
        let first = dirty.iter().copied().min();
        let last = dirty.iter().copied().max();
        if let (Some(a), Some(b)) = (first, last) {
            let bytes = bytemuck::cast_slice(&self.records[a..=b]);
            queue.write_buffer(&self.buffer, a as u64 * RECORD, bytes);
        }
        if outside_changed || reset {
            let bytes = bytemuck::bytes_of(&self.records[cells]);
            queue.write_buffer(&self.buffer, cells as u64 * RECORD, bytes);
        }
        Ok(reset)
    }
}

fn proof_buffer(device: &wgpu::Device, records: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("craterfield refine proofs"),
        size: records.max(1) * RECORD,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// What the proof reads about cell `i`.
fn cell_proof<F: Sdf>(terrain: &Terrain<F>, i: usize) -> GpuCellProof {
    match terrain.cell_bounds(i) {
        Some(b) => GpuCellProof::new(
            b.lipschitz,
            b.error,
            terrain.cell_material(i),
            terrain.cell_start_range(i),
        ),
        None => GpuCellProof::new(f32::INFINITY, f32::INFINITY, None, None),
    }
}

/// Pixel blocks per axis of an image.
pub(crate) fn block_dims(width: u32, height: u32) -> (u32, u32) {
    let b = BLOCK as u32;
    (width.div_ceil(b), height.div_ceil(b))
}

/// The per-frame buffers of one image size.
pub(crate) struct RefineTargets {
    pub(crate) blocks: wgpu::Buffer,
    pub(crate) corners: wgpu::Buffer,
    pub(crate) work: wgpu::Buffer,
    pub(crate) list: wgpu::Buffer,
    /// The exact pass's colours, two words per pixel of each listed block.
    pub(crate) colors: wgpu::Buffer,
    work_start: wgpu::Buffer,
    readback: wgpu::Buffer,
    /// Blocks per axis.
    pub(crate) dims: (u32, u32),
}

impl RefineTargets {
    /// Buffers for an image of `width x height` pixels.
    pub(crate) fn new(device: &wgpu::Device, width: u32, height: u32) -> Result<Self, RenderError> {
        let dims = block_dims(width, height);
        let blocks = u64::from(dims.0) * u64::from(dims.1);
        let state_bytes = std::mem::size_of::<GpuBlockState>() as u64;
        let corners = u64::from(dims.0 + 1) * u64::from(dims.1 + 1);
        if blocks >= 1 << OPEN_INDEX_BITS {
            return Err(RenderError::Unsupported {
                what: Unsupported::RefineBlocks {
                    width,
                    height,
                    index_bits: OPEN_INDEX_BITS,
                },
            });
        }
        let pixels_per_block = (BLOCK * BLOCK) as u64;
        for (what, bytes) in [
            ("refine block states (bytes)", blocks * state_bytes),
            ("refine corner samples (bytes)", corners * 16),
            (
                "refine exact colours (bytes)",
                blocks * pixels_per_block * 8,
            ),
            ("refine block list (bytes)", (blocks + 1) * 4),
        ] {
            craterfield_gpu::check_storage(device, what, bytes)?;
        }
        let storage = |label: &str, bytes: u64, extra: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(16),
                usage: wgpu::BufferUsages::STORAGE | extra,
                mapped_at_creation: false,
            })
        };
        let none = wgpu::BufferUsages::empty();
        let work_usage = wgpu::BufferUsages::INDIRECT
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC;
        Ok(RefineTargets {
            blocks: storage("craterfield refine blocks", blocks * state_bytes, none),
            corners: storage("craterfield refine corners", corners * 16, none),
            work: storage("craterfield refine work", WORK_BYTES, work_usage),
            // The open-block list (a count, then the blocks), then the exact list.
            list: storage("craterfield refine block list", (blocks + 1) * 4, none),
            colors: storage(
                "craterfield refine exact colours",
                blocks * pixels_per_block * 8,
                none,
            ),
            work_start: buffer_with(
                device,
                "craterfield refine work start",
                bytemuck::bytes_of(&GpuWork::start()),
                wgpu::BufferUsages::COPY_SRC,
            ),
            readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("craterfield refine counters readback"),
                size: WORK_BYTES,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            dims,
        })
    }

    /// Whether these buffers serve an image of `width x height`.
    pub(crate) fn fits(&self, width: u32, height: u32) -> bool {
        self.dims == block_dims(width, height)
    }

    /// Resets the exact list and the counters, then records the eight dispatches (see the
    /// module doc).
    pub(crate) fn encode(&self, encoder: &mut wgpu::CommandEncoder, passes: ClassifyPasses<'_>) {
        encoder.copy_buffer_to_buffer(&self.work_start, 0, &self.work, 0, WORK_BYTES);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("craterfield refine classify"),
            timestamp_writes: None,
        });
        let (bx, by) = self.dims;
        let groups = |n: u32| n.div_ceil(WORKGROUP);
        pass.set_pipeline(passes.classify);
        pass.set_bind_group(0, passes.classify_bind, &[]);
        pass.dispatch_workgroups(groups(bx), groups(by), 1);
        pass.set_pipeline(passes.signs);
        pass.set_bind_group(0, passes.field_bind, &[]);
        pass.set_bind_group(1, passes.signs_bind, &[]);
        pass.dispatch_workgroups(groups(bx), groups(by), 1);
        pass.set_pipeline(passes.open);
        pass.set_bind_group(0, passes.classify_bind, &[]);
        pass.dispatch_workgroups(groups(bx), groups(by), 1);
        pass.set_pipeline(passes.corner_args);
        pass.dispatch_workgroups(1, 1, 1);
        pass.set_pipeline(passes.corners);
        pass.set_bind_group(0, passes.field_bind, &[]);
        pass.set_bind_group(1, passes.corners_bind, &[]);
        pass.dispatch_workgroups_indirect(&self.work, CORNER_DISPATCH_OFFSET);
        pass.set_pipeline(passes.blocks);
        pass.set_bind_group(0, passes.classify_bind, &[]);
        pass.dispatch_workgroups(groups(bx), groups(by), 1);
        pass.set_pipeline(passes.args);
        pass.dispatch_workgroups(1, 1, 1);
        pass.set_pipeline(passes.exact);
        pass.set_bind_group(0, passes.field_bind, &[]);
        pass.set_bind_group(1, passes.exact_bind, &[]);
        pass.dispatch_workgroups_indirect(&self.work, 0);
    }

    /// Reads the counters of the last submitted frame back (waits for the device).
    pub(crate) async fn stats(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        texels: u64,
        pixels: u64,
    ) -> Result<RefineStats, RenderError> {
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("craterfield refine counters"),
        });
        encoder.copy_buffer_to_buffer(&self.work, 0, &self.readback, 0, WORK_BYTES);
        queue.submit([encoder.finish()]);
        let work: GpuWork = map_read_async(device, &self.readback, |bytes| {
            bytemuck::pod_read_unaligned(&bytes[..WORK_BYTES as usize])
        })
        .await?;
        Ok(stats_of(&work, texels, pixels))
    }
}

/// The pipelines and bind groups [`RefineTargets::encode`] records.
pub(crate) struct ClassifyPasses<'a> {
    pub(crate) classify: &'a wgpu::ComputePipeline,
    pub(crate) open: &'a wgpu::ComputePipeline,
    pub(crate) corner_args: &'a wgpu::ComputePipeline,
    pub(crate) corners: &'a wgpu::ComputePipeline,
    pub(crate) blocks: &'a wgpu::ComputePipeline,
    pub(crate) signs: &'a wgpu::ComputePipeline,
    pub(crate) args: &'a wgpu::ComputePipeline,
    pub(crate) exact: &'a wgpu::ComputePipeline,
    pub(crate) classify_bind: &'a wgpu::BindGroup,
    pub(crate) field_bind: &'a wgpu::BindGroup,
    pub(crate) corners_bind: &'a wgpu::BindGroup,
    pub(crate) signs_bind: &'a wgpu::BindGroup,
    pub(crate) exact_bind: &'a wgpu::BindGroup,
}

/// `COUNT_*` slots of `shaders/refine_common.wgsl`.
mod slot {
    pub(super) const BLOCKS: usize = 0;
    pub(super) const SKY: usize = 1;
    pub(super) const SOLID: usize = 2;
    pub(super) const EXACT_BLOCKS: usize = 3;
    pub(super) const EXACT_PIXELS: usize = 4;
    pub(super) const CORNERS: usize = 5;
}

fn stats_of(work: &GpuWork, texels: u64, pixels: u64) -> RefineStats {
    let c = |i: usize| u64::from(work.counters[i]);
    RefineStats {
        blocks: c(slot::BLOCKS),
        sky_blocks: c(slot::SKY),
        solid_blocks: c(slot::SOLID),
        refined_blocks: c(slot::EXACT_BLOCKS),
        pixels,
        refined_pixels: c(slot::EXACT_PIXELS),
        exact_evaluations: texels + c(slot::CORNERS) + c(slot::EXACT_PIXELS),
    }
}
