//! The world: bodies on a terrain, stepped at a fixed tick from the players' inputs.
//!
//! One tick, in a fixed order: inputs (drive, jump, stick, fire), forces (gravity, or the
//! stick pull along the field gradient; wind on projectiles), projectile sweeps (batched),
//! vehicle and debris contacts with the terrain (one batch of samples), the move,
//! body-body contacts, explosions (carve or fill events, impulses, damage), removals.
//! Everything is `f32` arithmetic from the determinism contract, in a fixed order, so the
//! same inputs give the same bits everywhere; [`World::state_hash`] checks it.

use std::collections::VecDeque;

use glam::Vec2;
use thiserror::Error;

use craterfield_core::backend::{Backend, BackendError};
use craterfield_core::det::math::{cos_turns, sin_turns};
use craterfield_field::tape::EvalError;
use craterfield_field::terrain::{RollbackError, TerrainMark};
use craterfield_field::{Event, EventKind};
use craterfield_field::{Graph, Level, Sample, Sdf, Terrain, TerrainError};

use super::body::{Body, BodyKind, ProbeCache};
use super::collide::{self, Broadphase, Overlap};
use super::contact;
use super::hash::{self, setup_hash, state_hash_of};
use super::input::{Input, buttons};
use super::projectile::{self, Flight, Sweep};
use super::settings::{Settings, SettingsError, WeaponSettings, units};

/// Most players in a match.
pub const MAX_PLAYERS: usize = 8;

/// Bodies this far beside the terrain's bounds are removed.
const OUT_OF_WORLD: f32 = 1024.0;
/// Bodies this far below the terrain's bounds are removed (they fell out of the world).
const BELOW_WORLD: f32 = 64.0;

/// Explosion centres are snapped to this fixed-point step (1/4 world unit): compact on the
/// wire, and far below anything visible.
pub const EVENT_CENTER_STEP: i32 = 64;

