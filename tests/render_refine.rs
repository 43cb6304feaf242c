//! The `refine` reconstruction against the exact render, and the proofs it rests on
//! (per-cell slope bounds, event signs, material margins) against sampled points. A proof
//! that fails is a bug, not noise: every check here is exact.
#![cfg(feature = "raster")]

mod common;

use common::Rng;
use common::shade_steps::shade_steps;
use craterfield::field2d::Event;
use craterfield::field2d::terrain::RectSign;
use craterfield::field2d::{Graph, Level, Sdf, Terrain};
use craterfield::render2d::twin::{exact_field, render_direct, render_refine};
use craterfield::render2d::{
    Camera, ExactRenderOptions, Reconstruction, RenderOptions, Scale, ShadeOptions, field_image,
    render_exact, render_twin,
};
use glam::Vec2;

fn camera(x: f32, y: f32, upp: f32, width: u32, height: u32) -> Camera {
    Camera {
        center: Vec2::new(x, y),
        units_per_pixel: upp,
        width,
        height,
    }
}

fn refine(scale: Scale) -> RenderOptions {
    RenderOptions {
        scale,
        reconstruction: Reconstruction::Refine,
        ..RenderOptions::default()
    }
}

/// The default level after `count` events aimed at its surface: sharp and smooth carves,
/// and fills of the last material (so that cells hold several materials), at full size.
fn cratered(count: usize, seed: u64) -> (Level, Terrain<Graph>) {
    let level = Level::default_level();
    let mut terrain = level.terrain().unwrap();
    let b = level.bounds();
    let fill = (level.materials().len() - 1) as u16;
    let mut rng = Rng(seed);
    for _ in 0..count {
        let x = b.min.x + rng.unit() * (b.max.x - b.min.x);
        let mut p = Vec2::new(x, b.max.y);
        while p.y > b.min.y {
            let d = terrain.distance(p);
            if d < 0.0 {
                let r = 6.0 + rng.unit() * 40.0;
                let roll = rng.unit();
                let e = if roll < 0.6 {
                    Event::carve(p, r).unwrap()
                } else if roll < 0.8 {
                    Event::carve(p, r)
                        .unwrap()
                        .with_rim(2.0 + 8.0 * rng.unit())
                        .unwrap()
                } else {
                    Event::fill(p + Vec2::new(0.0, 0.4 * r), r * 0.5, fill).unwrap()
                };
                terrain.apply(e).unwrap();
                break;
            }
            p.y -= d.max(1.0);
        }
    }
    (level, terrain)
}

fn palette(level: &Level) -> Vec<[u8; 3]> {
    level.materials().iter().map(|m| m.color).collect()
}

/// Views over the surface, the caves, the islands, zoomed in and out.
fn views() -> Vec<Camera> {
    vec![
        camera(1240.0, 650.0, 1.0, 480, 300),
        camera(2350.0, 400.0, 0.5, 320, 240),
        camera(1920.0, 800.0, 2.0, 480, 256),
        camera(640.0, 420.0, 1.0, 256, 256),
        camera(3300.0, 1150.0, 0.75, 300, 200),
    ]
}

#[test]
fn inside_outside_and_materials_equal_the_exact_field_at_every_pixel() {
    for (count, seed) in [(0, 1), (1500, 7), (4000, 0xfeed)] {
        let (_, terrain) = cratered(count, seed);
        for cam in views() {
            let truth = exact_field(&terrain, &cam, 0).unwrap();
            for scale in [Scale::Quarter, Scale::Sixteenth, Scale::ThirtySecond] {
                let test = field_image(&terrain, &cam, &refine(scale), 0).unwrap();
                for i in 0..truth.distance_px.len() {
                    let (a, b) = (truth.distance_px[i], test.distance_px[i]);
                    let at = (i as u32 % cam.width, i as u32 / cam.width);
                    let what = format!("{count} events, {cam:?}, {scale:?}, pixel {at:?}");
                    assert_eq!(a < 0.0, b < 0.0, "{what}: exact {a}, refine {b}");
                    if a < 0.0 {
                        assert_eq!(truth.material[i], test.material[i], "{what}");
                    }
                }
            }
        }
    }
}

#[test]
fn sky_and_surface_pixels_are_the_exact_render_bit_for_bit() {
    let (level, terrain) = cratered(2500, 3);
    let pal = palette(&level);
    let shade = ShadeOptions::default();
    // Deeper than this, a pixel is proven solid and shaded from the texels.
    let deep = -(shade.outline_px + 0.5);
    for cam in views() {
        let exact = render_exact(&terrain, &pal, &cam, &ExactRenderOptions::default()).unwrap();
        let direct = render_direct(&terrain, &pal, &cam, &shade, 0).unwrap();
        assert_eq!(
            exact, direct,
            "{cam:?}: the batch direct render is the exact render"
        );
        let truth = exact_field(&terrain, &cam, 0).unwrap();
        let (image, stats) =
            render_refine(&terrain, &pal, &cam, &refine(Scale::Sixteenth), 0).unwrap();
        assert_eq!(
            image,
            render_twin(&terrain, &pal, &cam, &refine(Scale::Sixteenth), 0).unwrap()
        );
        let mut solid_differing = 0;
        for (i, (p, q)) in exact.pixels().zip(image.pixels()).enumerate() {
            if truth.distance_px[i] > deep {
                assert_eq!(p, q, "{cam:?} pixel {i}: d = {}", truth.distance_px[i]);
            } else if p != q {
                solid_differing += 1;
            }
        }
        // Inside, only the depth shade comes from the texels: few pixels, never by much.
        let n = u64::from(cam.width) * u64::from(cam.height);
        assert!(
            solid_differing * 10 < n,
            "{cam:?}: {solid_differing} solid pixels differ"
        );
        assert_eq!(stats.pixels, n);
        assert!(stats.refined_pixels < n / 2, "{cam:?}: {stats:?}");
        assert_eq!(
            stats.blocks,
            stats.sky_blocks + stats.solid_blocks + stats.refined_blocks
        );
    }
}

