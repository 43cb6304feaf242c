//! Colours of a packet of camera rays: the reference paper's shading (point lights, Phong,
//! soft shadows, fog, mirror bounces with per-lane weights) and the outdoor world shading
//! (sun, sky, ambient occlusion, both shadow modes, fog), then gamma.

use glam::Vec3;

use super::constants::{SceneConstants, TerrainC};
use super::eval::{Tally, map};
use super::lanes::{MAX_WIDTH, V3};
use super::march::{Hit, MarchC, march, normal, soft_shadow};
use super::prims::ray_meets_sphere;
use super::stream::{Packets, march_packets, shadow_packets};
use crate::math;
use crate::plan3d::{
    AoMode, Camera3d, Material, PaperShading, Plan, Shading, ShadowMode, Sphere, WorldShading,
};
use crate::simd::Pack;

/// Everything one frame's kernel reads: compiled once, shared by all threads.
#[derive(Clone, Debug)]
pub(crate) struct Frame {
    pub scene: SceneConstants,
    pub march: MarchC,
    pub shading: Shading,
    pub materials: Vec<Material>,
    pub bounds: Vec<Sphere>,
    pub camera: Camera3d,
    pub width: u32,
    pub height: u32,
}

impl Frame {
    /// The frame of a valid plan.
    pub(super) fn new(plan: &Plan, camera: &Camera3d, width: u32, height: u32) -> Frame {
        Frame {
            scene: SceneConstants::new(plan),
            march: MarchC::new(&plan.march),
            shading: plan.shading.clone(),
            materials: plan.materials.clone(),
            bounds: plan.nodes.iter().map(|n| n.bound).collect(),
            camera: *camera,
            width,
            height,
        }
    }
}

/// Per-lane material colour and reflectivity (zero for the sky and inactive lanes).
#[inline(always)]
fn looks<P: Pack>(p: P, f: &Frame, m: P::I, live: P::M) -> (V3<P>, P::F) {
    let mut ids = [0i32; MAX_WIDTH];
    p.store_i(m, &mut ids);
    let live = p.bitmask(live);
    let mut c = [[0.0f32; MAX_WIDTH]; 4];
    for (lane, &id) in ids.iter().enumerate().take(P::WIDTH) {
        if live & (1 << lane) != 0
            && let Some(mat) = f.materials.get(id as u32 as usize)
        {
            c[0][lane] = mat.colour.x;
            c[1][lane] = mat.colour.y;
            c[2][lane] = mat.colour.z;
            c[3][lane] = mat.reflectivity;
        }
    }
    (
        V3 {
            x: p.load(&c[0]),
            y: p.load(&c[1]),
            z: p.load(&c[2]),
        },
        p.load(&c[3]),
    )
}

/// The camera rays of the packet whose top-left pixel is `(i0, j0)`, laid out by
/// [`packet_shape`] (lanes past the image repeat its last column or row).
#[inline(always)]
pub(crate) fn camera_rays<P: Pack>(p: P, f: &Frame, (i0, j0): (u32, u32)) -> V3<P> {
    let (pw, _) = packet_shape::<P>();
    let (mut xs, mut ys) = ([0.0f32; MAX_WIDTH], [0.0f32; MAX_WIDTH]);
    for lane in 0..P::WIDTH as u32 {
        xs[lane as usize] = (i0 + lane % pw).min(f.width - 1) as f32;
        ys[lane as usize] = (j0 + lane / pw).min(f.height - 1) as f32;
    }
    let c = &f.camera;
    let (w, h) = (f.width as f32, f.height as f32);
    let (i, j) = (p.load(&xs), p.load(&ys));
    let (one, half, two) = (p.splat(1.0), p.splat(0.5), p.splat(2.0));
    // x = (2 (i + 0.5) / W - 1) * aspect * tan, y = (1 - 2 (j + 0.5) / H) * tan.
    let x = p.mul(
        p.sub(p.div(p.mul(two, p.add(i, half)), p.splat(w)), one),
        p.splat(w / h * c.tan_half_fov),
    );
    let y = p.mul(
        p.sub(one, p.div(p.mul(two, p.add(j, half)), p.splat(h))),
        p.splat(c.tan_half_fov),
    );
    let base = V3 {
        x: p.add(p.splat(c.forward.x), p.mul(p.splat(c.up.x), y)),
        y: p.add(p.splat(c.forward.y), p.mul(p.splat(c.up.y), y)),
        z: p.add(p.splat(c.forward.z), p.mul(p.splat(c.up.z), y)),
    };
    V3::splat(p, c.right).mul_add(p, x, base).normalize(p)
}

