//! Rollback netcode through bevy_ggrs: the world is stepped in `GgrsSchedule` from GGRS's
//! inputs, its [`Snapshot`] is the rollback state (saved each frame, restored on a
//! rollback in O(bodies + terrain changes since)), and its state hash is the checksum the
//! peers and the sync test compare. The GGRS parameters are the library's own
//! ([`GgrsConfig`]: the simulation's `Input`, UDP addresses), as `net::rollback` uses.

use std::collections::VecDeque;

use bevy::prelude::*;
use bevy_ggrs::{
    GgrsPlugin, GgrsSchedule, LoadWorld, LoadWorldSystems, PlayerInputs as GgrsInputs,
    ResourceChecksumPlugin, RollbackFrameCount, SaveWorld, SaveWorldSystems,
};
use craterfield::net::rollback::GgrsConfig;
use craterfield::sim::{Input, Snapshot};

use crate::world::{Craterfield, CraterfieldFailed, Stepping, Ticked};

/// The GGRS session type of a craterfield match.
pub type Session = bevy_ggrs::Session<GgrsConfig>;

/// Adds bevy_ggrs with the library's GGRS parameters and makes the world a rollback
/// resource: steps in `GgrsSchedule` (not `FixedUpdate`), snapshots, checksums. Add it
/// after `CraterfieldPlugin`; insert a [`Session`] to start, and fill
/// `bevy_ggrs::LocalInputs<GgrsConfig>` in the `ReadInputs` schedule.
///
/// Terrain edits sent as messages are not part of GGRS's inputs, so under rollback they
/// would desync the peers: only the simulation's own weapons change the terrain here.
#[derive(Default)]
pub struct CraterfieldRollbackPlugin;

/// Snapshots by GGRS frame, the last few (GGRS rolls back at most its prediction window).
#[derive(Resource, Default)]
struct RollbackSnapshots(VecDeque<(i32, Snapshot)>);

/// Frames of snapshots kept: above any prediction window GGRS allows by default (8), and
/// below the world's own rollback depth (`Settings::rollback_ticks`, 128 by default).
const KEPT_SNAPSHOTS: usize = 32;

impl Plugin for CraterfieldRollbackPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(GgrsPlugin::<GgrsConfig>::default())
            .add_plugins(ResourceChecksumPlugin::<Craterfield>(checksum))
            .insert_resource(Stepping::External)
            .init_resource::<RollbackSnapshots>()
            .add_systems(
                GgrsSchedule,
                rollback_step.in_set(crate::CraterfieldSystems::Step),
            )
            .add_systems(SaveWorld, save.in_set(SaveWorldSystems::Snapshot))
            .add_systems(LoadWorld, load.in_set(LoadWorldSystems::Data));
    }
}

fn checksum(cf: &Craterfield) -> u64 {
    cf.state_hash()
}

fn rollback_step(
    cf: Option<ResMut<Craterfield>>,
    inputs: Res<GgrsInputs<GgrsConfig>>,
    mut ticked: MessageWriter<Ticked>,
    mut failed: MessageWriter<CraterfieldFailed>,
) {
    let Some(mut cf) = cf else {
        return;
    };
    let players = cf.world().players();
    let mut step: Vec<Input> = inputs.iter().map(|(input, _)| *input).collect();
    step.resize(players, Input::default());
    match cf.step_unrecorded(&step) {
        Ok(()) => {
            ticked.write(Ticked {
                tick: cf.world().tick(),
                state_hash: cf.state_hash(),
            });
        }
        Err(error) => {
            error!("craterfield: rollback step: {error}");
            failed.write(CraterfieldFailed {
                what: format!("rollback step of tick {}", cf.world().tick()),
                error,
            });
        }
    }
}

fn save(
    cf: Option<Res<Craterfield>>,
    frame: Res<RollbackFrameCount>,
    mut snapshots: ResMut<RollbackSnapshots>,
) {
    let Some(cf) = cf else {
        return;
    };
    let s = &mut snapshots.0;
    s.retain(|(f, _)| *f < frame.0);
    s.push_back((frame.0, cf.world().snapshot()));
    while s.len() > KEPT_SNAPSHOTS {
        s.pop_front();
    }
}

fn load(
    cf: Option<ResMut<Craterfield>>,
    frame: Res<RollbackFrameCount>,
    snapshots: Res<RollbackSnapshots>,
    mut failed: MessageWriter<CraterfieldFailed>,
) {
    let Some(mut cf) = cf else {
        return;
    };
    let Some((_, snapshot)) = snapshots.0.iter().find(|(f, _)| *f == frame.0) else {
        error!(
            "craterfield: no snapshot of frame {} to roll back to",
            frame.0
        );
        return;
    };
    if let Err(e) = cf.restore(snapshot) {
        error!("craterfield: rollback to frame {}: {e}", frame.0);
        failed.write(CraterfieldFailed {
            what: format!("rollback to frame {}", frame.0),
            error: e.into(),
        });
    }
}
