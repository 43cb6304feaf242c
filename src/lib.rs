//! craterfield: destructible 2D terrain on signed distance fields.
//!
//! The field ([`field2d`]) is a level graph of SDF primitives and operators minus carved
//! circles plus filled circles, kept in an explosion grid so that a query reads only its cell.
//! Everything on the collision path ([`det`], [`field2d`], [`sim`], [`net`]) is bit-for-bit
//! deterministic: see the determinism contract in `docs/ARCHITECTURE.md`, which also maps the
//! crates of the workspace and the one direction of every arrow between them.
//!
//! This crate is the facade: each module is one of the workspace's crates, re-exported under
//! the name games use, and present with the feature that brings it in. A dedicated server
//! builds it without default features: the field, the world and the network formats, and no
//! renderer, emitter or 3D code.
//!
//! A game starts from [`prelude`]: `use craterfield::prelude::*;`.

#![forbid(unsafe_code)]

pub use craterfield_core::{backend, det, files};
pub use craterfield_field as field2d;
#[cfg(feature = "gpu")]
pub use craterfield_gpu as gpu;
#[cfg(feature = "march3d")]
pub use craterfield_march3d as march3d;
pub use craterfield_net as net;
#[cfg(feature = "raster")]
pub use craterfield_render2d as render2d;
#[cfg(feature = "emit")]
pub use craterfield_render2d::emit;
pub use craterfield_sim as sim;
#[cfg(feature = "raster")]
pub use craterfield_visdiff as visdiff;
#[cfg(any(feature = "emit", feature = "march3d"))]
pub use craterfield_wgsl as wgsl;

pub mod prelude;

/// The README's code examples, compiled and run as doctests.
#[doc = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))]
#[cfg(all(doctest, feature = "gpu"))]
pub struct ReadmeDoctests;