/// The pixels of one packet, `(columns, rows)`: as square as the lane count allows (4x4 on
/// 16 lanes, 4x2 on 8, 2x2 on 4), so that a packet's rays stay close together and its lanes
/// finish their marches at similar steps.
#[inline(always)]
pub(crate) fn packet_shape<P: Pack>() -> (u32, u32) {
    let lanes = P::WIDTH as u32;
    let rows = 1 << (lanes.trailing_zeros() / 2);
    (lanes / rows, rows)
}

/// Gamma-encoded colours of the packets of camera rays `dir` (lanes of `live`).
#[inline(always)]
pub(crate) fn shade<P: Pack>(
    p: P,
    f: &Frame,
    dir: &[V3<P>],
    live: &[P::M],
    tally: &mut Tally,
) -> Vec<V3<P>> {
    match &f.shading {
        Shading::Paper(s) => paper(p, f, s, dir, live, tally),
        Shading::World(w) => {
            let mut out = Vec::with_capacity(dir.len());
            for (&dir, &live) in dir.iter().zip(live) {
                out.push(world(p, f, w, dir, live, tally));
            }
            out
        }
    }
}

/// `pow(clamp(c, 0, 1), gamma)`, black staying black.
#[inline(always)]
fn encode<P: Pack>(p: P, c: P::F, gamma: f32) -> P::F {
    let x = p.max(p.splat(0.0), p.min(p.splat(1.0), c));
    p.select(
        p.le(x, p.splat(0.0)),
        p.splat(0.0),
        math::pow(p, x, p.splat(gamma)),
    )
}

#[inline(always)]
fn encode3<P: Pack>(p: P, c: V3<P>, gamma: f32) -> V3<P> {
    V3 {
        x: encode(p, c.x, gamma),
        y: encode(p, c.y, gamma),
        z: encode(p, c.z, gamma),
    }
}

/// The paper's model: the primary hit and up to `bounces` mirror bounces, each weighted by
/// the product of the reflectivities (times the reflection scale) before it. The packets'
/// marches and shadow rays go as streams (`super::stream`); the rest packet by packet.
#[inline(always)]
fn paper<P: Pack>(
    p: P,
    f: &Frame,
    s: &PaperShading,
    primary: &[V3<P>],
    live: &[P::M],
    tally: &mut Tally,
) -> Vec<V3<P>> {
    let mc = &f.march;
    let packets = primary.len();
    let mut colour = vec![V3::splat(p, Vec3::ZERO); packets];
    let mut weight = vec![p.splat(1.0); packets];
    let mut o = vec![V3::splat(p, f.camera.position); packets];
    let mut dir = primary.to_vec();
    let mut live = live.to_vec();
    for bounce in 0..=s.bounces {
        let rays = Packets {
            from: &o,
            dir: &dir,
            live: &live,
        };
        let hits = march_packets(p, &f.scene, mc, rays, tally);
        for (l, h) in live.iter_mut().zip(&hits) {
            *l = p.and(*l, h.hit);
        }
        if !any_lane(p, &live) {
            break;
        }
        let mut q = Vec::with_capacity(packets);
        let mut n = Vec::with_capacity(packets);
        let mut albedo = Vec::with_capacity(packets);
        let mut refl = Vec::with_capacity(packets);
        let mut t = Vec::with_capacity(packets);
        // Packets without a live lane are done: they only hold their places.
        let nothing = V3::splat(p, Vec3::ZERO);
        for k in 0..packets {
            let h = &hits[k];
            t.push(h.t);
            if !p.any(live[k]) {
                q.push(nothing);
                n.push(nothing);
                albedo.push(nothing);
                refl.push(p.splat(0.0));
                continue;
            }
            q.push(dir[k].mul_add(p, h.t, o[k]));
            n.push(normal(p, &f.scene, mc, (q[k], h.m, h.d), live[k], tally));
            let (a, r) = looks(p, f, h.m, live[k]);
            albedo.push(a);
            refl.push(r);
        }
        let seen = Packets {
            from: &q,
            dir: &dir,
            live: &live,
        };
        let local = paper_local(p, f, s, seen, &n, &t, &albedo, tally);
        for k in 0..packets {
            if !p.any(live[k]) {
                continue;
            }
            let add = V3::select(
                p,
                live[k],
                local[k].scale(p, weight[k]),
                V3::splat(p, Vec3::ZERO),
            );
            colour[k] = colour[k].add(p, add);
        }
        if bounce == s.bounces {
            break;
        }
        for k in 0..packets {
            if !p.any(live[k]) {
                continue;
            }
            weight[k] = p.mul(weight[k], p.mul(refl[k], p.splat(s.reflection_scale)));
            live[k] = p.and(live[k], p.gt(weight[k], p.splat(0.0)));
            if !p.any(live[k]) {
                continue;
            }
            o[k] = n[k].mul_add(p, p.splat(mc.m.ray_offset), q[k]);
            dir[k] = dir[k].reflect(p, n[k]);
        }
        if !any_lane(p, &live) {
            break;
        }
    }
    for c in &mut colour {
        *c = encode3(p, *c, s.gamma);
    }
    colour
}

