//! Running the solver's passes: colour after colour, the constraints of a
//! colour on rayon's threads when the `parallel` feature is on, serially
//! otherwise. Within a colour no moving body is shared (`coloring`), so both
//! ways give bit-identical results, whatever the number of threads.

#[cfg(feature = "parallel")]
use rayon::prelude::*;

use super::body_state::BodyState;
use super::contact_constraint::ContactConstraint;

/// Constraints or bodies handed to one task; below this a pass stays serial.
#[cfg(feature = "parallel")]
const CHUNK: usize = 256;

/// The body states, shared by the tasks of one colour or one body pass.
#[derive(Clone, Copy)]
struct SharedStates {
    ptr: *mut BodyState,
    len: usize,
}

// SAFETY: tasks only touch states as the methods below allow (see their
// contracts); the pointer outlives every task (the passes are scoped).
unsafe impl Send for SharedStates {}
unsafe impl Sync for SharedStates {}

impl SharedStates {
    fn new(states: &mut [BodyState]) -> Self {
        Self {
            ptr: states.as_mut_ptr(),
            len: states.len(),
        }
    }

    /// The states of a constraint's two bodies. A static body (the room, a
    /// sleeping balloon) is copied into `spare` — it takes no impulse, and
    /// other tasks read it at the same time.
    ///
    /// # Safety
    /// No other task may hold a moving state of this pair at the same time:
    /// true within one colour, and in a serial loop.
    unsafe fn pair<'a>(
        &self,
        a: u32,
        b: u32,
        spare: &'a mut [BodyState; 2],
    ) -> (&'a mut BodyState, &'a mut BodyState) {
        let (a, b) = (a as usize, b as usize);
        assert!(a < self.len && b < self.len && a != b);
        let [spare_a, spare_b] = spare;
        let pick = |i: usize, spare: &'a mut BodyState| -> &'a mut BodyState {
            // SAFETY: in bounds (asserted); a moving state is ours alone (the
            // caller's contract), a static one is only read.
            unsafe {
                let state = self.ptr.add(i);
                if (*state).inv_mass > 0.0 {
                    &mut *state
                } else {
                    *spare = *state;
                    spare
                }
            }
        };
        (pick(a, spare_a), pick(b, spare_b))
    }

    /// # Safety
    /// No other task may use state `i` at the same time.
    #[allow(clippy::mut_from_ref)] // the point of the type: disjoint indices, shared pointer
    unsafe fn get(&self, i: u32) -> &mut BodyState {
        assert!((i as usize) < self.len);
        // SAFETY: in bounds (asserted), and ours alone (the caller's contract).
        unsafe { &mut *self.ptr.add(i as usize) }
    }
}

/// Runs `kernel` on every constraint, colour by colour (`ranges` from
/// `Coloring`; the last range, the overflow, always serially).
pub(crate) fn for_each_colored<K>(
    ranges: &[(u32, u32)],
    constraints: &mut [ContactConstraint],
    states: &mut [BodyState],
    kernel: K,
) where
    K: Fn(&mut ContactConstraint, &mut BodyState, &mut BodyState) + Sync,
{
    let shared = SharedStates::new(states);
    let run = |chunk: &mut [ContactConstraint]| {
        let mut spare = [BodyState::STATIC; 2];
        for c in chunk {
            // SAFETY: a chunk lies within one colour, or runs alone.
            let (sa, sb) = unsafe { shared.pair(c.a, c.b, &mut spare) };
            kernel(c, sa, sb);
        }
    };
    let overflow = ranges.len().saturating_sub(1);
    for (k, &(start, end)) in ranges.iter().enumerate() {
        let colour = &mut constraints[start as usize..end as usize];
        #[cfg(feature = "parallel")]
        if k != overflow && colour.len() > CHUNK {
            colour.par_chunks_mut(CHUNK).for_each(run);
            continue;
        }
        let _ = (k, overflow);
        run(colour);
    }
}

/// Runs `kernel` on every constraint with read-only states.
pub(crate) fn for_each_constraint<K>(
    constraints: &mut [ContactConstraint],
    states: &[BodyState],
    kernel: K,
) where
    K: Fn(&mut ContactConstraint, &BodyState, &BodyState) + Sync,
{
    let run = |chunk: &mut [ContactConstraint]| {
        for c in chunk {
            kernel(c, &states[c.a as usize], &states[c.b as usize]);
        }
    };
    #[cfg(feature = "parallel")]
    if constraints.len() > CHUNK {
        constraints.par_chunks_mut(CHUNK).for_each(run);
        return;
    }
    run(constraints);
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
    if bodies.len() > CHUNK {
        bodies.par_chunks(CHUNK).for_each(run);
        return;
    }
    run(bodies);
}
