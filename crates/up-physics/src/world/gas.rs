//! The balloons' gas in the world: filling a balloon, the air of the moment
//! (the temperature schedule), every gas a step on with the bodies, the
//! size and mass each body takes from its gas, and the time-lapse that
//! jumps over stretches in which everything sleeps.
//!
//! A sleeping balloon keeps the size and mass it fell asleep with (its
//! placed tree and its pile's contacts stay valid), while its gas goes on
//! leaking. Once the gas has moved it far enough from that (its lift by
//! `WAKE_LIFT_CHANGE`, or its size by `WAKE_GROWTH` / `WAKE_SHRINK`) its
//! island wakes, takes the gas's sizes, settles and sleeps again. Growing
//! is held to a small step so that a pile wakes with overlap the position
//! pass removes in one step; shrinking only opens gaps that buoyancy
//! closes, so it may go further.

use serde::{Deserialize, Serialize};

use super::{PhysicsError, World};
use crate::body::BodyId;
use crate::forces::atmosphere::Atmosphere;
use crate::gas::{EnvelopeDef, Gas};

/// A sleeper wakes when its free lift has moved by this share of what it
/// was when it fell asleep, plus `WAKE_LIFT_FLOOR`, or a balloon on a ribbon
/// by the finer `WAKE_LIFT_KNEE` rule. Each wake costs its island a second
/// or two of steps to settle again, so the threshold is as coarse as the
/// picture allows: a balloon pressed to the ceiling (where a change of lift
/// moves nothing) wakes a few times an hour.
pub const WAKE_LIFT_CHANGE: f64 = 0.05;
/// kg of free lift below which a balloon on a ribbon wakes on the share
/// `WAKE_LIFT_CHANGE` shrunk in proportion, plus `WAKE_LIFT_HOVER` (2 g): it
/// may hover, where 2.5 mg of lift is a centimetre of a 0.25 g/m ribbon
/// lifted off the floor, and it leaves the ceiling once its lift falls below
/// its ribbon's weight (0.4 g), late by the threshold (`docs/perf-log.md`,
/// the time-lapse entries).
pub const WAKE_LIFT_KNEE: f64 = 2e-3;
/// kg of lift: the smallest change that wakes a balloon on a ribbon while
/// its lift is positive (10 mg, 4 cm of such a ribbon).
pub const WAKE_LIFT_HOVER: f64 = 1e-5;
/// kg of lift: the smallest change that wakes any other (40 mg).
pub const WAKE_LIFT_FLOOR: f64 = 4e-5;
/// Growth of a sleeper's size that wakes it: 0.2 %, ≈ 0.3 mm on an 11″
/// balloon, within the position pass's target overlap.
pub const WAKE_GROWTH: f64 = 0.002;
/// Shrinking that wakes it: 2 %, a gap of ≈ 3 mm on an 11″ balloon, which
/// buoyancy closes when it wakes.
pub const WAKE_SHRINK: f64 = 0.02;
/// Longest jump of the time-lapse while everything sleeps, s: when a sleeper
/// wakes is known to within it.
pub const MAX_JUMP_S: f64 = 10.0;

/// What `World::advance` did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Advance {
    /// Simulated seconds advanced.
    pub seconds: f64,
    /// Steps of `def.dt`.
    pub steps: u64,
    /// Jumps over time in which every body slept.
    pub jumps: u64,
}

