//! A world's whole state as plain data: what a peer that has desynced (or joins late,
//! after the terrain's log was compacted) continues from, to the bit.
//!
//! [`World::state`] takes it; [`World::resync`] puts it back on a world of the same
//! level, settings and player count. It carries the bodies, the counters that the state
//! hash covers, the terrain's [`TerrainState`] and the sender's state hash, which the
//! receiver recomputes from the parts before it changes anything: a state altered on the
//! way, or taken from another match, is refused whole.

use serde::{Deserialize, Serialize};

use super::body::{Body, BodyKind};
use super::hash::state_hash_of;
use super::world::{SimError, World, in_play};
use craterfield_field::TerrainState;

/// Largest speed a received body may have, world units per second (far above anything
/// the settings allow: a bound on nonsense, not on play).
const MAX_BODY_SPEED: f32 = 1.0e6;
/// Largest size (radius or half length) a received body may have, world units.
const MAX_BODY_SIZE: f32 = 65_536.0;

/// A world's whole state: the bodies, the counters the state hash covers, the terrain's
/// [`TerrainState`], a digest of it and the sender's state hash, which
/// [`World::resync`] recomputes from the parts before changing anything.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WorldState {
    setup: u64,
    tick: u32,
    next_id: u32,
    events_hash: u64,
    bodies: Vec<Body>,
    terrain: TerrainState,
    /// A hash of the terrain state's encoding (the state hash covers the terrain's event
    /// chain, not its grid).
    terrain_digest: u64,
    /// The sender's [`World::state_hash`].
    hash: u64,
}

/// The hash of a terrain state's canonical (postcard) bytes.
fn terrain_digest(t: &TerrainState) -> u64 {
    let bytes = postcard::to_stdvec(t).unwrap_or_default();
    super::hash::hash_bytes(0x7465_7272_6100, &bytes)
}

impl WorldState {
    /// The tick the state was taken at.
    pub fn tick(&self) -> u32 {
        self.tick
    }

    /// The bodies.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The terrain's state.
    pub fn terrain(&self) -> &TerrainState {
        &self.terrain
    }

    /// The sender's state hash at that tick.
    pub fn state_hash(&self) -> u64 {
        self.hash
    }

    /// The state hash recomputed from the parts.
    fn recomputed_hash(&self) -> u64 {
        state_hash_of(
            self.setup,
            self.tick,
            self.next_id,
            self.events_hash,
            self.terrain.events_applied(),
            &self.bodies,
        )
    }
}

impl World {
    /// The whole state of the current tick (see [`WorldState`]). Costs O(bodies + the
    /// terrain's cells, events and bricks).
    pub fn state(&self) -> WorldState {
        let terrain = self.terrain.state();
        WorldState {
            setup: self.setup,
            tick: self.tick,
            next_id: self.next_id,
            events_hash: self.events_hash,
            // The probe caches are derived (a hit gives the bits a fresh sample would) and
            // not sent.
            bodies: (self.bodies.iter())
                .map(|b| Body {
                    probes: [None; 2],
                    ..*b
                })
                .collect(),
            terrain_digest: terrain_digest(&terrain),
            terrain,
            hash: self.state_hash(),
        }
    }

    /// Continues from `state`, taken by [`World::state`] on a peer's world of the same
    /// level, settings and player count: from here on both step to the same bits. The
    /// rollback history starts afresh (earlier snapshots are refused). A state of another
    /// match is [`SimError::ForeignSnapshot`]; one whose parts do not fit (a body out of
    /// range, a terrain index, a hash that does not match) is [`SimError::BadState`] or
    /// [`SimError::Terrain`]; either way nothing changes.
    pub fn resync(&mut self, state: &WorldState) -> Result<(), SimError> {
        let tick = state.tick;
        let bad = |detail: String| SimError::BadState { tick, detail };
        if state.setup != self.setup {
            return Err(SimError::ForeignSnapshot { tick });
        }
        if state.terrain.tick() != tick {
            return Err(bad(format!(
                "the terrain is at tick {}",
                state.terrain.tick()
            )));
        }
        self.check_bodies(state).map_err(bad)?;
        if state.recomputed_hash() != state.hash
            || terrain_digest(&state.terrain) != state.terrain_digest
        {
            return Err(bad("its state hash does not match its contents".into()));
        }
        self.terrain.restore_state(&state.terrain)?;
        self.tick = tick;
        self.next_id = state.next_id;
        self.events_hash = state.events_hash;
        self.bodies.clone_from(&state.bodies);
        self.marks.clear();
        Ok(())
    }

