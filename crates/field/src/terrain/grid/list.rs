//! A cell's event list: the indices into the terrain's log of the events that can reach
//! the cell, in order, with a copy of each event beside its index.
//!
//! Queries, bakes and the pruning of a new event read every listed event; through the
//! indices alone each read lands somewhere in a log of thousands of events, where the
//! profile of an insert's pruning and of a near-surface query put much of their time. The
//! copies make the reads one sequential pass. Events never change once logged (compaction only
//! renumbers them), so a copy stays equal to the log's event for as long as it is listed.

use std::ops::Deref;
use std::sync::OnceLock;

use glam::Vec2;

use crate::event::{Event, EventKind};

/// A listed event with its centre, radius and rim already in world units: a query reads
/// them for every listed event, and converting the fixed-point fields each time was a
/// tenth of a near-surface distance query. The conversions are exact, so the cached
/// values are the bits [`Event::center_f32`] and the others return.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Listed {
    event: Event,
    center: Vec2,
    radius: f32,
    rim: f32,
}

impl Listed {
    fn new(event: Event) -> Listed {
        Listed {
            event,
            center: event.center_f32(),
            radius: event.radius_f32(),
            rim: event.rim_f32(),
        }
    }

    /// The event as logged.
    pub(crate) fn event(&self) -> &Event {
        &self.event
    }

    /// [`Event::center_f32`].
    pub(crate) fn center_f32(&self) -> Vec2 {
        self.center
    }

    /// [`Event::rim_f32`].
    pub(crate) fn rim_f32(&self) -> f32 {
        self.rim
    }

    /// [`Event::radius_at`].
    pub(crate) fn radius_at(&self, tick: u32) -> Option<f32> {
        self.event.radius_at_with(self.radius, tick)
    }

    /// The full radius, [`Event::radius_f32`]: [`Listed::radius_at`] from the tick the
    /// event is settled (a radius is positive, so it is never `None` then).
    pub(crate) fn radius_f32(&self) -> f32 {
        self.radius
    }

    /// Whether applying the event is one `max` with the negated disc distance (a carve
    /// without a rim); a fill or a rim is anything else.
    fn is_sharp_carve(&self) -> bool {
        self.event.kind == EventKind::Carve && self.event.is_sharp()
    }
}

impl Deref for Listed {
    type Target = Event;

    fn deref(&self) -> &Event {
        &self.event
    }
}

/// The indices (ascending) and copies of a cell's events; derefs to the indices.
#[derive(Clone, Debug, Default)]
pub(crate) struct EventList {
    indices: Vec<u32>,
    events: Vec<Listed>,
    /// How many of `events` are not sharp carves (kept exact through every edit).
    others: usize,
    /// The events' discs for SIMD lanes, laid out when a query first asks for them.
    discs: DiscCache,
}

/// [`DiscChunks`] of a list, made on the first query that asks and dropped by every edit:
/// a function of the listed events alone, so wherever and whenever it is made it holds
/// the same bits, and inserts (which edit lists many times a tick) pay nothing for it. A
/// clone starts empty: the clones are the undo journal's pre-images, which are read
/// again only after a rollback.
#[derive(Debug, Default)]
struct DiscCache(OnceLock<DiscChunks>);

impl Clone for DiscCache {
    fn clone(&self) -> Self {
        DiscCache::default()
    }
}

/// Events per chunk of [`DiscChunks`]: the widest register's lanes (AVX-512), a multiple
/// of every narrower one's.
pub(crate) const DISC_LANES: usize = 16;

/// The listed events' centres and full radii laid out for SIMD lanes: chunks of
/// [`DISC_LANES`] events, each chunk their `x`, then their `y`, then their radii, so that a
/// register loads one coordinate of consecutive events. The last chunk is padded with a
/// disc at `x = +inf` of radius 0, whose negated distance from any finite point is
/// `-inf`, which no running maximum takes unless every operand is `-inf` (the same bits).
#[derive(Clone, Debug, Default)]
pub(crate) struct DiscChunks(Vec<f32>);

impl DiscChunks {
    const CHUNK: usize = 3 * DISC_LANES;

