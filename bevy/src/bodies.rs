//! Bodies as entities: every body of the world (vehicles, projectiles, debris) has an entity
//! with a [`CraterfieldBody`] and a `Transform` interpolated between the last two ticks, so
//! that motion is smooth at any frame rate while the world steps at its fixed tick.

use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::*;
use craterfield::sim::BodyKind;

use crate::world::Craterfield;

/// What a body entity mirrors. Added by the plugin; give the entity a sprite or a mesh in an
/// `On<Add, CraterfieldBody>` observer or an `Added<CraterfieldBody>` query.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
#[require(Transform, Visibility)]
pub struct CraterfieldBody {
    /// The body's id in the world (stable for its life).
    pub id: u32,
    /// What it is.
    pub kind: BodyRole,
    /// Its radius (world units).
    pub radius: f32,
    /// Half the length of its capsule segment (0 for a disc).
    pub half_length: f32,
}

/// A body's role.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BodyRole {
    /// A player's vehicle.
    Vehicle {
        /// Its player.
        player: u8,
    },
    /// A projectile in flight.
    Projectile {
        /// The weapon fired.
        weapon: u8,
    },
    /// Passive debris.
    Debris,
}

impl BodyRole {
    fn of(kind: &BodyKind) -> BodyRole {
        match *kind {
            BodyKind::Vehicle { player, .. } => BodyRole::Vehicle { player },
            BodyKind::Projectile { weapon, .. } => BodyRole::Projectile { weapon },
            BodyKind::Debris => BodyRole::Debris,
        }
    }
}

/// Body id to entity, kept by the plugin.
#[derive(Resource, Default, Debug)]
pub struct BodyEntities(pub HashMap<u32, Entity>);

/// Spawns entities for new bodies, despawns those of removed bodies, and sets every body
/// entity's `Transform` from the interpolated pose.
pub(crate) fn mirror_bodies(
    mut commands: Commands,
    cf: Option<Res<Craterfield>>,
    time: Res<Time<Fixed>>,
    mut map: ResMut<BodyEntities>,
    mut transforms: Query<&mut Transform, With<CraterfieldBody>>,
) {
    let Some(cf) = cf else {
        for (_, e) in map.0.drain() {
            commands.entity(e).try_despawn();
        }
        return;
    };
    let alpha = time.overstep_fraction();
    let alive: HashSet<u32> = cf.world().bodies().iter().map(|b| b.id).collect();
    map.0.retain(|id, e| {
        let keep = alive.contains(id);
        if !keep {
            commands.entity(*e).try_despawn();
        }
        keep
    });
    for (body, pos, axis) in cf.interpolated_poses(alpha) {
        let transform = pose_transform(pos, axis);
        if let Some(e) = map.0.get(&body.id).copied() {
            if let Ok(mut t) = transforms.get_mut(e) {
                // Keep the game's z (draw order) and scale.
                t.translation.x = transform.translation.x;
                t.translation.y = transform.translation.y;
                t.rotation = transform.rotation;
            }
            continue;
        }
        let e = commands
            .spawn((
                CraterfieldBody {
                    id: body.id,
                    kind: BodyRole::of(&body.kind),
                    radius: body.radius,
                    half_length: body.half_length,
                },
                transform,
                Name::new(format!("craterfield body {}", body.id)),
            ))
            .id();
        map.0.insert(body.id, e);
    }
}

/// A body's pose as a `Transform`: at `pos`, rotated so that local `+x` is `axis`.
fn pose_transform(pos: Vec2, axis: Vec2) -> Transform {
    Transform::from_xyz(pos.x, pos.y, 0.0).with_rotation(Quat::from_rotation_z(axis.to_angle()))
}
