//! Integrating velocities under the step's forces (`forces::BodyForces`), once per substep.

use glam::Vec3;
use up_geom::norm::Norm;

use super::body_state::BodyState;
use super::parallel;
use crate::forces::BodyForces;
use crate::quarantine;

/// A soft spring pulling a point of one body toward a target (the mouse).
#[derive(Clone, Copy, Debug)]
pub(crate) struct GrabSpring {
    pub state: u32,
    /// Grabbed point from the centre of mass, body frame at the step start... rotated by dq.
    pub anchor: Vec3,
    /// World centre of mass at the step start.
    pub center0: Vec3,
    pub target: Vec3,
    /// N/m and N·s/m, from the body's mass so any balloon follows alike.
    pub stiffness: f32,
    pub damping: f32,
    pub max_force: f32,
}

/// v ← (v + h·F/m) / (1 + h·k|v|/m): drag taken implicitly, so that a balloon
/// thrown at 30 m/s cannot overshoot, and the terminal velocity is exact.
/// In moving air u (`BodyForces::air`) the drag is on v − u:
/// v ← (v + h·F/m + h·k|v − u|·u/m) / (1 + h·k|v − u|/m), the relative speed
/// taken at the substep's start as the speed is in still air. Where u is zero
/// the still-air form runs, so still air gives the same bits as before.
///
/// The added mass (in m, `forces::drag`) multiplies the body's own
/// acceleration, not its acceleration relative to the air: the air's own
/// acceleration (and the pressure gradient that drives it) is left out,
/// which is exact in a steady, uniform stream and a fair guess in a jet,
/// whose air changes speed over metres while a balloon crosses it.
pub(crate) fn integrate_velocities(
    states: &mut [BodyState],
    forces: &[BodyForces],
    awake: &[u32],
    angular_damping: f32,
    h: f32,
) {
    parallel::for_each_body(awake, states, |i, s| {
        integrate_velocity(s, &forces[i as usize], angular_damping, h)
    });
}

/// `integrate_velocities` for one body's state `s` under its forces `f`.
#[inline]
pub(crate) fn integrate_velocity(s: &mut BodyState, f: &BodyForces, angular_damping: f32, h: f32) {
    if s.runaway {
        return; // frozen until the step ends (its forces may be infinite)
    }
    let torque = f.torque_at(s.q, s.v);
    if f.air == Vec3::ZERO {
        let speed_damping = h * f.drag_factor * s.v.norm() * s.inv_mass;
        s.v = (s.v + h * s.inv_mass * f.force) / (1.0 + speed_damping);
    } else {
        let speed_damping = h * f.drag_factor * (s.v - f.air).norm() * s.inv_mass;
        let pushed = s.v + h * s.inv_mass * f.force + speed_damping * f.air;
        s.v = pushed / (1.0 + speed_damping);
    }
    s.w = (s.w + h * (s.inv_inertia * torque)) / (1.0 + h * angular_damping);
    if s.inv_mass > 0.0 && !quarantine::is_sane_motion(s.v, s.w) {
        s.freeze_runaway();
    }
}

/// The grab spring's pull on its body over substep `h`; returns the impulse, N·s.
pub(crate) fn apply_grab(states: &mut [BodyState], g: &GrabSpring, h: f32) -> Vec3 {
    let s = &mut states[g.state as usize];
    let r = s.dq * g.anchor;
    let point = g.center0 + s.dp + r;
    let mut force = g.stiffness * (g.target - point) - g.damping * s.point_velocity(r);
    let len = force.norm();
    if len > g.max_force {
        force *= g.max_force / len;
    }
    s.apply_impulse(h * force, r);
    h * force
}
