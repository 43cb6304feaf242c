//! What a game uses, in one import: `use craterfield::prelude::*;`.
//!
//! The level and its terrain, the events that change it, collision queries, the
//! deterministic world with its inputs and settings, replays and network messages, and (with
//! the default features) the renderers. Everything else is in the module that owns it.
//!
//! ```
//! use craterfield::prelude::*;
//!
//! let level = Level::default_level();
//! let bounds = level.bounds();
//! let mut terrain =
//!     Terrain::new(level.graph().clone(), bounds.min, bounds.max, level.terrain_options())?;
//! let from_the_sky = Vec2::new(1000.0, 1590.0);
//! let hit = raycast(&terrain, from_the_sky, Vec2::NEG_Y, 2000.0, &RayOptions::default())?
//!     .expect("the ray meets the ground");
//! terrain.apply(Event::carve(hit.point, 40.0)?)?;
//! assert!(terrain.distance(hit.point) > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub use glam::Vec2;

pub use craterfield_field::query::{
    CapsuleOptions, ClosestOptions, Contact, QueryError, RayHit, RayOptions, SurfacePoint,
    SweepHit, closest_point, contact_capsule, contact_circle, raycast, sweep_circle,
};
pub use craterfield_field::{
    Aabb, Event, EventError, EventKind, Level, LevelError, MaterialId, Sample, Sdf, Terrain,
    TerrainError, TerrainOptions,
};
pub use craterfield_net::{
    DecodeError, Recorder, Replay, TerrainSnapshot, decode_events, encode_events,
};
pub use craterfield_sim::{Input, Settings, SimError, Snapshot, World, WorldState, buttons};

#[cfg(feature = "raster")]
pub use craterfield_render2d::{Camera, Reconstruction, RenderOptions, render_exact, render_twin};

#[cfg(feature = "gpu")]
pub use craterfield_gpu::{GpuContext, GpuError};
#[cfg(feature = "gpu")]
pub use craterfield_render2d::gpu::{RenderError, TerrainRenderer};
