//! One point's running maximum over a list of sharp carves, on SIMD lanes across the
//! events: the list's disc distances computed a register of events at a time, instead of
//! one square root after another feeding one chain of maxima.
//!
//! A list of sharp, settled carves applies as `nmax(d, -c_1)`, then `-c_2`, and so on
//! (`terrain::field::sharp_carves`). Without NaN operands that chain ends at the largest
//! value, with the bits of the last operand equal to it; equal non-zero floats have the
//! same bits, so any order of maxima gives the chain's bits unless the largest value is
//! a zero (whose sign the order decides) or an operand is NaN (which the chain drops at
//! the next step). In those two cases the lanes answer `None` and the caller runs the
//! chain. Each lane computes the scalar path's operations in its order (subtract, square,
//! add, square root, add the negated radius, negate), all exactly rounded, so the values
//! are the chain's bits on every backend.

use craterfield_core::backend::Backend;
use craterfield_core::simd::{self, Kernel, Lanes};

use super::grid::{DISC_LANES, EventList};

/// Lists shorter than this stay on the scalar chain: below it the dispatch to the lanes
/// costs more than the chain.
pub(super) const LANES_FROM: usize = 8;

/// `nmax(d, -c_1, ..., -c_n)` over the carves of `list` at `(x, y)`, with the chain's bits,
/// or `None` where only the chain gives them (see the module doc) or `backend` is the
/// scalar one (its lanes are the chain).
pub(super) fn carve_max(backend: Backend, x: f32, y: f32, list: &EventList, d: f32) -> Option<f32> {
    let (top, _) = lanes::<false>(backend, x, y, list)?;
    with_state(d, top).map(|(top, _)| top)
}

/// [`carve_max`] with the operand the chain's result came from: `Some(k)` for the `k`-th
/// listed event, `None` for `d` (the chain moves to an event's value whenever it is not
/// below the running maximum, so on a tie the event wins, the last of equal events).
pub(super) fn carve_max_term(
    backend: Backend,
    x: f32,
    y: f32,
    list: &EventList,
    d: f32,
) -> Option<(f32, Option<usize>)> {
    let (top, k) = lanes::<true>(backend, x, y, list)?;
    let (top, from_event) = with_state(d, top)?;
    Some((top, from_event.then_some(k)))
}

/// The events' largest value and (with `TERM`) the last event that has it.
fn lanes<const TERM: bool>(
    backend: Backend,
    x: f32,
    y: f32,
    list: &EventList,
) -> Option<(f32, usize)> {
    if backend == Backend::Scalar {
        return None;
    }
    // Laid out on the first ask (a scalar backend never asks).
    let chunks = list.discs().chunks();
    simd::run(backend, CarveMax::<TERM> { x, y, chunks }).ok()?
}

/// `nmax(d, top)` and whether `top` won (a NaN `d` gives `top`, as the chain's first step
/// drops it); `None` at zero, whose sign the order decides.
fn with_state(d: f32, top: f32) -> Option<(f32, bool)> {
    let (top, from_event) = if d > top { (d, false) } else { (top, true) };
    (top != 0.0).then_some((top, from_event))
}

/// The kernel of [`carve_max`] and [`carve_max_term`]: the largest negated disc distance
/// and, with `TERM`, the last event that has it; `None` if one is NaN, or if the largest
/// is the padding's `-inf` (which event the chain ended at is then its to say).
struct CarveMax<'a, const TERM: bool> {
    x: f32,
    y: f32,
    chunks: &'a [f32],
}

