//! What both demos share: the command line, the frame driver behind `--frames` and
//! `--screenshot`, the texture that carries a library renderer's picture into egui, and
//! the device they ask for, and the native start-up that turns "no GPU" into a clear
//! message.

mod args;
mod device;
mod driver;
mod gpu_image;
#[cfg(not(target_family = "wasm"))]
mod launch;
mod stats;

pub use args::{ArgsError, RunArgs};
pub use device::wgpu_setup;
pub use driver::{FrameDriver, FrameStep, RunStatus};
pub use gpu_image::GpuImage;
#[cfg(not(target_family = "wasm"))]
pub use launch::{Build, LaunchError, launch, require_adapter};
pub use stats::Tails;
