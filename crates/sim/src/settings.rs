//! Match settings: every number the simulation depends on, as integers.
//!
//! Settings travel in replay headers and between peers, so (like events) they are fixed
//! point ([`craterfield_core::det::quant`], 1/256 world unit) and convert exactly to `f32` on
//! every machine. Speeds are world units per second, accelerations units per second².

use serde::{Deserialize, Serialize};
use thiserror::Error;

use craterfield_core::det::quant::{self, FIXED_MAX, FIXED_ONE};

/// A fixed-point number (1/256 unit) as settings store it.
pub(crate) type Fixed = i32;

/// A vehicle's chassis and handling.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct VehicleSettings {
    /// Chassis radius (circle, or the capsule's rounding).
    pub radius: Fixed,
    /// Half the capsule's straight part; 0 makes the chassis a circle.
    pub half_length: Fixed,
    /// Mass (arbitrary units; impulses divide by it).
    pub mass: Fixed,
    /// Coulomb friction coefficient against the terrain and other bodies.
    pub friction: Fixed,
    /// Restitution: the fraction of the approach speed a bounce returns.
    pub restitution: Fixed,
    /// Top driving speed along the surface.
    pub drive_speed: Fixed,
    /// Launch speed of a jump, along the surface normal.
    pub jump_speed: Fixed,
    /// Starting health.
    pub health: i32,
}

/// One weapon: the projectile and what its impact does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct WeaponSettings {
    /// Projectile radius.
    pub radius: Fixed,
    /// Launch speed at full power.
    pub speed: Fixed,
    /// Radius of the crater (carving weapons) or of the added disc (filling weapons).
    pub crater_radius: Fixed,
    /// Whether the impact adds terrain (true) or carves it (false).
    pub fills: bool,
    /// Material of added terrain.
    pub material: u16,
    /// Radius within which bodies are pushed and damaged.
    pub blast_radius: Fixed,
    /// Speed change given to a body of unit mass at the blast centre; falls off linearly to
    /// zero at `blast_radius`.
    pub impulse: Fixed,
    /// Damage at the blast centre; falls off linearly to zero at `blast_radius`.
    pub damage: i32,
    /// Ticks between two shots of the same player.
    pub cooldown_ticks: u16,
}

/// Everything that parameterises a match.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Settings {
    /// Ticks per second.
    pub tick_hz: u16,
    /// Gravity (downwards, `-y`).
    pub gravity: Fixed,
    /// Wind acceleration on projectiles, `[x, y]`.
    pub wind: [Fixed; 2],
    /// Within this clearance of a surface, a vehicle in stick mode is pulled towards it
    /// along the field gradient instead of falling.
    pub stick_range: Fixed,
    /// The fastest any body may move. Projectiles never tunnel at any speed up to it.
    pub max_speed: Fixed,
    /// The vehicles.
    pub vehicle: VehicleSettings,
    /// Weapon 0: the shell (carves).
    pub shell: WeaponSettings,
    /// Weapon 1: dirt (fills).
    pub dirt: WeaponSettings,
    /// Most bodies alive at once (at most 65,536); shots beyond it are dropped. It also
    /// bounds one tick's body-body work: 32 candidate pair tests per body allowed.
    pub max_bodies: u32,
    /// How many ticks back a snapshot can be restored (the terrain's undo journal keeps
    /// this much history).
    pub rollback_ticks: u32,
}

const fn fx(units: i32) -> Fixed {
    units * FIXED_ONE
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tick_hz: 60,
            gravity: fx(600),
            wind: [fx(20), 0],
            stick_range: fx(12),
            max_speed: fx(3000),
            vehicle: VehicleSettings {
                radius: fx(10),
                half_length: fx(8),
                mass: fx(1),
                friction: FIXED_ONE * 9 / 10,
                restitution: FIXED_ONE / 10,
                drive_speed: fx(120),
                jump_speed: fx(260),
                health: 100,
            },
            shell: WeaponSettings {
                radius: fx(2),
                speed: fx(900),
                crater_radius: fx(40),
                fills: false,
                material: 0,
                blast_radius: fx(80),
                impulse: fx(500),
                damage: 40,
                cooldown_ticks: 30,
            },
            dirt: WeaponSettings {
                radius: fx(3),
                speed: fx(700),
                crater_radius: fx(30),
                fills: true,
                material: 0,
                blast_radius: fx(40),
                impulse: fx(150),
                damage: 0,
                cooldown_ticks: 30,
            },
            max_bodies: 20_000,
            rollback_ticks: 128,
        }
    }
}

/// Why settings were rejected.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum SettingsError {
    /// A value is outside its accepted range.
    #[error("setting {name} = {value} is invalid: {reason}")]
    OutOfRange {
        /// The setting's path (`vehicle.radius`, ...).
        name: &'static str,
        /// The raw value.
        value: i64,
        /// What it must satisfy.
        reason: &'static str,
    },
}

fn check(
    name: &'static str,
    value: i64,
    ok: bool,
    reason: &'static str,
) -> Result<(), SettingsError> {
    if ok {
        Ok(())
    } else {
        Err(SettingsError::OutOfRange {
            name,
            value,
            reason,
        })
    }
}

