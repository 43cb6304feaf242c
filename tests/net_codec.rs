//! Replay files and wire messages: round trips, one specific error per corruption class,
//! decoders that never panic on hostile bytes, and the size figures the formats promise.

mod common;
use common::Rng;

use std::time::Instant;

use craterfield::det::quant::FIXED_MAX;
use craterfield::field2d::Level;
use craterfield::field2d::{Event, EventKind};
use craterfield::net::replay::{self, Recorder, Replay, VerifyError};
use craterfield::net::wire::{self, MessageKind, TerrainSnapshot};
use craterfield::net::{DecodeError, DecodeErrorKind};
use craterfield::net::{DecodeLimits, crc32};
use craterfield::sim::{Input, Settings, World, buttons, level_hash};
use proptest::prelude::*;

impl Rng {
    /// Any valid input.
    fn input(&mut self) -> Input {
        Input {
            aim: self.next() as u16,
            buttons: self.below(8) as u8,
            drive: (self.below(255) as i16 - 127) as i8,
            power: self.next() as u8,
            weapon: self.below(2) as u8,
        }
    }
}

/// A replay whose every tick is a fresh random row (the worst case for run lengths), with
/// made-up hashes (no simulation needed to test the format).
fn random_replay(rng: &mut Rng, players: u8, ticks: u32) -> Replay {
    let mut rec = Recorder::new(rng.next(), Settings::default(), players, 60).unwrap();
    for t in 1..=ticks {
        let row: Vec<Input> = (0..players).map(|_| rng.input()).collect();
        rec.record(&row, t, rng.next()).unwrap();
    }
    rec.finish(ticks, rng.next())
}

/// A human-like script: each player changes one thing every 10 to 30 ticks (2 to 6 times a
/// second at 60 Hz): throttle, a new aim, power, weapon, or a one-tick fire or jump press.
fn scripted_rows(players: usize, ticks: u32, seed: u64) -> Vec<Vec<Input>> {
    let mut rng = Rng(seed);
    let mut row = vec![Input::default(); players];
    let mut next_change: Vec<u32> = (0..players).map(|_| rng.below(30) as u32).collect();
    let mut rows = Vec::new();
    for t in 0..ticks {
        for (p, input) in row.iter_mut().enumerate() {
            // A press lasts one tick.
            input.buttons &= buttons::STICK;
            if t < next_change[p] {
                continue;
            }
            next_change[p] = t + 10 + rng.below(21) as u32;
            match rng.below(6) {
                0 => input.drive = [-127, 0, 127][rng.below(3) as usize],
                1 => input.aim = rng.next() as u16,
                2 => input.power = rng.next() as u8,
                3 => input.weapon ^= 1,
                4 => input.buttons |= buttons::FIRE,
                _ => input.buttons |= buttons::JUMP,
            }
        }
        rows.push(row.clone());
    }
    rows
}

fn scripted_replay(players: u8, ticks: u32, seed: u64) -> Replay {
    let mut rec = Recorder::new(seed, Settings::default(), players, 60).unwrap();
    let mut rng = Rng(seed ^ 1);
    for (t, row) in scripted_rows(players.into(), ticks, seed)
        .iter()
        .enumerate()
    {
        rec.record(row, t as u32 + 1, rng.next()).unwrap();
    }
    rec.finish(ticks, rng.next())
}

/// Overwrites the trailing CRC-32 so a mutation reaches the section parsers.
fn fix_crc(bytes: &mut [u8]) {
    if bytes.len() >= 4 {
        let n = bytes.len() - 4;
        let c = crc32(&bytes[..n]);
        bytes[n..].copy_from_slice(&c.to_le_bytes());
    }
}

fn kind_of<T: std::fmt::Debug>(r: Result<T, DecodeError>) -> DecodeError {
    r.expect_err("the corrupted input must be rejected")
}

/// `e` refuses an event count past the reader's limit.
fn assert_event_count_too_large(e: &DecodeError) {
    assert!(
        matches!(
            e.kind,
            DecodeErrorKind::TooLarge {
                what: "event count",
                ..
            }
        ),
        "{e}"
    );
}

// ---------------------------------------------------------------------------------------
// Replays
// ---------------------------------------------------------------------------------------

#[test]
fn replay_round_trips_for_two_to_four_players() {
    let mut rng = Rng(7);
    for players in 2..=4u8 {
        for replay in [
            random_replay(&mut rng, players, 3_000),
            scripted_replay(players, 5_000, players.into()),
        ] {
            let bytes = replay.encode().unwrap();
            let back = Replay::decode(&bytes).unwrap();
            assert_eq!(back, replay);
            assert_eq!(back.ticks(), replay.ticks());
            assert_eq!(back.row(17), replay.row(17));
            // Every 60 ticks, plus the final tick.
            assert_eq!(back.hashes.len() as u32, replay.ticks().div_ceil(60));
            assert_eq!(back.hash_at(60), replay.hashes.first().map(|h| h.1));
        }
    }
}

#[test]
fn recorder_misuse_is_an_error_not_a_panic() {
    for (players, interval) in [(0, 60), (9, 60), (2, 0)] {
        let e = Recorder::new(1, Settings::default(), players, interval).unwrap_err();
        assert!(
            e.to_string()
                .contains(if interval == 0 { "interval" } else { "players" }),
            "{e}"
        );
    }
    let mut rec = Recorder::new(1, Settings::default(), 2, 60).unwrap();
    let e = rec.record(&[Input::default(); 3], 1, 5).unwrap_err();
    assert!(
        e.to_string().contains("3 inputs recorded for 2 players"),
        "{e}"
    );
    assert_eq!(rec.ticks(), 0, "nothing recorded");
}

