//! Archimedes: the displaced air pushes up with its weight, at the centroid of
//! the displaced volume (the centre of buoyancy). That point lies above the
//! centre of mass (the knot and neck are heavy), so a tilted balloon feels a
//! torque back to upright: balloons right themselves by physics, from any
//! angle, with no torque written toward "up".

use glam::Vec3;

/// N. `air_density` kg/m³ (1.204 at 20 °C), `volume` m³ (≈ 0.0142 for 11″).
#[inline]
pub fn buoyancy_force(air_density: f32, volume: f32, gravity: Vec3) -> Vec3 {
    -air_density * volume * gravity
}

/// N·m about the centre of mass, with `arm` the centre of buoyancy's offset from it (world frame).
#[inline]
pub fn buoyancy_torque(arm: Vec3, force: Vec3) -> Vec3 {
    arm.cross(force)
}
