//! What a game names: `use craterfield_bevy::prelude::*;`.

#[cfg(feature = "ggrs")]
pub use crate::CraterfieldRollbackPlugin;
#[cfg(feature = "render")]
pub use crate::TerrainView;
pub use crate::{
    BodyRole, Craterfield, CraterfieldBody, CraterfieldFailed, CraterfieldPlugin,
    CraterfieldSystems, Detonate, LevelAsset, PlayerInputs, StartMatch, TerrainEdit, TerrainQuery,
    Ticked,
};
pub use craterfield::field2d::Event as TerrainEvent;
pub use craterfield::sim::{Input, Settings, buttons};
