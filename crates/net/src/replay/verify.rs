//! Verifying a replay: re-simulating it and comparing every stored state hash.

use craterfield_field::Level;
use craterfield_sim::World;

use super::{Replay, VerifyError};

/// What [`verify`] checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VerifyReport {
    /// Ticks simulated.
    pub ticks: u32,
    /// Stored hashes compared (all of them, when verification succeeds).
    pub hashes_checked: usize,
    /// The state hash after the last tick.
    pub final_hash: u64,
}

/// Re-simulates `replay` on `level` and compares every stored hash.
///
/// Checks the level hash first, then builds the world from the replay's settings, advances
/// it once per input row ([`Replay::advance`]: the tick's edits, then its step) and
/// compares the stored hash of every tick the world reaches (including its starting tick).
/// Stops at the first mismatch.
pub fn verify(replay: &Replay, level: &Level) -> Result<VerifyReport, VerifyError> {
    replay
        .validate()
        .map_err(|detail| VerifyError::Inconsistent { detail })?;
    replay.check_level(craterfield_sim::level_hash(level))?;
    let mut world = World::new(level, replay.settings, usize::from(replay.players))?;
    let mut pending = replay.hashes.iter().peekable();
    let mut checked = 0;
    checked += check_hashes(&mut pending, world.tick(), world.state_hash())?;
    for _ in 0..replay.ticks() {
        replay.advance(&mut world)?;
        checked += check_hashes(&mut pending, world.tick(), world.state_hash())?;
    }
    if let Some(&&(tick, _)) = pending.peek() {
        return Err(VerifyError::HashNotReached { tick });
    }
    Ok(VerifyReport {
        ticks: replay.ticks(),
        hashes_checked: checked,
        final_hash: world.state_hash(),
    })
}

/// Compares the stored hashes up to `tick` against `hash`; a stored tick that was skipped
/// over is an error. Returns how many were compared.
fn check_hashes<'a>(
    pending: &mut std::iter::Peekable<impl Iterator<Item = &'a (u32, u64)>>,
    tick: u32,
    hash: u64,
) -> Result<usize, VerifyError> {
    let mut checked = 0;
    while let Some(&&(t, expected)) = pending.peek() {
        if t > tick {
            break;
        }
        if t < tick {
            return Err(VerifyError::HashNotReached { tick: t });
        }
        if expected != hash {
            return Err(VerifyError::Diverged {
                tick,
                expected,
                found: hash,
            });
        }
        pending.next();
        checked += 1;
    }
    Ok(checked)
}