#[test]
fn empty_and_single_tick_replays_round_trip() {
    let rec = Recorder::new(1, Settings::default(), 1, 60).unwrap();
    let empty = rec.finish(0, 99);
    assert_eq!((empty.ticks(), empty.hashes.clone()), (0, vec![(0, 99)]));
    assert_eq!(Replay::decode(&empty.encode().unwrap()).unwrap(), empty);
    let mut rec = Recorder::new(1, Settings::default(), 8, 1).unwrap();
    rec.record(&[Input::default(); 8], 1, 5).unwrap();
    let one = rec.finish(1, 5);
    assert_eq!(one.hashes, vec![(1, 5)]);
    assert_eq!(Replay::decode(&one.encode().unwrap()).unwrap(), one);
}

/// The layout in the module documentation, written by hand byte by byte.
#[test]
fn hand_written_file_follows_the_documented_layout() {
    let settings = Settings::default();
    let header = postcard::to_stdvec(&(0xabcd_u64, settings, 2u8, 60u32, 3u32)).unwrap();
    let mut inputs = vec![2u8, 0b10, 0b0000_0101]; // 2 ticks: player 1 sets aim and drive
    inputs.extend_from_slice(&[0x34, 0x12, 0xff]); // aim 0x1234, drive -1
    inputs.extend_from_slice(&[1, 0b01, 0b0000_1000, 200]); // 1 tick: player 0 power 200
    let mut hashes = vec![1u8, 3]; // one hash, for tick 3
    hashes.extend_from_slice(&7u64.to_le_bytes());
    let mut file = b"CRTRPLY\0".to_vec();
    file.extend_from_slice(&1u16.to_le_bytes());
    for section in [&header, &inputs, &hashes] {
        file.extend_from_slice(&(section.len() as u32).to_le_bytes());
        file.extend_from_slice(section);
    }
    file.extend_from_slice(&[0; 4]);
    fix_crc(&mut file);

    let r = Replay::decode(&file).unwrap();
    let p1 = Input {
        aim: 0x1234,
        drive: -1,
        ..Input::default()
    };
    let p0 = Input {
        power: 200,
        ..Input::default()
    };
    assert_eq!(
        (r.level_hash, r.players, r.hash_interval, r.ticks()),
        (0xabcd, 2, 60, 3)
    );
    assert_eq!(
        r.inputs,
        vec![Input::default(), p1, Input::default(), p1, p0, p1]
    );
    assert_eq!(r.hashes, vec![(3, 7)]);
    assert_eq!(
        r.encode().unwrap(),
        file,
        "the encoder writes the same bytes"
    );
}

#[test]
fn truncation_at_every_offset_is_reported_in_its_section() {
    let replay = scripted_replay(2, 200, 3);
    let bytes = replay.encode().unwrap();
    for cut in 0..bytes.len() {
        let e = kind_of(Replay::decode(&bytes[..cut]));
        assert!(
            matches!(e.kind, DecodeErrorKind::Truncated { .. }),
            "cut at {cut}: {e}"
        );
        assert!(e.offset <= cut, "cut at {cut}: {e}");
        let expected = ["magic", "version", "header", "inputs", "hashes", "checksum"];
        assert!(expected.contains(&e.section.as_ref()), "cut at {cut}: {e}");
    }
    let e = kind_of(Replay::decode(&bytes[..bytes.len() - 2]));
    assert_eq!(e.section, "checksum");
    let mut longer = bytes.clone();
    longer.push(0);
    let e = kind_of(Replay::decode(&longer));
    assert_eq!(
        (e.section.as_ref(), e.kind),
        ("checksum", DecodeErrorKind::TrailingBytes { count: 1 })
    );
}

#[test]
fn flipped_bytes_are_caught() {
    let bytes = scripted_replay(3, 300, 5).encode().unwrap();
    // The framing: magic, version and the three section lengths.
    let len_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    let inputs_at = 14 + len_at(10);
    let hashes_at = inputs_at + 4 + len_at(inputs_at);
    let framing = |i: usize| {
        i < 14 || (inputs_at..inputs_at + 4).contains(&i) || (hashes_at..hashes_at + 4).contains(&i)
    };
    for i in 0..bytes.len() {
        for bit in [0x01, 0x80] {
            let mut bad = bytes.clone();
            bad[i] ^= bit;
            let e = kind_of(Replay::decode(&bad));
            // Damage to the contents of a section can only show in the checksum.
            if !framing(i) {
                assert!(
                    matches!(e.kind, DecodeErrorKind::ChecksumMismatch { .. }),
                    "byte {i}: {e}"
                );
            }
        }
    }
    let mut bad = bytes.clone();
    bad[20] ^= 0x10;
    let e = kind_of(Replay::decode(&bad));
    assert_eq!(e.section, "checksum");
    assert!(e.to_string().contains("checksum mismatch"), "{e}");
}

#[test]
fn wrong_magic_and_version_are_named() {
    let bytes = scripted_replay(2, 100, 9).encode().unwrap();
    let mut bad = bytes.clone();
    bad[0] = b'X';
    let e = kind_of(Replay::decode(&bad));
    assert!(matches!(e.kind, DecodeErrorKind::BadMagic { .. }), "{e}");
    assert_eq!((e.section.as_ref(), e.offset), ("magic", 0));
    let e = kind_of(Replay::decode(b"PNG\x89 not a replay"));
    assert!(matches!(e.kind, DecodeErrorKind::BadMagic { .. }), "{e}");

    let mut bad = bytes.clone();
    bad[8..10].copy_from_slice(&3u16.to_le_bytes());
    fix_crc(&mut bad);
    let e = kind_of(Replay::decode(&bad));
    assert_eq!(
        e.kind,
        DecodeErrorKind::UnsupportedVersion {
            found: 3,
            supported: 2
        }
    );
    assert_eq!((e.section.as_ref(), e.offset), ("version", 8));
}

