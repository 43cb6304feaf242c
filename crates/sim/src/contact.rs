//! Body-terrain contacts: one batch of field samples for every body, then a velocity
//! solve per body (speculative contacts, Coulomb friction with a drive belt).
//!
//! Contacts are solved on velocities before the move, with the clearance known from the
//! samples: a body may approach a surface by at most its clearance this tick, so it lands
//! exactly on it instead of sinking in and being pushed back out (which makes resting
//! bodies jitter and creep down slopes). Friction acts on the difference between the
//! tangential velocity and the drive target, limited by `friction × normal impulse`; when
//! the limit holds and there is no drive, the velocity is rebuilt as exactly zero along the
//! tangent, so a body at rest on a slope stays bit-for-bit still.

use glam::Vec2;

use craterfield_core::det::math::{clamp, max, min};
use craterfield_field::Sample;

use super::body::Body;

/// Penetration left alone (not pushed out), world units: keeps resting contacts still.
pub(crate) const SLOP: f32 = 0.02;
/// A body within this clearance of a surface is grounded (can jump and drive).
pub(crate) const GROUND_RANGE: f32 = 1.0;
/// The fraction of penetration beyond the slop removed per tick.
const PUSH_OUT: f32 = 0.4;
/// Velocity iterations over a body's contacts.
const ITERATIONS: usize = 3;
/// Below this approach speed a contact does not bounce (units per second).
const BOUNCE_THRESHOLD: f32 = 60.0;
/// A grounded body without drive slower than this (units per second) comes to rest:
/// two contacts with slightly different normals otherwise leave a residue that creeps.
const REST_SPEED: f32 = 0.5;

/// Where the body samples the field: the centre of a circle, the two ends of a capsule.
/// Returns the points and how many are used.
pub(crate) fn probe_points(b: &Body) -> ([Vec2; 2], usize) {
    if b.half_length > 0.0 {
        let (a, c) = b.segment();
        ([a, c], 2)
    } else {
        ([b.pos, b.pos], 1)
    }
}

/// Unit normal from a sample's gradient; `None` where the gradient vanishes.
pub(crate) fn normal_of(s: &Sample) -> Option<Vec2> {
    let g = s.gradient;
    let len2 = g.x * g.x + g.y * g.y;
    let usable = len2 > 1e-12 && len2.is_finite();
    if !usable {
        return None;
    }
    let len = len2.sqrt();
    Some(Vec2::new(g.x / len, g.y / len))
}

/// One contact of a body with the terrain.
#[derive(Clone, Copy, Debug)]
struct Contact {
    normal: Vec2,
    /// Clearance `d / L - radius` (negative when penetrating).
    gap: f32,
    /// Normal velocity change accumulated this tick (limits friction).
    impulse: f32,
}

/// Solves the body's terrain contacts from its probe samples. `lipschitz` scales distances
/// to conservative clearances. Updates `ground`, `surface` and `clearance`, and the
/// velocity.
pub(crate) fn solve(b: &mut Body, samples: &[Sample], lipschitz: f32, dt: f32) {
    let mut contacts = [None::<Contact>; 2];
    let mut clearance = f32::MAX;
    let mut surface = Vec2::ZERO;
    let mut ground = Vec2::ZERO;
    let mut ground_gap = GROUND_RANGE;
    let speed = (b.vel.x * b.vel.x + b.vel.y * b.vel.y).sqrt();
    let margin = speed * dt + GROUND_RANGE;
    for (slot, s) in contacts.iter_mut().zip(samples) {
        let gap = s.distance / lipschitz - b.radius;
        // Deep inside the terrain (beyond the band, where the field is a clamped constant)
        // the gradient vanishes: push the body up, towards where the surface usually is,
        // rather than let it fall through.
        let escape = (gap < 0.0).then_some(Vec2::Y);
        let Some(normal) = normal_of(s).or(escape) else {
            clearance = min(clearance, gap);
            continue;
        };
        if gap < clearance {
            surface = normal;
        }
        clearance = min(clearance, gap);
        if gap < ground_gap {
            ground_gap = gap;
            ground = normal;
        }
        if gap < margin {
            *slot = Some(Contact {
                normal,
                gap,
                impulse: 0.0,
            });
        }
    }
    b.clearance = clearance;
    b.surface = surface;
    b.ground = ground;
    for _ in 0..ITERATIONS {
        for c in contacts.iter_mut().flatten() {
            solve_contact(b, c, dt);
        }
    }
    let speed2 = b.vel.x * b.vel.x + b.vel.y * b.vel.y;
    if b.ground != Vec2::ZERO && b.drive == 0.0 && speed2 < REST_SPEED * REST_SPEED {
        b.vel = Vec2::ZERO;
    }
}

/// The lowest normal velocity the contact allows.
fn normal_target(b: &Body, c: &Contact, vn: f32, dt: f32) -> f32 {
    let mut target = if c.gap > SLOP {
        // Speculative: approach by at most the clearance this tick.
        -(c.gap - SLOP) / dt
    } else if c.gap < -SLOP {
        (-c.gap - SLOP) * PUSH_OUT / dt
    } else {
        0.0
    };
    if vn < -BOUNCE_THRESHOLD && c.gap <= SLOP + GROUND_RANGE {
        target = max(target, -vn * b.restitution);
    }
    target
}

/// One pass of one contact: normal impulse, then friction against the drive belt.
fn solve_contact(b: &mut Body, c: &mut Contact, dt: f32) {
    let n = c.normal;
    let t = Vec2::new(n.y, -n.x);
    let vn = b.vel.x * n.x + b.vel.y * n.y;
    let vt = b.vel.x * t.x + b.vel.y * t.y;
    let target = normal_target(b, c, vn, dt);
    // Accumulated impulses stay non-negative (contacts push, never pull).
    let new_impulse = max(c.impulse + (target - vn), 0.0);
    let vn_new = vn + (new_impulse - c.impulse);
    c.impulse = new_impulse;
    // Only touching contacts (not speculative ones far away) carry friction.
    let limit = if c.gap <= GROUND_RANGE {
        b.friction * c.impulse
    } else {
        0.0
    };
    let belt = if c.gap <= GROUND_RANGE { b.drive } else { vt };
    let vt_new = vt + clamp(belt - vt, -limit, limit);
    // Rebuilt from components so a contact at rest gives exactly zero.
    b.vel = Vec2::new(n.x * vn_new + t.x * vt_new, n.y * vn_new + t.y * vt_new);
}
