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
//! pile beside a fan costs a quarter of its jet evaluations a step. The
//! time-lapse (`World::advance`) jumps no further than the air allows
//! (`air_jump`) and checks every sleeper after each jump.

use std::mem;

use super::World;
use crate::air::{RESTLESS_AIR_SPEED, SPIN_UP_S};

/// Each step, the sleepers whose dense index is the step count modulo this
/// are checked against the air: a source reaches a sleeper within this many
/// steps.
const SLEEPER_STRIDE: usize = 4;

impl World {
    /// The sources as they blow at the step's start; the sleepers the air
    /// now reaches woken, with their islands.
    pub(super) fn wake_in_air(&mut self) {
        let first = (self.step_count % SLEEPER_STRIDE as u64) as usize;
        self.wake_sleepers_in_air(first, SLEEPER_STRIDE);
    }

    /// The sources as they blow now; the sleepers from dense index `first`
    /// on, every `stride`th, woken where the air reaches them.
    pub(super) fn wake_sleepers_in_air(&mut self, first: usize, stride: usize) {
        if self.air_flow.is_still() {
            return;
        }
        let now = &mut self.stages.air_now;
        now.refresh(&self.air_flow, self.time);
        let mut woken = mem::take(&mut self.stages.air_woken);
        woken.clear();
        let b = &self.bodies;
        let restless = RESTLESS_AIR_SPEED * RESTLESS_AIR_SPEED;
        for i in (first..b.len()).step_by(stride) {
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

    /// The longest jump of the time-lapse from now, at most `jump` s, that
    /// the moving air allows while everything sleeps: none past a moment a
    /// source starts or stops changing speed (an interval's start or end, or
    /// its spin-up's), and at most an eighth of a sweep, so that every
    /// sleeper is checked (`wake_sleepers_in_air`) wherever a sweep or a
    /// source switched on reaches it.
    pub(super) fn air_jump(&self, jump: f64) -> f64 {
        if self.air_flow.is_still() {
            return jump;
        }
        let now = self.time;
        let mut longest = jump;
        let mut until = |moment: f64| {
            if moment > now {
                longest = longest.min(moment - now);
            }
        };
        let schedules = self.air_flow.jets.iter().map(|j| &j.schedule);
        let schedules = schedules.chain(self.air_flow.draughts.iter().map(|d| &d.schedule));
        for schedule in schedules {
            for &[start, end] in &schedule.on {
                for moment in [start, start + SPIN_UP_S, end, end + SPIN_UP_S] {
                    until(moment);
                }
            }
        }
        for jet in &self.air_flow.jets {
            if jet.sweep.angle_rad > 0.0 && jet.sweep.period_s > 0.0 {
                longest = longest.min(f64::from(jet.sweep.period_s) / 8.0);
            }
        }
        longest
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
