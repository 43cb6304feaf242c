//! Per cell, a lower bound of its field over the whole cell, laid out densely for ray
//! walks: a ray crossing open air reads four bytes a cell instead of the cell, its state
//! and its base tape.
//!
//! The terrain computes a cell's bound when a walk first asks (it needs the cell's base
//! tape, which the grid does not hold), and the grid forgets it whenever it hands the cell
//! out for an edit, restores it, or replaces the cells: every path that changes a cell goes
//! through those. A bound is a function of the cell's state, its list and the base alone,
//! so whenever and on whichever thread it is computed it is the same bits.

use std::sync::atomic::{AtomicU32, Ordering};

/// Bits that no bound takes: a NaN ("not computed yet").
const UNKNOWN: u32 = u32::MAX;

/// One bound per cell, each `UNKNOWN` until asked.
#[derive(Debug, Default)]
pub(crate) struct CellLows(Vec<AtomicU32>);

impl Clone for CellLows {
    /// A clone holds the same cells, so the same bounds.
    fn clone(&self) -> Self {
        CellLows(
            self.0
                .iter()
                .map(|b| AtomicU32::new(b.load(Ordering::Relaxed)))
                .collect(),
        )
    }
}

impl CellLows {
    /// `cells` unknown bounds.
    pub(crate) fn new(cells: usize) -> CellLows {
        CellLows((0..cells).map(|_| AtomicU32::new(UNKNOWN)).collect())
    }

    /// Cell `cell`'s bound, or `None` when it is not computed yet (or past the end).
    #[inline]
    pub(crate) fn get(&self, cell: usize) -> Option<f32> {
        let bits = self.0.get(cell)?.load(Ordering::Relaxed);
        (bits != UNKNOWN).then_some(f32::from_bits(bits))
    }

    /// Keeps `low` as cell `cell`'s bound (a NaN is kept as unknown).
    pub(crate) fn set(&self, cell: usize, low: f32) {
        if let Some(slot) = self.0.get(cell) {
            let bits = if low.is_nan() { UNKNOWN } else { low.to_bits() };
            slot.store(bits, Ordering::Relaxed);
        }
    }

    /// Forgets cell `cell`'s bound (its cell is about to change).
    pub(crate) fn forget(&mut self, cell: usize) {
        if let Some(slot) = self.0.get_mut(cell) {
            *slot.get_mut() = UNKNOWN;
        }
    }

    /// Forgets every bound.
    pub(crate) fn forget_all(&mut self) {
        for slot in &mut self.0 {
            *slot.get_mut() = UNKNOWN;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_kept_until_forgotten() {
        let mut lows = CellLows::new(3);
        assert_eq!(lows.get(1), None);
        lows.set(1, -0.0);
        lows.set(2, f32::NEG_INFINITY);
        assert_eq!(lows.get(1).map(f32::to_bits), Some((-0.0f32).to_bits()));
        assert_eq!(lows.get(2), Some(f32::NEG_INFINITY));
        let copy = lows.clone();
        lows.forget(1);
        assert_eq!(lows.get(1), None);
        assert_eq!(copy.get(1).map(f32::to_bits), Some((-0.0f32).to_bits()));
        lows.set(0, f32::NAN);
        assert_eq!(lows.get(0), None);
        lows.forget_all();
        assert_eq!(lows.get(2), None);
        assert_eq!(lows.get(7), None);
    }
}
