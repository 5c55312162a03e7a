//! Filling a scene's balloons: the envelope each group's balloons get
//! (`World::fill`), and the spread between balloons of one group.
//!
//! Latex: `EnvelopeDef::latex` from the model's envelope mass over its mesh's
//! surface (the wall's thickness follows), untreated or Hi-Float. Foil:
//! `EnvelopeDef::foil`, the 18″ balloon's permeance scaled by the surface,
//! (d / 18″)² (the mesh keeps its shape as it scales). Air-filled balloons
//! are filled too, with helium fraction 0: no helium to lose, and air that
//! hardly moves through the wall.
//!
//! No two real balloons leak alike (the latex's thickness, the tie, the
//! seal). Each balloon's permeance is its group's times a factor uniform in
//! [0.9, 1.1], drawn in the order the balloons are made from a stream of its
//! own seeded by `sim.seed` (the spawn layout's stream is left as it was).
//! The ±10 % is a guess, not a measurement: it spreads a group's fall from
//! the ceiling over an hour or two, as decorators see, instead of the
//! whole group dropping at once.

use up_geom::SplitMix64;
use up_physics::gas::envelope::HI_FLOAT_FACTOR;
use up_physics::gas::{EnvelopeDef, EnvelopeKind};
use up_physics::{BodyId, PhysicsError, World};

use crate::balloon::BalloonModel;
use crate::scene::{BalloonGroup, GasKind, Treatment, DEFAULT_FOIL_DIAMETER_M};

/// Half the width of the per-balloon permeance factor: [1 − s, 1 + s].
pub const PERMEANCE_SPREAD: f64 = 0.1;
/// Mixed into `sim.seed` for the permeance stream, so that it is not the
/// spawn layout's stream ("gas" in ASCII).
const PERMEANCE_STREAM: u64 = 0x0067_6173;

/// The envelope the balloons of `group` (built as `model`) are filled with,
/// before each balloon's own factor.
pub fn group_envelope(group: &BalloonGroup, model: &BalloonModel) -> EnvelopeDef {
    let helium_fraction = match group.gas {
        GasKind::Helium => 1.0,
        GasKind::Air => 0.0,
    };
    let solid = model.parts.envelope_kg + model.parts.knot_kg;
    match model.spec.kind {
        EnvelopeKind::Latex => {
            let treatment = match group.treatment {
                Treatment::Untreated => 1.0,
                Treatment::HiFloat => HI_FLOAT_FACTOR,
            };
            EnvelopeDef::latex(
                solid,
                model.parts.envelope_kg,
                model.envelope_area_m2,
                treatment,
                helium_fraction,
            )
        }
        EnvelopeKind::Foil => {
            let ratio = f64::from(model.spec.diameter_m / DEFAULT_FOIL_DIAMETER_M);
            EnvelopeDef::foil(solid, ratio * ratio, helium_fraction)
        }
    }
}

/// The stream of per-balloon permeance factors of a scene.
#[derive(Clone, Debug)]
pub struct PermeanceFactors {
    rng: SplitMix64,
}

impl PermeanceFactors {
    /// The factors of the scene whose `sim.seed` is `seed`.
    pub fn new(seed: u64) -> Self {
        Self {
            rng: SplitMix64::new(seed ^ PERMEANCE_STREAM),
        }
    }

    /// The next balloon's factor, uniform in [1 − `PERMEANCE_SPREAD`, 1 + `PERMEANCE_SPREAD`).
    pub fn next_factor(&mut self) -> f64 {
        1.0 - PERMEANCE_SPREAD + 2.0 * PERMEANCE_SPREAD * self.rng.unit_f64()
    }
}

/// `envelope` with its permeance times `factor`.
pub fn with_factor(envelope: &EnvelopeDef, factor: f64) -> EnvelopeDef {
    EnvelopeDef {
        helium_permeance: envelope.helium_permeance * factor,
        ..*envelope
    }
}

/// Fills body `id` with `envelope` times `factor`, filled `hours_before` h
/// before now.
pub fn fill_balloon(
    world: &mut World,
    id: BodyId,
    envelope: &EnvelopeDef,
    factor: f64,
    hours_before: f32,
) -> Result<(), PhysicsError> {
    let age_s = f64::from(hours_before) * 3600.0;
    world.fill(id, &with_factor(envelope, factor), age_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors_are_within_ten_percent_spread_and_repeat() {
        let draw = |seed| {
            let mut f = PermeanceFactors::new(seed);
            (0..2000).map(|_| f.next_factor()).collect::<Vec<_>>()
        };
        let a = draw(7);
        assert_eq!(a, draw(7));
        assert_ne!(a, draw(8));
        assert!(a.iter().all(|f| (0.9..1.1).contains(f)));
        let (lo, hi) = a
            .iter()
            .fold((2.0f64, 0.0f64), |(l, h), &f| (l.min(f), h.max(f)));
        assert!(lo < 0.91 && hi > 1.09, "[{lo}, {hi}]");
        let mean = a.iter().sum::<f64>() / a.len() as f64;
        assert!((mean - 1.0).abs() < 0.005, "mean {mean}");
    }
}
