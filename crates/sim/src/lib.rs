//! Deterministic physics on the terrain field: vehicles, projectiles and debris, explosions
//! that carve and fill, snapshots for rollback and a per-tick state hash.
//!
//! Every peer of a match steps its own [`World`] with the same [`Input`]s and gets the same
//! bits (the determinism contract of `docs/ARCHITECTURE.md`): the world uses only exactly
//! rounded `f32` operations in a fixed order, its settings and inputs are integers, its terrain events are
//! fixed point, and every field query goes through the terrain's batch evaluator, whose
//! backends all agree bit for bit. [`World::state_hash`] summarises a tick in 64 bits for
//! desync checks; [`World::snapshot`] and [`World::restore`] cost O(bodies + terrain changes
//! since the snapshot), never O(terrain). [`World::state`] and [`World::resync`] move a
//! whole world, terrain grid included, to a peer that must continue from it (a desync).

#![forbid(unsafe_code)]

pub(crate) mod body;
pub(crate) mod collide;
pub(crate) mod contact;
pub(crate) mod hash;
pub(crate) mod input;
pub mod projectile;
pub(crate) mod settings;
pub(crate) mod state;
pub(crate) mod world;

pub use body::{Body, BodyKind};
pub use hash::{StateHasher, level_hash};
pub use input::{Input, InputError, buttons};
pub use settings::{Settings, SettingsError, VehicleSettings, WeaponSettings, units};
pub use state::WorldState;
pub use world::{EVENT_CENTER_STEP, MAX_PLAYERS, SimError, Snapshot, World};
