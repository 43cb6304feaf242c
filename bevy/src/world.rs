//! The deterministic world in the ECS: the [`Craterfield`] resource holding `sim::World`,
//! stepped on Bevy's fixed tick from [`PlayerInputs`], with terrain edits and detonations
//! arriving as messages and applied at the next tick boundary, as the network carries them.

use bevy::prelude::*;
use craterfield::field2d::{Event, Level};
use craterfield::net::{EncodeError, Recorder, Replay};
use craterfield::sim::{Input, Settings, SimError, World as SimWorld, level_hash};

/// The match: the library's deterministic world, what the renderer draws, and an optional
/// replay being recorded. Insert it with [`Craterfield::new`], or let [`StartMatch`] do it
/// once its level asset has loaded.
#[derive(Resource)]
pub struct Craterfield {
    world: SimWorld,
    level: Level,
    palette: Vec<[u8; 3]>,
    recorder: Option<Recorder>,
    /// Each body's pose before the last tick, for interpolation (by id).
    previous: Vec<(u32, Vec2, Vec2)>,
    inputs: Vec<Input>,
}

/// How often a recorded replay stores the state hash (ticks).
const REPLAY_HASH_INTERVAL: u32 = 60;

impl Craterfield {
    /// A match on `level` for `players` players.
    pub fn new(level: &Level, settings: Settings, players: usize) -> Result<Craterfield, SimError> {
        let world = SimWorld::new(level, settings, players)?;
        Ok(Craterfield::from_world(world, level))
    }

    /// Wraps a world built elsewhere (a resynced state, a replay's start) on `level`.
    pub fn from_world(world: SimWorld, level: &Level) -> Craterfield {
        let palette = level.materials().iter().map(|m| m.color).collect();
        let players = world.players();
        let mut c = Craterfield {
            world,
            level: level.clone(),
            palette,
            recorder: None,
            previous: Vec::new(),
            inputs: vec![Input::default(); players],
        };
        c.remember_poses();
        c
    }

    /// The simulation.
    pub fn world(&self) -> &SimWorld {
        &self.world
    }

    /// The simulation, for what the plugin does not wrap (resyncs, debris, backends).
    /// Changes made here bypass the replay recorder.
    pub fn world_mut(&mut self) -> &mut SimWorld {
        &mut self.world
    }

    /// The level the match is played on.
    pub fn level(&self) -> &Level {
        &self.level
    }

    /// The level's material colours (sRGB), index = material id.
    pub fn palette(&self) -> &[[u8; 3]] {
        &self.palette
    }

    /// The 64-bit state hash of the world (the same on every machine for the same inputs).
    pub fn state_hash(&self) -> u64 {
        self.world.state_hash()
    }

    /// The inputs the last tick was stepped with.
    pub fn last_inputs(&self) -> &[Input] {
        &self.inputs
    }

    /// Starts recording a replay from the current tick (which must be 0: a replay starts
    /// with the match). Errors if the world has already been stepped.
    pub fn start_recording(&mut self) -> Result<(), EncodeError> {
        if self.world.tick() != 0 {
            return Err(EncodeError::Inconsistent {
                detail: format!(
                    "a replay starts at tick 0; the match is at tick {}",
                    self.world.tick()
                ),
            });
        }
        let players = u8::try_from(self.world.players()).unwrap_or(u8::MAX);
        self.recorder = Some(Recorder::new(
            level_hash(&self.level),
            *self.world.settings(),
            players,
            REPLAY_HASH_INTERVAL,
        )?);
        Ok(())
    }

    /// Whether a replay is being recorded.
    pub fn is_recording(&self) -> bool {
        self.recorder.is_some()
    }

    /// Stops recording and returns the replay, its last hash being the current state's.
    pub fn finish_recording(&mut self) -> Option<Replay> {
        let recorder = self.recorder.take()?;
        Some(recorder.finish(self.world.tick(), self.world.state_hash()))
    }

    /// Applies a terrain event at the current tick boundary (its tick is set to the world's
    /// tick), journaled in the state hash and in the replay being recorded.
    pub fn apply_edit(&mut self, mut event: Event) -> Result<(), CraterfieldError> {
        event.tick = self.world.tick();
        if let Some(recorder) = &mut self.recorder {
            // Recorded first: an edit the replay format refuses is not applied either.
            recorder.record_edit(event)?;
        }
        self.world.apply_event(event)?;
        Ok(())
    }

