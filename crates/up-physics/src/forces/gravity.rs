//! Gravity on the full mass: envelope, knot and gas.

use glam::Vec3;

/// N. `mass` in kg (≈ 0.0054 for 11″), `gravity` in m/s² (0, −9.81, 0).
#[inline]
pub fn gravity_force(mass: f32, gravity: Vec3) -> Vec3 {
    mass * gravity
}
