// Emitted by craterfield::emit::codegen3d for plan key 0xf907e0522f4ef598.
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
    return sd_sphere((p - vec3<f32>(-36.84f, 4.3724f, 54.06f)), 1.929f);
}
fn em_node11(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7765276f, 0.0);
    return sd_sphere((p - vec3<f32>(-41.23f, 5.0184f, 73.04f)), 2.2140002f);
}
fn em_node12(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.8735418f, 0.0);
    return sd_capsule((p - vec3<f32>(30.82f, 0.0f, 22.1f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.432f, 0.0f), 0.312f);
}
fn em_node13(pw: vec3<f32>) -> f32 {
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
fn em_node14(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.1402183f, 0.0);
    return sd_capsule((p - vec3<f32>(-0.02f, 0.0f, 37.87f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.08f, 0.0f), 0.28f);
}
fn em_node15(pw: vec3<f32>) -> f32 {
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
fn em_node16(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.8692427f, 0.0);
    return sd_sphere((p - vec3<f32>(-19.97f, 5.0864f, 74.74f)), 2.2440002f);
}
fn em_node17(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0833793f, 0.0);
    return sd_sphere((p - vec3<f32>(30.62f, 3.468f, 42.86f)), 1.5300001f);
}
fn em_node18(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.5053043f, 0.0);
    return sd_capsule((p - vec3<f32>(23.97f, 0.0f, 9.04f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.828f, 0.0f), 0.34800002f);
}
fn em_node19(pw: vec3<f32>) -> f32 {
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
fn em_node20(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.4830437f, 0.0);
    return sd_sphere((p - vec3<f32>(-10.21f, 4.7395997f, 70.38f)), 2.091f);
}
fn em_node21(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5359745f, 0.0);
    return sd_sphere((p - vec3<f32>(-2.7f, 3.6652f, 72.84f)), 1.617f);
}
fn em_node22(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.5996404f, 0.0);
    return sd_sphere((p - vec3<f32>(-38.43f, 4.5696f, 34.24f)), 2.016f);
}
fn em_node23(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.8178139f, 0.0);
    return sd_sphere((p - vec3<f32>(41.77f, 2.9988f, 48.38f)), 1.323f);
}
fn em_node24(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.113199f, 0.0);
    return sd_capsule((p - vec3<f32>(-29.01f, 0.0f, 26.52f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.0635002f, 0.0f), 0.27850002f);
}
fn em_node25(pw: vec3<f32>) -> f32 {
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
fn em_node26(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.6021414f, 0.0);
    return sd_sphere((p - vec3<f32>(-27.84f, 3.0328f, 45.51f)), 1.338f);
}
fn em_node27(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.8771548f, 0.0);
    return sd_sphere((p - vec3<f32>(42.38f, 3.4408f, 53.38f)), 1.518f);
}
fn em_node28(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0951214f, 0.0);
    return sd_sphere((p - vec3<f32>(31.89f, 2.958f, 35.6f)), 1.3050001f);
}
fn em_node29(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.3581817f, 0.0);
    return sd_capsule((p - vec3<f32>(24.54f, 0.0f, 1.19f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.772f, 0.0f), 0.252f);
}
fn em_node30(pw: vec3<f32>) -> f32 {
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
fn em_node31(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.415282f, 0.0);
    return sd_capsule((p - vec3<f32>(-23.13f, 0.0f, 31.14f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.9150002f, 0.0f), 0.26500002f);
}
fn em_node32(pw: vec3<f32>) -> f32 {
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
fn em_node33(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.5268855f, 0.0);
    return sd_sphere((p - vec3<f32>(-31.13f, 4.6648f, 64.93f)), 2.058f);
}
fn em_node34(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.016303f, 0.0);
    return sd_sphere((p - vec3<f32>(34.4f, 3.7264001f, 31.39f)), 1.644f);
}
fn em_node35(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5042877f, 0.0);
    return sd_sphere((p - vec3<f32>(-21.87f, 4.1412f, 55.61f)), 1.8270001f);
}
fn em_node36(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.3964553f, 0.0);
    return sd_sphere((p - vec3<f32>(-19.78f, 3.2028f, 65.91f)), 1.4130001f);
}
fn em_node37(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.6431036f, 0.0);
    return sd_capsule((p - vec3<f32>(-11.81f, 0.0f, 27.94f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.453f, 0.0f), 0.223f);
}
fn em_node38(pw: vec3<f32>) -> f32 {
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
fn em_node39(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.491605f, 0.0);
    return sd_sphere((p - vec3<f32>(-12.41f, 5.0524f, 63.0f)), 2.229f);
}
fn em_node40(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.011732f, 0.0);
    return sd_sphere((p - vec3<f32>(14.12f, 4.1140003f, 41.03f)), 1.8150002f);
}
fn em_node41(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.019718f, 0.0);
    return sd_sphere((p - vec3<f32>(-43.39f, 4.3859997f, 65.12f)), 1.9350001f);
}
fn em_node42(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.2893558f, 0.0);
    return sd_sphere((p - vec3<f32>(-1.6f, 3.4816f, 45.35f)), 1.536f);
}
fn em_node43(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0105286f, 0.0);
    return sd_sphere((p - vec3<f32>(21.33f, 4.4744f, 64.02f)), 1.9740001f);
}
fn em_node44(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.34078f, 0.0);
    return sd_sphere((p - vec3<f32>(18.33f, 4.896f, 52.26f)), 2.16f);
}
fn em_node45(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.976197f, 0.0);
    return sd_sphere((p - vec3<f32>(-13.33f, 4.862f, 40.37f)), 2.1450002f);
}
fn em_node46(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7079594f, 0.0);
    return sd_capsule((p - vec3<f32>(33.4f, 0.0f, 10.89f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.7235f, 0.0f), 0.3385f);
}
fn em_node47(pw: vec3<f32>) -> f32 {
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
fn em_node48(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.0153046f, 0.0);
    return sd_capsule((p - vec3<f32>(32.71f, 0.0f, 28.01f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.4045f, 0.0f), 0.3095f);
}
fn em_node49(pw: vec3<f32>) -> f32 {
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
fn em_node50(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.0830808f, 0.0);
    return sd_sphere((p - vec3<f32>(44.4f, 4.454f, 61.78f)), 1.9650002f);
}
fn em_node51(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.731479f, 0.0);
    return sd_sphere((p - vec3<f32>(-10.04f, 4.1004f, 45.85f)), 1.8090001f);
}
fn em_node52(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5753603f, 0.0);
    return sd_sphere((p - vec3<f32>(-5.35f, 2.9172f, 57.22f)), 1.2870001f);
}
fn em_node53(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.654002f, 0.0);
    return sd_sphere((p - vec3<f32>(10.31f, 3.332f, 66.25f)), 1.47f);
}
fn em_node54(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.8710983f, 0.0);
    return sd_sphere((p - vec3<f32>(36.51f, 3.7740002f, 37.6f)), 1.6650001f);
}
fn em_node55(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.2105634f, 0.0);
    return sd_capsule((p - vec3<f32>(-27.13f, 0.0f, 12.4f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.7510002f, 0.0f), 0.34100002f);
}
fn em_node56(pw: vec3<f32>) -> f32 {
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
fn em_node57(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.2847717f, 0.0);
    return sd_sphere((p - vec3<f32>(37.28f, 3.638f, 61.83f)), 1.605f);
}
fn em_node58(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 1.3532633f, 0.0);
    return sd_capsule((p - vec3<f32>(7.48f, 0.0f, -0.19f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 2.464f, 0.0f), 0.224f);
}
fn em_node59(pw: vec3<f32>) -> f32 {
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
fn em_node60(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.604102f, 0.0);
    return sd_sphere((p - vec3<f32>(-0.32f, 4.7395997f, 57.08f)), 2.091f);
}
fn em_node61(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.234625f, 0.0);
    return sd_sphere((p - vec3<f32>(19.01f, 3.3795998f, 69.5f)), 1.4909999f);
}
fn em_node62(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.449419f, 0.0);
    return sd_capsule((p - vec3<f32>(-7.74f, 0.0f, 33.83f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.1515f, 0.0f), 0.2865f);
}
fn em_node63(pw: vec3<f32>) -> f32 {
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
fn em_node64(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5855465f, 0.0);
    return sd_sphere((p - vec3<f32>(-16.62f, 5.0592003f, 57.3f)), 2.232f);
}
fn em_node65(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.0260677f, 0.0);
    return sd_capsule((p - vec3<f32>(11.7f, 0.0f, 37.05f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.7565f, 0.0f), 0.3415f);
}
fn em_node66(pw: vec3<f32>) -> f32 {
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
fn em_node67(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.4430048f, 0.0);
    return sd_sphere((p - vec3<f32>(41.26f, 3.1959999f, 40.29f)), 1.41f);
}
fn em_node68(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.165685f, 0.0);
    return sd_capsule((p - vec3<f32>(1.84f, 0.0f, 32.59f)), vec3<f32>(0.0f, -0.3f, 0.0f), vec3<f32>(0.0f, 3.6575f, 0.0f), 0.3325f);
}
fn em_node69(pw: vec3<f32>) -> f32 {
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
fn em_node70(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.7021904f, 0.0);
    return sd_sphere((p - vec3<f32>(-9.58f, 4.8756003f, 52.11f)), 2.151f);
}
fn em_node71(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.9767118f, 0.0);
    return sd_sphere((p - vec3<f32>(-37.15f, 4.4404f, 67.59f)), 1.9590001f);
}
fn em_node72(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.5402503f, 0.0);
    return sd_sphere((p - vec3<f32>(34.14f, 4.964f, 52.64f)), 2.19f);
}
fn em_node73(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.6278534f, 0.0);
    return sd_sphere((p - vec3<f32>(43.24f, 3.9984002f, 72.51f)), 1.764f);
}
fn em_node74(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.646919f, 0.0);
    return sd_sphere((p - vec3<f32>(4.53f, 3.8828f, 49.51f)), 1.713f);
}
fn em_node75(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.194234f, 0.0);
    return sd_sphere((p - vec3<f32>(-42.44f, 2.8695998f, 54.01f)), 1.266f);
}
fn em_node76(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.791979f, 0.0);
    return sd_ellipsoid((p - vec3<f32>(20.4f, 0.40500003f, 35.15f)), vec3<f32>(1.6200001f, 1.0125f, 1.35f));
}
fn em_node77(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.41636154f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(1.6f, 0.348f, 3.21f)), vec3<f32>(1.392f, 0.87f, 1.16f)) + 0.4176f * (noise3(p * 1.3793104f) - 0.5)) * 0.40056208f;
}
fn em_node78(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.188795f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(8.33f, 0.37800002f, 21.82f)), vec3<f32>(1.5120001f, 0.945f, 1.26f)) + 0.45360002f * (noise3(p * 1.2698413f) - 0.5)) * 0.40056208f;
}
fn em_node79(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.4994054f, 0.0);
    return sd_ellipsoid((p - vec3<f32>(-7.13f, 0.393f, 47.62f)), vec3<f32>(1.572f, 0.98249996f, 1.31f));
}
fn em_node80(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 6.064709f, 0.0);
    return sd_ellipsoid((p - vec3<f32>(-17.51f, 0.411f, 48.06f)), vec3<f32>(1.644f, 1.0275f, 1.37f));
}
fn em_node81(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.410062f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(1.45f, 0.20400001f, 25.84f)), vec3<f32>(0.81600004f, 0.51f, 0.68f)) + 0.24480002f * (noise3(p * 2.3529413f) - 0.5)) * 0.40056208f;
}
fn em_node82(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 3.7356312f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(2.15f, 0.312f, 20.25f)), vec3<f32>(1.248f, 0.78f, 1.04f)) + 0.3744f * (noise3(p * 1.5384616f) - 0.5)) * 0.40056208f;
}
fn em_node83(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.472352f, 0.0);
    return sd_ellipsoid((p - vec3<f32>(-28.33f, 0.28800002f, 57.55f)), vec3<f32>(1.1520001f, 0.71999997f, 0.96f));
}
fn em_node84(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.468969f, 0.0);
    return sd_ellipsoid((p - vec3<f32>(-5.96f, 0.303f, 44.09f)), vec3<f32>(1.212f, 0.7575f, 1.01f));
}
fn em_node85(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.83435273f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-1.61f, 0.26700002f, -9.84f)), vec3<f32>(1.0680001f, 0.6675f, 0.89f)) + 0.3204f * (noise3(p * 1.7977529f) - 0.5)) * 0.40056208f;
}
fn em_node86(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.70222676f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-1.41f, 0.20100002f, 5.38f)), vec3<f32>(0.8040001f, 0.5025f, 0.67f)) + 0.24120001f * (noise3(p * 2.3880596f) - 0.5)) * 0.40056208f;
}
fn em_node87(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.5562773f, 0.0);
    return sd_ellipsoid((p - vec3<f32>(7.07f, 0.186f, 54.02f)), vec3<f32>(0.744f, 0.465f, 0.62f));
}
fn em_node88(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 5.557621f, 0.0);
    return sd_ellipsoid((p - vec3<f32>(-16.36f, 0.23700002f, 34.96f)), vec3<f32>(0.9480001f, 0.59250003f, 0.79f));
}
fn em_node89(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 4.797424f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(-8.68f, 0.177f, 29.58f)), vec3<f32>(0.708f, 0.4425f, 0.59f)) + 0.2124f * (noise3(p * 2.7118645f) - 0.5)) * 0.40056208f;
}
fn em_node90(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 2.335278f, 0.0);
    return (sd_ellipsoid((p - vec3<f32>(13.85f, 0.28800002f, -10.18f)), vec3<f32>(1.1520001f, 0.71999997f, 0.96f)) + 0.3456f * (noise3(p * 1.6666667f) - 0.5)) * 0.40056208f;
}
fn em_node91(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.5620043f, 0.0);
    return sd_torus((mat3x3<f32>(1.0f, 0.0f, 0.0f, 0.0f, -4.371139e-8f, -1.0f, 0.0f, 1.0f, -4.371139e-8f) * (p - vec3<f32>(-4.0f, 2.2f, 4.0f))), 1.2f, 0.25f);
}
fn em_node92(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.49063477f, 0.0);
    return sd_cylinder((p - vec3<f32>(3.5f, 2.0f, 0.0f)), 0.35f, 2.5f);
}
fn em_node93(pw: vec3<f32>) -> f32 {
    let p = pw - vec3<f32>(0.0, 0.49063477f, 0.0);
    return sd_sphere((p - vec3<f32>(3.5f, 4.9f, 0.0f)), 0.7f);
}
fn em_map(p: vec3<f32>) -> MapHit {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    d = (p.y - em_height(p.xz).x) * 0.863672f;
    m = 0x0u;
    if (p.y > 13.483197f) {
        let e = p.y - 12.983197f;
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
        m = 0x2u;
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
        m = 0x2u;
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
        m = 0x2u;
    }
    let d21 = em_node21(p);
    if (d21 < d) {
        d = d21;
        m = 0x2u;
    }
    let d22 = em_node22(p);
    if (d22 < d) {
        d = d22;
        m = 0x2u;
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
        m = 0x2u;
    }
    let d27 = em_node27(p);
    if (d27 < d) {
        d = d27;
        m = 0x2u;
    }
    let d28 = em_node28(p);
    if (d28 < d) {
        d = d28;
        m = 0x2u;
    }
    let d29 = em_node29(p);
    if (d29 < d) {
        d = d29;
        m = 0x1u;
    }
    let d30 = em_node30(p);
    if (d30 < d) {
        d = d30;
        m = 0x2u;
    }
    let d31 = em_node31(p);
    if (d31 < d) {
        d = d31;
        m = 0x1u;
    }
    let d32 = em_node32(p);
    if (d32 < d) {
        d = d32;
        m = 0x2u;
    }
    let d33 = em_node33(p);
    if (d33 < d) {
        d = d33;
        m = 0x2u;
    }
    let d34 = em_node34(p);
    if (d34 < d) {
        d = d34;
        m = 0x2u;
    }
    let d35 = em_node35(p);
    if (d35 < d) {
        d = d35;
        m = 0x2u;
    }
    let d36 = em_node36(p);
    if (d36 < d) {
        d = d36;
        m = 0x2u;
    }
    let d37 = em_node37(p);
    if (d37 < d) {
        d = d37;
        m = 0x1u;
    }
    let d38 = em_node38(p);
    if (d38 < d) {
        d = d38;
        m = 0x2u;
    }
    let d39 = em_node39(p);
    if (d39 < d) {
        d = d39;
        m = 0x2u;
    }
    let d40 = em_node40(p);
    if (d40 < d) {
        d = d40;
        m = 0x2u;
    }
    let d41 = em_node41(p);
    if (d41 < d) {
        d = d41;
        m = 0x2u;
    }
    let d42 = em_node42(p);
    if (d42 < d) {
        d = d42;
        m = 0x2u;
    }
    let d43 = em_node43(p);
    if (d43 < d) {
        d = d43;
        m = 0x2u;
    }
    let d44 = em_node44(p);
    if (d44 < d) {
        d = d44;
        m = 0x2u;
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
        m = 0x2u;
    }
    let d51 = em_node51(p);
    if (d51 < d) {
        d = d51;
        m = 0x2u;
    }
    let d52 = em_node52(p);
    if (d52 < d) {
        d = d52;
        m = 0x2u;
    }
    let d53 = em_node53(p);
    if (d53 < d) {
        d = d53;
        m = 0x2u;
    }
    let d54 = em_node54(p);
    if (d54 < d) {
        d = d54;
        m = 0x2u;
    }
    let d55 = em_node55(p);
    if (d55 < d) {
        d = d55;
        m = 0x1u;
    }
    let d56 = em_node56(p);
    if (d56 < d) {
        d = d56;
        m = 0x2u;
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
        m = 0x2u;
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
        m = 0x2u;
    }
    let d65 = em_node65(p);
    if (d65 < d) {
        d = d65;
        m = 0x1u;
    }
    let d66 = em_node66(p);
    if (d66 < d) {
        d = d66;
        m = 0x2u;
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
        m = 0x2u;
    }
    let d71 = em_node71(p);
    if (d71 < d) {
        d = d71;
        m = 0x2u;
    }
    let d72 = em_node72(p);
    if (d72 < d) {
        d = d72;
        m = 0x2u;
    }
    let d73 = em_node73(p);
    if (d73 < d) {
        d = d73;
        m = 0x2u;
    }
    let d74 = em_node74(p);
    if (d74 < d) {
        d = d74;
        m = 0x2u;
    }
    let d75 = em_node75(p);
    if (d75 < d) {
        d = d75;
        m = 0x2u;
    }
    let d76 = em_node76(p);
    if (d76 < d) {
        d = d76;
        m = 0x3u;
    }
    let d77 = em_node77(p);
    if (d77 < d) {
        d = d77;
        m = 0x3u;
    }
    let d78 = em_node78(p);
    if (d78 < d) {
        d = d78;
        m = 0x3u;
    }
    let d79 = em_node79(p);
    if (d79 < d) {
        d = d79;
        m = 0x3u;
    }
    let d80 = em_node80(p);
    if (d80 < d) {
        d = d80;
        m = 0x3u;
    }
    let d81 = em_node81(p);
    if (d81 < d) {
        d = d81;
        m = 0x3u;
    }
    let d82 = em_node82(p);
    if (d82 < d) {
        d = d82;
        m = 0x3u;
    }
    let d83 = em_node83(p);
    if (d83 < d) {
        d = d83;
        m = 0x3u;
    }
    let d84 = em_node84(p);
    if (d84 < d) {
        d = d84;
        m = 0x3u;
    }
    let d85 = em_node85(p);
    if (d85 < d) {
        d = d85;
        m = 0x3u;
    }
    let d86 = em_node86(p);
    if (d86 < d) {
        d = d86;
        m = 0x3u;
    }
    let d87 = em_node87(p);
    if (d87 < d) {
        d = d87;
        m = 0x3u;
    }
    let d88 = em_node88(p);
    if (d88 < d) {
        d = d88;
        m = 0x3u;
    }
    let d89 = em_node89(p);
    if (d89 < d) {
        d = d89;
        m = 0x3u;
    }
    let d90 = em_node90(p);
    if (d90 < d) {
        d = d90;
        m = 0x3u;
    }
    let d91 = em_node91(p);
    if (d91 < d) {
        d = d91;
        m = 0x6u;
    }
    let d92 = em_node92(p);
    if (d92 < d) {
        d = d92;
        m = 0x6u;
    }
    let d93 = em_node93(p);
    if (d93 < d) {
        d = d93;
        m = 0x6u;
    }
    return MapHit(d, m);
}
fn em_dist(p: vec3<f32>) -> f32 {
    var d = em_f32_bits(2139095040u);
    var m = SKY;
    d = (p.y - em_height(p.xz).x) * 0.863672f;
    m = 0x0u;
    if (p.y > 13.483197f) {
        let e = p.y - 12.983197f;
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
        m = 0x2u;
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
        m = 0x2u;
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
        m = 0x2u;
    }
    let d21 = em_node21(p);
    if (d21 < d) {
        d = d21;
        m = 0x2u;
    }
    let d22 = em_node22(p);
    if (d22 < d) {
        d = d22;
        m = 0x2u;
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
        m = 0x2u;
    }
    let d27 = em_node27(p);
    if (d27 < d) {
        d = d27;
        m = 0x2u;
    }
    let d28 = em_node28(p);
    if (d28 < d) {
        d = d28;
        m = 0x2u;
    }
    let d29 = em_node29(p);
    if (d29 < d) {
        d = d29;
        m = 0x1u;
    }
    let d30 = em_node30(p);
    if (d30 < d) {
        d = d30;
        m = 0x2u;
    }
    let d31 = em_node31(p);
    if (d31 < d) {
        d = d31;
        m = 0x1u;
    }
    let d32 = em_node32(p);
    if (d32 < d) {
        d = d32;
        m = 0x2u;
    }
    let d33 = em_node33(p);
    if (d33 < d) {
        d = d33;
        m = 0x2u;
    }
    let d34 = em_node34(p);
    if (d34 < d) {
        d = d34;
        m = 0x2u;
    }
    let d35 = em_node35(p);
    if (d35 < d) {
        d = d35;
        m = 0x2u;
    }
    let d36 = em_node36(p);
    if (d36 < d) {
        d = d36;
        m = 0x2u;
    }
    let d37 = em_node37(p);
    if (d37 < d) {
        d = d37;
        m = 0x1u;
    }
    let d38 = em_node38(p);
    if (d38 < d) {
        d = d38;
        m = 0x2u;
    }
    let d39 = em_node39(p);
    if (d39 < d) {
        d = d39;
        m = 0x2u;
    }
    let d40 = em_node40(p);
    if (d40 < d) {
        d = d40;
        m = 0x2u;
    }
    let d41 = em_node41(p);
    if (d41 < d) {
        d = d41;
        m = 0x2u;
    }
    let d42 = em_node42(p);
    if (d42 < d) {
        d = d42;
        m = 0x2u;
    }
    let d43 = em_node43(p);
    if (d43 < d) {
        d = d43;
        m = 0x2u;
    }
    let d44 = em_node44(p);
    if (d44 < d) {
        d = d44;
        m = 0x2u;
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
        m = 0x2u;
    }
    let d51 = em_node51(p);
    if (d51 < d) {
        d = d51;
        m = 0x2u;
    }
    let d52 = em_node52(p);
    if (d52 < d) {
        d = d52;
        m = 0x2u;
    }
    let d53 = em_node53(p);
    if (d53 < d) {
        d = d53;
        m = 0x2u;
    }
    let d54 = em_node54(p);
    if (d54 < d) {
        d = d54;
        m = 0x2u;
    }
    let d55 = em_node55(p);
    if (d55 < d) {
        d = d55;
        m = 0x1u;
    }
    let d56 = em_node56(p);
    if (d56 < d) {
        d = d56;
        m = 0x2u;
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
        m = 0x2u;
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
        m = 0x2u;
    }
    let d65 = em_node65(p);
    if (d65 < d) {
        d = d65;
        m = 0x1u;
    }
    let d66 = em_node66(p);
    if (d66 < d) {
        d = d66;
        m = 0x2u;
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
        m = 0x2u;
    }
    let d71 = em_node71(p);
    if (d71 < d) {
        d = d71;
        m = 0x2u;
    }
    let d72 = em_node72(p);
    if (d72 < d) {
        d = d72;
        m = 0x2u;
    }
    let d73 = em_node73(p);
    if (d73 < d) {
        d = d73;
        m = 0x2u;
    }
    let d74 = em_node74(p);
    if (d74 < d) {
        d = d74;
        m = 0x2u;
    }
    let d75 = em_node75(p);
    if (d75 < d) {
        d = d75;
        m = 0x2u;
    }
    let d76 = em_node76(p);
    if (d76 < d) {
        d = d76;
        m = 0x3u;
    }
    let d77 = em_node77(p);
    if (d77 < d) {
        d = d77;
        m = 0x3u;
    }
    let d78 = em_node78(p);
    if (d78 < d) {
        d = d78;
        m = 0x3u;
    }
    let d79 = em_node79(p);
    if (d79 < d) {
        d = d79;
        m = 0x3u;
    }
    let d80 = em_node80(p);
    if (d80 < d) {
        d = d80;
        m = 0x3u;
    }
    let d81 = em_node81(p);
    if (d81 < d) {
        d = d81;
        m = 0x3u;
    }
    let d82 = em_node82(p);
    if (d82 < d) {
        d = d82;
        m = 0x3u;
    }
    let d83 = em_node83(p);
    if (d83 < d) {
        d = d83;
        m = 0x3u;
    }
    let d84 = em_node84(p);
    if (d84 < d) {
        d = d84;
        m = 0x3u;
    }
    let d85 = em_node85(p);
    if (d85 < d) {
        d = d85;
        m = 0x3u;
    }
    let d86 = em_node86(p);
    if (d86 < d) {
        d = d86;
        m = 0x3u;
    }
    let d87 = em_node87(p);
    if (d87 < d) {
        d = d87;
        m = 0x3u;
    }
    let d88 = em_node88(p);
    if (d88 < d) {
        d = d88;
        m = 0x3u;
    }
    let d89 = em_node89(p);
    if (d89 < d) {
        d = d89;
        m = 0x3u;
    }
    let d90 = em_node90(p);
    if (d90 < d) {
        d = d90;
        m = 0x3u;
    }
    let d91 = em_node91(p);
    if (d91 < d) {
        d = d91;
        m = 0x6u;
    }
    let d92 = em_node92(p);
    if (d92 < d) {
        d = d92;
        m = 0x6u;
    }
    let d93 = em_node93(p);
    if (d93 < d) {
        d = d93;
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
    {
        let oc = vec3<f32>(9.0f, 3.316963f, 11.5f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 83.36251f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-10.0f, 4.5820127f, 14.0f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 18.013685f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(16.0f, 6.869408f, 30.0f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 18.013685f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-22.0f, 7.60354f, 40.0f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 18.013685f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-4.29f, 6.0570817f, 26.57f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 6.2487507f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-4.2486343f, 8.828599f, 26.549192f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 7.453604f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-3.09f, 4.858754f, 20.86f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.49228f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-3.0553284f, 7.2060423f, 20.84256f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.2364264f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-28.38f, 5.4742837f, 21.31f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.687225f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-28.344526f, 7.8723345f, 21.292156f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.481168f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-36.84f, 9.860928f, 54.06f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.721041f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-41.23f, 8.794928f, 73.04f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.901797f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(30.82f, 5.439542f, 22.1f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.743684f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(30.855701f, 7.852096f, 22.082043f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.552122f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-0.02f, 6.530218f, 37.87f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.8808997f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(0.012039706f, 8.710715f, 37.85388f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.4716306f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-19.97f, 9.955643f, 74.74f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.035537f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(30.62f, 7.551379f, 42.86f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.3409002f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(23.97f, 5.2693043f, 9.04f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.8177447f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(24.00982f, 7.9429226f, 9.01997f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 6.907299f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-10.21f, 10.222643f, 70.38f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.3722816f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-2.7f, 9.201175f, 72.84f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.6146889f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-38.43f, 9.169241f, 34.24f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.064256f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(41.77f, 5.816614f, 48.38f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.7503289f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-29.01f, 5.4949493f, 26.52f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.8425806f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-28.978132f, 7.6645694f, 26.50397f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.4238462f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-27.84f, 8.634941f, 45.51f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.7902441f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(42.38f, 6.317955f, 53.38f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.304324f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(31.89f, 7.0531216f, 35.6f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.7030252f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(24.54f, 4.594182f, 1.19f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.196944f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(24.568836f, 6.5716295f, 1.1754954f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.6220207f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-23.13f, 5.722782f, 31.14f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.5062566f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-23.099676f, 7.7945027f, 31.124746f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.0053606f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-31.13f, 9.191686f, 64.93f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.2353644f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(34.4f, 7.7427034f, 31.39f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.7027361f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-21.87f, 9.645488f, 55.61f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.3379295f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-19.78f, 8.599256f, 65.91f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.9965693f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-11.81f, 5.7196035f, 27.94f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.5584004f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-11.784483f, 7.4867496f, 27.927166f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.8363488f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-12.41f, 10.544004f, 63.0f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.9684415f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(14.12f, 9.125732f, 41.03f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.2942257f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-43.39f, 8.405718f, 65.12f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.7442253f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-1.6f, 8.770956f, 45.35f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.359296f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(21.33f, 8.484928f, 64.02f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.8966763f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(18.33f, 9.23678f, 52.26f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.6656003f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-13.33f, 10.838197f, 40.37f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.601026f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(33.4f, 5.419709f, 10.89f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.523675f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(33.438736f, 8.024436f, 10.870517f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 6.535325f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(32.71f, 5.5675545f, 28.01f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.6731634f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(32.745415f, 7.961981f, 27.992186f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.4634976f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(44.4f, 7.537081f, 61.78f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.8612256f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-10.04f, 9.831879f, 45.85f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.2724814f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-5.35f, 8.49256f, 57.22f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.6563692f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(10.31f, 7.986002f, 66.25f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.1609f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(36.51f, 7.6450987f, 37.6f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.7722254f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-27.13f, 4.936064f, 12.4f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.6003227f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-27.090979f, 7.55892f, 12.380372f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 6.632214f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(37.28f, 6.9227715f, 61.83f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.576025f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(7.48f, 2.4352632f, -0.19f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.5792358f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(7.505632f, 4.2096615f, -0.20289302f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.8618429f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-0.32f, 10.343702f, 57.08f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.3722816f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(19.01f, 7.6142244f, 69.5f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.2230809f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-7.74f, 6.875169f, 33.83f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.04915f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-7.7072163f, 9.102802f, 33.81351f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.6816516f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-16.62f, 10.644747f, 57.3f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.9818244f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(11.7f, 6.7543178f, 37.05f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.615715f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(11.739077f, 9.3808f, 37.030342f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 6.651674f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(41.26f, 6.6390047f, 40.29f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.9880999f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(1.84f, 6.844435f, 32.59f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 5.3418765f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(1.8780472f, 9.405651f, 32.57086f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 6.305698f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-9.58f, 10.577791f, 52.11f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.626801f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-37.15f, 8.417112f, 67.59f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.8376815f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(34.14f, 8.504251f, 52.64f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 4.7961f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(43.24f, 7.6262536f, 72.51f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.1116962f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(4.53f, 9.529718f, 49.51f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.934369f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-42.44f, 8.063833f, 54.01f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.602756f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(20.4f, 5.196979f, 35.15f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.6244004f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(1.6f, 0.7643615f, 3.21f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.5625603f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(8.33f, 4.5667953f, 21.82f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 3.0234256f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-7.13f, 5.8924055f, 47.62f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.471184f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-17.51f, 6.475709f, 48.06f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.7027361f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(1.45f, 4.614062f, 25.84f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 0.8805946f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(2.15f, 4.0476313f, 20.25f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.059799f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-28.33f, 5.760352f, 57.55f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.3271042f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-5.96f, 5.771969f, 44.09f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.4689441f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-1.61f, 1.1013527f, -9.84f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.5084754f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-1.41f, 0.9032268f, 5.38f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 0.8548853f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(7.07f, 5.742277f, 54.02f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 0.553536f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-16.36f, 5.794621f, 34.96f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 0.8987041f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-8.68f, 4.974424f, 29.58f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 0.6629216f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(13.85f, 2.6232781f, -10.18f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 1.7550951f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(-4.0f, 2.7620044f, 4.0f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 2.1025002f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(3.5f, 2.4906347f, 0.0f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 6.3725004f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    {
        let oc = vec3<f32>(3.5f, 5.390635f, 0.0f) - o;
        let b = dot(oc, em_sun);
        let c = dot(oc, oc) - 0.48999998f;
        if (b > 0.0 && b * b > c) {
            return true;
        }
    }
    return false;
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

