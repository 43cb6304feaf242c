//! Tests of the tracer's internals: the ray streams against the packet marches, ray by ray,
//! on every backend.

use super::eval::Tally;
use super::lanes::{MAX_WIDTH, V3};
use super::march::{march, normal, soft_shadow};
use super::shade::{Frame, camera_rays, packet_shape};
use super::stream::{Packets, march_packets, shadow_packets};
use crate::compile::{CompileOptions, emit};
use crate::scene::Scene;
use crate::simd::{Pack, PackKernel};
use craterfield_core::backend::Backend;
use glam::Vec3;

/// Streams against packet marches over one frame: the rays' mismatches (`t`, hit,
/// material or distance of a ray's march; a shadow's value), bit for bit.
#[derive(Clone)]
struct Compare<'a> {
    frame: &'a Frame,
}

impl PackKernel for Compare<'_> {
    type Output = (usize, usize);

    fn run<P: Pack>(self, p: P) -> (usize, usize) {
        let f = self.frame;
        let (pw, ph) = packet_shape::<P>();
        let mut dirs = Vec::new();
        for j0 in (0..f.height).step_by(ph as usize) {
            for i0 in (0..f.width).step_by(pw as usize) {
                dirs.push(camera_rays(p, f, (i0, j0)));
            }
        }
        let every = p.gt(p.splat(1.0), p.splat(0.0));
        // Every third packet without its first lanes, so that some rays are not live.
        let live: Vec<P::M> = (0..dirs.len())
            .map(|k| {
                let mut v = [1.0f32; MAX_WIDTH];
                if k % 3 == 0 {
                    v[..P::WIDTH / 2].fill(0.0);
                }
                p.and(every, p.gt(p.load(&v), p.splat(0.5)))
            })
            .collect();
        let o = vec![V3::splat(p, f.camera.position); dirs.len()];
        let (s, mc) = (&f.scene, &f.march);
        let mut tally = Tally::default();
        let rays = Packets {
            from: &o,
            dir: &dirs,
            live: &live,
        };
        let streamed = march_packets(p, s, mc, rays, &mut tally);
        let bits = |v: P::F| {
            let mut a = [0.0f32; MAX_WIDTH];
            p.store(v, &mut a);
            a.map(f32::to_bits)
        };
        let mut march_bad = 0;
        let (mut pos, mut n, mut hits) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..dirs.len() {
            let h = march(p, s, mc, o[k], dirs[k], live[k], &mut tally);
            let g = &streamed[k];
            let lanes = p.bitmask(live[k]);
            let hit = p.bitmask(h.hit);
            let (mut hm, mut gm) = ([0i32; MAX_WIDTH], [0i32; MAX_WIDTH]);
            p.store_i(h.m, &mut hm);
            p.store_i(g.m, &mut gm);
            for lane in (0..P::WIDTH).filter(|l| lanes & (1 << l) != 0) {
                let same_hit = (hit ^ p.bitmask(g.hit)) & (1 << lane) == 0;
                let same = same_hit
                    && bits(h.t)[lane] == bits(g.t)[lane]
                    && (hit & (1 << lane) == 0
                        || (hm[lane] == gm[lane] && bits(h.d)[lane] == bits(g.d)[lane]));
                march_bad += usize::from(!same);
            }
            let q = dirs[k].mul_add(p, h.t, o[k]);
            n.push(normal(p, s, mc, (q, h.m, h.d), h.hit, &mut tally));
            pos.push(q);
            hits.push(h.hit);
        }
        let l = V3::splat(p, Vec3::new(0.3, 0.9, -0.2).normalize());
        let ls = vec![l; dirs.len()];
        let limit = (f32::INFINITY, 16.0, mc.m.max_steps);
        let rays = Packets {
            from: &pos,
            dir: &ls,
            live: &hits,
        };
        let streamed = shadow_packets(p, s, mc, rays, &n, limit, &mut tally);
        let mut shadow_bad = 0;
        for k in 0..dirs.len() {
            let (inf, sk, steps) = limit;
            let packet = (pos[k], n[k], l);
            let r = soft_shadow(
                p,
                s,
                mc,
                packet,
                p.splat(inf),
                sk,
                steps,
                hits[k],
                &mut tally,
            );
            let (a, b) = (bits(r), bits(streamed[k]));
            shadow_bad += (0..P::WIDTH).filter(|&lane| a[lane] != b[lane]).count();
        }
        (march_bad, shadow_bad)
    }
}

/// A builtin scene's frame with the paper preset at `w x h`, with `steps` steps at most
/// where given.
fn paper_frame(name: &str, (w, h): (u32, u32), steps: Option<u32>) -> Frame {
    let scene = Scene::builtin(name).unwrap();
    let camera = scene.camera.camera().unwrap();
    let opts = CompileOptions {
        aspect: w as f32 / h as f32,
        height: h,
        ..CompileOptions::paper()
    };
    let mut plan = emit(&scene, &camera, &opts).unwrap();
    if let Some(steps) = steps {
        plan.march.max_steps = steps;
    }
    Frame::new(&plan, &camera, w, h)
}

#[test]
fn streams_give_every_ray_the_bits_of_its_packet_march() {
    for (name, steps) in [
        ("scene0", None),
        ("mandelbulb", None),
        ("mandelbulb", Some(40)),
    ] {
        // With few steps, rays that run out of them leave their lanes too.
        let frame = paper_frame(name, (37, 23), steps);
        let k = Compare { frame: &frame };
        let mut runs = vec![("counting", crate::simd::count::Counting.call(k.clone()))];
        for b in [
            Backend::Scalar,
            Backend::Avx2,
            Backend::Avx512,
            Backend::Neon,
        ] {
            if b.is_available() {
                runs.push((b.name(), crate::simd::run(b, k.clone()).unwrap()));
            }
        }
        for (backend, (march_bad, shadow_bad)) in runs {
            assert_eq!(
                (march_bad, shadow_bad),
                (0, 0),
                "{name} (max steps {steps:?}) on {backend}: rays whose march or shadow differ"
            );
        }
    }
}

#[test]
fn far_bounds_skip_the_bulb_without_changing_a_bit() {
    let bounded = paper_frame("mandelbulb", (128, 72), None);
    let mut unbounded = bounded.clone();
    for node in &mut unbounded.scene.nodes {
        assert!(node.far.take().is_some() || node.plane);
    }
    let counted = |frame: &Frame| {
        super::run_threads(frame, 1, 16, |job| {
            Ok(crate::simd::count::Counting.call(job))
        })
        .unwrap()
    };
    let ((with, t_with), (without, t_without)) = (counted(&bounded), counted(&unbounded));
    assert_eq!(with.rgba, without.rgba, "counting backend");
    // Every skip is an evaluation not made.
    assert!(
        t_with.tally.sdf < t_without.tally.sdf * 95 / 100,
        "{} of {} evaluations",
        t_with.tally.sdf,
        t_without.tally.sdf
    );
    for b in [
        Backend::Scalar,
        Backend::Avx2,
        Backend::Avx512,
        Backend::Neon,
    ] {
        if !b.is_available() {
            continue;
        }
        let render = |frame: &Frame| {
            super::run_threads(frame, 1, 16, |job| Ok(crate::simd::run(b, job)?))
                .unwrap()
                .0
                .rgba
        };
        assert!(render(&bounded) == render(&unbounded), "{b}");
    }
}
