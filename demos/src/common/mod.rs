//! What both demos share: the command line, the frame driver behind `--frames` and
//! `--screenshot`, the texture that carries a library renderer's picture into egui, and
//! the start-up that turns "no GPU" into a clear message.

mod args;
mod driver;
mod gpu_image;
mod launch;
mod stats;

pub use args::{ArgsError, RunArgs};
pub use driver::{FrameDriver, FrameStep, RunStatus};
pub use gpu_image::GpuImage;
pub use launch::{Build, LaunchError, launch, require_adapter, wgpu_setup};
pub use stats::Tails;
