//! craterfield: destructible 2D terrain on signed distance fields.
//!
//! The field ([`field2d`]) is a level graph of SDF primitives and operators minus carved
//! circles plus filled circles, kept in an explosion grid so that a query reads only its cell.
//! Everything on the collision path ([`det`], [`field2d`], [`sim`], [`net`]) is bit-for-bit
//! deterministic: see the determinism contract in `docs/ARCHITECTURE.md`, which also maps the
//! modules and the one direction of every arrow between them.
//!
//! A game starts from [`prelude`]: `use craterfield::prelude::*;`.

pub mod backend;
pub mod det;
#[cfg(feature = "emit")]
pub mod emit;
pub mod field2d;
pub mod files;
#[cfg(feature = "gpu")]
pub mod gpu;
#[cfg(feature = "march3d")]
pub mod march3d;
pub mod net;
pub mod prelude;
#[cfg(feature = "raster")]
pub mod render2d;
pub mod sim;
#[cfg(feature = "raster")]
pub mod visdiff;

/// The README's code examples, compiled and run as doctests.
#[doc = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))]
#[cfg(all(doctest, feature = "gpu"))]
pub struct ReadmeDoctests;
