// Mode `refine` on the GPU, the full-screen draw of the proven blocks: sky, deep solid (one
// colour per material and row) and shaded solid (bilinear in the exact corner samples, the
// distance clamped to the proof's bound, so coverage and outline stay the exact render's),
// and the exact blocks' colours from the exact pass (refine_exact.wgsl). Needs common.wgsl,
// shade.wgsl, refine_common.wgsl and refine_proof.wgsl.

@group(0) @binding(2) var<storage, read> proof: array<CellProof>;
@group(0) @binding(3) var<storage, read> blocks: array<BlockState>;
@group(0) @binding(4) var<storage, read> corners: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> exact_colors: array<vec2<u32>>;
@group(0) @binding(7) var<uniform> palette: Palette;

// Far enough from the surface that shade_pixel takes its clamped branch.
const FAR: f32 = 1.0e6;

// The colour refine_exact.wgsl's `pack_color` stored.
fn unpack_color(c: vec2<u32>) -> vec4<f32> {
    if frame.srgb_target != 0u {
        return vec4<f32>(unpack2x16float(c.x), unpack2x16float(c.y));
    }
    return unpack4x8unorm(c.x);
}

@fragment
fn fs_refine(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let px = floor(pos.xy);
    let x = u32(px.x);
    let y = u32(px.y);
    let b = vec2<u32>(x / BLOCK, y / BLOCK);
    let state = blocks[b.y * block_dims().x + b.x];
    let p = pixel_to_world(px);
    switch state.kind {
        case CLASS_DEEP: {
            let base = palette_color(f32(pixel_material(state.material, p)));
            return shade_pixel(-FAR, vec2<f32>(0.0), base, px.y);
        }
        case CLASS_SHADED: {
            let base = palette_color(f32(pixel_material(state.material, p)));
            let t = vec2<f32>(f32(x - b.x * BLOCK), f32(y - b.y * BLOCK)) / f32(BLOCK);
            let s00 = corners[corner_index(b.x, b.y)];
            let s10 = corners[corner_index(b.x + 1u, b.y)];
            let s01 = corners[corner_index(b.x, b.y + 1u)];
            let s11 = corners[corner_index(b.x + 1u, b.y + 1u)];
            let v = mix(mix(s00.xyz, s10.xyz, t.x), mix(s01.xyz, s11.xyz, t.x), t.y);
            let g = v.yz;
            let n = select(vec2<f32>(0.0), normalize(g), dot(g, g) > 0.0);
            return shade_pixel(min(v.x, state.hi) / frame.upp, n, base, px.y);
        }
        case CLASS_EXACT: {
            // `material` holds the block's slot in the exact list.
            let local = (y - b.y * BLOCK) * BLOCK + (x - b.x * BLOCK);
            return unpack_color(exact_colors[state.material * BLOCK * BLOCK + local]);
        }
        default: {
            return sky_pixel(px.y);
        }
    }
}
