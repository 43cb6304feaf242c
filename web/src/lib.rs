//! craterfield's destruction sandbox as a web page: the `sandbox` demo's app on eframe's
//! web runner, drawing with the library's refine renderer on the browser's WebGPU.
//!
//! `scripts/web` builds this package for `wasm32-unknown-unknown`, runs wasm-bindgen on it
//! and serves `index.html` beside the output; the page calls [`start`] with its canvas's id
//! and shows the error where the browser has no WebGPU. On other targets the package is
//! empty.

#![cfg(target_family = "wasm")]

use std::cell::{Cell, RefCell};

use craterfield_demos::common::{FrameDriver, wgpu_setup};
use craterfield_demos::sandbox::SandboxApp;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

thread_local! {
    /// The running app's runner: dropping it would stop the app.
    static RUNNER: RefCell<Option<eframe::WebRunner>> = const { RefCell::new(None) };
    /// Frames the app has drawn, for the page and its tests.
    static FRAMES: Cell<u32> = const { Cell::new(0) };
    /// The intervals between the last frames, milliseconds (at most `KEPT_FRAME_TIMES`).
    static FRAME_TIMES: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
    static LAST_FRAME: Cell<Option<web_time::Instant>> = const { Cell::new(None) };
}

/// Frame intervals kept for [`frame_times_ms`].
const KEPT_FRAME_TIMES: usize = 1000;

/// Starts the sandbox on the canvas whose id is `canvas_id`. Resolves once the app runs;
/// rejects with a message when the canvas is missing, the browser gives no WebGPU device,
/// or the app cannot start.
#[wasm_bindgen]
pub async fn start(canvas_id: String) -> Result<(), JsValue> {
    // A second logger is refused; the first one is as good.
    let _ = eframe::WebLogger::init(log::LevelFilter::Warn);
    let canvas = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id(&canvas_id))
        .ok_or_else(|| JsValue::from_str(&format!("no element with id {canvas_id:?}")))?
        .dyn_into::<web_sys::HtmlCanvasElement>()
        .map_err(|_| JsValue::from_str(&format!("{canvas_id:?} is not a canvas")))?;
    let options = eframe::WebOptions {
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: wgpu_setup(),
            ..Default::default()
        },
        ..Default::default()
    };
    let runner = eframe::WebRunner::new();
    runner
        .start(
            canvas,
            options,
            Box::new(|cc| {
                let app = SandboxApp::new(cc, None, FrameDriver::interactive(), false)?;
                Ok(Box::new(Counted(app)))
            }),
        )
        .await?;
    RUNNER.with(|r| r.replace(Some(runner)));
    Ok(())
}

/// Frames the sandbox has drawn since it started.
#[wasm_bindgen]
pub fn frames() -> u32 {
    FRAMES.with(Cell::get)
}

/// The intervals between the sandbox's last frames (up to 1000), in milliseconds: the
/// frame time a player sees, for the page's tests.
#[wasm_bindgen]
pub fn frame_times_ms() -> Vec<f64> {
    FRAME_TIMES.with(|t| t.borrow().clone())
}

/// The sandbox, counting its frames and timing them.
struct Counted(SandboxApp);

impl eframe::App for Counted {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.0.ui(ui, frame);
        FRAMES.with(|f| f.set(f.get().saturating_add(1)));
        let now = web_time::Instant::now();
        if let Some(last) = LAST_FRAME.with(|l| l.replace(Some(now))) {
            FRAME_TIMES.with(|t| {
                let mut t = t.borrow_mut();
                if t.len() == KEPT_FRAME_TIMES {
                    t.remove(0);
                }
                t.push((now - last).as_secs_f64() * 1e3);
            });
        }
    }
}
