//! Batch evaluation of a [`Tape`] over slices of points, on a chosen backend.

use glam::Vec2;

use super::{Dv, Fv, Val, load_points, run_tape};
use crate::sample::{MaterialId, Sample};
use crate::tape::{EvalError, MatOut, Tape, check};
use craterfield_core::backend::Backend;
use craterfield_core::simd::{self, Kernel, Lanes};

/// The per-backend scratch of a block: coordinates and registers.
pub(crate) struct Block<L: Lanes, V, const NB: usize> {
    pub xs: [L::F; NB],
    pub ys: [L::F; NB],
    pub regs: Vec<[V; NB]>,
}

impl<L: Lanes, V: Val<L>, const NB: usize> Block<L, V, NB> {
    #[inline(always)]
    pub(crate) fn new(l: L, tape: &Tape) -> Self {
        Block {
            xs: [l.splat(0.0); NB],
            ys: [l.splat(0.0); NB],
            regs: vec![[V::cst(l, 0.0); NB]; tape.registers()],
        }
    }

    /// Runs the tape on up to `NB * WIDTH` points.
    #[inline(always)]
    pub(crate) fn run(&mut self, l: L, tape: &Tape, points: &[Vec2]) {
        self.run_used(l, tape, points, NB);
    }

    /// Runs the tape on the first `used` lane registers of up to `NB * WIDTH` points
    /// (a short block: the registers past the points would only repeat the last one).
    #[inline(always)]
    pub(crate) fn run_used(&mut self, l: L, tape: &Tape, points: &[Vec2], used: usize) {
        if self.regs.len() < tape.registers() {
            self.regs.resize(tape.registers(), [V::cst(l, 0.0); NB]);
        }
        load_points(l, points, &mut self.xs, &mut self.ys, used);
        run_tape(l, tape, &mut self.regs, &self.xs, &self.ys, used);
    }

    /// The value register `reg`'s lane register `r`.
    #[inline(always)]
    pub(crate) fn get(&self, reg: u32, r: usize) -> V {
        self.regs[reg as usize][r]
    }

    /// Materials of lane register `r` (`out` gets `WIDTH` entries).
    #[inline(always)]
    pub(crate) fn materials(&self, l: L, tape: &Tape, r: usize, out: &mut [MaterialId; 16]) {
        match tape.material {
            MatOut::Const(m) => out.fill(m),
            MatOut::Value(reg) => {
                let mut bits = [0i32; 16];
                l.store_i(l.bits_int(self.get(reg, r).v()), &mut bits);
                for (o, b) in out.iter_mut().zip(bits) {
                    *o = b as MaterialId;
                }
            }
        }
    }
}

struct Distances<'a> {
    tape: &'a Tape,
    points: &'a [Vec2],
    out: &'a mut [f32],
}

impl Kernel for Distances<'_> {
    type Output = ();
    #[inline(always)]
    fn run<L: Lanes, const NB: usize>(self, l: L) {
        let mut block = Block::<L, Fv<L>, NB>::new(l, self.tape);
        let step = NB * L::WIDTH;
        let mut lanes = [0.0f32; 16];
        for (pts, out) in self.points.chunks(step).zip(self.out.chunks_mut(step)) {
            block.run(l, self.tape, pts);
            for (r, out) in out.chunks_mut(L::WIDTH).enumerate() {
                l.store(block.get(self.tape.value, r).0, &mut lanes);
                out.copy_from_slice(&lanes[..out.len()]);
            }
        }
    }
}

struct Samples<'a> {
    tape: &'a Tape,
    points: &'a [Vec2],
    out: &'a mut [Sample],
}

impl Kernel for Samples<'_> {
    type Output = ();
    #[inline(always)]
    fn run<L: Lanes, const NB: usize>(self, l: L) {
        let mut block = Block::<L, Dv<L>, NB>::new(l, self.tape);
        let step = NB * L::WIDTH;
        let (mut v, mut gx, mut gy) = ([0.0f32; 16], [0.0f32; 16], [0.0f32; 16]);
        let mut mats = [0; 16];
        for (pts, out) in self.points.chunks(step).zip(self.out.chunks_mut(step)) {
            block.run(l, self.tape, pts);
            for (r, out) in out.chunks_mut(L::WIDTH).enumerate() {
                let d = block.get(self.tape.value, r);
                l.store(d.v, &mut v);
                l.store(d.dx, &mut gx);
                l.store(d.dy, &mut gy);
                block.materials(l, self.tape, r, &mut mats);
                for (k, s) in out.iter_mut().enumerate() {
                    *s = Sample {
                        distance: v[k],
                        gradient: Vec2::new(gx[k], gy[k]),
                        material: mats[k],
                    };
                }
            }
        }
    }
}

impl Tape {
    /// Distances at `points` into `out` on `backend`.
    pub fn distances(
        &self,
        points: &[Vec2],
        out: &mut [f32],
        backend: Backend,
    ) -> Result<(), EvalError> {
        check(points.len(), out.len())?;
        simd::run(
            backend,
            Distances {
                tape: self,
                points,
                out,
            },
        )?;
        Ok(())
    }

    /// Distance, gradient and material at `points` into `out` on `backend` (the material
    /// is 0 unless the tape computes materials, see [`crate::tape::Outputs`]).
    pub fn samples(
        &self,
        points: &[Vec2],
        out: &mut [Sample],
        backend: Backend,
    ) -> Result<(), EvalError> {
        check(points.len(), out.len())?;
        simd::run(
            backend,
            Samples {
                tape: self,
                points,
                out,
            },
        )?;
        Ok(())
    }
}