/// Whether any lane of any packet is set.
#[inline(always)]
fn any_lane<P: Pack>(p: P, masks: &[P::M]) -> bool {
    let mut any = false;
    for &m in masks {
        any |= p.any(m);
    }
    any
}

/// One light's terms at paper-shaded hits.
struct LightTerms<P: Pack> {
    /// Unit direction to the light.
    l: V3<P>,
    intensity: P::F,
    diff: P::F,
    spec: P::F,
    /// Lanes with diffuse or specular light (the others gain nothing from a shadow ray).
    lit: P::M,
}

impl<P: Pack> LightTerms<P> {
    /// The terms of a packet without a hit: no light.
    #[inline(always)]
    fn none(p: P) -> Self {
        let zero = p.splat(0.0);
        LightTerms {
            l: V3::splat(p, Vec3::ZERO),
            intensity: zero,
            diff: zero,
            spec: zero,
            lit: p.none(),
        }
    }
}

#[inline(always)]
fn light_terms<P: Pack>(
    p: P,
    s: &PaperShading,
    light: &crate::plan3d::PointLight,
    (q, n, dir): (V3<P>, V3<P>, V3<P>),
    live: P::M,
) -> LightTerms<P> {
    let zero = p.splat(0.0);
    let ndir = n.dot(p, dir);
    let to = V3::splat(p, light.position).sub(p, q);
    let r = to.len(p);
    let inv = p.div(p.splat(1.0), r);
    let l = to.scale(p, inv);
    let intensity = p.mul(p.splat(light.emission), inv);
    let nl = l.dot(p, n);
    let diff = p.max(nl, zero);
    // dot(reflect(-l, n), -dir) = dot(l, dir) - 2 dot(n, l) dot(n, dir).
    let rv = p.fnma(p.mul(p.splat(2.0), nl), ndir, l.dot(p, dir));
    let rv = p.max(rv, zero);
    let spec = math::pow(p, rv, p.splat(s.shininess));
    let lit = p.and(live, p.or(p.gt(diff, zero), p.gt(rv, zero)));
    LightTerms {
        l,
        intensity,
        diff,
        spec,
        lit,
    }
}

/// The local colours of paper-shaded hits (before reflections), fog included, of every
/// packet: `seen` are the hit points and the directions they were seen along, `n` their
/// normals, `t` their distances.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn paper_local<P: Pack>(
    p: P,
    f: &Frame,
    s: &PaperShading,
    seen: Packets<'_, P>,
    n: &[V3<P>],
    t: &[P::F],
    albedo: &[V3<P>],
    tally: &mut Tally,
) -> Vec<V3<P>> {
    let Packets { from: q, dir, live } = seen;
    let packets = q.len();
    let zero = p.splat(0.0);
    let (mut diffuse, mut specular) = (vec![zero; packets], vec![zero; packets]);
    for light in &s.lights {
        let mut terms: Vec<LightTerms<P>> = Vec::with_capacity(packets);
        for k in 0..packets {
            terms.push(if p.any(live[k]) {
                light_terms(p, s, light, (q[k], n[k], dir[k]), live[k])
            } else {
                LightTerms::none(p)
            });
        }
        let shadow = match s.shadow_k {
            Some(k) => {
                let l: Vec<V3<P>> = terms.iter().map(|t| t.l).collect();
                let lit: Vec<P::M> = terms.iter().map(|t| t.lit).collect();
                // As in the reference renderer, the light ray runs until it escapes, past
                // the light.
                let rays = Packets {
                    from: q,
                    dir: &l,
                    live: &lit,
                };
                let limit = (f32::INFINITY, k, f.march.m.max_steps);
                shadow_packets(p, &f.scene, &f.march, rays, n, limit, tally)
            }
            None => vec![p.splat(1.0); packets],
        };
        for (k, t) in terms.iter().enumerate() {
            if !p.any(live[k]) {
                continue;
            }
            let si = p.mul(shadow[k], t.intensity);
            diffuse[k] = p.fma(t.diff, si, diffuse[k]);
            specular[k] = p.fma(t.spec, si, specular[k]);
        }
    }
    let mut out = Vec::with_capacity(packets);
    for k in 0..packets {
        if !p.any(live[k]) {
            out.push(V3::splat(p, Vec3::ZERO));
            continue;
        }
        let tk = t[k];
        let fog = math::exp(p, p.neg(p.mul(p.splat(s.fog), p.mul(p.mul(tk, tk), tk))));
        let base = p.add(p.splat(s.ambient), diffuse[k]);
        let spec = p.mul(p.splat(s.specular), specular[k]);
        let c = V3 {
            x: p.fma(albedo[k].x, base, spec),
            y: p.fma(albedo[k].y, base, spec),
            z: p.fma(albedo[k].z, base, spec),
        };
        out.push(c.scale(p, fog));
    }
    out
}

