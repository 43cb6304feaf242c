//! artillery: a small Worms-like match on destructible terrain. Two or four players take
//! turns: drive, aim, set the power, fire a shell (carves) or dirt (fills), cling to walls
//! in stick mode; a shell's blast hurts, and the last vehicle standing wins.
//!
//! ```text
//! cargo run --release --example artillery [-- --players 2|3|4] [--hotseat] [--level levels/caverns.ron]
//!     [--frames N --screenshot shot.png]   (scripted: every player is the AI, one tick per frame)
//!     [--culling off|view]                 (the terrain pipeline: the whole level, or per view)
//! ```
//!
//! The view follows the shell in flight, else the vehicle whose turn it is.
//!
//! Keys for the player whose turn it is: A/D or Left/Right drive, W/S or Up/Down aim,
//! Q/E power, 1/2 shell/dirt, Space fire, T stick mode, J jump, R restart after a win.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::time::TimeUpdateStrategy;
use bevy::window::WindowResolution;
use craterfield_bevy::craterfield::sim::{Settings, World as SimWorld, units};
use craterfield_bevy::prelude::*;
use craterfield_bevy::{Culling, TerrainFrameCosts};

/// Player colours (sprites, HUD).
const COLORS: [Color; 4] = [
    Color::srgb(0.95, 0.25, 0.2),
    Color::srgb(0.2, 0.55, 1.0),
    Color::srgb(0.95, 0.85, 0.15),
    Color::srgb(0.75, 0.3, 0.95),
];
/// Ticks a turn may last before it passes.
const TURN_TICKS: u32 = 20 * 60;
/// Ticks after the last projectile lands before the next turn.
const SETTLE_TICKS: u32 = 45;
/// Ticks the AI waits into its turn before it fires.
const AI_THINK_TICKS: u32 = 40;

fn main() -> AppExit {
    let args = match Args::parse() {
        Ok(args) => args,
        Err(e) => {
            eprintln!("artillery: {e}");
            return AppExit::error();
        }
    };
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: Some(Window {
                    title: "craterfield artillery".into(),
                    resolution: WindowResolution::new(1280, 720),
                    ..default()
                }),
                ..default()
            })
            .set(AssetPlugin {
                file_path: args.assets.clone(),
                ..default()
            }),
    )
    .add_plugins(CraterfieldPlugin)
    .insert_resource(ClearColor(Color::srgb(0.05, 0.05, 0.08)))
    .insert_resource(Game::new(&args))
    .insert_resource(args.clone())
    .init_resource::<FrameTimes>()
    .init_resource::<Blasts>()
    .add_systems(Startup, setup)
    .add_systems(
        Update,
        (
            follow_camera,
            blasts,
            dress_bodies,
            human_controls,
            aim_line,
            hud,
            restart,
            frame_script,
        ),
    )
    .add_systems(
        FixedUpdate,
        (
            player_inputs.before(CraterfieldSystems::Step),
            advance_turn.after(CraterfieldSystems::Step),
        ),
    );
    if args.frames.is_some() {
        // Scripted runs are the same run on any machine: one tick per frame.
        app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            1.0 / 60.0,
        )));
    }
    app.run()
}

#[derive(Resource, Clone, Debug)]
struct Args {
    players: usize,
    hotseat: bool,
    level: String,
    assets: String,
    frames: Option<u32>,
    screenshot: Option<PathBuf>,
    culling: Culling,
}

