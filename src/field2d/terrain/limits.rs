//! The hard limits every terrain is checked against, whatever its options.

/// Largest accepted world coordinate magnitude (bounds, and so event centres).
pub const MAX_COORD: f32 = 65536.0;

/// Most memory the bricks of one terrain may ever take (every cell baked): the grid size
/// and brick resolution are checked against it up front, so memory stays bounded whatever
/// the events.
pub const MAX_BRICK_BYTES: u64 = 1 << 30;