/// A file with a valid checksum whose header or lengths claim 2^31 of something.
#[test]
fn absurd_counts_are_rejected_before_allocating() {
    let build = |ticks: u32, players: u8, inputs: &[u8], hashes: &[u8]| {
        let header =
            postcard::to_stdvec(&(1u64, Settings::default(), players, 60u32, ticks)).unwrap();
        let mut file = b"CRTRPLY\0".to_vec();
        file.extend_from_slice(&1u16.to_le_bytes());
        for section in [&header[..], inputs, hashes] {
            file.extend_from_slice(&(section.len() as u32).to_le_bytes());
            file.extend_from_slice(section);
        }
        file.extend_from_slice(&[0; 4]);
        fix_crc(&mut file);
        file
    };
    let start = Instant::now();
    // 2^31 ticks in one run.
    let e = kind_of(Replay::decode(&build(
        1 << 31,
        2,
        &[0x80, 0x80, 0x80, 0x80, 0x08, 0],
        &[0],
    )));
    assert_eq!(
        (e.section.as_ref(), e.kind),
        (
            "header",
            DecodeErrorKind::TooLarge {
                what: "ticks",
                value: 1 << 31,
                limit: 864_000
            }
        )
    );
    // Within the tick limit, but a 2^31-entry hash list in a few bytes.
    let e = kind_of(Replay::decode(&build(
        0,
        2,
        &[],
        &[0x80, 0x80, 0x80, 0x80, 0x08],
    )));
    assert!(
        matches!(
            e.kind,
            DecodeErrorKind::TooLarge {
                what: "hash count",
                ..
            }
        ),
        "{e}"
    );
    let e = kind_of(Replay::decode(&build(
        100_000,
        2,
        &[0xa0, 0x8d, 0x06, 0],
        &[0xff, 0xff, 0x01],
    )));
    assert!(
        matches!(e.kind, DecodeErrorKind::Truncated { .. }) && e.section == "hashes",
        "{e}"
    );
    // Players beyond the format.
    let e = kind_of(Replay::decode(&build(0, 200, &[], &[0])));
    assert!(
        matches!(
            e.kind,
            DecodeErrorKind::TooLarge {
                what: "players",
                ..
            }
        ),
        "{e}"
    );
    // A section length of 2^31 in a short file.
    let mut file = build(0, 2, &[], &[0]);
    let at = 14 + u32::from_le_bytes(file[10..14].try_into().unwrap()) as usize;
    file[at..at + 4].copy_from_slice(&(1u32 << 31).to_le_bytes());
    fix_crc(&mut file);
    let e = kind_of(Replay::decode(&file));
    assert_eq!((e.section.as_ref(), e.offset), ("inputs", at));
    assert!(
        matches!(
            e.kind,
            DecodeErrorKind::TooLarge {
                what: "section length",
                ..
            }
        ),
        "{e}"
    );
    // Tighter limits apply too.
    let limits = DecodeLimits {
        max_ticks: 10,
        max_bytes: 1 << 20,
        ..DecodeLimits::default()
    };
    let e = kind_of(Replay::decode_with_limits(
        &build(11, 1, &[11, 0], &[0]),
        &limits,
    ));
    assert!(
        matches!(
            e.kind,
            DecodeErrorKind::TooLarge {
                what: "ticks",
                value: 11,
                limit: 10
            }
        ),
        "{e}"
    );
    let e = kind_of(Replay::decode_with_limits(&vec![0; (1 << 20) + 1], &limits));
    assert!(
        matches!(
            e.kind,
            DecodeErrorKind::TooLarge {
                what: "input length",
                ..
            }
        ),
        "{e}"
    );
    assert!(
        start.elapsed().as_millis() < 500,
        "rejected in {:?}",
        start.elapsed()
    );
}

/// A one-player file of `ticks` ticks with the given settings and inputs section.
fn one_player_file(settings: Settings, ticks: u32, inputs: &[u8]) -> Vec<u8> {
    let header = postcard::to_stdvec(&(1u64, settings, 1u8, 60u32, ticks)).unwrap();
    let mut file = b"CRTRPLY\0".to_vec();
    file.extend_from_slice(&1u16.to_le_bytes());
    for section in [&header[..], inputs, &[0]] {
        file.extend_from_slice(&(section.len() as u32).to_le_bytes());
        file.extend_from_slice(section);
    }
    file.extend_from_slice(&[0; 4]);
    fix_crc(&mut file);
    file
}

#[test]
fn invalid_values_are_rejected_with_the_validators_message() {
    let settings = Settings {
        tick_hz: 0,
        ..Settings::default()
    };
    let e = kind_of(Replay::decode(&one_player_file(settings, 1, &[1, 0])));
    assert!(
        matches!(e.kind, DecodeErrorKind::InvalidValue { .. }) && e.section == "header",
        "{e}"
    );
    assert!(e.to_string().contains("tick_hz"), "{e}");
    // Reserved button bits, weapon 9, drive -128.
    for (fields, value, needle) in [
        (0b10, 0x80, "reserved"),
        (0b1_0000, 9, "weapon 9"),
        (0b100, 0x80, "drive"),
    ] {
        let file = one_player_file(Settings::default(), 1, &[1, 1, fields, value]);
        let e = kind_of(Replay::decode(&file));
        assert!(
            matches!(e.kind, DecodeErrorKind::InvalidValue { .. }),
            "{e}"
        );
        // The input's change starts after the header, the inputs length, run length and mask.
        let input_at = 14 + u32::from_le_bytes(file[10..14].try_into().unwrap()) as usize + 4 + 2;
        assert_eq!(
            (e.section.as_ref(), e.offset),
            ("inputs at tick 0", input_at)
        );
        assert!(
            e.to_string().contains(needle) && e.to_string().contains("player 0"),
            "{e}"
        );
    }
    // Structure: a zero-length run, a player beyond the count, a run repeating its row, an
    // empty field mask, runs past the tick count, bytes after the last run.
    for (ticks, bytes, needle) in [
        (1, &[0u8, 0][..], "run of 0"),
        (1, &[1, 2], "player mask"),
        (2, &[1, 0, 1, 0], "repeats"),
        (1, &[1, 1, 0], "field mask"),
        (1, &[2, 0], "run of 2"),
        (1, &[1, 0, 1, 0], "2 trailing bytes"),
        (2, &[1, 0], "truncated"),
    ] {
        let e = kind_of(Replay::decode(&one_player_file(
            Settings::default(),
            ticks,
            bytes,
        )));
        assert!(
            e.section.starts_with("inputs") && e.to_string().contains(needle),
            "{e}"
        );
    }
}

