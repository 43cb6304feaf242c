//! Axis-aligned bounding boxes of solid regions, with infinite extents where a node is
//! unbounded.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use craterfield_core::det::math::{max, min};

/// An axis-aligned box `min ..= max`; components may be infinite. Empty when `min > max` on
/// some axis.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec2,
    /// Upper corner.
    pub max: Vec2,
}

impl Aabb {
    /// The whole plane.
    pub const EVERYTHING: Aabb = Aabb {
        min: Vec2::NEG_INFINITY,
        max: Vec2::INFINITY,
    };
    /// Nothing.
    pub const EMPTY: Aabb = Aabb {
        min: Vec2::INFINITY,
        max: Vec2::NEG_INFINITY,
    };

    /// A box from corners.
    pub fn new(min: Vec2, max: Vec2) -> Aabb {
        Aabb { min, max }
    }

    /// The box of a centre and half extents.
    pub fn centered(c: Vec2, half: Vec2) -> Aabb {
        Aabb {
            min: c - half,
            max: c + half,
        }
    }

    /// The box around a set of points.
    pub fn of_points(pts: impl IntoIterator<Item = Vec2>) -> Aabb {
        pts.into_iter().fold(Aabb::EMPTY, |b, p| Aabb {
            min: Vec2::new(min(b.min.x, p.x), min(b.min.y, p.y)),
            max: Vec2::new(max(b.max.x, p.x), max(b.max.y, p.y)),
        })
    }

    /// True when it holds no point.
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y)
    }

    /// True when all four bounds are finite.
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// Smallest box holding both.
    pub fn union(&self, o: &Aabb) -> Aabb {
        if self.is_empty() {
            return *o;
        }
        if o.is_empty() {
            return *self;
        }
        Aabb {
            min: Vec2::new(min(self.min.x, o.min.x), min(self.min.y, o.min.y)),
            max: Vec2::new(max(self.max.x, o.max.x), max(self.max.y, o.max.y)),
        }
    }

    /// Overlap of both (possibly empty).
    pub fn intersection(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: Vec2::new(max(self.min.x, o.min.x), max(self.min.y, o.min.y)),
            max: Vec2::new(min(self.max.x, o.max.x), min(self.max.y, o.max.y)),
        }
    }

    /// Grown by `r` on every side.
    pub fn expand(&self, r: f32) -> Aabb {
        if self.is_empty() {
            return *self;
        }
        Aabb {
            min: self.min - Vec2::splat(r),
            max: self.max + Vec2::splat(r),
        }
    }

    /// Moved by `t`.
    pub fn translate(&self, t: Vec2) -> Aabb {
        if self.is_empty() {
            return *self;
        }
        Aabb {
            min: self.min + t,
            max: self.max + t,
        }
    }

    /// Scaled about the origin by `s > 0`.
    pub fn scale(&self, s: f32) -> Aabb {
        if self.is_empty() {
            return *self;
        }
        Aabb {
            min: self.min * s,
            max: self.max * s,
        }
    }

    /// The box around this box rotated about the origin (everything if it is unbounded).
    pub fn rotate(&self, cos: f32, sin: f32) -> Aabb {
        if self.is_empty() {
            return *self;
        }
        if !self.is_finite() {
            return Aabb::EVERYTHING;
        }
        let corners = [
            self.min,
            Vec2::new(self.max.x, self.min.y),
            self.max,
            Vec2::new(self.min.x, self.max.y),
        ];
        Aabb::of_points(corners.map(|c| Vec2::new(cos * c.x - sin * c.y, sin * c.x + cos * c.y)))
    }

    /// True when the point lies inside or on the box.
    pub fn contains(&self, p: Vec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
}
