//! Plain-data structs shared with the WGSL passes, byte for byte. Each one has a twin in
//! `shaders/` (named in its doc) with the same field order; the size assertions below and the
//! naga layout test in `tests/gpu_shaders.rs` keep the two sides in step.

use bytemuck::{Pod, Zeroable};
use glam::Vec2;

use crate::camera::Camera;
use crate::lattice::Lattice;
use crate::options::ShadeOptions;
use craterfield_field::{CellState, MaterialSource};
use craterfield_field::{Event, EventKind};

/// Per-frame values; `Frame` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub(crate) struct FrameUniform {
    /// Camera centre, world units.
    pub center: [f32; 2],
    /// World units per pixel.
    pub upp: f32,
    /// Bound on the field's change per world unit (`twin::slope_bound`).
    pub slope: f32,
    /// Output image size, pixels.
    pub image: [u32; 2],
    /// Lattice columns and rows.
    pub lattice_dims: [u32; 2],
    /// Lattice `i0`, `j0`.
    pub lattice_origin: [i32; 2],
    /// Texel spacing, world units.
    pub h: f32,
    /// The terrain's band `M`.
    pub band: f32,
    /// Lower-left corner of the explosion grid.
    pub grid_origin: [f32; 2],
    /// Grid cell side.
    pub cell_size: f32,
    /// Brick lattice spacing.
    pub brick_spacing: f32,
    /// Grid columns and rows.
    pub grid_dims: [u32; 2],
    /// Brick lattice intervals per cell side.
    pub brick_res: u32,
    /// The terrain's current tick.
    pub tick: u32,
    /// Sky colour at the top, 0..255.
    pub sky_top: [f32; 4],
    /// Sky colour at the bottom, 0..255.
    pub sky_bottom: [f32; 4],
    /// Light direction.
    pub light: [f32; 2],
    /// Outline width, pixels.
    pub outline_px: f32,
    /// Interior shading depth, pixels.
    pub shade_depth_px: f32,
    /// Palette entries.
    pub palette_len: u32,
    /// 1 when the render target is an sRGB format (the shader pre-linearizes).
    pub srgb_target: u32,
    /// Size of the reduced-scale textures (at least the lattice's).
    pub texture_dims: [u32; 2],
}

const _: () = assert!(std::mem::size_of::<FrameUniform>() == 144);

impl FrameUniform {
    /// The camera, lattice and shading part (the grid part is filled by [`GridFrame`]).
    pub(crate) fn new(
        camera: &Camera,
        lattice: &Lattice,
        shade: &ShadeOptions,
        srgb: bool,
    ) -> Self {
        let rgb = |c: [u8; 3]| [c[0] as f32, c[1] as f32, c[2] as f32, 255.0];
        FrameUniform {
            center: camera.center.to_array(),
            upp: camera.units_per_pixel,
            image: [camera.width, camera.height],
            lattice_dims: [lattice.cols, lattice.rows],
            lattice_origin: [lattice.i0, lattice.j0],
            h: lattice.h,
            sky_top: rgb(shade.sky_top),
            sky_bottom: rgb(shade.sky_bottom),
            light: shade.light.to_array(),
            outline_px: shade.outline_px,
            shade_depth_px: shade.shade_depth_px,
            srgb_target: u32::from(srgb),
            ..FrameUniform::default()
        }
    }

    /// Fills in the terrain's grid geometry, band and tick.
    pub(crate) fn with_grid(self, g: &GridFrame) -> Self {
        FrameUniform {
            band: g.band,
            grid_origin: g.origin.to_array(),
            cell_size: g.cell_size,
            brick_spacing: g.brick_spacing,
            grid_dims: g.dims,
            brick_res: g.brick_res,
            tick: g.tick,
            ..self
        }
    }
}

/// The grid-geometry part of [`FrameUniform`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct GridFrame {
    /// Band `M`.
    pub band: f32,
    /// Grid origin.
    pub origin: Vec2,
    /// Cell side.
    pub cell_size: f32,
    /// Brick spacing.
    pub brick_spacing: f32,
    /// Columns, rows.
    pub dims: [u32; 2],
    /// Brick resolution.
    pub brick_res: u32,
    /// Current tick.
    pub tick: u32,
}

/// Most palette entries the GPU passes hold; materials beyond draw magenta.
pub(crate) const MAX_PALETTE: usize = 256;

/// The material colours; `Palette` in `shaders/shade.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct PaletteUniform {
    /// RGB 0..255 and 255 alpha per material.
    pub colors: [[f32; 4]; MAX_PALETTE],
}

const _: () = assert!(std::mem::size_of::<PaletteUniform>() == 4096);

impl PaletteUniform {
    /// The first [`MAX_PALETTE`] colours of `palette`.
    pub(crate) fn new(palette: &[[u8; 3]]) -> PaletteUniform {
        let mut colors = [[0.0; 4]; MAX_PALETTE];
        for (slot, c) in colors.iter_mut().zip(palette) {
            *slot = [c[0] as f32, c[1] as f32, c[2] as f32, 255.0];
        }
        PaletteUniform { colors }
    }
}

/// One event; `GpuEvent` in `shaders/field.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub(crate) struct GpuEvent {
    /// Centre, world units.
    pub center: [f32; 2],
    /// Full radius.
    pub radius: f32,
    /// Blend width (0 = sharp).
    pub rim: f32,
    /// Start tick.
    pub tick: u32,
    /// Growth ticks.
    pub grow: u32,
    /// 0 carve, 1 fill.
    pub kind: u32,
    /// Fill material.
    pub material: u32,
}

const _: () = assert!(std::mem::size_of::<GpuEvent>() == 32);

