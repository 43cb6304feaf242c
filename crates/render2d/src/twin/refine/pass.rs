//! Pass 3 of mode `refine` over a whole frame: the image's quad rows split into units of
//! at least [`UNIT_ROWS`] pixel rows, spread over threads, each drawn by the [`Refiner`]
//! into an RGBA image or a field image.

use glam::Vec2;
use image::RgbaImage;

use super::refiner::{RefineScratch, Refiner};
use super::sink::{FieldSink, ImageSink, fill_sky};
use super::stats::RefineStats;
use crate::camera::Camera;
use crate::options::ShadeOptions;
use crate::twin::blocks::{Layout, split_row_groups};
use crate::twin::shade::Shader;
use crate::twin::threads::run_units;
use crate::twin::upsample::Textures;
use crate::twin::{FieldImage, LowRes, TwinError};
use craterfield_field::{Sdf, Terrain};

/// Pixel rows of one unit of work at least (see [`Refiner::band`]).
const UNIT_ROWS: usize = 32;

/// Pass 3 of mode `refine` into an RGBA image (see the `refine` module doc). `lowres`
/// holds the planes pair values.
#[allow(clippy::too_many_arguments)]
pub(in crate::twin) fn render_refined<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    lowres: &LowRes,
    tex: &Textures,
    layout: &Layout,
    palette: &[[u8; 3]],
    camera: &Camera,
    shade: &ShadeOptions,
    threads: usize,
    exact_only: bool,
    tint: bool,
) -> Result<(RgbaImage, RefineStats), TwinError> {
    let refiner = Refiner::new(terrain, lowres, tex, layout, camera, shade, exact_only);
    let shader = Shader::new(shade, camera.height);
    let width = camera.width as usize;
    let mut image = RgbaImage::new(camera.width, camera.height);
    let units = split_row_groups(&layout.rows.runs, &mut image, width * 4, UNIT_ROWS);
    run_units(
        units,
        threads,
        RefineScratch::default,
        |scratch, (rows, bytes)| {
            let y0 = rows.first().map_or(0, |r| r.pixels.start);
            fill_sky(&shader, bytes, width, y0);
            let mut sink = ImageSink {
                bytes,
                width,
                y0,
                shader: &shader,
                palette,
                upp: camera.units_per_pixel,
                tint,
                deep_at: refiner.prover.deep_at,
                deep_color: None,
            };
            refiner.band(scratch, rows, &mut sink)
        },
    )?;
    let pixels = u64::from(camera.width) * u64::from(camera.height);
    let stats = refiner.stats(lowres.texels.len() as u64, pixels);
    Ok((image, stats))
}

/// Pass 3 of mode `refine` into a field image (see [`render_refined`]).
#[allow(clippy::too_many_arguments)]
pub(in crate::twin) fn field_refined<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    lowres: &LowRes,
    tex: &Textures,
    layout: &Layout,
    camera: &Camera,
    shade: &ShadeOptions,
    threads: usize,
    exact_only: bool,
) -> Result<FieldImage, TwinError> {
    let refiner = Refiner::new(terrain, lowres, tex, layout, camera, shade, exact_only);
    let width = camera.width as usize;
    let pixels = width * camera.height as usize;
    let mut field = FieldImage {
        width: camera.width,
        height: camera.height,
        distance_px: vec![0.0; pixels],
        normal: vec![Vec2::ZERO; pixels],
        material: vec![0; pixels],
    };
    let runs = &layout.rows.runs;
    let units: Vec<_> = split_row_groups(runs, &mut field.distance_px, width, UNIT_ROWS)
        .into_iter()
        .zip(split_row_groups(runs, &mut field.normal, width, UNIT_ROWS))
        .zip(split_row_groups(
            runs,
            &mut field.material,
            width,
            UNIT_ROWS,
        ))
        .map(|(((rows, d), (_, n)), (_, m))| (rows, d, n, m))
        .collect();
    run_units(
        units,
        threads,
        RefineScratch::default,
        |scratch, (rows, d, n, m)| {
            let mut sink = FieldSink {
                d,
                n,
                m,
                width,
                upp: camera.units_per_pixel,
            };
            refiner.band(scratch, rows, &mut sink)
        },
    )?;
    Ok(field)
}
