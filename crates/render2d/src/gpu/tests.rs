//! Every hand-written WGSL pass, assembled exactly as the renderer assembles it, parses and
//! validates with naga (no GPU needed), over the emitted base fields of the example levels;
//! and the uniform structs have the same layout on both sides.

use super::shaders;
use super::uniforms::{FrameUniform, GpuBlockState, GpuCell, GpuCellProof, GpuEvent, GpuWork};
use crate::emit::terrain2d::TerrainEmitter;
use craterfield_field::Level;

fn validate(name: &str, source: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    module
}

fn level_fields() -> Vec<(String, String)> {
    // The example levels are the workspace's, two folders up.
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    ["default", "caverns", "skyrealm"]
        .iter()
        .map(|name| {
            let level = Level::load(std::path::Path::new(&format!("{root}/levels/{name}.ron")))
                .expect("example level");
            let emitter = TerrainEmitter::new(level.graph());
            let plan = emitter.plan(None, 32.0);
            (name.to_string(), emitter.emit(&plan))
        })
        .collect()
}

#[test]
fn every_pass_validates_over_every_example_level() {
    validate("reconstruct", &shaders::reconstruct_module());
    validate("upsample", &shaders::upsample_module());
    validate("refine classify", &shaders::refine_classify_module());
    validate("refine draw", &shaders::refine_draw_module());
    for (name, field) in level_fields() {
        validate(
            &format!("refine corners over {name}"),
            &shaders::refine_corners_module(&field),
        );
        validate(
            &format!("refine signs over {name}"),
            &shaders::refine_signs_module(&field),
        );
        validate(
            &format!("refine exact over {name}"),
            &shaders::refine_exact_module(&field),
        );
        validate(
            &format!("sdf pass over {name}"),
            &shaders::sdf_module(&field),
        );
        validate(
            &format!("direct over {name}"),
            &shaders::direct_module(&field),
        );
    }
}

#[test]
fn entry_points_are_the_ones_the_renderer_uses() {
    let module = validate("upsample", &shaders::upsample_module());
    let names: Vec<&str> = module
        .entry_points
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    for entry in [
        "vs_fullscreen",
        "fs_bilinear",
        "fs_bspline",
        "fs_catmull_rom",
        "fs_planes",
    ] {
        assert!(names.contains(&entry), "upsample lacks {entry}: {names:?}");
    }
    let module = validate("reconstruct", &shaders::reconstruct_module());
    let names: Vec<&str> = module
        .entry_points
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    assert!(names.contains(&"fs_divergence") && names.contains(&"fs_pairs"));
}

/// Size and member offsets of the WGSL struct `name`, as naga lays it out.
fn layout_of(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32)>) {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layout");
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name}"));
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("{name} is not a struct");
    };
    assert_eq!(layouter[handle].size, *span);
    let offsets = members
        .iter()
        .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
        .collect();
    (*span, offsets)
}

