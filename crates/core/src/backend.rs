//! The CPU instruction sets the SIMD evaluators run on: their names, their detection at run
//! time, the one environment variable that chooses among them, and the one error.
//!
//! Two lane sets use them, and keep fused operations apart on purpose (the reason is in
//! `docs/ARCHITECTURE.md`, "One SIMD foundation, two lane sets"):
//!
//! * [`crate::simd`], the deterministic field's exact lanes: no FMA, the same bits on every
//!   backend. It has code for every [`Backend`].
//! * `craterfield-march3d`'s `simd`, the CPU sphere tracer: the same tokens extended with
//!   fused multiply-adds, for speed. It has code for `scalar`, `avx2` and `neon`
//!   (`TRACER_BACKENDS` there).
//!
//! What they share is here. A backend is *available* when this CPU has its instruction set
//! and this build compiled it ([`Backend::is_available`]); the per-architecture files build
//! their tokens only after that check, which is what makes their intrinsics sound. `avx2`
//! means AVX2 together with FMA3 for both stacks: every CPU with AVX2 that either stack
//! targets has FMA3, and one meaning per name keeps a forced choice the same for both.
//!
//! Choosing: each stack takes the widest backend it has code for that is available
//! ([`Backend::best_of`]). The environment variable `CRATERFIELD_BACKEND` (`scalar`, `sse2`,
//! `avx2`, `avx512`, `neon`) caps that choice at the named instruction set: a stack without
//! code for the name takes the widest of its backends the named set includes (`sse2` gives
//! the tracer `scalar`; `avx512` gives it `avx2`). APIs also take an explicit [`Backend`].
//! Building with the feature `force-scalar` leaves `scalar` the only available backend.

use std::fmt;
use std::str::FromStr;
use std::sync::OnceLock;

use thiserror::Error;

/// The environment variable that caps the backend every evaluator chooses by default.
pub const BACKEND_ENV: &str = "CRATERFIELD_BACKEND";

/// An instruction set a SIMD evaluator can run on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Backend {
    /// One lane, plain Rust; every platform.
    Scalar,
    /// 4 lanes, x86_64 baseline.
    Sse2,
    /// 8 lanes, x86_64 with AVX2 and FMA3 (the deterministic field uses no FMA).
    Avx2,
    /// 16 lanes, x86_64 with AVX-512F.
    Avx512,
    /// 4 lanes, aarch64 Advanced SIMD.
    Neon,
}

/// A backend that this CPU or build lacks, one an evaluator has no code for, or a name no
/// backend has.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum BackendError {
    /// The backend exists but this CPU or build lacks it.
    #[error("backend {backend} is not available on this machine (available: {available})")]
    Unavailable {
        /// The backend asked for.
        backend: Backend,
        /// What is available to the evaluator asked, comma-separated.
        available: String,
    },
    /// The evaluator has no code for this backend.
    #[error("{evaluator} has no {backend} backend (it has {implemented})")]
    Unsupported {
        /// The backend asked for.
        backend: Backend,
        /// Which evaluator was asked.
        evaluator: &'static str,
        /// The backends it has code for, comma-separated.
        implemented: String,
    },
    /// The name is not a backend.
    #[error("unknown backend `{name}` (expected scalar, sse2, avx2, avx512 or neon)")]
    UnknownName {
        /// The name given.
        name: String,
    },
}

impl Backend {
    /// Every backend, narrowest first.
    pub const ALL: [Backend; 5] = [
        Backend::Scalar,
        Backend::Sse2,
        Backend::Avx2,
        Backend::Avx512,
        Backend::Neon,
    ];

    /// The lowercase name (`scalar`, `sse2`, `avx2`, `avx512`, `neon`).
    pub fn name(self) -> &'static str {
        match self {
            Backend::Scalar => "scalar",
            Backend::Sse2 => "sse2",
            Backend::Avx2 => "avx2",
            Backend::Avx512 => "avx512",
            Backend::Neon => "neon",
        }
    }

    /// Lanes per register.
    pub fn width(self) -> usize {
        match self {
            Backend::Scalar => 1,
            Backend::Sse2 | Backend::Neon => 4,
            Backend::Avx2 => 8,
            Backend::Avx512 => 16,
        }
    }

    /// Whether this CPU has the instruction set and this build compiled code for it: the
    /// one runtime detection both lane stacks rely on.
    pub fn is_available(self) -> bool {
        match self {
            Backend::Scalar => true,
            #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
            Backend::Sse2 => is_x86_feature_detected!("sse2"),
            #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
            Backend::Avx2 => is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma"),
            #[cfg(all(target_arch = "x86_64", not(feature = "force-scalar")))]
            Backend::Avx512 => is_x86_feature_detected!("avx512f"),
            #[cfg(all(target_arch = "aarch64", not(feature = "force-scalar")))]
            Backend::Neon => std::arch::is_aarch64_feature_detected!("neon"),
            #[allow(unreachable_patterns)]
            _ => false,
        }
    }

    /// The backends this machine can run, narrowest first.
    pub fn available() -> Vec<Backend> {
        available_of(&Backend::ALL)
    }

    /// `Ok(self)` if available, else an error listing what is.
    pub fn check(self) -> Result<Backend, BackendError> {
        self.check_of(&Backend::ALL, "the field evaluator")
    }

    /// `Ok(self)` if `evaluator` has code for it (it is in `implemented`) and it is
    /// available, else an error saying which of the two fails.
    pub fn check_of(
        self,
        implemented: &[Backend],
        evaluator: &'static str,
    ) -> Result<Backend, BackendError> {
        if !implemented.contains(&self) {
            return Err(BackendError::Unsupported {
                backend: self,
                evaluator,
                implemented: names(implemented.iter().copied()),
            });
        }
        if !self.is_available() {
            return Err(self.unavailable_to(implemented));
        }
        Ok(self)
    }

    /// The error for this backend when it is not available to an evaluator that has code
    /// for `implemented` (it lists what is).
    pub fn unavailable_to(self, implemented: &[Backend]) -> BackendError {
        BackendError::Unavailable {
            backend: self,
            available: names(available_of(implemented)),
        }
    }

    /// The widest available backend, whatever [`BACKEND_ENV`] says.
    pub fn widest() -> Backend {
        widest_of(&Backend::ALL, None)
    }

    /// The backend to use by default: the widest available, capped by [`BACKEND_ENV`].
    /// Chosen once per process.
    pub fn best() -> Backend {
        static BEST: OnceLock<Backend> = OnceLock::new();
        *BEST.get_or_init(|| Backend::best_of(&Backend::ALL))
    }

    /// The default backend of an evaluator that has code for `implemented`: the widest of
    /// them that is available and that the instruction set named by [`BACKEND_ENV`] (if
    /// set) includes. The variable is read once per process; a name that is unknown or not
    /// available here is reported on standard error once and ignored.
    pub fn best_of(implemented: &[Backend]) -> Backend {
        widest_of(implemented, forced())
    }

    /// Whether code for `other` runs wherever this instruction set does (every x86_64
    /// extension includes the ones below it; everything includes scalar).
    pub fn includes(self, other: Backend) -> bool {
        use Backend::{Avx2, Avx512, Neon, Scalar, Sse2};
        matches!(
            (self, other),
            (_, Scalar)
                | (Sse2 | Avx2 | Avx512, Sse2)
                | (Avx2 | Avx512, Avx2)
                | (Avx512, Avx512)
                | (Neon, Neon)
        )
    }
}