impl Args {
    fn parse() -> Result<Args, String> {
        let mut args = Args {
            players: 2,
            hotseat: false,
            level: "levels/default.ron".into(),
            assets: concat!(env!("CARGO_MANIFEST_DIR"), "/assets").into(),
            frames: None,
            screenshot: None,
            culling: TerrainView::default().culling,
        };
        let mut it = std::env::args().skip(1);
        while let Some(a) = it.next() {
            let mut value = |what: &str| it.next().ok_or(format!("{a} needs {what}"));
            match a.as_str() {
                "--players" => {
                    args.players = value("a count")?
                        .parse()
                        .ok()
                        .filter(|n| (2..=4).contains(n))
                        .ok_or("--players takes 2, 3 or 4")?;
                }
                "--hotseat" => args.hotseat = true,
                "--level" => args.level = value("an asset path")?,
                "--assets" => args.assets = value("a folder")?,
                "--frames" => {
                    args.frames = Some(
                        value("a count")?
                            .parse()
                            .map_err(|e| format!("--frames: {e}"))?,
                    );
                }
                "--screenshot" => args.screenshot = Some(value("a file")?.into()),
                "--culling" => {
                    args.culling = match value("view or off")?.as_str() {
                        "view" => Culling::View,
                        "off" => Culling::Off,
                        other => return Err(format!("--culling {other}: view or off")),
                    }
                }
                _ => return Err(format!("unknown argument {a} (see the example's docs)")),
            }
        }
        Ok(args)
    }
}

/// Whose turn it is and what each player has set.
#[derive(Resource, Debug)]
struct Game {
    players: usize,
    human: Vec<bool>,
    turn: u8,
    phase: Phase,
    /// Ticks into the current phase.
    phase_ticks: u32,
    aims: Vec<Aim>,
    fire_requested: bool,
    /// Toggle stick / jump requested by the active human for the next tick.
    stick_requested: bool,
    jump_requested: bool,
    winner: Option<Option<u8>>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Aiming,
    /// Fired; waiting for the projectiles to land.
    Flying,
}

#[derive(Debug, Clone, Copy)]
struct Aim {
    degrees: f32,
    power: f32,
    weapon: u8,
}

impl Game {
    fn new(args: &Args) -> Game {
        let scripted = args.frames.is_some();
        let human = (0..args.players)
            .map(|p| !scripted && (p == 0 || args.hotseat))
            .collect();
        Game {
            players: args.players,
            human,
            turn: 0,
            phase: Phase::Aiming,
            phase_ticks: 0,
            aims: (0..args.players)
                .map(|p| Aim {
                    degrees: if p % 2 == 0 { 50.0 } else { 130.0 },
                    power: 0.6,
                    weapon: 0,
                })
                .collect(),
            fire_requested: false,
            stick_requested: false,
            jump_requested: false,
            winner: None,
        }
    }
}

/// Real frame times, for the summary of a scripted run.
#[derive(Resource, Default)]
struct FrameTimes(Vec<f64>);

#[derive(Component)]
struct HudText;

fn setup(mut commands: Commands, assets: Res<AssetServer>, args: Res<Args>) {
    commands.spawn((
        Camera2d,
        TerrainView {
            culling: args.culling,
            ..default()
        },
    ));
    commands.insert_resource(StartMatch {
        level: assets.load(args.level.clone()),
        settings: Settings::default(),
        players: args.players,
        record: false,
    });
    commands.spawn((
        HudText,
        Text::new("loading the level..."),
        TextFont::from_font_size(18.0),
        TextColor(Color::WHITE),
        Node {
            position_type: PositionType::Absolute,
            left: Val::Px(12.0),
            top: Val::Px(8.0),
            ..default()
        },
    ));
}

/// World units per pixel: the view shows a third of the default level's width.
const UNITS_PER_PIXEL: f32 = 1.75;

/// The view follows the action (a shell in flight, else the active vehicle), kept inside
/// the level.
fn follow_camera(
    cf: Option<Res<Craterfield>>,
    game: Res<Game>,
    window: Single<&Window>,
    camera: Single<(&mut Transform, &mut Projection), With<Camera2d>>,
) {
    let Some(cf) = cf else { return };
    let (mut transform, mut projection) = camera.into_inner();
    let world = cf.world();
    let b = cf.level().bounds();
    let upp = UNITS_PER_PIXEL.max((b.max.x - b.min.x) / 4.0 / window.width());
    if let Projection::Orthographic(ortho) = projection.as_mut() {
        ortho.scale = upp;
    }
    let shell = world.bodies().iter().find(|b| {
        matches!(
            b.kind,
            craterfield_bevy::craterfield::sim::BodyKind::Projectile { .. }
        )
    });
    let focus = shell
        .or_else(|| world.vehicle(game.turn))
        .map_or((b.min + b.max) * 0.5, |body| body.pos);
    let half = Vec2::new(window.width(), window.height()) * 0.5 * upp;
    let lo = b.min + half;
    let hi = (b.max - half).max(lo);
    let target = focus.clamp(lo, hi);
    let current = transform.translation.truncate();
    // Eased, and in whole pixels so that the terrain does not shimmer as the view moves.
    let eased = if current == Vec2::ZERO {
        target
    } else {
        current.lerp(target, 0.12)
    };
    let snapped = (eased / upp).round() * upp;
    transform.translation = snapped.extend(0.0);
}

