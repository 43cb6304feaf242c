//! The human player's input from the keyboard and the pointer: A/D or the arrows drive,
//! W or up jumps, space fires, S toggles stick mode, Q switches weapon, and the pointer
//! aims (its distance from the vehicle sets the power).

use craterfield::sim::{Input, buttons};
use glam::Vec2;

/// Pointer distance, world units, that means full power.
const FULL_POWER_DISTANCE: f32 = 700.0;

/// What the keyboard holds this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Keys {
    /// Drive towards -x.
    pub(super) left: bool,
    /// Drive towards +x.
    pub(super) right: bool,
    /// Jump.
    pub(super) jump: bool,
    /// Fire.
    pub(super) fire: bool,
    /// Stick mode toggle (acts on the press).
    pub(super) stick: bool,
}

impl Keys {
    /// Reads the held keys from egui's input.
    pub(super) fn read(input: &egui::InputState) -> Keys {
        use egui::Key;
        let down = |keys: &[Key]| keys.iter().any(|&k| input.key_down(k));
        Keys {
            left: down(&[Key::A, Key::ArrowLeft]),
            right: down(&[Key::D, Key::ArrowRight]),
            jump: down(&[Key::W, Key::ArrowUp]),
            fire: down(&[Key::Space]),
            stick: down(&[Key::S]),
        }
    }
}

/// The input for `keys`, aiming from `vehicle` at `pointer` (world) with `weapon`.
pub(super) fn human_input(
    keys: Keys,
    vehicle: Option<Vec2>,
    pointer: Option<Vec2>,
    weapon: u8,
) -> Input {
    let drive = match (keys.left, keys.right) {
        (true, false) => -127,
        (false, true) => 127,
        _ => 0,
    };
    let mut bits = 0;
    for (held, bit) in [
        (keys.fire, buttons::FIRE),
        (keys.jump, buttons::JUMP),
        (keys.stick, buttons::STICK),
    ] {
        if held {
            bits |= bit;
        }
    }
    let (aim, power) = match (vehicle, pointer) {
        (Some(v), Some(p)) if (p - v).length() > 1.0 => {
            let d = p - v;
            let degrees = d.y.atan2(d.x).to_degrees();
            let power = (d.length() / FULL_POWER_DISTANCE * 255.0).clamp(20.0, 255.0) as u8;
            (Input::aim_from_degrees(degrees), power)
        }
        _ => (Input::aim_from_degrees(45.0), 160),
    };
    Input {
        aim,
        buttons: bits,
        drive,
        power,
        weapon,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_pointer_make_the_input() {
        let keys = Keys {
            right: true,
            fire: true,
            ..Keys::default()
        };
        let i = human_input(keys, Some(Vec2::ZERO), Some(Vec2::new(0.0, 350.0)), 1);
        assert_eq!(i.drive, 127);
        assert!(i.held(buttons::FIRE) && !i.held(buttons::JUMP));
        assert_eq!(i.aim, 16384, "straight up");
        assert_eq!(i.power, 127);
        assert_eq!(i.weapon, 1);
        assert!(i.validate().is_ok());
    }
}
