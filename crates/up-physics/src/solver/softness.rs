//! Soft constraint coefficients (Box2D v3's "soft step").
//!
//! A contact behaves like an implicit spring-damper of the given frequency
//! and damping ratio, relative to the constraint's effective mass; with
//! substepping this stays stable at any mass ratio, and the relax pass then
//! removes the velocity the push-out added so piles do not jitter.

/// Coefficients of a soft constraint for substep `h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Softness {
    /// Fraction of the position error turned into velocity per second, 1/s.
    pub bias_rate: f32,
    /// Scales the effective mass, in [0, 1].
    pub mass_scale: f32,
    /// Scales the accumulated impulse fed back, in [0, 1].
    pub impulse_scale: f32,
}

impl Softness {
    pub fn new(hertz: f32, damping_ratio: f32, h: f32) -> Self {
        if hertz <= 0.0 {
            return Self {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            };
        }
        let omega = 2.0 * std::f32::consts::PI * hertz;
        let a1 = 2.0 * damping_ratio + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Self {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_when_hertz_is_zero_and_soft_otherwise() {
        let rigid = Softness::new(0.0, 1.0, 1.0 / 240.0);
        assert_eq!(
            rigid,
            Softness {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0
            }
        );
        let soft = Softness::new(30.0, 10.0, 1.0 / 240.0);
        // mass_scale + impulse_scale = 1: the spring and the damper share the constraint.
        assert!((soft.mass_scale + soft.impulse_scale - 1.0).abs() < 1e-6);
        assert!(soft.bias_rate > 0.0 && soft.mass_scale > 0.0 && soft.mass_scale < 1.0);
    }
}
