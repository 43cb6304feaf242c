//! Physics behaviour: resting on slopes, driving on undersides in stick mode, no
//! tunnelling of fast projectiles, blast falloff and damage.

use craterfield::field2d::{Graph, Level, Terrain};
use craterfield::sim::projectile::{Flight, Sweep, fly};
use craterfield::sim::units;
use craterfield::sim::{Input, Settings, World, buttons};
use glam::Vec2;

fn level(root: &str, spawns: &str) -> Level {
    Level::from_ron(&format!(
        "Level(name: \"test\", bounds: (min: (0.0, 0.0), max: (2048.0, 1024.0)), cell_size: 64.0,
           materials: [(name: \"rock\", color: (100, 100, 100))], spawns: [{spawns}], root: {root})"
    ))
    .unwrap()
}

fn idle(players: usize) -> Vec<Input> {
    vec![Input::default(); players]
}

#[test]
fn a_vehicle_rests_on_a_slope_without_drifting() {
    // A 30-degree slope: y < 0.577 x + 100.
    let slope = level(
        "HalfPlane(point: (0.0, 100.0), normal: (-0.5, 0.8660254))",
        "(600.0, 480.0)",
    );
    let mut w = World::new(&slope, Settings::default(), 1).unwrap();
    for _ in 0..180 {
        w.step(&idle(1)).unwrap();
    }
    let v = *w.vehicle(0).unwrap();
    assert!(
        v.ground.x < -0.4,
        "resting on the slope: normal {}",
        v.ground
    );
    assert!(
        v.clearance.abs() < 0.1,
        "touching: clearance {}",
        v.clearance
    );
    for _ in 0..600 {
        w.step(&idle(1)).unwrap();
        let now = w.vehicle(0).unwrap();
        assert_eq!(now.pos, v.pos, "tick {}: drifted", w.tick());
        assert_eq!(now.vel, Vec2::ZERO);
    }
    // Steeper than the friction angle (tan 60 > 0.9): it slides.
    let steep = level(
        "HalfPlane(point: (0.0, 100.0), normal: (-0.8660254, 0.5))",
        "(300.0, 640.0)",
    );
    let mut w = World::new(&steep, Settings::default(), 1).unwrap();
    for _ in 0..240 {
        w.step(&idle(1)).unwrap();
    }
    assert!(
        w.vehicle(0).unwrap().pos.y < 400.0,
        "slides down a 60 degree slope"
    );
}

/// A slab whose underside is at y = 500, from x = 200 to 1800.
fn ceiling() -> Level {
    level(
        "Box(center: (1000.0, 520.0), half_size: (800.0, 20.0))",
        "(400.0, 489.0)",
    )
}

#[test]
fn stick_mode_drives_along_an_underside() {
    let lvl = ceiling();
    let r = units(Settings::default().vehicle.radius);
    let mut w = World::new(&lvl, Settings::default(), 1).unwrap();
    let stick = Input {
        buttons: buttons::STICK,
        ..Input::default()
    };
    w.step(&[stick]).unwrap();
    let x0 = w.vehicle(0).unwrap().pos.x;
    // On an underside the surface tangent runs the other way: negative throttle is +x.
    let drive = Input {
        drive: -127,
        ..Input::default()
    };
    for t in 0..240 {
        w.step(&[drive]).unwrap();
        let v = w.vehicle(0).unwrap();
        if t > 30 {
            assert!(
                v.ground.y < -0.99,
                "tick {t}: clinging to the underside, normal {}",
                v.ground
            );
            assert!(
                (v.pos.y - (500.0 - r)).abs() < 0.5,
                "tick {t}: y {}",
                v.pos.y
            );
        }
    }
    let x1 = w.vehicle(0).unwrap().pos.x;
    assert!(x1 - x0 > 150.0, "drove along the underside: {x0} -> {x1}");

    // Without stick mode the same vehicle falls.
    let mut w = World::new(&lvl, Settings::default(), 1).unwrap();
    for _ in 0..60 {
        w.step(&[drive]).unwrap();
    }
    assert!(
        w.vehicle(0).unwrap().pos.y < 300.0,
        "falls without stick mode"
    );
}

/// A wall one unit thick at x = 1000, standing on a floor at y = 100.
fn wall() -> Level {
    level(
        "Union([Box(center: (1000.0, 600.0), half_size: (0.5, 20000.0)), HalfPlane(point: (0.0, 100.0), normal: (0.0, 1.0))])",
        "(900.0, 112.0)",
    )
}

#[test]
fn fast_projectiles_never_pass_a_one_unit_wall() {
    let lvl = wall();
    let b = lvl.bounds();
    let terrain: Terrain<Graph> =
        Terrain::new(lvl.graph().clone(), b.min, b.max, lvl.terrain_options()).unwrap();
    let max_step = units(Settings::default().max_speed) * Settings::default().dt();
    let mut sweeps = Vec::new();
    for i in 0..2000 {
        let y = 150.0 + (i % 97) as f32 * 9.3;
        let angle = ((i * 37) % 140) as f32 - 70.0;
        let (s, c) = craterfield::det::math::sin_cos_deg(angle);
        let len = [max_step, 4.0 * max_step, 3000.0][i % 3];
        let from = Vec2::new(
            1000.0 - 0.5 - 2.0 - (i % 13) as f32 * 0.37 - c * len * 0.5,
            y,
        );
        sweeps.push(Sweep {
            from,
            dir: Vec2::new(c, s),
            len,
            radius: 0.5 + (i % 4) as f32,
        });
    }
    let mut out = Vec::new();
    fly(&terrain, &sweeps, &mut out).unwrap();
    let mut hits = 0;
    for (s, f) in sweeps.iter().zip(&out) {
        let at = match *f {
            Flight::Hit { at } => {
                hits += 1;
                at
            }
            Flight::Moved { to } => to,
        };
        assert!(
            at.x + s.radius <= 999.5 + 0.01 || s.from.x > 999.0,
            "sweep {s:?} ended at {at}: through the wall"
        );
    }
    assert!(hits > 1000, "most sweeps reach the wall ({hits})");

    // In the world: shells at top speed against the wall all explode on the near side.
    let mut settings = Settings::default();
    settings.shell.speed = settings.max_speed;
    settings.shell.cooldown_ticks = 2;
    // Craters too small to reach the wall from the impact centre, so that it stays whole.
    settings.shell.crater_radius = 1;
    settings.wind = [0, 0];
    let mut w = World::new(&lvl, settings, 1).unwrap();
    for t in 0..400u32 {
        let fire = Input {
            buttons: if t % 4 == 0 { buttons::FIRE } else { 0 },
            aim: Input::aim_from_degrees((t % 40) as f32),
            power: 255,
            ..Input::default()
        };
        w.step(&[fire]).unwrap();
        for b in w.bodies() {
            assert!(b.pos.x < 1000.0, "tick {t}: {:?} passed the wall", b);
        }
    }
    let near_wall = w
        .terrain()
        .events()
        .iter()
        .filter(|e| (e.center_f32().x - 1000.0).abs() < 20.0)
        .count();
    assert!(near_wall > 20, "shells exploded at the wall ({near_wall})");
}

#[test]
fn impulses_fall_off_with_distance_and_damage_kills() {
    let lvl = level(
        "HalfPlane(point: (0.0, 10.0), normal: (0.0, 1.0))",
        "(100.0, 600.0)",
    );
    let settings = Settings {
        gravity: 0,
        ..Settings::default()
    };
    let mut w = World::new(&lvl, settings, 1).unwrap();
    let blast = Vec2::new(1000.0, 600.0);
    let reach = units(settings.shell.blast_radius);
    let ids: Vec<u32> = [5.0, 20.0, 40.0, 60.0, 79.0, 81.0, 200.0]
        .iter()
        .map(|&d| w.add_debris(blast + Vec2::new(d, 0.0), 2.0).unwrap())
        .collect();
    w.detonate(blast, 0).unwrap();
    let speeds: Vec<f32> = ids
        .iter()
        .map(|id| w.bodies().iter().find(|b| b.id == *id).unwrap().vel.x)
        .collect();
    for pair in speeds.windows(2) {
        assert!(pair[0] >= pair[1], "falloff is monotonic: {speeds:?}");
    }
    assert!(speeds[0] > 0.9 * units(settings.shell.impulse));
    assert!((speeds[2] - units(settings.shell.impulse) * (1.0 - 40.0 / reach)).abs() < 1e-2);
    assert_eq!(speeds[5], 0.0);
    assert_eq!(speeds[6], 0.0);
    // The vehicle loses health by distance and is removed at zero.
    let v = w.vehicle(0).unwrap().pos;
    let health = w.vehicle(0).unwrap().health;
    w.detonate(v + Vec2::new(reach * 0.5, 0.0), 0).unwrap();
    let after = w.vehicle(0).unwrap().health;
    assert_eq!(health - after, settings.shell.damage / 2);
    for _ in 0..10 {
        if w.vehicle(0).is_none() {
            break;
        }
        w.detonate(v, 0).unwrap();
    }
    assert!(w.vehicle(0).is_none(), "destroyed");
    assert!(w.detonate(Vec2::NAN, 0).is_err());
    assert!(
        w.detonate(v, 7)
            .unwrap_err()
            .to_string()
            .contains("weapon 7")
    );
}

#[test]
fn a_body_buried_deep_in_the_terrain_climbs_out_instead_of_falling_through() {
    use craterfield::field2d::Sdf;
    let lvl = level(
        "HalfPlane(point: (0.0, 600.0), normal: (0.0, 1.0))",
        "(100.0, 620.0)",
    );
    let mut w = World::new(&lvl, Settings::default(), 1).unwrap();
    // 300 units under the surface: far beyond the band, where the gradient is zero.
    let id = w.add_debris(Vec2::new(1000.0, 300.0), 4.0).unwrap();
    for _ in 0..240 {
        w.step(&idle(1)).unwrap();
    }
    let b = w
        .bodies()
        .iter()
        .find(|b| b.id == id)
        .expect("still in the world");
    assert!(b.pos.y > 595.0, "climbed out: {}", b.pos);
    assert!(
        w.terrain().distance(b.pos) > 3.5,
        "resting on the surface: {}",
        b.pos
    );
}
