//! What the substeps did to the probed bodies (`world::probe`) besides the
//! contacts, whose impulses the constraints keep: the drag as it was
//! integrated, and the grab spring's pull. Nothing here runs when no body
//! is probed.

use glam::Vec3;
use up_geom::norm::Norm;

use super::body_state::BodyState;
use crate::forces::BodyForces;

/// The probed bodies' impulses over one step.
#[derive(Clone, Debug, Default)]
pub(crate) struct SubstepProbe {
    /// Dense indices of the probed awake bodies, ascending.
    pub bodies: Vec<u32>,
    /// Their speeds relative to the air before this substep's velocity
    /// update, m/s.
    speed: Vec<f32>,
    /// Drag impulses summed over the substeps, N·s.
    pub drag: Vec<Vec3>,
    /// The grab spring's impulses summed, N·s.
    pub grab: Vec<Vec3>,
}

impl SubstepProbe {
    /// Probes `bodies` (dense, ascending) this step, from zero.
    pub fn begin(&mut self, bodies: impl Iterator<Item = u32>) {
        self.bodies.clear();
        self.bodies.extend(bodies);
        let n = self.bodies.len();
        self.speed.clear();
        self.speed.resize(n, 0.0);
        self.drag.clear();
        self.drag.resize(n, Vec3::ZERO);
        self.grab.clear();
        self.grab.resize(n, Vec3::ZERO);
    }

    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// Before a substep's velocity update: the speeds relative to the air
    /// (`BodyForces::air`) that the drag is taken at.
    pub fn before(&mut self, states: &[BodyState], forces: &[BodyForces]) {
        for (speed, &i) in self.speed.iter_mut().zip(&self.bodies) {
            *speed = (states[i as usize].v - forces[i as usize].air).norm();
        }
    }

    /// After it: v' = (v + h·F/M + h·k·|v − u|·u/M) / (1 + h·k·|v − u|/M)
    /// is M·(v' − v)/h = F − k·|v − u|·(v' − u), so the drag this substep
    /// applied is −h·k·|v − u|·(v' − u) (u = 0 in still air).
    pub fn after(&mut self, states: &[BodyState], forces: &[BodyForces], h: f32) {
        for (k, &i) in self.bodies.iter().enumerate() {
            let (s, f) = (&states[i as usize], &forces[i as usize]);
            if s.runaway {
                continue;
            }
            self.drag[k] += -(h * f.drag_factor * self.speed[k]) * (s.v - f.air);
        }
    }

    /// The grab spring gave `state` `impulse`, N·s.
    pub fn grabbed(&mut self, state: u32, impulse: Vec3) {
        if let Ok(k) = self.bodies.binary_search(&state) {
            self.grab[k] += impulse;
        }
    }
}
