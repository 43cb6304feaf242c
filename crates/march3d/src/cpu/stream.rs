//! Marches of many rays at once, with each lane refilled from the queue as soon as its ray
//! finishes.
//!
//! A packet marched alone keeps every lane busy until its slowest ray is done: rays of one
//! packet that graze a fractal take hundreds of steps more than their neighbours, and the
//! other lanes wait (on the Mandelbulb, fewer than half the lanes of a 16-wide packet did
//! useful work). Here a lane whose ray hit, escaped or ran out of steps takes the next ray
//! of the queue, as soon as a quarter of the packet is free (a refill goes through memory;
//! between refills the lanes stay in registers). Each step is [`plain_step`] or
//! [`shadow_step`], whose lanes do not depend on each other, so every ray ends with the
//! bits the packet march gives it. In scenes with long dependent chains (the Mandelbulb)
//! a stream marches two registers at once ([`Pair`]), which hides their latency.

use super::constants::SceneConstants;
use super::eval::{SKY_I, Tally};
use super::lanes::{MAX_WIDTH, V3};
use super::march::{Hit, MarchC, PlainState, ShadowState, march, plain_step, shadow_step};
use crate::simd::{Pack, Pair};

/// The per-lane values a stream keeps in memory between steps (a backend's registers
/// cannot be indexed by lane).
#[derive(Clone, Copy)]
struct Lane<const N: usize> {
    f: [[f32; MAX_WIDTH]; N],
    /// The ray each lane holds.
    ray: [Option<usize>; MAX_WIDTH],
    /// Steps each lane's ray has left (integer lanes: the counting backend counts no
    /// bookkeeping as flops).
    left: [i32; MAX_WIDTH],
}

impl<const N: usize> Lane<N> {
    #[inline(always)]
    fn new() -> Self {
        Lane {
            f: [[0.0; MAX_WIDTH]; N],
            ray: [None; MAX_WIDTH],
            left: [0; MAX_WIDTH],
        }
    }

    #[inline(always)]
    fn load<P: Pack>(&self, p: P, k: usize) -> P::F {
        p.load(&self.f[k])
    }

    #[inline(always)]
    fn load3<P: Pack>(&self, p: P, k: usize) -> V3<P> {
        V3 {
            x: self.load(p, k),
            y: self.load(p, k + 1),
            z: self.load(p, k + 2),
        }
    }

    #[inline(always)]
    fn store3<P: Pack>(&mut self, p: P, k: usize, v: V3<P>) {
        p.store(v.x, &mut self.f[k]);
        p.store(v.y, &mut self.f[k + 1]);
        p.store(v.z, &mut self.f[k + 2]);
    }

    /// Whether the queue has rays left and enough lanes are free to be worth the trip
    /// through memory that a refill takes (a quarter of the packet).
    #[inline(always)]
    fn wants_refill(&self, width: usize, next: usize, rays: usize) -> bool {
        let free = self.ray[..width].iter().filter(|r| r.is_none()).count();
        next < rays && free >= (width / 4).max(1)
    }

    /// The lanes holding a ray, as a mask.
    #[inline(always)]
    fn occupied<P: Pack>(&self, p: P) -> P::M {
        let mut v = [0.0f32; MAX_WIDTH];
        for (v, r) in v.iter_mut().zip(&self.ray) {
            *v = if r.is_some() { 1.0 } else { 0.0 };
        }
        p.gt(p.load(&v), p.splat(0.5))
    }

    /// Gives each free lane the next live ray of the queue (`next`, advanced past the rays
    /// that are not live, whose results stay as they were made) with `steps` steps to go;
    /// `fill` loads a ray into a lane. False when no lane holds a ray any more.
    #[inline(always)]
    fn refill(
        &mut self,
        (width, steps): (usize, u32),
        next: &mut usize,
        live: &[bool],
        mut fill: impl FnMut(&mut Self, usize, usize),
    ) -> bool {
        for lane in 0..width {
            if self.ray[lane].is_some() {
                continue;
            }
            while *next < live.len() && !live[*next] {
                *next += 1;
            }
            if *next < live.len() {
                self.ray[lane] = Some(*next);
                self.left[lane] = steps.min(i32::MAX as u32) as i32;
                fill(self, lane, *next);
                *next += 1;
            }
        }
        self.ray[..width].iter().any(Option::is_some)
    }
}

