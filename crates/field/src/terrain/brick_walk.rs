//! A ray's walk over a brick's lattice squares in closed form, for the squares of a
//! brick whose block floors fall short of a ray's threshold (`super::ray`).
//!
//! Along a line, the bilinear interpolant of one lattice square is a quadratic in the
//! ray's parameter, so the first point where it may fall below the threshold is a root.
//! The threshold is raised by what the caller's rounded points and the `f32` lookup can
//! move the value: the piecewise-bilinear interpolant of samples of an `L`-Lipschitz field
//! changes by at most `sqrt(2) L` per unit, and the lookup's arithmetic by a few ulps of
//! the band. A square whose four samples already clear the raised threshold is passed
//! without solving anything: the interpolant never goes below its smallest sample.
//!
//! Sphere tracing converges on a surface geometrically, about a dozen evaluations for a
//! ray meeting it at a moderate angle; the walk stops at the root instead, a few
//! thousandths of a unit short of the surface, where the march needs one or two. Listed
//! carves are not read: where they dig through the brick's surface, the walk stops at the
//! interpolant's root and the march's evaluations find the air.

use std::ops::Range;

use glam::DVec2;

/// How far a walk proves a ray's piece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum BrickRun {
    /// The whole piece is proven.
    Through,
    /// Proven up to `clear`; asking again before `retry_at` proves nothing more (the end
    /// of the lattice square the proof stopped in).
    StopsAt { clear: f64, retry_at: f64 },
}

/// The interpolant's largest slope per unit over `sqrt(2) L`, with room for the rounding of
/// the samples (each a few ulps of the band, over a spacing of at least `2^-8` units).
const SLOPE_ROOM: f64 = 1.0 + 1.0 / 64.0;

/// The value the `f32` lookup and interpolation can lose against the exact bilinear, in
/// units of the band (a handful of roundings of numbers at most `M`, each `2^-24 M`).
const LOOKUP_ROOM: f64 = 1.0 / 65536.0;

/// What a walk needs of the ray, whatever the brick: its threshold raised by the rounding
/// room, and the bound on the interpolant's slope along it.
#[derive(Clone, Copy, Debug)]
pub(super) struct WalkRay {
    floor: f64,
    /// `1 / G`, `G` a bound on the interpolant's slope per unit of the ray's parameter.
    inverse_slope: f64,
}

impl WalkRay {
    /// The ray along the (unit, to `f32`'s rounding) direction `d` proving `above`, its
    /// points rounded by up to `slack`, in a field of Lipschitz bound `lipschitz` clamped
    /// to `band`.
    pub(super) fn new(d: DVec2, above: f32, slack: f64, lipschitz: f32, band: f32) -> WalkRay {
        let slope = std::f64::consts::SQRT_2 * f64::from(lipschitz) * SLOPE_ROOM;
        // `|d| <= max(1, |d|^2)`, without a square root (`d` is unit to `f32`'s rounding
        // when a march asks).
        let length = d.length_squared().max(1.0);
        WalkRay {
            floor: f64::from(above) + slope * slack + f64::from(band) * LOOKUP_ROOM,
            inverse_slope: 1.0 / (slope * length * (1.0 + 1.0e-6)),
        }
    }
}

/// The walk of the ray `p + d t` over the `n x n` squares of a brick with samples
/// `values`, lower corner `corner` and spacing `h`.
pub(super) fn walk<'a>(
    ray: &WalkRay,
    values: &'a [f32],
    n: u32,
    corner: DVec2,
    h: f64,
    p: DVec2,
    d: DVec2,
) -> Walk<'a> {
    let step = d / h;
    Walk {
        values,
        n,
        line: Line {
            start: (p - corner) / h,
            step,
            inverse_step: DVec2::ONE / step,
        },
        floor: ray.floor,
        inverse_slope: ray.inverse_slope,
    }
}

/// A ray in a brick's lattice coordinates: `start + step t`, `t` the ray's parameter.
struct Line {
    start: DVec2,
    step: DVec2,
    /// `1 / step`, per component.
    inverse_step: DVec2,
}

impl Line {
    fn at(&self, t: f64) -> DVec2 {
        self.start + self.step * t
    }
}

/// A brick's samples and what a walk along a line proves of them.
pub(super) struct Walk<'a> {
    values: &'a [f32],
    /// The brick's resolution: `n x n` squares.
    n: u32,
    line: Line,
    /// The value to stay at or above.
    floor: f64,
    /// `1 / G`, `G` a bound on the interpolant's slope per unit of the ray's parameter.
    inverse_slope: f64,
}

