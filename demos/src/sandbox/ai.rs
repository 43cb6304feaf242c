//! The scripted opponents: each drives towards the human's vehicle until it is in range,
//! then lobs shells at it on a fixed rhythm. Purely a function of the world, so a replay
//! needs only the inputs it produced.

use craterfield::sim::{Input, Settings, World, buttons, units};
use glam::Vec2;

/// Distance within which an opponent stops and fires.
const RANGE: f32 = 900.0;

/// Ticks between two shots of one opponent.
const FIRE_EVERY: u32 = 150;

/// The input of opponent `player` this tick.
pub(super) fn opponent_input(world: &World, player: u8) -> Input {
    let (Some(me), Some(target)) = (world.vehicle(player), world.vehicle(0)) else {
        return Input::default();
    };
    let to = target.pos - me.pos;
    let drive = if to.x.abs() > RANGE {
        if to.x > 0.0 { 90 } else { -90 }
    } else {
        0
    };
    let (aim, power) = lob(world.settings(), to);
    // Opponents fire in turn, not all on the same tick.
    let phase = u32::from(player) * 47;
    let fire = (world.tick() + phase).is_multiple_of(FIRE_EVERY) && to.length() <= RANGE * 1.5;
    Input {
        aim,
        buttons: if fire { buttons::FIRE } else { 0 },
        drive,
        power,
        weapon: 0,
    }
}

/// A 45° lob whose range, without drag or wind, reaches `to` horizontally.
fn lob(settings: &Settings, to: Vec2) -> (u16, u8) {
    let degrees = if to.x >= 0.0 { 45.0 } else { 135.0 };
    let g = units(settings.gravity).max(1.0);
    let top = units(settings.shell.speed).max(1.0);
    // Range of a 45° launch at speed v is v² / g.
    let speed = (to.x.abs().max(50.0) * g).sqrt();
    let power = (speed / top * 255.0).clamp(30.0, 255.0) as u8;
    (Input::aim_from_degrees(degrees), power)
}