#[test]
fn encoding_rejects_inconsistent_replays() {
    let good = scripted_replay(2, 10, 1);
    let mut bad = good.clone();
    bad.inputs.pop();
    assert!(bad.encode().is_err());
    let mut bad = good.clone();
    bad.inputs[3].buttons = 0x40;
    assert!(
        bad.encode()
            .unwrap_err()
            .to_string()
            .contains("tick 1 player 1")
    );
    let mut bad = good.clone();
    bad.hashes.push((11, 0));
    assert!(bad.encode().is_err());
    let mut bad = good;
    bad.players = 9;
    assert!(bad.encode().is_err());
}

/// Each way a hand-built replay can break its invariants: verify refuses it with the
/// invariant named, before simulating anything (encode refuses the same replays).
#[test]
fn verify_refuses_the_replays_encode_refuses() {
    let level = Level::default_level();
    let mut good = scripted_replay(2, 10, 1);
    good.level_hash = level_hash(&level);
    let mut breaks: Vec<(Replay, &str)> = Vec::new();
    let mut ragged = good.clone();
    ragged.inputs.pop();
    breaks.push((ragged, "not whole rows"));
    let mut reserved = good.clone();
    reserved.inputs[3].buttons = 0x40;
    breaks.push((reserved, "tick 1 player 1"));
    let mut late_hash = good.clone();
    late_hash.hashes.push((11, 0));
    breaks.push((late_hash, "hash ticks"));
    let mut unordered = good.clone();
    unordered.hashes = vec![(5, 0), (3, 0)];
    breaks.push((unordered, "hash ticks"));
    let mut no_players = good.clone();
    no_players.players = 0;
    breaks.push((no_players, "0 players"));
    let mut interval = good.clone();
    interval.hash_interval = 0;
    breaks.push((interval, "hash interval"));
    let mut settings = good.clone();
    settings.settings.tick_hz = 0;
    breaks.push((settings, "tick_hz"));
    for (replay, needle) in breaks {
        assert!(replay.encode().is_err(), "{needle}");
        match replay::verify(&replay, &level) {
            Err(VerifyError::Inconsistent { detail }) => {
                assert!(detail.contains(needle), "{needle}: {detail}")
            }
            other => panic!("{needle}: {other:?}"),
        }
    }
}

/// What `encode` writes, `decode` reads: a replay longer (or larger) than the decoder's
/// limits is refused when it is written, and a recorder stops at the tick limit.
#[test]
fn encode_refuses_what_decode_would_refuse() {
    let limits = DecodeLimits {
        max_ticks: 50,
        ..DecodeLimits::default()
    };
    let replay = scripted_replay(2, 51, 3);
    let e = replay.encode_with_limits(&limits).unwrap_err().to_string();
    assert!(e.contains("ticks = 51") && e.contains("50"), "{e}");
    let fits = scripted_replay(2, 50, 3);
    let bytes = fits.encode_with_limits(&limits).unwrap();
    assert_eq!(Replay::decode_with_limits(&bytes, &limits).unwrap(), fits);
    let few_players = DecodeLimits {
        max_players: 1,
        ..DecodeLimits::default()
    };
    assert!(fits.encode_with_limits(&few_players).is_err());
    let small = DecodeLimits {
        max_bytes: 16,
        ..DecodeLimits::default()
    };
    let e = fits.encode_with_limits(&small).unwrap_err().to_string();
    assert!(e.contains("file length"), "{e}");

    // The default limit, through the recorder: the tick past it is refused, the replay
    // up to it encodes and decodes.
    let max = DecodeLimits::default().max_ticks;
    let mut rec = Recorder::new(0, Settings::default(), 1, max).unwrap();
    let row = [Input::default()];
    for t in 1..=max {
        rec.record(&row, t, 0).unwrap();
    }
    let e = rec.record(&row, max + 1, 0).unwrap_err().to_string();
    assert!(e.contains("ticks"), "{e}");
    let full = rec.finish(max, 0);
    let bytes = full.encode().unwrap();
    assert_eq!(Replay::decode(&bytes).unwrap().ticks(), max);
    let mut over = full;
    over.inputs.push(Input::default());
    assert!(matches!(
        over.encode(),
        Err(craterfield::net::EncodeError::TooLarge { what: "ticks", .. })
    ));
}

