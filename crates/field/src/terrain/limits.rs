//! The hard limits every terrain is checked against, whatever its options.

/// Largest accepted world coordinate magnitude (bounds, and so event centres).
pub const MAX_COORD: f32 = 65536.0;

/// Most memory the specialized tapes of one terrain's cells may take. Cells that
/// specialize alike share one copy; once the budget is spent the remaining cells use the
/// whole program (the same bits, only slower), so a level whose tapes do not shrink per
/// cell costs one tape, not one per touched cell (590 KB each, 80 GB for one such level).
pub const MAX_CELL_TAPE_BYTES: usize = 64 << 20;

/// Most memory the bricks of one terrain may ever take (every cell baked): the grid size
/// and brick resolution are checked against it up front, so memory stays bounded whatever
/// the events.
pub const MAX_BRICK_BYTES: u64 = 1 << 30;
