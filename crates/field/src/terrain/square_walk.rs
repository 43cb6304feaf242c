//! A ray's walk through a lattice of squares (the grid's cells, the halo's tiles): the
//! square it is in and how far along it it leaves it, square by square in the order it
//! crosses them.

use glam::{DVec2, Vec2};

/// `nx x ny` squares of side `size` from `origin`, whose sides lie where the lookups that
/// place points in them put them: at `origin + i * size`, computed in `f32`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lattice {
    pub(super) origin: Vec2,
    pub(super) size: f32,
    pub(super) nx: u32,
    pub(super) ny: u32,
}

/// The walk of the ray `p + d t` (in `f64`) through a [`Lattice`], from the square that
/// holds `p`.
pub(super) struct SquareWalk {
    x: Axis,
    y: Axis,
}

impl SquareWalk {
    /// Starts in square `(ix, iy)`, which holds `p`.
    #[inline]
    pub(super) fn new(lattice: Lattice, (ix, iy): (u32, u32), p: DVec2, d: DVec2) -> SquareWalk {
        let Lattice { origin, size, .. } = lattice;
        SquareWalk {
            x: Axis::new(ix, lattice.nx, origin.x, size, p.x, d.x),
            y: Axis::new(iy, lattice.ny, origin.y, size, p.y, d.y),
        }
    }

    /// The square the walk is in, as `(column, row)`.
    #[inline]
    pub(super) fn square(&self) -> (u32, u32) {
        (self.x.i, self.y.i)
    }

    /// Distance along the ray to where it leaves the square.
    #[inline]
    pub(super) fn exit(&self) -> f64 {
        self.x.exit.min(self.y.exit)
    }

    /// Moves into the next square the ray enters (through the side it reaches first, `x`
    /// on a tie); `false` past the lattice's edge.
    #[inline]
    pub(super) fn step(&mut self) -> bool {
        if self.x.exit <= self.y.exit {
            self.x.step()
        } else {
            self.y.step()
        }
    }
}

/// One axis of the walk: the column (or row) the ray is in, and where along the ray it
/// leaves it.
struct Axis {
    i: u32,
    count: u32,
    origin: f32,
    size: f32,
    p: f64,
    /// `1 / d`; the ray never leaves through this axis's sides when `d` is zero.
    inverse: f64,
    forward: bool,
    /// Distance along the ray to the far side of column `i`.
    exit: f64,
}

impl Axis {
    fn new(i: u32, count: u32, origin: f32, size: f32, p: f64, d: f64) -> Axis {
        let mut axis = Axis {
            i,
            count,
            origin,
            size,
            p,
            inverse: if d == 0.0 { 0.0 } else { 1.0 / d },
            forward: d > 0.0,
            exit: f64::INFINITY,
        };
        axis.exit = axis.far_side();
        axis
    }

    /// Distance along the ray to the far side of column `i` (infinite where the ray runs
    /// along the axis).
    #[inline]
    fn far_side(&self) -> f64 {
        if self.inverse == 0.0 {
            return f64::INFINITY;
        }
        let side = self.i + u32::from(self.forward);
        (f64::from(self.origin + side as f32 * self.size) - self.p) * self.inverse
    }

    /// Moves to the next column the ray enters; `false` past the lattice's edge.
    #[inline]
    fn step(&mut self) -> bool {
        match self.forward {
            true if self.i + 1 < self.count => self.i += 1,
            false if self.inverse != 0.0 && self.i > 0 => self.i -= 1,
            _ => return false,
        }
        self.exit = self.far_side();
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The walk visits the squares a dense sampling of the ray passes through, in order,
    /// and each exit lies where the next square begins.
    #[test]
    fn the_walk_visits_the_squares_the_ray_crosses() {
        let lattice = Lattice {
            origin: Vec2::new(-40.0, 8.0),
            size: 16.0,
            nx: 9,
            ny: 7,
        };
        let square_of = |q: DVec2| {
            let f = (q - lattice.origin.as_dvec2()) / f64::from(lattice.size);
            (f.x >= 0.0 && f.y >= 0.0 && f.x < 9.0 && f.y < 7.0)
                .then(|| (f.x.floor() as u32, f.y.floor() as u32))
        };
        let mut unit = crate::test_rng::unit_f64(7);
        for _ in 0..200 {
            let p = DVec2::new(-40.0 + 144.0 * unit(), 8.0 + 112.0 * unit());
            let angle = std::f64::consts::TAU * unit();
            let d = DVec2::new(angle.cos(), angle.sin());
            let start = square_of(p).expect("p is in the lattice");
            let mut walk = SquareWalk::new(lattice, start, p, d);
            let mut seen = vec![start];
            let mut exits = vec![walk.exit()];
            while walk.step() {
                seen.push(walk.square());
                exits.push(walk.exit());
            }
            // Dense samples between the exits fall in the square the walk was in.
            let mut from = 0.0;
            for (square, &exit) in seen.iter().zip(&exits) {
                let to = exit.min(400.0);
                for k in 1..64 {
                    let t = from + (to - from) * f64::from(k) / 64.0;
                    if let Some(found) = square_of(p + d * t) {
                        assert_eq!(found, *square, "p {p} d {d} t {t}");
                    }
                }
                from = exit;
            }
            assert!(exits.windows(2).all(|w| w[0] <= w[1]), "{exits:?}");
            let last = p + d * (exits.last().unwrap() + 1e-9);
            assert!(
                square_of(last).is_none(),
                "the walk ends where the ray leaves"
            );
        }
    }
}