/// Why the world could not be built or stepped.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum SimError {
    /// The settings are out of range.
    #[error("invalid settings: {0}")]
    Settings(#[from] SettingsError),
    /// The player count is 0 or above [`MAX_PLAYERS`].
    #[error("player count {players} must be 1..={MAX_PLAYERS}")]
    PlayerCount {
        /// The count asked for.
        players: usize,
    },
    /// The level has no spawn points.
    #[error("the level has no spawn points")]
    NoSpawns,
    /// `step` got a different number of inputs than there are players.
    #[error("step got {got} inputs for {players} players")]
    InputCount {
        /// Inputs given.
        got: usize,
        /// Players in the match.
        players: usize,
    },
    /// The terrain could not be built or refused an event.
    #[error("terrain: {0}")]
    Terrain(#[from] TerrainError),
    /// A field batch failed.
    #[error("field evaluation: {0}")]
    Eval(#[from] EvalError),
    /// The backend is unavailable.
    #[error("backend: {0}")]
    Backend(#[from] BackendError),
    /// A snapshot could not be restored.
    #[error("cannot restore the snapshot of tick {tick}: {source}")]
    Restore {
        /// The snapshot's tick.
        tick: u32,
        /// Why.
        source: RollbackError,
    },
    /// The snapshot was taken on a world of another level, settings or player count.
    #[error(
        "cannot restore the snapshot of tick {tick}: it was taken on a world of another level, settings or player count"
    )]
    ForeignSnapshot {
        /// The snapshot's tick.
        tick: u32,
    },
    /// A body could not be added.
    #[error("cannot add a body: {reason}")]
    BadBody {
        /// Why.
        reason: String,
    },
    /// A [`WorldState`](super::WorldState) does not fit this world (another match, or
    /// altered on the way).
    #[error("cannot resync from the state of tick {tick}: {detail}")]
    BadState {
        /// The state's tick.
        tick: u32,
        /// What does not fit.
        detail: String,
    },
}

/// Everything needed to return the world to one tick: the bodies and a terrain mark.
/// Costs O(bodies) to take; restoring costs O(bodies + terrain changes since).
#[derive(Clone, Debug)]
pub struct Snapshot {
    tick: u32,
    setup: u64,
    bodies: Vec<Body>,
    next_id: u32,
    events_hash: u64,
    mark: TerrainMark,
}

impl Snapshot {
    /// The tick the snapshot was taken at.
    pub fn tick(&self) -> u32 {
        self.tick
    }
}

/// A match in progress.
#[derive(Clone, Debug)]
pub struct World {
    pub(super) settings: Settings,
    /// Hash of the level, the settings and the player count (see [`hash::setup_hash`]).
    pub(super) setup: u64,
    pub(super) terrain: Terrain<Graph>,
    pub(super) players: usize,
    pub(super) tick: u32,
    pub(super) bodies: Vec<Body>,
    pub(super) next_id: u32,
    /// Chain hash of the terrain's event log.
    pub(super) events_hash: u64,
    /// Terrain marks at the start of each of the last `rollback_ticks` ticks.
    pub(super) marks: VecDeque<(u32, TerrainMark)>,
    threads: usize,
    scratch: Scratch,
}

/// Buffers reused from tick to tick.
#[derive(Clone, Debug, Default)]
struct Scratch {
    points: Vec<Vec2>,
    /// For each point of `points`: its body, its probe and the region stamp.
    pending: Vec<(usize, usize, Option<u64>)>,
    samples: Vec<Sample>,
    sweeps: Vec<Sweep>,
    sweep_of: Vec<usize>,
    flights: Vec<Flight>,
    overlaps: Vec<Overlap>,
    broadphase: Broadphase,
}

/// An explosion waiting to be applied this tick.
#[derive(Clone, Copy, Debug)]
struct Blast {
    at: Vec2,
    weapon: WeaponSettings,
}

impl World {
    /// A match on `level` for `players` players, one vehicle each at the level's spawn
    /// points (in order, wrapping around).
    pub fn new(level: &Level, settings: Settings, players: usize) -> Result<World, SimError> {
        settings.validate()?;
        if players == 0 || players > MAX_PLAYERS {
            return Err(SimError::PlayerCount { players });
        }
        let spawns: Vec<Vec2> = level.spawns().collect();
        if spawns.is_empty() {
            return Err(SimError::NoSpawns);
        }
        let mut terrain = level.terrain()?;
        terrain.enable_rollback();
        let mut world = World {
            settings,
            setup: setup_hash(level, &settings, players),
            terrain,
            players,
            tick: 0,
            bodies: Vec::new(),
            next_id: 0,
            events_hash: 0,
            marks: VecDeque::new(),
            threads: 1,
            scratch: Scratch::default(),
        };
        for p in 0..players {
            let at = spawns[p % spawns.len()];
            world.push_vehicle(p as u8, at);
        }
        Ok(world)
    }

    fn push_vehicle(&mut self, player: u8, at: Vec2) {
        let v = self.settings.vehicle;
        let kind = BodyKind::Vehicle {
            player,
            prev_buttons: 0,
            cooldown: 0,
            stick: false,
        };
        let body = Body {
            half_length: units(v.half_length),
            inv_mass: 1.0 / units(v.mass),
            friction: units(v.friction),
            restitution: units(v.restitution),
            health: v.health,
            ..Body::new(self.next_id, kind, at, units(v.radius))
        };
        self.push(body);
    }

    /// Adds a passive circular body (debris) at `at`; returns its id.
    pub fn add_debris(&mut self, at: Vec2, radius: f32) -> Result<u32, SimError> {
        let bad = |reason: &str| SimError::BadBody {
            reason: reason.to_string(),
        };
        if !(at.is_finite() && at.x.abs() <= 65536.0 && at.y.abs() <= 65536.0) {
            return Err(bad("the position must be finite and within 65536 units"));
        }
        if !(radius > 0.0 && radius <= 256.0) {
            return Err(bad("the radius must be in (0, 256]"));
        }
        if self.bodies.len() >= self.settings.max_bodies as usize {
            return Err(bad("the world already holds max_bodies bodies"));
        }
        let id = self.next_id;
        self.push(Body {
            friction: units(self.settings.vehicle.friction),
            restitution: units(self.settings.vehicle.restitution),
            ..Body::new(id, BodyKind::Debris, at, radius)
        });
        Ok(id)
    }

    /// Adds a body built with the next id.
    fn push(&mut self, body: Body) {
        self.next_id += 1;
        self.bodies.push(body);
    }

    /// Applies a destruction event from outside (an authoritative server's stream, a late
    /// joiner's terrain snapshot). Hashed and journaled like the world's own.
    pub fn apply_event(&mut self, e: Event) -> Result<(), SimError> {
        self.terrain.apply(e)?;
        self.chain_event(&e);
        Ok(())
    }

    /// Sets off weapon `weapon`'s explosion at `at` now (scripted hazards, server-side
    /// effects): the same event, impulses and damage as a projectile impact.
    pub fn detonate(&mut self, at: Vec2, weapon: u8) -> Result<(), SimError> {
        if !(at.is_finite() && at.x.abs() <= 65536.0 && at.y.abs() <= 65536.0) {
            return Err(SimError::BadBody {
                reason: format!("detonation point {at} must be finite and within 65536 units"),
            });
        }
        let w = *self
            .settings
            .weapon(weapon)
            .ok_or_else(|| SimError::BadBody {
                reason: format!("weapon {weapon} does not exist"),
            })?;
        self.explode(&[Blast { at, weapon: w }]);
        self.remove_dead();
        Ok(())
    }

    fn chain_event(&mut self, e: &Event) {
        self.events_hash = hash::chain_event(self.events_hash, e);
    }

    /// The settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The terrain (read-only: change it through the world so hashes and rollback see it).
    pub fn terrain(&self) -> &Terrain<Graph> {
        &self.terrain
    }

    /// The bodies, in a fixed order (creation order).
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// Players in the match.
    pub fn players(&self) -> usize {
        self.players
    }

    /// Ticks stepped so far.
    pub fn tick(&self) -> u32 {
        self.tick
    }

    /// The vehicle of `player`, if it is still alive.
    pub fn vehicle(&self, player: u8) -> Option<&Body> {
        self.bodies.iter().find(|b| b.player() == Some(player))
    }

    /// Chooses the field evaluator backend (every backend gives the same bits).
    pub fn set_backend(&mut self, backend: Backend) -> Result<(), SimError> {
        self.terrain.set_backend(backend)?;
        Ok(())
    }

    /// Splits the per-tick field batches over `threads` threads (1 = none). Results are
    /// the same bits for every count.
    pub fn set_threads(&mut self, threads: usize) {
        self.threads = threads.clamp(1, 64);
    }

    /// The state hash: the match's setup (level, settings, players), the tick, the bodies
    /// and the terrain's event log, over canonical words. O(bodies): the event log is
    /// folded into a chain hash as events are applied.
    pub fn state_hash(&self) -> u64 {
        state_hash_of(
            self.setup,
            self.tick,
            self.next_id,
            self.events_hash,
            self.terrain.events_applied(),
            &self.bodies,
        )
    }

    /// A snapshot of the current tick.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            tick: self.tick,
            setup: self.setup,
            bodies: self.bodies.clone(),
            next_id: self.next_id,
            events_hash: self.events_hash,
            mark: self.current_mark(),
        }
    }

    fn current_mark(&self) -> TerrainMark {
        // Rollback is enabled in `new`, so a mark always exists.
        self.terrain
            .mark()
            .unwrap_or_else(|| unreachable!("rollback is enabled on every world's terrain"))
    }

    /// Returns to a snapshot taken on this world within the last `rollback_ticks` ticks of
    /// its current timeline. A snapshot of a world with another level, settings or player
    /// count is [`SimError::ForeignSnapshot`]; one of another world of the same setup, of
    /// a clone that has diverged since, or from a rolled-back future is
    /// [`SimError::Restore`]. On error nothing changes.
    pub fn restore(&mut self, s: &Snapshot) -> Result<(), SimError> {
        if s.setup != self.setup {
            return Err(SimError::ForeignSnapshot { tick: s.tick });
        }
        self.terrain
            .rollback(&s.mark)
            .map_err(|source| SimError::Restore {
                tick: s.tick,
                source,
            })?;
        self.tick = s.tick;
        self.bodies.clone_from(&s.bodies);
        self.next_id = s.next_id;
        self.events_hash = s.events_hash;
        while self.marks.back().is_some_and(|m| m.0 >= s.tick) {
            self.marks.pop_back();
        }
        Ok(())
    }

    /// Advances one tick with one input per player (in player order).
    pub fn step(&mut self, inputs: &[Input]) -> Result<(), SimError> {
        if inputs.len() != self.players {
            return Err(SimError::InputCount {
                got: inputs.len(),
                players: self.players,
            });
        }
        self.remember_mark();
        self.tick += 1;
        self.terrain.set_tick(self.tick)?;
        let dt = self.settings.dt();
        let mut blasts = Vec::new();
        self.control(inputs);
        self.forces(dt);
        self.fly(dt, &mut blasts)?;
        self.contacts(dt)?;
        self.bodies_collide(&mut blasts);
        self.explode(&blasts);
        self.remove_dead();
        Ok(())
    }

    fn remember_mark(&mut self) {
        let mark = self.current_mark();
        self.marks.push_back((self.tick, mark));
        let keep = self.settings.rollback_ticks as usize + 1;
        while self.marks.len() > keep {
            self.marks.pop_front();
        }
        let oldest = self.marks.front().filter(|_| self.marks.len() == keep);
        if let Some(&(_, oldest)) = oldest {
            self.terrain.forget_before(&oldest);
        }
    }

    /// Inputs: throttle, jump, stick toggle, fire.
    fn control(&mut self, inputs: &[Input]) {
        let mut shots = Vec::new();
        for b in &mut self.bodies {
            let BodyKind::Vehicle {
                player,
                prev_buttons,
                cooldown,
                stick,
            } = &mut b.kind
            else {
                continue;
            };
            let input = inputs[*player as usize].sanitized();
            let prev = Input {
                buttons: *prev_buttons,
                ..Input::default()
            };
            *prev_buttons = input.buttons;
            *cooldown = cooldown.saturating_sub(1);
            if input.pressed(prev, buttons::STICK) {
                *stick = !*stick;
            }
            let grounded = b.ground != Vec2::ZERO;
            b.drive = f32::from(input.drive) / 127.0 * units(self.settings.vehicle.drive_speed);
            if grounded && input.pressed(prev, buttons::JUMP) {
                b.vel += b.ground * units(self.settings.vehicle.jump_speed);
            }
            let weapon = self.settings.weapon(input.weapon);
            let fires = input.pressed(prev, buttons::FIRE) && *cooldown == 0;
            if let Some(w) = weapon.filter(|_| fires) {
                *cooldown = w.cooldown_ticks;
                shots.push((*player, b.pos, b.vel, b.bounding_radius(), input));
            }
        }
        for (player, pos, vel, reach, input) in shots {
            self.launch(player, pos, vel, reach, input);
        }
    }

    fn launch(&mut self, owner: u8, pos: Vec2, vel: Vec2, reach: f32, input: Input) {
        let Some(w) = self.settings.weapon(input.weapon).copied() else {
            return;
        };
        if self.bodies.len() >= self.settings.max_bodies as usize {
            return;
        }
        let t = input.aim_turns();
        let dir = Vec2::new(cos_turns(t), sin_turns(t));
        let radius = units(w.radius);
        let speed = units(w.speed) * (f32::from(input.power) / 255.0);
        let kind = BodyKind::Projectile {
            owner,
            weapon: input.weapon,
        };
        let at = pos + dir * (reach + radius + 1.0);
        self.push(Body {
            vel: vel + dir * speed,
            ..Body::new(self.next_id, kind, at, radius)
        });
    }

    /// Gravity (or the stick pull), wind on projectiles, and the speed limit.
    fn forces(&mut self, dt: f32) {
        let g = units(self.settings.gravity);
        let wind = Vec2::new(units(self.settings.wind[0]), units(self.settings.wind[1]));
        let stick_range = units(self.settings.stick_range);
        let max_speed = units(self.settings.max_speed);
        for b in &mut self.bodies {
            let accel = match b.kind {
                BodyKind::Projectile { .. } => Vec2::new(wind.x, wind.y - g),
                BodyKind::Vehicle { stick: true, .. }
                    if b.surface != Vec2::ZERO && b.clearance <= stick_range =>
                {
                    -b.surface * g
                }
                _ => Vec2::new(0.0, -g),
            };
            b.vel += accel * dt;
            let speed2 = b.vel.x * b.vel.x + b.vel.y * b.vel.y;
            if speed2 > max_speed * max_speed {
                let s = max_speed / speed2.sqrt();
                b.vel = Vec2::new(b.vel.x * s, b.vel.y * s);
            }
        }
    }

    /// Projectiles: batched sweeps; hits become blasts.
    fn fly(&mut self, dt: f32, blasts: &mut Vec<Blast>) -> Result<(), SimError> {
        let s = &mut self.scratch;
        s.sweeps.clear();
        s.sweep_of.clear();
        for (i, b) in self.bodies.iter().enumerate() {
            if !b.is_projectile() {
                continue;
            }
            let motion = b.vel * dt;
            let len = (motion.x * motion.x + motion.y * motion.y).sqrt();
            let dir = if len > 0.0 {
                Vec2::new(motion.x / len, motion.y / len)
            } else {
                Vec2::ZERO
            };
            s.sweeps.push(Sweep {
                from: b.pos,
                dir,
                len,
                radius: b.radius,
            });
            s.sweep_of.push(i);
        }
        if s.sweeps.is_empty() {
            return Ok(());
        }
        projectile::fly(&self.terrain, &s.sweeps, &mut s.flights)?;
        for (k, &i) in s.sweep_of.iter().enumerate() {
            let b = &mut self.bodies[i];
            match s.flights[k] {
                Flight::Moved { to } => b.pos = to,
                Flight::Hit { at } => {
                    b.pos = at;
                    b.health = 0;
                    if let Some(weapon) = weapon_of(&self.settings, b) {
                        blasts.push(Blast { at, weapon });
                    }
                }
            }
        }
        Ok(())
    }

    /// Vehicles and debris against the terrain: one batch of samples for every probe
    /// point whose cached sample is stale, then the solve and the move.
    fn contacts(&mut self, dt: f32) -> Result<(), SimError> {
        let s = &mut self.scratch;
        s.points.clear();
        s.pending.clear();
        for (i, b) in self.bodies.iter().enumerate() {
            if b.is_projectile() {
                continue;
            }
            let (points, n) = contact::probe_points(b);
            for (k, &p) in points.iter().enumerate().take(n) {
                let stamp = self.terrain.region_stamp(p);
                let fresh = stamp.zip(b.probes[k]).is_some_and(|(st, c)| c.holds(p, st));
                if !fresh {
                    s.points.push(p);
                    s.pending.push((i, k, stamp));
                }
            }
        }
        let blank = Sample {
            distance: 0.0,
            gradient: Vec2::ZERO,
            material: 0,
        };
        s.samples.clear();
        s.samples.resize(s.points.len(), blank);
        sample_all(&self.terrain, &s.points, &mut s.samples, self.threads)?;
        for (j, &(i, k, stamp)) in s.pending.iter().enumerate() {
            let cache = ProbeCache {
                point: s.points[j],
                stamp: stamp.unwrap_or(0),
                sample: s.samples[j],
            };
            // A tick-dependent region gets a sample for this tick only.
            self.bodies[i].probes[k] = Some(cache).filter(|_| stamp.is_some());
        }
        let lipschitz = self.terrain.lipschitz();
        let mut j = 0;
        for (i, b) in self.bodies.iter_mut().enumerate() {
            if b.is_projectile() {
                continue;
            }
            let n = contact::probe_points(b).1;
            let mut samples = [blank; 2];
            for (k, slot) in samples.iter_mut().enumerate().take(n) {
                *slot = match s.pending.get(j) {
                    Some(&(pi, pk, _)) if pi == i && pk == k => {
                        j += 1;
                        s.samples[j - 1]
                    }
                    _ => b.probes[k].map_or(blank, |c| c.sample),
                };
            }
            contact::solve(b, &samples[..n], lipschitz, dt);
            b.pos += b.vel * dt;
            follow_surface(b);
        }
        Ok(())
    }

    /// Body-body overlaps; a projectile touching a vehicle or debris explodes.
    fn bodies_collide(&mut self, blasts: &mut Vec<Blast>) {
        let s = &mut self.scratch;
        let budget = u64::from(self.settings.max_bodies) * collide::PAIR_TESTS_PER_BODY;
        s.broadphase.overlaps(&self.bodies, &mut s.overlaps, budget);
        for o in &s.overlaps {
            let (lo, hi) = self.bodies.split_at_mut(o.b);
            let (a, b) = (&mut lo[o.a], &mut hi[0]);
            match (a.is_projectile(), b.is_projectile()) {
                (false, false) => collide::resolve(a, b, o),
                (true, false) | (false, true) => {
                    let p = if a.is_projectile() { a } else { b };
                    if p.health > 0 {
                        p.health = 0;
                        if let Some(weapon) = weapon_of(&self.settings, p) {
                            blasts.push(Blast { at: p.pos, weapon });
                        }
                    }
                }
                (true, true) => {}
            }
        }
    }

    /// Terrain events, impulses and damage of this tick's blasts, in order.
    fn explode(&mut self, blasts: &[Blast]) {
        for blast in blasts {
            // A crater outside the terrain's bounds changes no terrain; the blast still
            // pushes and damages.
            let event = self
                .blast_event(blast)
                .filter(|e| self.terrain.apply(*e).is_ok());
            if let Some(e) = event {
                self.chain_event(&e);
            }
            let reach = units(blast.weapon.blast_radius);
            let push = units(blast.weapon.impulse);
            for b in &mut self.bodies {
                if b.is_projectile() || reach <= 0.0 {
                    continue;
                }
                let d = b.pos - blast.at;
                let dist = (d.x * d.x + d.y * d.y).sqrt();
                let inside = dist < reach;
                if !inside {
                    continue;
                }
                let falloff = 1.0 - dist / reach;
                let dir = if dist > 1e-3 {
                    Vec2::new(d.x / dist, d.y / dist)
                } else {
                    Vec2::Y
                };
                b.vel += dir * (push * falloff * b.inv_mass);
                let damage = (blast.weapon.damage as f32 * falloff) as i32;
                if b.player().is_some() {
                    b.health = b.health.saturating_sub(damage);
                }
            }
        }
    }

    /// The terrain event of a blast: centre snapped to [`EVENT_CENTER_STEP`].
    fn blast_event(&self, blast: &Blast) -> Option<Event> {
        let w = &blast.weapon;
        let snap = |v: f32| -> Option<i32> {
            let fixed = craterfield_core::det::quant::from_f32(v).ok()?;
            Some((fixed + EVENT_CENTER_STEP / 2).div_euclid(EVENT_CENTER_STEP) * EVENT_CENTER_STEP)
        };
        Some(Event {
            kind: if w.fills {
                EventKind::Fill
            } else {
                EventKind::Carve
            },
            center: [snap(blast.at.x)?, snap(blast.at.y)?],
            radius: w.crater_radius,
            rim: 0,
            grow_ticks: 0,
            tick: self.tick,
            material: if w.fills { w.material } else { 0 },
        })
    }

    /// Removes spent projectiles, destroyed vehicles and bodies that left the world.
    fn remove_dead(&mut self) {
        let (lo, hi) = self.terrain.bounds();
        self.bodies
            .retain(|b| b.health > 0 && in_play(b.pos, lo, hi));
    }
}

