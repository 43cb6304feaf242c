//! Errors of level files and level graphs.

use thiserror::Error;

/// What is wrong with a level file or a level graph. Every variant names where (a node path
/// such as `nodes["caves"].Union[2].Circle.radius`, or a position in the file) and why.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LevelError {
    /// The file could not be read.
    #[error("cannot read level file {path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The input is larger than the parser accepts.
    #[error("level file is {size} bytes, over the limit of {limit} bytes")]
    TooLarge {
        /// Input size in bytes.
        size: usize,
        /// The limit.
        limit: usize,
    },
    /// The text is not a valid level (syntax, unknown node kind, missing or mistyped field).
    #[error("level file is not valid: {0}")]
    Parse(String),
    /// A value is out of its domain.
    #[error("{path}: {reason}")]
    Invalid {
        /// Where.
        path: String,
        /// Why.
        reason: String,
    },
    /// A `Ref` names no node of the level.
    #[error("{path}: unknown node reference \"{name}\" (the level names: {known})")]
    UnknownRef {
        /// Where.
        path: String,
        /// The missing name.
        name: String,
        /// The names the level defines.
        known: String,
    },
    /// References form a cycle.
    #[error("{path}: reference cycle {cycle}")]
    Cycle {
        /// Where the cycle closes.
        path: String,
        /// The cycle, e.g. `a -> b -> a`.
        cycle: String,
    },
    /// The graph is too large or too deep.
    #[error("{path}: graph exceeds the {what} limit of {limit}")]
    Limit {
        /// Where the limit was crossed.
        path: String,
        /// Which limit.
        what: &'static str,
        /// The limit.
        limit: u64,
    },
    /// One evaluation of the compiled level costs more than the limit allows: every query
    /// and every pixel would pay it.
    #[error(
        "root: one evaluation costs {work} work units ({instructions} tape instructions plus polygon edges, height-profile segments and noise), over the limit of {limit} (GraphLimits::max_eval_work): simplify the level"
    )]
    TooCostly {
        /// Work units of one evaluation ([`crate::tape::EvalCost::work`]).
        work: u64,
        /// Instructions of the compiled tape.
        instructions: usize,
        /// The limit.
        limit: u64,
    },
}
