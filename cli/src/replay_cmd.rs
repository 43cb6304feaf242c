//! `craterfield replay`: check a replay by re-simulating it (`verify`), describe it
//! (`info`), and picture any tick of it (`render`).
//!
//! Every failure is a message and exit status 1: an unreadable file names the section and
//! byte offset where decoding stopped, a divergent re-simulation names the first tick whose
//! state hash differs.

use std::path::Path;
use std::process::ExitCode;

use craterfield::field2d::Level;
use craterfield::net::{Replay, VerifyError, verify as verify_replay};
use craterfield::sim::units;
use craterfield::sim::{World, level_hash};

use crate::frame;

fn load_level(level: Option<&Path>) -> Result<Level, String> {
    match level {
        Some(path) => Level::load(path).map_err(|e| format!("{}: {e}", path.display())),
        None => Ok(Level::default_level()),
    }
}

/// Reads and decodes a replay file; returns it with its size in bytes and the format
/// version in its header.
fn load(file: &Path) -> Result<(Replay, usize, u16), String> {
    let limit = craterfield::net::DecodeLimits::default().max_bytes as u64;
    let bytes = craterfield::files::read(file, limit).map_err(|e| e.to_string())?;
    let replay = Replay::decode(&bytes)
        .map_err(|e| format!("{}: not a readable replay: {e}", file.display()))?;
    // A decoded replay has its magic and version, so these bytes exist.
    let version = match bytes.get(8..10) {
        Some(&[lo, hi]) => u16::from_le_bytes([lo, hi]),
        _ => 0,
    };
    Ok((replay, bytes.len(), version))
}

fn seconds(replay: &Replay) -> f64 {
    f64::from(replay.ticks()) / f64::from(replay.settings.tick_hz.max(1))
}

