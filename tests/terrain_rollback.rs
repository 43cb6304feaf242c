//! Rolling a terrain back to a mark and re-applying gives the same bits as never having
//! rolled back: events, growth, fills, pruning and baked bricks included.

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
            Step::Tick(k) => t.set_tick(k),
        }
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

        let mut rng = Rng(seed ^ 0xabc);
        let mut t = terrain();
        let mut done = 0;
        let mut marks = vec![(0, t.mark().unwrap())];
        while done < steps.len() {
            let upto = (done + 1 + (rng.next() % 40) as usize).min(steps.len());
            run(&mut t, &steps[done..upto]);
            done = upto;
            marks.push((done, t.mark().unwrap()));
            // Sometimes go back to an earlier mark and redo from there.
            if rng.unit() < 0.5 {
                let k = (rng.next() % marks.len() as u64) as usize;
                let (at, m) = marks[k];
                t.rollback(&m).unwrap();
                assert_eq!(t.events().len() as u32, m.events());
                marks.truncate(k + 1);
                done = at;
            }
        }
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
    t.set_tick(t.tick() + 10);
    assert!(t.region_stamp(p).is_some());
    // Outside the grid nothing ever changes.
    assert_eq!(t.region_stamp(Vec2::new(-500.0, -500.0)), Some(0));
}
