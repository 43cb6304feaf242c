//! A cell's event list: the indices into the terrain's log of the events that can reach
//! the cell, in order, with a copy of each event beside its index.
//!
//! Queries, bakes and the pruning of a new event read every listed event; through the
//! indices alone each read lands somewhere in a log of thousands of events, and the
//! profile of an insert showed most of its pruning waiting on those loads. The copies make
//! the reads one sequential pass. Events never change once logged (compaction only
//! renumbers them), so a copy stays equal to the log's event for as long as it is listed.

use std::ops::Deref;

use crate::event::Event;

/// The indices (ascending) and copies of a cell's events; derefs to the indices.
#[derive(Clone, Debug, Default)]
pub(crate) struct EventList {
    indices: Vec<u32>,
    events: Vec<Event>,
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
            .map(|&i| log.get(i as usize).copied())
            .collect::<Option<Vec<Event>>>()?;
        Some(EventList {
            indices: indices.to_vec(),
            events,
        })
    }

    /// The listed events, in list order (`events()[k]` is the log's event `self[k]`).
    pub(crate) fn events(&self) -> &[Event] {
        &self.events
    }

    /// Appends event `index` of the log, which is `event`.
    pub(crate) fn push(&mut self, index: u32, event: Event) {
        self.indices.push(index);
        self.events.push(event);
    }

    pub(crate) fn clear(&mut self) {
        self.indices.clear();
        self.events.clear();
    }

    /// Drops the last event.
    pub(crate) fn pop(&mut self) {
        self.indices.pop();
        self.events.pop();
    }

    /// Drops the event at position `pos` (none past the end).
    pub(crate) fn remove(&mut self, pos: usize) {
        if pos < self.indices.len() {
            self.indices.remove(pos);
            self.events.remove(pos);
        }
    }

    /// Drops the first `n` events (all of them when there are fewer).
    pub(crate) fn drop_prefix(&mut self, n: usize) {
        let n = n.min(self.indices.len());
        self.indices.drain(..n);
        self.events.drain(..n);
    }

    /// Rewrites the indices through `renumber` (compaction dropped events before them;
    /// the events themselves stay).
    pub(crate) fn renumber(&mut self, renumber: &[u32]) {
        for i in &mut self.indices {
            *i = renumber.get(*i as usize).copied().unwrap_or(u32::MAX);
        }
    }
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
        assert_eq!(list.events(), &expected[..]);
        list.renumber(&[0, 0, 0, 1, 2, 3]);
        assert_eq!(&list[..], &[1, 2, 0]);
        assert_eq!(list.events(), &expected[..]);
        list.clear();
        assert!(list.is_empty() && list.events().is_empty());
        assert!(EventList::from_log(&[6], &log).is_none());
    }
}
