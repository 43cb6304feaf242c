//! The plain-data uniform shared with the raymarcher's WGSL, byte for byte: `MarchFrame`
//! here and `struct MarchFrame` in `shaders/march3d.wgsl` have the same fields in the same
//! order, and the size assertion below keeps them in step.

use bytemuck::{Pod, Zeroable};

use crate::plan3d::Camera3d;

/// The camera and image size of a frame; `MarchFrame` in `shaders/march3d.wgsl`. Each
/// `vec3` is followed by a 4-byte scalar, which fills the 16-byte alignment WGSL gives it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct MarchFrame {
    /// Eye position.
    pub position: [f32; 3],
    /// `tan(fov_y / 2)`.
    pub tan_half_fov: f32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// Image width, pixels.
    pub width: u32,
    /// Unit screen-right direction.
    pub right: [f32; 3],
    /// Image height, pixels.
    pub height: u32,
    /// Unit screen-up direction.
    pub up: [f32; 3],
    /// Padding to the struct's 16-byte alignment.
    pub pad: u32,
}

const _: () = assert!(std::mem::size_of::<MarchFrame>() == 64);

impl MarchFrame {
    /// The uniform of `camera` for a `width x height` image.
    pub fn new(camera: &Camera3d, width: u32, height: u32) -> MarchFrame {
        MarchFrame {
            position: camera.position.to_array(),
            tan_half_fov: camera.tan_half_fov,
            forward: camera.forward.to_array(),
            width,
            right: camera.right.to_array(),
            height,
            up: camera.up.to_array(),
            pad: 0,
        }
    }
}
