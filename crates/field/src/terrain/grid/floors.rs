//! Block floors of a brick: its lattice cut into at most 8x8 blocks, each with a value no
//! larger than the brick's bilinear interpolation anywhere on the block, so that a ray can
//! cross a brick's air a block at a time without reading its samples.
//!
//! A bilinear interpolation on one lattice square lies between the square's smallest and
//! largest corner, up to the rounding of its three operations; a block's floor is its
//! smallest sample less an allowance for that rounding. Floors are a function of the
//! samples alone (computed when a ray first asks, see `Brick::floors`), so they are the
//! same bits wherever the brick came from (a bake, a rollback, a restored state).

use glam::Vec2;

/// Blocks per side of a brick, at most.
const BLOCKS: usize = 8;

/// The floors of one brick's blocks, row-major (y outer), `side x side` of them.
#[derive(Clone, Debug)]
pub(crate) struct BlockFloors {
    floors: [f32; BLOCKS * BLOCKS],
    /// The least floor of each row of blocks (NaN where one is): a ray's piece over a
    /// brick's air spans rows whose every block clears it, decided one row at a time.
    row_floors: [f32; BLOCKS],
    /// Lattice squares per block side (the last block of a row may have fewer).
    squares: u32,
    /// Blocks per side.
    side: u32,
}

impl Default for BlockFloors {
    /// Floors of no brick: nothing is proven.
    fn default() -> Self {
        BlockFloors {
            floors: [f32::NEG_INFINITY; BLOCKS * BLOCKS],
            row_floors: [f32::NEG_INFINITY; BLOCKS],
            squares: 1,
            side: 1,
        }
    }
}

impl BlockFloors {
    /// The floors of the `(n + 1) x (n + 1)` samples `values` (row-major). Fewer samples
    /// than that (a brick not fully baked) prove nothing.
    pub(crate) fn of(values: &[f32], n: u32) -> BlockFloors {
        let row = n as usize + 1;
        if n == 0 || values.len() != row * row {
            return BlockFloors::default();
        }
        let squares = n.div_ceil(BLOCKS as u32);
        let side = n.div_ceil(squares);
        let mut out = BlockFloors {
            floors: [f32::INFINITY; BLOCKS * BLOCKS],
            row_floors: [f32::INFINITY; BLOCKS],
            squares,
            side,
        };
        let (side_us, squares_us) = (side as usize, squares as usize);
        let mut largest = [0.0f32; BLOCKS * BLOCKS];
        let mut nan = [false; BLOCKS * BLOCKS];
        for (j, samples) in values.chunks_exact(row).enumerate() {
            // This row's least and largest sample on each block's span of columns (a
            // sample on a block's edge belongs to both blocks it bounds)...
            let (mut lo, mut big, mut bad) =
                ([f32::INFINITY; BLOCKS], [0.0f32; BLOCKS], [false; BLOCKS]);
            for k in 0..side_us {
                let span = k * squares_us..=((k + 1) * squares_us).min(n as usize);
                for &v in &samples[span] {
                    lo[k] = if v < lo[k] { v } else { lo[k] };
                    big[k] = big[k].max(v.abs());
                    bad[k] |= v.is_nan();
                }
            }
            // ...folded into the one or two rows of blocks the row bounds.
            for kj in out.blocks_of(j as u32) {
                let at = kj as usize * side_us;
                for k in 0..side_us {
                    out.floors[at + k] = out.floors[at + k].min(lo[k]);
                    largest[at + k] = largest[at + k].max(big[k]);
                    nan[at + k] |= bad[k];
                }
            }
        }
        for k in 0..side_us * side_us {
            // Each of the interpolation's roundings is within half an ulp of a value at
            // most twice the largest corner; 2^-18 of it is many times their sum. A NaN
            // sample proves nothing.
            out.floors[k] = match nan[k] {
                true => f32::NAN,
                false => out.floors[k] - largest[k] * (1.0 / 262_144.0),
            };
            // NaN wins: a row with a NaN floor proves nothing at once.
            let row = &mut out.row_floors[k / side_us];
            *row = if out.floors[k] < *row || out.floors[k].is_nan() {
                out.floors[k]
            } else {
                *row
            };
        }
        out
    }

