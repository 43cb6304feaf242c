//! craterfield's interactive demos: [`sandbox`], destruction on the GPU renderer with a
//! vehicle on the deterministic simulation and replays, and [`viewer3d`], the 3D world
//! viewer on the GPU raymarcher. Both are eframe applications on the wgpu backend that
//! draw with the library's renderers on eframe's own device, the way a game embeds them.
//!
//! The binaries in `src/bin` only parse the command line and start eframe; the apps live
//! here so that the tests drive the same code through egui_kittest, and so that the
//! `craterfield-web` package runs the sandbox in a browser (WebAssembly on WebGPU; `web`
//! has the page's file handling there). The 3D viewer is native only.

pub mod common;
pub mod sandbox;
#[cfg(not(target_family = "wasm"))]
pub mod viewer3d;
#[cfg(target_family = "wasm")]
pub mod web;
