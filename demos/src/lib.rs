//! craterfield's interactive demos: [`sandbox`], destruction on the GPU renderer with a
//! vehicle on the deterministic simulation and replays, and [`viewer3d`], the 3D world
//! viewer on the GPU raymarcher. Both are eframe applications on the wgpu backend that
//! draw with the library's renderers on eframe's own device, the way a game embeds them.
//!
//! The binaries in `src/bin` only parse the command line and start eframe; the apps live
//! here so that the tests drive the same code through egui_kittest.

pub mod common;
pub mod sandbox;
pub mod viewer3d;
