//! The gas in one balloon: moles of helium and of air, and what follows from
//! them in the room's air (ideal gas): volume, size, mass and lift.

use serde::{Deserialize, Serialize};

use super::envelope::{EnvelopeDef, EnvelopeKind};
use crate::forces::atmosphere::Atmosphere;

/// J/(mol·K).
pub const GAS_CONSTANT: f64 = 8.314_462_618;
/// kg/mol.
pub const HELIUM_MOLAR_MASS: f64 = 4.002_602e-3;
/// kg/mol, dry air.
pub const AIR_MOLAR_MASS: f64 = 28.964_7e-3;
/// The smallest size a balloon takes, over its fill size: an emptied
/// envelope is still rubber or foil (an 11″ latex balloon's is ≈ 7 cm
/// across), so it is never collided or drawn smaller.
pub const MIN_SCALE: f32 = 0.25;
/// Longest stretch, s, integrated in one Runge–Kutta step: the gas changes
/// over hours, so a minute's step is exact to far below what matters.
pub const MAX_GAS_STEP_S: f64 = 60.0;

/// The gas of one balloon and its envelope.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Gas {
    pub envelope: EnvelopeDef,
    /// mol.
    pub helium_mol: f64,
    /// mol.
    pub air_mol: f64,
    /// m³: the volume at scale 1 (the shape's); a foil balloon's most.
    pub full_volume: f64,
    /// kg: the gas's lift at fill (displaced air less the gas), for the share left.
    pub fill_lift_kg: f64,
    /// s the world has run on since this gas was last advanced: the world
    /// advances gas a second at a time (`world::gas`).
    #[serde(default)]
    pub(crate) owed_s: f64,
}

/// Temperature and pressure, f64.
#[derive(Clone, Copy, Debug)]
struct Air {
    temperature_k: f64,
    pressure_pa: f64,
}

impl From<&Atmosphere> for Air {
    fn from(a: &Atmosphere) -> Self {
        Air {
            temperature_k: f64::from(a.temperature_k),
            pressure_pa: f64::from(a.pressure_pa),
        }
    }
}

impl Air {
    /// kg/m³.
    fn density(&self) -> f64 {
        self.pressure_pa * AIR_MOLAR_MASS / (GAS_CONSTANT * self.temperature_k)
    }
}

impl Gas {
    /// A balloon filled to `full_volume` m³ in `air`, with the envelope's
    /// overpressure inside.
    pub fn fill(envelope: EnvelopeDef, full_volume: f64, air: &Atmosphere) -> Gas {
        let a = Air::from(air);
        let p = a.pressure_pa + f64::from(envelope.overpressure_pa);
        let moles = p * full_volume / (GAS_CONSTANT * a.temperature_k);
        let x = f64::from(envelope.helium_fraction);
        let mut gas = Gas {
            envelope,
            helium_mol: moles * x,
            air_mol: moles * (1.0 - x),
            full_volume,
            fill_lift_kg: 0.0,
            owed_s: 0.0,
        };
        gas.fill_lift_kg = gas.gas_lift_kg(air);
        gas
    }

    /// mol.
    pub fn moles(&self) -> f64 {
        self.helium_mol + self.air_mol
    }

    /// (m³, Pa): the volume and the pressure inside for `moles` in `air`.
    fn volume_and_pressure(&self, moles: f64, a: &Air) -> (f64, f64) {
        let rt = GAS_CONSTANT * a.temperature_k;
        let over = f64::from(self.envelope.overpressure_pa);
        match self.envelope.kind {
            EnvelopeKind::Latex => {
                let p = a.pressure_pa + over;
                (moles * rt / p, p)
            }
            EnvelopeKind::Foil => {
                // Slack: the room's pressure. Taut: whatever the gas needs.
                let slack = moles * rt / a.pressure_pa;
                if slack <= self.full_volume {
                    (slack, a.pressure_pa)
                } else {
                    (self.full_volume, moles * rt / self.full_volume)
                }
            }
        }
    }

    /// m³.
    pub fn volume(&self, air: &Atmosphere) -> f64 {
        self.volume_and_pressure(self.moles(), &Air::from(air)).0
    }