#[test]
fn replay_compactness_of_a_four_player_match() {
    let minutes = 5;
    let replay = scripted_replay(4, minutes * 60 * 60, 42);
    let bytes = replay.encode().unwrap();
    let per_minute = bytes.len() as f64 / f64::from(minutes);
    let changes = replay
        .rows()
        .zip(replay.rows().skip(1))
        .filter(|(a, b)| a != b)
        .count();
    eprintln!(
        "replay: 4 players, {} ticks at 60 Hz, {changes} row changes ({:.1}/s), hash every 60 ticks: \
         {} bytes = {per_minute:.0} bytes/minute ({:.2} bytes/tick)",
        replay.ticks(),
        changes as f64 / f64::from(minutes * 60),
        bytes.len(),
        bytes.len() as f64 / f64::from(replay.ticks()),
    );
    assert!(per_minute < 8_000.0, "{per_minute} bytes/minute");
}

// ---------------------------------------------------------------------------------------
// Verification against the simulation
// ---------------------------------------------------------------------------------------

fn played_match(level: &Level, ticks: u32) -> (Replay, World) {
    let settings = Settings::default();
    let mut world = World::new(level, settings, 2).unwrap();
    let mut rec = Recorder::new(level_hash(level), settings, 2, 30).unwrap();
    for row in scripted_rows(2, ticks, 11) {
        world.step(&row).unwrap();
        rec.record(&row, world.tick(), world.state_hash()).unwrap();
    }
    (rec.finish(world.tick(), world.state_hash()), world)
}

/// A match whose terrain is also edited from outside the simulation (a sandbox's brush):
/// carves and fills applied between steps and recorded as the replay's edits.
fn edited_match(level: &Level, ticks: u32) -> (Replay, World) {
    let settings = Settings::default();
    let mut world = World::new(level, settings, 2).unwrap();
    let mut rec = Recorder::new(level_hash(level), settings, 2, 30).unwrap();
    let ground = level.bounds().min + (level.bounds().max - level.bounds().min) * 0.5;
    for (t, row) in scripted_rows(2, ticks, 5).iter().enumerate() {
        let t = t as u32;
        if t % 40 == 7 {
            let at = ground + glam::Vec2::new(t as f32 * 3.0, 0.0);
            let carve = Event::carve(at, 25.0).unwrap().at_tick(t);
            let fill = Event::fill(at, 10.0, 0).unwrap().at_tick(t);
            for e in [carve, fill] {
                world.apply_event(e).unwrap();
                rec.record_edit(e).unwrap();
            }
        }
        world.step(row).unwrap();
        rec.record(row, world.tick(), world.state_hash()).unwrap();
    }
    (rec.finish(world.tick(), world.state_hash()), world)
}

#[test]
fn edits_round_trip_in_version_2_and_verify() {
    let level = Level::default_level();
    let (replay, world) = edited_match(&level, 200);
    assert_eq!(replay.edits.len(), 10);
    assert_eq!(replay.edits_at(47).len(), 2);
    assert!(replay.edits_at(48).is_empty());
    let bytes = replay.encode().unwrap();
    assert_eq!(u16::from_le_bytes([bytes[8], bytes[9]]), replay::VERSION);
    let back = Replay::decode(&bytes).unwrap();
    assert_eq!(back, replay);
    let report = replay::verify(&back, &level).unwrap();
    assert_eq!(report.final_hash, world.state_hash());

    // The edits are part of what the hashes prove: without one, the match diverges.
    let mut lost = back.clone();
    lost.edits.remove(4);
    assert!(matches!(
        replay::verify(&lost, &level),
        Err(VerifyError::Diverged { .. })
    ));

    // Advancing tick by tick is what verify does.
    let mut again = World::new(&level, back.settings, 2).unwrap();
    for _ in 0..back.ticks() {
        back.advance(&mut again).unwrap();
    }
    assert_eq!(again.state_hash(), world.state_hash());
    assert!(back.advance(&mut again).is_err(), "past the last row");
    assert_eq!(again.state_hash(), world.state_hash());

    // A replay without edits is still written as version 1.
    let plain = scripted_replay(2, 50, 3).encode().unwrap();
    assert_eq!(
        u16::from_le_bytes([plain[8], plain[9]]),
        replay::VERSION_WITHOUT_EDITS
    );
}

#[test]
fn bad_edits_are_refused_on_every_side() {
    let level = Level::default_level();
    let (replay, _) = edited_match(&level, 100);
    let carve = Event::carve(glam::Vec2::new(10.0, 10.0), 5.0).unwrap();

    let mut rec = Recorder::new(1, Settings::default(), 1, 10).unwrap();
    assert!(
        rec.record_edit(carve.at_tick(3)).is_err(),
        "not the current tick"
    );
    rec.record_edit(carve.at_tick(0)).unwrap();

    for (what, edit) in [
        ("past the end", carve.at_tick(100)),
        ("decreasing", carve.at_tick(0)),
    ] {
        let mut bad = replay.clone();
        bad.edits.push(edit);
        assert!(bad.validate().is_err(), "{what}");
        assert!(bad.encode().is_err(), "{what}");
        assert!(
            matches!(
                replay::verify(&bad, &level),
                Err(VerifyError::Inconsistent { .. })
            ),
            "{what}"
        );
    }

    let bytes = replay.encode().unwrap();
    let limits = DecodeLimits {
        max_events: 3,
        ..DecodeLimits::default()
    };
    assert_event_count_too_large(&kind_of(Replay::decode_with_limits(&bytes, &limits)));
    assert!(replay.encode_with_limits(&limits).is_err());
    // Cut anywhere in the edits section: an error, never a panic.
    for n in (bytes.len() - 40)..bytes.len() {
        assert!(Replay::decode(&bytes[..n]).is_err());
    }
}

