//! Collision against the terrain as a system parameter, for game code outside the
//! simulation (AI line of sight, cursor picking, effects): the library's deterministic
//! queries on the current terrain of the match.

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use craterfield::field2d::query::{
    CapsuleOptions, Contact, QueryError, RayHit, RayOptions, SweepHit, contact_capsule,
    contact_circle, raycast, sweep_circle,
};
use craterfield::field2d::{Sample, Sdf};
use thiserror::Error;

use crate::world::Craterfield;

/// Why a [`TerrainQuery`] has no answer.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
#[non_exhaustive]
pub enum TerrainQueryError {
    /// No match is running (the [`Craterfield`] resource is absent).
    #[error("no match is running: the Craterfield resource is absent")]
    NoMatch,
    /// The query refused its arguments (non-finite, zero direction, budget).
    #[error("{0}")]
    Query(#[from] QueryError),
    /// A point had a non-finite coordinate.
    #[error("the point {0} is not finite")]
    NonFinitePoint(Vec2),
}

/// The terrain of the running match, queried from any system:
///
/// ```no_run
/// # use bevy::prelude::*;
/// # use craterfield_bevy::prelude::*;
/// fn line_of_sight(terrain: TerrainQuery) {
///     let blocked = terrain
///         .raycast(Vec2::new(0.0, 300.0), Vec2::new(1.0, -0.2), 800.0)
///         .ok()
///         .flatten()
///         .is_some();
///     info!("blocked: {blocked}");
/// }
/// ```
#[derive(SystemParam)]
pub struct TerrainQuery<'w> {
    craterfield: Option<Res<'w, Craterfield>>,
}

impl TerrainQuery<'_> {
    fn field(
        &self,
    ) -> Result<&craterfield::field2d::Terrain<craterfield::field2d::Graph>, TerrainQueryError>
    {
        self.craterfield
            .as_deref()
            .map(|c| c.world().terrain())
            .ok_or(TerrainQueryError::NoMatch)
    }

    /// Whether a match is running.
    pub fn is_ready(&self) -> bool {
        self.craterfield.is_some()
    }

    /// The first hit of a ray from `origin` along `dir` within `max_t` (default options).
    pub fn raycast(
        &self,
        origin: Vec2,
        dir: Vec2,
        max_t: f32,
    ) -> Result<Option<RayHit>, TerrainQueryError> {
        Ok(raycast(
            self.field()?,
            origin,
            dir,
            max_t,
            &RayOptions::default(),
        )?)
    }

    /// The first contact of a circle of `radius` moving from `from` to `to`.
    pub fn sweep_circle(
        &self,
        from: Vec2,
        to: Vec2,
        radius: f32,
    ) -> Result<Option<SweepHit>, TerrainQueryError> {
        Ok(sweep_circle(
            self.field()?,
            from,
            to,
            radius,
            &RayOptions::default(),
        )?)
    }

    /// The signed distance at `p` (negative inside the terrain).
    pub fn distance(&self, p: Vec2) -> Result<f32, TerrainQueryError> {
        let field = self.field()?;
        check_point(p)?;
        Ok(field.distance(p))
    }

    /// Distance, gradient and material at `p`.
    pub fn sample(&self, p: Vec2) -> Result<Sample, TerrainQueryError> {
        let field = self.field()?;
        check_point(p)?;
        Ok(field.sample(p))
    }

    /// Whether `p` is inside the terrain.
    pub fn is_solid(&self, p: Vec2) -> Result<bool, TerrainQueryError> {
        Ok(self.distance(p)? < 0.0)
    }

    /// The contact of a circle at `center`, if it overlaps the terrain.
    pub fn contact_circle(
        &self,
        center: Vec2,
        radius: f32,
    ) -> Result<Option<Contact>, TerrainQueryError> {
        Ok(contact_circle(self.field()?, center, radius)?)
    }

    /// The deepest contact of the capsule `a-b` of `radius`, if it overlaps the terrain.
    pub fn contact_capsule(
        &self,
        a: Vec2,
        b: Vec2,
        radius: f32,
    ) -> Result<Option<Contact>, TerrainQueryError> {
        Ok(contact_capsule(
            self.field()?,
            a,
            b,
            radius,
            &CapsuleOptions::default(),
        )?)
    }
}

fn check_point(p: Vec2) -> Result<(), TerrainQueryError> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(TerrainQueryError::NonFinitePoint(p))
    }
}
