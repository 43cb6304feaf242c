//! Rolling a terrain back to a mark and re-applying gives the same bits as never having
//! rolled back: events, growth, fills, pruning and baked bricks included; compacting the
//! event log changes no query, with or without rollbacks.

mod common;
use common::Rng;

use craterfield::field2d::terrain::RollbackError;
use craterfield::field2d::{Event, Level, Sdf, Terrain};
use glam::Vec2;

/// One step of a scripted history: an event, or a tick advance.
#[derive(Clone, Copy)]
enum Step {
    Event(Event),
    Tick(u32),
}

fn script(seed: u64, n: usize) -> Vec<Step> {
    let mut rng = Rng(seed);
    let mut tick = 0;
    let mut out = Vec::new();
    for _ in 0..n {
        if rng.unit() < 0.2 {
            tick += 1 + (rng.next() % 5) as u32;
            out.push(Step::Tick(tick));
            continue;
        }
        // Clustered centres so cells overflow their cap and bake bricks.
        let c = Vec2::new(1200.0 + rng.unit() * 300.0, 450.0 + rng.unit() * 250.0);
        let r = 4.0 + rng.unit() * 40.0;
        let mut e = if rng.unit() < 0.25 {
            Event::fill(c, r, (rng.next() % 4) as u16).unwrap()
        } else {
            Event::carve(c, r).unwrap()
        };
        if rng.unit() < 0.2 {
            e = e.with_rim(rng.unit() * 8.0).unwrap();
        }
        if rng.unit() < 0.2 {
            e = e.with_growth(1 + (rng.next() % 8) as u16);
        }
        out.push(Step::Event(e.at_tick(tick)));
    }
    out
}

fn run(t: &mut Terrain<craterfield::field2d::Graph>, steps: &[Step]) {
    for s in steps {
        match *s {
            Step::Event(e) => t.apply(e).unwrap(),
            Step::Tick(k) => t.set_tick(k).unwrap(),
        }
    }
}

/// Runs `steps` on `t` in chunks of 1 to 40, marking after each and, half the time, going
/// back to a random earlier mark and redoing from there; `after_each` sees the terrain
/// after every chunk (and rollback).
fn run_with_rollbacks(
    t: &mut Terrain<craterfield::field2d::Graph>,
    steps: &[Step],
    seed: u64,
    mut after_each: impl FnMut(&Terrain<craterfield::field2d::Graph>),
) {
    let mut rng = Rng(seed);
    let mut done = 0;
    let mut marks = vec![(0, t.mark().unwrap())];
    while done < steps.len() {
        let upto = (done + 1 + (rng.next() % 40) as usize).min(steps.len());
        run(t, &steps[done..upto]);
        done = upto;
        marks.push((done, t.mark().unwrap()));
        if rng.unit() < 0.5 {
            let k = (rng.next() % marks.len() as u64) as usize;
            let (at, m) = marks[k];
            t.rollback(&m).unwrap();
            assert_eq!(t.events_applied(), m.events());
            marks.truncate(k + 1);
            done = at;
        }
        after_each(t);
    }
}

fn fingerprint(t: &Terrain<craterfield::field2d::Graph>) -> Vec<u32> {
    let mut out = Vec::new();
    for j in 0..60 {
        for i in 0..90 {
            let p = Vec2::new(1150.0 + i as f32 * 4.37, 400.0 + j as f32 * 5.91);
            let s = t.sample(p);
            out.extend([
                s.distance.to_bits(),
                s.gradient.x.to_bits(),
                s.gradient.y.to_bits(),
                u32::from(s.material),
            ]);
        }
    }
    out
}

fn terrain() -> Terrain<craterfield::field2d::Graph> {
    let level = Level::default_level();
    let b = level.bounds();
    let mut o = level.terrain_options();
    o.cell_cap = 6;
    o.brick_resolution = 8;
    let mut t = Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap();
    t.enable_rollback();
    t
}

#[test]
fn rollback_then_replay_matches_a_straight_run() {
    for seed in 0..3u64 {
        let steps = script(seed, 300);
        let mut straight = terrain();
        run(&mut straight, &steps);
        assert!(straight.stats().bakes > 0, "the script must bake bricks");

        let mut t = terrain();
        run_with_rollbacks(&mut t, &steps, seed ^ 0xabc, |_| {});
        assert_eq!(t.events(), straight.events(), "seed {seed}");
        assert_eq!(t.tick(), straight.tick());
        assert_eq!(t.stats(), straight.stats(), "seed {seed}");
        assert!(
            fingerprint(&t) == fingerprint(&straight),
            "seed {seed}: field differs"
        );
    }
}