/// Expanding rings where the terrain was just carved or filled.
#[derive(Resource, Default)]
struct Blasts {
    seen: usize,
    rings: Vec<(Vec2, f32, u32, bool)>,
}

fn blasts(cf: Option<Res<Craterfield>>, mut blasts: ResMut<Blasts>, mut gizmos: Gizmos) {
    let Some(cf) = cf else { return };
    let events = cf.world().terrain().events();
    if events.len() < blasts.seen {
        blasts.seen = 0;
    }
    for e in &events[blasts.seen..] {
        let carve = e.kind == craterfield_bevy::craterfield::field2d::EventKind::Carve;
        blasts
            .rings
            .push((e.center_f32(), e.radius_f32(), 0, carve));
    }
    blasts.seen = events.len();
    for (at, radius, age, carve) in &mut blasts.rings {
        *age += 1;
        let t = *age as f32 / 24.0;
        let color = if *carve {
            Color::srgba(1.0, 0.75, 0.2, 1.0 - t)
        } else {
            Color::srgba(0.6, 0.4, 0.2, 1.0 - t)
        };
        gizmos.circle_2d(*at, *radius * (1.0 + 0.6 * t), color);
    }
    blasts.rings.retain(|r| r.2 < 24);
}

/// Sprites for new bodies: vehicles in their player's colour with a marker above, shells
/// dark, dirt brown, debris grey.
fn dress_bodies(
    mut commands: Commands,
    bodies: Query<(Entity, &CraterfieldBody), Added<CraterfieldBody>>,
) {
    for (e, body) in &bodies {
        let (color, size) = match body.kind {
            BodyRole::Vehicle { player } => (
                COLORS[usize::from(player) % COLORS.len()],
                Vec2::new(2.0 * (body.half_length + body.radius), 2.0 * body.radius),
            ),
            BodyRole::Projectile { weapon: 0 } => {
                (Color::srgb(0.1, 0.1, 0.1), Vec2::splat(4.0 * body.radius))
            }
            BodyRole::Projectile { .. } => {
                (Color::srgb(0.45, 0.3, 0.15), Vec2::splat(4.0 * body.radius))
            }
            BodyRole::Debris => (Color::srgb(0.5, 0.5, 0.5), Vec2::splat(2.0 * body.radius)),
        };
        let mut entity = commands.entity(e);
        entity.insert(Sprite::from_color(color, size));
        if let BodyRole::Vehicle { .. } = body.kind {
            // A marker above the vehicle, unrotated in spirit: small enough not to matter.
            entity.with_child((
                Sprite::from_color(color, Vec2::splat(14.0)),
                Transform::from_xyz(0.0, 3.0 * body.radius, 1.0),
            ));
        }
    }
}

fn human_controls(keys: Res<ButtonInput<KeyCode>>, time: Res<Time>, mut game: ResMut<Game>) {
    let turn = usize::from(game.turn);
    if game.winner.is_some() || !game.human[turn] || game.phase != Phase::Aiming {
        return;
    }
    let dt = time.delta_secs();
    let held = |a: KeyCode, b: KeyCode| keys.pressed(a) || keys.pressed(b);
    let aim = &mut game.aims[turn];
    if held(KeyCode::KeyW, KeyCode::ArrowUp) {
        aim.degrees = (aim.degrees + 60.0 * dt).min(180.0);
    }
    if held(KeyCode::KeyS, KeyCode::ArrowDown) {
        aim.degrees = (aim.degrees - 60.0 * dt).max(0.0);
    }
    if keys.pressed(KeyCode::KeyE) {
        aim.power = (aim.power + 0.5 * dt).min(1.0);
    }
    if keys.pressed(KeyCode::KeyQ) {
        aim.power = (aim.power - 0.5 * dt).max(0.05);
    }
    if keys.just_pressed(KeyCode::Digit1) {
        aim.weapon = 0;
    }
    if keys.just_pressed(KeyCode::Digit2) {
        aim.weapon = 1;
    }
    if keys.just_pressed(KeyCode::Space) {
        game.fire_requested = true;
    }
    if keys.just_pressed(KeyCode::KeyT) {
        game.stick_requested = true;
    }
    if keys.just_pressed(KeyCode::KeyJ) {
        game.jump_requested = true;
    }
}

