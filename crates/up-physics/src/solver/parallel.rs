//! Running the solver's passes: colour after colour, the contact groups of a
//! colour on rayon's threads when the `parallel` feature is on, serially
//! otherwise. Within a colour no moving body is shared (`coloring`), so both
//! ways give bit-identical results, whatever the number of threads.

use std::marker::PhantomData;

#[cfg(feature = "parallel")]
use rayon::prelude::*;

use super::body_state::BodyState;
#[cfg(feature = "parallel")]
use super::coloring::ColourBlocks;
use super::coloring::{Coloring, Moving};
#[cfg(feature = "parallel")]
use super::contact_constraint;
use super::contact_constraint::ContactGroup;
#[cfg(feature = "parallel")]
use super::contact_constraint::{GroupAnchors, GroupRecords, PreparedContact};
use super::lanes::LANES;
#[cfg(feature = "parallel")]
use crate::threading::staged::run_in_stages;
use crate::threading::tasks::for_each_run;
#[cfg(feature = "parallel")]
use crate::threading::tasks::worth_splitting;
#[cfg(feature = "parallel")]
use crate::threading::thread_times;

/// Contact groups (of four constraints) handed to one task of a pass over
/// all groups at once; below this such a pass stays serial.
const GROUP_CHUNK: usize = 64;
/// Bodies handed to one task.
#[cfg(feature = "parallel")]
const BODY_CHUNK: usize = 256;

/// A slice shared by the tasks of one pass, each touching only its own
/// elements (the body states of a colour or a body pass, the groups of a
/// pass's blocks), or its own bytes of an element others write too (a
/// group's lanes, `ptr`).
pub(super) struct SharedSlice<T> {
    ptr: *mut T,
    len: usize,
}

impl<T> Clone for SharedSlice<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for SharedSlice<T> {}

// SAFETY: tasks only touch elements as the methods below allow (see their
// contracts, and for `ptr` its users'); the pointer outlives every task
// (the passes are scoped).
unsafe impl<T: Send> Send for SharedSlice<T> {}
unsafe impl<T: Send> Sync for SharedSlice<T> {}

impl<T> SharedSlice<T> {
    pub(super) fn new(items: &mut [T]) -> Self {
        Self {
            ptr: items.as_mut_ptr(),
            len: items.len(),
        }
    }

    /// # Safety
    /// No other task may use element `i` at the same time.
    #[allow(clippy::mut_from_ref)] // the point of the type: disjoint indices, shared pointer
    pub(super) unsafe fn get(&self, i: u32) -> &mut T {
        assert!((i as usize) < self.len);
        // SAFETY: in bounds (asserted), and ours alone (the caller's contract).
        unsafe { &mut *self.ptr.add(i as usize) }
    }

    /// A pointer to element `i`, for tasks that write parts of one element
    /// at the same time: what each may touch is for the unsafe code that
    /// writes through it to keep apart.
    #[cfg(feature = "parallel")]
    fn ptr(&self, i: u32) -> *mut T {
        assert!((i as usize) < self.len);
        self.ptr.wrapping_add(i as usize)
    }

    /// # Safety
    /// No other task may use elements `start..end` at the same time.
    #[cfg(feature = "parallel")]
    #[allow(clippy::mut_from_ref)]
    unsafe fn range(&self, start: u32, end: u32) -> &mut [T] {
        assert!(start <= end && (end as usize) <= self.len);
        // SAFETY: in bounds (asserted), and ours alone (the caller's contract).
        unsafe {
            std::slice::from_raw_parts_mut(self.ptr.add(start as usize), (end - start) as usize)
        }
    }

    /// # Safety
    /// No other task may use any element at the same time.
    #[cfg(feature = "parallel")]
    #[allow(clippy::mut_from_ref)]
    pub(super) unsafe fn all(&self) -> &mut [T] {
        // SAFETY: the whole slice, ours alone (the caller's contract).
        unsafe { self.range(0, self.len as u32) }
    }
}

pub(super) type SharedStates = SharedSlice<BodyState>;

/// The states of a contact group's bodies, side A and side B, one per lane,
/// as a task of `for_each_colored` sees them: every state can be read, only
/// moving ones written (static ones — the room, sleeping balloons, empty
/// lanes — are read by other tasks at the same time and take no impulse).
pub(crate) struct GroupStates<'a> {
    shared: SharedStates,
    bodies: [[u32; LANES]; 2],
    /// The sides whose states are not all fixed (`coloring::Moving`).
    pub moving: Moving,
    _states: PhantomData<&'a mut [BodyState]>,
}

