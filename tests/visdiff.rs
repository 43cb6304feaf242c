//! The visual diff: exact pixel statistics on constructed differences, the perceptual score
//! ranking a visible blur above invisible noise of the same mean error, black heat-maps
//! where images agree, PNG errors naming the file, and the golden-image workflow (missing
//! reference, update, mismatch evidence, clean-up on pass).
#![cfg(feature = "raster")]

use std::path::PathBuf;

use craterfield::visdiff::{
    DiffError, DiffOptions, GoldenError, GoldenMode, HeatSource, Metric, check_golden_with,
    compare, heatmap, load_png, save_png,
};
use image::{Rgba, RgbaImage};

mod common;
use common::splitmix64;

/// A 128x128 picture with a sky gradient, a dark disc and a bright bar: sharp edges in
/// several directions and no saturated channels (so shifts do not clip).
fn scene() -> RgbaImage {
    RgbaImage::from_fn(128, 128, |x, y| {
        let (fx, fy) = (x as f32 - 60.0, y as f32 - 70.0);
        if fx * fx + fy * fy < 30.0 * 30.0 {
            Rgba([60, 40, 30, 255])
        } else if (20..36).contains(&y) && (10..118).contains(&x) {
            Rgba([220, 200, 90, 255])
        } else {
            Rgba([40 + (y / 2) as u8, 70 + (y / 3) as u8, 160, 255])
        }
    })
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("visdiff-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn identical_images_pass_with_zero_error() {
    let a = scene();
    let report = compare(&a, &a.clone(), &DiffOptions::default()).unwrap();
    assert!(report.passed(), "{report}");
    assert_eq!(report.differing_pixels, 0);
    assert_eq!(
        (report.mean, report.max, report.percentile_value),
        (0.0, 0, 0)
    );
    assert_eq!(report.flip, 0.0);
    assert_eq!((report.width, report.height), (128, 128));
}

#[test]
fn a_one_pixel_change_is_counted_exactly() {
    let a = scene();
    let mut b = a.clone();
    let p = b.get_pixel_mut(77, 5);
    p.0[1] = p.0[1].wrapping_add(200);
    let changed = a.get_pixel(77, 5).0[1].abs_diff(b.get_pixel(77, 5).0[1]);
    let report = compare(&a, &b, &DiffOptions::default()).unwrap();
    assert_eq!(report.differing_pixels, 1);
    assert_eq!(report.differing_fraction, 1.0 / (128.0 * 128.0));
    assert_eq!(report.max, changed);
    assert_eq!(report.mean, f64::from(changed) / (128.0 * 128.0));
    assert_eq!(
        report.percentile_value, 0,
        "one pixel is above the 99th percentile"
    );
    assert!(report.flip > 0.0 && report.flip_max > 0.1, "{report}");
    assert_eq!(report.pixel_errors()[5 * 128 + 77], changed);
    // One pixel in 16,384 is within the default 0.1% budget: only a limit on the max
    // catches it.
    assert!(report.passed(), "{report}");
    let strict = DiffOptions {
        max_error: 10.0,
        ..DiffOptions::default()
    };
    let report = compare(&a, &b, &strict).unwrap();
    assert_eq!(report.failures.len(), 1);
    assert_eq!(report.failures[0].metric, Metric::Max);
    assert!(report.to_string().contains("FAIL: max"), "{report}");
}

#[test]
fn a_global_brightness_shift_is_caught_by_the_mean_but_not_a_tolerance_of_4() {
    let a = scene();
    let mut b = a.clone();
    for p in b.pixels_mut() {
        for c in &mut p.0[..3] {
            *c += 3;
        }
    }
    let options = DiffOptions {
        pixel_tolerance: 4,
        max_mean: 1.0,
        ..DiffOptions::default()
    };
    let report = compare(&a, &b, &options).unwrap();
    assert_eq!(report.differing_pixels, 0, "{report}");
    assert_eq!(
        (report.mean, report.max, report.percentile_value),
        (3.0, 3, 3)
    );
    let failed: Vec<Metric> = report.failures.iter().map(|f| f.metric).collect();
    assert!(failed.contains(&Metric::Mean), "{report}");
    assert!(!failed.contains(&Metric::DifferingFraction), "{report}");
    let tight = DiffOptions {
        pixel_tolerance: 2,
        ..options
    };
    let report = compare(&a, &b, &tight).unwrap();
    assert_eq!(report.differing_pixels, 128 * 128);
    assert_eq!(report.failures[0].metric, Metric::DifferingFraction);
}

/// `image` with a 5x5 box blur.
fn blurred(image: &RgbaImage) -> RgbaImage {
    let (w, h) = image.dimensions();
    RgbaImage::from_fn(w, h, |x, y| {
        let mut sum = [0u32; 3];
        let mut n = 0;
        for dy in -2i32..=2 {
            for dx in -2i32..=2 {
                let (sx, sy) = (x as i32 + dx, y as i32 + dy);
                if sx >= 0 && sy >= 0 && sx < w as i32 && sy < h as i32 {
                    let p = image.get_pixel(sx as u32, sy as u32);
                    for (total, &v) in sum.iter_mut().zip(&p.0[..3]) {
                        *total += u32::from(v);
                    }
                    n += 1;
                }
            }
        }
        Rgba([
            (sum[0] / n) as u8,
            (sum[1] / n) as u8,
            (sum[2] / n) as u8,
            255,
        ])
    })
}

/// `image` with fine-grained noise whose per-pixel error is `target_mean` on average: a
/// random amplitude in `0..=2k` on every channel, with signs alternating like a
/// checkerboard (the finest pattern a screen shows, which the eye averages away).
fn noisy(image: &RgbaImage, target_mean: f64) -> RgbaImage {
    let mut out = image.clone();
    let k = target_mean.round() as u64;
    for (x, y, p) in out.enumerate_pixels_mut() {
        let amplitude = (splitmix64(u64::from(y * 1000 + x)) % (2 * k + 1)) as i32;
        let sign = if (x + y) % 2 == 0 { 1 } else { -1 };
        for c in &mut p.0[..3] {
            *c = (i32::from(*c) + sign * amplitude).clamp(0, 255) as u8;
        }
    }
    out
}

#[test]
fn a_blurred_edge_scores_worse_than_fine_noise_of_the_same_mean_error() {
    let sharp = scene();
    let blur = blurred(&sharp);
    let options = DiffOptions::default();
    let blur_report = compare(&sharp, &blur, &options).unwrap();
    let noise = noisy(&sharp, blur_report.mean);
    let noise_report = compare(&sharp, &noise, &options).unwrap();
    let ratio = noise_report.mean / blur_report.mean;
    assert!(
        (0.8..1.25).contains(&ratio),
        "mean errors should match: blur {blur_report}\nnoise {noise_report}"
    );
    assert!(
        blur_report.flip > 2.0 * noise_report.flip,
        "blur should look worse: blur {blur_report}\nnoise {noise_report}"
    );
}

#[test]
fn heatmap_is_black_exactly_where_the_images_agree() {
    let a = scene();
    let mut b = a.clone();
    for y in 40..50 {
        for x in 90..100 {
            b.put_pixel(x, y, Rgba([255, 255, 255, 255]));
        }
    }
    b.get_pixel_mut(3, 3).0[2] ^= 1;
    let report = compare(&a, &b, &DiffOptions::default()).unwrap();
    let heat = heatmap(&report, HeatSource::Pixel);
    assert_eq!(heat.dimensions(), a.dimensions());
    for (x, y, p) in heat.enumerate_pixels() {
        let equal = a.get_pixel(x, y) == b.get_pixel(x, y);
        assert_eq!(p.0[..3] == [0, 0, 0], equal, "({x}, {y}): {p:?}");
    }
    // The largest difference is at the top of the ramp (pale yellow), the one-level change
    // near the bottom.
    let hot = heat.get_pixel(95, 45).0;
    assert!(hot[0] > 240 && hot[1] > 240, "{hot:?}");
    let faint = heat.get_pixel(3, 3).0;
    assert!(u32::from(faint[0]) + u32::from(faint[1]) + u32::from(faint[2]) < 60);
    let perceptual = heatmap(&report, HeatSource::Perceptual);
    assert_eq!(perceptual.get_pixel(10, 120).0, [0, 0, 0, 255]);
    assert_ne!(perceptual.get_pixel(95, 45).0, [0, 0, 0, 255]);
}

#[test]
fn png_round_trip_and_errors_name_the_file() {
    let dir = temp_dir("png");
    let path = dir.join("scene.png");
    save_png(&scene(), &path).unwrap();
    assert_eq!(load_png(&path).unwrap(), scene());
    let missing = dir.join("nope.png");
    let err = load_png(&missing).unwrap_err();
    assert!(matches!(err, DiffError::Read { .. }));
    assert!(err.to_string().contains("nope.png"), "{err}");
    let garbage = dir.join("garbage.png");
    std::fs::write(&garbage, b"\x89PNG\r\n\x1a\nnot really").unwrap();
    let err = load_png(&garbage).unwrap_err();
    assert!(err.to_string().contains("garbage.png"), "{err}");
}

#[test]
fn golden_missing_update_mismatch_and_recovery() {
    let dir = temp_dir("golden");
    let options = DiffOptions::default();
    let image = scene();

    let err = check_golden_with("scene", &image, &dir, &options, GoldenMode::Check).unwrap_err();
    assert!(matches!(err, GoldenError::Missing { .. }));
    let message = err.to_string();
    assert!(
        message.contains("CRATERFIELD_UPDATE_GOLDEN=1") && message.contains("scene.png"),
        "{message}"
    );

    let report = check_golden_with("scene", &image, &dir, &options, GoldenMode::Update).unwrap();
    assert!(report.passed());
    assert_eq!(load_png(&dir.join("scene.png")).unwrap(), image);
    check_golden_with("scene", &image, &dir, &options, GoldenMode::Check).unwrap();

    let mut changed = image.clone();
    for y in 0..20 {
        for x in 0..20 {
            changed.put_pixel(x, y, Rgba([255, 0, 0, 255]));
        }
    }
    let err = check_golden_with("scene", &changed, &dir, &options, GoldenMode::Check).unwrap_err();
    let (actual, heat) = match &err {
        GoldenError::Mismatch { actual, heat, .. } => (actual.clone(), heat.clone()),
        other => panic!("expected a mismatch, got {other}"),
    };
    let message = err.to_string();
    assert!(
        message.contains("differing_fraction") && message.contains("flip"),
        "{message}"
    );
    assert!(message.contains("scene.actual.png") && message.contains("scene.heat.png"));
    assert_eq!(actual, dir.join("scene.actual.png"));
    assert_eq!(load_png(&actual).unwrap(), changed);
    let heat_image = load_png(&heat).unwrap();
    assert_ne!(heat_image.get_pixel(5, 5).0[..3], [0, 0, 0]);
    assert_eq!(heat_image.get_pixel(100, 100).0[..3], [0, 0, 0]);

    // A different size is reported as such, with the output written for inspection.
    let small = RgbaImage::new(64, 64);
    let err = check_golden_with("scene", &small, &dir, &options, GoldenMode::Check).unwrap_err();
    assert!(
        matches!(err, GoldenError::SizeMismatch { width: 64, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("128x128"), "{err}");

    // Passing again clears the evidence of the failure.
    check_golden_with("scene", &image, &dir, &options, GoldenMode::Check).unwrap();
    assert!(!actual.exists() && !heat.exists());

    let err = check_golden_with("../escape", &image, &dir, &options, GoldenMode::Update);
    assert!(matches!(err, Err(GoldenError::BadName { .. })));
}
