//! Quarantine: a body whose motion runs away (an absurd user force, a bug) is
//! frozen for the rest of the step as soon as its velocity is integrated, so
//! that it cannot spread huge or NaN impulses through its contacts, and is
//! taken out of the world at the end of the step and reported.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::body::{Bodies, BodyId};
use crate::threading::tasks::collect_in_order;

/// A body taken out of the world because its state was no longer finite.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct QuarantinedBody {
    /// Its handle, now stale.
    pub id: BodyId,
    /// What the caller gave it (`BodyDef::user_data`).
    pub user_data: u32,
    /// `World::step_count()` after the step that found it.
    pub step: u64,
}

/// The most reports kept until `World::take_quarantined` collects them; older
/// ones are dropped first (the count in `StepStats` keeps growing).
pub const MAX_QUARANTINE_REPORTS: usize = 1024;

/// m/s: no balloon gets near this (scenes cap initial speeds at the speed of
/// sound, 343); beyond it the motion has run away.
pub const MAX_SPEED: f32 = 1.0e4;
/// rad/s: likewise (scenes cap initial spins at 1000).
pub const MAX_SPIN: f32 = 1.0e5;

/// Whether a body's velocity is finite and below the runaway bounds.
#[inline]
pub(crate) fn is_sane_motion(v: Vec3, w: Vec3) -> bool {
    v.is_finite()
        && w.is_finite()
        && v.length_squared() < MAX_SPEED * MAX_SPEED
        && w.length_squared() < MAX_SPIN * MAX_SPIN
}

/// Bodies one task checks.
const CHECK_CHUNK: usize = 512;

/// Adds to `out` the dense indices of the bodies with a non-finite position
/// or orientation, or a runaway velocity, then sorts `out` highest first
/// without repeats (so that swap-removal keeps the other indices valid).
/// `lists` are the tasks' own (kept for their buffers).
/// `among`: the dense indices to check (every body if None).
pub(crate) fn find_faulty(
    bodies: &Bodies,
    among: Option<&[u32]>,
    lists: &mut Vec<Vec<usize>>,
    out: &mut Vec<usize>,
) {
    let count = among.map_or(bodies.len(), <[u32]>::len);
    collect_in_order(count, CHECK_CHUNK, lists, out, |range, out| {
        for k in range {
            let i = among.map_or(k, |among| among[k] as usize);
            let sane = bodies.center[i].is_finite()
                && bodies.rotation[i].is_finite()
                && is_sane_motion(bodies.linear_velocity[i], bodies.angular_velocity[i]);
            if !sane {
                out.push(i);
            }
        }
    });
    out.sort_unstable_by(|a, b| b.cmp(a));
    out.dedup();
}

/// The quarantine check's buffers.
#[derive(Clone, Debug, Default)]
pub(crate) struct FaultBuffers {
    /// Dense indices of the bodies to take out this step (the solve's
    /// runaways first, then `find_faulty`'s).
    pub non_finite: Vec<usize>,
    /// Each task's finds: the solve's runaways (`finish_motion`), then
    /// `find_faulty`'s.
    pub task_faulty: Vec<Vec<usize>>,
}

impl FaultBuffers {
    /// Gives back the capacity the tasks' lists left unused (`spare`).
    pub fn release_spare(&mut self) {
        crate::threading::spare::release_spare_each(&mut self.task_faulty);
    }
}
