//! The field's definition at one point (see the terrain module doc): the numbers it runs
//! on, the smooth minimum and maximum, and what one event does to a distance and a
//! material. The grid and the proofs apply events through [`apply_event`]; the batch lanes
//! (`super::batch`) transcribe it operation for operation, which is what makes every path's
//! results share bits.

use glam::Vec2;

use super::cell_tapes::CellTape;
use super::grid::Listed;
use crate::event::{Event, EventKind};
use crate::exec;
use crate::sample::MaterialId;
use crate::sdf::Sdf;
use craterfield_core::det::math::{Dual, Num, V2, nclamp, nmax, nmin};

/// The numbers the field runs on: `f32` for distances, [`Dual`] for samples.
pub(super) trait Lift: Num {
    /// Whether this path reports materials (the `f32` path does not need them).
    const MATERIAL: bool;
    /// Whether this is the `f32` path, a value without a gradient (a result computed on
    /// values alone is then this type's [`Num::constant`]).
    const VALUE: bool;
    fn point(p: Vec2) -> V2<Self>;
    /// The base field at `p`; `material` asks the `f32` path to report the material too.
    fn base<F: Sdf>(f: &F, p: Vec2, material: bool) -> (Self, MaterialId);
    /// The same from the base's tapes for the region holding `p`.
    fn tape(plan: &CellTape, p: Vec2, material: bool) -> (Self, MaterialId);
    /// Whether this is exactly the band's top, `+M` with a `+0` gradient: what the clamp
    /// makes of every value above it, so a carve (which only raises) leaves it as it is.
    fn is_top(self, band: f32) -> bool;
}

impl Lift for f32 {
    const MATERIAL: bool = false;
    const VALUE: bool = true;
    fn point(p: Vec2) -> V2<f32> {
        V2::new(p.x, p.y)
    }
    fn base<F: Sdf>(f: &F, p: Vec2, material: bool) -> (f32, MaterialId) {
        if material {
            f.distance_material(p)
        } else {
            (f.distance(p), 0)
        }
    }
    fn is_top(self, band: f32) -> bool {
        self == band
    }
    fn tape(plan: &CellTape, p: Vec2, material: bool) -> (f32, MaterialId) {
        if material {
            exec::point::value(&plan.material, p)
        } else {
            (exec::point::value(&plan.value, p).0, 0)
        }
    }
}

impl Lift for Dual {
    const MATERIAL: bool = true;
    const VALUE: bool = false;
    fn point(p: Vec2) -> V2<Dual> {
        let (x, y) = Dual::point(p);
        V2::new(x, y)
    }
    fn base<F: Sdf>(f: &F, p: Vec2, _material: bool) -> (Dual, MaterialId) {
        let s = f.sample(p);
        (
            Dual {
                v: s.distance,
                dx: s.gradient.x,
                dy: s.gradient.y,
            },
            s.material,
        )
    }
    fn tape(plan: &CellTape, p: Vec2, _material: bool) -> (Dual, MaterialId) {
        exec::point::dual(&plan.material, p)
    }
    fn is_top(self, band: f32) -> bool {
        self.v == band && self.dx.to_bits() == 0 && self.dy.to_bits() == 0
    }
}

/// Smooth minimum (see the module doc); the select keeps `min`'s bits where `h == 0`.
pub(super) fn smin<N: Num>(a: N, b: N, k: f32) -> N {
    let m = nmin(a, b);
    let h = nmax(N::constant(k) - (a - b).abs(), N::constant(0.0)) / N::constant(k);
    if h.value() > 0.0 {
        m - (h * h).scale(k).scale(0.25)
    } else {
        m
    }
}

/// Smooth maximum (see the module doc).
pub(super) fn smax<N: Num>(a: N, b: N, k: f32) -> N {
    let m = nmax(a, b);
    let h = nmax(N::constant(k) - (a - b).abs(), N::constant(0.0)) / N::constant(k);
    if h.value() > 0.0 {
        m + (h * h).scale(k).scale(0.25)
    } else {
        m
    }
}