/// The backend [`BACKEND_ENV`] names, if it names an available one.
fn forced() -> Option<Backend> {
    static FORCED: OnceLock<Option<Backend>> = OnceLock::new();
    *FORCED.get_or_init(|| {
        let name = std::env::var(BACKEND_ENV).ok()?;
        match name.parse::<Backend>().and_then(Backend::check) {
            Ok(b) => Some(b),
            Err(e) => {
                eprintln!("{BACKEND_ENV}: {e}; ignoring it");
                None
            }
        }
    })
}

fn available_of(implemented: &[Backend]) -> Vec<Backend> {
    let mut out: Vec<Backend> = implemented
        .iter()
        .copied()
        .filter(|b| b.is_available())
        .collect();
    out.sort();
    out
}

fn widest_of(implemented: &[Backend], cap: Option<Backend>) -> Backend {
    available_of(implemented)
        .into_iter()
        .filter(|b| cap.is_none_or(|c| c.includes(*b)))
        .max_by_key(|b| b.width())
        .unwrap_or(Backend::Scalar)
}

fn names(backends: impl IntoIterator<Item = Backend>) -> String {
    backends
        .into_iter()
        .map(Backend::name)
        .collect::<Vec<_>>()
        .join(", ")
}

impl fmt::Display for Backend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Backend {
    type Err = BackendError;
    fn from_str(s: &str) -> Result<Backend, BackendError> {
        Backend::ALL
            .into_iter()
            .find(|b| b.name() == s.trim().to_ascii_lowercase())
            .ok_or_else(|| BackendError::UnknownName { name: s.into() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_scalar_is_always_there() {
        for b in Backend::ALL {
            assert_eq!(b.name().parse::<Backend>(), Ok(b));
        }
        assert!(Backend::Scalar.is_available());
        assert!(Backend::available().contains(&Backend::Scalar));
        let e = "mmx".parse::<Backend>().unwrap_err();
        assert!(e.to_string().contains("mmx"), "{e}");
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn neon_is_unavailable_on_x86() {
        let e = Backend::Neon.check().unwrap_err().to_string();
        assert!(e.contains("neon") && e.contains("scalar"), "{e}");
    }

    #[test]
    fn an_evaluator_without_code_for_a_backend_says_so() {
        let tracer = [Backend::Scalar, Backend::Avx2, Backend::Neon];
        let e = Backend::Sse2.check_of(&tracer, "the tracer").unwrap_err();
        assert!(
            matches!(e, BackendError::Unsupported { .. }),
            "{e}: sse2 is not the tracer's"
        );
        assert!(e.to_string().contains("scalar, avx2, neon"), "{e}");
        assert_eq!(
            Backend::Scalar.check_of(&tracer, "the tracer"),
            Ok(Backend::Scalar)
        );
    }

    #[test]
    fn a_cap_keeps_each_evaluator_within_the_named_instruction_set() {
        let tracer = [Backend::Scalar, Backend::Avx2, Backend::Neon];
        for cap in Backend::available() {
            let chosen = widest_of(&tracer, Some(cap));
            assert!(cap.includes(chosen), "{cap} chose {chosen}");
            assert_eq!(
                widest_of(&Backend::ALL, Some(cap)),
                cap,
                "the field runs {cap} itself"
            );
        }
        assert_eq!(widest_of(&tracer, Some(Backend::Scalar)), Backend::Scalar);
        assert_eq!(widest_of(&tracer, Some(Backend::Sse2)), Backend::Scalar);
        assert!(Backend::Avx512.includes(Backend::Avx2));
        assert!(!Backend::Avx2.includes(Backend::Avx512));
        assert!(!Backend::Neon.includes(Backend::Sse2));
    }
}