    /// One tick with one input per player, recorded when recording.
    pub fn step(&mut self, inputs: &[Input]) -> Result<(), CraterfieldError> {
        self.step_unrecorded(inputs)?;
        if let Some(recorder) = &mut self.recorder {
            recorder.record(inputs, self.world.tick(), self.world.state_hash())?;
        }
        Ok(())
    }

    /// One tick without recording (rollback resimulates ticks a replay must not repeat).
    pub(crate) fn step_unrecorded(&mut self, inputs: &[Input]) -> Result<(), CraterfieldError> {
        self.remember_poses();
        self.world.step(inputs)?;
        self.inputs.clear();
        self.inputs.extend_from_slice(inputs);
        Ok(())
    }

    /// Returns the world to a snapshot taken earlier in this match.
    pub fn restore(&mut self, snapshot: &craterfield::sim::Snapshot) -> Result<(), SimError> {
        self.world.restore(snapshot)?;
        self.remember_poses();
        Ok(())
    }

    fn remember_poses(&mut self) {
        self.previous.clear();
        self.previous
            .extend(self.world.bodies().iter().map(|b| (b.id, b.pos, b.axis)));
        self.previous.sort_unstable_by_key(|p| p.0);
    }

    /// A body's position and axis interpolated between the last two ticks (`alpha` in
    /// `[0, 1]`: 0 is the previous tick, 1 the current), or `None` if it no longer exists.
    pub fn interpolated_pose(&self, id: u32, alpha: f32) -> Option<(Vec2, Vec2)> {
        let body = self.world.bodies().iter().find(|b| b.id == id)?;
        Some(self.interpolate(body, alpha))
    }

    /// Every body with its interpolated position and axis (see [`Self::interpolated_pose`]).
    pub fn interpolated_poses(
        &self,
        alpha: f32,
    ) -> impl Iterator<Item = (&craterfield::sim::Body, Vec2, Vec2)> + '_ {
        self.world.bodies().iter().map(move |b| {
            let (pos, axis) = self.interpolate(b, alpha);
            (b, pos, axis)
        })
    }

    fn interpolate(&self, body: &craterfield::sim::Body, alpha: f32) -> (Vec2, Vec2) {
        let alpha = alpha.clamp(0.0, 1.0);
        match self.previous.binary_search_by_key(&body.id, |p| p.0) {
            Ok(i) => {
                let (_, p, a) = self.previous[i];
                let axis = a
                    .lerp(body.axis, alpha)
                    .try_normalize()
                    .unwrap_or(body.axis);
                (p.lerp(body.pos, alpha), axis)
            }
            // Born this tick: no earlier pose.
            Err(_) => (body.pos, body.axis),
        }
    }
}

/// Why the plugin could not apply an edit or step the world.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CraterfieldError {
    /// The simulation refused (a terrain limit, an input count).
    #[error("simulation: {0}")]
    Sim(#[from] SimError),
    /// The replay being recorded refused (its size limits).
    #[error("replay recording: {0}")]
    Replay(#[from] EncodeError),
}

/// One input per player for the next fixed tick. Game code writes it (keyboard, AI,
/// network); the plugin steps the world with it each `FixedUpdate`. Resized to the match's
/// player count when a match starts.
#[derive(Resource, Default, Debug, Clone, PartialEq)]
pub struct PlayerInputs(pub Vec<Input>);

/// A terrain event (carve or fill, e.g. [`Event::carve`]) applied at the next tick boundary
/// through `World::apply_event`; its `tick` is replaced by that tick.
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct TerrainEdit(pub Event);

/// Weapon `weapon`'s explosion at `at` (crater or fill, impulses, damage) at the next tick
/// boundary, as `World::detonate` does for scripted hazards.
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub struct Detonate {
    /// Where.
    pub at: Vec2,
    /// Which weapon's explosion (0 shell, 1 dirt).
    pub weapon: u8,
}

/// Sent after each fixed tick the plugin stepped.
#[derive(Message, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ticked {
    /// The world's tick after the step.
    pub tick: u32,
    /// The state hash after the step.
    pub state_hash: u64,
}

/// Sent when an edit, a detonation or a step failed (logged as well); nothing of the
/// failed change is applied.
#[derive(Message, Debug, Clone, PartialEq)]
pub struct CraterfieldFailed {
    /// What failed, and where.
    pub what: String,
    /// Why.
    pub error: CraterfieldError,
}