/// Packets of rays (lane `l` of packet `k` is ray `k * WIDTH + l`) as per-ray values.
#[inline(always)]
fn spread<P: Pack>(p: P, packs: &[P::F]) -> Vec<f32> {
    let mut out = vec![0.0; packs.len() * P::WIDTH];
    for (chunk, &v) in out.chunks_exact_mut(P::WIDTH).zip(packs) {
        p.store(v, chunk);
    }
    out
}

#[inline(always)]
fn spread_mask<P: Pack>(p: P, masks: &[P::M]) -> Vec<bool> {
    let mut out = Vec::with_capacity(masks.len() * P::WIDTH);
    for &m in masks {
        let bits = p.bitmask(m);
        out.extend((0..P::WIDTH).map(|lane| bits & (1 << lane) != 0));
    }
    out
}

/// Per-ray values back into packets.
#[inline(always)]
fn gather<P: Pack>(p: P, values: &[f32]) -> Vec<P::F> {
    let mut out = Vec::with_capacity(values.len() / P::WIDTH);
    for c in values.chunks_exact(P::WIDTH) {
        out.push(p.load(c));
    }
    out
}

#[inline(always)]
fn gather_mask<P: Pack>(p: P, values: &[bool]) -> Vec<P::M> {
    let mut out = Vec::with_capacity(values.len() / P::WIDTH);
    for c in values.chunks_exact(P::WIDTH) {
        let mut v = [0.0f32; MAX_WIDTH];
        for (v, &b) in v.iter_mut().zip(c) {
            *v = if b { 1.0 } else { 0.0 };
        }
        out.push(p.gt(p.load(&v), p.splat(0.5)));
    }
    out
}

/// Whether streams on `P` march two of its registers per step ([`Pair`]): on backends
/// that gain from it, in scenes whose distance is a long dependent chain.
#[inline(always)]
fn in_pairs<P: Pack>(s: &SceneConstants) -> bool {
    P::STREAM_PAIRS && s.long_chains
}

/// Packets of rays: starting points, unit directions and the lanes that are rays.
#[derive(Clone, Copy)]
pub(crate) struct Packets<'a, P: Pack> {
    pub from: &'a [V3<P>],
    pub dir: &'a [V3<P>],
    pub live: &'a [P::M],
}

/// [`march`] of every packet, as one stream of rays where the march is plain; over-relaxed
/// marches go packet by packet.
#[inline(always)]
pub(crate) fn march_packets<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    rays: Packets<'_, P>,
    tally: &mut Tally,
) -> Vec<Hit<P>> {
    let Packets { from: o, dir, live } = rays;
    if mc.m.relax > 1.0 {
        let mut out = Vec::with_capacity(live.len());
        for k in 0..live.len() {
            out.push(march(p, s, mc, o[k], dir[k], live[k], tally));
        }
        return out;
    }
    let rays = PlainRays::new(p, o, dir, live);
    let done = if in_pairs::<P>(s) {
        rays.march(Pair(p), s, mc, tally)
    } else {
        rays.march(p, s, mc, tally)
    };
    let hit = gather_mask(p, &done.hit);
    let t = gather(p, &done.t);
    let d = gather(p, &done.d);
    let mut out = Vec::with_capacity(live.len());
    for k in 0..live.len() {
        let m = p.load_i(&done.m[k * P::WIDTH..]);
        let mut h = Hit {
            hit: hit[k],
            t: t[k],
            m,
            d: d[k],
        };
        super::march::find_materials(p, s, (o[k], dir[k]), &mut h, tally);
        out.push(h);
    }
    out
}

/// The rays of a plain march, one value per ray.
struct PlainRays {
    o: [Vec<f32>; 3],
    dir: [Vec<f32>; 3],
    live: Vec<bool>,
}

/// What a plain march found, one value per ray.
struct PlainDone {
    hit: Vec<bool>,
    t: Vec<f32>,
    m: Vec<i32>,
    d: Vec<f32>,
}

/// Lane slots of a plain march: origin, direction, `t`.
const O: usize = 0;
const DIR: usize = 3;
const T: usize = 6;