/// `a + (b - a) t` for constant colours.
#[inline(always)]
fn mix_c<P: Pack>(p: P, a: Vec3, b: Vec3, t: P::F) -> V3<P> {
    V3::splat(p, b - a).mul_add(p, t, V3::splat(p, a))
}

/// The outdoor model.
#[inline(always)]
fn world<P: Pack>(
    p: P,
    f: &Frame,
    w: &WorldShading,
    dir: V3<P>,
    live: P::M,
    tally: &mut Tally,
) -> V3<P> {
    let zero = p.splat(0.0);
    let one = p.splat(1.0);
    let sky = mix_c(p, w.sky[0], w.sky[1], p.max(zero, p.min(one, dir.y)));
    let o = V3::splat(p, f.camera.position);
    let mut h = march(p, &f.scene, &f.march, o, dir, live, tally);
    let mut q = dir.mul_add(p, h.t, o);
    if let Some(t) = &f.scene.terrain {
        land_on_terrain(p, t, (o, dir), live, (&mut h, &mut q), tally);
    }
    let hit = p.and(live, h.hit);
    if !p.any(hit) {
        return encode3(p, sky, w.gamma);
    }
    let n = normal(p, &f.scene, &f.march, (q, h.m, h.d), hit, tally);
    let (albedo, _) = looks(p, f, h.m, hit);
    let sun = V3::splat(p, w.sun);
    let diff = p.max(n.dot(p, sun), zero);
    let lit = p.and(hit, p.gt(diff, zero));
    let sh = if p.any(lit) {
        sun_shadow(p, f, w, (q, n), lit, tally)
    } else {
        one
    };
    let occ = occlusion(p, f, w, (q, n, h.t, h.m), hit, tally);
    let amb = mix_c(
        p,
        w.sky[0],
        w.sky[1],
        p.fma(p.splat(0.5), n.y, p.splat(0.5)),
    );
    let ds = p.mul(diff, sh);
    let amb_k = p.mul(p.splat(0.6), occ);
    let light: V3<P> = V3 {
        x: p.fma(p.splat(w.sun_colour.x), ds, p.mul(amb.x, amb_k)),
        y: p.fma(p.splat(w.sun_colour.y), ds, p.mul(amb.y, amb_k)),
        z: p.fma(p.splat(w.sun_colour.z), ds, p.mul(amb.z, amb_k)),
    };
    let c = V3 {
        x: p.mul(albedo.x, light.x),
        y: p.mul(albedo.y, light.y),
        z: p.mul(albedo.z, light.z),
    };
    // mix(c, sky0, 1 - exp(-fog t)) = sky0 + (c - sky0) exp(-fog t).
    let keep = math::exp(p, p.neg(p.mul(p.splat(w.fog), h.t)));
    let s0 = V3::splat(p, w.sky[0]);
    let fogged = c.sub(p, s0).mul_add(p, keep, s0);
    encode3(p, V3::select(p, hit, fogged, sky), w.gamma)
}

