//! What a balloon's skin is made of, and how fast gas goes through it.
//!
//! Permeation through a membrane: dn/dt = −Π·A·Δp/h (mol/s), with Π the
//! material's permeability, A the area and h the thickness. A latex
//! balloon's wall thins as it stretches (rubber keeps its volume), so at
//! scale s of its fill size its area is A·s² and its thickness h/s²: the
//! loss grows like s⁴. A foil balloon's envelope hardly stretches: constant
//! A and h. `EnvelopeDef::helium_permeance` holds Π·A/h at the fill size.

use serde::{Deserialize, Serialize};

/// Permeability of natural rubber to helium, mol·m/(m²·s·Pa): 31 Barrer
/// (polymer handbooks give 25–35), 1 Barrer = 3.35·10⁻¹⁶ mol·m/(m²·s·Pa).
pub const LATEX_HELIUM_PERMEABILITY: f64 = 31.0 * BARRER;
/// Air's permeability over helium's through natural rubber: nitrogen 8.1
/// and oxygen 23.3 Barrer, mixed 79:21, against helium's 31.
pub const LATEX_AIR_RATIO: f64 = 0.36;
/// kg/m³ of natural rubber latex.
pub const LATEX_DENSITY: f64 = 930.0;
/// The factor that brings the handbook's permeability to the float times
/// balloons show: 0.593 puts an untreated 11″ balloon on a 1.5 m ribbon
/// down from the ceiling at 15 h, the middle of the retail charts' 12–18 h (the wall of a
/// real balloon is not even, the latex is compounded, and the gas warms).
/// Fitted, not measured: `gas::calibration` tests it.
pub const LATEX_CALIBRATION: f64 = 0.593;
/// Helium permeance of a Hi-Float treated balloon over an untreated one: a
/// gel on the inside wall. 0.2 puts an 11″ balloon's fall at ≈ 3 days,
/// the middle of the charts' 2–4 days (a fit: makers claim "up to 25×").
pub const HI_FLOAT_FACTOR: f64 = 0.2;
/// Helium permeance of an 18″ foil (metallised nylon) balloon, mol/(s·Pa):
/// fitted so it stays taut ≈ 4 days (charts: taut 3–5 days, afloat ≥ 2
/// weeks); it then floats for weeks more. Air barely enters metallised film.
pub const FOIL_HELIUM_PERMEANCE: f64 = 4.1e-13;
/// Pa above the room inside a latex balloon: the rubber's tension. Party
/// balloons hold 1–3 kPa, and past the inflation curve's peak the pressure
/// hardly changes with size, so one figure serves (a simplification).
pub const LATEX_OVERPRESSURE_PA: f32 = 2000.0;
/// Pa above the room inside a foil balloon filled taut (a guess: foil is
/// filled until the seams' wrinkles just go).
pub const FOIL_OVERPRESSURE_PA: f32 = 2500.0;

const BARRER: f64 = 3.35e-16;

/// The envelope's material.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum EnvelopeKind {
    /// Stretches with its gas: the volume follows the gas at the
    /// overpressure, and the wall thins as it grows.
    #[default]
    Latex,
    /// Inextensible: taut at its full volume while the gas would fill more
    /// (the pressure inside rises instead), slack and shrinking below it.
    Foil,
}

/// A balloon's envelope and fill, for `World::fill`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EnvelopeDef {
    pub kind: EnvelopeKind,
    /// kg of everything but the gas: envelope, knot, valve.
    pub solid_mass: f32,
    /// Share of helium in the fill gas, by moles: 1 helium, 0 air.
    pub helium_fraction: f32,
    /// mol/(s·Pa): Π·A/h of the whole envelope at its fill size, helium.
    pub helium_permeance: f64,
    /// Air's permeance over helium's, ≥ 0.
    pub air_ratio: f64,
    /// Pa above the room's pressure inside: latex's tension, or the foil's
    /// fill pressure when taut.
    pub overpressure_pa: f32,
}

impl EnvelopeDef {
    /// A latex balloon: `envelope_mass` kg of latex over `envelope_area` m²
    /// (its wall h = m/(ρ·A)), `solid_mass` kg in all without the gas, its
    /// permeance times `treatment` (1 untreated, `HI_FLOAT_FACTOR` treated).
    pub fn latex(
        solid_mass: f32,
        envelope_mass: f32,
        envelope_area: f32,
        treatment: f64,
        helium_fraction: f32,
    ) -> Self {
        let area = f64::from(envelope_area);
        let thickness = f64::from(envelope_mass) / (LATEX_DENSITY * area);
        Self {
            kind: EnvelopeKind::Latex,
            solid_mass,
            helium_fraction,
            helium_permeance: LATEX_CALIBRATION * LATEX_HELIUM_PERMEABILITY * area / thickness
                * treatment,
            air_ratio: LATEX_AIR_RATIO,
            overpressure_pa: LATEX_OVERPRESSURE_PA,
        }
    }

    /// A foil balloon of `solid_mass` kg, its permeance scaled from the 18″'s
    /// by `area_ratio` (its envelope's area over an 18″'s).
    pub fn foil(solid_mass: f32, area_ratio: f64, helium_fraction: f32) -> Self {
        Self {
            kind: EnvelopeKind::Foil,
            solid_mass,
            helium_fraction,
            helium_permeance: FOIL_HELIUM_PERMEANCE * area_ratio,
            air_ratio: 0.0,
            overpressure_pa: FOIL_OVERPRESSURE_PA,
        }
    }

    /// The checks `World::fill` makes: the key that is wrong and what it must be.
    pub(crate) fn problem(&self) -> Option<(&'static str, f64, &'static str)> {
        let checks: [(&'static str, f64, bool, &'static str); 5] = [
            (
                "envelope.solid_mass",
                f64::from(self.solid_mass),
                self.solid_mass > 0.0,
                "> 0 kg",
            ),
            (
                "envelope.helium_fraction",
                f64::from(self.helium_fraction),
                (0.0..=1.0).contains(&self.helium_fraction),
                "0 to 1",
            ),
            (
                "envelope.helium_permeance",
                self.helium_permeance,
                self.helium_permeance >= 0.0,
                "≥ 0 mol/(s·Pa)",
            ),
            (
                "envelope.air_ratio",
                self.air_ratio,
                self.air_ratio >= 0.0,
                "≥ 0",
            ),
            (
                "envelope.overpressure_pa",
                f64::from(self.overpressure_pa),
                (0.0..=50_000.0).contains(&self.overpressure_pa),
                "0 to 50 000 Pa",
            ),
        ];
        checks
            .into_iter()
            .find(|&(_, v, ok, _)| !(ok && v.is_finite()))
            .map(|(key, v, _, expected)| (key, v, expected))
    }
}
