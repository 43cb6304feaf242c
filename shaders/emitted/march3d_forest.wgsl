// Emitted by craterfield::emit::codegen3d for plan key 0xbf8f11412f5690c9.
var<private> em_zero_bits: u32 = 0u;
fn em_f32_bits(bits: u32) -> f32 {
    return bitcast<f32>(bits | em_zero_bits);
}
const em_max_steps: u32 = 0x60u;
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
    let p = pw - vec3<f32>(0.0, 4.707846f, 0.0);
    let db = guard_distance(p, vec3<f32>(16.0f, 2.161562f, 30.0f), vec3<f32>(4.244253f, 4.244253f, 4.244253f));
    if (db > 1.0610633f) {
        return db;
    }
    var d = sd_box((p - vec3<f32>(16.0f, 1.08f, 30.0f)), vec3<f32>(1.8f, 1.8f, 1.8f));
    d = smin(d, sd_capped_cone((p - vec3<f32>(16.0f, 3.6f, 30.0f)), 0.9f, 2.6100001f, 0.17999999f), 0.17999999f);
    return d;
}
fn em_node3(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.441978f, 0.0);
    let db = guard_distance(p, vec3<f32>(-22.0f, 2.161562f, 40.0f), vec3<f32>(4.244253f, 4.244253f, 4.244253f));
    if (db > 1.0610633f) {
        return db;
    }
    var d = sd_box((p - vec3<f32>(-22.0f, 1.08f, 40.0f)), vec3<f32>(1.8f, 1.8f, 1.8f));
    d = smin(d, sd_capped_cone((p - vec3<f32>(-22.0f, 3.6f, 40.0f)), 0.9f, 2.6100001f, 0.17999999f), 0.17999999f);
    return d;
}
fn em_node4(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.2188315f, 0.0);
    return sd_capsule((p - vec3<f32>(-4.29f, 0.0f, 26.57f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.9765f, 0.0f), 0.3615f);
}
fn em_node5(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.2188315f, 0.0);
    let db = guard_distance(p, vec3<f32>(-4.2486343f, 4.6097674f, 26.549192f), vec3<f32>(2.730129f, 2.730129f, 2.730129f));
    if (db > 0.68253225f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-4.29f, 2.892f, 26.57f), vec3<f32>(-2.9885998f, 4.4826f, 26.9315f), 0.18075f);
    d = smin(d, sd_capsule(p, vec3<f32>(-4.29f, 3.2535f, 26.57f), vec3<f32>(-5.3745003f, 4.7718f, 25.9916f), 0.18075f), 0.43379998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-4.29f, 5.3502f, 26.57f)), vec3<f32>(1.8798f, 1.5906f, 1.8798f)), 0.43379998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-3.2055f, 4.4826f, 27.0038f)), 1.1568f), 0.43379998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-5.2299f, 4.6272f, 25.9916f)), 1.0845001f), 0.43379998f);
    return d;
}
fn em_node6(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.3422544f, 0.0);
    return sd_capsule((p - vec3<f32>(-3.09f, 0.0f, 20.86f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.333f, 0.0f), 0.303f);
}
fn em_node7(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.3422544f, 0.0);
    let db = guard_distance(p, vec3<f32>(-3.0553284f, 3.8637881f, 20.84256f), vec3<f32>(2.2883239f, 2.2883239f, 2.2883239f));
    if (db > 0.57208097f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-3.09f, 2.424f, 20.86f), vec3<f32>(-1.9991999f, 3.7572f, 21.163f), 0.1515f);
    d = smin(d, sd_capsule(p, vec3<f32>(-3.09f, 2.727f, 20.86f), vec3<f32>(-3.999f, 3.9996002f, 20.3752f), 0.1515f), 0.3636f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-3.09f, 4.4844f, 20.86f)), vec3<f32>(1.5755999f, 1.3332f, 1.5755999f)), 0.3636f);
    d = smin(d, sd_sphere((p - vec3<f32>(-2.1809998f, 3.7572f, 21.2236f)), 0.96959996f), 0.3636f);
    d = smin(d, sd_sphere((p - vec3<f32>(-3.8778f, 3.8783998f, 20.3752f)), 0.90900004f), 0.3636f);
    return d;
}
fn em_node8(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.9192836f, 0.0);
    return sd_capsule((p - vec3<f32>(-28.38f, 0.0f, 21.31f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.41f, 0.0f), 0.31f);
}
fn em_node9(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.9192836f, 0.0);
    let db = guard_distance(p, vec3<f32>(-28.344526f, 3.9530506f, 21.292156f), vec3<f32>(2.3411894f, 2.3411894f, 2.3411894f));
    if (db > 0.58529735f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-28.38f, 2.48f, 21.31f), vec3<f32>(-27.264f, 3.8439999f, 21.619999f), 0.155f);
    d = smin(d, sd_capsule(p, vec3<f32>(-28.38f, 2.7899997f, 21.31f), vec3<f32>(-29.31f, 4.092f, 20.814f), 0.155f), 0.37199998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-28.38f, 4.588f, 21.31f)), vec3<f32>(1.6119999f, 1.364f, 1.6119999f)), 0.37199998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-27.449999f, 3.8439999f, 21.682f)), 0.9919999f), 0.37199998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-29.185999f, 3.9679997f, 20.814f)), 0.93f), 0.37199998f);
    return d;
}
fn em_node10(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.488528f, 0.0);
    return sd_capsule((p - vec3<f32>(-36.84f, 0.0f, 54.06f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.5365f, 0.0f), 0.3215f);
}
fn em_node11(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.488528f, 0.0);
    let db = guard_distance(p, vec3<f32>(-36.80321f, 4.0996966f, 54.041496f), vec3<f32>(2.4280403f, 2.4280403f, 2.4280403f));
    if (db > 0.60701007f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-36.84f, 2.572f, 54.06f), vec3<f32>(-35.682602f, 3.9866f, 54.3815f), 0.16075f);
    d = smin(d, sd_capsule(p, vec3<f32>(-36.84f, 2.8934999f, 54.06f), vec3<f32>(-37.8045f, 4.2438f, 53.5456f), 0.16075f), 0.38579997f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-36.84f, 4.7582f, 54.06f)), vec3<f32>(1.6717999f, 1.4145999f, 1.6717999f)), 0.38579997f);
    d = smin(d, sd_sphere((p - vec3<f32>(-35.8755f, 3.9866f, 54.4458f)), 1.0287999f), 0.38579997f);
    d = smin(d, sd_sphere((p - vec3<f32>(-37.6759f, 4.1151996f, 53.5456f)), 0.9645f), 0.38579997f);
    return d;
}
fn em_node12(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7765276f, 0.0);
    return sd_capsule((p - vec3<f32>(-41.23f, 0.0f, 73.04f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 4.059f, 0.0f), 0.36900002f);
}
fn em_node13(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7765276f, 0.0);
    let db = guard_distance(p, vec3<f32>(-41.187775f, 4.705405f, 73.01876f), vec3<f32>(2.7867713f, 2.7867713f, 2.7867713f));
    if (db > 0.6966928f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-41.23f, 2.9520001f, 73.04f), vec3<f32>(-39.9016f, 4.5756f, 73.409004f), 0.18450001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-41.23f, 3.3209999f, 73.04f), vec3<f32>(-42.336998f, 4.8708005f, 72.4496f), 0.18450001f), 0.4428f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-41.23f, 5.4612f, 73.04f)), vec3<f32>(1.9188f, 1.6236f, 1.9188f)), 0.4428f);
    d = smin(d, sd_sphere((p - vec3<f32>(-40.123f, 4.5756f, 73.4828f)), 1.1808f), 0.4428f);
    d = smin(d, sd_sphere((p - vec3<f32>(-42.1894f, 4.7232f, 72.4496f)), 1.1070001f), 0.4428f);
    return d;
}
fn em_node14(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.8735418f, 0.0);
    return sd_capsule((p - vec3<f32>(30.82f, 0.0f, 22.1f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.432f, 0.0f), 0.312f);
}
fn em_node15(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.8735418f, 0.0);
    let db = guard_distance(p, vec3<f32>(30.855701f, 3.9785542f, 22.082043f), vec3<f32>(2.3562942f, 2.3562942f, 2.3562942f));
    if (db > 0.58907354f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(30.82f, 2.496f, 22.1f), vec3<f32>(31.9432f, 3.8688f, 22.412f), 0.156f);
    d = smin(d, sd_capsule(p, vec3<f32>(30.82f, 2.8079998f, 22.1f), vec3<f32>(29.883999f, 4.1184f, 21.6008f), 0.156f), 0.3744f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(30.82f, 4.6176f, 22.1f)), vec3<f32>(1.6223999f, 1.3728f, 1.6223999f)), 0.3744f);
    d = smin(d, sd_sphere((p - vec3<f32>(31.756f, 3.8688f, 22.4744f)), 0.9983999f), 0.3744f);
    d = smin(d, sd_sphere((p - vec3<f32>(30.0088f, 3.9935997f, 21.6008f)), 0.936f), 0.3744f);
    return d;
}
fn em_node16(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.1402183f, 0.0);
    return sd_capsule((p - vec3<f32>(-0.02f, 0.0f, 37.87f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.08f, 0.0f), 0.28f);
}
fn em_node17(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.1402183f, 0.0);
    let db = guard_distance(p, vec3<f32>(0.012039706f, 3.570497f, 37.85388f), vec3<f32>(2.114623f, 2.114623f, 2.114623f));
    if (db > 0.52865577f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-0.02f, 2.24f, 37.87f), vec3<f32>(0.98800004f, 3.472f, 38.149998f), 0.14f);
    d = smin(d, sd_capsule(p, vec3<f32>(-0.02f, 2.52f, 37.87f), vec3<f32>(-0.86f, 3.696f, 37.421997f), 0.14f), 0.336f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-0.02f, 4.144f, 37.87f)), vec3<f32>(1.456f, 1.232f, 1.456f)), 0.336f);
    d = smin(d, sd_sphere((p - vec3<f32>(0.82000005f, 3.472f, 38.205997f)), 0.89599997f), 0.336f);
    d = smin(d, sd_sphere((p - vec3<f32>(-0.74799997f, 3.5839999f, 37.421997f)), 0.84000003f), 0.336f);
    return d;
}
fn em_node18(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.8692427f, 0.0);
    return sd_capsule((p - vec3<f32>(-19.97f, 0.0f, 74.74f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 4.1140003f, 0.0f), 0.374f);
}
fn em_node19(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.8692427f, 0.0);
    let db = guard_distance(p, vec3<f32>(-19.927202f, 4.769164f, 74.71847f), vec3<f32>(2.824532f, 2.824532f, 2.824532f));
    if (db > 0.706133f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-19.97f, 2.992f, 74.74f), vec3<f32>(-18.6236f, 4.6376f, 75.114f), 0.187f);
    d = smin(d, sd_capsule(p, vec3<f32>(-19.97f, 3.366f, 74.74f), vec3<f32>(-21.092f, 4.9368f, 74.1416f), 0.187f), 0.4488f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-19.97f, 5.5352f, 74.74f)), vec3<f32>(1.9447999f, 1.6456f, 1.9447999f)), 0.4488f);
    d = smin(d, sd_sphere((p - vec3<f32>(-18.848f, 4.6376f, 75.1888f)), 1.1968f), 0.4488f);
    d = smin(d, sd_sphere((p - vec3<f32>(-20.9424f, 4.7872f, 74.1416f)), 1.1220001f), 0.4488f);
    return d;
}
fn em_node20(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0833793f, 0.0);
    return sd_capsule((p - vec3<f32>(30.62f, 0.0f, 42.86f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.805f, 0.0f), 0.255f);
}
fn em_node21(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0833793f, 0.0);
    let db = guard_distance(p, vec3<f32>(30.64918f, 3.2517028f, 42.845325f), vec3<f32>(1.9258175f, 1.9258175f, 1.9258175f));
    if (db > 0.48145437f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(30.62f, 2.04f, 42.86f), vec3<f32>(31.538f, 3.162f, 43.115f), 0.1275f);
    d = smin(d, sd_capsule(p, vec3<f32>(30.62f, 2.2949998f, 42.86f), vec3<f32>(29.855001f, 3.3660002f, 42.452f), 0.1275f), 0.306f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(30.62f, 3.774f, 42.86f)), vec3<f32>(1.326f, 1.122f, 1.326f)), 0.306f);
    d = smin(d, sd_sphere((p - vec3<f32>(31.385f, 3.162f, 43.166f)), 0.816f), 0.306f);
    d = smin(d, sd_sphere((p - vec3<f32>(29.957f, 3.264f, 42.452f)), 0.76500005f), 0.306f);
    return d;
}
fn em_node22(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.5053043f, 0.0);
    return sd_capsule((p - vec3<f32>(23.97f, 0.0f, 9.04f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.828f, 0.0f), 0.34800002f);
}
fn em_node23(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.5053043f, 0.0);
    let db = guard_distance(p, vec3<f32>(24.00982f, 4.4376183f, 9.01997f), vec3<f32>(2.628174f, 2.628174f, 2.628174f));
    if (db > 0.6570435f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(23.97f, 2.7840002f, 9.04f), vec3<f32>(25.2228f, 4.3152f, 9.388f), 0.17400001f);
    d = smin(d, sd_capsule(p, vec3<f32>(23.97f, 3.132f, 9.04f), vec3<f32>(22.925999f, 4.5936003f, 8.4832f), 0.17400001f), 0.4176f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(23.97f, 5.1504f, 9.04f)), vec3<f32>(1.8096f, 1.5312f, 1.8096f)), 0.4176f);
    d = smin(d, sd_sphere((p - vec3<f32>(25.014f, 4.3152f, 9.4576f)), 1.1136f), 0.4176f);
    d = smin(d, sd_sphere((p - vec3<f32>(23.065199f, 4.4544f, 8.4832f)), 1.044f), 0.4176f);
    return d;
}
fn em_node24(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.4830437f, 0.0);
    return sd_capsule((p - vec3<f32>(-10.21f, 0.0f, 70.38f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.8335f, 0.0f), 0.34849998f);
}
fn em_node25(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.4830437f, 0.0);
    let db = guard_distance(p, vec3<f32>(-10.170122f, 4.443994f, 70.35994f), vec3<f32>(2.6319494f, 2.6319494f, 2.6319494f));
    if (db > 0.65798736f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-10.21f, 2.7879999f, 70.38f), vec3<f32>(-8.9554f, 4.3213997f, 70.7285f), 0.17424999f);
    d = smin(d, sd_capsule(p, vec3<f32>(-10.21f, 3.1365f, 70.38f), vec3<f32>(-11.2555f, 4.6002f, 69.822395f), 0.17424999f), 0.4182f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-10.21f, 5.1577997f, 70.38f)), vec3<f32>(1.8121998f, 1.5333999f, 1.8121998f)), 0.4182f);
    d = smin(d, sd_sphere((p - vec3<f32>(-9.1645f, 4.3213997f, 70.798195f)), 1.1151999f), 0.4182f);
    d = smin(d, sd_sphere((p - vec3<f32>(-11.1161f, 4.4607997f, 69.822395f)), 1.0455f), 0.4182f);
    return d;
}
fn em_node26(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5359745f, 0.0);
    return sd_capsule((p - vec3<f32>(-2.7f, 0.0f, 72.84f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.9645f, 0.0f), 0.2695f);
}
fn em_node27(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5359745f, 0.0);
    let db = guard_distance(p, vec3<f32>(-2.6691618f, 3.4366038f, 72.824486f), vec3<f32>(2.0353243f, 2.0353243f, 2.0353243f));
    if (db > 0.5088311f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-2.7f, 2.156f, 72.84f), vec3<f32>(-1.7298f, 3.3418f, 73.1095f), 0.13475f);
    d = smin(d, sd_capsule(p, vec3<f32>(-2.7f, 2.4255f, 72.84f), vec3<f32>(-3.5085f, 3.5574f, 72.4088f), 0.13475f), 0.3234f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-2.7f, 3.9886f, 72.84f)), vec3<f32>(1.4014f, 1.1858f, 1.4014f)), 0.3234f);
    d = smin(d, sd_sphere((p - vec3<f32>(-1.8915f, 3.3418f, 73.1634f)), 0.86239994f), 0.3234f);
    d = smin(d, sd_sphere((p - vec3<f32>(-3.4007f, 3.4495997f, 72.4088f)), 0.8085f), 0.3234f);
    return d;
}
fn em_node28(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.5996404f, 0.0);
    return sd_capsule((p - vec3<f32>(-38.43f, 0.0f, 34.24f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.6959999f, 0.0f), 0.336f);
}
fn em_node29(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.5996404f, 0.0);
    let db = guard_distance(p, vec3<f32>(-38.391552f, 4.284598f, 34.22066f), vec3<f32>(2.5375464f, 2.5375464f, 2.5375464f));
    if (db > 0.6343866f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-38.43f, 2.688f, 34.24f), vec3<f32>(-37.2204f, 4.1664f, 34.576f), 0.168f);
    d = smin(d, sd_capsule(p, vec3<f32>(-38.43f, 3.024f, 34.24f), vec3<f32>(-39.438f, 4.4352f, 33.7024f), 0.168f), 0.40319997f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-38.43f, 4.9728f, 34.24f)), vec3<f32>(1.7471999f, 1.4784f, 1.7471999f)), 0.40319997f);
    d = smin(d, sd_sphere((p - vec3<f32>(-37.422f, 4.1664f, 34.6432f)), 1.0752f), 0.40319997f);
    d = smin(d, sd_sphere((p - vec3<f32>(-39.3036f, 4.3008f, 33.7024f)), 1.008f), 0.40319997f);
    return d;
}
fn em_node30(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.8178139f, 0.0);
    return sd_capsule((p - vec3<f32>(41.77f, 0.0f, 48.38f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.4255f, 0.0f), 0.22049999f);
}
fn em_node31(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.8178139f, 0.0);
    let db = guard_distance(p, vec3<f32>(41.79523f, 2.8117669f, 48.36731f), vec3<f32>(1.6652651f, 1.6652651f, 1.6652651f));
    if (db > 0.41631627f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(41.77f, 1.7639999f, 48.38f), vec3<f32>(42.5638f, 2.7342f, 48.600502f), 0.110249996f);
    d = smin(d, sd_capsule(p, vec3<f32>(41.77f, 1.9844999f, 48.38f), vec3<f32>(41.1085f, 2.9106f, 48.027203f), 0.110249996f), 0.26459998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(41.77f, 3.2633998f, 48.38f)), vec3<f32>(1.1465999f, 0.97019994f, 1.1465999f)), 0.26459998f);
    d = smin(d, sd_sphere((p - vec3<f32>(42.4315f, 2.7342f, 48.6446f)), 0.70559996f), 0.26459998f);
    d = smin(d, sd_sphere((p - vec3<f32>(41.1967f, 2.8223999f, 48.027203f)), 0.6615f), 0.26459998f);
    return d;
}
fn em_node32(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.113199f, 0.0);
    return sd_capsule((p - vec3<f32>(-29.01f, 0.0f, 26.52f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.0635002f, 0.0f), 0.27850002f);
}
fn em_node33(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.113199f, 0.0);
    let db = guard_distance(p, vec3<f32>(-28.978132f, 3.5513701f, 26.50397f), vec3<f32>(2.1032941f, 2.1032941f, 2.1032941f));
    if (db > 0.52582353f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-29.01f, 2.2280002f, 26.52f), vec3<f32>(-28.0074f, 3.4534001f, 26.7985f), 0.13925001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-29.01f, 2.5065f, 26.52f), vec3<f32>(-29.8455f, 3.6762002f, 26.0744f), 0.13925001f), 0.3342f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-29.01f, 4.1218f, 26.52f)), vec3<f32>(1.4482f, 1.2254001f, 1.4482f)), 0.3342f);
    d = smin(d, sd_sphere((p - vec3<f32>(-28.1745f, 3.4534001f, 26.8542f)), 0.8912f), 0.3342f);
    d = smin(d, sd_sphere((p - vec3<f32>(-29.7341f, 3.5648f, 26.0744f)), 0.83550006f), 0.3342f);
    return d;
}
fn em_node34(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.6021414f, 0.0);
    return sd_capsule((p - vec3<f32>(-27.84f, 0.0f, 45.51f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.453f, 0.0f), 0.223f);
}
fn em_node35(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.6021414f, 0.0);
    let db = guard_distance(p, vec3<f32>(-27.814482f, 2.8436463f, 45.49716f), vec3<f32>(1.684146f, 1.684146f, 1.684146f));
    if (db > 0.4210365f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-27.84f, 1.784f, 45.51f), vec3<f32>(-27.0372f, 2.7652001f, 45.732998f), 0.1115f);
    d = smin(d, sd_capsule(p, vec3<f32>(-27.84f, 2.007f, 45.51f), vec3<f32>(-28.509f, 2.9436002f, 45.1532f), 0.1115f), 0.2676f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-27.84f, 3.3004f, 45.51f)), vec3<f32>(1.1596f, 0.9812f, 1.1596f)), 0.2676f);
    d = smin(d, sd_sphere((p - vec3<f32>(-27.171f, 2.7652001f, 45.7776f)), 0.7136f), 0.2676f);
    d = smin(d, sd_sphere((p - vec3<f32>(-28.4198f, 2.8544f, 45.1532f)), 0.669f), 0.2676f);
    return d;
}
fn em_node36(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.8771548f, 0.0);
    return sd_capsule((p - vec3<f32>(42.38f, 0.0f, 53.38f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.783f, 0.0f), 0.253f);
}
fn em_node37(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.8771548f, 0.0);
    let db = guard_distance(p, vec3<f32>(42.40895f, 3.2261996f, 53.36544f), vec3<f32>(1.9107127f, 1.9107127f, 1.9107127f));
    if (db > 0.47767818f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(42.38f, 2.024f, 53.38f), vec3<f32>(43.290802f, 3.1371999f, 53.633f), 0.1265f);
    d = smin(d, sd_capsule(p, vec3<f32>(42.38f, 2.277f, 53.38f), vec3<f32>(41.621002f, 3.3396f, 52.9752f), 0.1265f), 0.30359998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(42.38f, 3.7444f, 53.38f)), vec3<f32>(1.3155999f, 1.1132f, 1.3155999f)), 0.30359998f);
    d = smin(d, sd_sphere((p - vec3<f32>(43.139f, 3.1371999f, 53.6836f)), 0.8096f), 0.30359998f);
    d = smin(d, sd_sphere((p - vec3<f32>(41.722202f, 3.2384f, 52.9752f)), 0.759f), 0.30359998f);
    return d;
}
fn em_node38(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0951214f, 0.0);
    return sd_capsule((p - vec3<f32>(31.89f, 0.0f, 35.6f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.3925f, 0.0f), 0.2175f);
}
fn em_node39(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0951214f, 0.0);
    let db = guard_distance(p, vec3<f32>(31.914888f, 2.773511f, 35.58748f), vec3<f32>(1.6426095f, 1.6426095f, 1.6426095f));
    if (db > 0.41065237f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(31.89f, 1.74f, 35.6f), vec3<f32>(32.673f, 2.697f, 35.817497f), 0.10875f);
    d = smin(d, sd_capsule(p, vec3<f32>(31.89f, 1.9574999f, 35.6f), vec3<f32>(31.2375f, 2.871f, 35.252f), 0.10875f), 0.26099998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(31.89f, 3.2189999f, 35.6f)), vec3<f32>(1.1309999f, 0.95699996f, 1.1309999f)), 0.26099998f);
    d = smin(d, sd_sphere((p - vec3<f32>(32.5425f, 2.697f, 35.861f)), 0.696f), 0.26099998f);
    d = smin(d, sd_sphere((p - vec3<f32>(31.3245f, 2.784f, 35.252f)), 0.65250003f), 0.26099998f);
    return d;
}
fn em_node40(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.3581817f, 0.0);
    return sd_capsule((p - vec3<f32>(24.54f, 0.0f, 1.19f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.772f, 0.0f), 0.252f);
}
fn em_node41(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.3581817f, 0.0);
    let db = guard_distance(p, vec3<f32>(24.568836f, 3.2134476f, 1.1754954f), vec3<f32>(1.9031607f, 1.9031607f, 1.9031607f));
    if (db > 0.47579017f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(24.54f, 2.016f, 1.19f), vec3<f32>(25.4472f, 3.1248f, 1.442f), 0.126f);
    d = smin(d, sd_capsule(p, vec3<f32>(24.54f, 2.268f, 1.19f), vec3<f32>(23.784f, 3.3264f, 0.7868f), 0.126f), 0.3024f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(24.54f, 3.7296f, 1.19f)), vec3<f32>(1.3103999f, 1.1087999f, 1.3103999f)), 0.3024f);
    d = smin(d, sd_sphere((p - vec3<f32>(25.296001f, 3.1248f, 1.4924f)), 0.8064f), 0.3024f);
    d = smin(d, sd_sphere((p - vec3<f32>(23.884802f, 3.2256f, 0.7868f)), 0.75600004f), 0.3024f);
    return d;
}
fn em_node42(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.415282f, 0.0);
    return sd_capsule((p - vec3<f32>(-23.13f, 0.0f, 31.14f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.9150002f, 0.0f), 0.26500002f);
}
fn em_node43(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.415282f, 0.0);
    let db = guard_distance(p, vec3<f32>(-23.099676f, 3.379221f, 31.124746f), vec3<f32>(2.0013397f, 2.0013397f, 2.0013397f));
    if (db > 0.5003349f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-23.13f, 2.1200001f, 31.14f), vec3<f32>(-22.175999f, 3.2860003f, 31.404999f), 0.13250001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-23.13f, 2.385f, 31.14f), vec3<f32>(-23.925f, 3.4980004f, 30.716f), 0.13250001f), 0.31800002f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-23.13f, 3.9220002f, 31.14f)), vec3<f32>(1.378f, 1.166f, 1.378f)), 0.31800002f);
    d = smin(d, sd_sphere((p - vec3<f32>(-22.335f, 3.2860003f, 31.458f)), 0.848f), 0.31800002f);
    d = smin(d, sd_sphere((p - vec3<f32>(-23.818998f, 3.392f, 30.716f)), 0.7950001f), 0.31800002f);
    return d;
}
fn em_node44(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.5268855f, 0.0);
    return sd_capsule((p - vec3<f32>(-31.13f, 0.0f, 64.93f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.7730002f, 0.0f), 0.34300002f);
}
fn em_node45(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.5268855f, 0.0);
    let db = guard_distance(p, vec3<f32>(-31.090752f, 4.3738594f, 64.910255f), vec3<f32>(2.5904133f, 2.5904133f, 2.5904133f));
    if (db > 0.64760333f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-31.13f, 2.7440002f, 64.93f), vec3<f32>(-29.895199f, 4.2532f, 65.273f), 0.17150001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-31.13f, 3.087f, 64.93f), vec3<f32>(-32.159f, 4.5276003f, 64.3812f), 0.17150001f), 0.4116f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-31.13f, 5.0764003f, 64.93f)), vec3<f32>(1.7836f, 1.5092f, 1.7836f)), 0.4116f);
    d = smin(d, sd_sphere((p - vec3<f32>(-30.101f, 4.2532f, 65.3416f)), 1.0976f), 0.4116f);
    d = smin(d, sd_sphere((p - vec3<f32>(-32.0218f, 4.3904f, 64.3812f)), 1.029f), 0.4116f);
    return d;
}
fn em_node46(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.016303f, 0.0);
    return sd_capsule((p - vec3<f32>(34.4f, 0.0f, 31.39f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.0140002f, 0.0f), 0.27400002f);
}
fn em_node47(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.016303f, 0.0);
    let db = guard_distance(p, vec3<f32>(34.431355f, 3.4939864f, 31.37423f), vec3<f32>(2.06931f, 2.06931f, 2.06931f));
    if (db > 0.5173275f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(34.4f, 2.1920002f, 31.39f), vec3<f32>(35.386402f, 3.3976f, 31.664f), 0.13700001f);
    d = smin(d, sd_capsule(p, vec3<f32>(34.4f, 2.4659998f, 31.39f), vec3<f32>(33.578003f, 3.6168f, 30.9516f), 0.13700001f), 0.3288f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(34.4f, 4.0552f, 31.39f)), vec3<f32>(1.4247999f, 1.2056f, 1.4247999f)), 0.3288f);
    d = smin(d, sd_sphere((p - vec3<f32>(35.222f, 3.3976f, 31.7188f)), 0.8768f), 0.3288f);
    d = smin(d, sd_sphere((p - vec3<f32>(33.687603f, 3.5072f, 30.9516f)), 0.822f), 0.3288f);
    return d;
}
fn em_node48(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5042877f, 0.0);
    return sd_capsule((p - vec3<f32>(-21.87f, 0.0f, 55.61f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.3495002f, 0.0f), 0.3045f);
}
fn em_node49(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5042877f, 0.0);
    let db = guard_distance(p, vec3<f32>(-21.835157f, 3.8829155f, 55.592476f), vec3<f32>(2.2996533f, 2.2996533f, 2.2996533f));
    if (db > 0.5749133f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-21.87f, 2.436f, 55.61f), vec3<f32>(-20.7738f, 3.7758002f, 55.9145f), 0.15225f);
    d = smin(d, sd_capsule(p, vec3<f32>(-21.87f, 2.7405f, 55.61f), vec3<f32>(-22.7835f, 4.0194f, 55.1228f), 0.15225f), 0.3654f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-21.87f, 4.5066004f, 55.61f)), vec3<f32>(1.5834f, 1.3398f, 1.5834f)), 0.3654f);
    d = smin(d, sd_sphere((p - vec3<f32>(-20.956501f, 3.7758002f, 55.9754f)), 0.9744f), 0.3654f);
    d = smin(d, sd_sphere((p - vec3<f32>(-22.661701f, 3.8976f, 55.1228f)), 0.9135001f), 0.3654f);
    return d;
}
fn em_node50(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.3964553f, 0.0);
    return sd_capsule((p - vec3<f32>(-19.78f, 0.0f, 65.91f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.5905f, 0.0f), 0.23550001f);
}
fn em_node51(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.3964553f, 0.0);
    let db = guard_distance(p, vec3<f32>(-19.753054f, 3.0030437f, 65.896454f), vec3<f32>(1.7785486f, 1.7785486f, 1.7785486f));
    if (db > 0.44463715f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-19.78f, 1.8840001f, 65.91f), vec3<f32>(-18.932201f, 2.9202f, 66.1455f), 0.117750004f);
    d = smin(d, sd_capsule(p, vec3<f32>(-19.78f, 2.1195f, 65.91f), vec3<f32>(-20.4865f, 3.1086001f, 65.5332f), 0.117750004f), 0.2826f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-19.78f, 3.4854f, 65.91f)), vec3<f32>(1.2246f, 1.0362f, 1.2246f)), 0.2826f);
    d = smin(d, sd_sphere((p - vec3<f32>(-19.073502f, 2.9202f, 66.192604f)), 0.7536f), 0.2826f);
    d = smin(d, sd_sphere((p - vec3<f32>(-20.392302f, 3.0144f, 65.5332f)), 0.70650005f), 0.2826f);
    return d;
}
fn em_node52(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.6431036f, 0.0);
    return sd_capsule((p - vec3<f32>(-11.81f, 0.0f, 27.94f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.453f, 0.0f), 0.223f);
}
fn em_node53(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.6431036f, 0.0);
    let db = guard_distance(p, vec3<f32>(-11.784483f, 2.843646f, 27.927166f), vec3<f32>(1.6841463f, 1.6841463f, 1.6841463f));
    if (db > 0.42103657f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-11.81f, 1.784f, 27.94f), vec3<f32>(-11.0072f, 2.7652001f, 28.163f), 0.1115f);
    d = smin(d, sd_capsule(p, vec3<f32>(-11.81f, 2.007f, 27.94f), vec3<f32>(-12.479f, 2.9436002f, 27.5832f), 0.1115f), 0.2676f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-11.81f, 3.3004f, 27.94f)), vec3<f32>(1.1596f, 0.9812f, 1.1596f)), 0.2676f);
    d = smin(d, sd_sphere((p - vec3<f32>(-11.141001f, 2.7652001f, 28.2076f)), 0.7136f), 0.2676f);
    d = smin(d, sd_sphere((p - vec3<f32>(-12.3898f, 2.8544f, 27.5832f)), 0.669f), 0.2676f);
    return d;
}
fn em_node54(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.491605f, 0.0);
    return sd_capsule((p - vec3<f32>(-12.41f, 0.0f, 63.0f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 4.0865f, 0.0f), 0.3715f);
}
fn em_node55(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.491605f, 0.0);
    let db = guard_distance(p, vec3<f32>(-12.36749f, 4.737285f, 62.97862f), vec3<f32>(2.805651f, 2.805651f, 2.805651f));
    if (db > 0.70141274f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-12.41f, 2.972f, 63.0f), vec3<f32>(-11.072599f, 4.6066f, 63.3715f), 0.18575f);
    d = smin(d, sd_capsule(p, vec3<f32>(-12.41f, 3.3435f, 63.0f), vec3<f32>(-13.5245f, 4.9038f, 62.4056f), 0.18575f), 0.44579998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-12.41f, 5.4982f, 63.0f)), vec3<f32>(1.9317999f, 1.6345999f, 1.9317999f)), 0.44579998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-11.2955f, 4.6066f, 63.4458f)), 1.1888f), 0.44579998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-13.3759f, 4.7552f, 62.4056f)), 1.1145f), 0.44579998f);
    return d;
}
fn em_node56(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.011732f, 0.0);
    return sd_capsule((p - vec3<f32>(14.12f, 0.0f, 41.03f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.3275f, 0.0f), 0.3025f);
}
fn em_node57(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.011732f, 0.0);
    let db = guard_distance(p, vec3<f32>(14.154614f, 3.8574128f, 41.01259f), vec3<f32>(2.284548f, 2.284548f, 2.284548f));
    if (db > 0.571137f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(14.12f, 2.42f, 41.03f), vec3<f32>(15.209f, 3.7510002f, 41.3325f), 0.15125f);
    d = smin(d, sd_capsule(p, vec3<f32>(14.12f, 2.7225f, 41.03f), vec3<f32>(13.2125f, 3.9930003f, 40.545998f), 0.15125f), 0.363f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(14.12f, 4.477f, 41.03f)), vec3<f32>(1.573f, 1.3310001f, 1.573f)), 0.363f);
    d = smin(d, sd_sphere((p - vec3<f32>(15.0275f, 3.7510002f, 41.392998f)), 0.968f), 0.363f);
    d = smin(d, sd_sphere((p - vec3<f32>(13.3335f, 3.872f, 40.545998f)), 0.9075001f), 0.363f);
    return d;
}
fn em_node58(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.019718f, 0.0);
    return sd_capsule((p - vec3<f32>(-43.39f, 0.0f, 65.12f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.5475f, 0.0f), 0.3225f);
}
fn em_node59(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.019718f, 0.0);
    let db = guard_distance(p, vec3<f32>(-43.353096f, 4.1124487f, 65.10144f), vec3<f32>(2.4355917f, 2.4355917f, 2.4355917f));
    if (db > 0.6088979f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-43.39f, 2.58f, 65.12f), vec3<f32>(-42.229f, 3.9989998f, 65.442505f), 0.16125f);
    d = smin(d, sd_capsule(p, vec3<f32>(-43.39f, 2.9025f, 65.12f), vec3<f32>(-44.3575f, 4.257f, 64.604004f), 0.16125f), 0.387f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-43.39f, 4.773f, 65.12f)), vec3<f32>(1.6769999f, 1.4189999f, 1.6769999f)), 0.387f);
    d = smin(d, sd_sphere((p - vec3<f32>(-42.4225f, 3.9989998f, 65.507f)), 1.032f), 0.387f);
    d = smin(d, sd_sphere((p - vec3<f32>(-44.2285f, 4.128f, 64.604004f)), 0.96750003f), 0.387f);
    return d;
}
fn em_node60(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.2893558f, 0.0);
    return sd_capsule((p - vec3<f32>(-1.6f, 0.0f, 45.35f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.816f, 0.0f), 0.256f);
}
fn em_node61(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.2893558f, 0.0);
    let db = guard_distance(p, vec3<f32>(-1.5707065f, 3.2644548f, 45.335262f), vec3<f32>(1.9333692f, 1.9333692f, 1.9333692f));
    if (db > 0.4833423f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-1.6f, 2.048f, 45.35f), vec3<f32>(-0.6784f, 3.1743999f, 45.606f), 0.128f);
    d = smin(d, sd_capsule(p, vec3<f32>(-1.6f, 2.304f, 45.35f), vec3<f32>(-2.368f, 3.3792f, 44.9404f), 0.128f), 0.30719998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-1.6f, 3.7888f, 45.35f)), vec3<f32>(1.3311999f, 1.1264f, 1.3311999f)), 0.30719998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-0.832f, 3.1743999f, 45.6572f)), 0.8192f), 0.30719998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-2.2656f, 3.2768f, 44.9404f)), 0.768f), 0.30719998f);
    return d;
}
fn em_node62(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0105286f, 0.0);
    return sd_capsule((p - vec3<f32>(21.33f, 0.0f, 64.02f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.619f, 0.0f), 0.329f);
}
fn em_node63(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0105286f, 0.0);
    let db = guard_distance(p, vec3<f32>(21.367647f, 4.1953354f, 64.00106f), vec3<f32>(2.4846816f, 2.4846816f, 2.4846816f));
    if (db > 0.6211704f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(21.33f, 2.632f, 64.02f), vec3<f32>(22.5144f, 4.0796f, 64.349f), 0.1645f);
    d = smin(d, sd_capsule(p, vec3<f32>(21.33f, 2.961f, 64.02f), vec3<f32>(20.343f, 4.3428f, 63.493595f), 0.1645f), 0.39479998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(21.33f, 4.8692f, 64.02f)), vec3<f32>(1.7107999f, 1.4476f, 1.7107999f)), 0.39479998f);
    d = smin(d, sd_sphere((p - vec3<f32>(22.317f, 4.0796f, 64.414795f)), 1.0527999f), 0.39479998f);
    d = smin(d, sd_sphere((p - vec3<f32>(20.4746f, 4.2111998f, 63.493595f)), 0.98700005f), 0.39479998f);
    return d;
}
fn em_node64(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.34078f, 0.0);
    return sd_capsule((p - vec3<f32>(18.33f, 0.0f, 52.26f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.96f, 0.0f), 0.35999998f);
}
fn em_node65(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.34078f, 0.0);
    let db = guard_distance(p, vec3<f32>(18.371195f, 4.5906396f, 52.239277f), vec3<f32>(2.7188005f, 2.7188005f, 2.7188005f));
    if (db > 0.67970014f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(18.33f, 2.8799999f, 52.26f), vec3<f32>(19.626f, 4.4639997f, 52.62f), 0.17999999f);
    d = smin(d, sd_capsule(p, vec3<f32>(18.33f, 3.2399998f, 52.26f), vec3<f32>(17.25f, 4.752f, 51.684f), 0.17999999f), 0.43199998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(18.33f, 5.328f, 52.26f)), vec3<f32>(1.8719999f, 1.584f, 1.8719999f)), 0.43199998f);
    d = smin(d, sd_sphere((p - vec3<f32>(19.41f, 4.4639997f, 52.691998f)), 1.152f), 0.43199998f);
    d = smin(d, sd_sphere((p - vec3<f32>(17.394f, 4.608f, 51.684f)), 1.08f), 0.43199998f);
    return d;
}
fn em_node66(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.976197f, 0.0);
    return sd_capsule((p - vec3<f32>(-13.33f, 0.0f, 40.37f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.9325001f, 0.0f), 0.35750002f);
}
fn em_node67(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.976197f, 0.0);
    let db = guard_distance(p, vec3<f32>(-13.289092f, 4.5587606f, 40.349422f), vec3<f32>(2.69992f, 2.69992f, 2.69992f));
    if (db > 0.67498f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-13.33f, 2.8600001f, 40.37f), vec3<f32>(-12.043f, 4.433f, 40.727497f), 0.17875001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-13.33f, 3.2175f, 40.37f), vec3<f32>(-14.4025f, 4.7190003f, 39.798f), 0.17875001f), 0.429f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-13.33f, 5.2910004f, 40.37f)), vec3<f32>(1.859f, 1.573f, 1.859f)), 0.429f);
    d = smin(d, sd_sphere((p - vec3<f32>(-12.2575f, 4.433f, 40.799f)), 1.1439999f), 0.429f);
    d = smin(d, sd_sphere((p - vec3<f32>(-14.2595f, 4.5759997f, 39.798f)), 1.0725001f), 0.429f);
    return d;
}
fn em_node68(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7079594f, 0.0);
    return sd_capsule((p - vec3<f32>(33.4f, 0.0f, 10.89f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.7235f, 0.0f), 0.3385f);
}
fn em_node69(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7079594f, 0.0);
    let db = guard_distance(p, vec3<f32>(33.438736f, 4.3164763f, 10.870517f), vec3<f32>(2.5564282f, 2.5564282f, 2.5564282f));
    if (db > 0.63910705f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(33.4f, 2.708f, 10.89f), vec3<f32>(34.618603f, 4.1974f, 11.2285f), 0.16925f);
    d = smin(d, sd_capsule(p, vec3<f32>(33.4f, 3.0465f, 10.89f), vec3<f32>(32.384502f, 4.4682f, 10.3484f), 0.16925f), 0.4062f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(33.4f, 5.0098f, 10.89f)), vec3<f32>(1.7601999f, 1.4894f, 1.7601999f)), 0.4062f);
    d = smin(d, sd_sphere((p - vec3<f32>(34.4155f, 4.1974f, 11.296201f)), 1.0832f), 0.4062f);
    d = smin(d, sd_sphere((p - vec3<f32>(32.5199f, 4.3328f, 10.3484f)), 1.0155001f), 0.4062f);
    return d;
}
fn em_node70(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0153046f, 0.0);
    return sd_capsule((p - vec3<f32>(32.71f, 0.0f, 28.01f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.4045f, 0.0f), 0.3095f);
}
fn em_node71(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0153046f, 0.0);
    let db = guard_distance(p, vec3<f32>(32.745415f, 3.946676f, 27.992186f), vec3<f32>(2.3374126f, 2.3374126f, 2.3374126f));
    if (db > 0.58435315f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(32.71f, 2.476f, 28.01f), vec3<f32>(33.8242f, 3.8378f, 28.3195f), 0.15475f);
    d = smin(d, sd_capsule(p, vec3<f32>(32.71f, 2.7855f, 28.01f), vec3<f32>(31.7815f, 4.0854f, 27.514801f), 0.15475f), 0.3714f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(32.71f, 4.5806003f, 28.01f)), vec3<f32>(1.6093999f, 1.3618f, 1.6093999f)), 0.3714f);
    d = smin(d, sd_sphere((p - vec3<f32>(33.6385f, 3.8378f, 28.381401f)), 0.9904f), 0.3714f);
    d = smin(d, sd_sphere((p - vec3<f32>(31.905298f, 3.9616f, 27.514801f)), 0.92850006f), 0.3714f);
    return d;
}
fn em_node72(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.0830808f, 0.0);
    return sd_capsule((p - vec3<f32>(44.4f, 0.0f, 61.78f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.6025002f, 0.0f), 0.32750002f);
}
fn em_node73(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.0830808f, 0.0);
    let db = guard_distance(p, vec3<f32>(44.437477f, 4.176207f, 61.761147f), vec3<f32>(2.4733534f, 2.4733534f, 2.4733534f));
    if (db > 0.61833835f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(44.4f, 2.6200001f, 61.78f), vec3<f32>(45.579002f, 4.0610003f, 62.1075f), 0.16375001f);
    d = smin(d, sd_capsule(p, vec3<f32>(44.4f, 2.9475f, 61.78f), vec3<f32>(43.417503f, 4.3230004f, 61.256f), 0.16375001f), 0.393f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(44.4f, 4.847f, 61.78f)), vec3<f32>(1.703f, 1.441f, 1.703f)), 0.393f);
    d = smin(d, sd_sphere((p - vec3<f32>(45.3825f, 4.0610003f, 62.173f)), 1.048f), 0.393f);
    d = smin(d, sd_sphere((p - vec3<f32>(43.5485f, 4.192f, 61.256f)), 0.9825001f), 0.393f);
    return d;
}
fn em_node74(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.731479f, 0.0);
    return sd_capsule((p - vec3<f32>(-10.04f, 0.0f, 45.85f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.3165002f, 0.0f), 0.30150002f);
}
fn em_node75(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.731479f, 0.0);
    let db = guard_distance(p, vec3<f32>(-10.0055f, 3.8446608f, 45.832645f), vec3<f32>(2.276996f, 2.276996f, 2.276996f));
    if (db > 0.569249f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-10.04f, 2.4120002f, 45.85f), vec3<f32>(-8.954599f, 3.7386003f, 46.151497f), 0.15075001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-10.04f, 2.7135f, 45.85f), vec3<f32>(-10.9445f, 3.9798002f, 45.3676f), 0.15075001f), 0.36180001f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-10.04f, 4.4622f, 45.85f)), vec3<f32>(1.5678f, 1.3266001f, 1.5678f)), 0.36180001f);
    d = smin(d, sd_sphere((p - vec3<f32>(-9.1355f, 3.7386003f, 46.2118f)), 0.9648f), 0.36180001f);
    d = smin(d, sd_sphere((p - vec3<f32>(-10.8239f, 3.8592f, 45.3676f)), 0.90450007f), 0.36180001f);
    return d;
}
fn em_node76(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5753603f, 0.0);
    return sd_capsule((p - vec3<f32>(-5.35f, 0.0f, 57.22f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.3595f, 0.0f), 0.2145f);
}
fn em_node77(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5753603f, 0.0);
    let db = guard_distance(p, vec3<f32>(-5.325455f, 2.735256f, 57.207657f), vec3<f32>(1.6199523f, 1.6199523f, 1.6199523f));
    if (db > 0.40498808f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-5.35f, 1.716f, 57.22f), vec3<f32>(-4.5778f, 2.6598f, 57.4345f), 0.10725f);
    d = smin(d, sd_capsule(p, vec3<f32>(-5.35f, 1.9304999f, 57.22f), vec3<f32>(-5.9934998f, 2.8314002f, 56.8768f), 0.10725f), 0.2574f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-5.35f, 3.1746001f, 57.22f)), vec3<f32>(1.1154f, 0.9438f, 1.1154f)), 0.2574f);
    d = smin(d, sd_sphere((p - vec3<f32>(-4.7065f, 2.6598f, 57.4774f)), 0.6864f), 0.2574f);
    d = smin(d, sd_sphere((p - vec3<f32>(-5.9077f, 2.7456f, 56.8768f)), 0.64350003f), 0.2574f);
    return d;
}
fn em_node78(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.654002f, 0.0);
    return sd_capsule((p - vec3<f32>(10.31f, 0.0f, 66.25f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.6950002f, 0.0f), 0.245f);
}
fn em_node79(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.654002f, 0.0);
    let db = guard_distance(p, vec3<f32>(10.338036f, 3.1241858f, 66.23589f), vec3<f32>(1.8502946f, 1.8502946f, 1.8502946f));
    if (db > 0.46257365f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(10.31f, 1.96f, 66.25f), vec3<f32>(11.192f, 3.038f, 66.495f), 0.1225f);
    d = smin(d, sd_capsule(p, vec3<f32>(10.31f, 2.205f, 66.25f), vec3<f32>(9.575001f, 3.2340002f, 65.858f), 0.1225f), 0.294f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(10.31f, 3.6260002f, 66.25f)), vec3<f32>(1.2739999f, 1.0780001f, 1.2739999f)), 0.294f);
    d = smin(d, sd_sphere((p - vec3<f32>(11.045f, 3.038f, 66.544f)), 0.784f), 0.294f);
    d = smin(d, sd_sphere((p - vec3<f32>(9.673f, 3.136f, 65.858f)), 0.735f), 0.294f);
    return d;
}
fn em_node80(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.8710983f, 0.0);
    return sd_capsule((p - vec3<f32>(36.51f, 0.0f, 37.6f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.0525002f, 0.0f), 0.2775f);
}
fn em_node81(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.8710983f, 0.0);
    let db = guard_distance(p, vec3<f32>(36.54175f, 3.5386186f, 37.584026f), vec3<f32>(2.095742f, 2.095742f, 2.095742f));
    if (db > 0.5239355f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(36.51f, 2.22f, 37.6f), vec3<f32>(37.509f, 3.4410002f, 37.8775f), 0.13875f);
    d = smin(d, sd_capsule(p, vec3<f32>(36.51f, 2.4975f, 37.6f), vec3<f32>(35.677498f, 3.6630003f, 37.156f), 0.13875f), 0.333f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(36.51f, 4.1070004f, 37.6f)), vec3<f32>(1.443f, 1.2210001f, 1.443f)), 0.333f);
    d = smin(d, sd_sphere((p - vec3<f32>(37.3425f, 3.4410002f, 37.933f)), 0.888f), 0.333f);
    d = smin(d, sd_sphere((p - vec3<f32>(35.788498f, 3.552f, 37.156f)), 0.83250004f), 0.333f);
    return d;
}
fn em_node82(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.2105634f, 0.0);
    return sd_capsule((p - vec3<f32>(-27.13f, 0.0f, 12.4f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.7510002f, 0.0f), 0.34100002f);
}
fn em_node83(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.2105634f, 0.0);
    let db = guard_distance(p, vec3<f32>(-27.090979f, 4.3483562f, 12.380372f), vec3<f32>(2.5753086f, 2.5753086f, 2.5753086f));
    if (db > 0.64382714f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-27.13f, 2.7280002f, 12.4f), vec3<f32>(-25.9024f, 4.2284f, 12.740999f), 0.17050001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-27.13f, 3.069f, 12.4f), vec3<f32>(-28.153f, 4.5012f, 11.8544f), 0.17050001f), 0.4092f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-27.13f, 5.0468f, 12.4f)), vec3<f32>(1.7732f, 1.5004001f, 1.7732f)), 0.4092f);
    d = smin(d, sd_sphere((p - vec3<f32>(-26.106998f, 4.2284f, 12.809199f)), 1.0912f), 0.4092f);
    d = smin(d, sd_sphere((p - vec3<f32>(-28.0166f, 4.3648f, 11.8544f)), 1.0230001f), 0.4092f);
    return d;
}
fn em_node84(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.2847717f, 0.0);
    return sd_capsule((p - vec3<f32>(37.28f, 0.0f, 61.83f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.9425f, 0.0f), 0.2675f);
}
fn em_node85(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.2847717f, 0.0);
    let db = guard_distance(p, vec3<f32>(37.310608f, 3.4110994f, 61.814606f), vec3<f32>(2.0202208f, 2.0202208f, 2.0202208f));
    if (db > 0.5050552f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(37.28f, 2.14f, 61.83f), vec3<f32>(38.243f, 3.317f, 62.097504f), 0.13375f);
    d = smin(d, sd_capsule(p, vec3<f32>(37.28f, 2.4074998f, 61.83f), vec3<f32>(36.477497f, 3.5310001f, 61.402f), 0.13375f), 0.32099998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(37.28f, 3.9589999f, 61.83f)), vec3<f32>(1.3909999f, 1.1769999f, 1.3909999f)), 0.32099998f);
    d = smin(d, sd_sphere((p - vec3<f32>(38.0825f, 3.317f, 62.151f)), 0.85599995f), 0.32099998f);
    d = smin(d, sd_sphere((p - vec3<f32>(36.5845f, 3.4239998f, 61.402f)), 0.8025f), 0.32099998f);
    return d;
}
fn em_node86(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 1.3532633f, 0.0);
    return sd_capsule((p - vec3<f32>(7.48f, 0.0f, -0.19f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.464f, 0.0f), 0.224f);
}
fn em_node87(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 1.3532633f, 0.0);
    let db = guard_distance(p, vec3<f32>(7.505632f, 2.856398f, -0.20289302f), vec3<f32>(1.6916982f, 1.6916982f, 1.6916982f));
    if (db > 0.42292455f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(7.48f, 1.792f, -0.19f), vec3<f32>(8.2864f, 2.7776f, 0.03400001f), 0.112f);
    d = smin(d, sd_capsule(p, vec3<f32>(7.48f, 2.016f, -0.19f), vec3<f32>(6.808f, 2.9568002f, -0.5484f), 0.112f), 0.2688f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(7.48f, 3.3152f, -0.19f)), vec3<f32>(1.1647999f, 0.9856f, 1.1647999f)), 0.2688f);
    d = smin(d, sd_sphere((p - vec3<f32>(8.152f, 2.7776f, 0.07879999f)), 0.7168f), 0.2688f);
    d = smin(d, sd_sphere((p - vec3<f32>(6.8976f, 2.8672f, -0.5484f)), 0.67200005f), 0.2688f);
    return d;
}
fn em_node88(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.604102f, 0.0);
    return sd_capsule((p - vec3<f32>(-0.32f, 0.0f, 57.08f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.8335f, 0.0f), 0.34849998f);
}
fn em_node89(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.604102f, 0.0);
    let db = guard_distance(p, vec3<f32>(-0.28012186f, 4.443994f, 57.05994f), vec3<f32>(2.6319494f, 2.6319494f, 2.6319494f));
    if (db > 0.65798736f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-0.32f, 2.7879999f, 57.08f), vec3<f32>(0.93460006f, 4.3213997f, 57.4285f), 0.17424999f);
    d = smin(d, sd_capsule(p, vec3<f32>(-0.32f, 3.1365f, 57.08f), vec3<f32>(-1.3655f, 4.6002f, 56.522404f), 0.17424999f), 0.4182f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-0.32f, 5.1577997f, 57.08f)), vec3<f32>(1.8121998f, 1.5333999f, 1.8121998f)), 0.4182f);
    d = smin(d, sd_sphere((p - vec3<f32>(0.72550005f, 4.3213997f, 57.498203f)), 1.1151999f), 0.4182f);
    d = smin(d, sd_sphere((p - vec3<f32>(-1.2261f, 4.4607997f, 56.522404f)), 1.0455f), 0.4182f);
    return d;
}
fn em_node90(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.234625f, 0.0);
    return sd_capsule((p - vec3<f32>(19.01f, 0.0f, 69.5f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.7335f, 0.0f), 0.24849999f);
}
fn em_node91(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.234625f, 0.0);
    let db = guard_distance(p, vec3<f32>(19.038435f, 3.168816f, 69.485695f), vec3<f32>(1.876728f, 1.876728f, 1.876728f));
    if (db > 0.469182f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(19.01f, 1.9879999f, 69.5f), vec3<f32>(19.9046f, 3.0814f, 69.7485f), 0.124249995f);
    d = smin(d, sd_capsule(p, vec3<f32>(19.01f, 2.2364998f, 69.5f), vec3<f32>(18.2645f, 3.2802f, 69.1024f), 0.124249995f), 0.29819998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(19.01f, 3.6778f, 69.5f)), vec3<f32>(1.2921999f, 1.0934f, 1.2921999f)), 0.29819998f);
    d = smin(d, sd_sphere((p - vec3<f32>(19.7555f, 3.0814f, 69.7982f)), 0.79519993f), 0.29819998f);
    d = smin(d, sd_sphere((p - vec3<f32>(18.363901f, 3.1807997f, 69.1024f)), 0.74549997f), 0.29819998f);
    return d;
}
fn em_node92(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.449419f, 0.0);
    return sd_capsule((p - vec3<f32>(-7.74f, 0.0f, 33.83f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.1515f, 0.0f), 0.2865f);
}
fn em_node93(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.449419f, 0.0);
    let db = guard_distance(p, vec3<f32>(-7.7072163f, 3.6533837f, 33.81351f), vec3<f32>(2.1637125f, 2.1637125f, 2.1637125f));
    if (db > 0.5409281f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-7.74f, 2.292f, 33.83f), vec3<f32>(-6.7085996f, 3.5526001f, 34.1165f), 0.14325f);
    d = smin(d, sd_capsule(p, vec3<f32>(-7.74f, 2.5785f, 33.83f), vec3<f32>(-8.5995f, 3.7818003f, 33.3716f), 0.14325f), 0.3438f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-7.74f, 4.2402f, 33.83f)), vec3<f32>(1.4898f, 1.2606f, 1.4898f)), 0.3438f);
    d = smin(d, sd_sphere((p - vec3<f32>(-6.8805f, 3.5526001f, 34.1738f)), 0.91679996f), 0.3438f);
    d = smin(d, sd_sphere((p - vec3<f32>(-8.4848995f, 3.6671999f, 33.3716f)), 0.85950005f), 0.3438f);
    return d;
}
fn em_node94(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5855465f, 0.0);
    return sd_capsule((p - vec3<f32>(-16.62f, 0.0f, 57.3f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 4.092f, 0.0f), 0.372f);
}
fn em_node95(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5855465f, 0.0);
    let db = guard_distance(p, vec3<f32>(-16.577435f, 4.743661f, 57.278587f), vec3<f32>(2.8094275f, 2.8094275f, 2.8094275f));
    if (db > 0.7023569f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-16.62f, 2.976f, 57.3f), vec3<f32>(-15.280801f, 4.6128f, 57.672f), 0.186f);
    d = smin(d, sd_capsule(p, vec3<f32>(-16.62f, 3.348f, 57.3f), vec3<f32>(-17.736f, 4.9104004f, 56.7048f), 0.186f), 0.4464f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-16.62f, 5.5056f, 57.3f)), vec3<f32>(1.9344f, 1.6368f, 1.9344f)), 0.4464f);
    d = smin(d, sd_sphere((p - vec3<f32>(-15.504001f, 4.6128f, 57.7464f)), 1.1904f), 0.4464f);
    d = smin(d, sd_sphere((p - vec3<f32>(-17.5872f, 4.7616f, 56.7048f)), 1.116f), 0.4464f);
    return d;
}
fn em_node96(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.0260677f, 0.0);
    return sd_capsule((p - vec3<f32>(11.7f, 0.0f, 37.05f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.7565f, 0.0f), 0.3415f);
}
fn em_node97(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.0260677f, 0.0);
    let db = guard_distance(p, vec3<f32>(11.739077f, 4.3547325f, 37.030342f), vec3<f32>(2.579084f, 2.579084f, 2.579084f));
    if (db > 0.644771f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(11.7f, 2.732f, 37.05f), vec3<f32>(12.9293995f, 4.2346f, 37.3915f), 0.17075f);
    d = smin(d, sd_capsule(p, vec3<f32>(11.7f, 3.0735f, 37.05f), vec3<f32>(10.6755f, 4.5078f, 36.5036f), 0.17075f), 0.4098f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(11.7f, 5.0542f, 37.05f)), vec3<f32>(1.7757999f, 1.5026f, 1.7757999f)), 0.4098f);
    d = smin(d, sd_sphere((p - vec3<f32>(12.7245f, 4.2346f, 37.4598f)), 1.0928f), 0.4098f);
    d = smin(d, sd_sphere((p - vec3<f32>(10.812099f, 4.3712f, 36.5036f)), 1.0245f), 0.4098f);
    return d;
}
fn em_node98(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.4430048f, 0.0);
    return sd_capsule((p - vec3<f32>(41.26f, 0.0f, 40.29f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.585f, 0.0f), 0.235f);
}
fn em_node99(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.4430048f, 0.0);
    let db = guard_distance(p, vec3<f32>(41.28689f, 2.996667f, 40.276474f), vec3<f32>(1.7747732f, 1.7747732f, 1.7747732f));
    if (db > 0.4436933f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(41.26f, 1.88f, 40.29f), vec3<f32>(42.106f, 2.9139998f, 40.525f), 0.1175f);
    d = smin(d, sd_capsule(p, vec3<f32>(41.26f, 2.1149998f, 40.29f), vec3<f32>(40.554996f, 3.102f, 39.914f), 0.1175f), 0.28199998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(41.26f, 3.478f, 40.29f)), vec3<f32>(1.2219999f, 1.0339999f, 1.2219999f)), 0.28199998f);
    d = smin(d, sd_sphere((p - vec3<f32>(41.965f, 2.9139998f, 40.572002f)), 0.752f), 0.28199998f);
    d = smin(d, sd_sphere((p - vec3<f32>(40.649f, 3.008f, 39.914f)), 0.705f), 0.28199998f);
    return d;
}
fn em_node100(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.165685f, 0.0);
    return sd_capsule((p - vec3<f32>(1.84f, 0.0f, 32.59f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.6575f, 0.0f), 0.3325f);
}
fn em_node101(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.165685f, 0.0);
    let db = guard_distance(p, vec3<f32>(1.8780472f, 4.2399654f, 32.57086f), vec3<f32>(2.5111148f, 2.5111148f, 2.5111148f));
    if (db > 0.6277787f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(1.84f, 2.66f, 32.59f), vec3<f32>(3.0370002f, 4.123f, 32.9225f), 0.16625f);
    d = smin(d, sd_capsule(p, vec3<f32>(1.84f, 2.9925f, 32.59f), vec3<f32>(0.8425f, 4.3890004f, 32.058f), 0.16625f), 0.399f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(1.84f, 4.921f, 32.59f)), vec3<f32>(1.729f, 1.463f, 1.729f)), 0.399f);
    d = smin(d, sd_sphere((p - vec3<f32>(2.8375f, 4.123f, 32.989f)), 1.064f), 0.399f);
    d = smin(d, sd_sphere((p - vec3<f32>(0.97550005f, 4.256f, 32.058f)), 0.99750006f), 0.399f);
    return d;
}
fn em_node102(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.7021904f, 0.0);
    return sd_capsule((p - vec3<f32>(-9.58f, 0.0f, 52.11f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.9435f, 0.0f), 0.3585f);
}
fn em_node103(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.7021904f, 0.0);
    let db = guard_distance(p, vec3<f32>(-9.538978f, 4.5715117f, 52.089367f), vec3<f32>(2.7074726f, 2.7074726f, 2.7074726f));
    if (db > 0.67686814f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-9.58f, 2.868f, 52.11f), vec3<f32>(-8.2894f, 4.4454f, 52.468502f), 0.17925f);
    d = smin(d, sd_capsule(p, vec3<f32>(-9.58f, 3.2265f, 52.11f), vec3<f32>(-10.6555f, 4.7322f, 51.5364f), 0.17925f), 0.43019998f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-9.58f, 5.3058f, 52.11f)), vec3<f32>(1.8642f, 1.5774f, 1.8642f)), 0.43019998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-8.504499f, 4.4454f, 52.5402f)), 1.1472f), 0.43019998f);
    d = smin(d, sd_sphere((p - vec3<f32>(-10.5121f, 4.5888f, 51.5364f)), 1.0755f), 0.43019998f);
    return d;
}
fn em_node104(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.9767118f, 0.0);
    return sd_capsule((p - vec3<f32>(-37.15f, 0.0f, 67.59f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.5915003f, 0.0f), 0.32650003f);
}
fn em_node105(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.9767118f, 0.0);
    let db = guard_distance(p, vec3<f32>(-37.11264f, 4.163455f, 67.571205f), vec3<f32>(2.4658015f, 2.4658015f, 2.4658015f));
    if (db > 0.61645037f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-37.15f, 2.6120002f, 67.59f), vec3<f32>(-35.9746f, 4.0486f, 67.9165f), 0.16325001f);
    d = smin(d, sd_capsule(p, vec3<f32>(-37.15f, 2.9385f, 67.59f), vec3<f32>(-38.1295f, 4.3098f, 67.0676f), 0.16325001f), 0.39180002f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-37.15f, 4.8322f, 67.59f)), vec3<f32>(1.6978f, 1.4366001f, 1.6978f)), 0.39180002f);
    d = smin(d, sd_sphere((p - vec3<f32>(-36.1705f, 4.0486f, 67.9818f)), 1.0448f), 0.39180002f);
    d = smin(d, sd_sphere((p - vec3<f32>(-37.9989f, 4.1792f, 67.0676f)), 0.97950006f), 0.39180002f);
    return d;
}
fn em_node106(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.5402503f, 0.0);
    return sd_capsule((p - vec3<f32>(34.14f, 0.0f, 52.64f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 4.0150003f, 0.0f), 0.365f);
}
fn em_node107(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.5402503f, 0.0);
    let db = guard_distance(p, vec3<f32>(34.181763f, 4.654399f, 52.61899f), vec3<f32>(2.7565618f, 2.7565618f, 2.7565618f));
    if (db > 0.68914044f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(34.14f, 2.92f, 52.64f), vec3<f32>(35.454f, 4.526f, 53.005f), 0.1825f);
    d = smin(d, sd_capsule(p, vec3<f32>(34.14f, 3.285f, 52.64f), vec3<f32>(33.045f, 4.8180003f, 52.056f), 0.1825f), 0.438f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(34.14f, 5.4020004f, 52.64f)), vec3<f32>(1.898f, 1.6060001f, 1.898f)), 0.438f);
    d = smin(d, sd_sphere((p - vec3<f32>(35.235f, 4.526f, 53.078f)), 1.168f), 0.438f);
    d = smin(d, sd_sphere((p - vec3<f32>(33.190998f, 4.672f, 52.056f)), 1.095f), 0.438f);
    return d;
}
fn em_node108(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.6278534f, 0.0);
    return sd_capsule((p - vec3<f32>(43.24f, 0.0f, 72.51f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.2340002f, 0.0f), 0.294f);
}
fn em_node109(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.6278534f, 0.0);
    let db = guard_distance(p, vec3<f32>(43.273643f, 3.7490232f, 72.49308f), vec3<f32>(2.2203534f, 2.2203534f, 2.2203534f));
    if (db > 0.55508834f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(43.24f, 2.352f, 72.51f), vec3<f32>(44.2984f, 3.6456f, 72.804f), 0.147f);
    d = smin(d, sd_capsule(p, vec3<f32>(43.24f, 2.646f, 72.51f), vec3<f32>(42.358f, 3.8808002f, 72.039604f), 0.147f), 0.3528f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(43.24f, 4.3512f, 72.51f)), vec3<f32>(1.5288f, 1.2936f, 1.5288f)), 0.3528f);
    d = smin(d, sd_sphere((p - vec3<f32>(44.122f, 3.6456f, 72.8628f)), 0.9408f), 0.3528f);
    d = smin(d, sd_sphere((p - vec3<f32>(42.4756f, 3.7632f, 72.039604f)), 0.882f), 0.3528f);
    return d;
}
fn em_node110(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.646919f, 0.0);
    return sd_capsule((p - vec3<f32>(4.53f, 0.0f, 49.51f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.1405f, 0.0f), 0.28550002f);
}
fn em_node111(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.646919f, 0.0);
    let db = guard_distance(p, vec3<f32>(4.5626693f, 3.6406326f, 49.493565f), vec3<f32>(2.1561596f, 2.1561596f, 2.1561596f));
    if (db > 0.5390399f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(4.53f, 2.2840002f, 49.51f), vec3<f32>(5.5578003f, 3.5402f, 49.795498f), 0.14275001f);
    d = smin(d, sd_capsule(p, vec3<f32>(4.53f, 2.5695f, 49.51f), vec3<f32>(3.6735f, 3.7686002f, 49.0532f), 0.14275001f), 0.3426f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(4.53f, 4.2254f, 49.51f)), vec3<f32>(1.4846f, 1.2562f, 1.4846f)), 0.3426f);
    d = smin(d, sd_sphere((p - vec3<f32>(5.3865004f, 3.5402f, 49.8526f)), 0.91359997f), 0.3426f);
    d = smin(d, sd_sphere((p - vec3<f32>(3.7877002f, 3.6543999f, 49.0532f)), 0.8565f), 0.3426f);
    return d;
}
fn em_node112(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.194234f, 0.0);
    return sd_capsule((p - vec3<f32>(-42.44f, 0.0f, 54.01f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.3209999f, 0.0f), 0.211f);
}
fn em_node113(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.194234f, 0.0);
    let db = guard_distance(p, vec3<f32>(-42.415855f, 2.6906238f, 53.997852f), vec3<f32>(1.5935203f, 1.5935203f, 1.5935203f));
    if (db > 0.39838007f) {
        return db;
    }
    var d = sd_capsule(p, vec3<f32>(-42.44f, 1.688f, 54.01f), vec3<f32>(-41.680397f, 2.6164f, 54.220997f), 0.1055f);
    d = smin(d, sd_capsule(p, vec3<f32>(-42.44f, 1.8989998f, 54.01f), vec3<f32>(-43.072998f, 2.7851999f, 53.672398f), 0.1055f), 0.2532f);
    d = smin(d, sd_ellipsoid((p - vec3<f32>(-42.44f, 3.1227999f, 54.01f)), vec3<f32>(1.0971999f, 0.9283999f, 1.0971999f)), 0.2532f);
    d = smin(d, sd_sphere((p - vec3<f32>(-41.807f, 2.6164f, 54.2632f)), 0.6751999f), 0.2532f);
    d = smin(d, sd_sphere((p - vec3<f32>(-42.988598f, 2.7007997f, 53.672398f)), 0.633f), 0.2532f);
    return d;
}
fn em_node114(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.791979f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(20.4f, 0.40500003f, 35.15f)), vec3<f32>(1.6200001f, 1.0125f, 1.35f)) + 0.48600003f * (noise3(p * 1.1851852f) - 0.5)) * 0.40056208f;
}
fn em_node115(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.41636154f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(1.6f, 0.348f, 3.21f)), vec3<f32>(1.392f, 0.87f, 1.16f)) + 0.4176f * (noise3(p * 1.3793104f) - 0.5)) * 0.40056208f;
}
fn em_node116(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.188795f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(8.33f, 0.37800002f, 21.82f)), vec3<f32>(1.5120001f, 0.945f, 1.26f)) + 0.45360002f * (noise3(p * 1.2698413f) - 0.5)) * 0.40056208f;
}
fn em_node117(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.4994054f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-7.13f, 0.393f, 47.62f)), vec3<f32>(1.572f, 0.98249996f, 1.31f)) + 0.4716f * (noise3(p * 1.2213742f) - 0.5)) * 0.40056208f;
}
fn em_node118(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 6.064709f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-17.51f, 0.411f, 48.06f)), vec3<f32>(1.644f, 1.0275f, 1.37f)) + 0.49320003f * (noise3(p * 1.1678833f) - 0.5)) * 0.40056208f;
}
fn em_node119(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.410062f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(1.45f, 0.20400001f, 25.84f)), vec3<f32>(0.81600004f, 0.51f, 0.68f)) + 0.24480002f * (noise3(p * 2.3529413f) - 0.5)) * 0.40056208f;
}
fn em_node120(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7356312f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(2.15f, 0.312f, 20.25f)), vec3<f32>(1.248f, 0.78f, 1.04f)) + 0.3744f * (noise3(p * 1.5384616f) - 0.5)) * 0.40056208f;
}
fn em_node121(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.472352f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-28.33f, 0.28800002f, 57.55f)), vec3<f32>(1.1520001f, 0.71999997f, 0.96f)) + 0.3456f * (noise3(p * 1.6666667f) - 0.5)) * 0.40056208f;
}
fn em_node122(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.468969f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-5.96f, 0.303f, 44.09f)), vec3<f32>(1.212f, 0.7575f, 1.01f)) + 0.36360002f * (noise3(p * 1.5841584f) - 0.5)) * 0.40056208f;
}
fn em_node123(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.83435273f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-1.61f, 0.26700002f, -9.84f)), vec3<f32>(1.0680001f, 0.6675f, 0.89f)) + 0.3204f * (noise3(p * 1.7977529f) - 0.5)) * 0.40056208f;
}
fn em_node124(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.70222676f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-1.41f, 0.20100002f, 5.38f)), vec3<f32>(0.8040001f, 0.5025f, 0.67f)) + 0.24120001f * (noise3(p * 2.3880596f) - 0.5)) * 0.40056208f;
}
fn em_node125(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5562773f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(7.07f, 0.186f, 54.02f)), vec3<f32>(0.744f, 0.465f, 0.62f)) + 0.22320001f * (noise3(p * 2.580645f) - 0.5)) * 0.40056208f;
}
fn em_node126(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.557621f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-16.36f, 0.23700002f, 34.96f)), vec3<f32>(0.9480001f, 0.59250003f, 0.79f)) + 0.28440002f * (noise3(p * 2.0253165f) - 0.5)) * 0.40056208f;
}
fn em_node127(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.797424f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-8.68f, 0.177f, 29.58f)), vec3<f32>(0.708f, 0.4425f, 0.59f)) + 0.2124f * (noise3(p * 2.7118645f) - 0.5)) * 0.40056208f;
}
fn em_node128(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.335278f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(13.85f, 0.28800002f, -10.18f)), vec3<f32>(1.1520001f, 0.71999997f, 0.96f)) + 0.3456f * (noise3(p * 1.6666667f) - 0.5)) * 0.40056208f;
}
fn em_node129(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.5620043f, 0.0);
    return sd_torus((mat3x3<f32>(1.0f, 0.0f, 0.0f, 0.0f, -4.371139e-8f, -1.0f, 0.0f, 1.0f, -4.371139e-8f) * (p - vec3<f32>(-4.0f, 2.2f, 4.0f))), 1.2f, 0.25f);
}
fn em_node130(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.49063477f, 0.0);
    return sd_cylinder((p - vec3<f32>(3.5f, 2.0f, 0.0f)), 0.35f, 2.5f);
}
fn em_node131(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.49063477f, 0.0);
    return sd_sphere((p - vec3<f32>(3.5f, 4.9f, 0.0f)), 0.7f);
}
fn em_map(p: vec3<f32>) -> MapHit {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    d = (p.y - em_height(p.xz).x) * 0.863672f;
    m = 0x0u;
    if (p.y > 13.734878f) {
        let e = p.y - 13.234878f;
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
        m = 0x5u;
    }
    let d3 = em_node3(p);
    if (d3 < d) {
        d = d3;
        m = 0x5u;
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
        m = 0x1u;
    }
    let d7 = em_node7(p);
    if (d7 < d) {
        d = d7;
        m = 0x2u;
    }
    let d8 = em_node8(p);
    if (d8 < d) {
        d = d8;
        m = 0x1u;
    }
    let d9 = em_node9(p);
    if (d9 < d) {
        d = d9;
        m = 0x2u;
    }
    let d10 = em_node10(p);
    if (d10 < d) {
        d = d10;
        m = 0x1u;
    }
    let d11 = em_node11(p);
    if (d11 < d) {
        d = d11;
        m = 0x2u;
    }
    let d12 = em_node12(p);
    if (d12 < d) {
        d = d12;
        m = 0x1u;
    }
    let d13 = em_node13(p);
    if (d13 < d) {
        d = d13;
        m = 0x2u;
    }
    let d14 = em_node14(p);
    if (d14 < d) {
        d = d14;
        m = 0x1u;
    }
    let d15 = em_node15(p);
    if (d15 < d) {
        d = d15;
        m = 0x2u;
    }
    let d16 = em_node16(p);
    if (d16 < d) {
        d = d16;
        m = 0x1u;
    }
    let d17 = em_node17(p);
    if (d17 < d) {
        d = d17;
        m = 0x2u;
    }
    let d18 = em_node18(p);
    if (d18 < d) {
        d = d18;
        m = 0x1u;
    }
    let d19 = em_node19(p);
    if (d19 < d) {
        d = d19;
        m = 0x2u;
    }
    let d20 = em_node20(p);
    if (d20 < d) {
        d = d20;
        m = 0x1u;
    }
    let d21 = em_node21(p);
    if (d21 < d) {
        d = d21;
        m = 0x2u;
    }
    let d22 = em_node22(p);
    if (d22 < d) {
        d = d22;
        m = 0x1u;
    }
    let d23 = em_node23(p);
    if (d23 < d) {
        d = d23;
        m = 0x2u;
    }
    let d24 = em_node24(p);
    if (d24 < d) {
        d = d24;
        m = 0x1u;
    }
    let d25 = em_node25(p);
    if (d25 < d) {
        d = d25;
        m = 0x2u;
    }
    let d26 = em_node26(p);
    if (d26 < d) {
        d = d26;
        m = 0x1u;
    }
    let d27 = em_node27(p);
    if (d27 < d) {
        d = d27;
        m = 0x2u;
    }
    let d28 = em_node28(p);
    if (d28 < d) {
        d = d28;
        m = 0x1u;
    }
    let d29 = em_node29(p);
    if (d29 < d) {
        d = d29;
        m = 0x2u;
    }
    let d30 = em_node30(p);
    if (d30 < d) {
        d = d30;
        m = 0x1u;
    }
    let d31 = em_node31(p);
    if (d31 < d) {
        d = d31;
        m = 0x2u;
    }
    let d32 = em_node32(p);
    if (d32 < d) {
        d = d32;
        m = 0x1u;
    }
    let d33 = em_node33(p);
    if (d33 < d) {
        d = d33;
        m = 0x2u;
    }
    let d34 = em_node34(p);
    if (d34 < d) {
        d = d34;
        m = 0x1u;
    }
    let d35 = em_node35(p);
    if (d35 < d) {
        d = d35;
        m = 0x2u;
    }
    let d36 = em_node36(p);
    if (d36 < d) {
        d = d36;
        m = 0x1u;
    }
    let d37 = em_node37(p);
    if (d37 < d) {
        d = d37;
        m = 0x2u;
    }
    let d38 = em_node38(p);
    if (d38 < d) {
        d = d38;
        m = 0x1u;
    }
    let d39 = em_node39(p);
    if (d39 < d) {
        d = d39;
        m = 0x2u;
    }
    let d40 = em_node40(p);
    if (d40 < d) {
        d = d40;
        m = 0x1u;
    }
    let d41 = em_node41(p);
    if (d41 < d) {
        d = d41;
        m = 0x2u;
    }
    let d42 = em_node42(p);
    if (d42 < d) {
        d = d42;
        m = 0x1u;
    }
    let d43 = em_node43(p);
    if (d43 < d) {
        d = d43;
        m = 0x2u;
    }
    let d44 = em_node44(p);
    if (d44 < d) {
        d = d44;
        m = 0x1u;
    }
    let d45 = em_node45(p);
    if (d45 < d) {
        d = d45;
        m = 0x2u;
    }
    let d46 = em_node46(p);
    if (d46 < d) {
        d = d46;
        m = 0x1u;
    }
    let d47 = em_node47(p);
    if (d47 < d) {
        d = d47;
        m = 0x2u;
    }
    let d48 = em_node48(p);
    if (d48 < d) {
        d = d48;
        m = 0x1u;
    }
    let d49 = em_node49(p);
    if (d49 < d) {
        d = d49;
        m = 0x2u;
    }
    let d50 = em_node50(p);
    if (d50 < d) {
        d = d50;
        m = 0x1u;
    }
    let d51 = em_node51(p);
    if (d51 < d) {
        d = d51;
        m = 0x2u;
    }
    let d52 = em_node52(p);
    if (d52 < d) {
        d = d52;
        m = 0x1u;
    }
    let d53 = em_node53(p);
    if (d53 < d) {
        d = d53;
        m = 0x2u;
    }
    let d54 = em_node54(p);
    if (d54 < d) {
        d = d54;
        m = 0x1u;
    }
    let d55 = em_node55(p);
    if (d55 < d) {
        d = d55;
        m = 0x2u;
    }
    let d56 = em_node56(p);
    if (d56 < d) {
        d = d56;
        m = 0x1u;
    }
    let d57 = em_node57(p);
    if (d57 < d) {
        d = d57;
        m = 0x2u;
    }
    let d58 = em_node58(p);
    if (d58 < d) {
        d = d58;
        m = 0x1u;
    }
    let d59 = em_node59(p);
    if (d59 < d) {
        d = d59;
        m = 0x2u;
    }
    let d60 = em_node60(p);
    if (d60 < d) {
        d = d60;
        m = 0x1u;
    }
    let d61 = em_node61(p);
    if (d61 < d) {
        d = d61;
        m = 0x2u;
    }
    let d62 = em_node62(p);
    if (d62 < d) {
        d = d62;
        m = 0x1u;
    }
    let d63 = em_node63(p);
    if (d63 < d) {
        d = d63;
        m = 0x2u;
    }
    let d64 = em_node64(p);
    if (d64 < d) {
        d = d64;
        m = 0x1u;
    }
    let d65 = em_node65(p);
    if (d65 < d) {
        d = d65;
        m = 0x2u;
    }
    let d66 = em_node66(p);
    if (d66 < d) {
        d = d66;
        m = 0x1u;
    }
    let d67 = em_node67(p);
    if (d67 < d) {
        d = d67;
        m = 0x2u;
    }
    let d68 = em_node68(p);
    if (d68 < d) {
        d = d68;
        m = 0x1u;
    }
    let d69 = em_node69(p);
    if (d69 < d) {
        d = d69;
        m = 0x2u;
    }
    let d70 = em_node70(p);
    if (d70 < d) {
        d = d70;
        m = 0x1u;
    }
    let d71 = em_node71(p);
    if (d71 < d) {
        d = d71;
        m = 0x2u;
    }
    let d72 = em_node72(p);
    if (d72 < d) {
        d = d72;
        m = 0x1u;
    }
    let d73 = em_node73(p);
    if (d73 < d) {
        d = d73;
        m = 0x2u;
    }
    let d74 = em_node74(p);
    if (d74 < d) {
        d = d74;
        m = 0x1u;
    }
    let d75 = em_node75(p);
    if (d75 < d) {
        d = d75;
        m = 0x2u;
    }
    let d76 = em_node76(p);
    if (d76 < d) {
        d = d76;
        m = 0x1u;
    }
    let d77 = em_node77(p);
    if (d77 < d) {
        d = d77;
        m = 0x2u;
    }
    let d78 = em_node78(p);
    if (d78 < d) {
        d = d78;
        m = 0x1u;
    }
    let d79 = em_node79(p);
    if (d79 < d) {
        d = d79;
        m = 0x2u;
    }
    let d80 = em_node80(p);
    if (d80 < d) {
        d = d80;
        m = 0x1u;
    }
    let d81 = em_node81(p);
    if (d81 < d) {
        d = d81;
        m = 0x2u;
    }
    let d82 = em_node82(p);
    if (d82 < d) {
        d = d82;
        m = 0x1u;
    }
    let d83 = em_node83(p);
    if (d83 < d) {
        d = d83;
        m = 0x2u;
    }
    let d84 = em_node84(p);
    if (d84 < d) {
        d = d84;
        m = 0x1u;
    }
    let d85 = em_node85(p);
    if (d85 < d) {
        d = d85;
        m = 0x2u;
    }
    let d86 = em_node86(p);
    if (d86 < d) {
        d = d86;
        m = 0x1u;
    }
    let d87 = em_node87(p);
    if (d87 < d) {
        d = d87;
        m = 0x2u;
    }
    let d88 = em_node88(p);
    if (d88 < d) {
        d = d88;
        m = 0x1u;
    }
    let d89 = em_node89(p);
    if (d89 < d) {
        d = d89;
        m = 0x2u;
    }
    let d90 = em_node90(p);
    if (d90 < d) {
        d = d90;
        m = 0x1u;
    }
    let d91 = em_node91(p);
    if (d91 < d) {
        d = d91;
        m = 0x2u;
    }
    let d92 = em_node92(p);
    if (d92 < d) {
        d = d92;
        m = 0x1u;
    }
    let d93 = em_node93(p);
    if (d93 < d) {
        d = d93;
        m = 0x2u;
    }
    let d94 = em_node94(p);
    if (d94 < d) {
        d = d94;
        m = 0x1u;
    }
    let d95 = em_node95(p);
    if (d95 < d) {
        d = d95;
        m = 0x2u;
    }
    let d96 = em_node96(p);
    if (d96 < d) {
        d = d96;
        m = 0x1u;
    }
    let d97 = em_node97(p);
    if (d97 < d) {
        d = d97;
        m = 0x2u;
    }
    let d98 = em_node98(p);
    if (d98 < d) {
        d = d98;
        m = 0x1u;
    }
    let d99 = em_node99(p);
    if (d99 < d) {
        d = d99;
        m = 0x2u;
    }
    let d100 = em_node100(p);
    if (d100 < d) {
        d = d100;
        m = 0x1u;
    }
    let d101 = em_node101(p);
    if (d101 < d) {
        d = d101;
        m = 0x2u;
    }
    let d102 = em_node102(p);
    if (d102 < d) {
        d = d102;
        m = 0x1u;
    }
    let d103 = em_node103(p);
    if (d103 < d) {
        d = d103;
        m = 0x2u;
    }
    let d104 = em_node104(p);
    if (d104 < d) {
        d = d104;
        m = 0x1u;
    }
    let d105 = em_node105(p);
    if (d105 < d) {
        d = d105;
        m = 0x2u;
    }
    let d106 = em_node106(p);
    if (d106 < d) {
        d = d106;
        m = 0x1u;
    }
    let d107 = em_node107(p);
    if (d107 < d) {
        d = d107;
        m = 0x2u;
    }
    let d108 = em_node108(p);
    if (d108 < d) {
        d = d108;
        m = 0x1u;
    }
    let d109 = em_node109(p);
    if (d109 < d) {
        d = d109;
        m = 0x2u;
    }
    let d110 = em_node110(p);
    if (d110 < d) {
        d = d110;
        m = 0x1u;
    }
    let d111 = em_node111(p);
    if (d111 < d) {
        d = d111;
        m = 0x2u;
    }
    let d112 = em_node112(p);
    if (d112 < d) {
        d = d112;
        m = 0x1u;
    }
    let d113 = em_node113(p);
    if (d113 < d) {
        d = d113;
        m = 0x2u;
    }
    let d114 = em_node114(p);
    if (d114 < d) {
        d = d114;
        m = 0x3u;
    }
    let d115 = em_node115(p);
    if (d115 < d) {
        d = d115;
        m = 0x3u;
    }
    let d116 = em_node116(p);
    if (d116 < d) {
        d = d116;
        m = 0x3u;
    }
    let d117 = em_node117(p);
    if (d117 < d) {
        d = d117;
        m = 0x3u;
    }
    let d118 = em_node118(p);
    if (d118 < d) {
        d = d118;
        m = 0x3u;
    }
    let d119 = em_node119(p);
    if (d119 < d) {
        d = d119;
        m = 0x3u;
    }
    let d120 = em_node120(p);
    if (d120 < d) {
        d = d120;
        m = 0x3u;
    }
    let d121 = em_node121(p);
    if (d121 < d) {
        d = d121;
        m = 0x3u;
    }
    let d122 = em_node122(p);
    if (d122 < d) {
        d = d122;
        m = 0x3u;
    }
    let d123 = em_node123(p);
    if (d123 < d) {
        d = d123;
        m = 0x3u;
    }
    let d124 = em_node124(p);
    if (d124 < d) {
        d = d124;
        m = 0x3u;
    }
    let d125 = em_node125(p);
    if (d125 < d) {
        d = d125;
        m = 0x3u;
    }
    let d126 = em_node126(p);
    if (d126 < d) {
        d = d126;
        m = 0x3u;
    }
    let d127 = em_node127(p);
    if (d127 < d) {
        d = d127;
        m = 0x3u;
    }
    let d128 = em_node128(p);
    if (d128 < d) {
        d = d128;
        m = 0x3u;
    }
    let d129 = em_node129(p);
    if (d129 < d) {
        d = d129;
        m = 0x6u;
    }
    let d130 = em_node130(p);
    if (d130 < d) {
        d = d130;
        m = 0x6u;
    }
    let d131 = em_node131(p);
    if (d131 < d) {
        d = d131;
        m = 0x6u;
    }
    return MapHit(d, m);
}
fn em_dist(p: vec3<f32>) -> f32 {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    d = (p.y - em_height(p.xz).x) * 0.863672f;
    m = 0x0u;
    if (p.y > 13.734878f) {
        let e = p.y - 13.234878f;
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
        m = 0x5u;
    }
    let d3 = em_node3(p);
    if (d3 < d) {
        d = d3;
        m = 0x5u;
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
        m = 0x1u;
    }
    let d7 = em_node7(p);
    if (d7 < d) {
        d = d7;
        m = 0x2u;
    }
    let d8 = em_node8(p);
    if (d8 < d) {
        d = d8;
        m = 0x1u;
    }
    let d9 = em_node9(p);
    if (d9 < d) {
        d = d9;
        m = 0x2u;
    }
    let d10 = em_node10(p);
    if (d10 < d) {
        d = d10;
        m = 0x1u;
    }
    let d11 = em_node11(p);
    if (d11 < d) {
        d = d11;
        m = 0x2u;
    }
    let d12 = em_node12(p);
    if (d12 < d) {
        d = d12;
        m = 0x1u;
    }
    let d13 = em_node13(p);
    if (d13 < d) {
        d = d13;
        m = 0x2u;
    }
    let d14 = em_node14(p);
    if (d14 < d) {
        d = d14;
        m = 0x1u;
    }
    let d15 = em_node15(p);
    if (d15 < d) {
        d = d15;
        m = 0x2u;
    }
    let d16 = em_node16(p);
    if (d16 < d) {
        d = d16;
        m = 0x1u;
    }
    let d17 = em_node17(p);
    if (d17 < d) {
        d = d17;
        m = 0x2u;
    }
    let d18 = em_node18(p);
    if (d18 < d) {
        d = d18;
        m = 0x1u;
    }
    let d19 = em_node19(p);
    if (d19 < d) {
        d = d19;
        m = 0x2u;
    }
    let d20 = em_node20(p);
    if (d20 < d) {
        d = d20;
        m = 0x1u;
    }
    let d21 = em_node21(p);
    if (d21 < d) {
        d = d21;
        m = 0x2u;
    }
    let d22 = em_node22(p);
    if (d22 < d) {
        d = d22;
        m = 0x1u;
    }
    let d23 = em_node23(p);
    if (d23 < d) {
        d = d23;
        m = 0x2u;
    }
    let d24 = em_node24(p);
    if (d24 < d) {
        d = d24;
        m = 0x1u;
    }
    let d25 = em_node25(p);
    if (d25 < d) {
        d = d25;
        m = 0x2u;
    }
    let d26 = em_node26(p);
    if (d26 < d) {
        d = d26;
        m = 0x1u;
    }
    let d27 = em_node27(p);
    if (d27 < d) {
        d = d27;
        m = 0x2u;
    }
    let d28 = em_node28(p);
    if (d28 < d) {
        d = d28;
        m = 0x1u;
    }
    let d29 = em_node29(p);
    if (d29 < d) {
        d = d29;
        m = 0x2u;
    }
    let d30 = em_node30(p);
    if (d30 < d) {
        d = d30;
        m = 0x1u;
    }
    let d31 = em_node31(p);
    if (d31 < d) {
        d = d31;
        m = 0x2u;
    }
    let d32 = em_node32(p);
    if (d32 < d) {
        d = d32;
        m = 0x1u;
    }
    let d33 = em_node33(p);
    if (d33 < d) {
        d = d33;
        m = 0x2u;
    }
    let d34 = em_node34(p);
    if (d34 < d) {
        d = d34;
        m = 0x1u;
    }
    let d35 = em_node35(p);
    if (d35 < d) {
        d = d35;
        m = 0x2u;
    }
    let d36 = em_node36(p);
    if (d36 < d) {
        d = d36;
        m = 0x1u;
    }
    let d37 = em_node37(p);
    if (d37 < d) {
        d = d37;
        m = 0x2u;
    }
    let d38 = em_node38(p);
    if (d38 < d) {
        d = d38;
        m = 0x1u;
    }
    let d39 = em_node39(p);
    if (d39 < d) {
        d = d39;
        m = 0x2u;
    }
    let d40 = em_node40(p);
    if (d40 < d) {
        d = d40;
        m = 0x1u;
    }
    let d41 = em_node41(p);
    if (d41 < d) {
        d = d41;
        m = 0x2u;
    }
    let d42 = em_node42(p);
    if (d42 < d) {
        d = d42;
        m = 0x1u;
    }
    let d43 = em_node43(p);
    if (d43 < d) {
        d = d43;
        m = 0x2u;
    }
    let d44 = em_node44(p);
    if (d44 < d) {
        d = d44;
        m = 0x1u;
    }
    let d45 = em_node45(p);
    if (d45 < d) {
        d = d45;
        m = 0x2u;
    }
    let d46 = em_node46(p);
    if (d46 < d) {
        d = d46;
        m = 0x1u;
    }
    let d47 = em_node47(p);
    if (d47 < d) {
        d = d47;
        m = 0x2u;
    }
    let d48 = em_node48(p);
    if (d48 < d) {
        d = d48;
        m = 0x1u;
    }
    let d49 = em_node49(p);
    if (d49 < d) {
        d = d49;
        m = 0x2u;
    }
    let d50 = em_node50(p);
    if (d50 < d) {
        d = d50;
        m = 0x1u;
    }
    let d51 = em_node51(p);
    if (d51 < d) {
        d = d51;
        m = 0x2u;
    }
    let d52 = em_node52(p);
    if (d52 < d) {
        d = d52;
        m = 0x1u;
    }
    let d53 = em_node53(p);
    if (d53 < d) {
        d = d53;
        m = 0x2u;
    }
    let d54 = em_node54(p);
    if (d54 < d) {
        d = d54;
        m = 0x1u;
    }
    let d55 = em_node55(p);
    if (d55 < d) {
        d = d55;
        m = 0x2u;
    }
    let d56 = em_node56(p);
    if (d56 < d) {
        d = d56;
        m = 0x1u;
    }
    let d57 = em_node57(p);
    if (d57 < d) {
        d = d57;
        m = 0x2u;
    }
    let d58 = em_node58(p);
    if (d58 < d) {
        d = d58;
        m = 0x1u;
    }
    let d59 = em_node59(p);
    if (d59 < d) {
        d = d59;
        m = 0x2u;
    }
    let d60 = em_node60(p);
    if (d60 < d) {
        d = d60;
        m = 0x1u;
    }
    let d61 = em_node61(p);
    if (d61 < d) {
        d = d61;
        m = 0x2u;
    }
    let d62 = em_node62(p);
    if (d62 < d) {
        d = d62;
        m = 0x1u;
    }
    let d63 = em_node63(p);
    if (d63 < d) {
        d = d63;
        m = 0x2u;
    }
    let d64 = em_node64(p);
    if (d64 < d) {
        d = d64;
        m = 0x1u;
    }
    let d65 = em_node65(p);
    if (d65 < d) {
        d = d65;
        m = 0x2u;
    }
    let d66 = em_node66(p);
    if (d66 < d) {
        d = d66;
        m = 0x1u;
    }
    let d67 = em_node67(p);
    if (d67 < d) {
        d = d67;
        m = 0x2u;
    }
    let d68 = em_node68(p);
    if (d68 < d) {
        d = d68;
        m = 0x1u;
    }
    let d69 = em_node69(p);
    if (d69 < d) {
        d = d69;
        m = 0x2u;
    }
    let d70 = em_node70(p);
    if (d70 < d) {
        d = d70;
        m = 0x1u;
    }
    let d71 = em_node71(p);
    if (d71 < d) {
        d = d71;
        m = 0x2u;
    }
    let d72 = em_node72(p);
    if (d72 < d) {
        d = d72;
        m = 0x1u;
    }
    let d73 = em_node73(p);
    if (d73 < d) {
        d = d73;
        m = 0x2u;
    }
    let d74 = em_node74(p);
    if (d74 < d) {
        d = d74;
        m = 0x1u;
    }
    let d75 = em_node75(p);
    if (d75 < d) {
        d = d75;
        m = 0x2u;
    }
    let d76 = em_node76(p);
    if (d76 < d) {
        d = d76;
        m = 0x1u;
    }
    let d77 = em_node77(p);
    if (d77 < d) {
        d = d77;
        m = 0x2u;
    }
    let d78 = em_node78(p);
    if (d78 < d) {
        d = d78;
        m = 0x1u;
    }
    let d79 = em_node79(p);
    if (d79 < d) {
        d = d79;
        m = 0x2u;
    }
    let d80 = em_node80(p);
    if (d80 < d) {
        d = d80;
        m = 0x1u;
    }
    let d81 = em_node81(p);
    if (d81 < d) {
        d = d81;
        m = 0x2u;
    }
    let d82 = em_node82(p);
    if (d82 < d) {
        d = d82;
        m = 0x1u;
    }
    let d83 = em_node83(p);
    if (d83 < d) {
        d = d83;
        m = 0x2u;
    }
    let d84 = em_node84(p);
    if (d84 < d) {
        d = d84;
        m = 0x1u;
    }
    let d85 = em_node85(p);
    if (d85 < d) {
        d = d85;
        m = 0x2u;
    }
    let d86 = em_node86(p);
    if (d86 < d) {
        d = d86;
        m = 0x1u;
    }
    let d87 = em_node87(p);
    if (d87 < d) {
        d = d87;
        m = 0x2u;
    }
    let d88 = em_node88(p);
    if (d88 < d) {
        d = d88;
        m = 0x1u;
    }
    let d89 = em_node89(p);
    if (d89 < d) {
        d = d89;
        m = 0x2u;
    }
    let d90 = em_node90(p);
    if (d90 < d) {
        d = d90;
        m = 0x1u;
    }
    let d91 = em_node91(p);
    if (d91 < d) {
        d = d91;
        m = 0x2u;
    }
    let d92 = em_node92(p);
    if (d92 < d) {
        d = d92;
        m = 0x1u;
    }
    let d93 = em_node93(p);
    if (d93 < d) {
        d = d93;
        m = 0x2u;
    }
    let d94 = em_node94(p);
    if (d94 < d) {
        d = d94;
        m = 0x1u;
    }
    let d95 = em_node95(p);
    if (d95 < d) {
        d = d95;
        m = 0x2u;
    }
    let d96 = em_node96(p);
    if (d96 < d) {
        d = d96;
        m = 0x1u;
    }
    let d97 = em_node97(p);
    if (d97 < d) {
        d = d97;
        m = 0x2u;
    }
    let d98 = em_node98(p);
    if (d98 < d) {
        d = d98;
        m = 0x1u;
    }
    let d99 = em_node99(p);
    if (d99 < d) {
        d = d99;
        m = 0x2u;
    }
    let d100 = em_node100(p);
    if (d100 < d) {
        d = d100;
        m = 0x1u;
    }
    let d101 = em_node101(p);
    if (d101 < d) {
        d = d101;
        m = 0x2u;
    }
    let d102 = em_node102(p);
    if (d102 < d) {
        d = d102;
        m = 0x1u;
    }
    let d103 = em_node103(p);
    if (d103 < d) {
        d = d103;
        m = 0x2u;
    }
    let d104 = em_node104(p);
    if (d104 < d) {
        d = d104;
        m = 0x1u;
    }
    let d105 = em_node105(p);
    if (d105 < d) {
        d = d105;
        m = 0x2u;
    }
    let d106 = em_node106(p);
    if (d106 < d) {
        d = d106;
        m = 0x1u;
    }
    let d107 = em_node107(p);
    if (d107 < d) {
        d = d107;
        m = 0x2u;
    }
    let d108 = em_node108(p);
    if (d108 < d) {
        d = d108;
        m = 0x1u;
    }
    let d109 = em_node109(p);
    if (d109 < d) {
        d = d109;
        m = 0x2u;
    }
    let d110 = em_node110(p);
    if (d110 < d) {
        d = d110;
        m = 0x1u;
    }
    let d111 = em_node111(p);
    if (d111 < d) {
        d = d111;
        m = 0x2u;
    }
    let d112 = em_node112(p);
    if (d112 < d) {
        d = d112;
        m = 0x1u;
    }
    let d113 = em_node113(p);
    if (d113 < d) {
        d = d113;
        m = 0x2u;
    }
    let d114 = em_node114(p);
    if (d114 < d) {
        d = d114;
        m = 0x3u;
    }
    let d115 = em_node115(p);
    if (d115 < d) {
        d = d115;
        m = 0x3u;
    }
    let d116 = em_node116(p);
    if (d116 < d) {
        d = d116;
        m = 0x3u;
    }
    let d117 = em_node117(p);
    if (d117 < d) {
        d = d117;
        m = 0x3u;
    }
    let d118 = em_node118(p);
    if (d118 < d) {
        d = d118;
        m = 0x3u;
    }
    let d119 = em_node119(p);
    if (d119 < d) {
        d = d119;
        m = 0x3u;
    }
    let d120 = em_node120(p);
    if (d120 < d) {
        d = d120;
        m = 0x3u;
    }
    let d121 = em_node121(p);
    if (d121 < d) {
        d = d121;
        m = 0x3u;
    }
    let d122 = em_node122(p);
    if (d122 < d) {
        d = d122;
        m = 0x3u;
    }
    let d123 = em_node123(p);
    if (d123 < d) {
        d = d123;
        m = 0x3u;
    }
    let d124 = em_node124(p);
    if (d124 < d) {
        d = d124;
        m = 0x3u;
    }
    let d125 = em_node125(p);
    if (d125 < d) {
        d = d125;
        m = 0x3u;
    }
    let d126 = em_node126(p);
    if (d126 < d) {
        d = d126;
        m = 0x3u;
    }
    let d127 = em_node127(p);
    if (d127 < d) {
        d = d127;
        m = 0x3u;
    }
    let d128 = em_node128(p);
    if (d128 < d) {
        d = d128;
        m = 0x3u;
    }
    let d129 = em_node129(p);
    if (d129 < d) {
        d = d129;
        m = 0x6u;
    }
    let d130 = em_node130(p);
    if (d130 < d) {
        d = d130;
        m = 0x6u;
    }
    let d131 = em_node131(p);
    if (d131 < d) {
        d = d131;
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
        let oc = vec3<f32>(16.0f, 6.869408f, 30.0f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 18.013685f);
    }
    {
        let oc = vec3<f32>(-22.0f, 7.60354f, 40.0f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 18.013685f);
    }
    {
        let oc = vec3<f32>(-4.29f, 6.0570817f, 26.57f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.2487507f);
    }
    {
        let oc = vec3<f32>(-4.2486343f, 8.828599f, 26.549192f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.453604f);
    }
    {
        let oc = vec3<f32>(-3.09f, 4.858754f, 20.86f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.49228f);
    }
    {
        let oc = vec3<f32>(-3.0553284f, 7.2060423f, 20.84256f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.2364264f);
    }
    {
        let oc = vec3<f32>(-28.38f, 5.4742837f, 21.31f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.687225f);
    }
    {
        let oc = vec3<f32>(-28.344526f, 7.8723345f, 21.292156f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.481168f);
    }
    {
        let oc = vec3<f32>(-36.84f, 7.1067777f, 54.06f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.0164795f);
    }
    {
        let oc = vec3<f32>(-36.80321f, 9.588224f, 54.041496f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.8953795f);
    }
    {
        let oc = vec3<f32>(-41.23f, 5.656028f, 73.04f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.4948525f);
    }
    {
        let oc = vec3<f32>(-41.187775f, 8.481933f, 73.01876f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.766094f);
    }
    {
        let oc = vec3<f32>(30.82f, 5.439542f, 22.1f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.743684f);
    }
    {
        let oc = vec3<f32>(30.855701f, 7.852096f, 22.082043f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.552122f);
    }
    {
        let oc = vec3<f32>(-0.02f, 6.530218f, 37.87f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.8808997f);
    }
    {
        let oc = vec3<f32>(0.012039706f, 8.710715f, 37.85388f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.4716306f);
    }
    {
        let oc = vec3<f32>(-19.97f, 6.7762427f, 74.74f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.661563f);
    }
    {
        let oc = vec3<f32>(-19.927202f, 9.638407f, 74.71847f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.977981f);
    }
    {
        let oc = vec3<f32>(30.62f, 5.3358793f, 42.86f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.2670562f);
    }
    {
        let oc = vec3<f32>(30.64918f, 7.335082f, 42.845325f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.708773f);
    }
    {
        let oc = vec3<f32>(23.97f, 5.2693043f, 9.04f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.8177447f);
    }
    {
        let oc = vec3<f32>(24.00982f, 7.9429226f, 9.01997f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.907299f);
    }
    {
        let oc = vec3<f32>(-10.21f, 7.2497935f, 70.38f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.8334327f);
    }
    {
        let oc = vec3<f32>(-10.170122f, 9.927038f, 70.35994f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.927158f);
    }
    {
        let oc = vec3<f32>(-2.7f, 6.8682246f, 72.84f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.616653f);
    }
    {
        let oc = vec3<f32>(-2.6691618f, 8.972578f, 72.824486f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.142545f);
    }
    {
        let oc = vec3<f32>(-38.43f, 6.2976403f, 34.24f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.4475555f);
    }
    {
        let oc = vec3<f32>(-38.391552f, 8.884238f, 34.22066f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.4391418f);
    }
    {
        let oc = vec3<f32>(41.77f, 3.8805637f, 48.38f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.5066803f);
    }
    {
        let oc = vec3<f32>(41.79523f, 5.6295805f, 48.36731f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.7731078f);
    }
    {
        let oc = vec3<f32>(-29.01f, 5.4949493f, 26.52f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.8425806f);
    }
    {
        let oc = vec3<f32>(-28.978132f, 7.6645694f, 26.50397f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.4238462f);
    }
    {
        let oc = vec3<f32>(-27.84f, 6.6786413f, 45.51f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.5584004f);
    }
    {
        let oc = vec3<f32>(-27.814482f, 8.445787f, 45.49716f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.8363478f);
    }
    {
        let oc = vec3<f32>(42.38f, 4.1186547f, 53.38f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.2202303f);
    }
    {
        let oc = vec3<f32>(42.40895f, 6.1033545f, 53.36544f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.650823f);
    }
    {
        let oc = vec3<f32>(31.89f, 5.1413713f, 35.6f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.4453137f);
    }
    {
        let oc = vec3<f32>(31.914888f, 6.8686323f, 35.58748f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.698166f);
    }
    {
        let oc = vec3<f32>(24.54f, 4.594182f, 1.19f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.196944f);
    }
    {
        let oc = vec3<f32>(24.568836f, 6.5716295f, 1.1754954f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.6220207f);
    }
    {
        let oc = vec3<f32>(-23.13f, 5.722782f, 31.14f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.5062566f);
    }
    {
        let oc = vec3<f32>(-23.099676f, 7.7945027f, 31.124746f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.0053606f);
    }
    {
        let oc = vec3<f32>(-31.13f, 6.263386f, 64.93f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.662021f);
    }
    {
        let oc = vec3<f32>(-31.090752f, 8.900745f, 64.910255f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.7102413f);
    }
    {
        let oc = vec3<f32>(34.4f, 5.3733034f, 31.39f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.7287614f);
    }
    {
        let oc = vec3<f32>(34.431355f, 7.510289f, 31.37423f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.2820435f);
    }
    {
        let oc = vec3<f32>(-21.87f, 7.029038f, 55.61f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.5337057f);
    }
    {
        let oc = vec3<f32>(-21.835157f, 9.387203f, 55.592476f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.2884054f);
    }
    {
        let oc = vec3<f32>(-19.78f, 6.541705f, 65.91f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.8249207f);
    }
    {
        let oc = vec3<f32>(-19.753054f, 8.399499f, 65.896454f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.1632352f);
    }
    {
        let oc = vec3<f32>(-11.81f, 5.7196035f, 27.94f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.5584004f);
    }
    {
        let oc = vec3<f32>(-11.784483f, 7.4867496f, 27.927166f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.8363488f);
    }
    {
        let oc = vec3<f32>(-12.41f, 7.384855f, 63.0f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.5779433f);
    }
    {
        let oc = vec3<f32>(-12.36749f, 10.228889f, 62.97862f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.8716774f);
    }
    {
        let oc = vec3<f32>(14.12f, 6.525482f, 41.03f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.478514f);
    }
    {
        let oc = vec3<f32>(14.154614f, 8.869144f, 41.01259f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.2191596f);
    }
    {
        let oc = vec3<f32>(-43.39f, 5.643468f, 65.12f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.0456386f);
    }
    {
        let oc = vec3<f32>(-43.353096f, 8.132167f, 65.10144f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.932107f);
    }
    {
        let oc = vec3<f32>(-1.6f, 6.5473557f, 45.35f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.290596f);
    }
    {
        let oc = vec3<f32>(-1.5707065f, 8.55381f, 45.335262f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.7379162f);
    }
    {
        let oc = vec3<f32>(21.33f, 5.6700287f, 64.02f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.2372313f);
    }
    {
        let oc = vec3<f32>(21.367647f, 8.205864f, 64.00106f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.1736426f);
    }
    {
        let oc = vec3<f32>(18.33f, 6.1707797f, 52.26f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.2001f);
    }
    {
        let oc = vec3<f32>(18.371195f, 8.931419f, 52.239277f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.391876f);
    }
    {
        let oc = vec3<f32>(-13.33f, 7.792447f, 40.37f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.1194396f);
    }
    {
        let oc = vec3<f32>(-13.289092f, 10.534958f, 40.349422f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.2895675f);
    }
    {
        let oc = vec3<f32>(33.4f, 5.419709f, 10.89f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.523675f);
    }
    {
        let oc = vec3<f32>(33.438736f, 8.024436f, 10.870517f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.535325f);
    }
    {
        let oc = vec3<f32>(32.71f, 5.5675545f, 28.01f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.6731634f);
    }
    {
        let oc = vec3<f32>(32.745415f, 7.961981f, 27.992186f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.4634976f);
    }
    {
        let oc = vec3<f32>(44.4f, 4.734331f, 61.78f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.1927023f);
    }
    {
        let oc = vec3<f32>(44.437477f, 7.259288f, 61.761147f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.117477f);
    }
    {
        let oc = vec3<f32>(-10.04f, 7.2397294f, 45.85f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.451045f);
    }
    {
        let oc = vec3<f32>(-10.0055f, 9.576139f, 45.832645f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.1847105f);
    }
    {
        let oc = vec3<f32>(-5.35f, 6.60511f, 57.22f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.3847077f);
    }
    {
        let oc = vec3<f32>(-5.325455f, 8.3106165f, 57.207657f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.6242454f);
    }
    {
        let oc = vec3<f32>(10.31f, 5.8515024f, 66.25f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.0363064f);
    }
    {
        let oc = vec3<f32>(10.338036f, 7.7781878f, 66.23589f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.4235902f);
    }
    {
        let oc = vec3<f32>(36.51f, 5.2473483f, 37.6f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.8171396f);
    }
    {
        let oc = vec3<f32>(36.54175f, 7.4097166f, 37.584026f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.3921347f);
    }
    {
        let oc = vec3<f32>(-27.13f, 4.936064f, 12.4f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.6003227f);
    }
    {
        let oc = vec3<f32>(-27.090979f, 7.55892f, 12.380372f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.632214f);
    }
    {
        let oc = vec3<f32>(37.28f, 4.606022f, 61.83f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.5673769f);
    }
    {
        let oc = vec3<f32>(37.310608f, 6.6958714f, 61.814606f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.0812917f);
    }
    {
        let oc = vec3<f32>(7.48f, 2.4352632f, -0.19f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.5792358f);
    }
    {
        let oc = vec3<f32>(7.505632f, 4.2096615f, -0.20289302f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.8618429f);
    }
    {
        let oc = vec3<f32>(-0.32f, 7.370852f, 57.08f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.8334327f);
    }
    {
        let oc = vec3<f32>(-0.28012186f, 10.048096f, 57.05994f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.927158f);
    }
    {
        let oc = vec3<f32>(19.01f, 5.451375f, 69.5f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.1161075f);
    }
    {
        let oc = vec3<f32>(19.038435f, 7.403441f, 69.485695f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.5221083f);
    }
    {
        let oc = vec3<f32>(-7.74f, 6.875169f, 33.83f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.04915f);
    }
    {
        let oc = vec3<f32>(-7.7072163f, 9.102802f, 33.81351f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.6816516f);
    }
    {
        let oc = vec3<f32>(-16.62f, 7.4815464f, 57.3f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.5946245f);
    }
    {
        let oc = vec3<f32>(-16.577435f, 10.329207f, 57.278587f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.892883f);
    }
    {
        let oc = vec3<f32>(11.7f, 6.7543178f, 37.05f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.615715f);
    }
    {
        let oc = vec3<f32>(11.739077f, 9.3808f, 37.030342f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.651674f);
    }
    {
        let oc = vec3<f32>(41.26f, 4.585505f, 40.29f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.8140063f);
    }
    {
        let oc = vec3<f32>(41.28689f, 6.4396715f, 40.276474f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.14982f);
    }
    {
        let oc = vec3<f32>(1.84f, 6.844435f, 32.59f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.3418765f);
    }
    {
        let oc = vec3<f32>(1.8780472f, 9.405651f, 32.57086f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.305698f);
    }
    {
        let oc = vec3<f32>(-9.58f, 7.5239406f, 52.11f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.151641f);
    }
    {
        let oc = vec3<f32>(-9.538978f, 10.273703f, 52.089367f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.3304076f);
    }
    {
        let oc = vec3<f32>(-37.15f, 5.622462f, 67.59f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 5.1631207f);
    }
    {
        let oc = vec3<f32>(-37.11264f, 8.140167f, 67.571205f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.080177f);
    }
    {
        let oc = vec3<f32>(34.14f, 5.3977504f, 52.64f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 6.3630075f);
    }
    {
        let oc = vec3<f32>(34.181763f, 8.194649f, 52.61899f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 7.598633f);
    }
    {
        let oc = vec3<f32>(43.24f, 5.0948534f, 72.51f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.2477217f);
    }
    {
        let oc = vec3<f32>(43.273643f, 7.376877f, 72.49308f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.929969f);
    }
    {
        let oc = vec3<f32>(4.53f, 7.0671687f, 49.51f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.0230327f);
    }
    {
        let oc = vec3<f32>(4.5626693f, 9.287552f, 49.493565f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 4.6490245f);
    }
    {
        let oc = vec3<f32>(-42.44f, 6.204734f, 54.01f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.314962f);
    }
    {
        let oc = vec3<f32>(-42.415855f, 7.8848577f, 53.997852f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.5393069f);
    }
    {
        let oc = vec3<f32>(20.4f, 5.196979f, 35.15f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.4707696f);
    }
    {
        let oc = vec3<f32>(1.6f, 0.7643615f, 3.21f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.5625603f);
    }
    {
        let oc = vec3<f32>(8.33f, 4.5667953f, 21.82f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.0234256f);
    }
    {
        let oc = vec3<f32>(-7.13f, 5.8924055f, 47.62f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.268141f);
    }
    {
        let oc = vec3<f32>(-17.51f, 6.475709f, 48.06f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 3.5743687f);
    }
    {
        let oc = vec3<f32>(1.45f, 4.614062f, 25.84f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 0.8805946f);
    }
    {
        let oc = vec3<f32>(2.15f, 4.0476313f, 20.25f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 2.059799f);
    }
    {
        let oc = vec3<f32>(-28.33f, 5.760352f, 57.55f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 1.7550951f);
    }
    {
        let oc = vec3<f32>(-5.96f, 5.771969f, 44.09f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 1.9426785f);
    }
    {
        let oc = vec3<f32>(-1.61f, 1.1013527f, -9.84f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 1.5084754f);
    }
    {
        let oc = vec3<f32>(-1.41f, 0.9032268f, 5.38f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 0.8548853f);
    }
    {
        let oc = vec3<f32>(7.07f, 5.742277f, 54.02f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 0.7320514f);
    }
    {
        let oc = vec3<f32>(-16.36f, 5.794621f, 34.96f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 1.1885362f);
    }
    {
        let oc = vec3<f32>(-8.68f, 4.974424f, 29.58f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 0.6629216f);
    }
    {
        let oc = vec3<f32>(13.85f, 2.6232781f, -10.18f) - o;
        let b = dot(oc, em_sun);
        meets = meets || (b > 0.0 && b * b > dot(oc, oc) - 1.7550951f);
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