#[test]
fn uniform_structs_match_their_rust_twins() {
    let (_, field) = &level_fields()[0];
    let module = validate("sdf pass", &shaders::sdf_module(field));
    let (size, offsets) = layout_of(&module, "Frame");
    assert_eq!(size as usize, std::mem::size_of::<FrameUniform>());
    let expect = [
        ("center", std::mem::offset_of!(FrameUniform, center)),
        ("upp", std::mem::offset_of!(FrameUniform, upp)),
        ("slope", std::mem::offset_of!(FrameUniform, slope)),
        ("image", std::mem::offset_of!(FrameUniform, image)),
        (
            "lattice_dims",
            std::mem::offset_of!(FrameUniform, lattice_dims),
        ),
        (
            "lattice_origin",
            std::mem::offset_of!(FrameUniform, lattice_origin),
        ),
        ("h", std::mem::offset_of!(FrameUniform, h)),
        ("band", std::mem::offset_of!(FrameUniform, band)),
        (
            "grid_origin",
            std::mem::offset_of!(FrameUniform, grid_origin),
        ),
        ("cell_size", std::mem::offset_of!(FrameUniform, cell_size)),
        (
            "brick_spacing",
            std::mem::offset_of!(FrameUniform, brick_spacing),
        ),
        ("grid_dims", std::mem::offset_of!(FrameUniform, grid_dims)),
        ("brick_res", std::mem::offset_of!(FrameUniform, brick_res)),
        ("tick", std::mem::offset_of!(FrameUniform, tick)),
        ("sky_top", std::mem::offset_of!(FrameUniform, sky_top)),
        ("sky_bottom", std::mem::offset_of!(FrameUniform, sky_bottom)),
        ("light", std::mem::offset_of!(FrameUniform, light)),
        ("outline_px", std::mem::offset_of!(FrameUniform, outline_px)),
        (
            "shade_depth_px",
            std::mem::offset_of!(FrameUniform, shade_depth_px),
        ),
        (
            "palette_len",
            std::mem::offset_of!(FrameUniform, palette_len),
        ),
        (
            "srgb_target",
            std::mem::offset_of!(FrameUniform, srgb_target),
        ),
        (
            "texture_dims",
            std::mem::offset_of!(FrameUniform, texture_dims),
        ),
    ];
    for (name, offset) in expect {
        let found = offsets.iter().find(|(n, _)| n == name).map(|(_, o)| *o);
        assert_eq!(found, Some(offset as u32), "Frame.{name}");
    }
    let (size, _) = layout_of(&module, "GpuEvent");
    assert_eq!(size as usize, std::mem::size_of::<GpuEvent>());
    let (size, _) = layout_of(&module, "GpuCell");
    assert_eq!(size as usize, std::mem::size_of::<GpuCell>());
}

/// The entry points of a module.
fn entry_names(module: &naga::Module) -> Vec<String> {
    module.entry_points.iter().map(|e| e.name.clone()).collect()
}

#[test]
fn refine_modules_have_their_entry_points_and_struct_layouts() {
    let classify = validate("refine classify", &shaders::refine_classify_module());
    let names = entry_names(&classify);
    for entry in [
        "cs_classify",
        "cs_open",
        "cs_corner_args",
        "cs_blocks",
        "cs_args",
    ] {
        assert!(names.contains(&entry.into()), "classify lacks {entry}");
    }
    let draw = validate("refine draw", &shaders::refine_draw_module());
    assert!(entry_names(&draw).contains(&"fs_refine".into()));
    let (_, field) = &level_fields()[0];
    let corners = validate("refine corners", &shaders::refine_corners_module(field));
    assert!(entry_names(&corners).contains(&"cs_corners".into()));
    let signs = validate("refine signs", &shaders::refine_signs_module(field));
    assert!(entry_names(&signs).contains(&"cs_signs".into()));
    let exact = validate("refine exact", &shaders::refine_exact_module(field));
    assert!(entry_names(&exact).contains(&"cs_exact".into()));
    for (name, size) in [
        ("CellProof", std::mem::size_of::<GpuCellProof>()),
        ("BlockState", std::mem::size_of::<GpuBlockState>()),
        ("Work", std::mem::size_of::<GpuWork>()),
    ] {
        let (found, _) = layout_of(&classify, name);
        assert_eq!(found as usize, size, "{name}");
    }
    let (_, offsets) = layout_of(&classify, "Work");
    let offset = |field: &str| offsets.iter().find(|(n, _)| n == field).map(|(_, o)| *o);
    for (field, rust) in [
        ("counters", std::mem::offset_of!(GpuWork, counters)),
        (
            "corner_dispatch",
            std::mem::offset_of!(GpuWork, corner_dispatch),
        ),
        ("open_blocks", std::mem::offset_of!(GpuWork, open_blocks)),
    ] {
        assert_eq!(offset(field), Some(rust as u32), "Work.{field}");
    }
    // refine_exact.wgsl reads the same buffer through its own copy of the struct.
    let exact_work = layout_of(&exact, "WorkCounts").0;
    assert_eq!(exact_work as usize, std::mem::size_of::<GpuWork>());
}