#[test]
fn verify_resimulates_and_catches_divergence_and_wrong_levels() {
    let level = Level::default_level();
    let (replay, world) = played_match(&level, 240);
    let decoded = Replay::decode(&replay.encode().unwrap()).unwrap();
    let report = replay::verify(&decoded, &level).unwrap();
    assert_eq!((report.ticks, report.hashes_checked), (240, 8));
    assert_eq!(report.final_hash, world.state_hash());

    let mut tampered = decoded.clone();
    tampered.hashes[3].1 ^= 1;
    match replay::verify(&tampered, &level) {
        Err(VerifyError::Diverged { tick, .. }) => assert_eq!(tick, 120),
        other => panic!("expected a divergence at tick 120, got {other:?}"),
    }

    // A hash past the last tick could never be compared: the replay is refused whole.
    let mut unreachable = decoded.clone();
    unreachable.hashes.push((1_000, 0));
    assert!(matches!(
        replay::verify(&unreachable, &level),
        Err(VerifyError::Inconsistent { .. })
    ));

    let other = Level::from_ron(include_str!("../levels/caverns.ron")).unwrap();
    let e = replay::verify(&decoded, &other).unwrap_err();
    assert!(matches!(e, VerifyError::LevelMismatch { .. }), "{e}");
    assert!(decoded.check_level(level_hash(&other)).is_err());
    decoded.check_level(level_hash(&level)).unwrap();
}

#[test]
fn snapshot_of_a_simulated_terrain_round_trips() {
    let level = Level::default_level();
    let (_, world) = played_match(&level, 600);
    let snap = TerrainSnapshot::of_terrain(level_hash(&level), world.terrain()).unwrap();
    let bytes = snap.encode().unwrap();
    assert_eq!(TerrainSnapshot::decode(&bytes).unwrap(), snap);
    eprintln!(
        "simulated snapshot: {} events, {} bytes ({:.2} bytes/event)",
        snap.events.len(),
        bytes.len(),
        wire::bytes_per_event(&bytes, snap.events.len())
    );
}

// ---------------------------------------------------------------------------------------
// Wire messages
// ---------------------------------------------------------------------------------------

/// Events like the simulation makes: centres on the 64 grid of a 3840 x 1600 world, ticks
/// 0 to 30 apart, a carving and a filling preset.
fn sim_like_events(n: usize, seed: u64) -> Vec<Event> {
    let mut rng = Rng(seed);
    let mut tick = 0;
    (0..n)
        .map(|_| {
            tick += rng.below(31) as u32;
            let fill = rng.below(4) == 0;
            Event {
                kind: if fill {
                    EventKind::Fill
                } else {
                    EventKind::Carve
                },
                center: [
                    rng.below(983_040 / 64 + 1) as i32 * 64,
                    rng.below(409_600 / 64 + 1) as i32 * 64,
                ],
                radius: if fill { 30 * 256 } else { 40 * 256 },
                rim: 0,
                grow_ticks: 0,
                tick,
                material: 0,
            }
        })
        .collect()
}

/// One message bounds the work it can cause: a batch past `max_batch_events` is refused
/// when read (before any event is decoded) and when written, and a reader that raises the
/// limit reads it.
#[test]
fn event_batches_are_bounded_on_both_sides() {
    let limits = DecodeLimits::default();
    let max = limits.max_batch_events as usize;
    let fits = sim_like_events(max, 9);
    let bytes = wire::encode_events(&fits).unwrap();
    assert_eq!(wire::decode_events(&bytes).unwrap(), fits);
    let over = sim_like_events(max + 1, 9);
    let e = wire::encode_events(&over).unwrap_err().to_string();
    assert!(
        e.contains("events in a batch") && e.contains(&max.to_string()),
        "{e}"
    );
    let raised = DecodeLimits {
        max_batch_events: max as u32 + 1,
        ..limits
    };
    let bytes = wire::encode_events_with_limits(&over, &raised).unwrap();
    let e = kind_of(wire::decode_events(&bytes));
    assert_event_count_too_large(&e);
    assert_eq!(
        wire::decode_events_with_limits(&bytes, &raised).unwrap(),
        over
    );
}

/// A terrain snapshot bounds the replay work of a joiner the same way.
#[test]
fn terrain_snapshots_are_bounded_on_both_sides() {
    let limits = DecodeLimits::default();
    let max = limits.max_events as usize;
    let snap = |n| TerrainSnapshot {
        level_hash: 1,
        tick: 9,
        events: sim_like_events(n, 4),
    };
    let fits = snap(max);
    assert_eq!(
        TerrainSnapshot::decode(&fits.encode().unwrap()).unwrap(),
        fits
    );
    let over = snap(max + 1);
    let e = over.encode().unwrap_err().to_string();
    assert!(
        e.contains("events in a snapshot") && e.contains(&max.to_string()),
        "{e}"
    );
    let raised = DecodeLimits {
        max_events: max as u32 + 1,
        ..limits
    };
    let bytes = over.encode_with_limits(&raised).unwrap();
    let e = kind_of(TerrainSnapshot::decode(&bytes));
    assert_event_count_too_large(&e);
    assert_eq!(
        TerrainSnapshot::decode_with_limits(&bytes, &raised).unwrap(),
        over
    );
}

#[test]
fn sim_events_cost_at_most_eight_bytes_each() {
    let events = sim_like_events(1_000, 3);
    let bytes = wire::encode_events(&events).unwrap();
    let per_event = wire::bytes_per_event(&bytes, events.len());
    eprintln!(
        "event batch: 1000 sim-like events in {} bytes = {per_event:.3} bytes/event",
        bytes.len()
    );
    assert!(per_event <= 8.0, "{per_event} bytes/event");
    let back = wire::decode_events(&bytes).unwrap();
    assert_eq!(back, events);
    assert!(back.iter().all(|e| e.validate().is_ok()));
    assert_eq!(wire::message_kind(&bytes).unwrap(), MessageKind::Events);
}

