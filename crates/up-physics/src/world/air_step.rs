//! The moving air's parts of the step (`crate::air`): `wake_in_air`, second
//! in the step, takes the sources as they blow now (`AirNow`, which the
//! forces and the ribbons then sample) and wakes the sleepers the air
//! reaches; `keep_awake_in_air`, after the ribbons, keeps the awake bodies
//! it pushes from resting. Both do nothing in still air.
//!
//! The rule: a body rests only where the air at its centre, and at every
//! point of its ribbon, is slower than `RESTLESS_AIR_SPEED`; a sleeper wakes
//! (its island with it) once the air at its centre or at its ribbon's free
//! end reaches that speed, which is how a fan switched on, a sweep passing
//! over or a source added wakes what it blows on. Sleepers are checked a
//! quarter at a time, in turn by dense index (`SLEEPER_STRIDE`): a sleeping
//! pile beside a fan costs a quarter of its jet evaluations a step.

use std::mem;

use super::World;
use crate::air::RESTLESS_AIR_SPEED;

/// Each step, the sleepers whose dense index is the step count modulo this
/// are checked against the air: a source reaches a sleeper within this many
/// steps.
const SLEEPER_STRIDE: usize = 4;

impl World {
    /// The sources as they blow at the step's start; the sleepers the air
    /// now reaches woken, with their islands.
    pub(super) fn wake_in_air(&mut self) {
        if self.air_flow.is_still() {
            return;
        }
        let now = &mut self.stages.air_now;
        now.refresh(&self.air_flow, self.time);
        let mut woken = mem::take(&mut self.stages.air_woken);
        woken.clear();
        let b = &self.bodies;
        let restless = RESTLESS_AIR_SPEED * RESTLESS_AIR_SPEED;
        let first = (self.step_count % SLEEPER_STRIDE as u64) as usize;
        for i in (first..b.len()).step_by(SLEEPER_STRIDE) {
            if b.awake[i] {
                continue;
            }
            let blows = |p| now.velocity_at(p).length_squared() >= restless;
            let ribbon = self.ribbons.on(b.id[i]).and_then(|r| self.ribbons.get(r));
            let end = ribbon.and_then(|r| r.points.last().copied());
            if blows(b.center[i]) || end.is_some_and(blows) {
                woken.push(b.island[i]);
            }
        }
        woken.sort_unstable();
        woken.dedup();
        for &island in &woken {
            self.wake_island(island);
        }
        self.stages.air_woken = woken;
    }

    /// After the ribbons have marked the bodies whose ribbons still move (or
    /// stand in moving air): the awake bodies the air at their centres
    /// pushes may not rest either.
    pub(super) fn keep_awake_in_air(&mut self) {
        if self.air_flow.is_still() {
            return;
        }
        let restless = RESTLESS_AIR_SPEED * RESTLESS_AIR_SPEED;
        let forces = &self.stages.solve.solver.forces;
        let kept = &mut self.stages.ribbons.moving;
        let awake = &self.bodies.awake;
        for (i, keep) in kept.iter_mut().enumerate() {
            if awake[i] && forces[i].air.length_squared() >= restless {
                *keep = true;
            }
        }
    }
}