    fn of(events: &[Listed]) -> DiscChunks {
        let mut chunks = Vec::with_capacity(events.len().div_ceil(DISC_LANES) * Self::CHUNK);
        for group in events.chunks(DISC_LANES) {
            let lanes = |of: fn(&Listed) -> f32, pad: f32| {
                (0..DISC_LANES).map(move |k| group.get(k).map_or(pad, of))
            };
            chunks.extend(lanes(|e| e.center_f32().x, f32::INFINITY));
            chunks.extend(lanes(|e| e.center_f32().y, 0.0));
            chunks.extend(lanes(Listed::radius_f32, 0.0));
        }
        DiscChunks(chunks)
    }

    /// The chunks, `3 * DISC_LANES` floats each.
    pub(crate) fn chunks(&self) -> &[f32] {
        &self.0
    }
}

impl Deref for EventList {
    type Target = [u32];

    fn deref(&self) -> &[u32] {
        &self.indices
    }
}

impl EventList {
    /// The list of `indices` into `log`; `None` when one is not in it.
    pub(crate) fn from_log(indices: &[u32], log: &[Event]) -> Option<EventList> {
        let events = indices
            .iter()
            .map(|&i| log.get(i as usize).copied().map(Listed::new))
            .collect::<Option<Vec<Listed>>>()?;
        Some(EventList {
            indices: indices.to_vec(),
            others: others(&events),
            discs: DiscCache::default(),
            events,
        })
    }

    /// Whether every listed event is a sharp carve: then applying the list is one running
    /// maximum (see `terrain::field::sharp_carves`).
    pub(crate) fn sharp_carves_only(&self) -> bool {
        self.others == 0
    }

    /// The listed events, in list order (`listed()[k]` is the log's event `self[k]`).
    pub(crate) fn listed(&self) -> &[Listed] {
        &self.events
    }

    /// Appends event `index` of the log, which is `event`.
    pub(crate) fn push(&mut self, index: u32, event: Event) {
        let listed = Listed::new(event);
        self.others += usize::from(!listed.is_sharp_carve());
        self.indices.push(index);
        self.events.push(listed);
        self.discs = DiscCache::default();
    }

    /// The listed events' discs, for lanes.
    pub(crate) fn discs(&self) -> &DiscChunks {
        self.discs.0.get_or_init(|| DiscChunks::of(&self.events))
    }

    pub(crate) fn clear(&mut self) {
        self.indices.clear();
        self.events.clear();
        self.others = 0;
        self.discs = DiscCache::default();
    }

    /// Drops the last event.
    pub(crate) fn pop(&mut self) {
        self.indices.pop();
        if let Some(e) = self.events.pop() {
            self.others -= usize::from(!e.is_sharp_carve());
            self.discs = DiscCache::default();
        }
    }

    /// Drops the event at position `pos` (none past the end).
    pub(crate) fn remove(&mut self, pos: usize) {
        if pos < self.indices.len() {
            self.indices.remove(pos);
            let e = self.events.remove(pos);
            self.others -= usize::from(!e.is_sharp_carve());
            self.discs = DiscCache::default();
        }
    }

    /// Drops the first `n` events (all of them when there are fewer).
    pub(crate) fn drop_prefix(&mut self, n: usize) {
        let n = n.min(self.indices.len());
        self.indices.drain(..n);
        self.events.drain(..n);
        self.others = others(&self.events);
        self.discs = DiscCache::default();
    }

    /// Rewrites the indices through `renumber` (compaction dropped events before them;
    /// the events themselves stay).
    pub(crate) fn renumber(&mut self, renumber: &[u32]) {
        for i in &mut self.indices {
            *i = renumber.get(*i as usize).copied().unwrap_or(u32::MAX);
        }
    }
}