#[test]
fn cell_slope_bounds_hold_between_sampled_points() {
    let (_, terrain) = cratered(3000, 11);
    let grid = terrain.grid();
    let (nx, ny) = grid.dims();
    let mut rng = Rng(5);
    let s = grid.cell_size();
    for cell in 0..(nx * ny) as usize {
        let bounds = terrain.cell_bounds(cell).unwrap();
        let min =
            grid.origin() + Vec2::new((cell as u32 % nx) as f32, (cell as u32 / nx) as f32) * s;
        for _ in 0..12 {
            let a = min + Vec2::new(rng.unit(), rng.unit()) * (s * 0.999);
            let b = min + Vec2::new(rng.unit(), rng.unit()) * (s * 0.999);
            let (da, db) = (terrain.distance(a), terrain.distance(b));
            let allowed = bounds.lipschitz * a.distance(b) * 1.0001 + 1.0e-3;
            assert!(
                (da - db).abs() <= allowed,
                "cell {cell} {bounds:?}: |d({a}) - d({b})| = {} > {allowed}",
                (da - db).abs()
            );
        }
    }
}

#[test]
fn event_signs_and_material_margins_hold_at_sampled_points() {
    let (_, terrain) = cratered(3000, 13);
    let grid = terrain.grid();
    let (nx, ny) = grid.dims();
    let s = grid.cell_size();
    let mut rng = Rng(9);
    let (mut above, mut below, mut margins) = (0, 0, 0);
    for _ in 0..20_000 {
        let cell = rng.below(u64::from(nx * ny)) as usize;
        let min =
            grid.origin() + Vec2::new((cell as u32 % nx) as f32, (cell as u32 / nx) as f32) * s;
        let side = 1.0 + rng.unit() * 12.0;
        let lo = min + Vec2::new(rng.unit(), rng.unit()) * (s - side);
        let hi = lo + Vec2::splat(side);
        let sign = terrain.rect_sign(cell, lo, hi, 0.5, -2.5);
        for _ in 0..6 {
            let p = lo + Vec2::new(rng.unit(), rng.unit()) * side;
            let d = terrain.distance(p);
            match sign {
                RectSign::Above => assert!(d >= 0.5, "cell {cell} [{lo}, {hi}] at {p}: {d}"),
                RectSign::Below => assert!(d <= -2.5, "cell {cell} [{lo}, {hi}] at {p}: {d}"),
                RectSign::Unknown => {}
            }
        }
        above += usize::from(sign == RectSign::Above);
        below += usize::from(sign == RectSign::Below);
        // Margins: every point of the cell within margin / 2L of p has p's material.
        let p = min + Vec2::new(rng.unit(), rng.unit()) * (s * 0.999);
        let m = terrain.material_margin(p);
        let slope = 2.0 * terrain.cell_bounds(cell).unwrap().lipschitz.max(1.0);
        let radius = (m / slope).min(s);
        if radius > 0.0 && m.is_finite() {
            margins += 1;
            let material = terrain.sample(p).material;
            for _ in 0..8 {
                let q = p + Vec2::new(rng.unit() - 0.5, rng.unit() - 0.5) * radius * 1.4;
                let inside = grid.cell_index(q) == Some(cell) && q.distance(p) < radius * 0.999;
                if inside {
                    assert_eq!(
                        terrain.sample(q).material,
                        material,
                        "margin {m} at {p}, {q}"
                    );
                }
            }
        }
    }
    // The proofs are not vacuous here.
    assert!(
        above > 1000 && below > 1000 && margins > 100,
        "{above} {below} {margins}"
    );
}

/// The interior shade of proven solid blocks has no block steps at any zoom: zoomed out,
/// where the band the terrain clamps its distance to is only a few pixels deep and its
/// contour cuts the lit rim with a hard edge, the refined picture follows the exact one
/// (few pixels off by more than 8 levels, and the error does not jump across block edges
/// more often than inside blocks).
#[test]
fn interior_shade_has_no_block_steps_at_any_zoom() {
    let (level, terrain) = cratered(600, 3);
    let pal = palette(&level);
    let shade = ShadeOptions::default();
    let deep = -(shade.outline_px + 0.5);
    let b = level.bounds();
    let mut failures = Vec::new();
    for width in [470, 940, 1920, 3840] {
        let cam = Camera::fit(b.min, b.max, width);
        let exact = render_exact(&terrain, &pal, &cam, &ExactRenderOptions::default()).unwrap();
        let truth = exact_field(&terrain, &cam, 0).unwrap();
        let (image, stats) =
            render_refine(&terrain, &pal, &cam, &refine(Scale::Sixteenth), 0).unwrap();
        let s = shade_steps(&image, &exact, &truth.distance_px, deep);
        eprintln!(
            "width {width} (upp {:.2}): {s:?}, {:.2}% of blocks refined, {} evaluations",
            cam.units_per_pixel,
            100.0 * stats.refined_block_fraction(),
            stats.exact_evaluations
        );
        if s.stepped() {
            failures.push(format!("width {width}: {s:?}"));
        }
    }
    assert!(
        failures.is_empty(),
        "block steps in the interior shade (more than 10 + 0.01% of the interior pixels \
         off by more than 8 levels, or the error jumping across block edges more than \
         twice as often as inside blocks): {failures:#?}"
    );
}
