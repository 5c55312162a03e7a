//! The air in the room, and the densities that follow from it (ideal gas).

use serde::{Deserialize, Serialize};

/// Specific gas constant of dry air, J/(kg·K).
pub const R_AIR: f32 = 287.05;
/// Specific gas constant of helium, J/(kg·K).
pub const R_HELIUM: f32 = 2077.1;

/// Temperature and pressure of the room's air.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Atmosphere {
    /// K; typical 293.15 (20 °C).
    pub temperature_k: f32,
    /// Pa; typical 101 325 (sea level).
    pub pressure_pa: f32,
}

impl Default for Atmosphere {
    fn default() -> Self {
        Self {
            temperature_k: 293.15,
            pressure_pa: 101_325.0,
        }
    }
}

impl Atmosphere {
    /// kg/m³; 1.204 at 20 °C and 101.325 kPa.
    pub fn air_density(&self) -> f32 {
        self.pressure_pa / (R_AIR * self.temperature_k)
    }

    /// kg/m³ of helium at the room's temperature and pressure; 0.166 at 20 °C.
    /// (A latex balloon's overpressure is a few hundred Pa: under 1 %, ignored.)
    pub fn helium_density(&self) -> f32 {
        self.pressure_pa / (R_HELIUM * self.temperature_k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn densities_match_the_reference_at_20_celsius() {
        let a = Atmosphere::default();
        assert!(
            (a.air_density() - 1.204).abs() < 0.002,
            "{}",
            a.air_density()
        );
        assert!(
            (a.helium_density() - 0.166).abs() < 0.001,
            "{}",
            a.helium_density()
        );
    }
}