    /// Every body in range: ids ascending below `next_id`, kinds of this match (players,
    /// weapons, one vehicle each), finite values of sane size, in play.
    fn check_bodies(&self, s: &WorldState) -> Result<(), String> {
        if s.bodies.len() > self.settings.max_bodies as usize {
            return Err(format!(
                "{} bodies (max_bodies is {})",
                s.bodies.len(),
                self.settings.max_bodies
            ));
        }
        let mut vehicles = [false; super::MAX_PLAYERS];
        let mut previous: Option<u32> = None;
        for b in &s.bodies {
            let id = b.id;
            if id >= s.next_id || previous.is_some_and(|p| p >= id) {
                return Err(format!(
                    "body {id} is out of order or not below the next id {}",
                    s.next_id
                ));
            }
            previous = Some(id);
            self.check_kind(b, &mut vehicles)
                .map_err(|why| format!("body {id}: {why}"))?;
            check_values(b, self.terrain.bounds()).map_err(|why| format!("body {id}: {why}"))?;
        }
        Ok(())
    }

    fn check_kind(&self, b: &Body, vehicles: &mut [bool]) -> Result<(), String> {
        match b.kind {
            BodyKind::Vehicle { player, .. } => match vehicles.get_mut(usize::from(player)) {
                Some(seen @ false) if usize::from(player) < self.players => {
                    *seen = true;
                    Ok(())
                }
                _ => Err(format!("a second or unknown vehicle of player {player}")),
            },
            BodyKind::Projectile { owner, weapon } => {
                if usize::from(owner) >= self.players {
                    Err(format!("a projectile of unknown player {owner}"))
                } else if self.settings.weapon(weapon).is_none() {
                    Err(format!("a projectile of unknown weapon {weapon}"))
                } else {
                    Ok(())
                }
            }
            BodyKind::Debris => Ok(()),
        }
    }
}

/// Finite values of sane size, and a position still in play.
fn check_values(b: &Body, (lo, hi): (glam::Vec2, glam::Vec2)) -> Result<(), String> {
    let vectors = [b.pos, b.vel, b.axis, b.ground, b.surface];
    let scalars = [
        b.radius,
        b.half_length,
        b.inv_mass,
        b.friction,
        b.restitution,
        b.drive,
        b.clearance,
    ];
    if !(vectors.iter().all(|v| v.is_finite()) && scalars.iter().all(|x| x.is_finite())) {
        return Err("a value is NaN or infinite".into());
    }
    if !(b.radius > 0.0 && b.radius <= MAX_BODY_SIZE && b.half_length >= 0.0)
        || b.half_length > MAX_BODY_SIZE
    {
        return Err(format!(
            "radius {} and half length {} must be in (0, {MAX_BODY_SIZE}] and [0, {MAX_BODY_SIZE}]",
            b.radius, b.half_length
        ));
    }
    if !(b.inv_mass >= 0.0 && b.friction >= 0.0 && b.restitution >= 0.0) {
        return Err("mass, friction and restitution must not be negative".into());
    }
    if b.vel.length() > MAX_BODY_SPEED || b.drive.abs() > MAX_BODY_SPEED {
        return Err(format!("speeds must be at most {MAX_BODY_SPEED}"));
    }
    if !in_play(b.pos, lo, hi) {
        return Err(format!("position {} is out of play", b.pos));
    }
    Ok(())
}
