//! What an emitted module may cost the GPU compiler that receives it, and the error of a
//! module past that budget.

use thiserror::Error;

/// What an emitted module may cost the GPU compiler that receives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShaderBudget {
    /// Longest module text, bytes.
    pub max_bytes: usize,
    /// Most statements once every call is inlined (each emitter counts them).
    pub max_inlined_statements: u64,
}

impl ShaderBudget {
    /// [`EmitError::TooLarge`] when a module of `inlined` statements (once every call is
    /// inlined) is past the budget: checked before the text is written.
    pub fn check_inlined(&self, inlined: u64) -> Result<(), EmitError> {
        if inlined > self.max_inlined_statements {
            return Err(EmitError::TooLarge {
                what: "inlined statements",
                size: inlined,
                limit: self.max_inlined_statements,
            });
        }
        Ok(())
    }

    /// [`EmitError::TooLarge`] when a module's `text` is past the budget.
    pub fn check_text(&self, text: &str) -> Result<(), EmitError> {
        if text.len() > self.max_bytes {
            return Err(EmitError::TooLarge {
                what: "text bytes",
                size: text.len() as u64,
                limit: self.max_bytes as u64,
            });
        }
        Ok(())
    }
}

impl Default for ShaderBudget {
    /// 1 MiB of text and 20,000 inlined statements: the shipped levels need at most 43
    /// statements and 21 KB, the prospero expression (about 6,600 operations) 6,603 and
    /// 316 KB, while Mesa's compiler went past 9 GB inlining 2^12 copies of a shared node.
    fn default() -> Self {
        ShaderBudget {
            max_bytes: 1 << 20,
            max_inlined_statements: 20_000,
        }
    }
}

/// Why a module was not emitted. Exhaustive: the emitters' callers map it onto their own
/// errors field by field (the 3D raymarcher's `MarchGpuError::TooLarge` adds the plan's key).
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum EmitError {
    /// The module is past its [`ShaderBudget`].
    #[error(
        "the level's shader would be too large for a GPU compiler: {what} {size} past the budget of {limit} (render it on the CPU)"
    )]
    TooLarge {
        /// `text bytes` or `inlined statements`.
        what: &'static str,
        /// What the module needs.
        size: u64,
        /// The budget.
        limit: u64,
    },
}