    /// Pa inside.
    pub fn pressure(&self, air: &Atmosphere) -> f64 {
        self.volume_and_pressure(self.moles(), &Air::from(air)).1
    }

    /// Linear size over the fill's: (V / V_full)^⅓, at least `MIN_SCALE`.
    pub fn scale(&self, air: &Atmosphere) -> f32 {
        (libm::cbrt(self.volume(air) / self.full_volume) as f32).max(MIN_SCALE)
    }

    /// kg of gas.
    pub fn gas_mass(&self) -> f64 {
        self.helium_mol * HELIUM_MOLAR_MASS + self.air_mol * AIR_MOLAR_MASS
    }

    /// kg: the whole balloon, gas and envelope.
    pub fn mass(&self) -> f64 {
        f64::from(self.envelope.solid_mass) + self.gas_mass()
    }

    /// kg: the air the balloon displaces less its gas: what the gas lifts.
    pub fn gas_lift_kg(&self, air: &Atmosphere) -> f64 {
        Air::from(air).density() * self.volume(air) - self.gas_mass()
    }

    /// kg: displaced air less the whole balloon (its free lift; negative
    /// when it sinks).
    pub fn free_lift_kg(&self, air: &Atmosphere) -> f64 {
        self.gas_lift_kg(air) - f64::from(self.envelope.solid_mass)
    }

    /// The gas's lift now over at fill: 1 full, 0 none left.
    pub fn lift_fraction(&self, air: &Atmosphere) -> f64 {
        if self.fill_lift_kg > 0.0 {
            self.gas_lift_kg(air) / self.fill_lift_kg
        } else {
            0.0
        }
    }

    /// (d helium, d air)/dt, mol/s, for the amounts (he, ai).
    fn rates(&self, he: f64, ai: f64, a: &Air) -> (f64, f64) {
        let moles = he + ai;
        if moles <= 0.0 {
            return (0.0, 0.0);
        }
        let (volume, pressure) = self.volume_and_pressure(moles, a);
        let stretch = match self.envelope.kind {
            // Area s², thickness 1/s²: s⁴ = (V/V_full)^{4/3}.
            EnvelopeKind::Latex => {
                let s = libm::cbrt(volume / self.full_volume);
                let s2 = s * s;
                s2 * s2
            }
            EnvelopeKind::Foil => 1.0,
        };
        let k = self.envelope.helium_permeance * stretch;
        let helium = -k * (he / moles) * pressure;
        // The room's air is (nearly) all "air": its partial pressure is the room's.
        let air = k * self.envelope.air_ratio * (a.pressure_pa - (ai / moles) * pressure);
        (helium, air)
    }

    /// Advances the gas by `seconds` in `air` (held over the stretch), by
    /// classical Runge–Kutta in steps of at most `MAX_GAS_STEP_S`.
    pub fn advance(&mut self, seconds: f64, air: &Atmosphere) {
        if seconds <= 0.0 || self.envelope.helium_permeance == 0.0 {
            return;
        }
        let a = Air::from(air);
        let steps = libm::ceil(seconds / MAX_GAS_STEP_S).max(1.0);
        let h = seconds / steps;
        for _ in 0..steps as u64 {
            self.runge_kutta(h, &a);
        }
    }

    fn runge_kutta(&mut self, h: f64, a: &Air) {
        let (he, ai) = (self.helium_mol, self.air_mol);
        let k1 = self.rates(he, ai, a);
        let k2 = self.rates(he + 0.5 * h * k1.0, ai + 0.5 * h * k1.1, a);
        let k3 = self.rates(he + 0.5 * h * k2.0, ai + 0.5 * h * k2.1, a);
        let k4 = self.rates(he + h * k3.0, ai + h * k3.1, a);
        let d =
            |i: fn(&(f64, f64)) -> f64| h / 6.0 * (i(&k1) + 2.0 * i(&k2) + 2.0 * i(&k3) + i(&k4));
        self.helium_mol = (he + d(|k| k.0)).max(0.0);
        self.air_mol = (ai + d(|k| k.1)).max(0.0);
    }
}
