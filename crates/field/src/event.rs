//! Destruction events: carved and filled circles in fixed point, validated on construction.
//!
//! An [`Event`] is plain data (serializable, replayable). All lengths are fixed point
//! ([`craterfield_core::det::quant`], 1/256 world unit), so replays reproduce the same bits. The
//! constructors convert from world units and reject NaN, infinities, non-positive radii and
//! out-of-range values with an error naming the field and the value.

use glam::Vec2;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::sample::MaterialId;
use craterfield_core::det::quant::{self, QuantError};

/// What an event does to the terrain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EventKind {
    /// Removes a disc of terrain (an explosion). Keeps the material of what was there.
    Carve,
    /// Adds a disc of terrain made of the event's material.
    Fill,
}

/// One carve or fill, in fixed point (1/256 world unit, see [`quant`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Event {
    /// Carve or fill.
    pub kind: EventKind,
    /// Disc centre, fixed point.
    pub center: [i32; 2],
    /// Disc radius, fixed point, positive.
    pub radius: i32,
    /// Smooth blend width `k`, fixed point; 0 = sharp.
    pub rim: i32,
    /// Ticks the disc takes to grow to full radius; 0 = instant.
    pub grow_ticks: u16,
    /// The tick the event starts at; before it the event has no effect.
    pub tick: u32,
    /// Material painted by a fill where it wins (ignored by carves).
    pub material: MaterialId,
}

/// Why an event could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum EventError {
    /// A field could not be stored in fixed point (NaN, infinite or out of range).
    #[error("event {field} is invalid: {source}")]
    NotRepresentable {
        /// The field (`center.x`, `center.y`, `radius`, `rim`).
        field: &'static str,
        /// The conversion error, naming the value.
        source: QuantError,
    },
    /// The radius is zero or negative (after rounding to 1/256 world unit).
    #[error("event radius must be positive, got {value}")]
    NonPositiveRadius {
        /// The offending radius, world units.
        value: f32,
    },
    /// The rim (blend width) is negative.
    #[error("event rim must not be negative, got {value}")]
    NegativeRim {
        /// The offending rim, world units.
        value: f32,
    },
    /// A fixed-point field is outside `[-FIXED_MAX, FIXED_MAX]` (only reachable by building
    /// the struct by hand or deserializing it).
    #[error("event {field} = {value} (fixed point) is outside the fixed-point range")]
    FixedOutOfRange {
        /// The field.
        field: &'static str,
        /// The raw fixed-point value.
        value: i32,
    },
}

fn fixed(field: &'static str, x: f32) -> Result<i32, EventError> {
    quant::from_f32(x).map_err(|source| EventError::NotRepresentable { field, source })
}

impl Event {
    fn disc(
        kind: EventKind,
        center: Vec2,
        radius: f32,
        material: MaterialId,
    ) -> Result<Event, EventError> {
        let cx = fixed("center.x", center.x)?;
        let cy = fixed("center.y", center.y)?;
        let r = fixed("radius", radius)?;
        if r <= 0 {
            return Err(EventError::NonPositiveRadius { value: radius });
        }
        Ok(Event {
            kind,
            center: [cx, cy],
            radius: r,
            rim: 0,
            grow_ticks: 0,
            tick: 0,
            material,
        })
    }

    /// A sharp, instant carve of a disc (world units). Material is 0 (unused by carves).
    pub fn carve(center: Vec2, radius: f32) -> Result<Event, EventError> {
        Event::disc(EventKind::Carve, center, radius, 0)
    }

    /// A sharp, instant fill of a disc (world units) with `material`.
    pub fn fill(center: Vec2, radius: f32, material: MaterialId) -> Result<Event, EventError> {
        Event::disc(EventKind::Fill, center, radius, material)
    }

    /// The same event with a smooth blend of width `rim` world units (0 = sharp).
    pub fn with_rim(self, rim: f32) -> Result<Event, EventError> {
        let k = fixed("rim", rim)?;
        if k < 0 {
            return Err(EventError::NegativeRim { value: rim });
        }
        Ok(Event { rim: k, ..self })
    }

    /// The same event growing to full radius over `ticks` ticks (0 = instant).
    pub fn with_growth(self, ticks: u16) -> Event {
        Event {
            grow_ticks: ticks,
            ..self
        }
    }

    /// The same event starting at `tick`.
    pub fn at_tick(self, tick: u32) -> Event {
        Event { tick, ..self }
    }

    /// Centre in world units (exact for valid events).
    pub fn center_f32(&self) -> Vec2 {
        Vec2::new(quant::to_f32(self.center[0]), quant::to_f32(self.center[1]))
    }

    /// Full radius in world units (exact for valid events).
    pub fn radius_f32(&self) -> f32 {
        quant::to_f32(self.radius)
    }

    /// Blend width in world units (exact for valid events).
    pub fn rim_f32(&self) -> f32 {
        quant::to_f32(self.rim)
    }

    /// Whether the event blends sharply (`rim == 0`).
    pub fn is_sharp(&self) -> bool {
        self.rim == 0
    }

