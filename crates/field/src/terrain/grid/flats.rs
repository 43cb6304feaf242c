//! Per cell, the squares of an [`FLAT_SIDE`] by [`FLAT_SIDE`] split where the whole field
//! (state and list) is proven to be the band's top or bottom, laid out densely: a point
//! query in such a square reads twenty bytes instead of the cell, its state, its list and
//! its base tape. After a barrage most of a level is deep air or deep ground, so most
//! queries land in one.
//!
//! The terrain computes a cell's squares when a query first asks (it needs the cell's
//! base tape, which the grid does not hold), and the grid forgets them with the cell's
//! ray bound ([`super::CellLows`]), on every path that changes a cell. They are a function
//! of the cell's state, its list and the base alone, so whenever and on whichever thread
//! they are computed they are the same bits.

use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};

use crate::sample::MaterialId;

/// Squares per cell side: 64 squares, one bit each of a `u64`.
pub(crate) const FLAT_SIDE: u32 = 8;

/// Every square of a cell.
pub(crate) const ALL_SQUARES: u64 = u64::MAX;

/// The squares of one cell where the field is the band's constant, and the material the
/// cell's state has everywhere, if it is one material.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Flats {
    /// Bit `j * FLAT_SIDE + i`: the field is `+band` over square `(i, j)`.
    pub(crate) top: u64,
    /// The same, `-band`. Never sharing a bit with `top`.
    pub(crate) bottom: u64,
    /// The material of every point of the cell's flat squares, where the state has one.
    pub(crate) material: Option<MaterialId>,
}

/// A material word: the material in the low 16 bits, bit 16 set where there is one.
const HAS_MATERIAL: u32 = 1 << 16;

/// One cell's slot. "Not computed" is `top` and `bottom` both full: no proof gives that.
#[derive(Debug)]
struct Slot {
    top: AtomicU64,
    bottom: AtomicU64,
    material: AtomicU32,
}

impl Slot {
    fn unknown() -> Slot {
        Slot {
            top: AtomicU64::new(ALL_SQUARES),
            bottom: AtomicU64::new(ALL_SQUARES),
            material: AtomicU32::new(0),
        }
    }

    fn forget(&mut self) {
        *self.top.get_mut() = ALL_SQUARES;
        *self.bottom.get_mut() = ALL_SQUARES;
        *self.material.get_mut() = 0;
    }
}

/// Every cell's flat squares, each unknown until asked.
#[derive(Debug, Default)]
pub(crate) struct CellFlats(Vec<Slot>);

impl Clone for CellFlats {
    /// A clone holds the same cells, so the same squares.
    fn clone(&self) -> Self {
        CellFlats(
            self.0
                .iter()
                .map(|s| Slot {
                    top: AtomicU64::new(s.top.load(Ordering::Acquire)),
                    bottom: AtomicU64::new(s.bottom.load(Ordering::Relaxed)),
                    material: AtomicU32::new(s.material.load(Ordering::Relaxed)),
                })
                .collect(),
        )
    }
}

impl CellFlats {
    /// `cells` cells, none computed.
    pub(crate) fn new(cells: usize) -> CellFlats {
        CellFlats((0..cells).map(|_| Slot::unknown()).collect())
    }

    /// Cell `cell`'s squares, or `None` when they are not computed yet (or past the end).
    #[inline]
    pub(crate) fn get(&self, cell: usize) -> Option<Flats> {
        let slot = self.0.get(cell)?;
        // `top` is written last, with release: a `top` of this computation brings its
        // `bottom` and material along.
        let top = slot.top.load(Ordering::Acquire);
        let bottom = slot.bottom.load(Ordering::Relaxed);
        if top & bottom != 0 {
            return None;
        }
        let m = slot.material.load(Ordering::Relaxed);
        Some(Flats {
            top,
            bottom,
            material: (m & HAS_MATERIAL != 0).then_some(m as MaterialId),
        })
    }

