//! The accepted range of each world parameter that a scene can set, written
//! once: `WorldDef::validate`, the scene's checks (up-scene) and the page
//! (through up-wasm) all read these.

use serde::Serialize;

/// A closed range `[min, max]`, or `(min, max]` when `min_exclusive`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Limit {
    pub min: f32,
    pub max: f32,
    pub min_exclusive: bool,
    /// The unit of the values ("" for a pure number).
    pub unit: &'static str,
}

impl Limit {
    const fn closed(min: f32, max: f32, unit: &'static str) -> Limit {
        Limit {
            min,
            max,
            min_exclusive: false,
            unit,
        }
    }

    const fn above(min: f32, max: f32, unit: &'static str) -> Limit {
        Limit {
            min,
            max,
            min_exclusive: true,
            unit,
        }
    }

    /// Whether `value` is finite and inside.
    pub fn contains(&self, value: f32) -> bool {
        let above = if self.min_exclusive {
            value > self.min
        } else {
            value >= self.min
        };
        value.is_finite() && above && value <= self.max
    }

    /// "a finite number in [0, 10]", with the unit if there is one.
    pub fn describe(&self) -> String {
        let open = if self.min_exclusive { '(' } else { '[' };
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        format!("a finite number in {open}{}, {}]{unit}", self.min, self.max)
    }
}

/// s per step.
pub const DT: Limit = Limit::above(0.0, 0.1, "s");
/// Solver substeps per step (whole numbers).
pub const SUBSTEPS: Limit = Limit::closed(1.0, 64.0, "");
pub const FRICTION: Limit = Limit::closed(0.0, 10.0, "");
pub const RESTITUTION: Limit = Limit::closed(0.0, 1.0, "");
pub const DRAG_COEFFICIENT: Limit = Limit::closed(0.0, 10.0, "");
pub const ADDED_MASS_COEFFICIENT: Limit = Limit::closed(0.0, 10.0, "");
pub const ANGULAR_DAMPING: Limit = Limit::closed(0.0, 1000.0, "1/s");
pub const CONTACT_HERTZ: Limit = Limit::above(0.0, 10_000.0, "Hz");
pub const CONTACT_DAMPING_RATIO: Limit = Limit::closed(0.0, 1000.0, "");

/// Every limit above by the scene key that sets it (`[sim]` in a scene file).
pub const SIM_LIMITS: [(&str, Limit); 9] = [
    ("dt", DT),
    ("substeps", SUBSTEPS),
    ("friction", FRICTION),
    ("restitution", RESTITUTION),
    ("drag_coefficient", DRAG_COEFFICIENT),
    ("added_mass_coefficient", ADDED_MASS_COEFFICIENT),
    ("angular_damping", ANGULAR_DAMPING),
    ("contact_hertz", CONTACT_HERTZ),
    ("contact_damping_ratio", CONTACT_DAMPING_RATIO),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_hold_their_ends_as_described() {
        assert!(FRICTION.contains(0.0) && FRICTION.contains(10.0));
        assert!(!FRICTION.contains(10.5) && !FRICTION.contains(-0.1));
        assert!(!DT.contains(0.0) && DT.contains(0.1) && !DT.contains(f32::NAN));
        assert_eq!(FRICTION.describe(), "a finite number in [0, 10]");
        assert_eq!(DT.describe(), "a finite number in (0, 0.1] s");
    }
}
