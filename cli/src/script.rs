//! Scripted matches: seeded, deterministic "players" that drive around, turn their aim
//! towards an opponent (or somewhere random), fire shells and dirt, jump and toggle stick
//! mode, recorded into a replay as they are played.
//!
//! The script looks at the world to choose its inputs (where the opponents are, whether a
//! vehicle may fire), but only the inputs go into the replay: re-simulating them gives
//! the same match whatever the script would do.

use craterfield::field2d::Event;
use craterfield::field2d::Level;
use craterfield::net::{Recorder, Replay};
use craterfield::sim::units;
use craterfield::sim::{BodyKind, Input, Settings, World, buttons, level_hash};

use crate::rng::Rng;

/// The most the aim turns in one tick while a player lines up a shot (about 2.2 degrees).
const AIM_STEP: u16 = 400;

/// A shot being lined up: the aim turns towards `aim`, then the player fires.
#[derive(Clone, Copy)]
struct Plan {
    aim: u16,
    power: u8,
    weapon: u8,
}

/// The scripted players of one match.
pub(crate) struct Script {
    rng: Rng,
    held: Vec<Input>,
    plans: Vec<Option<Plan>>,
}

impl Script {
    /// A script for `players` players; the same seed gives the same match.
    pub(crate) fn new(seed: u64, players: usize) -> Script {
        Script {
            rng: Rng::new(seed),
            held: vec![Input::default(); players],
            plans: vec![None; players],
        }
    }

    /// The inputs of the next tick of `world`, one per player.
    pub(crate) fn next_row(&mut self, world: &World) -> Vec<Input> {
        let settings = *world.settings();
        let mut row = Vec::with_capacity(self.held.len());
        for p in 0..self.held.len() {
            let input = self.player(world, &settings, p);
            row.push(input);
        }
        row
    }

    fn player(&mut self, world: &World, settings: &Settings, p: usize) -> Input {
        let rng = &mut self.rng;
        let held = &mut self.held[p];
        let Some(me) = world.vehicle(p as u8) else {
            // A destroyed vehicle's player lets go of everything.
            *held = Input::default();
            return *held;
        };
        // Buttons are pressed for one tick at a time (they act on the press).
        held.buttons = 0;
        if rng.unit() < 1.0 / 45.0 {
            let r = rng.unit();
            held.drive = if r < 0.25 {
                0
            } else {
                (rng.range(-127.0, 127.0) as i8).max(-127)
            };
        }
        if rng.unit() < 1.0 / 150.0 {
            held.buttons |= buttons::JUMP;
        }
        if rng.unit() < 1.0 / 400.0 {
            held.buttons |= buttons::STICK;
        }
        let cooldown = match me.kind {
            BodyKind::Vehicle { cooldown, .. } => cooldown,
            _ => 0,
        };
        if self.plans[p].is_none() && cooldown == 0 && rng.unit() < 1.0 / 20.0 {
            let weapon = u8::from(rng.unit() < 0.25);
            let opponents: Vec<glam::Vec2> = world
                .bodies()
                .iter()
                .filter(|b| b.player().is_some_and(|q| usize::from(q) != p))
                .map(|b| b.pos)
                .collect();
            let plan = if opponents.is_empty() || rng.unit() < 0.25 {
                // Somewhere into the sky, at a random power.
                Plan {
                    aim: Input::aim_from_degrees(rng.range(20.0, 160.0)),
                    power: rng.range(90.0, 255.0) as u8,
                    weapon,
                }
            } else {
                let target = opponents[(rng.next_u64() % opponents.len() as u64) as usize];
                let speed = settings.weapon(weapon).map_or(1.0, |w| units(w.speed));
                lob(
                    target - me.pos,
                    units(settings.gravity),
                    speed,
                    rng.range(-6.0, 6.0),
                    rng.range(0.9, 1.1),
                    weapon,
                )
            };
            self.plans[p] = Some(plan);
        }
        if let Some(plan) = self.plans[p] {
            let diff = plan.aim.wrapping_sub(held.aim) as i16;
            if diff == 0 {
                held.power = plan.power;
                held.weapon = plan.weapon;
                held.buttons |= buttons::FIRE;
                self.plans[p] = None;
            } else {
                let step = diff.clamp(-(AIM_STEP as i16), AIM_STEP as i16);
                held.aim = held.aim.wrapping_add(step as u16);
            }
        }
        *held
    }
}

/// A 45-degree lob towards `offset` (target minus shooter), with the aim off by
/// `jitter_deg` and the power scaled by `power_scale`.
fn lob(
    offset: glam::Vec2,
    gravity: f32,
    speed: f32,
    jitter_deg: f32,
    power_scale: f32,
    weapon: u8,
) -> Plan {
    let dx = offset.x.abs().max(1.0);
    // A 45-degree shot lands `dy` higher after `dx` when v^2 = g dx^2 / (dx - dy).
    let denom = dx - offset.y;
    let needed = if denom > 1.0 {
        (gravity * dx * dx / denom).sqrt()
    } else {
        speed
    };
    let degrees = if offset.x >= 0.0 { 45.0 } else { 135.0 } + jitter_deg;
    Plan {
        aim: Input::aim_from_degrees(degrees),
        power: (needed / speed * 255.0 * power_scale).clamp(40.0, 255.0) as u8,
        weapon,
    }
}

/// A played and recorded match.
pub(crate) struct Played {
    /// The world after the last tick.
    pub world: World,
    /// The recording.
    pub replay: Replay,
    /// Shots fired (fire presses).
    pub shots: usize,
}

impl Played {
    /// The terrain events the match produced (it started from the pristine level).
    pub(crate) fn events(&self) -> &[Event] {
        self.world.terrain().events()
    }
}

/// Plays `ticks` ticks of a scripted match on `level`, recording a state hash every
/// `hash_interval` ticks.
pub(crate) fn play(
    level: &Level,
    settings: Settings,
    players: u8,
    ticks: u32,
    seed: u64,
    hash_interval: u32,
) -> Result<Played, String> {
    let mut world =
        World::new(level, settings, usize::from(players)).map_err(|e| format!("match: {e}"))?;
    let mut recorder = Recorder::new(level_hash(level), settings, players, hash_interval)
        .map_err(|e| format!("match recorder: {e}"))?;
    let mut script = Script::new(seed, usize::from(players));
    let mut shots = 0;
    for _ in 0..ticks {
        let row = script.next_row(&world);
        shots += row
            .iter()
            .filter(|i| i.buttons & buttons::FIRE != 0)
            .count();
        world
            .step(&row)
            .map_err(|e| format!("match tick {}: {e}", world.tick() + 1))?;
        recorder
            .record(&row, world.tick(), world.state_hash())
            .map_err(|e| format!("match tick {}: {e}", world.tick()))?;
    }
    let replay = recorder.finish(world.tick(), world.state_hash());
    Ok(Played {
        world,
        replay,
        shots,
    })
}