/// Starts a match once `level` has loaded: inserts [`Craterfield`] and sets Bevy's fixed
/// timestep to the settings' tick rate. A level that fails to load is logged with its path
/// and reason, and the request is dropped.
#[derive(Resource, Debug, Clone)]
pub struct StartMatch {
    /// The level asset.
    pub level: Handle<crate::LevelAsset>,
    /// The match settings.
    pub settings: Settings,
    /// Players in the match.
    pub players: usize,
    /// Record a replay from tick 0.
    pub record: bool,
}

pub(crate) fn start_match_when_loaded(
    mut commands: Commands,
    start: Res<StartMatch>,
    levels: Res<Assets<crate::LevelAsset>>,
    server: Res<AssetServer>,
) {
    if let Some(asset) = levels.get(&start.level) {
        commands.remove_resource::<StartMatch>();
        match Craterfield::new(&asset.level, start.settings, start.players) {
            Ok(mut cf) => {
                if start.record
                    && let Err(e) = cf.start_recording()
                {
                    error!("craterfield: cannot record the match: {e}");
                }
                commands.queue(install_match(cf));
            }
            Err(e) => error!("craterfield: cannot start the match: {e}"),
        }
    } else if let Some(bevy::asset::LoadState::Failed(e)) = server.get_load_state(&start.level) {
        commands.remove_resource::<StartMatch>();
        error!("craterfield: the level did not load: {e}");
    }
}

/// Inserts a match and makes the fixed tick its tick rate.
pub fn install_match(cf: Craterfield) -> impl FnOnce(&mut bevy::ecs::world::World) {
    move |world: &mut bevy::ecs::world::World| {
        let hz = f64::from(cf.world().settings().tick_hz);
        let players = cf.world().players();
        world.resource_mut::<Time<Fixed>>().set_timestep_hz(hz);
        world.resource_mut::<PlayerInputs>().0 = vec![Input::default(); players];
        world.insert_resource(cf);
    }
}

/// Who steps the world: the plugin on `FixedUpdate` (the default), or something else (the
/// rollback plugin in `GgrsSchedule`, a server loop, a test).
#[derive(Resource, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stepping {
    /// Once per `FixedUpdate`, from [`PlayerInputs`].
    #[default]
    FixedUpdate,
    /// Not by the plugin.
    External,
}

/// Applies the messages of the frame, then steps once: the `FixedUpdate` system.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fixed_tick(
    stepping: Res<Stepping>,
    cf: Option<ResMut<Craterfield>>,
    inputs: Res<PlayerInputs>,
    mut edits: MessageReader<TerrainEdit>,
    mut detonations: MessageReader<Detonate>,
    mut ticked: MessageWriter<Ticked>,
    mut failed: MessageWriter<CraterfieldFailed>,
) {
    let Some(mut cf) = cf.filter(|_| *stepping == Stepping::FixedUpdate) else {
        let dropped = edits.read().count() + detonations.read().count();
        if dropped > 0 {
            // Under rollback an edit from outside GGRS's inputs would desync the peers.
            warn!(
                "craterfield: {dropped} terrain edits and detonations ignored: no match, or \
                 the world is stepped outside FixedUpdate"
            );
        }
        return;
    };
    let mut fail = |what: String, error: CraterfieldError| {
        error!("craterfield: {what}: {error}");
        failed.write(CraterfieldFailed { what, error });
    };
    for TerrainEdit(event) in edits.read() {
        if let Err(e) = cf.apply_edit(*event) {
            fail(format!("terrain edit {event:?}"), e);
        }
    }
    for d in detonations.read() {
        if cf.is_recording() {
            // A replay holds inputs and terrain edits; impulses and damage from outside
            // would not be in it, and it would not replay to the same state.
            fail(
                format!("detonation {d:?}"),
                EncodeError::Inconsistent {
                    detail: "a detonation cannot be recorded in a replay (send a TerrainEdit)"
                        .to_string(),
                }
                .into(),
            );
            continue;
        }
        if let Err(e) = cf.world_mut().detonate(d.at, d.weapon) {
            fail(format!("detonation {d:?}"), e.into());
        }
    }
    let players = cf.world().players();
    let mut step_inputs = inputs.0.clone();
    step_inputs.resize(players, Input::default());
    match cf.step(&step_inputs) {
        Ok(()) => {
            ticked.write(Ticked {
                tick: cf.world().tick(),
                state_hash: cf.state_hash(),
            });
        }
        Err(e) => fail(format!("step of tick {}", cf.world().tick()), e),
    }
}