impl GroupStates<'_> {
    /// The states of side `side` (0: A, 1: B).
    #[inline]
    pub fn read(&self, side: usize) -> [&BodyState; LANES] {
        self.bodies[side].map(|i| {
            assert!((i as usize) < self.shared.len);
            // SAFETY: in bounds (asserted); nobody writes these states while
            // this task runs (`for_each_colored`'s contract).
            unsafe { &*self.shared.ptr.add(i as usize) }
        })
    }

    /// Hands `update` each moving state of side `side`, with its lane.
    #[inline]
    pub fn write(&mut self, side: usize, mut update: impl FnMut(usize, &mut BodyState)) {
        for (lane, &i) in self.bodies[side].iter().enumerate() {
            assert!((i as usize) < self.shared.len);
            // SAFETY: in bounds (asserted). Only a moving state is borrowed
            // mutably: it belongs to this task alone (`for_each_colored`'s
            // contract), and no reference from `read` outlives `&mut self`.
            // A static one, which other tasks read, is only read here, through
            // the pointer.
            unsafe {
                let state = self.shared.ptr.add(i as usize);
                if (*state).inv_mass > 0.0 {
                    update(lane, &mut *state);
                }
            }
        }
    }
}

/// Runs `kernel` on every contact group, with its index (for the group's
/// other parts), colour after colour (`coloring`'s runs: a colour's runs,
/// one per kind of sides that move, come together, the overflow's levels
/// after the colours; the last run, the serial rest, always serially). Within
/// a colour no moving body appears twice, so each task owns the moving states
/// of its groups. On several threads the colours' blocks (`ColourBlocks`)
/// run as the stages of one `run_in_stages`: one fork-join a pass.
pub(crate) fn for_each_colored<K>(
    coloring: &Coloring,
    groups: &mut [ContactGroup],
    states: &mut [BodyState],
    kernel: K,
) where
    K: Fn(usize, &mut ContactGroup, GroupStates) + Sync,
{
    let shared = SharedStates::new(states);
    #[cfg(feature = "parallel")]
    {
        let blocks = &coloring.blocks;
        if rayon::current_num_threads() > 1 && blocks.stages.blocks() > 1 {
            let shared_groups = SharedSlice::new(groups);
            thread_times::pass(|| {
                run_in_stages(&blocks.stages, |k| {
                    // SAFETY: each block is run by one task, and blocks that
                    // run at once belong to one stage (`run_colour_block`).
                    unsafe { run_colour_block(blocks, k, shared_groups, shared, &kernel) }
                })
            });
            return;
        }
    }
    for r in &coloring.ranges {
        let colour = &mut groups[r.start as usize..r.end as usize];
        run_groups(shared, r.start as usize, r.moving, colour, &kernel);
    }
}

/// Runs `kernel` on `chunk`, groups from `first` on whose sides move as `moving` says.
#[inline]
fn run_groups<K>(
    shared: SharedStates,
    first: usize,
    moving: Moving,
    chunk: &mut [ContactGroup],
    kernel: &K,
) where
    K: Fn(usize, &mut ContactGroup, GroupStates) + Sync,
{
    for (k, g) in chunk.iter_mut().enumerate() {
        let sides = GroupStates {
            shared,
            bodies: [g.a, g.b],
            moving,
            _states: PhantomData,
        };
        kernel(first + k, g, sides);
    }
}

/// Runs `kernel` on the groups of block `k` of `blocks`, as `for_each_colored` does.
///
/// # Safety
/// No other task may run block `k` at the same time, and blocks that run
/// at the same time must belong to one stage (a colour or level): then the
/// blocks' pieces do not overlap, so the block's groups are its own, and
/// the stage's groups share no moving body (the `GroupStates` writes).
#[cfg(feature = "parallel")]
pub(super) unsafe fn run_colour_block<K>(
    blocks: &ColourBlocks,
    k: usize,
    groups: SharedSlice<ContactGroup>,
    states: SharedStates,
    kernel: &K,
) where
    K: Fn(usize, &mut ContactGroup, GroupStates) + Sync,
{
    for piece in blocks.block(k) {
        // SAFETY: the caller's contract.
        let chunk = unsafe { groups.range(piece.start, piece.end) };
        run_groups(states, piece.start as usize, piece.moving, chunk, kernel);
    }
}