impl From<&Event> for GpuEvent {
    fn from(e: &Event) -> Self {
        GpuEvent {
            center: e.center_f32().to_array(),
            radius: e.radius_f32(),
            rim: e.rim_f32(),
            tick: e.tick,
            grow: u32::from(e.grow_ticks),
            kind: u32::from(e.kind == EventKind::Fill),
            material: u32::from(e.material),
        }
    }
}

/// One grid cell; `GpuCell` in `shaders/field.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub(crate) struct GpuCell {
    /// `CELL_*` in `field.wgsl`.
    pub state: u32,
    /// Material or brick id, by state.
    pub payload: u32,
    /// First list entry in the list buffer.
    pub start: u32,
    /// List length.
    pub len: u32,
}

const _: () = assert!(std::mem::size_of::<GpuCell>() == 16);

/// `(state, payload)` codes of a cell state (`CELL_*` in `shaders/field.wgsl`).
pub(crate) fn encode_state(state: CellState) -> (u32, u32) {
    match state {
        CellState::Base => (0, 0),
        CellState::Air(MaterialSource::Base) => (1, 0),
        CellState::Air(MaterialSource::Constant(m)) => (2, u32::from(m)),
        CellState::Air(MaterialSource::Brick(id)) => (3, id),
        CellState::Solid(m) => (4, u32::from(m)),
        CellState::Brick(id) => (5, id),
    }
}

/// The refine proof's view of one grid cell; `CellProof` in `shaders/refine_proof.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub(crate) struct GpuCellProof {
    /// Slope bound of the field over the cell (`Terrain::cell_bounds`).
    pub lipschitz: f32,
    /// Jump allowance at the cell's borders.
    pub error: f32,
    /// The cell's constant material, or [`MATERIAL_NONE`].
    pub material: u32,
    /// 1 when the bounds are known (finite).
    pub known: u32,
    /// Bounds of the cell's starting state over the cell (`Terrain::cell_start_range`),
    /// `[-UNBOUNDED, UNBOUNDED]` when there are none.
    pub start: [f32; 2],
    /// Keeps the record at 32 bytes.
    pub pad: [u32; 2],
}

const _: () = assert!(std::mem::size_of::<GpuCellProof>() == 32);

/// `MATERIAL_NONE` in `shaders/refine_common.wgsl`: the material is not constant.
pub(crate) const MATERIAL_NONE: u32 = u32::MAX;

/// `UNBOUNDED` in `shaders/refine_proof.wgsl`: bounds at or past it prove nothing.
pub(crate) const UNBOUNDED: f32 = 1.0e30;

impl GpuCellProof {
    /// A cell with slope bound `lipschitz`, border error `error`, constant material
    /// `material` and starting-state range `start`; bounds that are not finite (or past
    /// [`UNBOUNDED`]) are unknown.
    pub(crate) fn new(
        lipschitz: f32,
        error: f32,
        material: Option<u16>,
        start: Option<(f32, f32)>,
    ) -> GpuCellProof {
        let known = lipschitz.is_finite()
            && error.is_finite()
            && lipschitz < UNBOUNDED * 0.5
            && error < UNBOUNDED * 0.5;
        GpuCellProof {
            lipschitz: if known { lipschitz } else { 0.0 },
            error: if known { error } else { 0.0 },
            material: material.map_or(MATERIAL_NONE, u32::from),
            known: u32::from(known),
            start: match start {
                Some((lo, hi)) if lo.is_finite() && hi.is_finite() && lo <= hi => [lo, hi],
                _ => [-UNBOUNDED, UNBOUNDED],
            },
            pad: [0; 2],
        }
    }
}

/// One pixel block's class and bounds; `BlockState` in `shaders/refine_common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub(crate) struct GpuBlockState {
    /// `CLASS_*` in `refine_common.wgsl`.
    pub kind: u32,
    /// Proven material, `MATERIAL_PER_CELL` or [`MATERIAL_NONE`]; an exact block's slot
    /// in the exact list.
    pub material: u32,
    /// Lower bound of the distance over the block.
    pub lo: f32,
    /// Upper bound.
    pub hi: f32,
    /// What the events force over the block (`SIGN_*` bits in `refine_common.wgsl`).
    pub signs: u32,
}

const _: () = assert!(std::mem::size_of::<GpuBlockState>() == 20);

/// The exact pass's indirect dispatch, its block count and the frame's refine counters;
/// `Work` in `shaders/refine_common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub(crate) struct GpuWork {
    /// Workgroups of the exact pass (written on the GPU by `cs_args`).
    pub dispatch: [u32; 3],
    /// Blocks in the exact list.
    pub exact_blocks: u32,
    /// `COUNT_*` slots of `refine_common.wgsl`.
    pub counters: [u32; 8],
    /// Workgroups of the corner pass (written on the GPU by `cs_corner_args`).
    pub corner_dispatch: [u32; 3],
    /// Open blocks listed for the corner pass.
    pub open_blocks: u32,
}

const _: () = assert!(std::mem::size_of::<GpuWork>() == WORK_BYTES as usize);

/// Bytes of [`GpuWork`].
pub(crate) const WORK_BYTES: u64 = 64;

/// Offset of [`GpuWork::corner_dispatch`], the corner pass's indirect arguments.
pub(crate) const CORNER_DISPATCH_OFFSET: u64 = 48;

const _: () =
    assert!(std::mem::offset_of!(GpuWork, corner_dispatch) == CORNER_DISPATCH_OFFSET as usize);

impl GpuWork {
    /// What the frame starts from: nothing listed, counters at zero.
    pub(crate) fn start() -> GpuWork {
        GpuWork::default()
    }
}
