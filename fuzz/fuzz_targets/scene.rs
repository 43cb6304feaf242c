//! 3D scene files: parse and validate; if the scene loads, compile it for its camera.
#![no_main]

use craterfield::march3d::compile::{CompileOptions, emit};
use craterfield::march3d::scene::Scene;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = Scene::from_ron(text) else {
        return;
    };
    if let Ok(camera) = scene.camera.camera() {
        let _ = emit(&scene, &camera, &CompileOptions::default());
    }
});
