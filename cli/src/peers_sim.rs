//! The physics peer of `bench sim --peers` (feature `peers`): rapier2d stepping the same
//! bodies as the world (circles as balls, capsules as capsules, with their positions,
//! velocities, masses, friction and restitution) on the same terrain as static polylines
//! from `extract_contours`, at the world's tick rate and gravity, on one thread (rapier2d
//! without its `parallel` feature). Its terrain does not change: rapier2d has no explosions,
//! so the world's players do not fire in the compared rows. Like the world, the peer removes
//! the bodies that leave play (the world's explosions have holed its floor: bodies fall out).

use craterfield::field2d::Aabb;
use craterfield::field2d::contour::{ContourOptions, extract_contours};
use craterfield::sim::{World, units};
use glam::Vec2;
use rapier2d::prelude::{
    ColliderBuilder, IntegrationParameters, PhysicsWorld, RigidBodyBuilder, Vector,
};

/// Contour options for the peer's terrain: fine enough that a 2-unit ball rests on the
/// surface the world's bodies see.
pub(crate) const CONTOUR: ContourOptions = ContourOptions {
    spacing: 2.0,
    refine_iterations: 2,
    simplify_tolerance: 0.05,
};

/// The world removes bodies this far beside its bounds (`sim::world`'s `OUT_OF_WORLD`)...
const OUT_OF_WORLD: f32 = 1024.0;
/// ...and this far below them (`BELOW_WORLD`).
const BELOW_WORLD: f32 = 64.0;

/// rapier2d's world with the terrain and bodies of a craterfield world.
pub(crate) struct RapierPeer {
    physics: PhysicsWorld,
    /// The world's bounds, for removing bodies out of play as the world does.
    lo: Vec2,
    hi: Vec2,
    /// Terrain segments (polyline edges).
    pub segments: usize,
    /// Dynamic bodies.
    pub bodies: usize,
}

impl RapierPeer {
    /// The peer of `world` as it is now.
    pub(crate) fn new(world: &World) -> Result<RapierPeer, String> {
        // The world keeps bodies down to BELOW_WORLD under its bounds, and its explosions
        // reach below them: the terrain there, and beside, is the peer's too.
        let (lo, hi) = world.terrain().bounds();
        let region = Aabb::new(lo - Vec2::splat(BELOW_WORLD), hi + Vec2::splat(BELOW_WORLD));
        let contours = extract_contours(world.terrain(), region, &CONTOUR)
            .map_err(|e| format!("contours for rapier2d: {e}"))?;
        let settings = world.settings();
        let mut physics = PhysicsWorld {
            gravity: Vector::new(0.0, -units(settings.gravity)),
            integration_parameters: IntegrationParameters {
                dt: 1.0 / f32::from(settings.tick_hz),
                ..IntegrationParameters::default()
            },
            ..PhysicsWorld::default()
        };
        let mut segments = 0;
        for contour in &contours.loops {
            let vertices: Vec<Vector> = contour
                .points
                .iter()
                .map(|p| Vector::new(p.x, p.y))
                .collect();
            let n = vertices.len() as u32;
            let indices = (0..n).map(|i| [i, (i + 1) % n]).collect();
            segments += n as usize;
            physics
                .colliders
                .insert(ColliderBuilder::polyline(vertices, Some(indices)));
        }
        for body in world.bodies() {
            let shape = if body.half_length > 0.0 {
                ColliderBuilder::capsule_x(body.half_length, body.radius)
            } else {
                ColliderBuilder::ball(body.radius)
            };
            let shape = shape.friction(body.friction).restitution(body.restitution);
            let shape = if body.inv_mass > 0.0 {
                shape.mass(1.0 / body.inv_mass)
            } else {
                shape
            };
            let rigid = RigidBodyBuilder::dynamic()
                .translation(Vector::new(body.pos.x, body.pos.y))
                .rotation(body.axis.y.atan2(body.axis.x))
                .linvel(Vector::new(body.vel.x, body.vel.y))
                // Small bodies fall several radii per tick: without continuous collision
                // detection they pass through the terrain's segments (the world never
                // tunnels, so the peer must not either).
                .ccd_enabled(true);
            physics.insert(rigid, shape);
        }
        Ok(RapierPeer {
            physics,
            lo,
            hi,
            segments,
            bodies: world.bodies().len(),
        })
    }

    /// One tick, then the removal of bodies out of play.
    pub(crate) fn step(&mut self) {
        self.physics.step();
        let (lo, hi) = (self.lo, self.hi);
        let gone: Vec<_> = self
            .physics
            .bodies
            .iter()
            .filter(|(_, b)| {
                let p = b.translation();
                !(p.x >= lo.x - OUT_OF_WORLD
                    && p.x <= hi.x + OUT_OF_WORLD
                    && p.y >= lo.y - BELOW_WORLD
                    && p.y <= hi.y + 8.0 * OUT_OF_WORLD)
            })
            .map(|(h, _)| h)
            .collect();
        for h in gone {
            self.physics.remove_body_with_colliders(h, true);
        }
    }

    /// Bodies still in play.
    pub(crate) fn bodies_in_play(&self) -> usize {
        self.physics.bodies.len()
    }

    /// Centres and radii of the bodies now, to check them against the terrain.
    pub(crate) fn discs(&self) -> Vec<(Vec2, f32)> {
        self.physics
            .colliders
            .iter()
            .filter_map(|(_, c)| {
                let radius = c.shape().as_ball().map(|b| b.radius)?;
                let at = c.translation();
                Some((Vec2::new(at.x, at.y), radius))
            })
            .collect()
    }

    /// Bodies rapier2d has put to sleep (it skips them until something wakes them).
    pub(crate) fn sleeping(&self) -> usize {
        self.physics
            .bodies
            .iter()
            .filter(|(_, b)| b.is_sleeping())
            .count()
    }
}