/// This tick's inputs: the active player's controls (or the AI's), everyone else idle.
fn player_inputs(
    cf: Option<Res<Craterfield>>,
    keys: Res<ButtonInput<KeyCode>>,
    mut game: ResMut<Game>,
    mut inputs: ResMut<PlayerInputs>,
) {
    let Some(cf) = cf else { return };
    let world = cf.world();
    let players = game.players;
    inputs.0 = (0..players)
        .map(|p| Input {
            aim: Input::aim_from_degrees(game.aims[p].degrees),
            power: power_byte(game.aims[p].power),
            weapon: game.aims[p].weapon,
            ..Input::default()
        })
        .collect();
    if game.winner.is_some() || game.phase != Phase::Aiming {
        return;
    }
    let turn = usize::from(game.turn);
    let mut input = inputs.0[turn];
    if game.human[turn] {
        let held = |a: KeyCode, b: KeyCode| keys.pressed(a) || keys.pressed(b);
        input.drive = match (
            held(KeyCode::KeyA, KeyCode::ArrowLeft),
            held(KeyCode::KeyD, KeyCode::ArrowRight),
        ) {
            (true, false) => -100,
            (false, true) => 100,
            _ => 0,
        };
        if std::mem::take(&mut game.stick_requested) {
            input.buttons |= buttons::STICK;
        }
        if std::mem::take(&mut game.jump_requested) {
            input.buttons |= buttons::JUMP;
        }
    } else {
        let ticks = game.phase_ticks;
        let (aim, drive, fire) = ai_turn(world, game.turn, ticks);
        game.aims[turn] = aim;
        input.aim = Input::aim_from_degrees(aim.degrees);
        input.power = power_byte(aim.power);
        input.weapon = aim.weapon;
        input.drive = drive;
        game.fire_requested |= fire;
    }
    if std::mem::take(&mut game.fire_requested) {
        input.buttons |= buttons::FIRE;
        game.phase = Phase::Flying;
        game.phase_ticks = 0;
    }
    inputs.0[turn] = input;
}