    /// The radius in effect at `tick`, or `None` where the event has no effect yet
    /// (`tick < self.tick`). Growing events reach `radius * (tick - self.tick + 1) / grow_ticks`
    /// and the full radius from `self.tick + grow_ticks` on.
    pub fn radius_at(&self, tick: u32) -> Option<f32> {
        self.radius_at_with(self.radius_f32(), tick)
    }

    /// [`Event::radius_at`] from the full radius `r` (`self.radius_f32()`, already
    /// converted).
    pub(crate) fn radius_at_with(&self, r: f32, tick: u32) -> Option<f32> {
        if tick < self.tick {
            return None;
        }
        let grow = u32::from(self.grow_ticks);
        let r_eff = if grow == 0 || tick >= self.tick.saturating_add(grow) {
            r
        } else {
            // tick - self.tick + 1 <= grow <= 65535: no overflow, exact in f32.
            let elapsed = tick - self.tick + 1;
            r * (elapsed as f32 / grow as f32)
        };
        if r_eff > 0.0 { Some(r_eff) } else { None }
    }

    /// Whether the event is at full radius at `tick` and stays so for every later tick.
    pub fn is_settled(&self, tick: u32) -> bool {
        tick >= self.tick.saturating_add(u32::from(self.grow_ticks))
    }

    /// Checks that the fixed-point fields are in range, the radius positive and the rim
    /// non-negative (for events built by hand or deserialized).
    pub fn validate(&self) -> Result<(), EventError> {
        for (field, value) in [
            ("center.x", self.center[0]),
            ("center.y", self.center[1]),
            ("radius", self.radius),
            ("rim", self.rim),
        ] {
            if !quant::in_range(value) {
                return Err(EventError::FixedOutOfRange { field, value });
            }
        }
        if self.radius <= 0 {
            return Err(EventError::NonPositiveRadius {
                value: self.radius_f32(),
            });
        }
        if self.rim < 0 {
            return Err(EventError::NegativeRim {
                value: self.rim_f32(),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builds_fixed_point_events() {
        let e = Event::carve(Vec2::new(1.5, -2.0), 10.0)
            .unwrap()
            .with_rim(2.0)
            .unwrap()
            .with_growth(4)
            .at_tick(7);
        assert_eq!(e.center, [384, -512]);
        assert_eq!(e.radius, 2560);
        assert_eq!(e.rim, 512);
        assert_eq!((e.grow_ticks, e.tick, e.kind), (4, 7, EventKind::Carve));
        assert_eq!(e.validate(), Ok(()));
        let f = Event::fill(Vec2::ZERO, 3.0, 9).unwrap();
        assert_eq!((f.kind, f.material, f.rim), (EventKind::Fill, 9, 0));
    }

    #[test]
    fn rejects_bad_values_naming_field_and_value() {
        let msg = Event::carve(Vec2::new(f32::NAN, 0.0), 1.0)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("center.x") && msg.contains("NaN"), "{msg}");
        let msg = Event::carve(Vec2::ZERO, f32::INFINITY)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("radius") && msg.contains("inf"), "{msg}");
        let msg = Event::carve(Vec2::ZERO, -3.0).unwrap_err().to_string();
        assert!(msg.contains("radius") && msg.contains("-3"), "{msg}");
        let msg = Event::fill(Vec2::ZERO, 0.0, 1).unwrap_err().to_string();
        assert!(msg.contains("radius") && msg.contains('0'), "{msg}");
        let msg = Event::carve(Vec2::new(0.0, 1e9), 1.0)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("center.y"), "{msg}");
        let msg = Event::carve(Vec2::ZERO, 1.0)
            .unwrap()
            .with_rim(-1.0)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("rim") && msg.contains("-1"), "{msg}");
        let bad = Event {
            radius: i32::MAX,
            ..Event::carve(Vec2::ZERO, 1.0).unwrap()
        };
        assert!(bad.validate().unwrap_err().to_string().contains("radius"));
    }

    #[test]
    fn growth_schedule() {
        let e = Event::carve(Vec2::ZERO, 8.0)
            .unwrap()
            .with_growth(4)
            .at_tick(10);
        assert_eq!(e.radius_at(9), None);
        assert_eq!(e.radius_at(10), Some(2.0));
        assert_eq!(e.radius_at(13), Some(8.0));
        assert_eq!(e.radius_at(u32::MAX), Some(8.0));
        assert!(!e.is_settled(13) && e.is_settled(14));
        let late = Event::carve(Vec2::ZERO, 8.0)
            .unwrap()
            .with_growth(u16::MAX)
            .at_tick(u32::MAX - 1);
        assert!(late.radius_at(u32::MAX).is_some());
        assert!(!late.is_settled(u32::MAX - 1) && late.is_settled(u32::MAX));
    }

    #[test]
    fn serde_round_trip() {
        let e = Event::fill(Vec2::new(3.0, 4.0), 5.0, 2)
            .unwrap()
            .with_growth(3);
        let s = ron::to_string(&e).unwrap();
        assert_eq!(ron::from_str::<Event>(&s).unwrap(), e);
    }
}
