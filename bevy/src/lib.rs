//! craterfield in Bevy: destructible terrain on signed distance fields, added to a game in
//! one line.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use craterfield_bevy::prelude::*;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, CraterfieldPlugin))
//!     .run();
//! ```
//!
//! [`CraterfieldPlugin`] brings:
//! - **levels as assets** ([`LevelAsset`], loaded from `.ron` files; a level the library
//!   refuses fails to load with the node path and the reason);
//! - **the deterministic world on the fixed tick**: the [`Craterfield`] resource holds the
//!   library's `sim::World`, stepped each `FixedUpdate` (at the settings' tick rate) from
//!   [`PlayerInputs`]; [`TerrainEdit`] and [`Detonate`] messages apply at the next tick
//!   boundary; every body is mirrored to an entity ([`CraterfieldBody`]) whose `Transform`
//!   is interpolated between the last two ticks; the state hash and a replay recorder are on
//!   the resource;
//! - **collision as a system parameter**: [`TerrainQuery`] (ray casts, swept circles,
//!   distances, samples, contacts);
//! - **rendering** (feature `render`): a [`TerrainView`] on a 2D camera draws the terrain
//!   with the library's refine renderer on Bevy's own device, under the camera's sprites and
//!   meshes;
//! - **rollback** (feature `ggrs`): [`CraterfieldRollbackPlugin`] runs the world under
//!   bevy_ggrs, its snapshot as rollback state and its state hash as checksum.
//!
//! The crate is built on Bevy 0.19, whose renderer is on wgpu 29; the library's renderers
//! take that device as they take a wgpu 30 one.

#![forbid(unsafe_code)]

mod bodies;
mod level;
mod query;
#[cfg(feature = "render")]
mod render;
#[cfg(feature = "ggrs")]
mod rollback;
mod world;

pub mod prelude;

pub use bodies::{BodyEntities, BodyRole, CraterfieldBody};
pub use craterfield;
#[cfg(feature = "render")]
pub use craterfield::render2d::gpu::Culling;
pub use level::{LevelAsset, LevelLoadError, LevelLoader, level_from_bytes};
pub use query::{TerrainQuery, TerrainQueryError};
#[cfg(feature = "render")]
pub use render::{FrameCostLog, TerrainFrameCosts, TerrainView, terrain_camera};
#[cfg(feature = "ggrs")]
pub use rollback::{CraterfieldRollbackPlugin, Session};
pub use world::{
    Craterfield, CraterfieldError, CraterfieldFailed, Detonate, PlayerInputs, StartMatch, Stepping,
    TerrainEdit, Ticked, install_match,
};

use bevy::prelude::*;

/// The plugin: level assets, the world on the fixed tick, body entities, terrain queries,
/// and (feature `render`, in apps that render) the terrain in 2D cameras with a
/// [`TerrainView`]. See the [crate docs](crate).
#[derive(Default)]
pub struct CraterfieldPlugin;

/// The plugin's systems, for ordering game systems around them.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub enum CraterfieldSystems {
    /// `FixedUpdate`: messages applied, then one tick.
    Step,
    /// `PostUpdate`, before transforms propagate: body entities spawned, despawned and
    /// moved to their interpolated poses.
    MirrorBodies,
}

impl Plugin for CraterfieldPlugin {
    fn build(&self, app: &mut App) {
        app.init_asset::<LevelAsset>()
            .init_asset_loader::<LevelLoader>()
            .init_resource::<PlayerInputs>()
            .init_resource::<BodyEntities>()
            .init_resource::<Stepping>()
            .add_message::<TerrainEdit>()
            .add_message::<Detonate>()
            .add_message::<Ticked>()
            .add_message::<CraterfieldFailed>()
            .add_systems(
                PreUpdate,
                world::start_match_when_loaded.run_if(resource_exists::<StartMatch>),
            )
            .add_systems(
                FixedUpdate,
                world::fixed_tick.in_set(CraterfieldSystems::Step),
            )
            .add_systems(
                PostUpdate,
                bodies::mirror_bodies
                    .in_set(CraterfieldSystems::MirrorBodies)
                    .before(TransformSystems::Propagate),
            );
        #[cfg(feature = "render")]
        render::build(app);
    }
}

/// The README's code examples, compiled as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
