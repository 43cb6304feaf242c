//! The terrain's event log: a vector of events that reserves its room up front, and keeps
//! that room in its clones, so that appending an event never copies the log mid-match.

use std::ops::{Deref, DerefMut};

use crate::event::Event;

/// Events the log reserves room for up front (at most the terrain's `max_events`):
/// growing a vector copies it, which took 2 ms at half a million events. The room is
/// address space until events fill it (28 bytes an event).
const EVENT_RESERVE: usize = 1 << 20;

/// The events a terrain applied, in order (cell lists index into it).
#[derive(Debug, Default)]
pub(super) struct EventLog(Vec<Event>);

impl EventLog {
    /// An empty log with room for `max_events` (up to [`EVENT_RESERVE`]).
    pub(super) fn with_room(max_events: usize) -> EventLog {
        EventLog(Vec::with_capacity(max_events.min(EVENT_RESERVE)))
    }
}

impl Clone for EventLog {
    fn clone(&self) -> Self {
        let mut events = Vec::with_capacity(self.0.capacity());
        events.extend_from_slice(&self.0);
        EventLog(events)
    }
}

impl Deref for EventLog {
    type Target = Vec<Event>;
    fn deref(&self) -> &Vec<Event> {
        &self.0
    }
}

impl DerefMut for EventLog {
    fn deref_mut(&mut self) -> &mut Vec<Event> {
        &mut self.0
    }
}