    /// The blocks whose edges or inside hold lattice line `i` (one, or two on an edge).
    fn blocks_of(&self, i: u32) -> std::ops::RangeInclusive<u32> {
        let last = self.side - 1;
        let lo = (i.saturating_sub(1) / self.squares).min(last);
        let hi = (i / self.squares).min(last);
        lo..=hi
    }

    /// Lattice squares per block side.
    #[cfg(test)]
    fn squares(&self) -> u32 {
        self.squares
    }

    /// The floors laid over the brick of the cell with corner `corner` and lattice
    /// spacing `spacing`.
    pub(crate) fn over(&self, corner: Vec2, spacing: f32) -> FloorGrid<'_> {
        let side = self.side as usize;
        FloorGrid {
            corner,
            block: f64::from(spacing) * f64::from(self.squares),
            side: self.side,
            floors: &self.floors[..side * side],
            row_floors: &self.row_floors[..side],
        }
    }
}

/// A brick's floors laid over its cell: what a ray's walk reads of them (the blocks'
/// corner, size and floors), in world units.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FloorGrid<'a> {
    /// The grid's lower-left corner.
    pub corner: Vec2,
    /// The side of one square, in world units.
    pub block: f64,
    /// Squares per side.
    pub side: u32,
    /// The floors, row-major (y outer), `side * side` of them.
    pub floors: &'a [f32],
    /// The least floor of each row (`side` of them).
    pub row_floors: &'a [f32],
}

