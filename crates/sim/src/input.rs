//! One player's input for one tick: a small `Copy` value that crosses the network and files.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Button bits of [`Input::buttons`]. Fire, jump and stick act on the tick a bit goes
/// from 0 to 1 (holding a button does not repeat it).
pub mod buttons {
    /// Launch a projectile of the selected weapon along the aim, at the given power.
    pub const FIRE: u8 = 1 << 0;
    /// Jump off the surface the vehicle stands on.
    pub const JUMP: u8 = 1 << 1;
    /// Toggle stick mode (cling to walls and undersides).
    pub const STICK: u8 = 1 << 2;
    /// Every defined bit; the others must be zero.
    pub const ALL: u8 = FIRE | JUMP | STICK;
}

/// Number of weapons ([`Input::weapon`] must be below it).
pub(crate) const WEAPON_COUNT: u8 = 2;

/// What a player does during one tick.
///
/// Six bytes, all integers, so it is exact on every machine and cheap to send every tick.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[repr(C)]
pub struct Input {
    /// Aim angle in 1/65536 of a turn, counter-clockwise from `+x` (16384 is straight up).
    pub aim: u16,
    /// Bits from [`buttons`].
    pub buttons: u8,
    /// Throttle along the ground, `-127..=127` (negative drives towards `-x` on a floor).
    pub drive: i8,
    /// Launch power, `0..=255` of the weapon's top speed.
    pub power: u8,
    /// The weapon fired by [`buttons::FIRE`]: 0 = shell (carves), 1 = dirt (fills).
    pub weapon: u8,
}

const _: () = assert!(std::mem::size_of::<Input>() == 6);

/// Why an input was rejected (only inputs from outside, such as replays and the network,
/// are checked; the simulation treats an invalid input as "do nothing").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum InputError {
    /// A reserved button bit is set.
    #[error(
        "input buttons {buttons:#010b} set reserved bits (allowed: {:#010b})",
        buttons::ALL
    )]
    ReservedButtons {
        /// The offending byte.
        buttons: u8,
    },
    /// The weapon index is unknown.
    #[error("input weapon {weapon} is unknown (there are {WEAPON_COUNT})")]
    UnknownWeapon {
        /// The offending index.
        weapon: u8,
    },
    /// The throttle is -128 (the range is symmetric: -127..=127).
    #[error("input drive -128 is out of range (-127..=127)")]
    DriveOutOfRange,
}

impl Input {
    /// Whether `bit` (from [`buttons`]) is held.
    pub fn held(self, bit: u8) -> bool {
        self.buttons & bit != 0
    }

    /// Whether `bit` is held now but was not in `previous`.
    pub fn pressed(self, previous: Input, bit: u8) -> bool {
        self.held(bit) && !previous.held(bit)
    }

    /// Checks the fields' ranges.
    pub fn validate(self) -> Result<Input, InputError> {
        if self.buttons & !buttons::ALL != 0 {
            return Err(InputError::ReservedButtons {
                buttons: self.buttons,
            });
        }
        if self.weapon >= WEAPON_COUNT {
            return Err(InputError::UnknownWeapon {
                weapon: self.weapon,
            });
        }
        if self.drive == i8::MIN {
            return Err(InputError::DriveOutOfRange);
        }
        Ok(self)
    }

    /// The input as the simulation uses it: an invalid one becomes the empty input.
    pub fn sanitized(self) -> Input {
        self.validate().unwrap_or_default()
    }

    /// The six bytes of the input in a fixed order (aim little-endian first).
    pub fn to_bytes(self) -> [u8; 6] {
        let a = self.aim.to_le_bytes();
        [
            a[0],
            a[1],
            self.buttons,
            self.drive as u8,
            self.power,
            self.weapon,
        ]
    }

    /// The inverse of [`Input::to_bytes`] (no validation).
    pub fn from_bytes(b: [u8; 6]) -> Input {
        Input {
            aim: u16::from_le_bytes([b[0], b[1]]),
            buttons: b[2],
            drive: b[3] as i8,
            power: b[4],
            weapon: b[5],
        }
    }

    /// Aim angle in turns, `[0, 1)`, exact in `f32`.
    pub fn aim_turns(self) -> f32 {
        f32::from(self.aim) / 65536.0
    }

    /// The aim for an angle in degrees (counter-clockwise from `+x`), rounded to the
    /// nearest representable step.
    pub fn aim_from_degrees(degrees: f32) -> u16 {
        let turns = (degrees / 360.0).rem_euclid(1.0);
        ((turns * 65536.0).round() as u32 & 0xffff) as u16
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_round_trip_and_validation_names_the_field() {
        let i = Input {
            aim: 0xbeef,
            buttons: buttons::FIRE | buttons::STICK,
            drive: -5,
            power: 200,
            weapon: 1,
        };
        assert_eq!(Input::from_bytes(i.to_bytes()), i);
        assert_eq!(i.validate(), Ok(i));
        let bad = Input { buttons: 0x80, ..i };
        assert!(bad.validate().unwrap_err().to_string().contains("reserved"));
        assert_eq!(bad.sanitized(), Input::default());
        let bad = Input { weapon: 9, ..i };
        assert!(bad.validate().unwrap_err().to_string().contains("weapon 9"));
        let bad = Input { drive: -128, ..i };
        assert_eq!(bad.validate(), Err(InputError::DriveOutOfRange));
    }

    #[test]
    fn edges_and_aim() {
        let held = Input {
            buttons: buttons::FIRE,
            ..Input::default()
        };
        assert!(held.pressed(Input::default(), buttons::FIRE));
        assert!(!held.pressed(held, buttons::FIRE));
        assert_eq!(Input::aim_from_degrees(90.0), 16384);
        assert_eq!(Input::aim_from_degrees(-90.0), 49152);
        assert_eq!(Input::aim_from_degrees(360.0), 0);
    }
}