    /// Keeps `flats` as cell `cell`'s squares (squares claimed both ways are dropped).
    pub(crate) fn set(&self, cell: usize, flats: Flats) {
        let Some(slot) = self.0.get(cell) else {
            return;
        };
        let both = flats.top & flats.bottom;
        let m = flats.material.map_or(0, |m| HAS_MATERIAL | u32::from(m));
        slot.material.store(m, Ordering::Relaxed);
        slot.bottom.store(flats.bottom & !both, Ordering::Relaxed);
        slot.top.store(flats.top & !both, Ordering::Release);
    }

    /// Forgets cell `cell`'s squares (its cell is about to change).
    pub(crate) fn forget(&mut self, cell: usize) {
        if let Some(slot) = self.0.get_mut(cell) {
            slot.forget();
        }
    }

    /// Forgets every cell's squares.
    pub(crate) fn forget_all(&mut self) {
        for slot in &mut self.0 {
            slot.forget();
        }
    }
}

/// The bit of square `(i, j)`.
#[inline]
pub(crate) fn square_bit(i: u32, j: u32) -> u64 {
    1u64 << (j * FLAT_SIDE + i)
}

/// The lattice indices a point of square `s` (of [`FLAT_SIDE`]) may interpolate between,
/// on a brick of resolution `n`: the square's own, one more on each side for the
/// rounding of the point's coordinates, within `0..=n`.
fn lattice_span(s: u32, n: u32) -> std::ops::RangeInclusive<usize> {
    let lo = (s * n / FLAT_SIDE).saturating_sub(1);
    let hi = ((s + 1) * n).div_ceil(FLAT_SIDE) + 1;
    lo as usize..=hi.min(n) as usize
}

/// A brick's flat squares: those whose samples ([`lattice_span`] in both directions) are
/// all `band`, or all `-band`, where the bilinear interpolation gives that constant
/// exactly (with a zero gradient); and the material of every sample, if it is one.
pub(crate) fn brick_flats(values: &[f32], materials: &[MaterialId], n: u32, band: f32) -> Flats {
    let side = n as usize + 1;
    if values.len() != side * side {
        return Flats::default();
    }
    let (top_bits, bottom_bits) = (band.to_bits(), (-band).to_bits());
    // Per lattice row, per column of squares: whether the row's samples in the square's
    // span are all the top, all the bottom.
    let mut row_flags = vec![[(false, false); FLAT_SIDE as usize]; side];
    for (j, flags) in row_flags.iter_mut().enumerate() {
        let row = &values[j * side..(j + 1) * side];
        for (i, f) in flags.iter_mut().enumerate() {
            let span = &row[lattice_span(i as u32, n)];
            *f = (
                span.iter().all(|v| v.to_bits() == top_bits),
                span.iter().all(|v| v.to_bits() == bottom_bits),
            );
        }
    }
    let mut flats = Flats::default();
    for sj in 0..FLAT_SIDE {
        for si in 0..FLAT_SIDE {
            let rows = &row_flags[lattice_span(sj, n)];
            let bit = square_bit(si, sj);
            if rows.iter().all(|f| f[si as usize].0) {
                flats.top |= bit;
            } else if rows.iter().all(|f| f[si as usize].1) {
                flats.bottom |= bit;
            }
        }
    }
    flats.material = match materials.split_first() {
        Some((&m, rest)) if rest.iter().all(|&x| x == m) => Some(m),
        _ => None,
    };
    flats
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn squares_are_kept_until_forgotten() {
        let mut flats = CellFlats::new(3);
        assert_eq!(flats.get(1), None);
        let f = Flats {
            top: 0b1010,
            bottom: 0b0100,
            material: Some(7),
        };
        flats.set(1, f);
        flats.set(2, Flats::default());
        assert_eq!(flats.get(1), Some(f));
        assert_eq!(flats.get(2), Some(Flats::default()));
        let copy = flats.clone();
        flats.forget(1);
        assert_eq!(flats.get(1), None);
        assert_eq!(copy.get(1), Some(f));
        // A square claimed both ways is neither.
        flats.set(
            0,
            Flats {
                top: 0b11,
                bottom: 0b10,
                material: None,
            },
        );
        assert_eq!(
            flats.get(0),
            Some(Flats {
                top: 0b01,
                bottom: 0,
                material: None
            })
        );
        flats.forget_all();
        assert_eq!(flats.get(2), None);
        assert_eq!(flats.get(7), None);
    }
}
