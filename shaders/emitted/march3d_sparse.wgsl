// Emitted by craterfield::emit::codegen3d for plan key 0xe648347888e14b4e.
var<private> em_zero_bits: u32 = 0u;
fn em_f32_bits(bits: u32) -> f32 {
    return bitcast<f32>(bits | em_zero_bits);
}
const em_max_steps: u32 = 0x52u;
const em_hit: f32 = 0.001f;
const em_hit_per_t: f32 = 0.0015f;
const em_far: f32 = 160.0f;
const em_escape: f32 = 10000.0f;
const em_step_factor: f32 = 1.0f;
const em_ray_offset: f32 = 0.02f;
const em_normal_eps: f32 = 0.002f;
const em_relax: f32 = 1.0f;
const em_material_ids: bool = true;
const em_has_terrain: bool = true;
const em_terrain_material: u32 = 0x0u;
const em_analytic_normal: bool = true;
const em_terrain_top: f32 = 6.9744997f;
const em_paper: bool = false;
const em_ambient: f32 = 0.0f;
const em_specular: f32 = 0.0f;
const em_shininess: f32 = 0.0f;
const em_fog: f32 = 0.006f;
const em_gamma: f32 = 0.4545f;
const em_bounces: u32 = 0x0u;
const em_reflection_scale: f32 = 0.0f;
const em_paper_shadows: bool = false;
const em_shadow_k: f32 = 0.0f;
const em_sky0: vec3<f32> = vec3<f32>(0.75f, 0.82f, 0.9f);
const em_sky1: vec3<f32> = vec3<f32>(0.3f, 0.5f, 0.85f);
const em_sun: vec3<f32> = vec3<f32>(0.59136367f, 0.645124f, -0.48384297f);
const em_sun_colour: vec3<f32> = vec3<f32>(1.3f, 1.2f, 1.0f);
const em_full_shadow: bool = false;
const em_shadow_steps: u32 = 0x4u;
const em_shadow_spacing: f32 = 1.0f;
fn em_hash2(q: vec2<f32>) -> f32 {
    return hash2_dot_fract(q);
}
fn em_hash3(q: vec3<f32>) -> f32 {
    return hash3_dot_fract(q);
}
fn em_height(x: vec2<f32>) -> vec3<f32> {
    var q = x * 0.02f;
    var h = 0.0f;
    var g = vec2<f32>(0.0);
    var n: vec3<f32>;
    n = noise2(q);
    h += 4.0f * n.x;
    g += vec2<f32>(0.08f * n.y + 0.0f * n.z, 0.0f * n.y + 0.08f * n.z);
    q = vec2<f32>(1.6506712f * q.x - 1.129285f * q.y, 1.129285f * q.x + 1.6506712f * q.y);
    n = noise2(q);
    h += 1.8f * n.x;
    g += vec2<f32>(0.059424162f * n.y + 0.040654257f * n.z, -0.040654257f * n.y + 0.059424162f * n.z);
    q = vec2<f32>(1.6506712f * q.x - 1.129285f * q.y, 1.129285f * q.x + 1.6506712f * q.y);
    n = noise2(q);
    h += 0.80999994f * n.x;
    g += vec2<f32>(0.023480779f * n.y + 0.06039613f * n.z, -0.06039613f * n.y + 0.023480779f * n.z);
    q = vec2<f32>(1.6506712f * q.x - 1.129285f * q.y, 1.129285f * q.x + 1.6506712f * q.y);
    n = noise2(q);
    h += 0.36449996f * n.x;
    g += vec2<f32>(-0.013250429f * n.y + 0.05679479f * n.z, -0.05679479f * n.y + -0.013250429f * n.z);
    return vec3<f32>(h, g);
}
fn em_node0(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.866963f, 0.0);
    let db = guard_distance(p, vec3<f32>(9.0f, 0.45f, 11.5f), vec3<f32>(9.130307f, 9.130307f, 9.130307f));
    if (db > 2.2825768f) {
        return db;
    }
    let z = p.z - 6.0f;
    let c = clamp(round(z / 2.2f), 0.0, 5.0f);
    var d = sd_round_box(((p - vec3<f32>(0.0, 0.0, c * 2.2f)) - vec3<f32>(9.0f, 0.45f, 6.0f)), vec3<f32>(7.0f, 0.85f, 0.3f), 0.25f);
    let nb = c + sign(z - c * 2.2f);
    if (nb != c && nb >= 0.0 && nb <= 5.0f) {
        let dn = sd_round_box(((p - vec3<f32>(0.0, 0.0, nb * 2.2f)) - vec3<f32>(9.0f, 0.45f, 6.0f)), vec3<f32>(7.0f, 0.85f, 0.3f), 0.25f);
        if (dn < d) {
            d = dn;
        }
    }
    return d;
}
fn em_node1(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.4204507f, 0.0);
    let db = guard_distance(p, vec3<f32>(-10.0f, 2.161562f, 14.0f), vec3<f32>(4.244253f, 4.244253f, 4.244253f));
    if (db > 1.0610633f) {
        return db;
    }
    var d = sd_box((p - vec3<f32>(-10.0f, 1.08f, 14.0f)), vec3<f32>(1.8f, 1.8f, 1.8f));
    d = smin(d, sd_capped_cone((p - vec3<f32>(-10.0f, 3.6f, 14.0f)), 0.9f, 2.6100001f, 0.17999999f), 0.17999999f);
    return d;
}
fn em_node2(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.2211943f, 0.0);
    return sd_capsule((p - vec3<f32>(-38.48f, 0.0f, 23.95f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.9040003f, 0.0f), 0.26400003f);
}
fn em_node3(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.2211943f, 0.0);
    let db = guard_distance(p, vec3<f32>(-38.44979f, 3.366469f, 23.934805f), vec3<f32>(1.9937875f, 1.9937875f, 1.9937875f));
    if (db > 0.49844688f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-38.48f, 2.1120002f, 23.95f), vec3<f32>(-37.5296f, 3.2736f, 24.214f), 0.13200001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-38.48f, 2.376f, 23.95f), vec3<f32>(-39.272f, 3.4848003f, 23.527601f), 0.13200001f), 0.3168f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-38.48f, 3.9072f, 23.95f)), vec3<f32>(1.3728f, 1.1616f, 1.3728f)), 0.3168f);
    d = smin(d, sd_sphere((p - vec3<f32>(-37.688f, 3.2736f, 24.2668f)), 0.8448f), 0.3168f);
    d = smin(d, sd_sphere((p - vec3<f32>(-39.1664f, 3.3792f, 23.527601f)), 0.79200006f), 0.3168f);
    return d;
}
fn em_node4(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.9283235f, 0.0);
    return sd_capsule((p - vec3<f32>(40.29f, 0.0f, 28.48f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.9645f, 0.0f), 0.2695f);
}
fn em_node5(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.9283235f, 0.0);
    let db = guard_distance(p, vec3<f32>(40.32084f, 3.4366038f, 28.464487f), vec3<f32>(2.0353246f, 2.0353246f, 2.0353246f));
    if (db > 0.50883114f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(40.29f, 2.156f, 28.48f), vec3<f32>(41.2602f, 3.3418f, 28.7495f), 0.13475f);
    d = smin(d, sd_capsule(p, vec3<f32>(40.29f, 2.4255f, 28.48f), vec3<f32>(39.481503f, 3.5574f, 28.0488f), 0.13475f), 0.3234f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(40.29f, 3.9886f, 28.48f)), vec3<f32>(1.4014f, 1.1858f, 1.4014f)), 0.3234f);
    d = smin(d, sd_sphere((p - vec3<f32>(41.0985f, 3.3418f, 28.8034f)), 0.86239994f), 0.3234f);
    d = smin(d, sd_sphere((p - vec3<f32>(39.589302f, 3.4495997f, 28.0488f)), 0.8085f), 0.3234f);
    return d;
}
fn em_node6(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.2681823f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-19.16f, 0.32400003f, 26.53f)), vec3<f32>(1.2960001f, 0.81000006f, 1.08f)) + 0.38880002f * (noise3(p * 1.4814814f) - 0.5)) * 0.40056208f;
}
fn em_node7(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.771986f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-7.66f, 0.16800001f, 23.82f)), vec3<f32>(0.67200005f, 0.42000002f, 0.56f)) + 0.20160002f * (noise3(p * 2.857143f) - 0.5)) * 0.40056208f;
}
fn em_node8(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.79350084f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-4.34f, 0.30900002f, 5.13f)), vec3<f32>(1.2360001f, 0.7725f, 1.03f)) + 0.37080002f * (noise3(p * 1.5533981f) - 0.5)) * 0.40056208f;
}
fn em_node9(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.5620043f, 0.0);
    return sd_torus((mat3x3<f32>(1.0f, 0.0f, 0.0f, 0.0f, -4.371139e-8f, -1.0f, 0.0f, 1.0f, -4.371139e-8f) * (p - vec3<f32>(-4.0f, 2.2f, 4.0f))), 1.2f, 0.25f);
}
fn em_node10(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.49063477f, 0.0);
    return sd_cylinder((p - vec3<f32>(3.5f, 2.0f, 0.0f)), 0.35f, 2.5f);
}
fn em_node11(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.49063477f, 0.0);
    return sd_sphere((p - vec3<f32>(3.5f, 4.9f, 0.0f)), 0.7f);
}
fn em_map(p: vec3<f32>) -> MapHit {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    d = (p.y - em_height(p.xz).x) * 0.863672f;
    m = 0x0u;
    if (p.y > 12.94727f) {
        let e = p.y - 12.44727f;
        if (e < d) {
            d = e;
            m = SKY;
        }
        return MapHit(d, m);
    }
    let d0 = em_node0(p);
    if (d0 < d) {
        d = d0;
        m = 0x4u;
    }
    let d1 = em_node1(p);
    if (d1 < d) {
        d = d1;
        m = 0x5u;
    }
    let d2 = em_node2(p);
    if (d2 < d) {
        d = d2;
        m = 0x1u;
    }
    let d3 = em_node3(p);
    if (d3 < d) {
        d = d3;
        m = 0x2u;
    }
    let d4 = em_node4(p);
    if (d4 < d) {
        d = d4;
        m = 0x1u;
    }
    let d5 = em_node5(p);
    if (d5 < d) {
        d = d5;
        m = 0x2u;
    }
    let d6 = em_node6(p);
    if (d6 < d) {
        d = d6;
        m = 0x3u;
    }
    let d7 = em_node7(p);
    if (d7 < d) {
        d = d7;
        m = 0x3u;
    }
    let d8 = em_node8(p);
    if (d8 < d) {
        d = d8;
        m = 0x3u;
    }
    let d9 = em_node9(p);
    if (d9 < d) {
        d = d9;
        m = 0x6u;
    }
    let d10 = em_node10(p);
    if (d10 < d) {
        d = d10;
        m = 0x6u;
    }
    let d11 = em_node11(p);
    if (d11 < d) {
        d = d11;
        m = 0x6u;
    }
    return MapHit(d, m);
}
fn em_dist(p: vec3<f32>) -> f32 {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    d = (p.y - em_height(p.xz).x) * 0.863672f;
    m = 0x0u;
    if (p.y > 12.94727f) {
        let e = p.y - 12.44727f;
        if (e < d) {
            d = e;
            m = SKY;
        }
        return d;
    }
    let d0 = em_node0(p);
    if (d0 < d) {
        d = d0;
        m = 0x4u;
    }
    let d1 = em_node1(p);
    if (d1 < d) {
        d = d1;
        m = 0x5u;
    }
    let d2 = em_node2(p);
    if (d2 < d) {
        d = d2;
        m = 0x1u;
    }
    let d3 = em_node3(p);
    if (d3 < d) {
        d = d3;
        m = 0x2u;
    }
    let d4 = em_node4(p);
    if (d4 < d) {
        d = d4;
        m = 0x1u;
    }
    let d5 = em_node5(p);
    if (d5 < d) {
        d = d5;
        m = 0x2u;
    }
    let d6 = em_node6(p);
    if (d6 < d) {
        d = d6;
        m = 0x3u;
    }
    let d7 = em_node7(p);
    if (d7 < d) {
        d = d7;
        m = 0x3u;
    }
    let d8 = em_node8(p);
    if (d8 < d) {
        d = d8;
        m = 0x3u;
    }
    let d9 = em_node9(p);
    if (d9 < d) {
        d = d9;
        m = 0x6u;
    }
    let d10 = em_node10(p);
    if (d10 < d) {
        d = d10;
        m = 0x6u;
    }
    let d11 = em_node11(p);
    if (d11 < d) {
        d = d11;
        m = 0x6u;
    }
    return d;
}
fn em_material(m: u32) -> Look {
    switch m {
        case 0x0u: {
            return Look(vec3<f32>(0.2f, 0.34f, 0.11f), 0.0f);
        }
        case 0x1u: {
            return Look(vec3<f32>(0.28f, 0.18f, 0.1f), 0.0f);
        }
        case 0x2u: {
            return Look(vec3<f32>(0.09f, 0.27f, 0.07f), 0.0f);
        }
        case 0x3u: {
            return Look(vec3<f32>(0.4f, 0.38f, 0.35f), 0.0f);
        }
        case 0x4u: {
            return Look(vec3<f32>(0.22f, 0.36f, 0.09f), 0.0f);
        }
        case 0x5u: {
            return Look(vec3<f32>(0.55f, 0.4f, 0.28f), 0.0f);
        }
        case 0x6u: {
            return Look(vec3<f32>(0.62f, 0.6f, 0.56f), 0.0f);
        }
        default: {
            return Look(vec3<f32>(0.0), 0.0);
        }
    }
}
fn em_lights(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> Lit {
    var sum = Lit(0.0, 0.0);
    return sum;
}
fn em_bounds_shadow(o: vec3<f32>) -> bool {
    var meets = false;
    {
        let oc = vec3<f32>(9.0f, 3.316963f, 11.5f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 83.36251f);
    }
    {
        let oc = vec3<f32>(-10.0f, 4.5820127f, 14.0f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 18.013685f);
    }
    {
        let oc = vec3<f32>(-38.48f, 5.5231943f, 23.95f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.4819567f);
    }
    {
        let oc = vec3<f32>(-38.44979f, 7.587663f, 23.934805f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.9751887f);
    }
    {
        let oc = vec3<f32>(40.29f, 5.2605734f, 28.48f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.616653f);
    }
    {
        let oc = vec3<f32>(40.32084f, 7.3649273f, 28.464487f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.142546f);
    }
    {
        let oc = vec3<f32>(-19.16f, 4.592182f, 26.53f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.2212925f);
    }
    {
        let oc = vec3<f32>(-7.66f, 3.939986f, 23.82f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 0.59722f);
    }
    {
        let oc = vec3<f32>(-4.34f, 1.1025009f, 5.13f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.020378f);
    }
    {
        let oc = vec3<f32>(-4.0f, 2.7620044f, 4.0f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.1025002f);
    }
    {
        let oc = vec3<f32>(3.5f, 2.4906347f, 0.0f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.3725004f);
    }
    {
        let oc = vec3<f32>(3.5f, 5.390635f, 0.0f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 0.48999998f);
    }
    return meets;
}
fn em_ao_taps(p: vec3<f32>, n: vec3<f32>, t: f32, m: u32) -> u32 {
    if (em_has_terrain && m == em_terrain_material && n.y > 0.9 && p.y > frame.position.y) {
        return 0u;
    }
    if (t < 10.0f) {
        return 0x5u;
    }
    return 0x3u;
}

