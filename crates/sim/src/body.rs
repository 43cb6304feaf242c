//! Bodies: vehicles, projectiles and debris, and the canonical bytes the state hash reads.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use craterfield_field::Sample;

/// The field sample at one of a body's probe points, kept while the point stays where it
/// is and the terrain there does not change: a body at rest re-reads it instead of
/// evaluating the field again. Derived data, not state: never hashed, and a hit gives
/// exactly the bits a fresh evaluation would.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeCache {
    /// The probe point.
    pub point: Vec2,
    /// The terrain's region stamp there when sampled.
    pub stamp: u64,
    /// The sample.
    pub sample: Sample,
}

impl ProbeCache {
    /// Whether the cached sample is the field at `point` with the terrain at `stamp`.
    pub fn holds(&self, point: Vec2, stamp: u64) -> bool {
        self.stamp == stamp
            && self.point.x.to_bits() == point.x.to_bits()
            && self.point.y.to_bits() == point.y.to_bits()
    }
}

/// What a body is, with the state that only that kind has.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum BodyKind {
    /// A player's vehicle.
    Vehicle {
        /// The player driving it.
        player: u8,
        /// The buttons of the previous tick (presses act on edges).
        prev_buttons: u8,
        /// Ticks until the vehicle may fire again.
        cooldown: u16,
        /// Stick mode: cling to walls and undersides.
        stick: bool,
    },
    /// A projectile in flight.
    Projectile {
        /// The player who fired it.
        owner: u8,
        /// Its weapon index (see [`crate::Settings::weapon`]).
        weapon: u8,
    },
    /// A passive body (rubble, crates, bench loads): collides and is pushed, no input.
    Debris,
}

/// One rigid body: a circle, or a capsule (a segment of half-length `half_length` along
/// `axis`, thickened by `radius`). Rotation is not simulated: a grounded capsule's axis
/// follows the surface.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Body {
    /// Unique within a world, never reused.
    pub id: u32,
    /// Kind and kind-specific state.
    pub kind: BodyKind,
    /// Centre.
    pub pos: Vec2,
    /// Velocity, units per second.
    pub vel: Vec2,
    /// Unit direction of the capsule's segment (`+x` for circles).
    pub axis: Vec2,
    /// Rounding radius.
    pub radius: f32,
    /// Half the segment's length; 0 for a circle.
    pub half_length: f32,
    /// `1 / mass`.
    pub inv_mass: f32,
    /// Coulomb friction coefficient.
    pub friction: f32,
    /// Restitution of bounces.
    pub restitution: f32,
    /// Remaining health; the body is removed when it reaches 0 (vehicles only).
    pub health: i32,
    /// Throttle target along the surface, units per second (vehicles).
    pub drive: f32,
    /// Unit normal of the surface under the body, zero when airborne.
    pub ground: Vec2,
    /// Unit normal of the nearest surface at the last contact check (zero when unknown).
    pub surface: Vec2,
    /// Clearance to the terrain at the last contact check (`+inf`-like when far).
    pub clearance: f32,
    /// Samples of the last contact check, per probe point (see `ProbeCache`).
    #[serde(skip)]
    pub probes: [Option<ProbeCache>; 2],
}

impl Body {
    /// A unit-mass circle at rest at `pos`, frictionless and without bounce, with 1 health
    /// and no contact history; the kinds' constructors change what differs.
    pub fn new(id: u32, kind: BodyKind, pos: Vec2, radius: f32) -> Body {
        Body {
            id,
            kind,
            pos,
            vel: Vec2::ZERO,
            axis: Vec2::X,
            radius,
            half_length: 0.0,
            inv_mass: 1.0,
            friction: 0.0,
            restitution: 0.0,
            health: 1,
            drive: 0.0,
            ground: Vec2::ZERO,
            surface: Vec2::ZERO,
            clearance: f32::MAX,
            probes: [None; 2],
        }
    }

    /// The two ends of the body's segment (equal for a circle).
    pub fn segment(&self) -> (Vec2, Vec2) {
        let h = self.axis * self.half_length;
        (self.pos - h, self.pos + h)
    }

    /// Whether the body is a player's vehicle.
    pub fn player(&self) -> Option<u8> {
        match self.kind {
            BodyKind::Vehicle { player, .. } => Some(player),
            _ => None,
        }
    }

    /// Whether the body is a projectile.
    pub fn is_projectile(&self) -> bool {
        matches!(self.kind, BodyKind::Projectile { .. })
    }

    /// Radius of a disc around `pos` that holds the whole body.
    pub fn bounding_radius(&self) -> f32 {
        self.radius + self.half_length
    }
}