impl PlainRays {
    #[inline(always)]
    fn new<P: Pack>(p: P, o: &[V3<P>], dir: &[V3<P>], live: &[P::M]) -> PlainRays {
        let (mut ox, mut oy, mut oz) = (Vec::new(), Vec::new(), Vec::new());
        let (mut dx, mut dy, mut dz) = (Vec::new(), Vec::new(), Vec::new());
        for (o, d) in o.iter().zip(dir) {
            ox.push(o.x);
            oy.push(o.y);
            oz.push(o.z);
            dx.push(d.x);
            dy.push(d.y);
            dz.push(d.z);
        }
        PlainRays {
            o: [spread(p, &ox), spread(p, &oy), spread(p, &oz)],
            dir: [spread(p, &dx), spread(p, &dy), spread(p, &dz)],
            live: spread_mask(p, live),
        }
    }

    #[inline(always)]
    fn march<P: Pack>(
        &self,
        p: P,
        s: &SceneConstants,
        mc: &MarchC,
        tally: &mut Tally,
    ) -> PlainDone {
        let n = self.live.len();
        let mut done = PlainDone {
            hit: vec![false; n],
            t: vec![0.0; n],
            m: vec![SKY_I; n],
            d: vec![0.0; n],
        };
        let max_steps = mc.m.max_steps;
        if max_steps == 0 {
            return done;
        }
        let mut lanes = Lane::<7>::new();
        let (mut ts, mut ds, mut ms) =
            ([0.0f32; MAX_WIDTH], [0.0f32; MAX_WIDTH], [SKY_I; MAX_WIDTH]);
        let mut next = 0;
        let fill = |lanes: &mut Lane<7>, lane: usize, ray: usize| {
            for c in 0..3 {
                lanes.f[O + c][lane] = self.o[c][ray];
                lanes.f[DIR + c][lane] = self.dir[c][ray];
            }
            lanes.f[T][lane] = 0.0;
        };
        let (one, zero) = (p.splat_i(1), p.splat_i(0));
        while lanes.refill((P::WIDTH, max_steps), &mut next, &self.live, fill) {
            // Between refills the lanes stay in registers.
            let (o, dir) = (lanes.load3(p, O), lanes.load3(p, DIR));
            let (mut t, mut left) = (lanes.load(p, T), p.load_i(&lanes.left));
            let mut occupied = lanes.occupied(p);
            loop {
                let mut st = PlainState::start(p, occupied);
                st.t = t;
                plain_step(p, s, mc, (o, dir), &mut st, tally);
                t = st.t;
                left = p.sub_i(left, one);
                let going = p.and_not(st.active, p.eq_i(left, zero));
                let finished = p.and_not(occupied, going);
                if !p.any(finished) {
                    continue;
                }
                p.store(t, &mut ts);
                p.store(st.d, &mut ds);
                p.store_i(st.m, &mut ms);
                let (hit, bits) = (p.bitmask(st.hit), p.bitmask(finished));
                for lane in (0..P::WIDTH).filter(|&l| bits & (1 << l) != 0) {
                    let Some(ray) = lanes.ray[lane].take() else {
                        continue;
                    };
                    done.t[ray] = ts[lane];
                    if hit & (1 << lane) != 0 {
                        done.hit[ray] = true;
                        done.m[ray] = ms[lane];
                        done.d[ray] = ds[lane];
                    }
                }
                occupied = p.and_not(occupied, finished);
                if !p.any(occupied) || lanes.wants_refill(P::WIDTH, next, n) {
                    p.store(t, &mut lanes.f[T]);
                    p.store_i(left, &mut lanes.left);
                    break;
                }
            }
        }
        done
    }
}

