// Emitted by craterfield::emit::codegen3d for plan key 0x86973115d915cb4e.
var<private> em_zero_bits: u32 = 0u;
fn em_f32_bits(bits: u32) -> f32 {
    return bitcast<f32>(bits | em_zero_bits);
}
const em_max_steps: u32 = 0xbb8u;
const em_hit: f32 = 5e-6f;
const em_hit_per_t: f32 = 0.0f;
const em_far: f32 = 3.4028234663852886e38f;
const em_escape: f32 = 100.0f;
const em_step_factor: f32 = 1.0f;
const em_ray_offset: f32 = 0.001f;
const em_normal_eps: f32 = 0.0001f;
const em_relax: f32 = 1.0f;
const em_material_ids: bool = true;
const em_has_terrain: bool = false;
const em_terrain_material: u32 = 0xffffffffu;
const em_analytic_normal: bool = false;
const em_terrain_top: f32 = 0.0f;
const em_paper: bool = true;
const em_ambient: f32 = 0.01f;
const em_specular: f32 = 0.2f;
const em_shininess: f32 = 15.0f;
const em_fog: f32 = 7e-6f;
const em_gamma: f32 = 0.4545f;
const em_bounces: u32 = 0x3u;
const em_reflection_scale: f32 = 0.1f;
const em_paper_shadows: bool = true;
const em_shadow_k: f32 = 3.0f;
const em_sky0: vec3<f32> = vec3<f32>(0.0f, 0.0f, 0.0f);
const em_sky1: vec3<f32> = vec3<f32>(0.0f, 0.0f, 0.0f);
const em_sun: vec3<f32> = vec3<f32>(0.0f, 0.0f, 0.0f);
const em_sun_colour: vec3<f32> = vec3<f32>(0.0f, 0.0f, 0.0f);
const em_full_shadow: bool = false;
const em_shadow_steps: u32 = 0x0u;
const em_shadow_spacing: f32 = 0.0f;
fn em_hash2(q: vec2<f32>) -> f32 {
    return hash2_sin(q);
}
fn em_hash3(q: vec3<f32>) -> f32 {
    return hash3_sin(q);
}
// No terrain: objects stand on y = 0 (never called for the terrain).
fn em_height(x: vec2<f32>) -> vec3<f32> {
    return vec3<f32>(0.0);
}
fn em_node0(pw: vec3<f32>) -> f32 {
    let p = pw;
    return sd_plane(p, vec3<f32>(0.0f, 1.0f, 0.0f), -3.0f);
}
fn em_node1(pw: vec3<f32>) -> f32 {
    let p = pw;
    return sd_box((mat3x3<f32>(0.9778124f, 0.20784043f, -0.02617695f, -0.20851068f, 0.97767f, -0.026167978f, 0.020153653f, 0.031045547f, 0.9993148f) * (p - vec3<f32>(-4.0f, -1.5f, 15.0f))), vec3<f32>(0.25f, 0.5f, 1.0f));
}
fn em_node2(pw: vec3<f32>) -> f32 {
    let p = pw;
    return sd_sphere((p - vec3<f32>(0.0f, 0.0f, 20.0f)), 3.0f);
}
fn em_node3(pw: vec3<f32>) -> f32 {
    let p = pw;
    return sd_capped_cone((p - vec3<f32>(1.5f, -1.5f, 12.0f)), 1.0f, 1.0f, 0.5f);
}
fn em_node4(pw: vec3<f32>) -> f32 {
    let p = pw;
    return sd_torus((p - vec3<f32>(4.0f, -1.5f, 15.0f)), 1.0f, 0.5f);
}
fn em_node5(pw: vec3<f32>) -> f32 {
    let p = pw;
    return sd_octahedron((p - vec3<f32>(-1.5f, -1.5f, 12.0f)), 1.0f);
}
fn em_map(p: vec3<f32>) -> MapHit {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    let d0 = em_node0(p);
    if (d0 < d) {
        d = d0;
        m = 0x0u;
    }
    let d1 = em_node1(p);
    if (d1 < d) {
        d = d1;
        m = 0x1u;
    }
    let d2 = em_node2(p);
    if (d2 < d) {
        d = d2;
        m = 0x2u;
    }
    let d3 = em_node3(p);
    if (d3 < d) {
        d = d3;
        m = 0x1u;
    }
    let d4 = em_node4(p);
    if (d4 < d) {
        d = d4;
        m = 0x3u;
    }
    let d5 = em_node5(p);
    if (d5 < d) {
        d = d5;
        m = 0x4u;
    }
    return MapHit(d, m);
}
fn em_dist(p: vec3<f32>) -> f32 {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    let d0 = em_node0(p);
    if (d0 < d) {
        d = d0;
        m = 0x0u;
    }
    let d1 = em_node1(p);
    if (d1 < d) {
        d = d1;
        m = 0x1u;
    }
    let d2 = em_node2(p);
    if (d2 < d) {
        d = d2;
        m = 0x2u;
    }
    let d3 = em_node3(p);
    if (d3 < d) {
        d = d3;
        m = 0x1u;
    }
    let d4 = em_node4(p);
    if (d4 < d) {
        d = d4;
        m = 0x3u;
    }
    let d5 = em_node5(p);
    if (d5 < d) {
        d = d5;
        m = 0x4u;
    }
    return d;
}
fn em_material(m: u32) -> Look {
    switch m {
        case 0x0u: {
            return Look(vec3<f32>(1.0f, 1.0f, 1.0f), 0.0f);
        }
        case 0x1u: {
            return Look(vec3<f32>(0.0f, 0.1f, 0.6f), 0.0f);
        }
        case 0x2u: {
            return Look(vec3<f32>(0.3f, 0.0f, 0.0f), 0.5f);
        }
        case 0x3u: {
            return Look(vec3<f32>(0.5f, 0.5f, 0.0f), 0.0f);
        }
        case 0x4u: {
            return Look(vec3<f32>(0.0f, 0.6f, 0.1f), 0.0f);
        }
        default: {
            return Look(vec3<f32>(0.0), 0.0);
        }
    }
}
fn em_lights(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> Lit {
    var sum = Lit(0.0, 0.0);
    {
        let one = point_light(p, n, dir, vec3<f32>(0.0f, 100.0f, 0.0f), 200.0f);
        sum.diffuse += one.diffuse;
        sum.specular += one.specular;
    }
    return sum;
}
fn em_bounds_shadow(o: vec3<f32>) -> bool {
    var meets = false;
    return meets;
}
fn em_ao_taps(p: vec3<f32>, n: vec3<f32>, t: f32, m: u32) -> u32 {
    return 0u;
}

