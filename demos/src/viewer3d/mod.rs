//! The 3D world viewer: shows a builtin or RON scene through the library's GPU raymarcher
//! on eframe's device, with an orbit and a fly camera, a switch per emitter optimization
//! applied live, the plan's statistics, frame and pass times, and the CPU tracer's count
//! mode on demand.
//!
//! Module map: `app` (the eframe app and its frame), `source` (where the scene comes
//! from), `world` (the scene's compiler, options and the plan of the view), `camera`
//! (orbit and fly), `view` (the raymarcher, its texture and the pass's time), `panel` (the
//! side panel), `count` (the count mode), `timing` and `bench` (frame and pass times for
//! the panel and for `--bench`).

mod app;
mod bench;
mod camera;
mod count;
mod panel;
mod source;
mod timing;
mod view;
mod world;

pub use app::Viewer3dApp;
pub use camera::CameraMode;
pub use count::CountReport;
pub use source::SceneSource;
pub use world::PlanStats;
