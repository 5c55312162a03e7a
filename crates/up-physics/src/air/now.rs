//! The room's air at one instant: every source with its sweep and schedule
//! applied once (`AirNow::refresh`), so that the step samples the field at
//! each awake body and ribbon point without a sine or a schedule lookup
//! per point. It gives what `AirFlow::velocity_at` gives, bit for bit: both
//! sum the same sources' `now` in the same order.

use glam::Vec3;

use super::draught::DraughtNow;
use super::jet::JetNow;
use super::AirFlow;

/// Every source of an `AirFlow` as it blows at one time.
#[derive(Clone, Debug, Default)]
pub(crate) struct AirNow {
    jets: Vec<JetNow>,
    draughts: Vec<DraughtNow>,
}

impl AirNow {
    /// `flow`'s sources as they blow at `t` (no allocation once the
    /// buffers have grown to the sources).
    pub fn refresh(&mut self, flow: &AirFlow, t: f64) {
        self.jets.clear();
        self.jets.extend(flow.jets.iter().map(|j| j.now(t)));
        self.draughts.clear();
        self.draughts.extend(flow.draughts.iter().map(|d| d.now(t)));
    }

    /// The air's velocity at `p`, m/s.
    #[inline]
    pub fn velocity_at(&self, p: Vec3) -> Vec3 {
        sum(
            self.jets.iter().map(|j| j.velocity_at(p)),
            self.draughts.iter().map(|d| d.velocity_at(p)),
        )
    }
}

/// The jets' velocities then the draughts', summed in that order from zero.
#[inline]
pub(super) fn sum(jets: impl Iterator<Item = Vec3>, draughts: impl Iterator<Item = Vec3>) -> Vec3 {
    jets.chain(draughts).fold(Vec3::ZERO, |sum, u| sum + u)
}
