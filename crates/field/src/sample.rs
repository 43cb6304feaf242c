//! What a 2D field answers at one point: distance, gradient and material. Plain data below
//! every evaluator, so the interface ([`super::Sdf`]) and the tape compiler can both use it.

use glam::Vec2;

/// A material index into a level's palette.
pub type MaterialId = u16;

/// The field at one point: distance, analytic gradient, and the material that won there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Signed distance (negative inside solid terrain), exact or a bound (see the field).
    pub distance: f32,
    /// Gradient of `distance` at the point (unit length where the distance is exact and
    /// differentiable; zero where undefined, e.g. on a medial axis or in a clamped region).
    pub gradient: Vec2,
    /// Material of the nearest/winning surface.
    pub material: MaterialId,
}