/// Whether a body at `p` is still in play in a level of bounds `[lo, hi]`.
pub(super) fn in_play(p: Vec2, lo: Vec2, hi: Vec2) -> bool {
    p.x >= lo.x - OUT_OF_WORLD
        && p.x <= hi.x + OUT_OF_WORLD
        && p.y >= lo.y - BELOW_WORLD
        && p.y <= hi.y + 8.0 * OUT_OF_WORLD
}

/// The weapon of a projectile.
fn weapon_of(settings: &Settings, b: &Body) -> Option<WeaponSettings> {
    match b.kind {
        BodyKind::Projectile { weapon, .. } => settings.weapon(weapon).copied(),
        _ => None,
    }
}

/// A grounded capsule turns its axis towards the surface tangent.
fn follow_surface(b: &mut Body) {
    if b.half_length <= 0.0 || b.ground == Vec2::ZERO {
        return;
    }
    let n = b.ground;
    let mut t = Vec2::new(n.y, -n.x);
    if t.x * b.axis.x + t.y * b.axis.y < 0.0 {
        t = -t;
    }
    let a = b.axis + (t - b.axis) * 0.25;
    let len = (a.x * a.x + a.y * a.y).sqrt();
    if len > 1e-6 {
        b.axis = Vec2::new(a.x / len, a.y / len);
    }
}

