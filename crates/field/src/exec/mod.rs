//! The tape interpreter, written once over [`Lanes`] and run on every backend.
//!
//! A block of `NB` lane registers of points (`NB * WIDTH` points) goes through the tape
//! one instruction at a time: each instruction is decoded once and applied to the whole
//! block, which spreads the decoding over many lanes. The register file holds `NB` lane
//! registers per tape register, as plain values ([`Fv`]) or dual numbers ([`Dv`]). Masks and
//! integers (repetition indices, materials) are stored as bits in a register's value part.

pub(crate) mod batch;
pub(crate) mod point;
pub(crate) mod prims;
pub(crate) mod value;

use glam::Vec2;

use self::prims::Params;
pub(crate) use self::value::{Dv, Fv, P2, Val};
use crate::tape::{Op, Tape};
use craterfield_core::simd::Lanes;

/// Runs `tape` over the first `used` (at most `NB`) lane registers of a block of points:
/// `regs` holds at least `tape.registers()` registers. Results stay in the registers; the
/// lane registers past `used` keep whatever they held.
#[inline(always)]
pub(crate) fn run_tape<L: Lanes, V: Val<L>, const NB: usize>(
    l: L,
    tape: &Tape,
    regs: &mut [[V; NB]],
    xs: &[L::F; NB],
    ys: &[L::F; NB],
    used: usize,
) {
    let used = used.min(NB);
    let prm = Params(&tape.params);
    for ins in &tape.instrs {
        let (d, a, b, c) = (
            ins.dst as usize,
            ins.a as usize,
            ins.b as usize,
            ins.c as usize,
        );
        let imm = ins.imm_f32();
        // Operands are copied out before the result is written, so a destination may
        // share a register with an operand.
        macro_rules! each {
            (|$j:ident| $e:expr) => {{
                let mut out = regs[d];
                for $j in 0..used {
                    out[$j] = $e;
                }
                regs[d] = out;
            }};
        }
        macro_rules! un {
            (|$x:ident| $e:expr) => {{
                let xa = regs[a];
                each!(|j| {
                    let $x = xa[j];
                    $e
                })
            }};
        }
        macro_rules! bin {
            (|$x:ident, $y:ident| $e:expr) => {{
                let (xa, xb) = (regs[a], regs[b]);
                each!(|j| {
                    let ($x, $y) = (xa[j], xb[j]);
                    $e
                })
            }};
        }
        macro_rules! point {
            (|$p:ident| $e:expr) => {{
                let (xa, xb) = (regs[a], regs[b]);
                each!(|j| {
                    let $p = P2::new(xa[j], xb[j]);
                    $e
                })
            }};
        }
        let at = ins.imm as usize;
        match ins.op {
            Op::X => each!(|j| V::px(l, xs[j])),
            Op::Y => each!(|j| V::py(l, ys[j])),
            Op::Const => each!(|j| V::cst(l, imm)),
            Op::Add => bin!(|x, y| x.add(l, y)),
            Op::Sub => bin!(|x, y| x.sub(l, y)),
            Op::Mul => bin!(|x, y| x.mul(l, y)),
            Op::Neg => un!(|x| x.neg(l)),
            Op::Abs => un!(|x| x.abs(l)),
            Op::Sqrt => un!(|x| x.sqrt(l)),
            Op::Square => un!(|x| x.mul(l, x)),
            Op::Offset => un!(|x| x.offset(l, imm)),
            Op::Scale => un!(|x| x.scale(l, imm)),
            Op::Min => bin!(|x, y| x.min(l, y)),
            Op::Max => bin!(|x, y| x.max(l, y)),
            Op::ShiftSub => bin!(|x, y| x.offset_v(l, l.neg(y.v()))),
            Op::AddImm => un!(|x| x.add(l, V::cst(l, imm))),
            Op::SubImm => un!(|x| x.sub(l, V::cst(l, imm))),
            Op::RSubImm => un!(|x| V::cst(l, imm).sub(l, x)),
            Op::MulImm => un!(|x| x.mul(l, V::cst(l, imm))),
            Op::MinImm => un!(|x| x.min(l, V::cst(l, imm))),
            Op::MaxImm => un!(|x| x.max(l, V::cst(l, imm))),
            Op::SmoothMin => bin!(|x, y| prims::smooth(l, x, y, imm, false)),
            Op::SmoothMax => bin!(|x, y| prims::smooth(l, x, y, imm, true)),
            Op::Circle => point!(|p| prims::circle(l, p, prm.v2(at), prm.f(at + 2))),
            Op::Box => point!(|p| prims::aabox(l, p, prm.v2(at), prm.v2(at + 2))),
            Op::OrientedBox => {
                point!(|p| prims::oriented_box(l, p, prm.v2(at), prm.v2(at + 2), prm.v2(at + 4)))
            }
            Op::Capsule => point!(|p| prims::capsule(
                l,
                p,
                prm.v2(at),
                prm.v2(at + 2),
                prm.f(at + 4),
                prm.f(at + 5)
            )),
            Op::Polygon => point!(|p| prims::polygon(l, p, Params(&tape.params[at..]))),
            Op::Ellipse => point!(|p| prims::ellipse(l, p, prm.v2(at), prm.v2(at + 2))),
            Op::Ring => point!(|p| prims::ring(l, p, prm.v2(at), prm.f(at + 2), prm.f(at + 3))),
            Op::Arc => point!(|p| prims::arc(
                l,
                p,
                prm.v2(at),
                prm.v2(at + 2),
                prm.v2(at + 4),
                prm.f(at + 6),
                prm.f(at + 7)
            )),
            Op::HalfPlane => point!(|p| prims::half_plane(l, p, prm.v2(at), prm.f(at + 2))),
            Op::Height => {
                point!(|p| prims::height_profile(l, p, Params(&tape.params[at..]), tape.height_cap))
            }
            Op::Noise => bin!(|x, y| prims::value_noise(l, x, y, ins.imm)),
            Op::Wave => un!(|x| prims::wave(l, x)),
            Op::RepeatIndex => {
                let (period, lo, hi) = (prm.f(at), prm.u(at + 1) as i32, prm.u(at + 2) as i32);
                un!(|x| {
                    let t = l.floor(l.add(l.div(x.v(), l.splat(period)), l.splat(0.5)));
                    let k = l.to_i32(t);
                    let (lo, hi) = (l.splat_i(lo), l.splat_i(hi));
                    let k = l.select_i(l.lt_i(k, lo), lo, l.select_i(l.gt_i(k, hi), hi, k));
                    V::lanes(l, l.int_bits(k))
                })
            }
            Op::RepeatOffset => {
                let (dk, period) = (prm.u(at) as i32, prm.f(at + 1));
                un!(|x| {
                    let k = l.add_i(l.bits_int(x.v()), l.splat_i(dk));
                    V::lanes(l, l.mul(l.to_f32(k), l.splat(period)))
                })
            }
            Op::RepeatActive => {
                let (dk, lo, hi) = (prm.u(at) as i32, prm.u(at + 1) as i32, prm.u(at + 2) as i32);
                un!(|x| {
                    let k = l.add_i(l.bits_int(x.v()), l.splat_i(dk));
                    let out = l.or(l.lt_i(k, l.splat_i(lo)), l.gt_i(k, l.splat_i(hi)));
                    V::lanes(l, l.mask_bits(l.not(out)))
                })
            }
            Op::Lt => bin!(|x, y| V::lanes(l, l.mask_bits(l.lt(x.v(), y.v())))),
            Op::And => bin!(|x, y| {
                let m = l.and(l.bits_mask(x.v()), l.bits_mask(y.v()));
                V::lanes(l, l.mask_bits(m))
            }),
            Op::Select => {
                let (xa, xb, xc) = (regs[a], regs[b], regs[c]);
                each!(|j| V::select(l, l.bits_mask(xa[j].v()), xb[j], xc[j]))
            }
            Op::MatConst => each!(|j| V::lanes(l, l.int_bits(l.splat_i(ins.imm as i32)))),
            Op::MatSelect => {
                let (xa, xb, xc) = (regs[a], regs[b], regs[c]);
                each!(|j| V::lanes(l, l.select(l.bits_mask(xa[j].v()), xb[j].v(), xc[j].v())))
            }
            Op::Hypot => bin!(|x, y| x.mul(l, x).add(l, y.mul(l, y)).sqrt(l)),
            Op::MaxNeg => bin!(|x, y| x.max(l, y.neg(l))),
            Op::MinNeg => bin!(|x, y| x.min(l, y.neg(l))),
            Op::Max3 => {
                let (xa, xb, xc) = (regs[a], regs[b], regs[c]);
                each!(|j| xa[j].max(l, xb[j]).max(l, xc[j]))
            }
            Op::Min3 => {
                let (xa, xb, xc) = (regs[a], regs[b], regs[c]);
                each!(|j| xa[j].min(l, xb[j]).min(l, xc[j]))
            }
            Op::MaxSubImm => bin!(|x, y| x.max(l, y.sub(l, V::cst(l, imm)))),
            Op::MaxRSubImm => bin!(|x, y| x.max(l, V::cst(l, imm).sub(l, y))),
            Op::MaxAddImm => bin!(|x, y| x.max(l, y.add(l, V::cst(l, imm)))),
            Op::MinSubImm => bin!(|x, y| x.min(l, y.sub(l, V::cst(l, imm)))),
            Op::MinRSubImm => bin!(|x, y| x.min(l, V::cst(l, imm).sub(l, y))),
            Op::MinAddImm => bin!(|x, y| x.min(l, y.add(l, V::cst(l, imm)))),
            Op::MaxSub => {
                let (xa, xb, xc) = (regs[a], regs[b], regs[c]);
                each!(|j| xa[j].max(l, xb[j].sub(l, xc[j])))
            }
            Op::MinSub => {
                let (xa, xb, xc) = (regs[a], regs[b], regs[c]);
                each!(|j| xa[j].min(l, xb[j].sub(l, xc[j])))
            }
        }
    }
}

/// Loads the first `used` (at most `NB`) lane registers of x and y from `points`
/// (shorter input repeats its last point so every lane holds a real point).
#[inline(always)]
pub(crate) fn load_points<L: Lanes, const NB: usize>(
    l: L,
    points: &[Vec2],
    xs: &mut [L::F; NB],
    ys: &mut [L::F; NB],
    used: usize,
) {
    let w = L::WIDTH;
    let mut bx = [0.0f32; 16];
    let mut by = [0.0f32; 16];
    let last = points.len().saturating_sub(1);
    for r in 0..used.min(NB) {
        for k in 0..w {
            let p = points.get(r * w + k).or(points.get(last)).copied();
            let p = p.unwrap_or(Vec2::ZERO);
            bx[k] = p.x;
            by[k] = p.y;
        }
        xs[r] = l.load(&bx);
        ys[r] = l.load(&by);
    }
}