#[test]
fn rollback_restores_the_exact_field_of_the_mark() {
    let steps = script(99, 300);
    let mut t = terrain();
    run(&mut t, &steps[..100]);
    let before = fingerprint(&t);
    let stats = t.stats();
    let m = t.mark().unwrap();
    run(&mut t, &steps[100..]);
    assert!(fingerprint(&t) != before);
    t.rollback(&m).unwrap();
    assert_eq!(t.stats(), stats);
    assert!(fingerprint(&t) == before);
}

#[test]
fn stale_forgotten_and_disabled_marks_are_refused_without_change() {
    let steps = script(7, 200);
    let mut t = terrain();
    run(&mut t, &steps[..50]);
    let early = t.mark().unwrap();
    run(&mut t, &steps[50..100]);
    let future = t.mark().unwrap();
    t.rollback(&early).unwrap();
    run(&mut t, &steps[150..160]);
    // `future` was on the timeline that the rollback discarded.
    let fp = fingerprint(&t);
    assert!(matches!(
        t.rollback(&future),
        Err(RollbackError::NotOnTimeline { .. })
    ));
    assert!(fingerprint(&t) == fp);
    let now = t.mark().unwrap();
    t.forget_before(&now);
    assert_eq!(t.journal_len(), 0);
    let e = t.rollback(&early).unwrap_err();
    assert!(matches!(e, RollbackError::TooOld { .. }), "{e}");
    assert!(e.to_string().contains("older"), "{e}");
    t.rollback(&now).unwrap();

    let level = Level::default_level();
    let mut plain = level.terrain().unwrap();
    assert!(plain.mark().is_none());
    assert_eq!(plain.rollback(&now), Err(RollbackError::Disabled));
}

#[test]
fn region_stamps_change_with_the_field_and_never_repeat() {
    let mut t = terrain();
    let p = Vec2::new(1300.0, 500.0);
    let far = Vec2::new(3000.0, 500.0);
    let s0 = t.region_stamp(p).unwrap();
    let m = t.mark().unwrap();
    t.apply(Event::carve(p, 10.0).unwrap()).unwrap();
    let s1 = t.region_stamp(p).unwrap();
    assert_ne!(s0, s1, "an event in the cell changes its stamp");
    assert_eq!(t.region_stamp(far), Some(s0), "other cells keep theirs");
    // Rolled back, the cell is as it was and so is its stamp; changed again, it gets a
    // stamp never seen before, though the event count is the same as after the first.
    t.rollback(&m).unwrap();
    assert_eq!(t.region_stamp(p), Some(s0));
    t.apply(Event::carve(p + Vec2::new(3.0, 0.0), 10.0).unwrap())
        .unwrap();
    let s2 = t.region_stamp(p).unwrap();
    assert!(s2 != s0 && s2 != s1);
    // While a growing event is unsettled the field depends on the tick: no stamp.
    t.apply(
        Event::carve(p, 20.0)
            .unwrap()
            .with_growth(10)
            .at_tick(t.tick()),
    )
    .unwrap();
    assert_eq!(t.region_stamp(p), None);
    t.set_tick(t.tick() + 10).unwrap();
    assert!(t.region_stamp(p).is_some());
    // Outside the grid nothing ever changes.
    assert_eq!(t.region_stamp(Vec2::new(-500.0, -500.0)), Some(0));
}

fn compacting_terrain(max_events: usize) -> Terrain<craterfield::field2d::Graph> {
    let level = Level::default_level();
    let b = level.bounds();
    let mut o = level.terrain_options();
    o.cell_cap = 6;
    o.brick_resolution = 8;
    o.max_events = max_events;
    let mut t = Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap();
    t.enable_rollback();
    t
}

/// Every cell's list as the events it names (indices differ once a log is compacted).
fn lists(t: &Terrain<craterfield::field2d::Graph>) -> Vec<Vec<Event>> {
    let g = t.grid();
    (0..g.cell_count())
        .map(|i| {
            g.cell(i)
                .map(|c| c.events().iter().map(|&k| t.events()[k as usize]).collect())
                .unwrap_or_default()
        })
        .collect()
}

#[test]
fn compaction_changes_no_query_and_bounds_the_log() {
    for seed in 0..3u64 {
        let steps = script(seed ^ 0x5eed, 1500);
        let mut whole = terrain();
        let mut compact = compacting_terrain(64);
        for chunk in steps.chunks(100) {
            run(&mut whole, chunk);
            run(&mut compact, chunk);
            // Keep a short rollback window, as a world does, so the journal lets go.
            for t in [&mut whole, &mut compact] {
                let m = t.mark().unwrap();
                t.forget_before(&m);
            }
            assert!(fingerprint(&whole) == fingerprint(&compact), "seed {seed}");
            assert_eq!(lists(&whole), lists(&compact), "seed {seed}");
            assert_eq!(whole.stats(), compact.stats(), "seed {seed}");
            assert_eq!(whole.events_applied(), compact.events_applied());
        }
        assert!(whole.history_complete());
        assert!(!compact.history_complete(), "seed {seed}: it compacted");
        let kept = compact.events().len();
        let reachable: usize = lists(&compact).iter().map(Vec::len).sum();
        assert!(
            kept < 2 * 64.max(reachable) + 100,
            "seed {seed}: the log keeps {kept} events ({reachable} listed)"
        );
        assert!(kept < whole.events().len() / 2, "seed {seed}: {kept} kept");
    }
}

