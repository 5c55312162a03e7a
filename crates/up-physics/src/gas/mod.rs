//! Balloons over hours: the gas in each balloon, which leaks out through the
//! envelope while air leaks in, and a size, mass and lift that follow it and
//! the room's temperature.
//!
//! - `envelope`: the skin, latex or foil, and its permeance (calibrated to
//!   published float times: see the constants there).
//! - `model`: the gas of one balloon, its ideal-gas volume and its leak
//!   (integrated by Runge–Kutta).
//! - `schedule`: the room's temperature over the run.
//!
//! The world (`world::gas`) steps every balloon's gas with the bodies and
//! gives each body the size and mass its gas has; sleeping balloons keep
//! theirs until their gas has moved them past a threshold
//! (`world::gas::WAKE_LIFT_CHANGE`), which wakes them.

pub mod envelope;
pub mod model;
pub mod schedule;

pub use envelope::{EnvelopeDef, EnvelopeKind};
pub use model::Gas;
pub use schedule::TemperatureSchedule;

#[cfg(test)]
mod tests;