impl FloorGrid<'_> {
    /// Whether the squares `ki0..=ki1` by `kj0..=kj1` all have their floor at least
    /// `above`.
    #[inline]
    pub(crate) fn at_least(
        &self,
        (ki0, ki1): (u32, u32),
        (kj0, kj1): (u32, u32),
        above: f32,
    ) -> bool {
        let side = self.side as usize;
        if ki0 == ki1 && kj0 == kj1 {
            let k = kj0 as usize * side + ki0 as usize;
            return self.floors.get(k).is_some_and(|&f| f >= above);
        }
        let columns = ki0 as usize..=ki1 as usize;
        (kj0 as usize..=kj1 as usize).all(|kj| {
            if self.row_floors.get(kj).is_some_and(|&f| f >= above) {
                return true;
            }
            let row = self.floors.get(kj * side..(kj + 1) * side);
            row.and_then(|r| r.get(columns.clone()))
                .is_some_and(|r| r.iter().all(|&f| f >= above))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bilinear interpolation as the grid computes it, for the floors to bound.
    fn interpolate(values: &[f32], n: u32, u: f32, v: f32) -> f32 {
        let row = (n + 1) as usize;
        let (i, j) = ((u as u32).min(n - 1), (v as u32).min(n - 1));
        let (fu, fv) = (u - i as f32, v - j as f32);
        let at = |i: u32, j: u32| values[j as usize * row + i as usize];
        let bottom = fu * (at(i + 1, j) - at(i, j)) + at(i, j);
        let top = fu * (at(i + 1, j + 1) - at(i, j + 1)) + at(i, j + 1);
        (top - bottom) * fv + bottom
    }

    #[test]
    fn floors_bound_the_interpolation_on_every_block() {
        let mut unit = crate::test_rng::unit_f64(7);
        for n in [1u32, 3, 8, 9, 32, 33] {
            let row = (n + 1) as usize;
            let values: Vec<f32> = (0..row * row)
                .map(|_| (unit() * 64.0 - 32.0) as f32)
                .collect();
            let f = BlockFloors::of(&values, n);
            assert!(f.side as usize <= BLOCKS && f.side * f.squares() >= n);
            for _ in 0..4000 {
                let (u, v) = (
                    (unit() * f64::from(n)) as f32,
                    (unit() * f64::from(n)) as f32,
                );
                let d = interpolate(&values, n, u, v);
                let (i, j) = ((u as u32).min(n - 1), (v as u32).min(n - 1));
                // The block that holds the square read bounds the value from below...
                let k = ((j / f.squares()) * f.side + i / f.squares()) as usize;
                assert!(f.floors[k] <= d, "n {n} at {u},{v}: {} > {d}", f.floors[k]);
                // ...so a threshold above the value is never proven there.
                let (ki, kj) = (i / f.squares(), j / f.squares());
                assert!(
                    !f.over(Vec2::ZERO, 1.0)
                        .at_least((ki, ki), (kj, kj), d.next_up()),
                    "n {n} at {u},{v}"
                );
            }
            // And each floor is its block's smallest sample, less a small allowance.
            for kj in 0..f.side {
                for ki in 0..f.side {
                    let points = |k: u32| k * f.squares()..=((k + 1) * f.squares()).min(n);
                    let least = points(kj)
                        .flat_map(|j| points(ki).map(move |i| (i, j)))
                        .map(|(i, j)| values[j as usize * row + i as usize])
                        .fold(f32::INFINITY, f32::min);
                    let floor = f.floors[(kj * f.side + ki) as usize];
                    assert!(floor <= least && floor > least - 1e-3, "{floor} {least}");
                }
            }
        }
    }

    /// A rectangle of blocks is proven exactly when each of its floors is at least the
    /// threshold, whether its rows are decided by their least floor or block by block.
    #[test]
    fn a_rectangle_is_proven_when_every_floor_in_it_is() {
        let mut unit = crate::test_rng::unit_f64(11);
        for n in [8u32, 32, 33] {
            let row = (n + 1) as usize;
            for _ in 0..200 {
                // Bricks with air above a surface, as a ray's pieces meet them.
                let slope = unit() * 4.0;
                let values: Vec<f32> = (0..row * row)
                    .map(|k| ((k / row) as f64 * slope - 20.0 + unit() * 6.0) as f32)
                    .collect();
                let f = BlockFloors::of(&values, n);
                let grid = f.over(Vec2::ZERO, 1.0);
                for _ in 0..50 {
                    let [a, b, c, d] = [0; 4].map(|_| (unit() * f64::from(f.side)) as u32);
                    let (is, js) = ((a.min(b), a.max(b)), (c.min(d), c.max(d)));
                    let above = (unit() * 80.0 - 30.0) as f32;
                    let every = (js.0..=js.1).all(|kj| {
                        (is.0..=is.1).all(|ki| f.floors[(kj * f.side + ki) as usize] >= above)
                    });
                    assert_eq!(grid.at_least(is, js, above), every, "{is:?} {js:?} {above}");
                }
            }
        }
    }

    #[test]
    fn a_nan_sample_or_a_short_brick_proves_nothing() {
        let mut values = vec![5.0f32; 9 * 9];
        assert!(
            BlockFloors::of(&values, 8)
                .over(Vec2::ZERO, 1.0)
                .at_least((0, 7), (0, 7), 4.0)
        );
        // Sample (4, 4) is a corner of blocks 3 and 4 on each axis.
        values[40] = f32::NAN;
        let f = BlockFloors::of(&values, 8);
        assert!(!f.over(Vec2::ZERO, 1.0).at_least((3, 3), (3, 3), -100.0));
        assert!(!f.over(Vec2::ZERO, 1.0).at_least((4, 4), (4, 4), -100.0));
        assert!(
            f.over(Vec2::ZERO, 1.0).at_least((0, 2), (0, 2), 4.0),
            "blocks away from the NaN still prove"
        );
        assert!(
            !BlockFloors::of(&values[..80], 8)
                .over(Vec2::ZERO, 1.0)
                .at_least((0, 0), (0, 0), -100.0)
        );
    }
}
