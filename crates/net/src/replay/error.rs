//! Why a replay did not verify.

use thiserror::Error;

use craterfield_sim::SimError;

/// Why a replay did not verify.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum VerifyError {
    /// The replay was recorded on another level.
    #[error("the replay was recorded on level {expected:#018x}, not on this level ({found:#018x})")]
    LevelMismatch {
        /// The level hash stored in the replay.
        expected: u64,
        /// The hash of the level given.
        found: u64,
    },
    /// The replay breaks an invariant of [`Replay`](super::Replay) (see [`Replay::validate`](super::Replay::validate)).
    #[error("the replay is inconsistent: {detail}")]
    Inconsistent {
        /// Which invariant, and where.
        detail: String,
    },
    /// The simulation rejected the replay's settings, players or inputs.
    #[error("simulation error: {0}")]
    Sim(#[from] SimError),
    /// The re-simulation's state hash differs from the stored one.
    #[error("diverged at tick {tick}: stored hash {expected:#018x}, simulated {found:#018x}")]
    Diverged {
        /// The tick of the first mismatching hash.
        tick: u32,
        /// The stored hash.
        expected: u64,
        /// The re-simulation's hash.
        found: u64,
    },
    /// A stored hash is for a tick the re-simulation never stopped at (it ended earlier,
    /// or its tick counter skipped it).
    #[error(
        "the stored hash for tick {tick} was never compared: the simulation never reached that tick"
    )]
    HashNotReached {
        /// The tick of the stored hash.
        tick: u32,
    },
}