/// `events` (sharp carves, every one settled at the tick) applied to `d` at `p`, in order:
/// the same bits as [`apply_event`] one event at a time, in a loop of one distance and one
/// `nmax` per event.
///
/// A sharp carve is `v = nclamp(nmax(d, -c), -M, M)`. The clamp between two of them changes
/// nothing the last one does not: `nclamp(nmax(nclamp(x), y)) = nclamp(nmax(x, y))` for
/// every `x` and `y`, bit for bit and on duals too, because `nmax` and `nclamp` select one
/// of their operands or a bound by value and never compute a new one. Where `x` is
/// strictly inside the band the inner clamp returns `x` itself; where `x` is at or past a
/// bound (or NaN, which the clamp sends to `-M`), both sides select the same bound or the
/// same `y` (case by case: `x >= M` gives `M` either way; `x <= -M` gives `y` where
/// `y >= -M`, else `-M`). So the running maximum is clamped once, after the last event
/// (an empty list leaves `d` as it is, unclamped, as the loop would). A carve skipped at
/// the band's top ([`apply_unless_top`]) is one whose `nmax` could only keep that top.
pub(super) fn sharp_carves<N: Num>(d: N, p: V2<N>, events: &[Listed], band: f32) -> N {
    if events.is_empty() {
        return d;
    }
    let mut top = d;
    for e in events {
        let c = p.minus(e.center_f32()).length().offset(-e.radius_f32());
        top = nmax(top, -c);
    }
    nclamp(top, -band, band)
}

/// What applying an event reads of it: a logged [`Event`], or a cell list's copy with its
/// world units already converted (the same bits).
pub(super) trait Term {
    fn event(&self) -> &Event;
    fn center(&self) -> Vec2;
    fn rim(&self) -> f32;
    fn radius_at(&self, tick: u32) -> Option<f32>;
}

impl Term for Event {
    #[inline]
    fn event(&self) -> &Event {
        self
    }
    #[inline]
    fn center(&self) -> Vec2 {
        self.center_f32()
    }
    #[inline]
    fn rim(&self) -> f32 {
        self.rim_f32()
    }
    #[inline]
    fn radius_at(&self, tick: u32) -> Option<f32> {
        Event::radius_at(self, tick)
    }
}

impl Term for Listed {
    #[inline]
    fn event(&self) -> &Event {
        Listed::event(self)
    }
    #[inline]
    fn center(&self) -> Vec2 {
        self.center_f32()
    }
    #[inline]
    fn rim(&self) -> f32 {
        self.rim_f32()
    }
    #[inline]
    fn radius_at(&self, tick: u32) -> Option<f32> {
        Listed::radius_at(self, tick)
    }
}

/// [`apply_event`], except a carve on the band's top ([`Lift::is_top`]), where it changes
/// no bit (it only raises, the clamp brings it back, the material stays): air cells and
/// carved-out points skip their later carves.
#[inline]
pub(super) fn apply_unless_top<N: Lift>(
    d: N,
    mat: MaterialId,
    p: V2<N>,
    e: &impl Term,
    tick: u32,
    band: f32,
) -> (N, MaterialId) {
    if e.event().kind == EventKind::Carve && d.is_top(band) {
        return (d, mat);
    }
    apply_event(d, mat, p, e, tick, band)
}

/// Applies one event at `p` (the field definition's loop body).
#[inline]
pub(super) fn apply_event<N: Num>(
    d: N,
    mat: MaterialId,
    p: V2<N>,
    e: &impl Term,
    tick: u32,
    band: f32,
) -> (N, MaterialId) {
    let Some(r) = e.radius_at(tick) else {
        return (d, mat);
    };
    let c = p.minus(e.center()).length().offset(-r);
    let k = e.rim();
    match e.event().kind {
        EventKind::Carve => {
            let v = if k > 0.0 { smax(d, -c, k) } else { nmax(d, -c) };
            (nclamp(v, -band, band), mat)
        }
        EventKind::Fill => {
            // The fill wins where `nmin(d, c)` selects `c`.
            let keeps_d = d.value() < c.value();
            let wins = !keeps_d;
            let v = if k > 0.0 { smin(d, c, k) } else { nmin(d, c) };
            (
                nclamp(v, -band, band),
                if wins { e.event().material } else { mat },
            )
        }
    }
}
