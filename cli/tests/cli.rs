//! The command-line tool end to end: the demo writes its image and summary, `level check`
//! accepts good levels and names the problem in bad ones, the demo's match replay verifies
//! and damaged replays are refused with a message (never a panic), `replay render` writes
//! the picture asked for, `bench field --json`, `bench sim --json` and
//! `bench fidelity --json` print the documented keys, `diff` exits 0, 1 or 2 as
//! documented, and `render` draws every mode, measures it against the exact render and
//! refuses what it cannot draw.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use craterfield::net::Replay;

fn craterfield() -> Command {
    Command::new(env!("CARGO_BIN_EXE_craterfield"))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("craterfield-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn demo_writes_a_png_and_a_summary() {
    let out = temp_dir("demo");
    let status = craterfield()
        .args(["demo", "--events", "80", "--width", "480", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let stdout = String::from_utf8_lossy(&status.stdout);
    assert!(stdout.contains("events applied"), "{stdout}");

    let png = std::fs::read(out.join("terrain.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let img = image::load_from_memory(&png).unwrap().to_rgb8();
    assert_eq!(img.width(), 480);
    // Both sky and terrain are in the picture: the top-left is sky blue, the bottom row soil.
    let top = img.get_pixel(2, 2);
    let bottom = img.get_pixel(240, img.height() - 2);
    assert!(top[2] > top[0], "top-left should be sky: {top:?}");
    assert!(bottom[0] > bottom[2], "bottom should be soil: {bottom:?}");

    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let applied = summary["events"]["applied"].as_u64().unwrap();
    assert!(applied >= 60, "most of the 80 shells land: {summary}");
    assert!(summary["timings"]["distance_ns"].as_f64().unwrap() > 0.0);
    let solid = summary["field"]["solid_fraction"].as_f64().unwrap();
    assert!(solid > 0.1 && solid < 0.6, "solid fraction {solid}");
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn level_check_accepts_shipped_levels_and_rejects_bad_ones() {
    let levels = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../levels");
    for entry in std::fs::read_dir(&levels).unwrap() {
        let path = entry.unwrap().path();
        let out = craterfield()
            .args(["level", "check"])
            .arg(&path)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{}: {text}", path.display());
        assert!(
            text.contains("work units per evaluation") && text.contains("limit 8192"),
            "the check prints the level's cost: {text}"
        );
    }
    let dir = temp_dir("check");
    // A simple polygon of 10,000 vertices passes every limit but the cost of an evaluation.
    let points: Vec<String> = (0..10_000)
        .map(|k| {
            let t = k as f64 / 10_000.0 * std::f64::consts::TAU;
            format!(
                "({:.3}, {:.3})",
                50.0 + 30.0 * t.cos(),
                50.0 + 30.0 * t.sin()
            )
        })
        .collect();
    let costly = dir.join("costly.ron");
    std::fs::write(
        &costly,
        format!(
            r#"Level(name: "costly", bounds: (min: (0.0, 0.0), max: (100.0, 100.0)),
            materials: [(name: "a", color: (1, 2, 3))], root: Polygon(points: [{}]))"#,
            points.join(", ")
        ),
    )
    .unwrap();
    let out = craterfield()
        .args(["level", "check"])
        .arg(&costly)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("10003 work units")
            && text.contains("limit of 8192 (GraphLimits::max_eval_work)"),
        "{text}"
    );
    let bad = dir.join("bad.ron");
    std::fs::write(
        &bad,
        r#"Level(name: "bad", bounds: (min: (0.0, 0.0), max: (100.0, 100.0)),
            materials: [(name: "a", color: (1, 2, 3))],
            root: Union([Circle(radius: 3.0), Circle(radius: -2.0)]))"#,
    )
    .unwrap();
    let out = craterfield()
        .args(["level", "check"])
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("root.Union[1].Circle.radius") && text.contains("positive"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bench_field_json_has_the_documented_keys() {
    let out = craterfield()
        .args(["bench", "field", "--json", "--points", "2000"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in ["queries_per_s", "raycasts_per_s"] {
        for n in ["0", "1000", "10000"] {
            assert!(v[key][n].as_f64().unwrap() > 0.0, "{key}.{n} in {v}");
        }
    }
    assert!(v["insert_us_median"].as_f64().unwrap() > 0.0);
    // The per-query cost is bounded by the cell cap whatever the event count.
    let cap = v["max_cell_events"]["10000"].as_u64().unwrap();
    assert!(cap <= 48, "{v}");
}

/// Without the polygon peers compiled in, `--peers` says how to get them instead of
/// printing a table without them (the suite builds the CLI without the feature).
#[test]
#[cfg(not(feature = "peers"))]
fn bench_field_peers_without_the_feature_says_how_to_build_it() {
    let out = craterfield()
        .args(["bench", "field", "--peers", "--points", "1000"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--features peers"), "{err}");
}

/// Ticks of the small demo match the replay tests share.
const MATCH_TICKS: u32 = 300;

/// One small demo run (made once, shared by the replay tests): its summary and its match
/// replay's bytes.
struct DemoMatch {
    summary: serde_json::Value,
    replay: Vec<u8>,
}

fn demo_match() -> &'static DemoMatch {
    static RUN: OnceLock<DemoMatch> = OnceLock::new();
    RUN.get_or_init(|| {
        let out = temp_dir("match");
        let run = craterfield()
            .args(["demo", "--events", "40", "--width", "320"])
            .args(["--match-ticks", &MATCH_TICKS.to_string(), "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(run.status.success(), "{}", text(&run.stderr));
        let stdout = text(&run.stdout);
        assert!(
            stdout.contains(&format!("match: 4 players, {MATCH_TICKS} ticks")),
            "{stdout}"
        );
        assert!(out.join("match.png").exists());
        let summary = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap());
        let run = DemoMatch {
            summary: summary.unwrap(),
            replay: std::fs::read(out.join("match.replay")).unwrap(),
        };
        std::fs::remove_dir_all(&out).ok();
        run
    })
}

/// The demo's match replay, written into `dir`.
fn match_file(dir: &Path) -> PathBuf {
    let file = dir.join("match.replay");
    std::fs::write(&file, &demo_match().replay).unwrap();
    file
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn replay(args: &[&str], file: &Path) -> Output {
    craterfield()
        .arg("replay")
        .arg(args[0])
        .arg(file)
        .args(&args[1..])
        .output()
        .unwrap()
}

/// Exit status 1 with `needle` in the message, and no panic.
fn assert_refused(out: &Output, needle: &str) {
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.contains(needle), "expected {needle:?} in: {stderr}");
}

#[test]
fn demo_match_replay_verifies_and_info_describes_it() {
    let dir = temp_dir("verify");
    let file = match_file(&dir);
    let summary = &demo_match().summary;
    assert_eq!(summary["match"]["ticks"], MATCH_TICKS, "{summary}");
    assert_eq!(summary["match"]["players"], 4, "{summary}");
    let bytes = summary["match"]["replay_bytes"].as_u64().unwrap();
    assert_eq!(bytes, std::fs::metadata(&file).unwrap().len());
    // The existing summary keys are still there.
    assert!(summary["events"]["applied"].as_u64().unwrap() > 0);

    let out = replay(&["verify"], &file);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", text(&out.stderr));
    assert!(
        stdout.contains(&format!("ok: {MATCH_TICKS} ticks")) && stdout.contains("hashes match"),
        "{stdout}"
    );
    let hash = summary["match"]["final_hash"].as_str().unwrap();
    assert!(stdout.contains(hash), "{stdout} vs {hash}");

    let out = replay(&["info"], &file);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(stdout.contains("players:    4"), "{stdout}");
    assert!(
        stdout.contains(&format!("ticks:      {MATCH_TICKS} at 60 Hz (5.00 s)")),
        "{stdout}"
    );
    assert!(stdout.contains("matches level \"Default\""), "{stdout}");
    assert!(stdout.contains("bytes/minute"), "{stdout}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A replay without stored hashes re-simulates but proves nothing: verify says so and fails,
/// unless told to accept it.
#[test]
fn a_replay_without_hashes_is_not_reported_as_verified() {
    let dir = temp_dir("unverified");
    let mut recorded = craterfield::net::Replay::decode(&demo_match().replay).unwrap();
    recorded.hashes.clear();
    let file = dir.join("nohash.replay");
    std::fs::write(&file, recorded.encode().unwrap()).unwrap();
    let out = replay(&["verify"], &file);
    assert_refused(&out, "nothing was verified");
    assert!(!text(&out.stdout).contains("ok:"), "{}", text(&out.stdout));
    let out = replay(&["verify", "--allow-unverified"], &file);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("nothing was verified"),
        "{}",
        text(&out.stdout)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn damaged_replays_are_refused_with_the_problem_named() {
    let original = &demo_match().replay;
    let dir = temp_dir("damaged");

    let truncated = dir.join("truncated.replay");
    std::fs::write(&truncated, &original[..original.len() * 2 / 3]).unwrap();
    assert_refused(&replay(&["verify"], &truncated), "truncated");

    let flipped = dir.join("flipped.replay");
    let mut bytes = original.clone();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x10;
    std::fs::write(&flipped, &bytes).unwrap();
    assert_refused(&replay(&["verify"], &flipped), "checksum mismatch");

    let empty = dir.join("empty.replay");
    std::fs::write(&empty, b"").unwrap();
    assert_refused(&replay(&["verify"], &empty), "truncated");
    assert_refused(&replay(&["info"], &flipped), "checksum mismatch");

    // A well-formed file whose stored hash was changed: the checksum is right, so only the
    // re-simulation finds it, at that tick.
    let mut decoded = Replay::decode(original).unwrap();
    let (tick, hash) = decoded.hashes[2];
    decoded.hashes[2].1 = hash ^ 1;
    let forged = dir.join("forged.replay");
    std::fs::write(&forged, decoded.encode().unwrap()).unwrap();
    let out = replay(&["verify"], &forged);
    assert_refused(&out, &format!("first divergent tick {tick}:"));
    assert!(text(&out.stderr).contains(&format!("{:#018x}", hash ^ 1)));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn replay_render_writes_a_png_of_the_requested_width() {
    let dir = temp_dir("render");
    let file = match_file(&dir);
    let png = dir.join("frame.png");
    let out = craterfield()
        .args(["replay", "render"])
        .arg(&file)
        .args(["--tick", "150", "--width", "400", "--out"])
        .arg(&png)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("tick 150 of 300"),
        "{}",
        text(&out.stdout)
    );
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.width(), 400);
    // Every vehicle is still alive at tick 150 and drawn in its player's colour: the
    // red of player 0 is nowhere in the sky or the terrain palette.
    let red = img
        .pixels()
        .filter(|p| p[0] > 200 && p[1] < 90 && p[2] < 90)
        .count();
    assert!(red > 0, "player 0's vehicle should be drawn");

    let out = craterfield()
        .args(["replay", "render"])
        .arg(&file)
        .args(["--tick", "301", "--out"])
        .arg(dir.join("late.png"))
        .output()
        .unwrap();
    assert_refused(&out, "past the end");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bench_sim_json_has_the_documented_keys() {
    let out = craterfield()
        .args(["bench", "sim", "--json", "--bodies", "40,80"])
        .args(["--ticks", "4", "--warmup", "2", "--explosions", "200"])
        .args([
            "--snapshot-bodies",
            "40",
            "--reps",
            "4",
            "--match-seconds",
            "2",
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2, "{v}");
    for (row, n) in rows.iter().zip([40, 80]) {
        assert_eq!(row["bodies"], n, "{v}");
        assert!(row["ms_per_tick"].as_f64().unwrap() > 0.0, "{v}");
    }
    for key in [
        "snapshot_ms",
        "restore_ms",
        "replay_bytes_per_min",
        "bytes_per_event",
    ] {
        assert!(v[key].as_f64().unwrap() > 0.0, "{key} in {v}");
    }
    assert!(v["bytes_per_event"].as_f64().unwrap() <= 16.0, "{v}");
    assert_eq!(v["explosions"], 200, "{v}");
}

/// A 96x64 PNG with a sky gradient and a box whose colour is `fill`.
fn write_diff_image(path: &Path, fill: [u8; 3], width: u32) {
    let img = image::RgbaImage::from_fn(width, 64, |x, y| {
        if (30..60).contains(&x) && (20..40).contains(&y) {
            image::Rgba([fill[0], fill[1], fill[2], 255])
        } else {
            image::Rgba([40, 60 + y as u8, 150, 255])
        }
    });
    img.save(path).unwrap();
}

#[test]
fn diff_exits_0_within_and_1_over_the_thresholds() {
    let dir = temp_dir("diff");
    let (a, b) = (dir.join("a.png"), dir.join("b.png"));
    write_diff_image(&a, [200, 120, 60], 96);
    write_diff_image(&b, [90, 200, 60], 96);

    let same = craterfield()
        .arg("diff")
        .arg(&a)
        .arg(&a)
        .arg("--json")
        .output()
        .unwrap();
    assert_eq!(same.status.code(), Some(0), "{}", text(&same.stderr));
    let json: serde_json::Value = serde_json::from_slice(&same.stdout).unwrap();
    assert_eq!(json["passed"], true);
    assert_eq!(json["differing_pixels"], 0);
    assert_eq!(json["flip"], 0.0);

    let heat = dir.join("heat.png");
    let over = craterfield()
        .arg("diff")
        .arg(&a)
        .arg(&b)
        .arg("--out")
        .arg(&heat)
        .output()
        .unwrap();
    assert_eq!(over.status.code(), Some(1), "{}", text(&over.stderr));
    let stdout = text(&over.stdout);
    // The box is 30x20 = 600 of 6144 pixels.
    assert!(stdout.contains("600 differ by more than 2"), "{stdout}");
    assert!(stdout.contains("FAIL: differing_fraction"), "{stdout}");
    let heat_img = image::open(&heat).unwrap().to_rgba8();
    assert_eq!(heat_img.dimensions(), (96, 64));
    assert_eq!(heat_img.get_pixel(5, 5).0, [0, 0, 0, 255]);
    assert_ne!(heat_img.get_pixel(40, 30).0, [0, 0, 0, 255]);

    let loose = craterfield()
        .arg("diff")
        .arg(&a)
        .arg(&b)
        .args([
            "--tolerance",
            "255",
            "--max-mean",
            "255",
            "--max-percentile",
            "255",
        ])
        .args(["--max-flip", "1", "--json"])
        .output()
        .unwrap();
    assert_eq!(loose.status.code(), Some(0), "{}", text(&loose.stdout));
    let json: serde_json::Value = serde_json::from_slice(&loose.stdout).unwrap();
    assert_eq!(json["differing_pixels"], 0);
    assert!(json["mean"].as_f64().unwrap() > 5.0, "{json}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn diff_exits_2_on_unreadable_or_mismatched_images() {
    let dir = temp_dir("diff-bad");
    let (a, small, garbage) = (
        dir.join("a.png"),
        dir.join("small.png"),
        dir.join("junk.png"),
    );
    write_diff_image(&a, [200, 120, 60], 96);
    write_diff_image(&small, [200, 120, 60], 80);
    std::fs::write(&garbage, b"not a png at all").unwrap();
    let cases: [(&Path, &str); 3] = [
        (&dir.join("missing.png"), "missing.png"),
        (&garbage, "junk.png"),
        (&small, "96x64"),
    ];
    for (other, needle) in cases {
        let out = craterfield()
            .arg("diff")
            .arg(&a)
            .arg(other)
            .output()
            .unwrap();
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{needle}: {stderr}");
        assert!(
            stderr.contains(needle) && !stderr.contains("panicked"),
            "{stderr}"
        );
    }
    let nan = craterfield()
        .arg("diff")
        .arg(&a)
        .arg(&a)
        .args(["--max-mean", "NaN"])
        .output()
        .unwrap();
    assert_eq!(nan.status.code(), Some(2));
    assert!(
        text(&nan.stderr).contains("max_mean"),
        "{}",
        text(&nan.stderr)
    );
    // A viewing distance under which FLIP has no score is refused, not passed.
    let (red, green) = (dir.join("red.png"), dir.join("green.png"));
    write_diff_image(&red, [220, 30, 30], 96);
    write_diff_image(&green, [30, 200, 30], 96);
    for ppd in ["1e-20", "0", "-5", "inf"] {
        let out = craterfield()
            .arg("diff")
            .arg(&red)
            .arg(&green)
            .arg(format!("--ppd={ppd}"))
            .output()
            .unwrap();
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "--ppd {ppd}: {stderr}");
        assert!(stderr.contains("pixels_per_degree"), "{stderr}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bench_fidelity_json_has_the_documented_keys() {
    let out = craterfield()
        .args(["bench", "fidelity", "--json", "--scenes", "islands,corners"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2 * 5 * 4, "2 scenes x 5 methods x 4 scales");
    for row in rows {
        for key in [
            "scene",
            "method",
            "scale",
            "mismatch_pct",
            "material_mismatch_pct",
            "mean_offset_px",
        ] {
            assert!(!row[key].is_null(), "{key} in {row}");
        }
        for key in [
            "solid_recall",
            "gap_recall",
            "max_offset_px",
            "flip",
            "recall_1px",
        ] {
            assert!(row.get(key).is_some(), "{key} in {row}");
        }
        assert_eq!(row["flip"].is_null(), row["scale"] != 16, "{row}");
        if row["method"] == "refine" {
            assert_eq!(row["mismatch_pct"].as_f64(), Some(0.0), "{row}");
            assert_eq!(row["material_mismatch_pct"].as_f64(), Some(0.0), "{row}");
        }
        let mismatch = row["mismatch_pct"].as_f64().unwrap();
        assert!((0.0..=100.0).contains(&mismatch), "{row}");
    }
    let methods = ["bilinear", "bicubic", "divergence", "planes", "refine"];
    assert!(methods.contains(&json["best"].as_str().unwrap()), "{json}");
    let corners = rows
        .iter()
        .find(|r| r["scene"] == "corners" && r["method"] == "planes" && r["scale"] == 16)
        .unwrap();
    assert!(corners["gap_recall"].as_f64().is_some(), "{corners}");
}

fn render(args: &[&str], png: &Path) -> Output {
    let backend: &[&str] = if args.contains(&"--backend") {
        &[]
    } else {
        &["--backend", "cpu"]
    };
    craterfield()
        .args(["render", "--events", "60", "--seed", "3"])
        .args(backend)
        .args(args)
        .arg("--out")
        .arg(png)
        .output()
        .unwrap()
}

#[test]
fn render_draws_every_mode_and_compares_with_the_exact_render() {
    let dir = temp_dir("render2d");
    let view = ["--view", "1000,500,1400,740", "--width", "240"];
    for mode in ["refine", "planes", "divergence", "off", "exact"] {
        let png = dir.join(format!("{mode}.png"));
        let mut args = view.to_vec();
        args.extend(["--mode", mode, "--json", "--compare-exact"]);
        let out = render(&args, &png);
        assert!(out.status.success(), "{mode}: {}", text(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        for key in [
            "mismatch_pct",
            "material_mismatch_pct",
            "flip",
            "render_ms",
            "render_ms_p99",
        ] {
            assert!(json[key].as_f64().is_some(), "{mode}: {key} in {json}");
        }
        let img = image::open(&png).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (240, 144), "{mode}");
        let heat = dir.join(format!("{mode}-heatmap.png"));
        assert!(heat.is_file(), "{mode}: {}", heat.display());
        if mode == "refine" || mode == "exact" {
            // Proven exact: the same inside/outside state and material at every pixel.
            assert_eq!(json["mismatch_pct"].as_f64(), Some(0.0), "{json}");
            assert_eq!(json["material_mismatch_pct"].as_f64(), Some(0.0), "{json}");
            assert!(json["flip"].as_f64().unwrap() < 0.003, "{json}");
        }
        if mode == "exact" {
            assert_eq!(json["flip"].as_f64(), Some(0.0), "{json}");
        }
    }
    // The text report names the renderer and the comparison.
    let out = render(
        &["--width", "320", "--compare-exact"],
        &dir.join("whole.png"),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("inside/outside mismatch 0.0000%"),
        "{}",
        text(&out.stdout)
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Above the size where the field comparison goes in stripes, the pictures stay whole: each
/// stripe of the exact render once restarted the sky's gradient (FLIP 0.26 on an exact
/// refine picture).
#[test]
fn large_renders_compare_whole_pictures() {
    let dir = temp_dir("render2d-large");
    let out = render(
        &[
            "--width",
            "2800",
            "--height",
            "1600",
            "--compare-exact",
            "--json",
        ],
        &dir.join("large.png"),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["mismatch_pct"].as_f64(), Some(0.0), "{json}");
    assert!(json["flip"].as_f64().unwrap() < 0.003, "{json}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn render_refuses_views_and_options_it_cannot_draw() {
    let dir = temp_dir("render2d-bad");
    let png = dir.join("x.png");
    for (args, needle) in [
        (vec!["--scale", "3"], "--scale 3"),
        (vec!["--mode", "sharpest"], "--mode sharpest"),
        (vec!["--upsample", "lanczos"], "--upsample lanczos"),
        (vec!["--view", "10,10,5,20"], "--view"),
        (
            vec!["--view", "0,0,1e30,1", "--width", "64"],
            "cannot render",
        ),
        (vec!["--width", "100000"], "cannot render"),
        (vec!["--width", "64", "--height", "0"], "cannot render"),
        (vec!["--height", "100"], "--height needs --width"),
        (vec!["--backend", "tpu"], "--backend tpu"),
    ] {
        let out = render(&args, &png);
        assert_refused(&out, needle);
    }
    assert!(!png.exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// A one-circle level with the given bounds (and one spawn point).
fn level_of_bounds(dir: &Path, name: &str, max: (f32, f32)) -> PathBuf {
    let (w, h) = max;
    let text = format!(
        "Level(name: \"{name}\", bounds: (min: (0.0, 0.0), max: ({w:.1}, {h:.1})), cell_size: 64.0,\n\
         materials: [(name: \"rock\", color: (96, 90, 100))], spawns: [({:.1}, {:.1})],\n\
         root: Circle(center: ({:.1}, {:.1}), radius: 4.0), nodes: {{}})\n",
        w / 2.0,
        h - 1.0,
        w / 2.0,
        h / 2.0
    );
    let path = dir.join(format!("{name}.ron"));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn images_of_any_aspect_ratio_are_refused_with_the_width_that_fits() {
    let dir = temp_dir("aspect");
    // The default level past the pixel budget, and levels whose aspect ratio makes one
    // side (or the pixel count) too large at the width asked for.
    let cases: Vec<(Option<PathBuf>, &str)> = vec![
        (None, "12800"),
        (None, "20000"),
        (Some(level_of_bounds(&dir, "tall", (16.0, 65_536.0))), "64"),
        (
            Some(level_of_bounds(&dir, "wide", (65_536.0, 16.0))),
            "16385",
        ),
        (
            Some(level_of_bounds(&dir, "square", (4096.0, 4096.0))),
            "9000",
        ),
    ];
    for (level, width) in &cases {
        let mut cmd = craterfield();
        cmd.args([
            "demo",
            "--events",
            "0",
            "--match-ticks",
            "0",
            "--width",
            width,
        ]);
        if let Some(level) = level {
            cmd.arg("--level").arg(level);
        }
        let out = cmd.arg("--out").arg(dir.join("out")).output().unwrap();
        assert_refused(&out, "pixels wide fits");
    }
    // The same camera check runs before `replay render` re-simulates anything.
    let file = match_file(&dir);
    let tall = level_of_bounds(&dir, "tall", (16.0, 65_536.0));
    let out = craterfield()
        .args(["replay", "render"])
        .arg(&file)
        .arg("--level")
        .arg(&tall)
        .args(["--tick", "0", "--out"])
        .arg(dir.join("tall.png"))
        .output()
        .unwrap();
    assert_refused(&out, "cannot draw level \"tall\"");
    // A size that fits is drawn.
    let square = level_of_bounds(&dir, "square", (4096.0, 4096.0));
    let out = craterfield()
        .args([
            "demo",
            "--events",
            "0",
            "--match-ticks",
            "0",
            "--width",
            "256",
            "--level",
        ])
        .arg(&square)
        .arg("--out")
        .arg(dir.join("ok"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out.stderr));
    let img = image::open(dir.join("ok/terrain.png")).unwrap();
    assert_eq!((img.width(), img.height()), (256, 256));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_match_longer_than_a_replay_holds_is_refused_before_it_starts() {
    let dir = temp_dir("long-match");
    for ticks in ["864001", "4294967295"] {
        let out = craterfield()
            .args(["demo", "--events", "0", "--match-ticks", ticks, "--out"])
            .arg(&dir)
            .output()
            .unwrap();
        assert_refused(&out, "a replay holds at most 864000 ticks");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Every command that reads a file refuses a device, a FIFO (which would block) and a
/// directory at once, naming what it is: never reading until memory runs out.
#[cfg(unix)]
#[test]
fn every_reader_refuses_special_files() {
    let dir = temp_dir("special");
    let fifo = dir.join("fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let png = dir.join("a.png");
    write_diff_image(&png, [10, 20, 30], 8);
    let specials = [
        (PathBuf::from("/dev/zero"), "character device"),
        (fifo, "FIFO"),
        (dir.clone(), "directory"),
    ];
    for (special, kind) in &specials {
        let s = special.to_str().unwrap();
        let p = png.to_str().unwrap();
        let out_png = dir.join("out.png");
        let o = out_png.to_str().unwrap();
        let runs: Vec<Vec<&str>> = vec![
            vec!["level", "check", s],
            vec!["replay", "info", s],
            vec!["replay", "verify", s],
            vec!["march3d", "--scene", s, "--out", o],
            vec!["demo", "--level", s, "--out", o],
            vec!["diff", s, p],
            vec!["diff", p, s],
        ];
        for args in runs {
            let out = craterfield().args(&args).output().unwrap();
            // `level check` reports per file on stdout; the others on stderr.
            let stderr = text(&out.stderr) + &text(&out.stdout);
            assert!(!out.status.success(), "{args:?}");
            assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
            assert!(
                stderr.contains(kind),
                "{args:?}: expected {kind:?} in {stderr}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A GPU command on a machine without a desktop (no runtime directory, no display) prints
/// only its own output: the adapter search's loader layers say nothing.
#[test]
fn a_headless_gpu_run_prints_only_its_own_output() {
    let dir = temp_dir("headless");
    let out = craterfield()
        .args(["render", "--backend", "auto", "--width", "160", "--out"])
        .arg(dir.join("frame.png"))
        .env_remove("XDG_RUNTIME_DIR")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("DISPLAY")
        .env_remove("NODEVICE_SELECT")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        !stderr.contains("XDG_RUNTIME_DIR"),
        "the adapter search printed into the output: {stderr}"
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.starts_with("wrote "), "{stdout}");
    std::fs::remove_dir_all(&dir).ok();
}
