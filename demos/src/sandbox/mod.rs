//! The destruction sandbox: a level drawn by the library's GPU terrain renderer, edited
//! with the mouse through the simulation's event path, a drivable vehicle and scripted
//! opponents on the deterministic simulation, and a recording that can be saved, loaded,
//! verified and scrubbed.
//!
//! The files: [`session`] (the match and its clock), [`timeline`] (the recording),
//! `ai` (the opponents), `controls` (keys and pointer to inputs), [`view`] (pan and
//! zoom), [`terrain_view`] (the GPU renderer in a panel), `overlays` (what is painted
//! over it), `panel` (the side panel), `bench` (`--bench`), `app` (the eframe app).

mod ai;
mod app;
mod bench;
mod controls;
mod overlays;
mod panel;
pub mod session;
pub mod terrain_view;
pub mod timeline;
pub mod view;

pub use app::{Brush, SandboxApp, TERRAIN_VIEW_LABEL};
pub use overlays::Overlays;
pub use session::{Mode, PLAYERS, Session, Verified};