/// `replay verify`: re-simulates and compares every stored hash. A replay that stores none
/// verifies nothing: that is an error unless `allow_unverified`.
pub(crate) fn verify(
    file: &Path,
    level: Option<&Path>,
    allow_unverified: bool,
) -> Result<ExitCode, String> {
    let (replay, _, _) = load(file)?;
    let level = load_level(level)?;
    match verify_replay(&replay, &level) {
        Ok(report) if report.hashes_checked == 0 => {
            let what = format!(
                "{}: {} ticks re-simulated, but the replay stores no state hash: nothing was verified (final hash {:#018x})",
                file.display(),
                report.ticks,
                report.final_hash
            );
            if allow_unverified {
                println!("{what}");
                Ok(ExitCode::SUCCESS)
            } else {
                Err(format!("{what}; pass --allow-unverified to accept that"))
            }
        }
        Ok(report) => {
            println!(
                "{}: ok: {} ticks ({:.1} s, {} players) re-simulated, all {} stored hashes match, final hash {:#018x}",
                file.display(),
                report.ticks,
                seconds(&replay),
                replay.players,
                report.hashes_checked,
                report.final_hash
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(VerifyError::Diverged {
            tick,
            expected,
            found,
        }) => Err(format!(
            "{}: first divergent tick {tick}: expected {expected:#018x} found {found:#018x}",
            file.display()
        )),
        Err(e) => Err(format!("{}: {e}", file.display())),
    }
}

/// `replay info`: what the file holds.
pub(crate) fn info(file: &Path, level: Option<&Path>) -> Result<ExitCode, String> {
    let (replay, size, version) = load(file)?;
    let level = load_level(level)?;
    let level_name = level.name().to_string();
    let matches = if replay.level_hash == level_hash(&level) {
        format!("matches level \"{level_name}\"")
    } else {
        format!("does NOT match level \"{level_name}\"")
    };
    let secs = seconds(&replay);
    let s = &replay.settings;
    let v = &s.vehicle;
    println!("{}", file.display());
    println!("  format:     replay version {version}");
    println!("  level:      hash {:#018x} ({matches})", replay.level_hash);
    println!("  players:    {}", replay.players);
    println!(
        "  ticks:      {} at {} Hz ({secs:.2} s)",
        replay.ticks(),
        s.tick_hz
    );
    println!(
        "  hashes:     {} stored, every {} ticks{}",
        replay.hashes.len(),
        replay.hash_interval,
        replay
            .hashes
            .last()
            .map_or(String::new(), |h| format!(", last at tick {}", h.0))
    );
    println!(
        "  settings:   gravity {}, wind ({}, {}), max speed {}, stick range {}, max bodies {}, rollback {} ticks",
        units(s.gravity),
        units(s.wind[0]),
        units(s.wind[1]),
        units(s.max_speed),
        units(s.stick_range),
        s.max_bodies,
        s.rollback_ticks
    );
    println!(
        "              vehicle: radius {}, half-length {}, mass {}, drive {}, jump {}, health {}",
        units(v.radius),
        units(v.half_length),
        units(v.mass),
        units(v.drive_speed),
        units(v.jump_speed),
        v.health
    );
    for (name, w) in [("shell", &s.shell), ("dirt", &s.dirt)] {
        println!(
            "              {name}: speed {}, {} radius {}, blast {}, impulse {}, damage {}, cooldown {} ticks",
            units(w.speed),
            if w.fills { "fill" } else { "crater" },
            units(w.crater_radius),
            units(w.blast_radius),
            units(w.impulse),
            w.damage,
            w.cooldown_ticks
        );
    }
    let per_min = if secs > 0.0 {
        format!("{:.0} bytes/minute", size as f64 * 60.0 / secs)
    } else {
        "no ticks".to_string()
    };
    println!("  size:       {size} bytes ({per_min})");
    Ok(ExitCode::SUCCESS)
}

/// `replay render`: re-simulates to `tick` (the last tick by default) and writes a PNG.
pub(crate) fn render(
    file: &Path,
    tick: Option<u32>,
    out: &Path,
    width: u32,
    level: Option<&Path>,
) -> Result<ExitCode, String> {
    let level = load_level(level)?;
    // Checked before the re-simulation, which may take a while.
    frame::camera(&level, width)?;
    let (world, tick, ticks) = simulate_to(file, tick, &level)?;
    let img = frame::render(&level, &world, width)?;
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    img.save(out)
        .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
    let (vehicles, projectiles, debris) = frame::census(&world);
    println!(
        "{}: tick {tick} of {ticks}: {vehicles} vehicles, {projectiles} projectiles, {debris} debris, {} terrain events; wrote {} ({}x{})",
        file.display(),
        world.terrain().events_applied(),
        out.display(),
        img.width(),
        img.height()
    );
    Ok(ExitCode::SUCCESS)
}

/// The world of replay `file` (recorded on `level`) re-simulated to `tick` (default: the
/// last), warning on stderr where it diverges from the recorded hashes.
pub(crate) fn world_at(file: &Path, tick: Option<u32>, level: &Level) -> Result<World, String> {
    simulate_to(file, tick, level).map(|(world, _, _)| world)
}

/// [`world_at`], with the tick reached and the replay's length.
fn simulate_to(file: &Path, tick: Option<u32>, level: &Level) -> Result<(World, u32, u32), String> {
    let (replay, _, _) = load(file)?;
    replay
        .check_level(level_hash(level))
        .map_err(|e| format!("{}: {e}", file.display()))?;
    let ticks = replay.ticks();
    let tick = tick.unwrap_or(ticks);
    if tick > ticks {
        return Err(format!(
            "{}: tick {tick} is past the end of the replay ({ticks} ticks)",
            file.display()
        ));
    }
    let mut world = World::new(level, replay.settings, usize::from(replay.players))
        .map_err(|e| format!("{}: {e}", file.display()))?;
    let mut diverged = None;
    for t in 0..tick {
        replay
            .advance(&mut world)
            .map_err(|e| format!("{}: tick {}: {e}", file.display(), t + 1))?;
        if diverged.is_none()
            && let Some(expected) = replay.hash_at(world.tick())
        {
            let found = world.state_hash();
            if expected != found {
                diverged = Some((world.tick(), expected, found));
            }
        }
    }
    if let Some((t, expected, found)) = diverged {
        eprintln!(
            "warning: the re-simulation diverged from the recording at tick {t} (expected {expected:#018x} found {found:#018x}); the picture shows this build's simulation"
        );
    }
    Ok((world, tick, ticks))
}
