//! The perceptual error map: NVIDIA FLIP (LDR) through the `nv-flip` bindings.
//!
//! FLIP converts both sRGB images to an opponent colour space, blurs them with
//! contrast-sensitivity filters sized by the pixels per degree, takes the HyAB colour
//! difference, and raises it where luminance edges or points differ between the images. The
//! result is one error per pixel in `[0, 1]`; its mean is the FLIP score. FLIP compares
//! colours only, so alpha is dropped here (the pixel-wise metrics still see it).

use image::RgbaImage;

/// FLIP's per-pixel error of `test` against `reference` (same size, checked by the caller),
/// row-major; `None` on WebAssembly, where FLIP does not build.
#[cfg(not(target_family = "wasm"))]
pub(crate) fn flip_map(
    reference: &RgbaImage,
    test: &RgbaImage,
    pixels_per_degree: f32,
) -> Option<Vec<f32>> {
    use nv_flip::{FlipImageRgb8, flip};
    let (w, h) = reference.dimensions();
    let reference = FlipImageRgb8::with_data(w, h, &rgb_bytes(reference));
    let test = FlipImageRgb8::with_data(w, h, &rgb_bytes(test));
    Some(flip(reference, test, pixels_per_degree).to_vec())
}

#[cfg(target_family = "wasm")]
pub(crate) fn flip_map(_: &RgbaImage, _: &RgbaImage, _: f32) -> Option<Vec<f32>> {
    None
}

#[cfg(not(target_family = "wasm"))]
fn rgb_bytes(image: &RgbaImage) -> Vec<u8> {
    image
        .as_raw()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect()
}
