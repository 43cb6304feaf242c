//! The twin's entry points: whole frames (passes 1 to 3) and pass 3 alone over given
//! reduced-scale textures, as a shaded image or as the per-pixel field before shading.

use glam::Vec2;
use image::{Rgba, RgbaImage};

use super::blocks::{Block, Kernel, Layout, Run, Scratch, pixel_weights, split_rows};
use super::paint::{PaintScratch, Painter};
use super::reconstruct::reconstruct;
use super::refine::{RefineStats, field_refined, render_refined};
use super::sdf::sdf_pass;
use super::shade::{Shader, check_shade};
use super::threads::run_units;
use super::upsample::{Textures, normal, pixel};
use super::{FieldImage, LowRes, TwinError};
use crate::camera::Camera;
use crate::lattice::Lattice;
use crate::options::{Reconstruction, RenderOptions, Scale, ShadeOptions};
use craterfield_field::{Sdf, Terrain};

/// Renders `terrain` through `camera` with the reduced-scale pipeline on the CPU, colouring
/// material `i` with `palette[i]` (magenta where the palette has no entry), on `threads`
/// threads (0: all cores).
pub fn render_twin<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    palette: &[[u8; 3]],
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Result<RgbaImage, TwinError> {
    if options.reconstruction == Reconstruction::Refine {
        return render_refine(terrain, palette, camera, options, threads).map(|(image, _)| image);
    }
    check_shade(&options.shade)?;
    let lowres = low_res(terrain, camera, options, threads)?;
    render_lowres(&lowres, palette, camera, options, threads)
}

/// [`render_twin`] in mode `refine` (whatever `options.reconstruction` says), with what the
/// refinement did: blocks proven and refined, exact evaluations.
pub fn render_refine<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    palette: &[[u8; 3]],
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Result<(RgbaImage, RefineStats), TwinError> {
    refine_frame(terrain, palette, camera, options, threads, false)
}

fn refine_frame<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    palette: &[[u8; 3]],
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
    tint: bool,
) -> Result<(RgbaImage, RefineStats), TwinError> {
    let options = &refine_options(options);
    check_shade(&options.shade)?;
    let lowres = low_res(terrain, camera, options, threads)?;
    let tex = Textures::new(&lowres, options)?;
    let layout = Layout::new(camera, &tex);
    render_refined(
        terrain,
        &lowres,
        &tex,
        &layout,
        palette,
        camera,
        &options.shade,
        threads,
        false,
        tint,
    )
}

/// [`render_refine`] with every refined (exactly evaluated) pixel tinted red: where the
/// proofs failed.
pub fn render_refine_overlay<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    palette: &[[u8; 3]],
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Result<(RgbaImage, RefineStats), TwinError> {
    refine_frame(terrain, palette, camera, options, threads, true)
}

/// Full-resolution direct evaluation on the CPU: every pixel sampled with the terrain's
/// batch evaluator and shaded as [`crate::render_exact`] shades it (the same
/// image, faster). The reference `refine` is measured against.
pub fn render_direct<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    palette: &[[u8; 3]],
    camera: &Camera,
    shade: &ShadeOptions,
    threads: usize,
) -> Result<RgbaImage, TwinError> {
    check_shade(shade)?;
    let (lowres, options) = direct_inputs(camera, shade)?;
    let tex = Textures::new(&lowres, &options)?;
    let layout = Layout::new(camera, &tex);
    let (image, _) = render_refined(
        terrain, &lowres, &tex, &layout, palette, camera, shade, threads, true, false,
    )?;
    Ok(image)
}

/// The exact field at every pixel centre (distance in pixels, unit normal, material), from
/// the terrain's batch evaluator: the ground truth [`field_image`] is measured against.
pub fn exact_field<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    camera: &Camera,
    threads: usize,
) -> Result<FieldImage, TwinError> {
    let shade = ShadeOptions::default();
    let (lowres, options) = direct_inputs(camera, &shade)?;
    let tex = Textures::new(&lowres, &options)?;
    let layout = Layout::new(camera, &tex);
    field_refined(
        terrain, &lowres, &tex, &layout, camera, &shade, threads, true,
    )
}

/// Empty textures on the coarsest lattice of `camera`: the direct renderers use only their
/// pixel layout.
fn direct_inputs(
    camera: &Camera,
    shade: &ShadeOptions,
) -> Result<(LowRes, RenderOptions), TwinError> {
    let options = RenderOptions {
        scale: Scale::ThirtySecond,
        reconstruction: Reconstruction::Refine,
        shade: shade.clone(),
        ..RenderOptions::default()
    };
    let lattice = Lattice::new(camera, options.scale)?;
    let texels = vec![super::Texel::default(); lattice.len()];
    let lowres = LowRes {
        pairs: Some(vec![[0.0; 4]; texels.len()]),
        lattice,
        texels,
        slope: 1.0,
    };
    Ok((lowres, options))
}

/// `options` with the reconstruction set to `refine`.
fn refine_options(options: &RenderOptions) -> RenderOptions {
    RenderOptions {
        reconstruction: Reconstruction::Refine,
        ..options.clone()
    }
}

/// Passes 1 to 3 without shading: each pixel's reconstructed distance, normal and material.
pub fn field_image<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Result<FieldImage, TwinError> {
    if options.reconstruction == Reconstruction::Refine {
        check_shade(&options.shade)?;
        let lowres = low_res(terrain, camera, options, threads)?;
        let tex = Textures::new(&lowres, options)?;
        let layout = Layout::new(camera, &tex);
        return field_refined(
            terrain,
            &lowres,
            &tex,
            &layout,
            camera,
            &options.shade,
            threads,
            false,
        );
    }
    let lowres = low_res(terrain, camera, options, threads)?;
    field_image_lowres(&lowres, camera, options, threads)
}