impl Walk<'_> {
    /// The lattice squares the line crosses over `span`, each proven at or above `floor`
    /// (Amanatides and Woo's walk, clamped to the brick as the lookup clamps its points).
    /// Where the interpolant at the walk's point is well above the floor, its slope bound
    /// clears a stretch at once, however many squares it spans: in the air part of a
    /// brick, most of a cell in two or three steps.
    pub(super) fn run(&self, span: Range<f64>) -> BrickRun {
        let last = f64::from(self.n - 1);
        let (mut i, mut j) = self.square_at(span.start);
        let mut t = span.start;
        // Every pass moves to the next square or jumps past the current one; the bound
        // only guards against rounding that would do neither.
        for _ in 0..8 * self.n + 16 {
            let exit_u = axis_exit(self.line.start.x, self.line.inverse_step.x, i);
            let exit_v = axis_exit(self.line.start.y, self.line.inverse_step.y, j);
            let end = exit_u.min(exit_v).min(span.end).max(t);
            let samples = corners(self.values, self.n, i as usize, j as usize);
            let o = self.line.at(t) - DVec2::new(i, j);
            let reach = t + (bilinear(samples, o) - self.floor) * self.inverse_slope;
            if reach > end {
                if reach >= span.end {
                    return BrickRun::Through;
                }
                t = reach;
                (i, j) = self.square_at(t);
                continue;
            }
            if let Some(stop) = first_below(samples, &self.line, [i, j], t..end, self.floor) {
                return BrickRun::StopsAt {
                    clear: stop,
                    retry_at: end,
                };
            }
            if end >= span.end {
                return BrickRun::Through;
            }
            let (next_i, next_j) = if exit_u <= exit_v {
                (i + self.line.step.x.signum(), j)
            } else {
                (i, j + self.line.step.y.signum())
            };
            if !(0.0..=last).contains(&next_i) || !(0.0..=last).contains(&next_j) {
                // Past the brick's edge before the piece's end (rounding at the cell's
                // side): the clamped lookup keeps answering from this edge square.
                return BrickRun::Through;
            }
            (i, j, t) = (next_i, next_j, end);
        }
        BrickRun::StopsAt {
            clear: t,
            retry_at: t,
        }
    }

    /// The square the line enters at `t`: on a lattice line, the one on the side it moves
    /// towards.
    fn square_at(&self, t: f64) -> (f64, f64) {
        let last = f64::from(self.n - 1);
        let at = self.line.at(t);
        let square = |x: f64, step: f64| {
            let k = if step < 0.0 {
                -floor_small(-x) - 1.0
            } else {
                floor_small(x)
            };
            k.clamp(0.0, last)
        };
        (
            square(at.x, self.line.step.x),
            square(at.y, self.line.step.y),
        )
    }
}

/// The bilinear interpolant of `samples` (`[v00, v10, v01, v11]`) at offset `o` in its
/// square; NaN where a sample is.
fn bilinear(samples: [f64; 4], o: DVec2) -> f64 {
    let [v00, v10, v01, v11] = samples;
    let bottom = v00 + (v10 - v00) * o.x;
    let top = v01 + (v11 - v01) * o.x;
    bottom + (top - bottom) * o.y
}

/// The parameter at which the line leaves lattice column (or row) `[k, k + 1]` along one
/// axis, from the inverse of its step along it (infinite where it does not move along it).
fn axis_exit(start: f64, inverse_step: f64, k: f64) -> f64 {
    if inverse_step.is_infinite() {
        f64::INFINITY
    } else if inverse_step > 0.0 {
        (k + 1.0 - start) * inverse_step
    } else if inverse_step < 0.0 {
        (k - start) * inverse_step
    } else {
        f64::INFINITY
    }
}

/// `x.floor()` for the lattice's small coordinates, without a call into the C library
/// (the baseline x86-64 target has no rounding instruction); NaN gives 0.
fn floor_small(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x { t - 1.0 } else { t }
}

/// The samples at square `(i, j)`'s corners: `[v00, v10, v01, v11]`.
fn corners(values: &[f32], n: u32, i: usize, j: usize) -> [f64; 4] {
    let row = n as usize + 1;
    let at = |i: usize, j: usize| values.get(j * row + i).map_or(f64::NAN, |&v| f64::from(v));
    [at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)]
}

/// The first parameter in `span` at which the bilinear interpolant of `samples` over the
/// square with lower corner `corner` may fall below `floor` along the line; `None` where it
/// stays at or above it over the whole span.
fn first_below(
    samples: [f64; 4],
    line: &Line,
    corner: [f64; 2],
    span: Range<f64>,
    floor: f64,
) -> Option<f64> {
    let [v00, v10, v01, v11] = samples;
    if samples.iter().any(|v| v.is_nan()) {
        return Some(span.start);
    }
    if v00.min(v10).min(v01).min(v11) >= floor {
        return None;
    }
    // f(a, b) = v00 + bu a + bv b + buv a b, with (a, b) the offset in the square.
    let (bu, bv, buv) = (v10 - v00, v01 - v00, v00 - v10 - v01 + v11);
    let o = line.at(span.start) - DVec2::new(corner[0], corner[1]);
    let s = line.step;
    // g(x) = f(o + s x) - floor = c0 + c1 x + c2 x^2, x = t - span.start.
    let c0 = v00 + bu * o.x + bv * o.y + buv * o.x * o.y - floor;
    let c1 = bu * s.x + bv * s.y + buv * (o.x * s.y + o.y * s.x);
    let c2 = buv * s.x * s.y;
    if c0.is_nan() || c0 < 0.0 {
        return Some(span.start);
    }
    let len = span.end - span.start;
    let root = first_root(c0, c1, c2, len)?;
    // The root's own rounding is far inside the rounding room of `floor`.
    Some(span.start + root)
}