impl World {
    /// Gives body `id` a gas: filled to its shape's volume in the room's air
    /// now, with the envelope's overpressure, then aged `age_s` seconds in
    /// that air (filled that long before). From then on its size, mass,
    /// buoyancy and drag follow the gas.
    pub fn fill(
        &mut self,
        id: BodyId,
        envelope: &EnvelopeDef,
        age_s: f64,
    ) -> Result<(), PhysicsError> {
        if let Some((key, value, expected)) = envelope.problem() {
            return Err(PhysicsError::BadParameter {
                key,
                value: value as f32,
                expected: expected.to_string(),
            });
        }
        if !(age_s.is_finite() && age_s >= 0.0) {
            return Err(PhysicsError::BadParameter {
                key: "age_s",
                value: age_s as f32,
                expected: "≥ 0 s".to_string(),
            });
        }
        let i = self.dense(id)?;
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        let mut gas = Gas::fill(*envelope, f64::from(shape.def.volume), &self.air);
        gas.advance(age_s, &self.air);
        self.bodies.gas[i] = Some(gas);
        self.has_gas = true;
        if !self.bodies.awake[i] {
            self.wake_island(self.bodies.island[i]);
        }
        self.take_gas_size(i);
        Ok(())
    }

    /// The gas of body `id`; None for a body without one.
    pub fn gas(&self, id: BodyId) -> Option<Gas> {
        self.handles.dense(id).and_then(|i| self.bodies.gas[i])
    }

    /// Body `id`'s size now over its shape's: 1 without gas.
    pub fn body_scale(&self, id: BodyId) -> Option<f32> {
        self.handles.dense(id).map(|i| self.bodies.size[i].scale)
    }

    /// Each body's size over its shape's, dense order (as `write_poses`).
    pub fn write_body_scales(&self, out: &mut [f32]) {
        for (o, size) in out.iter_mut().zip(&self.bodies.size) {
            *o = size.scale;
        }
    }

    /// The room's air now: the atmosphere, at the schedule's temperature.
    pub fn air(&self) -> Atmosphere {
        self.air
    }

    /// kg: the air body `id` displaces less its mass (its free lift; a
    /// ribbon's weight not counted), from its gas if it has one.
    pub fn free_lift(&self, id: BodyId) -> Option<f32> {
        let i = self.handles.dense(id)?;
        if let Some(gas) = &self.bodies.gas[i] {
            return Some(gas.free_lift_kg(&self.air) as f32);
        }
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        Some(self.air.air_density() * shape.def.volume - shape.def.mass)
    }

    /// Time-lapse: advances `seconds` of simulated time, stepping while
    /// anything is awake and jumping (the gas alone, at most `MAX_JUMP_S` a
    /// jump) while everything sleeps, as many steps as plain stepping would
    /// take but at most `max_steps`. The gas is the same either way (a
    /// sleeper's gas moves on in steps too); only when a sleeper wakes is
    /// known to within a jump.
    pub fn advance(&mut self, seconds: f64, max_steps: u64) -> Advance {
        let start = self.time;
        let end = start + seconds.max(0.0);
        let dt = f64::from(self.def.dt);
        let mut done = Advance::default();
        // Half a step of slack: the clock is a sum of f32 steps.
        while end - self.time > 0.5 * dt {
            if self.everything_sleeps() {
                let jump = self.air_jump((end - self.time).min(MAX_JUMP_S));
                self.jump(jump);
                done.jumps += 1;
            } else if done.steps < max_steps {
                self.step();
                done.steps += 1;
            } else {
                break;
            }
        }
        done.seconds = self.time - start;
        done
    }

    fn everything_sleeps(&self) -> bool {
        self.bodies.len() > 0
            && !self.bodies.awake.contains(&true)
            && self.grab.is_none()
            && self.ribbon_grab.is_none()
    }

    /// `seconds` pass with every body asleep: only the air and the gas move;
    /// then every sleeper the moving air reaches wakes.
    fn jump(&mut self, seconds: f64) {
        let middle = self.air_at(self.time + 0.5 * seconds);
        self.age_gas(seconds, &middle, 0.0);
        self.time += seconds;
        self.air = self.air_at(self.time);
        self.wake_sleepers_in_air(0, 1);
    }

    /// The room's air at `time` s.
    pub(super) fn air_at(&self, time: f64) -> Atmosphere {
        let mut air = self.def.atmosphere;
        if let Some(k) = self.def.temperature_schedule.at(time) {
            air.temperature_k = k;
        }
        air
    }
}
