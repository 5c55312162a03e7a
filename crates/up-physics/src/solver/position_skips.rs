//! Which contact groups a position pass can skip, bit for bit.
//!
//! A position pass (`contact_constraint::stabilize`) moves a group's bodies
//! only where a contact is deeper than the slop, and a contact's separation
//! changes by no more than its two bodies moved. So each body counts how far
//! the passes have moved it this step (its travel, push by push), and each
//! group remembers, from when it last ran, its bodies' travel then and how
//! much its shallowest contact could still close before passing the slop. A
//! group whose bodies have travelled less than that since would find no
//! contact deep and move nothing: it is skipped. Most contacts of a pile are
//! speculative gaps or shallow, so after the first pass most groups are.
//!
//! The bound is kept with a margin far above rounding (`MARGIN`), so a group
//! is skipped only where running it would change nothing: the result is the
//! same as running every group. Groups run colour after colour, and the
//! groups of one colour share no moving body, so on any number of threads a
//! body's travel is written by one task and read by no other in that colour.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use super::lanes::LANES;
use crate::threading::spare::{release_spare, BUFFER_FLOOR};

/// How far short of the bound a group's bodies must stay to skip it, m:
/// separations are rounded to ≈ 1e-8 m in a room tens of metres wide.
const MARGIN: f32 = 1.0e-6;

/// A group's record of its last run.
#[derive(Debug)]
struct LastRun {
    /// The sum of its bodies' travel then, m (f32 bits).
    travel: AtomicU32,
    /// How much its shallowest movable contact could close before it is
    /// deeper than the slop, less `MARGIN`; −∞ if it moved something, or
    /// has not run (f32 bits).
    room_left: AtomicU32,
}

impl LastRun {
    fn none() -> LastRun {
        LastRun {
            travel: AtomicU32::new(0.0f32.to_bits()),
            room_left: AtomicU32::new(f32::NEG_INFINITY.to_bits()),
        }
    }
}

/// One step's position passes: each body's travel and each group's last run.
#[derive(Debug, Default)]
pub(crate) struct PositionSkips {
    /// Per state, m (f32 bits). Static states (the room, sleepers) never
    /// move, so stay at 0.
    travel: Vec<AtomicU32>,
    last_run: Vec<LastRun>,
}

/// Scratch, rebuilt by `begin` each step: a clone starts empty.
impl Clone for PositionSkips {
    fn clone(&self) -> Self {
        PositionSkips::default()
    }
}

impl PositionSkips {
    /// Forgets the last step: `states` bodies, `groups` groups, none run yet.
    pub fn begin(&mut self, states: usize, groups: usize) {
        self.travel.clear();
        self.travel
            .resize_with(states, || AtomicU32::new(0.0f32.to_bits()));
        self.last_run.clear();
        self.last_run.resize_with(groups, LastRun::none);
    }

    /// The summed travel of the states `bodies` (side A, side B), m.
    #[inline]
    pub fn travel_of(&self, bodies: [&[u32; LANES]; 2]) -> f32 {
        // Always the same order, so a sum never shrinks while travel grows.
        bodies
            .iter()
            .flat_map(|side| side.iter())
            .map(|&i| f32::from_bits(self.travel[i as usize].load(Relaxed)))
            .sum()
    }

    /// Whether group `group`, its bodies' travel now `travel`, would move
    /// nothing: they have not travelled far enough since it last ran to
    /// take a contact past the slop.
    #[inline]
    pub fn can_skip(&self, group: usize, travel: f32) -> bool {
        let last = &self.last_run[group];
        let since = travel - f32::from_bits(last.travel.load(Relaxed));
        since < f32::from_bits(last.room_left.load(Relaxed))
    }

    /// Records a run of group `group`: its bodies' travel before it, and the
    /// room its shallowest contact had left (`f32::NEG_INFINITY` if it moved
    /// something: then it runs again).
    #[inline]
    pub fn ran(&self, group: usize, travel: f32, room_left: f32) {
        let last = &self.last_run[group];
        last.travel.store(travel.to_bits(), Relaxed);
        last.room_left
            .store((room_left - MARGIN).to_bits(), Relaxed);
    }

    /// Adds `distance` to the travel of `state`, a moving one that the
    /// caller's task owns in this colour.
    #[inline]
    pub fn moved(&self, state: u32, distance: f32) {
        let travel = &self.travel[state as usize];
        let now = f32::from_bits(travel.load(Relaxed)) + distance;
        travel.store(now.to_bits(), Relaxed);
    }

    /// Gives back the capacity this step left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.travel, BUFFER_FLOOR);
        release_spare(&mut self.last_run, BUFFER_FLOOR);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_group_is_skipped_until_its_bodies_travel_its_room() {
        let mut skips = PositionSkips::default();
        skips.begin(10, 3);
        let bodies = [&[0, 1, 2, 9], &[3, 4, 5, 9]];
        // Never run: it must run.
        assert!(!skips.can_skip(1, skips.travel_of(bodies)));
        // It ran, its shallowest contact 0.2 mm from the slop.
        skips.ran(1, skips.travel_of(bodies), 0.0002);
        assert!(skips.can_skip(1, skips.travel_of(bodies)));
        // Others move two of its bodies by 0.15 mm in all: still skipped.
        skips.moved(4, 0.0001);
        skips.moved(0, 0.00005);
        assert!(skips.can_skip(1, skips.travel_of(bodies)));
        // 0.06 mm more: the contact could now be deep.
        skips.moved(2, 0.00006);
        assert!(!skips.can_skip(1, skips.travel_of(bodies)));
        // Bodies it does not hold move as they like.
        skips.ran(1, skips.travel_of(bodies), 0.0002);
        skips.moved(7, 1.0);
        assert!(skips.can_skip(1, skips.travel_of(bodies)));
        // A group that moved something runs again, though nobody moved since.
        skips.ran(2, skips.travel_of(bodies), f32::NEG_INFINITY);
        assert!(!skips.can_skip(2, skips.travel_of(bodies)));
    }
}
