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
// number of blocks in the exact list, then the frame's counters.
struct Work {
    dispatch: array<u32, 3>,
    exact_blocks: atomic<u32>,
    counters: array<atomic<u32>, 8>,
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