fn power_byte(power: f32) -> u8 {
    (power.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The AI: the nearest living opponent, a 50-degree lob whose range (without drag or
/// wind) reaches it, fired once it has thought for a moment.
fn ai_turn(world: &SimWorld, me: u8, ticks: u32) -> (Aim, i8, bool) {
    let idle = Aim {
        degrees: 50.0,
        power: 0.5,
        weapon: 0,
    };
    let Some(mine) = world.vehicle(me) else {
        return (idle, 0, false);
    };
    let target = (0..world.players() as u8)
        .filter(|&p| p != me)
        .filter_map(|p| world.vehicle(p))
        .min_by(|a, b| {
            let (da, db) = ((a.pos - mine.pos).length(), (b.pos - mine.pos).length());
            da.total_cmp(&db)
        });
    let Some(target) = target else {
        return (idle, 0, false);
    };
    let to = target.pos - mine.pos;
    let settings = world.settings();
    let g = units(settings.gravity).max(1.0);
    let top = units(settings.shell.speed).max(1.0);
    let angle = 50f32.to_radians();
    // Range of a launch at speed v and angle a on flat ground: v^2 sin(2a) / g.
    let speed = (to.x.abs().max(60.0) * g / (2.0 * angle).sin()).sqrt();
    let aim = Aim {
        degrees: if to.x >= 0.0 { 50.0 } else { 130.0 },
        power: (speed / top).clamp(0.1, 1.0),
        weapon: 0,
    };
    (aim, 0, ticks == AI_THINK_TICKS)
}

/// Passes the turn once the shot has landed (or the turn ran out), and declares a winner
/// when at most one vehicle is left.
fn advance_turn(cf: Option<Res<Craterfield>>, mut game: ResMut<Game>) {
    let Some(cf) = cf else { return };
    if game.winner.is_some() {
        return;
    }
    let world = cf.world();
    let alive: Vec<u8> = (0..game.players as u8)
        .filter(|&p| world.vehicle(p).is_some())
        .collect();
    if alive.len() <= 1 {
        game.winner = Some(alive.first().copied());
        return;
    }
    game.phase_ticks += 1;
    let flying = world.bodies().iter().any(|b| {
        matches!(
            b.kind,
            craterfield_bevy::craterfield::sim::BodyKind::Projectile { .. }
        )
    });
    let done = match game.phase {
        Phase::Aiming => game.phase_ticks >= TURN_TICKS || world.vehicle(game.turn).is_none(),
        Phase::Flying => {
            if flying {
                game.phase_ticks = 0;
            }
            game.phase_ticks >= SETTLE_TICKS
        }
    };
    if done {
        let next = alive
            .iter()
            .copied()
            .find(|&p| p > game.turn)
            .unwrap_or(alive[0]);
        game.turn = next;
        game.phase = Phase::Aiming;
        game.phase_ticks = 0;
    }
}

fn aim_line(
    cf: Option<Res<Craterfield>>,
    game: Res<Game>,
    bodies: Query<(&CraterfieldBody, &GlobalTransform)>,
    mut gizmos: Gizmos,
) {
    if cf.is_none() || game.winner.is_some() || game.phase != Phase::Aiming {
        return;
    }
    let turn = game.turn;
    let Some((_, at)) = bodies
        .iter()
        .find(|(b, _)| b.kind == BodyRole::Vehicle { player: turn })
    else {
        return;
    };
    let aim = game.aims[usize::from(turn)];
    let from = at.translation().truncate();
    let dir = Vec2::from_angle(aim.degrees.to_radians());
    gizmos.line_2d(
        from,
        from + dir * (40.0 + 160.0 * aim.power),
        COLORS[usize::from(turn) % COLORS.len()],
    );
}

fn hud(cf: Option<Res<Craterfield>>, game: Res<Game>, mut text: Single<&mut Text, With<HudText>>) {
    let Some(cf) = cf else { return };
    let world = cf.world();
    let mut s = String::new();
    for p in 0..game.players {
        let health = world.vehicle(p as u8).map_or(0, |v| v.health.max(0));
        let marker = if p == usize::from(game.turn) && game.winner.is_none() {
            ">"
        } else {
            " "
        };
        let who = if game.human[p] { "player" } else { "AI" };
        s.push_str(&format!("{marker} {who} {}: {health:3} hp   ", p + 1));
    }
    let turn = usize::from(game.turn);
    let aim = game.aims[turn];
    let weapon = if aim.weapon == 0 { "shell" } else { "dirt" };
    match game.winner {
        Some(Some(w)) => s.push_str(&format!("\n\nPlayer {} wins!  (R: play again)", w + 1)),
        Some(None) => s.push_str("\n\nNobody is left standing.  (R: play again)"),
        None => s.push_str(&format!(
            "\nangle {:.0}  power {:.0}%  {weapon}  tick {}",
            aim.degrees,
            aim.power * 100.0,
            world.tick()
        )),
    }
    text.0 = s;
}

fn restart(
    mut commands: Commands,
    keys: Res<ButtonInput<KeyCode>>,
    args: Res<Args>,
    assets: Res<AssetServer>,
    mut game: ResMut<Game>,
) {
    if game.winner.is_none() || !keys.just_pressed(KeyCode::KeyR) {
        return;
    }
    *game = Game::new(&args);
    commands.remove_resource::<Craterfield>();
    commands.insert_resource(StartMatch {
        level: assets.load(args.level.clone()),
        settings: Settings::default(),
        players: args.players,
        record: false,
    });
}

/// `--frames N --screenshot F`: after N frames, a screenshot of the window, a summary on
/// stdout, and exit.
fn frame_script(
    mut commands: Commands,
    args: Res<Args>,
    mut times: ResMut<FrameTimes>,
    mut frame: Local<u32>,
    mut last: Local<Option<Instant>>,
) {
    let Some(frames) = args.frames else { return };
    *frame += 1;
    // Wall-clock time between frames (a scripted run's game clock is fixed at 1/60 s).
    let now = Instant::now();
    if let Some(last) = last.replace(now) {
        times.0.push((now - last).as_secs_f64() * 1e3);
    }
    if *frame != frames {
        return;
    }
    match args.screenshot.clone() {
        Some(path) => {
            commands.spawn(Screenshot::primary_window()).observe(
                move |shot: On<ScreenshotCaptured>, mut commands: Commands| {
                    let saved = shot
                        .image
                        .clone()
                        .try_into_dynamic()
                        .map_err(|e| e.to_string())
                        .and_then(|img| img.to_rgba8().save(&path).map_err(|e| e.to_string()));
                    if let Err(e) = &saved {
                        eprintln!("artillery: cannot save {}: {e}", path.display());
                    }
                    commands.queue(move |world: &mut World| {
                        summary(world);
                        world.write_message(if saved.is_ok() {
                            AppExit::Success
                        } else {
                            AppExit::error()
                        });
                    });
                },
            );
        }
        None => commands.queue(|world: &mut World| {
            summary(world);
            world.write_message(AppExit::Success);
        }),
    }
}

/// What a scripted run did: the match, the craters, the frame times and the plugin's cost.
fn summary(world: &mut World) {
    let times = &world.resource::<FrameTimes>().0;
    // The first frames compile pipelines: the steady state starts after them.
    println!(
        "frame time (ms, after the first 30 frames): {}",
        tails(times.get(30..).unwrap_or(&[]))
    );
    if let Some(costs) = world.get_resource::<TerrainFrameCosts>() {
        let log = costs.snapshot();
        let ms = |d: &[Duration]| {
            d.iter()
                .skip(30)
                .map(|d| d.as_secs_f64() * 1e3)
                .collect::<Vec<_>>()
        };
        println!("terrain prepare (ms): {}", tails(&ms(&log.prepare)));
        println!("terrain record (ms): {}", tails(&ms(&log.record)));
        println!("terrain frames drawn: {}", log.frames);
    }
    let mut cameras = world.query_filtered::<(&Transform, &Projection), With<Camera2d>>();
    for (t, p) in cameras.iter(world) {
        if let Projection::Orthographic(o) = p {
            println!(
                "camera center ({:.3}, {:.3}) units_per_pixel {:.4}",
                t.translation.x, t.translation.y, o.scale
            );
        }
    }
    if let Some(cf) = world.get_resource::<Craterfield>() {
        let w = cf.world();
        println!("tick {} state hash {:#018x}", w.tick(), cf.state_hash());
        let alive: Vec<String> = (0..w.players() as u8)
            .filter_map(|p| {
                w.vehicle(p).map(|v| {
                    format!(
                        "{} at ({:.0}, {:.0}) {} hp",
                        p + 1,
                        v.pos.x,
                        v.pos.y,
                        v.health
                    )
                })
            })
            .collect();
        println!("vehicles: {}", alive.join(", "));
        for e in w.terrain().events() {
            let c = e.center_f32();
            println!(
                "event {:?} at ({:.1}, {:.1}) radius {:.1}",
                e.kind,
                c.x,
                c.y,
                e.radius_f32()
            );
        }
    }
}

fn tails(ms: &[f64]) -> String {
    if ms.is_empty() {
        return "no samples".into();
    }
    let mut v = ms.to_vec();
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
    format!(
        "n {} median {:.3} p95 {:.3} p99 {:.3} max {:.3}",
        v.len(),
        at(0.5),
        at(0.95),
        at(0.99),
        v[v.len() - 1]
    )
}
