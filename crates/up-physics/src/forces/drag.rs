//! Quadratic air drag, F = −½·ρ·C_D·A·|v|·v, and added mass.
//!
//! Added mass: accelerating a body in a fluid also accelerates the fluid
//! around it, as if the body were heavier by C_a·ρ·V (C_a = 0.5 for a sphere).
//! It enters the translational inertia only (not the weight): for a balloon it
//! is ≈ 8.5 g against a body mass of ≈ 5.4 g, so without it balloons would
//! accelerate 2.6 times too briskly.

use glam::Vec3;
use up_geom::norm::Norm;

/// The factor k in F = −k·|v|·v: ½·ρ·C_D·A, kg/m.
/// `air_density` kg/m³ (1.204), `drag_coefficient` (0.95), `area` m² (≈ 0.0708).
#[inline]
pub fn drag_factor(air_density: f32, drag_coefficient: f32, area: f32) -> f32 {
    0.5 * air_density * drag_coefficient * area
}

/// N, for velocity `v` (m/s).
#[inline]
pub fn drag_force(drag_factor: f32, v: Vec3) -> Vec3 {
    -drag_factor * v.norm() * v
}

/// kg: C_a·ρ·V. `added_mass_coefficient` 0.5 for a sphere.
#[inline]
pub fn added_mass(added_mass_coefficient: f32, air_density: f32, volume: f32) -> f32 {
    added_mass_coefficient * air_density * volume
}

/// m/s: where drag balances the net lift, v_t = √(2·g·(ρ·V − m) / (ρ·C_D·A)).
/// Negative when the balloon is heavier than air (it then sinks at that speed).
pub fn terminal_velocity(
    gravity: f32,
    air_density: f32,
    volume: f32,
    mass: f32,
    drag_coefficient: f32,
    area: f32,
) -> f32 {
    let net = air_density * volume - mass;
    let v = libm::sqrtf(2.0 * gravity * net.abs() / (air_density * drag_coefficient * area));
    if net >= 0.0 {
        v
    } else {
        -v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_balloon_rises_at_about_1_7_m_per_s() {
        // The physics reference's worked 11″ balloon: V 14.2 L, m 5.4 g, A 0.0708 m².
        let v = terminal_velocity(9.81, 1.204, 0.0142, 0.0054, 0.95, 0.0708);
        assert!((1.6..1.8).contains(&v), "{v}");
        assert!((added_mass(0.5, 1.204, 0.0142) - 0.0085).abs() < 0.0001);
    }
}