/// Lanes of `live` whose march stopped without a hit (out of steps or past `far`) while
/// pointing below the horizon or ending below the terrain's top become terrain hits at the
/// height field under their end point: such a ray can only be looking at the ground, and
/// shading it as sky draws sky through the hills.
#[inline(always)]
fn land_on_terrain<P: Pack>(
    p: P,
    t: &TerrainC,
    (o, dir): (V3<P>, V3<P>),
    live: P::M,
    (h, q): (&mut Hit<P>, &mut V3<P>),
    tally: &mut Tally,
) {
    let zero = p.splat(0.0);
    let low = p.or(p.lt(dir.y, zero), p.lt(q.y, p.splat(t.top)));
    let land = p.and(p.and_not(live, h.hit), low);
    if !p.any(land) {
        return;
    }
    tally.sdf += 1;
    let ground = V3 {
        y: t.fbm.height_only(p, q.x, q.z),
        ..*q
    };
    *q = V3::select(p, land, ground, *q);
    h.t = p.select(land, ground.sub(p, o).len(p), h.t);
    h.d = p.select(land, zero, h.d);
    h.m = p.select_i(land, p.splat_i(t.material), h.m);
    h.hit = p.or(h.hit, land);
}

/// The sun shadow of world shading: 1 lit, 0 shadowed (soft in between for `Full`).
#[inline(always)]
fn sun_shadow<P: Pack>(
    p: P,
    f: &Frame,
    w: &WorldShading,
    (q, n): (V3<P>, V3<P>),
    lit: P::M,
    tally: &mut Tally,
) -> P::F {
    let sun = V3::splat(p, w.sun);
    match w.shadow {
        ShadowMode::Full { steps, k } => soft_shadow(
            p,
            &f.scene,
            &f.march,
            (q, n, sun),
            p.splat(f.march.m.far),
            k,
            steps,
            lit,
            tally,
        ),
        ShadowMode::TerrainAndBounds { steps, spacing } => {
            let o = n.mul_add(p, p.splat(f.march.m.ray_offset), q);
            let mut dark = p.none();
            if let Some(t) = &f.scene.terrain {
                let mut reach = 1.0f32;
                for _ in 0..steps {
                    let x = sun.mul_add(p, p.splat(spacing * reach), o);
                    tally.sdf += 1;
                    let ground = t.fbm.height_only(p, x.x, x.z);
                    dark = p.or(dark, p.lt(x.y, ground));
                    if !p.any(p.and_not(lit, dark)) {
                        break;
                    }
                    reach = 2.0 * reach + 1.0;
                }
            }
            for b in &f.bounds {
                if !p.any(p.and_not(lit, dark)) {
                    break;
                }
                tally.sdf += 1;
                dark = p.or(dark, ray_meets_sphere(p, o, sun, b));
            }
            p.select(dark, p.splat(0.0), p.splat(1.0))
        }
    }
}

/// Ambient occlusion `clamp(1 - 3 ao, 0, 1)` of the hits in `live` (1 with no taps).
#[inline(always)]
fn occlusion<P: Pack>(
    p: P,
    f: &Frame,
    w: &WorldShading,
    (q, n, t, m): (V3<P>, V3<P>, P::F, P::I),
    live: P::M,
    tally: &mut Tally,
) -> P::F {
    let taps = match w.ao {
        AoMode::Fixed(k) => p.splat(k as f32),
        AoMode::Adaptive {
            near,
            far,
            near_distance,
        } => {
            let k = p.select(
                p.lt(t, p.splat(near_distance)),
                p.splat(near as f32),
                p.splat(far as f32),
            );
            match &f.scene.terrain {
                Some(ter) => {
                    // Flat terrain lying above the eye: none.
                    let flat = p.and(
                        p.and(p.eq_i(m, p.splat_i(ter.material)), p.gt(n.y, p.splat(0.9))),
                        p.gt(q.y, p.splat(f.camera.position.y)),
                    );
                    p.select(flat, p.splat(0.0), k)
                }
                None => k,
            }
        }
    };
    let most = match w.ao {
        AoMode::Fixed(k) => k,
        AoMode::Adaptive { near, far, .. } => near.max(far),
    };
    let mut ao = p.splat(0.0);
    let mut sca = p.splat(1.0);
    // h_i = 0.01 + 0.12 i / max(N - 1, 1), per lane's N.
    let step = p.div(
        p.splat(0.12),
        p.max(p.sub(taps, p.splat(1.0)), p.splat(1.0)),
    );
    for i in 0..most {
        let on = p.and(live, p.lt(p.splat(i as f32), taps));
        if !p.any(on) {
            break;
        }
        let h = p.fma(p.splat(i as f32), step, p.splat(0.01));
        let (d, _) = map(p, &f.scene, n.mul_add(p, h, q), on, false, tally);
        ao = p.select(on, p.fma(p.sub(h, d), sca, ao), ao);
        sca = p.mul(sca, p.splat(0.95));
    }
    p.max(
        p.splat(0.0),
        p.min(p.splat(1.0), p.fnma(p.splat(3.0), ao, p.splat(1.0))),
    )
}