/// Passes 1 and 2 for `camera` at `options.scale`.
fn low_res<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Result<LowRes, TwinError> {
    let lattice = Lattice::new(camera, options.scale)?;
    let mut lowres = sdf_pass(terrain, &lattice, threads)?;
    reconstruct(&mut lowres, options.reconstruction)?;
    Ok(lowres)
}

/// Pass 3 (upsample and shade) of `lowres`, the output of passes 1 and 2 for `camera` at
/// `options.scale` and in mode `options.reconstruction`.
pub fn render_lowres(
    lowres: &LowRes,
    palette: &[[u8; 3]],
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Result<RgbaImage, TwinError> {
    let tex = pass3_inputs(lowres, camera, options)?;
    let layout = Layout::new(camera, &tex);
    let shader = Shader::new(&options.shade, camera.height);
    let painter = Painter {
        tex: &tex,
        layout: &layout,
        shader: &shader,
        palette,
        upp: camera.units_per_pixel,
        width: camera.width as usize,
    };
    let mut image = RgbaImage::new(camera.width, camera.height);
    let units = split_rows(&layout.rows.runs, &mut image, camera.width as usize * 4);
    run_units(
        units,
        threads,
        PaintScratch::default,
        |scratch, (rows, bytes)| {
            painter.paint(scratch, rows, bytes);
            Ok::<(), TwinError>(())
        },
    )?;
    Ok(image)
}

/// Pass 3 computed pixel by pixel straight from the pipeline's formulas, on one thread,
/// with no blocks and no skipped regions: slow, and the image [`render_lowres`] must equal.
pub fn render_lowres_per_pixel(
    lowres: &LowRes,
    palette: &[[u8; 3]],
    camera: &Camera,
    options: &RenderOptions,
) -> Result<RgbaImage, TwinError> {
    let tex = pass3_inputs(lowres, camera, options)?;
    let shader = Shader::new(&options.shade, camera.height);
    let upp = camera.units_per_pixel;
    let mut image = RgbaImage::new(camera.width, camera.height);
    for y in 0..camera.height {
        let sky = shader.sky(y);
        for x in 0..camera.width {
            let p = camera.pixel_to_world(x, y);
            let f = pixel(&tex, p, tex.lattice.to_lattice(p));
            let base = palette.get(usize::from(f.material)).copied();
            let [r, g, b] = shader.shade(f.d / upp, f.normal, base, sky);
            image.put_pixel(x, y, Rgba([r, g, b, 255]));
        }
    }
    Ok(image)
}

/// Pass 3 without shading over `lowres` (see [`render_lowres`]).
pub fn field_image_lowres(
    lowres: &LowRes,
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Result<FieldImage, TwinError> {
    let tex = pass3_inputs(lowres, camera, options)?;
    let layout = Layout::new(camera, &tex);
    let (width, pixels) = (
        camera.width as usize,
        camera.width as usize * camera.height as usize,
    );
    let mut field = FieldImage {
        width: camera.width,
        height: camera.height,
        distance_px: vec![0.0; pixels],
        normal: vec![Vec2::ZERO; pixels],
        material: vec![0; pixels],
    };
    let runs = &layout.rows.runs;
    let units: Vec<_> = split_rows(runs, &mut field.distance_px, width)
        .into_iter()
        .zip(split_rows(runs, &mut field.normal, width))
        .zip(split_rows(runs, &mut field.material, width))
        .map(|(((rows, d), (_, n)), (_, m))| (rows, FieldRows { d, n, m }))
        .collect();
    let upp = camera.units_per_pixel;
    run_units(units, threads, Scratch::default, |scratch, (rows, out)| {
        field_rows(&tex, &layout, upp, scratch, rows, out);
        Ok::<(), TwinError>(())
    })?;
    Ok(field)
}

/// One band of a [`FieldImage`].
struct FieldRows<'a> {
    d: &'a mut [f32],
    n: &'a mut [Vec2],
    m: &'a mut [u16],
}

/// Fills the band of image rows `rows.pixels` of a field image.
fn field_rows(
    tex: &Textures,
    layout: &Layout,
    upp: f32,
    scratch: &mut Scratch,
    rows: &Run,
    out: FieldRows,
) {
    let width = layout.columns.world.len();
    for columns in &layout.columns.runs {
        let block = Block::at(columns, rows);
        let kernel = Kernel::new(tex, block);
        kernel.prepare(tex, layout, scratch);
        for (yi, y) in rows.pixels.clone().enumerate() {
            kernel.row(layout, y, scratch);
            for (&d, x) in scratch.dist.iter().zip(columns.pixels.clone()) {
                let i = yi * width + x;
                out.d[i] = d / upp;
                out.n[i] = normal(&kernel.quad, pixel_weights(layout, x, y));
                out.m[i] = kernel.material(layout, x, y);
            }
        }
    }
}

/// Checks that `lowres` is the camera's lattice and holds what `options` need.
fn pass3_inputs<'a>(
    lowres: &'a LowRes,
    camera: &Camera,
    options: &RenderOptions,
) -> Result<Textures<'a>, TwinError> {
    check_shade(&options.shade)?;
    if options.reconstruction == Reconstruction::Refine {
        return Err(TwinError::NeedsField);
    }
    let expected = Lattice::new(camera, options.scale)?;
    if lowres.lattice != expected {
        return Err(TwinError::LatticeMismatch {
            found: lowres.lattice,
            expected,
        });
    }
    Textures::new(lowres, options)
}