#[test]
fn compaction_keeps_rollback_exact() {
    let steps = script(41, 900);
    let mut straight = compacting_terrain(1 << 20);
    let mut t = compacting_terrain(32);
    run(&mut straight, &steps[..300]);
    run(&mut t, &steps[..300]);
    let m = t.mark().unwrap();
    // Events before the mark can go; the ones after it stay while the mark is kept.
    t.forget_before(&m);
    let at_mark = (fingerprint(&t), t.stats(), t.events_applied());
    // Compacts several times past the mark; the journal's pre-images are renumbered.
    run(&mut t, &steps[300..700]);
    assert!(!t.history_complete());
    t.rollback(&m).unwrap();
    assert!(
        (fingerprint(&t), t.stats(), t.events_applied()) == at_mark,
        "the mark's field, counters and event count come back"
    );
    run(&mut t, &steps[300..]);
    run(&mut straight, &steps[300..]);
    assert!(fingerprint(&t) == fingerprint(&straight));
    assert_eq!(lists(&t), lists(&straight));
    assert_eq!(t.stats(), straight.stats());
}

#[test]
fn moving_the_tick_back_after_compaction_is_refused_without_change() {
    let steps = script(5, 600);
    let mut t = compacting_terrain(16);
    run(&mut t, &steps);
    let m = t.mark().unwrap();
    t.forget_before(&m);
    t.compact_history();
    assert!(!t.history_complete());
    let before = (fingerprint(&t), t.tick(), t.stats());
    let err = t.set_tick(0).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("compaction") && msg.contains("mark"), "{msg}");
    assert!((fingerprint(&t), t.tick(), t.stats()) == before);
    // Forwards still works, and events still apply.
    t.set_tick(t.tick() + 1).unwrap();
    t.apply(
        Event::carve(Vec2::new(1300.0, 500.0), 20.0)
            .unwrap()
            .at_tick(t.tick()),
    )
    .unwrap();
}

/// Where clear runs ([`Sdf::clear_run`]) from a lattice of points around the edits end,
/// along eight directions and at two thresholds, as bits. The terrain keeps per-cell
/// bounds for these runs, computed on the first run that asks: asking here fills them.
fn clear_run_fingerprint(t: &Terrain<craterfield::field2d::Graph>) -> Vec<u32> {
    let mut out = Vec::new();
    for j in 0..24 {
        for i in 0..36 {
            let p = Vec2::new(1080.0 + i as f32 * 13.1, 330.0 + j as f32 * 19.7);
            for k in 0..8 {
                let dir = Vec2::from_angle(k as f32 * std::f32::consts::FRAC_PI_4 + 0.1);
                for above in [1.0e-3, 6.0] {
                    let run = t.clear_run(p, dir, above);
                    out.extend([run.clear.to_bits(), run.retry_after.to_bits()]);
                }
            }
        }
    }
    out
}

/// A terrain asked for clear runs between its edits (so that it holds bounds computed
/// before each edit), rolled back and forth, and restored from a state, ends with the
/// clear runs of a terrain that was never asked until the end: no bound outlives the
/// cell it was computed for (a fill into air, a bake, a rollback, a restore).
#[test]
fn clear_runs_follow_every_edit_rollback_and_restore() {
    for seed in 0..2u64 {
        let steps = script(seed + 40, 300);
        let mut straight = terrain();
        run(&mut straight, &steps);
        let mut t = terrain();
        let mut runs_changed = 0;
        let mut last = clear_run_fingerprint(&t);
        run_with_rollbacks(&mut t, &steps, seed ^ 0x5eed, |t| {
            let now = clear_run_fingerprint(t);
            runs_changed += usize::from(now != last);
            last = now;
        });
        assert!(
            runs_changed > 3,
            "seed {seed}: the edits changed the runs only {runs_changed} times"
        );
        assert!(
            clear_run_fingerprint(&t) == clear_run_fingerprint(&straight),
            "seed {seed}: clear runs differ after edits and rollbacks"
        );
        // A state restored over a terrain that holds bounds of another history.
        let mut restored = terrain();
        run(&mut restored, &script(seed + 90, 200));
        let _ = clear_run_fingerprint(&restored);
        restored.restore_state(&straight.state()).unwrap();
        assert!(
            clear_run_fingerprint(&restored) == clear_run_fingerprint(&straight),
            "seed {seed}: clear runs differ after a restore"
        );
    }
}