fn positive(name: &'static str, v: Fixed, max: Fixed) -> Result<(), SettingsError> {
    check(
        name,
        v.into(),
        v > 0 && v <= max,
        "must be positive and within the limit",
    )
}

fn non_negative(name: &'static str, v: Fixed, max: Fixed) -> Result<(), SettingsError> {
    check(
        name,
        v.into(),
        (0..=max).contains(&v),
        "must be >= 0 and within the limit",
    )
}

impl WeaponSettings {
    fn validate(&self, prefix: &'static [&'static str; 8]) -> Result<(), SettingsError> {
        positive(prefix[0], self.radius, fx(32))?;
        positive(prefix[1], self.speed, FIXED_MAX)?;
        positive(prefix[2], self.crater_radius, fx(512))?;
        non_negative(prefix[3], self.blast_radius, fx(2048))?;
        non_negative(prefix[4], self.impulse, FIXED_MAX)?;
        check(
            prefix[5],
            self.damage.into(),
            (0..=1_000_000).contains(&self.damage),
            "must be 0..=1000000",
        )?;
        check(
            prefix[6],
            self.cooldown_ticks.into(),
            self.cooldown_ticks >= 1,
            "must be at least 1",
        )?;
        check(prefix[7], self.material.into(), true, "")
    }
}

impl Settings {
    /// Checks every value's range (all are then exact in `f32`).
    pub fn validate(&self) -> Result<(), SettingsError> {
        check(
            "tick_hz",
            self.tick_hz.into(),
            (1..=1000).contains(&self.tick_hz),
            "must be 1..=1000",
        )?;
        non_negative("gravity", self.gravity, fx(100_000).min(FIXED_MAX))?;
        for (name, w) in [("wind.x", self.wind[0]), ("wind.y", self.wind[1])] {
            check(
                name,
                w.into(),
                quant::in_range(w),
                "must be within the fixed-point range",
            )?;
        }
        non_negative("stick_range", self.stick_range, fx(256))?;
        positive("max_speed", self.max_speed, FIXED_MAX)?;
        let v = &self.vehicle;
        positive("vehicle.radius", v.radius, fx(256))?;
        non_negative("vehicle.half_length", v.half_length, fx(256))?;
        positive("vehicle.mass", v.mass, FIXED_MAX)?;
        non_negative("vehicle.friction", v.friction, fx(16))?;
        non_negative("vehicle.restitution", v.restitution, FIXED_ONE)?;
        non_negative("vehicle.drive_speed", v.drive_speed, FIXED_MAX)?;
        non_negative("vehicle.jump_speed", v.jump_speed, FIXED_MAX)?;
        check(
            "vehicle.health",
            v.health.into(),
            (1..=1_000_000).contains(&v.health),
            "must be 1..=1000000",
        )?;
        self.shell.validate(&[
            "shell.radius",
            "shell.speed",
            "shell.crater_radius",
            "shell.blast_radius",
            "shell.impulse",
            "shell.damage",
            "shell.cooldown_ticks",
            "shell.material",
        ])?;
        self.dirt.validate(&[
            "dirt.radius",
            "dirt.speed",
            "dirt.crater_radius",
            "dirt.blast_radius",
            "dirt.impulse",
            "dirt.damage",
            "dirt.cooldown_ticks",
            "dirt.material",
        ])?;
        check(
            "max_bodies",
            self.max_bodies.into(),
            (1..=65_536).contains(&self.max_bodies),
            "must be 1..=65536",
        )?;
        check(
            "rollback_ticks",
            self.rollback_ticks.into(),
            (1..=100_000).contains(&self.rollback_ticks),
            "must be 1..=100000",
        )
    }

    /// The weapon with index `w` (see [`crate::Input::weapon`]).
    pub fn weapon(&self, w: u8) -> Option<&WeaponSettings> {
        match w {
            0 => Some(&self.shell),
            1 => Some(&self.dirt),
            _ => None,
        }
    }

    /// Seconds per tick, `1 / tick_hz` rounded to `f32`.
    pub fn dt(&self) -> f32 {
        1.0 / f32::from(self.tick_hz.max(1))
    }
}

/// A fixed-point setting in world units (exact: validated settings are in range).
pub fn units(v: Fixed) -> f32 {
    quant::to_f32(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_errors_name_the_setting() {
        Settings::default().validate().unwrap();
        let mut s = Settings::default();
        s.vehicle.radius = 0;
        let e = s.validate().unwrap_err().to_string();
        assert!(e.contains("vehicle.radius = 0"), "{e}");
        let mut s = Settings::default();
        s.dirt.cooldown_ticks = 0;
        assert!(
            s.validate()
                .unwrap_err()
                .to_string()
                .contains("dirt.cooldown_ticks")
        );
        let s = Settings {
            tick_hz: 0,
            ..Settings::default()
        };
        assert!(s.validate().unwrap_err().to_string().contains("tick_hz"));
    }
}
