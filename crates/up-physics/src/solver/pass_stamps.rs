//! Which contact groups a position pass can skip, bit for bit.
//!
//! A position pass (`contact_constraint::stabilize`) moves a group's bodies
//! only where a contact is deeper than the slop, and the depth depends on
//! nothing but the bodies' displacements. So a group that moved nothing when
//! it last ran, and whose bodies nobody has moved since, would move nothing
//! again: it is skipped. Most groups of a pile at rest are such after the
//! first pass, and the passes after it then cost a lookup per group.
//!
//! Runs are ordered by a stamp, pass · groups + group + 1: groups run in
//! index order within a pass (colour after colour, and the groups of one
//! colour share no moving body, so on any number of threads a body's stamp
//! is written by one task and read by no other in that colour).

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use super::lanes::LANES;
use crate::spare::{release_spare, BUFFER_FLOOR};

/// Whether the stamps of `passes` passes over `groups` groups fit a `u32`.
fn stamps_fit(groups: usize, passes: u32) -> bool {
    (passes as u64 + 1).saturating_mul(groups as u64) < u32::MAX as u64
}

/// The stamps of one step's position passes.
#[derive(Debug, Default)]
pub(crate) struct PassStamps {
    /// Per state: the stamp of the run that last moved it (0: none this step).
    /// Static states (the room, sleepers) are never moved, so stay 0.
    moved: Vec<AtomicU32>,
    /// Per group: the stamp of its last run if that run moved nothing, else 0.
    quiet: Vec<AtomicU32>,
    groups: u32,
    /// False when the stamps of this many passes would not fit a `u32`.
    enabled: bool,
}

/// Scratch, rebuilt by `begin` each step: a clone starts empty.
impl Clone for PassStamps {
    fn clone(&self) -> Self {
        PassStamps::default()
    }
}

impl PassStamps {
    /// Forgets the last step: `states` bodies, `groups` groups, at most `passes` passes.
    pub fn begin(&mut self, states: usize, groups: usize, passes: u32) {
        let reset = |v: &mut Vec<AtomicU32>, n: usize| {
            v.clear();
            v.resize_with(n, || AtomicU32::new(0));
        };
        reset(&mut self.moved, states);
        reset(&mut self.quiet, groups);
        self.groups = groups as u32;
        self.enabled = stamps_fit(groups, passes);
    }

    /// The stamp of group `group`'s run in pass `pass`.
    #[inline]
    pub fn stamp(&self, pass: u32, group: usize) -> u32 {
        pass.wrapping_mul(self.groups)
            .wrapping_add(group as u32)
            .wrapping_add(1)
    }

    /// Whether group `group`, between the states `bodies` (side A, side B),
    /// would move nothing: it moved nothing when it last ran, and none of
    /// its bodies moved after that.
    #[inline]
    pub fn unchanged(&self, group: usize, bodies: [&[u32; LANES]; 2]) -> bool {
        let quiet = self.quiet[group].load(Relaxed);
        self.enabled
            && quiet != 0
            && bodies
                .iter()
                .flat_map(|side| side.iter())
                .all(|&i| self.moved[i as usize].load(Relaxed) < quiet)
    }

    /// Records the run of group `group` at `stamp`: it moved nothing, or it
    /// may have moved its moving bodies (each passed to `moved_state`).
    #[inline]
    pub fn ran(&self, group: usize, stamp: u32, moved_anything: bool) {
        self.quiet[group].store(if moved_anything { 0 } else { stamp }, Relaxed);
    }

    /// Records that `state` (a moving one, owned by the caller's task) moved at `stamp`.
    #[inline]
    pub fn moved_state(&self, state: u32, stamp: u32) {
        self.moved[state as usize].store(stamp, Relaxed);
    }

    /// Gives back the capacity this step left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.moved, BUFFER_FLOOR);
        release_spare(&mut self.quiet, BUFFER_FLOOR);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quiet_group_is_skipped_until_one_of_its_bodies_moves() {
        let mut stamps = PassStamps::default();
        stamps.begin(10, 3, 8);
        let bodies = [&[0, 1, 2, 9], &[3, 4, 5, 9]];
        // Never run: it must run.
        assert!(!stamps.unchanged(1, bodies));
        let first = stamps.stamp(0, 1);
        stamps.ran(1, first, false);
        assert!(stamps.unchanged(1, bodies));
        // Group 2 moves body 4 after group 1 ran: group 1 must run again.
        let later = stamps.stamp(0, 2);
        stamps.moved_state(4, later);
        stamps.ran(2, later, true);
        assert!(!stamps.unchanged(1, bodies));
        // It runs in the next pass and moves nothing: skipped from then on.
        let again = stamps.stamp(1, 1);
        assert!(again > later);
        stamps.ran(1, again, false);
        assert!(stamps.unchanged(1, bodies));
        // A group that moved something runs again, though nobody moved since.
        assert!(!stamps.unchanged(2, [&[4, 9, 9, 9], &[9, 9, 9, 9]]));
    }

    #[test]
    fn skipping_is_off_where_the_stamps_would_overflow() {
        assert!(stamps_fit(1_000_000, 64));
        assert!(!stamps_fit(1 << 27, 32));
        let mut stamps = PassStamps::default();
        stamps.begin(2, 1, 8);
        stamps.enabled = false;
        stamps.ran(0, stamps.stamp(0, 0), false);
        assert!(!stamps.unchanged(0, [&[0; LANES], &[1; LANES]]));
    }
}
