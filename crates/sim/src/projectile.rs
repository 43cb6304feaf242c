//! Projectile flight: every projectile's continuous circle sweep for the tick, marched in
//! lockstep so that each march step is one batch query for all of them.
//!
//! Sphere tracing on the clearance `d / L - radius`: a projectile advances by its current
//! clearance, which it can travel without touching anything, so it cannot pass through a
//! feature of any thickness at any speed. A sweep that runs out of steps (a path grazing
//! a surface, where steps shrink to the clearance) ends the tick where it got to and goes
//! on next tick: a projectile may lag, it never tunnels.

use glam::Vec2;

use craterfield_field::tape::EvalError;
use craterfield_field::{Graph, Terrain};

/// Clearance under which a projectile hits, world units.
pub const HIT_EPSILON: f32 = 0.05;
/// March steps per projectile per tick.
pub const MAX_STEPS: u32 = 64;

/// One projectile's sweep for this tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep {
    /// Start of the motion.
    pub from: Vec2,
    /// Unit direction (zero for a projectile at rest).
    pub dir: Vec2,
    /// Length of the motion.
    pub len: f32,
    /// Projectile radius.
    pub radius: f32,
}

/// How a sweep ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Flight {
    /// It reached `to` (the end of the motion, or where the step budget ran out).
    Moved {
        /// Where it is now.
        to: Vec2,
    },
    /// It touched the terrain with its centre at `at`.
    Hit {
        /// The centre at contact.
        at: Vec2,
    },
}

/// Marches every sweep; `out[i]` is how sweep `i` ended.
pub fn fly(
    terrain: &Terrain<Graph>,
    sweeps: &[Sweep],
    out: &mut Vec<Flight>,
) -> Result<(), EvalError> {
    use craterfield_field::Sdf;
    let lipschitz = terrain.lipschitz();
    out.clear();
    out.extend(sweeps.iter().map(|s| Flight::Moved { to: s.from }));
    let mut t = vec![0.0f32; sweeps.len()];
    let mut active: Vec<usize> = (0..sweeps.len()).collect();
    let mut points = Vec::with_capacity(sweeps.len());
    let mut dist = Vec::with_capacity(sweeps.len());
    for _ in 0..MAX_STEPS {
        if active.is_empty() {
            break;
        }
        points.clear();
        points.extend(
            active
                .iter()
                .map(|&i| sweeps[i].from + sweeps[i].dir * t[i]),
        );
        dist.clear();
        dist.resize(points.len(), 0.0);
        terrain.distances(&points, &mut dist)?;
        let mut still = 0;
        for k in 0..active.len() {
            let i = active[k];
            let s = &sweeps[i];
            let clearance = dist[k] / lipschitz - s.radius;
            // NaN clearances (impossible for finite points) count as hits: never tunnel.
            let clear = clearance >= HIT_EPSILON;
            if !clear {
                out[i] = Flight::Hit { at: points[k] };
                continue;
            }
            let next = t[i] + clearance;
            if next >= s.len {
                out[i] = Flight::Moved {
                    to: s.from + s.dir * s.len,
                };
                continue;
            }
            t[i] = next;
            out[i] = Flight::Moved {
                to: s.from + s.dir * next,
            };
            active[still] = i;
            still += 1;
        }
        active.truncate(still);
    }
    Ok(())
}
