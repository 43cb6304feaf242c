//! Starting a demo in a native window: a check for an adapter before any window opens,
//! eframe's native runner on the device of [`super::wgpu_setup`], and the errors that the
//! binaries turn into exit statuses.

use std::sync::{Arc, Mutex};

use super::device::wgpu_setup;

use thiserror::Error;

use super::driver::RunStatus;
use super::{FrameDriver, RunArgs};

/// Why a demo did not run to the end.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LaunchError {
    /// wgpu found no adapter: the demos need one (the CLI's CPU paths do not).
    #[error(
        "no GPU adapter: {0}. The demos draw with wgpu and need a GPU or a software driver \
         (on Linux, Mesa's lavapipe: the package mesa-vulkan-drivers). Without one, the \
         command-line tool renders on the CPU: `craterfield render` and `craterfield march3d`."
    )]
    NoAdapter(String),
    /// eframe could not open the window or its renderer (no display, for example).
    #[error("could not open the window: {0}")]
    Window(String),
    /// The run itself failed (the screenshot could not be written, for example).
    #[error("{0}")]
    Run(String),
}

impl LaunchError {
    /// The process exit status for this error.
    pub fn exit_code(&self) -> i32 {
        match self {
            LaunchError::NoAdapter(_) => 3,
            LaunchError::Window(_) => 4,
            LaunchError::Run(_) => 1,
        }
    }
}

/// Fails with [`LaunchError::NoAdapter`] when wgpu finds no adapter at all.
pub fn require_adapter() -> Result<wgpu::AdapterInfo, LaunchError> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
        .map(|a| a.get_info())
        .map_err(|e| LaunchError::NoAdapter(e.to_string()))
}

/// The app constructor a binary hands to [`launch`].
pub type Build = Box<
    dyn FnOnce(&eframe::CreationContext<'_>, FrameDriver) -> Result<Box<dyn eframe::App>, String>,
>;

/// Opens the window titled `title` and runs the app `build` makes until the window closes
/// (or the command line's frame count is reached).
pub fn launch(title: &str, args: &RunArgs, build: Build) -> Result<(), LaunchError> {
    let adapter = require_adapter()?;
    eprintln!(
        "{title}: GPU adapter {} ({:?})",
        adapter.name, adapter.backend
    );
    let status: RunStatus = Arc::new(Mutex::new(Ok(())));
    let driver = FrameDriver::new(args, status.clone());
    let mut wgpu_options = egui_wgpu::WgpuConfiguration {
        wgpu_setup: wgpu_setup(),
        ..Default::default()
    };
    if args.bench || args.frames.is_some() {
        // Timed and scripted runs draw as fast as they can.
        wgpu_options.surface.present_mode = wgpu::PresentMode::AutoNoVsync;
    }
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(title)
            .with_inner_size([args.size[0] as f32, args.size[1] as f32])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options,
        ..Default::default()
    };
    eframe::run_native(
        title,
        options,
        Box::new(move |cc| build(cc, driver).map_err(Into::into)),
    )
    .map_err(|e| match e {
        eframe::Error::AppCreation(e) => LaunchError::Run(e.to_string()),
        other => LaunchError::Window(other.to_string()),
    })?;
    status
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .clone()
        .map_err(LaunchError::Run)
}
