//! Moving air: the room's air velocity u(x, t), which every drag in the
//! engine reads (a balloon's, a ribbon point's, a weight's), made of
//! sources that blow: fans and vents (round free jets, `jet`) and draughts
//! through an open door or window (`draught`), each switched on and off by
//! its schedule (`schedule`).
//!
//! The field is an analytic superposition of the sources' jets, one way
//! coupled (balloons do not stir the air). Its limits, stated once: a jet
//! does not feel the walls (it neither turns along a wall nor builds the
//! closed room's return flow), jets add as vectors where they cross, and
//! what draws a balloon toward a jet's axis is the jet's entrainment inflow
//! alone (no pressure field). With no sources the field is zero everywhere
//! and the step computes exactly what it does without moving air.
//!
//! The step samples the field once a step (`AirNow`, the sources as they
//! blow at the step's start): at each awake body's centre of mass
//! (`forces::BodyForces::air`), whose drag, and the drag's torque about the
//! centre of buoyancy, act on its velocity relative to the air; and at each
//! point of each awake ribbon at its first substep, whose drag across and
//! along likewise. Sleepers are checked against it a quarter a step
//! (`world::air_step`).

mod draught;
mod jet;
mod now;
mod schedule;

pub use draught::Draught;
pub use jet::{Jet, JetKind, Sweep, JET_DECAY_B, JET_SPREAD_S, JET_VIRTUAL_ORIGIN_D};
pub(crate) use now::AirNow;
pub use schedule::{Schedule, SPIN_UP_S};

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Air at least this fast, m/s, keeps a balloon awake where it blows (at
/// its centre or any point of its ribbon), and wakes a sleeper it reaches:
/// well under the 0.25 m/s people notice, and enough to stir a balloon's
/// ribbon (`sleep` has the whole rule).
pub const RESTLESS_AIR_SPEED: f32 = 0.1;

/// Every source of moving air in the room. The default is still air.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AirFlow {
    /// Fans and vents.
    pub jets: Vec<Jet>,
    /// Open doors and windows.
    pub draughts: Vec<Draught>,
}

impl AirFlow {
    /// No sources at all: the air is at rest everywhere, always.
    pub fn is_still(&self) -> bool {
        self.jets.is_empty() && self.draughts.is_empty()
    }

    /// The air's velocity at `p` (m, world frame) at simulated time `t`
    /// (s), m/s: the sum of every source's, in the order they are listed.
    pub fn velocity_at(&self, p: Vec3, t: f64) -> Vec3 {
        now::sum(
            self.jets.iter().map(|j| j.velocity_at(p, t)),
            self.draughts.iter().map(|d| d.velocity_at(p, t)),
        )
    }

    /// Checks every source, naming the first bad one (`jets[2].diameter_m`).
    pub fn validate(&self) -> Result<(), String> {
        for (i, jet) in self.jets.iter().enumerate() {
            jet.validate().map_err(|e| format!("jets[{i}].{e}"))?;
        }
        for (i, draught) in self.draughts.iter().enumerate() {
            draught
                .validate()
                .map_err(|e| format!("draughts[{i}].{e}"))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
