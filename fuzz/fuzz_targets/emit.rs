//! Levels to WGSL: a level that loads is emitted within the shader budget, and what the
//! emitter writes must parse and validate with naga.
#![no_main]

use craterfield::emit::{ShaderBudget, TerrainEmitter};
use craterfield::field2d::Level;
use libfuzzer_sys::fuzz_target;
use naga::valid::{Capabilities, ValidationFlags, Validator};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(level) = Level::from_ron(text) else {
        return;
    };
    let emitter = TerrainEmitter::new(level.graph());
    let plan = emitter.plan(None, 32.0);
    let Ok(base) = emitter.emit_within(&plan, &ShaderBudget::default()) else {
        return;
    };
    // A fragment shader entry point that calls the emitted function.
    let module = format!(
        "{base}\n@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {{ return base_sample(p.xy); }}\n"
    );
    let parsed = naga::front::wgsl::parse_str(&module)
        .unwrap_or_else(|e| panic!("emitted WGSL does not parse: {}", e.emit_to_string(&module)));
    Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&parsed)
        .unwrap_or_else(|e| {
            panic!(
                "emitted WGSL does not validate: {}",
                e.emit_to_string(&module)
            )
        });
});
