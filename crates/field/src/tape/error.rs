//! Why a tape evaluation could not run: the one error of every evaluator of a tape.

use craterfield_core::backend::BackendError;

/// Why a batch evaluation could not run.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum EvalError {
    /// The output slice is not as long as the input.
    #[error("output has {output} slots for {input} points")]
    LengthMismatch {
        /// Points given.
        input: usize,
        /// Output slots given.
        output: usize,
    },
    /// The backend cannot run here.
    #[error(transparent)]
    Backend(#[from] BackendError),
}

/// `Ok` when the output has one slot per input point.
pub(crate) fn check(input: usize, output: usize) -> Result<(), EvalError> {
    if input == output {
        Ok(())
    } else {
        Err(EvalError::LengthMismatch { input, output })
    }
}
