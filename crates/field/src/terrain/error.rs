//! Why a terrain could not be built or an event not applied.

use glam::Vec2;
use thiserror::Error;

use super::grid::GridError;
use super::limits::MAX_COORD;
use crate::event::EventError;
use crate::sample::MaterialId;

/// Why a terrain could not be built or an event not applied.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum TerrainError {
    /// A bound is NaN, infinite or beyond [`MAX_COORD`].
    #[error("terrain bound {name} = {value} must be finite with magnitude <= {MAX_COORD}")]
    BadBound {
        /// Which bound (`min.x`, ...).
        name: &'static str,
        /// The offending value.
        value: f32,
    },
    /// `bounds_min` is not below `bounds_max` on some axis.
    #[error("terrain bounds are empty: min {min} must be below max {max} on both axes")]
    EmptyBounds {
        /// Lower corner.
        min: Vec2,
        /// Upper corner.
        max: Vec2,
    },
    /// An option is out of its accepted range.
    #[error("terrain option {name} = {value} is invalid: {reason}")]
    BadOption {
        /// The option.
        name: &'static str,
        /// Its value, formatted.
        value: String,
        /// What is required.
        reason: &'static str,
    },
    /// The grid could not be built.
    #[error("terrain grid: {0}")]
    Grid(#[from] GridError),
    /// The event is malformed.
    #[error("invalid event: {0}")]
    Event(#[from] EventError),
    /// The event radius exceeds `max_event_radius`.
    #[error("event radius {radius} exceeds max_event_radius {max}")]
    RadiusTooLarge {
        /// The radius.
        radius: f32,
        /// The limit.
        max: f32,
    },
    /// The event rim exceeds `max_rim`.
    #[error("event rim {rim} exceeds max_rim {max}")]
    RimTooLarge {
        /// The rim.
        rim: f32,
        /// The limit.
        max: f32,
    },
    /// The event centre lies outside the terrain bounds.
    #[error("event center {center} lies outside the terrain bounds {min} .. {max}")]
    CenterOutOfBounds {
        /// The centre.
        center: Vec2,
        /// Lower bound.
        min: Vec2,
        /// Upper bound.
        max: Vec2,
    },
    /// A fill uses a material beyond `material_count`.
    #[error("fill material {material} is out of range (material_count is {count})")]
    BadMaterial {
        /// The material.
        material: MaterialId,
        /// The number of materials.
        count: u16,
    },
    /// A cell the event reaches already holds `max_cell_events` events that cannot be
    /// baked yet (a growing or not-yet-started event is among them).
    #[error(
        "the explosion-grid cell around {at} already holds {max} events waiting for growing events to settle (max_cell_events)"
    )]
    CellFull {
        /// The centre of the full cell, world units.
        at: glam::Vec2,
        /// The limit.
        max: usize,
    },
    /// The log still holds `u32::MAX` events after compaction (cell lists index it with
    /// `u32`): every one of them still reaches some cell.
    #[error("the event log holds {kept} events that all still reach a cell; no more fit")]
    LogFull {
        /// Events kept.
        kept: usize,
    },
    /// A [`TerrainState`](super::TerrainState) does not fit this terrain (it was taken
    /// from another level or options, or it was altered).
    #[error("terrain state: {detail}")]
    BadState {
        /// What does not fit, and where.
        detail: String,
    },
    /// Moving the tick backwards needs the whole event history, and compaction dropped
    /// part of it.
    #[error(
        "cannot move the tick back from {current} to {tick}: compaction dropped {forgotten} events a rebuild would need (roll back to a mark instead)"
    )]
    HistoryCompacted {
        /// The tick asked for.
        tick: u32,
        /// The terrain's tick.
        current: u32,
        /// Events compaction dropped.
        forgotten: u64,
    },
}