#[test]
fn event_messages_round_trip_odd_events() {
    let odd = vec![
        Event {
            kind: EventKind::Fill,
            center: [-3, 7],
            radius: 1,
            rim: 5,
            grow_ticks: 65_535,
            tick: 0,
            material: 65_535,
        },
        Event {
            kind: EventKind::Carve,
            center: [FIXED_MAX, -FIXED_MAX],
            radius: FIXED_MAX,
            rim: FIXED_MAX,
            grow_ticks: 1,
            tick: 0,
            material: 0,
        },
        Event {
            kind: EventKind::Carve,
            center: [0, 0],
            radius: 256,
            rim: 0,
            grow_ticks: 0,
            tick: u32::MAX,
            material: 3,
        },
    ];
    for events in [vec![], odd] {
        let bytes = wire::encode_events(&events).unwrap();
        assert_eq!(wire::decode_events(&bytes).unwrap(), events);
    }
}

#[test]
fn snapshot_round_trips_and_messages_are_not_confused() {
    let snap = TerrainSnapshot {
        level_hash: 0xfeed,
        tick: 12_345,
        events: sim_like_events(500, 8),
    };
    let bytes = snap.encode().unwrap();
    assert_eq!(TerrainSnapshot::decode(&bytes).unwrap(), snap);
    assert_eq!(
        wire::message_len(&bytes[..wire::HEADER_LEN], &DecodeLimits::default()).unwrap(),
        bytes.len()
    );
    let e = kind_of(wire::decode_events(&bytes));
    assert_eq!(
        e.kind,
        DecodeErrorKind::UnexpectedKind {
            found: 2,
            expected: 1
        }
    );
    let batch = wire::encode_events(&snap.events).unwrap();
    let e = kind_of(TerrainSnapshot::decode(&batch));
    assert_eq!(
        e.kind,
        DecodeErrorKind::UnexpectedKind {
            found: 1,
            expected: 2
        }
    );
}

#[test]
fn message_corruption_classes() {
    let bytes = wire::encode_events(&sim_like_events(50, 1)).unwrap();
    for cut in 0..bytes.len() {
        let e = kind_of(wire::decode_events(&bytes[..cut]));
        assert!(
            matches!(e.kind, DecodeErrorKind::Truncated { .. }),
            "cut at {cut}: {e}"
        );
    }
    let mut bad = bytes.clone();
    bad[20] ^= 4;
    let e = kind_of(wire::decode_events(&bad));
    assert!(
        matches!(e.kind, DecodeErrorKind::ChecksumMismatch { .. }),
        "{e}"
    );
    let mut bad = bytes.clone();
    bad[1] = 9;
    let e = kind_of(wire::decode_events(&bad));
    assert_eq!(
        e.kind,
        DecodeErrorKind::UnsupportedVersion {
            found: 9,
            supported: 1
        }
    );

    // A valid checksum over a count of 2^31, and over 2^19 events in a few bytes.
    let framed = |body: &[u8]| {
        let mut m = vec![1, 1];
        m.extend_from_slice(&(body.len() as u32).to_le_bytes());
        m.extend_from_slice(body);
        m.extend_from_slice(&[0; 4]);
        fix_crc(&mut m);
        m
    };
    let e = kind_of(wire::decode_events(&framed(&[
        0x80, 0x80, 0x80, 0x80, 0x08,
    ])));
    assert_event_count_too_large(&e);
    // 4,096 events (the limit) in a few bytes: more than the bytes left can hold.
    let e = kind_of(wire::decode_events(&framed(&[
        0x80, 0x20, 6, 0, 0, 1, 0, 2, 0, 0, 0,
    ])));
    assert!(matches!(e.kind, DecodeErrorKind::Truncated { .. }), "{e}");
    // A bad event: radius 0 in the shape dictionary, and a centre beyond the fixed range.
    let e = kind_of(wire::decode_events(&framed(&[
        1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    ])));
    assert!(
        matches!(e.kind, DecodeErrorKind::InvalidValue { .. }) && e.section == "shape 0",
        "{e}"
    );
    let e = kind_of(wire::decode_events(&framed(&[
        1, 24, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 2, 0,
    ])));
    assert!(
        matches!(e.kind, DecodeErrorKind::InvalidValue { .. }) && e.section == "event 0",
        "{e}"
    );
    assert!(e.to_string().contains("center.x"), "{e}");
}

// ---------------------------------------------------------------------------------------
// Fuzzing: no decoder panics, whatever the bytes
// ---------------------------------------------------------------------------------------

fn valid_input() -> impl Strategy<Value = Input> {
    (any::<u16>(), 0u8..8, -127i8..=127, any::<u8>(), 0u8..2).prop_map(
        |(aim, buttons, drive, power, weapon)| Input {
            aim,
            buttons,
            drive,
            power,
            weapon,
        },
    )
}

/// A mutation of a valid encoding: flips, overwrites, cuts or inserts, then (half the
/// time) a recomputed checksum so the section parsers see the damage.
#[derive(Clone, Debug)]
enum Mutation {
    Xor(usize, u8),
    Set(usize, u8),
    Cut(usize),
    Insert(usize, u8),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1..=255u8).prop_map(|(i, b)| Mutation::Xor(i, b)),
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Set(i, b)),
        any::<usize>().prop_map(Mutation::Cut),
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Insert(i, b)),
    ]
}

fn mutate(bytes: &[u8], mutations: &[Mutation], fix: bool) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for m in mutations {
        let n = b.len().max(1);
        match *m {
            Mutation::Xor(i, x) if !b.is_empty() => b[i % n] ^= x,
            Mutation::Set(i, x) if !b.is_empty() => b[i % n] = x,
            Mutation::Cut(i) => b.truncate(i % n),
            Mutation::Insert(i, x) => b.insert(i % (b.len() + 1), x),
            _ => {}
        }
    }
    if fix {
        fix_crc(&mut b);
    }
    b
}

