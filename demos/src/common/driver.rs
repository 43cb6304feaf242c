//! [`FrameDriver`]: runs a demo for a fixed number of frames (`--frames`, `--bench`), takes
//! the window's screenshot (`--screenshot`) and closes the window, recording whether the
//! run succeeded for the binary's exit status.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use super::RunArgs;

/// How the run ended, shared with the binary's `main` (the app itself is owned by eframe).
pub type RunStatus = Arc<Mutex<Result<(), String>>>;

/// Counts frames and ends the run as the command line asked.
#[derive(Debug)]
pub struct FrameDriver {
    limit: Option<u32>,
    screenshot: Option<PathBuf>,
    frames: u32,
    screenshot_sent: bool,
    closing: bool,
    status: RunStatus,
}

/// What this frame is, for the app.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameStep {
    /// Frames begun so far, this one included.
    pub frame: u32,
    /// Whether this is the last frame the run draws (print reports now).
    pub last: bool,
}

impl FrameDriver {
    /// A driver for `args`; its outcome goes to `status`.
    pub fn new(args: &RunArgs, status: RunStatus) -> FrameDriver {
        FrameDriver {
            limit: args.frame_limit(),
            screenshot: args.screenshot.clone(),
            frames: 0,
            screenshot_sent: false,
            closing: false,
            status,
        }
    }

    /// A driver that never ends the run (tests, interactive use).
    pub fn interactive() -> FrameDriver {
        FrameDriver::new(&RunArgs::default(), Arc::new(Mutex::new(Ok(()))))
    }

    /// Call once at the start of every frame.
    pub fn begin_frame(&mut self, ctx: &egui::Context) -> FrameStep {
        self.frames += 1;
        let Some(limit) = self.limit else {
            return FrameStep {
                frame: self.frames,
                last: false,
            };
        };
        // A timed run draws continuously, not only on input.
        ctx.request_repaint();
        let last = self.frames == limit;
        if self.frames >= limit && !self.closing {
            match self.screenshot.clone() {
                Some(path) if !self.screenshot_sent => {
                    self.request_screenshot(ctx, path);
                    self.screenshot_sent = true;
                }
                Some(_) => {}
                None => self.close(ctx),
            }
        }
        FrameStep {
            frame: self.frames,
            last,
        }
    }

    /// Asks for the next frame's image; the callback saves it and closes the window.
    fn request_screenshot(&mut self, ctx: &egui::Context, path: PathBuf) {
        let status = self.status.clone();
        let closer = ctx.clone();
        let callback = egui::ScreenshotCallback::new(move |image| {
            let saved = save_color_image(&image, &path);
            match &saved {
                Ok(()) => eprintln!("wrote {}", path.display()),
                Err(e) => eprintln!("error: {e}"),
            }
            *status.lock().unwrap_or_else(|e| e.into_inner()) = saved;
            closer.send_viewport_cmd(egui::ViewportCommand::Close);
            closer.request_repaint();
        });
        ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(callback));
    }

    fn close(&mut self, ctx: &egui::Context) {
        self.closing = true;
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

/// Saves an egui screenshot as PNG.
fn save_color_image(image: &egui::ColorImage, path: &std::path::Path) -> Result<(), String> {
    let [w, h] = image.size;
    let bytes: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_array()).collect();
    let rgba = image::RgbaImage::from_raw(w as u32, h as u32, bytes)
        .ok_or_else(|| format!("screenshot of {w}x{h} pixels has the wrong length"))?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    rgba.save(path)
        .map_err(|e| format!("writing the screenshot {}: {e}", path.display()))
}
