//! When a source blows: a list of on intervals, with a spin-up and a
//! run-down instead of a step, so that switching a fan on is not an impulse.

use serde::{Deserialize, Serialize};

/// Seconds a source takes to reach full speed after it is switched on (and
/// to stop after it is switched off). A household fan's blades spin up in
/// about a second or two: a guess, not a measurement.
pub const SPIN_UP_S: f64 = 1.0;

/// On intervals `[start, end]`, s of simulated time. Empty means always on.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Schedule {
    pub on: Vec<[f64; 2]>,
}

impl Schedule {
    pub fn always() -> Schedule {
        Schedule { on: Vec::new() }
    }

    /// How hard the source blows at `t`, 0 (off) to 1 (full): the strongest
    /// of its intervals, each ramped smoothly over `SPIN_UP_S` at both ends.
    /// An interval that starts at or before 0 is at full speed from the start.
    pub fn level_at(&self, t: f64) -> f32 {
        if self.on.is_empty() {
            return 1.0;
        }
        let level = |&[start, end]: &[f64; 2]| {
            let up = if start <= 0.0 {
                1.0
            } else {
                ramp((t - start) / SPIN_UP_S)
            };
            up * (1.0 - ramp((t - end) / SPIN_UP_S))
        };
        self.on.iter().map(level).fold(0.0, f64::max) as f32
    }

    pub fn validate(&self) -> Result<(), String> {
        for (i, &[start, end]) in self.on.iter().enumerate() {
            if !(start.is_finite() && end.is_finite() && start <= end) {
                return Err(format!(
                    "on[{i}]: expected [start, end] with start <= end, got [{start}, {end}]"
                ));
            }
        }
        Ok(())
    }
}

/// 0 before 0, 1 after 1, smoothstep between.
fn ramp(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}