/// How many of `events` are not sharp carves.
fn others(events: &[Listed]) -> usize {
    events.iter().filter(|e| !e.is_sharp_carve()).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    fn carve(x: f32) -> Event {
        Event::carve(Vec2::new(x, 0.0), 1.0).expect("a valid event")
    }

    #[test]
    fn copies_follow_their_indices_through_every_edit() {
        let log: Vec<Event> = (0..6).map(|k| carve(k as f32)).collect();
        let mut list = EventList::from_log(&[0, 2, 3, 4, 5], &log).unwrap();
        list.remove(1);
        list.drop_prefix(1);
        list.pop();
        list.push(1, log[1]);
        assert_eq!(&list[..], &[3, 4, 1]);
        let expected: Vec<Event> = list.iter().map(|&i| log[i as usize]).collect();
        let copies: Vec<Event> = list.listed().iter().map(|l| *l.event()).collect();
        assert_eq!(copies, expected);
        list.renumber(&[0, 0, 0, 1, 2, 3]);
        assert_eq!(&list[..], &[1, 2, 0]);
        let copies: Vec<Event> = list.listed().iter().map(|l| *l.event()).collect();
        assert_eq!(copies, expected);
        list.clear();
        assert!(list.is_empty() && list.listed().is_empty());
        assert!(EventList::from_log(&[6], &log).is_none());
    }

    /// The count of events that are not sharp carves follows every edit: a fill and a
    /// rimmed carve, listed, popped, removed and dropped with a prefix.
    #[test]
    fn sharp_carves_only_follows_every_edit() {
        let fill = Event::fill(Vec2::ZERO, 1.0, 1).expect("a valid event");
        let rimmed = carve(2.0).with_rim(0.5).expect("a valid event");
        let log = [carve(0.0), fill, rimmed, carve(3.0), carve(4.0)];
        let sharp = |l: &EventList| l.sharp_carves_only();
        let mut list = EventList::from_log(&[0, 1, 3], &log).unwrap();
        assert!(!sharp(&list));
        list.remove(1);
        assert!(sharp(&list));
        list.push(2, rimmed);
        assert!(!sharp(&list));
        list.pop();
        assert!(sharp(&list));
        list.push(1, fill);
        list.push(4, log[4]);
        assert!(!sharp(&list));
        list.drop_prefix(2);
        assert!(!sharp(&list), "the fill is still listed");
        list.drop_prefix(1);
        assert!(sharp(&list));
        list.push(2, rimmed);
        list.clear();
        assert!(sharp(&list));
        assert!(sharp(&EventList::from_log(&[0, 3, 4], &log).unwrap()));
        assert!(!sharp(&EventList::from_log(&[2], &log).unwrap()));
    }

    /// The lanes' discs follow the list through pushes across chunk boundaries, pops,
    /// removals and dropped prefixes: each event's centre and radius at its lane, the
    /// rest of the last chunk padding.
    #[test]
    fn discs_follow_every_edit() {
        let log: Vec<Event> = (0..40)
            .map(|k| Event::carve(Vec2::new(k as f32, -(k as f32)), 1.0 + k as f32).unwrap())
            .collect();
        let mut list = EventList::default();
        let check = |list: &EventList| {
            let chunks = list.discs().chunks();
            assert_eq!(
                chunks.len(),
                list.len().div_ceil(DISC_LANES) * 3 * DISC_LANES
            );
            for (slot, chunk) in chunks.chunks(3 * DISC_LANES).enumerate() {
                for lane in 0..DISC_LANES {
                    let (x, y, r) = (
                        chunk[lane],
                        chunk[DISC_LANES + lane],
                        chunk[2 * DISC_LANES + lane],
                    );
                    match list.listed().get(slot * DISC_LANES + lane) {
                        Some(e) => assert_eq!(
                            (x, y, r),
                            (e.center_f32().x, e.center_f32().y, e.radius_f32())
                        ),
                        None => assert_eq!((x, y, r), (f32::INFINITY, 0.0, 0.0)),
                    }
                }
            }
        };
        for (k, e) in log.iter().enumerate() {
            list.push(k as u32, *e);
            check(&list);
        }
        list.pop();
        check(&list);
        list.remove(16);
        check(&list);
        list.drop_prefix(7);
        check(&list);
        list.push(39, log[39]);
        check(&list);
        list.clear();
        check(&list);
    }

    #[test]
    fn cached_units_are_the_conversions_bits() {
        let e = Event::carve(Vec2::new(1234.567, -89.0123), 40.004)
            .and_then(|e| e.with_rim(3.3))
            .expect("a valid event")
            .with_growth(7)
            .at_tick(5);
        let l = Listed::new(e);
        assert_eq!(l.center_f32(), e.center_f32());
        assert_eq!(l.rim_f32().to_bits(), e.rim_f32().to_bits());
        for tick in 0..20 {
            assert_eq!(
                l.radius_at(tick).map(f32::to_bits),
                e.radius_at(tick).map(f32::to_bits)
            );
        }
    }
}