/// Samples every point, split over `threads` scoped threads (each point's result is the
/// same whichever chunk it lands in).
fn sample_all(
    terrain: &Terrain<Graph>,
    points: &[Vec2],
    out: &mut [Sample],
    threads: usize,
) -> Result<(), EvalError> {
    const MIN_CHUNK: usize = 256;
    let chunks = craterfield_core::threads::spawnable(threads).min(points.len() / MIN_CHUNK);
    if chunks <= 1 {
        return terrain.samples(points, out);
    }
    let size = points.len().div_ceil(chunks);
    std::thread::scope(|scope| {
        let handles: Vec<_> = points
            .chunks(size)
            .zip(out.chunks_mut(size))
            .map(|(p, o)| scope.spawn(move || terrain.samples(p, o)))
            .collect();
        handles
            .into_iter()
            .try_for_each(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::buttons;
    use craterfield_field::TerrainOptions;

    /// Player `p`'s input at tick `t`: both weapons, many aims and powers, fire toggled
    /// every other tick so each press is a new shot.
    fn input(p: usize, t: u32) -> Input {
        let k = t.wrapping_mul(2_654_435_761).rotate_left(p as u32 * 7);
        Input {
            aim: (k >> 8) as u16 % 32768,
            buttons: if t.is_multiple_of(2) {
                buttons::FIRE
            } else {
                0
            },
            drive: ((k >> 3) % 60) as i8 - 30,
            power: 120 + (k % 136) as u8,
            weapon: ((k >> 20) % 2) as u8,
        }
    }

    fn settings() -> Settings {
        let mut s = Settings::default();
        s.shell.cooldown_ticks = 1;
        s.dirt.cooldown_ticks = 1;
        s.vehicle.health = 1_000_000;
        s
    }

    /// A world whose terrain compacts its log past `max_events` events. The terrain is
    /// swapped in after `new`, so the setup (and every state hash) is the plain world's.
    fn compacting_world(max_events: usize) -> World {
        let level = Level::default_level();
        let mut w = World::new(&level, settings(), 4).unwrap();
        let b = level.bounds();
        let o = TerrainOptions {
            max_events,
            ..level.terrain_options()
        };
        let mut terrain = Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap();
        terrain.enable_rollback();
        w.terrain = terrain;
        w
    }

    #[test]
    fn a_compacting_terrain_keeps_every_state_hash_through_restores() {
        let level = Level::default_level();
        let mut plain = World::new(&level, settings(), 4).unwrap();
        let mut small = compacting_world(24);
        let mut saved = None;
        let mut applied_at = Vec::new();
        for t in 0..1200u32 {
            let inputs: Vec<Input> = (0..4).map(|p| input(p, t)).collect();
            plain.step(&inputs).unwrap();
            small.step(&inputs).unwrap();
            applied_at.push(plain.terrain.events_applied());
            assert_eq!(plain.state_hash(), small.state_hash(), "tick {t}");
            // Now and then go back a few ticks and play them again, as rollback does.
            if t % 97 == 0 {
                saved = Some(small.snapshot());
            } else if t % 97 == 9
                && let Some(s) = saved.take()
            {
                small.restore(&s).unwrap();
                for u in s.tick()..small.tick() + 9 {
                    let inputs: Vec<Input> = (0..4).map(|p| input(p, u)).collect();
                    small.step(&inputs).unwrap();
                }
                assert_eq!(plain.state_hash(), small.state_hash(), "redo to {t}");
            }
        }
        // Between compactions the log may grow to twice what the last one kept.
        let grown = small.terrain.events().len();
        small.terrain.compact_history();
        let (kept, applied) = (small.terrain.events().len(), small.terrain.events_applied());
        assert!(
            grown <= 2 * kept.max(24),
            "{grown} events held, {kept} needed"
        );
        assert!(applied > 1000, "{applied} explosions applied");
        assert_eq!(applied, plain.terrain.events_applied());
        assert!(!small.terrain.history_complete());
        // The log keeps what cells still list and what a restore may still take back.
        let grid = small.terrain.grid();
        let listed: std::collections::BTreeSet<u32> = (0..grid.cell_count())
            .filter_map(|i| grid.cell(i))
            .flat_map(|c| c.events().iter().copied())
            .collect();
        let window = (applied - applied_at[applied_at.len() - 130]) as usize;
        assert!(
            kept <= listed.len() + window,
            "{kept} of {applied} kept, {} listed, {window} in the rollback window",
            listed.len()
        );
        assert!(kept < applied as usize, "{kept} of {applied} kept");

        // A late joiner cannot replay a compacted history; it continues from the state.
        let mut joiner = World::new(&level, settings(), 4).unwrap();
        joiner.resync(&small.state()).unwrap();
        for t in 1200..1300u32 {
            let inputs: Vec<Input> = (0..4).map(|p| input(p, t)).collect();
            small.step(&inputs).unwrap();
            joiner.step(&inputs).unwrap();
            assert_eq!(small.state_hash(), joiner.state_hash(), "tick {t}");
        }
    }
}