/// [`super::march::soft_shadow`] of every packet (from surface points with normals `n`
/// towards unit directions to the light), as one stream of rays.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn shadow_packets<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    rays: Packets<'_, P>,
    n: &[V3<P>],
    (limit, k, max_steps): (f32, f32, u32),
    tally: &mut Tally,
) -> Vec<P::F> {
    let Packets {
        from: pos,
        dir: l,
        live,
    } = rays;
    // Each ray's starting state, as the packet march computes it.
    let mut init = [Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new()];
    let mut dirs = [Vec::new(), Vec::new(), Vec::new()];
    for i in 0..live.len() {
        // Packets without a live lane need no starting point (and count no flops for one).
        let start = if p.any(live[i]) {
            let st = ShadowState::start(p, mc, (pos[i], n[i]), live[i]);
            [st.x.x, st.x.y, st.x.z, st.s, st.prev]
        } else {
            [p.splat(0.0); 5]
        };
        for (c, v) in start.into_iter().enumerate() {
            init[c].push(v);
        }
        for (c, v) in [l[i].x, l[i].y, l[i].z].into_iter().enumerate() {
            dirs[c].push(v);
        }
    }
    let [x, y, z, sv, prev] = init;
    let init = [
        spread(p, &x),
        spread(p, &y),
        spread(p, &z),
        spread(p, &sv),
        spread(p, &prev),
    ];
    let [lx, ly, lz] = dirs;
    let dirs = [spread(p, &lx), spread(p, &ly), spread(p, &lz)];
    let live = spread_mask(p, live);
    let mut res = vec![1.0f32; live.len()];
    if max_steps > 0 {
        let (rays, params) = ((&init, &dirs, &live[..]), (limit, k, max_steps));
        if in_pairs::<P>(s) {
            shadow_stream(Pair(p), s, mc, rays, params, &mut res, tally);
        } else {
            shadow_stream(p, s, mc, rays, params, &mut res, tally);
        }
    }
    gather(p, &res)
}

/// Lane slots of a shadow march: the point, `s`, the previous distance, the shadow, the
/// direction.
const X: usize = 0;
const S: usize = 3;
const PREV: usize = 4;
const RES: usize = 5;
const L: usize = 6;

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn shadow_stream<P: Pack>(
    p: P,
    s: &SceneConstants,
    mc: &MarchC,
    (init, dirs, live): (&[Vec<f32>; 5], &[Vec<f32>; 3], &[bool]),
    (limit, k, max_steps): (f32, f32, u32),
    res: &mut [f32],
    tally: &mut Tally,
) {
    let mut lanes = Lane::<9>::new();
    let mut rs = [0.0f32; MAX_WIDTH];
    let mut next = 0;
    let fill = |lanes: &mut Lane<9>, lane: usize, ray: usize| {
        for (c, v) in init.iter().enumerate() {
            lanes.f[X + c][lane] = v[ray];
        }
        for (c, v) in dirs.iter().enumerate() {
            lanes.f[L + c][lane] = v[ray];
        }
        lanes.f[RES][lane] = 1.0;
    };
    let limit = p.splat(limit);
    let (one, zero) = (p.splat_i(1), p.splat_i(0));
    while lanes.refill((P::WIDTH, max_steps), &mut next, live, fill) {
        // Between refills the lanes stay in registers.
        let l = lanes.load3(p, L);
        let mut left = p.load_i(&lanes.left);
        let mut st = ShadowState {
            x: lanes.load3(p, X),
            s: lanes.load(p, S),
            res: lanes.load(p, RES),
            prev: lanes.load(p, PREV),
            active: lanes.occupied(p),
        };
        loop {
            let occupied = st.active;
            shadow_step(p, s, mc, (l, limit, k), &mut st, tally);
            left = p.sub_i(left, one);
            let going = p.and_not(st.active, p.eq_i(left, zero));
            let finished = p.and_not(occupied, going);
            st.active = going;
            if !p.any(finished) {
                continue;
            }
            p.store(st.res, &mut rs);
            let bits = p.bitmask(finished);
            for lane in (0..P::WIDTH).filter(|&l| bits & (1 << l) != 0) {
                if let Some(ray) = lanes.ray[lane].take() {
                    res[ray] = rs[lane];
                }
            }
            if !p.any(going) || lanes.wants_refill(P::WIDTH, next, live.len()) {
                lanes.store3(p, X, st.x);
                p.store(st.s, &mut lanes.f[S]);
                p.store(st.res, &mut lanes.f[RES]);
                p.store(st.prev, &mut lanes.f[PREV]);
                p.store_i(left, &mut lanes.left);
                break;
            }
        }
    }
}