/// The smallest `x` in `[0, len]` where `c0 + c1 x + c2 x^2` (`c0 >= 0`) reaches zero, or
/// `None`.
fn first_root(c0: f64, c1: f64, c2: f64, len: f64) -> Option<f64> {
    let roots = if c2 == 0.0 {
        if c1 >= 0.0 {
            return None;
        }
        [-c0 / c1, f64::INFINITY]
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return None;
        }
        // The stable pair: no difference of nearly equal numbers.
        let q = -0.5 * (c1 + disc.sqrt().copysign(c1));
        if q == 0.0 {
            // c1 = 0 and c0 = 0: the start itself is a root.
            return Some(0.0);
        }
        let (a, b) = (q / c2, c0 / q);
        [a.min(b), a.max(b)]
    };
    roots.into_iter().find(|&x| (0.0..=len).contains(&x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::unit_f64;

    /// Random squares and lines through them: the closed form's first point below the
    /// floor is where dense sampling first finds the interpolant below it, and nothing
    /// before it is below.
    #[test]
    fn the_first_root_is_the_first_crossing_dense_sampling_finds() {
        let mut next = unit_f64(0x0b1c_0001);
        let (mut stopped, mut through) = (0, 0);
        for _ in 0..20_000 {
            let samples = [0; 4].map(|_| next() * 8.0 - 3.0);
            let floor = next() * 2.0;
            let angle = next() * std::f64::consts::TAU;
            let step = DVec2::new(angle.cos(), angle.sin()) * (0.2 + next());
            let entry = DVec2::new(next(), next());
            let line = Line {
                start: entry,
                step,
                inverse_step: DVec2::ONE / step,
            };
            // The part of the line from `entry` that stays in the unit square.
            let exit = [(entry.x, step.x), (entry.y, step.y)]
                .map(|(o, s)| axis_exit(o, 1.0 / s, 0.0))
                .into_iter()
                .fold(f64::INFINITY, f64::min);
            let found = first_below(samples, &line, [0.0, 0.0], 0.0..exit, floor);
            let g = |t: f64| {
                let q = line.at(t);
                bilinear(samples, q) - floor
            };
            let dense = (0..=4000)
                .map(|k| exit * f64::from(k) / 4000.0)
                .find(|&t| g(t) < -1e-9);
            match (found, dense) {
                (None, None) => through += 1,
                (None, Some(t)) => panic!("{samples:?} floor {floor}: skipped the crossing at {t}"),
                (Some(stop), dense) => {
                    stopped += 1;
                    // Clear up to the stop, and the stop is the crossing (not an early
                    // give-up) to within the sampling's resolution.
                    for k in (0..400).filter(|_| stop > 0.0) {
                        let t = stop * f64::from(k) / 400.0;
                        assert!(
                            g(t) >= -1e-9,
                            "{samples:?}: below at {t} before the stop {stop}"
                        );
                    }
                    let near = g(stop).abs() < 1e-9 || dense.is_some_and(|t| t <= stop + 1e-3);
                    assert!(
                        near || stop == 0.0,
                        "{samples:?}: stop {stop}, dense {dense:?}"
                    );
                }
            }
        }
        assert!(
            stopped > 2000 && through > 2000,
            "{stopped} stopped, {through} through"
        );
    }

    #[test]
    fn degenerate_quadratics() {
        // Constant above the floor, or on it: never below.
        assert_eq!(first_root(1.0, 0.0, 0.0, 5.0), None);
        assert_eq!(first_root(0.0, 0.0, 0.0, 5.0), None);
        // Linear: falls to zero at 2.
        assert_eq!(first_root(2.0, -1.0, 0.0, 5.0), Some(2.0));
        assert_eq!(first_root(2.0, -1.0, 0.0, 1.5), None);
        // Touches zero at 1 (a double root) and at a vertex past the span.
        assert_eq!(first_root(1.0, -2.0, 1.0, 5.0), Some(1.0));
        assert_eq!(first_root(1.0, -2.0, 1.0, 0.5), None);
        // Concave from above zero: the larger root.
        let r = first_root(1.0, 0.0, -1.0, 5.0).unwrap();
        assert!((r - 1.0).abs() < 1e-15, "{r}");
        // No real roots.
        assert_eq!(first_root(1.0, 0.0, 1.0, 5.0), None);
    }

    #[test]
    fn a_nan_sample_proves_nothing() {
        let line = Line {
            start: DVec2::new(0.1, 0.1),
            step: DVec2::new(1.0, 0.0),
            inverse_step: DVec2::new(1.0, f64::INFINITY),
        };
        let samples = [5.0, f64::NAN, 5.0, 5.0];
        assert_eq!(
            first_below(samples, &line, [0.0, 0.0], 0.0..0.8, 1.0),
            Some(0.0)
        );
    }
}