/// What every successful decode must satisfy.
fn check_replay(bytes: &[u8]) {
    if let Ok(r) = Replay::decode(bytes) {
        r.settings.validate().unwrap();
        assert!(r.inputs.iter().all(|i| i.validate().is_ok()));
        assert_eq!(Replay::decode(&r.encode().unwrap()).unwrap(), r);
    }
}

fn check_events(bytes: &[u8]) {
    if let Ok(events) = wire::decode_events(bytes) {
        assert!(events.iter().all(|e| e.validate().is_ok()));
        assert!(events.windows(2).all(|w| w[0].tick <= w[1].tick));
        assert_eq!(
            wire::decode_events(&wire::encode_events(&events).unwrap()).unwrap(),
            events
        );
    }
    if let Ok(s) = TerrainSnapshot::decode(bytes) {
        assert!(s.events.iter().all(|e| e.validate().is_ok()));
        assert_eq!(TerrainSnapshot::decode(&s.encode().unwrap()).unwrap(), s);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..256), fix in any::<bool>()) {
        let mut bytes = bytes;
        if fix {
            fix_crc(&mut bytes);
        }
        check_replay(&bytes);
        check_events(&bytes);
        let _ = wire::message_len(&bytes, &DecodeLimits::default());
        let _ = wire::message_kind(&bytes);
    }

    #[test]
    fn random_bytes_behind_a_valid_prefix_never_panic(
        tail in proptest::collection::vec(any::<u8>(), 0..256),
        kind in 1u8..=2,
    ) {
        let mut replay = b"CRTRPLY\0\x01\x00".to_vec();
        replay.extend_from_slice(&tail);
        fix_crc(&mut replay);
        check_replay(&replay);
        let mut message = vec![kind, 1];
        message.extend_from_slice(&(tail.len().saturating_sub(4) as u32).to_le_bytes());
        message.extend_from_slice(&tail);
        fix_crc(&mut message);
        check_events(&message);
    }

    #[test]
    fn mutated_replays_never_panic(
        seed in any::<u64>(),
        mutations in proptest::collection::vec(mutation(), 1..4),
        fix in any::<bool>(),
    ) {
        let bytes = scripted_replay(1 + (seed % 4) as u8, 120, seed).encode().unwrap();
        check_replay(&mutate(&bytes, &mutations, fix));
    }

    #[test]
    fn mutated_messages_never_panic(
        seed in any::<u64>(),
        mutations in proptest::collection::vec(mutation(), 1..4),
        fix in any::<bool>(),
    ) {
        let events = sim_like_events(1 + (seed % 40) as usize, seed);
        let batch = wire::encode_events(&events).unwrap();
        check_events(&mutate(&batch, &mutations, fix));
        let snap = TerrainSnapshot { level_hash: seed, tick: 77, events }.encode().unwrap();
        check_events(&mutate(&snap, &mutations, fix));
    }

    #[test]
    fn replays_of_random_valid_inputs_round_trip(
        players in 1u8..=8,
        rows in proptest::collection::vec(proptest::collection::vec(valid_input(), 8), 0..200),
        interval in 1u32..50,
        hold in 1usize..5,
    ) {
        let mut rec = Recorder::new(5, Settings::default(), players, interval).unwrap();
        // Each random row held for `hold` ticks, so runs of several ticks occur.
        for (t, row) in rows.iter().flat_map(|r| std::iter::repeat_n(r, hold)).enumerate() {
            rec.record(&row[..usize::from(players)], t as u32 + 1, t as u64).unwrap();
        }
        let ticks = rec.ticks();
        let replay = rec.finish(ticks, 0);
        let back = Replay::decode(&replay.encode().unwrap()).unwrap();
        prop_assert_eq!(back, replay);
    }
}

/// Every setting is part of what peers and replays compare: a replay whose settings were
/// edited (and re-encoded, so its checksum is right) diverges at its first stored hash,
/// even where the edit changes nothing that the short match exercises.
#[test]
fn a_replay_with_any_setting_changed_does_not_verify() {
    let level = Level::default_level();
    let (replay, _) = played_match(&level, 60);
    replay::verify(&replay, &level).unwrap();
    type Edit = fn(&mut Settings);
    let edits: Vec<(&str, Edit)> = vec![
        ("tick_hz", |s| s.tick_hz += 1),
        ("gravity", |s| s.gravity += 1),
        ("wind.y", |s| s.wind[1] += 1),
        ("stick_range", |s| s.stick_range += 1),
        ("max_speed", |s| s.max_speed += 1),
        ("vehicle.health", |s| s.vehicle.health += 1),
        ("vehicle.jump_speed", |s| s.vehicle.jump_speed += 1),
        ("shell.material", |s| s.shell.material += 1),
        ("shell.cooldown_ticks", |s| s.shell.cooldown_ticks += 1),
        ("dirt.blast_radius", |s| s.dirt.blast_radius += 1),
        ("dirt.fills", |s| s.dirt.fills = !s.dirt.fills),
        ("max_bodies", |s| s.max_bodies -= 1),
        ("rollback_ticks", |s| s.rollback_ticks += 1),
    ];
    for (name, edit) in edits {
        let mut edited = replay.clone();
        edit(&mut edited.settings);
        let bytes = edited.encode().unwrap();
        let decoded = Replay::decode(&bytes).unwrap();
        match replay::verify(&decoded, &level) {
            Err(VerifyError::Diverged { tick: 30, .. }) => {}
            other => panic!("{name}: expected a divergence at the first hash, got {other:?}"),
        }
    }
}
