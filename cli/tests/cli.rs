//! The command-line tool end to end: the demo writes its image and summary, `level check`
//! accepts good levels and names the problem in bad ones, and `bench field --json` prints
//! the documented keys.

use std::path::PathBuf;
use std::process::Command;

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
        assert!(
            out.status.success(),
            "{}: {}",
            path.display(),
            String::from_utf8_lossy(&out.stdout)
        );
    }
    let dir = temp_dir("check");
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