impl<const TERM: bool> Kernel for CarveMax<'_, TERM> {
    type Output = Option<(f32, usize)>;

    #[inline(always)]
    fn run<L: Lanes, const NB: usize>(self, l: L) -> Option<(f32, usize)> {
        let (px, py) = (l.splat(self.x), l.splat(self.y));
        let mut top = l.splat(f32::NEG_INFINITY);
        let mut numbers = l.not_nan(top);
        let mut lane_of = [0i32; DISC_LANES];
        for (k, slot) in lane_of.iter_mut().enumerate() {
            *slot = k as i32;
        }
        let (mut at, step) = (l.load_i(&lane_of), l.splat_i(L::WIDTH as i32));
        let mut from = l.splat_i(-1);
        for chunk in self.chunks.chunks_exact(3 * DISC_LANES) {
            let (xs, rest) = chunk.split_at(DISC_LANES);
            let (ys, rs) = rest.split_at(DISC_LANES);
            for k in (0..DISC_LANES).step_by(L::WIDTH) {
                let dx = l.sub(px, l.load(&xs[k..]));
                let dy = l.sub(py, l.load(&ys[k..]));
                let length = l.sqrt(l.add(l.mul(dx, dx), l.mul(dy, dy)));
                let v = l.neg(l.add(length, l.neg(l.load(&rs[k..]))));
                numbers = l.and(numbers, l.not_nan(v));
                if TERM {
                    // `nmax(top, v)` lane by lane, noting where `v` is taken.
                    let keep = l.gt(top, v);
                    top = l.select(keep, top, v);
                    from = l.select_i(keep, from, at);
                    at = l.add_i(at, step);
                } else {
                    top = l.max(top, v);
                }
            }
        }
        if l.any(l.not(numbers)) {
            return None;
        }
        let mut values = [f32::NEG_INFINITY; DISC_LANES];
        l.store(top, &mut values);
        // Halving: the order of maxima does not change the value (no NaN is left).
        let mut width = L::WIDTH.min(DISC_LANES);
        while width > 1 {
            width /= 2;
            let (low, high) = values.split_at_mut(width);
            for (a, b) in low.iter_mut().zip(high.iter()) {
                *a = if *a > *b { *a } else { *b };
            }
        }
        let largest = values[0];
        if largest == f32::NEG_INFINITY {
            return None;
        }
        if !TERM {
            return Some((largest, 0));
        }
        // The last event with the largest value (equal values have equal bits unless
        // zero, which the caller leaves to the chain).
        let on_top = l.ge(top, l.splat(largest));
        let mut events = [-1i32; DISC_LANES];
        l.store_i(l.select_i(on_top, from, l.splat_i(-1)), &mut events);
        let last = events.iter().fold(-1, |a, &b| a.max(b));
        Some((largest, usize::try_from(last).ok()?))
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::{LANES_FROM, carve_max, carve_max_term};
    use crate::Event;
    use crate::terrain::grid::EventList;
    use craterfield_core::backend::Backend;
    use craterfield_core::det::math::{Num, V2};

    /// The chain of `terrain::field::sharp_carves` before its clamp, with the position of
    /// the operand it ended at (`None`: `d`).
    fn chain(d: f32, p: Vec2, list: &EventList) -> (f32, Option<usize>) {
        let (mut top, mut from) = (d, None);
        for (k, e) in list.listed().iter().enumerate() {
            let c = V2::new(p.x, p.y)
                .minus(e.center_f32())
                .length()
                .offset(-e.radius_f32());
            // `nmax(top, -c)`, noting where it takes `-c`.
            let keeps = top > -c;
            if !keeps {
                (top, from) = (-c, Some(k));
            }
        }
        (top, from)
    }

    /// Lists of up to 70 carves around a point: random discs, repeated discs (equal
    /// values), discs whose edge passes exactly through the point (a value of zero), and
    /// states `d` above, below and between the events' values, NaN and zero included.
    fn cases(seed: u64) -> Vec<(Vec2, EventList, f32)> {
        let mut unit = crate::test_rng::unit_f64(seed);
        let mut out = Vec::new();
        for case in 0..3000 {
            let p = Vec2::new(
                (unit() * 800.0 - 400.0) as f32,
                (unit() * 800.0 - 400.0) as f32,
            );
            let n = (unit() * 70.0) as usize;
            let mut log = Vec::new();
            for k in 0..n {
                let centre =
                    p + Vec2::new(unit() as f32 * 120.0 - 60.0, unit() as f32 * 120.0 - 60.0);
                let e = match (case % 5, k % 7) {
                    // An edge through `p` (3-4-5 triangles): the value is exactly zero.
                    (1, 0) => Event::carve(p.round() + Vec2::new(3.0, 4.0), 5.0),
                    (2, _) if k > 0 => Ok(log[k - 1]),
                    _ => Event::carve(centre, 1.0 + unit() as f32 * 50.0),
                };
                log.push(e.expect("a valid carve"));
            }
            let p = if case % 5 == 1 { p.round() } else { p };
            let indices: Vec<u32> = (0..n as u32).collect();
            let list = EventList::from_log(&indices, &log).expect("indices in the log");
            let d = match case % 4 {
                0 => (unit() * 80.0 - 40.0) as f32,
                1 => f32::NAN,
                2 => chain(f32::NEG_INFINITY, p, &list).0,
                _ => 0.0,
            };
            out.push((p, list, d));
        }
        out
    }

    /// On every backend this machine runs, the lanes give the chain's bits and the
    /// chain's last operand wherever they answer, and they answer all but the zero ties.
    #[test]
    fn lanes_give_the_chains_bits_and_term() {
        for backend in Backend::available() {
            let (mut answered, mut asked) = (0, 0);
            for (p, list, d) in cases(0xca7e ^ backend as u64) {
                let (value, from) = chain(d, p, &list);
                let got = carve_max_term(backend, p.x, p.y, &list, d);
                let plain = carve_max(backend, p.x, p.y, &list, d);
                assert_eq!(got.map(|(v, _)| v.to_bits()), plain.map(f32::to_bits));
                if list.len() < LANES_FROM || backend == Backend::Scalar {
                    continue;
                }
                asked += 1;
                let Some((v, k)) = got else {
                    assert!(value == 0.0, "{backend:?} at {p}: no answer for {value}");
                    continue;
                };
                answered += 1;
                assert_eq!(v.to_bits(), value.to_bits(), "{backend:?} at {p}, d {d}");
                assert_eq!(k, from, "{backend:?} at {p}, d {d}, value {value}");
            }
            if backend != Backend::Scalar {
                assert!(
                    answered * 10 > asked * 7,
                    "{backend:?}: {answered} of {asked}"
                );
            }
        }
    }

    /// A NaN or infinite point leaves the answer to the chain.
    #[test]
    fn points_off_the_numbers_are_left_to_the_chain() {
        let log: Vec<Event> = (0..20)
            .map(|k| Event::carve(Vec2::new(k as f32, 0.0), 3.0).expect("a valid carve"))
            .collect();
        let list = EventList::from_log(&(0..20).collect::<Vec<u32>>(), &log).unwrap();
        for backend in Backend::available() {
            for (x, y) in [
                (f32::NAN, 0.0),
                (0.0, f32::NAN),
                (f32::INFINITY, 0.0),
                (0.0, f32::NEG_INFINITY),
            ] {
                assert_eq!(
                    carve_max_term(backend, x, y, &list, 1.0),
                    None,
                    "{backend:?} at {x}, {y}"
                );
            }
        }
    }
}
