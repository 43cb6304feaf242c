//! A terrain's tuning and limits, and the one check that bounds what a terrain may cost
//! before anything is allocated.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use super::error::TerrainError;
use super::grid::Grid;
use super::limits::{MAX_BRICK_BYTES, MAX_COORD};

/// Tuning and limits of a [`Terrain`](super::Terrain).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TerrainOptions {
    /// Side of a grid cell, world units.
    pub cell_size: f32,
    /// The band `M`: distances are clamped to `[-M, M]`.
    pub band: f32,
    /// Longest event list a cell keeps before baking a brick. A list past it is baked at
    /// the following tick advances ([`Terrain::set_tick`](super::Terrain::set_tick)),
    /// [`TerrainOptions::bake_rows_per_tick`] lattice rows per advance, cells in cell
    /// order; only a list that reaches twice the cap (or `max_cell_events`) bakes whole as
    /// its event is applied.
    pub cell_cap: usize,
    /// Brick lattice rows baked per tick advance (a brick has `brick_resolution + 1`), so
    /// that one tick's cost stays bounded whatever the bricks cost: a bake spreads over
    /// several ticks, and lists wait their turn (their queries stay exact meanwhile). As
    /// many again for every 4 lists waiting past the cap, so that a flood of explosions
    /// does not pile them up.
    #[serde(default = "default_bake_rows_per_tick")]
    pub bake_rows_per_tick: usize,
    /// Longest event list a cell may hold at all. Lists past `cell_cap` bake their settled
    /// prefix, but a growing or not-yet-started event stops the prefix, and every event
    /// after it waits too; an event that would make a list longer than this is refused
    /// ([`TerrainError::CellFull`]), so one cell's queries stay bounded (100,000 growing
    /// events in one cell made a distance query take 254 us for 65,536 ticks).
    #[serde(default = "default_max_cell_events")]
    pub max_cell_events: usize,
    /// Brick lattice intervals per cell side.
    pub brick_resolution: u32,
    /// Largest accepted event radius, world units.
    pub max_event_radius: f32,
    /// Largest accepted rim (blend width), world units.
    pub max_rim: f32,
    /// Events the log holds before it is compacted (events no cell can reach any more
    /// are dropped; see [`Terrain::compact_history`](super::Terrain::compact_history)).
    /// The log reserves room for this many (up to 2^20) when the terrain is made, so that
    /// no event pays for growing it.
    /// Not a limit on a match's length: a terrain accepts events for as long as cells
    /// take them.
    pub max_events: usize,
    /// Fills must use a material below this.
    pub material_count: u16,
}

impl Default for TerrainOptions {
    fn default() -> Self {
        TerrainOptions {
            cell_size: 64.0,
            band: 32.0,
            cell_cap: 48,
            bake_rows_per_tick: default_bake_rows_per_tick(),
            max_cell_events: default_max_cell_events(),
            brick_resolution: 32,
            max_event_radius: 512.0,
            max_rim: 64.0,
            max_events: 1_000_000,
            material_count: 256,
        }
    }
}

fn default_max_cell_events() -> usize {
    256
}

fn default_bake_rows_per_tick() -> usize {
    7
}

fn check_positive(name: &'static str, value: f32, limit: f32) -> Result<(), TerrainError> {
    if value.is_finite() && value > 0.0 && value <= limit {
        Ok(())
    } else {
        Err(TerrainError::BadOption {
            name,
            value: value.to_string(),
            reason: "must be positive, finite and <= 65536",
        })
    }
}

impl TerrainOptions {
    /// Checks these options for a world `[bounds_min, bounds_max]` without allocating: the
    /// values' ranges, the grid's cell count and the most memory its bricks could take.
    /// Returns the rectangle the explosion grid covers (the bounds grown by the farthest
    /// reach of an event).
    pub fn check(&self, bounds_min: Vec2, bounds_max: Vec2) -> Result<(Vec2, Vec2), TerrainError> {
        for (name, value) in [
            ("min.x", bounds_min.x),
            ("min.y", bounds_min.y),
            ("max.x", bounds_max.x),
            ("max.y", bounds_max.y),
        ] {
            if !(value.is_finite() && value.abs() <= MAX_COORD) {
                return Err(TerrainError::BadBound { name, value });
            }
        }
        if !(bounds_min.x < bounds_max.x && bounds_min.y < bounds_max.y) {
            return Err(TerrainError::EmptyBounds {
                min: bounds_min,
                max: bounds_max,
            });
        }
        check_positive("cell_size", self.cell_size, MAX_COORD)?;
        check_positive("band", self.band, MAX_COORD)?;
        check_positive("max_event_radius", self.max_event_radius, MAX_COORD)?;
        if !(self.max_rim.is_finite() && self.max_rim >= 0.0 && self.max_rim <= MAX_COORD) {
            return Err(TerrainError::BadOption {
                name: "max_rim",
                value: self.max_rim.to_string(),
                reason: "must be finite, >= 0 and <= 65536",
            });
        }
        if self.cell_cap == 0 {
            return Err(TerrainError::BadOption {
                name: "cell_cap",
                value: "0".into(),
                reason: "must be at least 1",
            });
        }
        if self.bake_rows_per_tick == 0 {
            return Err(TerrainError::BadOption {
                name: "bake_rows_per_tick",
                value: "0".into(),
                reason: "must be at least 1",
            });
        }
        if self.max_cell_events < self.cell_cap {
            return Err(TerrainError::BadOption {
                name: "max_cell_events",
                value: self.max_cell_events.to_string(),
                reason: "must be at least cell_cap",
            });
        }
        if self.max_events == 0 || self.max_events > u32::MAX as usize {
            return Err(TerrainError::BadOption {
                name: "max_events",
                value: self.max_events.to_string(),
                reason: "must be in 1..=4294967295",
            });
        }
        if self.material_count == 0 {
            return Err(TerrainError::BadOption {
                name: "material_count",
                value: "0".into(),
                reason: "must be at least 1",
            });
        }
        let grow = self.max_event_radius + self.max_rim + self.band + 1.0;
        let (min, max) = (
            bounds_min - Vec2::splat(grow),
            bounds_max + Vec2::splat(grow),
        );
        let (nx, ny) = Grid::dims_for(min, max, self.cell_size, self.brick_resolution)?;
        let side = self.brick_resolution as u64 + 1;
        // f32 value + u16 material per lattice point.
        let worst = nx as u64 * ny as u64 * side * side * 6;
        if worst > MAX_BRICK_BYTES {
            return Err(TerrainError::BadOption {
                name: "brick_resolution",
                value: format!(
                    "{} ({nx}x{ny} cells could take {worst} bytes of bricks)",
                    self.brick_resolution
                ),
                reason: "cells x (resolution + 1)^2 x 6 bytes must stay within 1 GiB: lower the resolution or raise cell_size",
            });
        }
        Ok((min, max))
    }
}