/// Runs `kernel` on every contact group and its entry in `parts`, with read-only states.
pub(crate) fn for_each_group<P, K>(
    groups: &mut [ContactGroup],
    parts: &mut [P],
    states: &[BodyState],
    kernel: K,
) where
    P: Send,
    K: Fn(&mut ContactGroup, &mut P, [&BodyState; LANES], [&BodyState; LANES]) + Sync,
{
    assert_eq!(groups.len(), parts.len());
    let len = groups.len();
    for_each_run(len, GROUP_CHUNK, (groups, parts), |_, (groups, parts)| {
        for (g, part) in groups.iter_mut().zip(parts) {
            let (a, b) = (g.a, g.b);
            kernel(
                g,
                part,
                a.map(|i| &states[i as usize]),
                b.map(|i| &states[i as usize]),
            );
        }
    });
}

/// The three parts of a run of contact groups (see `Solver`).
#[cfg(feature = "parallel")]
type GroupParts<'a> = (
    &'a mut [ContactGroup],
    &'a mut [GroupAnchors],
    &'a mut [GroupRecords],
);

/// Prepared contacts handed to one task of `scatter_lanes`.
#[cfg(feature = "parallel")]
const SCATTER_CHUNK: usize = 1024;

/// Writes each prepared contact into its lane of the groups (`slots[i]`:
/// group · `LANES` + lane), runs of contacts on rayon's threads: read in
/// order and written where they go, since reading each group's lanes from
/// their places in `prepared` would wait on every read.
///
/// # Safety
/// No two of `slots` are equal (`Coloring::assign` gives each constraint a
/// slot of its own): two tasks writing one lane would race.
#[cfg(feature = "parallel")]
pub(crate) unsafe fn scatter_lanes(
    (groups, anchors, records): GroupParts,
    slots: &[u32],
    prepared: &[PreparedContact],
) {
    assert!(groups.len() == anchors.len() && groups.len() == records.len());
    assert_eq!(slots.len(), prepared.len());
    debug_assert!(
        {
            let mut sorted = slots.to_vec();
            sorted.sort_unstable();
            sorted.windows(2).all(|w| w[0] != w[1])
        },
        "two constraints share a slot"
    );
    let shared = (
        SharedSlice::new(groups),
        SharedSlice::new(anchors),
        SharedSlice::new(records),
    );
    for_each_run(
        prepared.len(),
        SCATTER_CHUNK,
        (prepared, slots),
        |_, (prepared, slots)| {
            for (c, &slot) in prepared.iter().zip(slots) {
                let (g, lane) = (slot / LANES as u32, slot as usize % LANES);
                let parts = (shared.0.ptr(g), shared.1.ptr(g), shared.2.ptr(g));
                // SAFETY: the slots are distinct (the caller's contract), so
                // no other task writes this lane, and no task reads the
                // groups until the pass is over.
                unsafe { contact_constraint::set_lane_shared(parts, lane, c) };
            }
        },
    );
}

/// Runs `fill` on every contact group's three parts, with the group's index.
#[cfg(feature = "parallel")]
pub(crate) fn fill_groups<F>((groups, anchors, records): GroupParts, fill: F)
where
    F: Fn(usize, (&mut ContactGroup, &mut GroupAnchors, &mut GroupRecords)) + Sync,
{
    assert!(groups.len() == anchors.len() && groups.len() == records.len());
    let len = groups.len();
    let parts = (groups, anchors, records);
    for_each_run(
        len,
        GROUP_CHUNK,
        parts,
        |first, (groups, anchors, records)| {
            let parts = groups.iter_mut().zip(anchors).zip(records);
            for (k, ((g, anchors), records)) in parts.enumerate() {
                fill(first + k, (g, anchors, records));
            }
        },
    );
}

/// Runs `kernel` on the state (and index) of every body in `bodies`, which
/// must not repeat an index.
pub(crate) fn for_each_body<K>(bodies: &[u32], states: &mut [BodyState], kernel: K)
where
    K: Fn(u32, &mut BodyState) + Sync,
{
    let shared = SharedStates::new(states);
    let run = |chunk: &[u32]| {
        for &i in chunk {
            // SAFETY: the indices are distinct (the awake list).
            kernel(i, unsafe { shared.get(i) });
        }
    };
    #[cfg(feature = "parallel")]
    if worth_splitting(bodies.len(), BODY_CHUNK) {
        thread_times::pass(|| {
            bodies
                .par_chunks(BODY_CHUNK)
                .for_each(|chunk| thread_times::task(|| run(chunk)))
        });
        return;
    }
    run(bodies);
}
