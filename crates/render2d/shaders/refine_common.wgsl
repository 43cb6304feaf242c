// Mode `refine` on the GPU: what every refine pass shares (docs/render2d-pipeline.md,
// "Refine on the GPU"). The frame is cut into BLOCK x BLOCK pixel blocks, row-major; block
// corners are the pixel centres (BLOCK i, BLOCK j), i in 0..=blocks.x, j in 0..=blocks.y,
// where the exact corner samples live. Needs common.wgsl. `BlockState`, `Work` and the
// kind codes mirror src/render2d/gpu/refine.rs.

const BLOCK: u32 = 4u;

// A block's kind. NEED is level 0's "not proven yet": level 1 decides it.
const CLASS_SKY: u32 = 0u;
const CLASS_DEEP: u32 = 1u;
const CLASS_SHADED: u32 = 2u;
const CLASS_NEED: u32 = 3u;
const CLASS_EXACT: u32 = 4u;

// `BlockState.material` when each pixel takes its own cell's constant material.
const MATERIAL_PER_CELL: u32 = 0xfffffffeu;
// `CellProof.material` of a cell whose material is not constant.
const MATERIAL_NONE: u32 = 0xffffffffu;

// Counter slots of `Work.counters`.
const COUNT_BLOCKS: u32 = 0u;
const COUNT_SKY: u32 = 1u;
const COUNT_SOLID: u32 = 2u;
const COUNT_EXACT_BLOCKS: u32 = 3u;
const COUNT_EXACT_PIXELS: u32 = 4u;
const COUNT_CORNERS: u32 = 5u;
// The slots `cs_blocks` counts (COUNT_BLOCKS to COUNT_EXACT_PIXELS).
const COUNTERS_PER_BLOCK: u32 = 5u;

struct BlockState {
    kind: u32,
    // The proven material (or MATERIAL_PER_CELL); an EXACT block's slot in the exact list.
    material: u32,
    // Bounds of the exact distance over the block's pixel centres, world units.
    lo: f32,
    hi: f32,
    // What the events of the cells it touches force over it (SIGN_* bits, from cs_signs).
    signs: u32,
}

// `BlockState.signs`: the field is at least sky_at() everywhere in the block, at most
// solid_at(), at most deep_at() (refine_proof.wgsl).
const SIGN_ABOVE: u32 = 1u;
const SIGN_BELOW_SOLID: u32 = 2u;
const SIGN_BELOW_DEEP: u32 = 4u;

// The indirect dispatch of the exact pass (workgroups x, y, z, written by `cs_args`), the
// number of blocks in the exact list, the frame's counters, then the indirect dispatch of
// the corner samples (written by `cs_corner_args`) and the number of open blocks listed
// for them.
struct Work {
    dispatch: array<u32, 3>,
    exact_blocks: atomic<u32>,
    counters: array<atomic<u32>, 8>,
    corner_dispatch: array<u32, 3>,
    open_blocks: atomic<u32>,
}

// The open-block list `cs_open` writes for `cs_corners` (in the exact list's buffer, before
// `cs_blocks` reuses it): word 0 the count, then one entry per open block, its index in the
// low OPEN_INDEX_BITS bits and above them the mask of the corners it samples (bit k: corner
// k of `block_corner`), each corner of an open block sampled by exactly one of them.
const OPEN_INDEX_BITS: u32 = 28u;
// Open blocks per workgroup of `cs_corners` (four invocations each, one per corner).
const OPEN_BLOCKS_PER_GROUP: u32 = 16u;

// Corner k (0: top left, 1: top right, 2: bottom left, 3: bottom right) of block b.
fn block_corner(b: vec2<u32>, k: u32) -> vec2<u32> {
    return b + vec2<u32>(k & 1u, k >> 1u);
}

// Workgroups for `n` items, `per_group` a workgroup, as a 2D grid when one dimension cannot
// hold them.
fn group_grid(n: u32, per_group: u32) -> array<u32, 3> {
    let groups = (n + per_group - 1u) / per_group;
    let x = min(groups, MAX_GROUPS_PER_DIM);
    let y = select(1u, (groups + x - 1u) / x, x > 0u);
    return array<u32, 3>(x, y, 1u);
}

// Exact blocks per workgroup of the exact pass (BLOCK * BLOCK pixels each).
const EXACT_BLOCKS_PER_GROUP: u32 = 4u;
// Most workgroups per dispatch dimension (the WebGPU default limit).
const MAX_GROUPS_PER_DIM: u32 = 65535u;

fn block_dims() -> vec2<u32> {
    return (frame.image + vec2<u32>(BLOCK - 1u)) / BLOCK;
}

fn corner_index(i: u32, j: u32) -> u32 {
    return j * (block_dims().x + 1u) + i;
}
