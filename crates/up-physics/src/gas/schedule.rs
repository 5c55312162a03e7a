//! The room's temperature over a run: points (s, K), linear between them,
//! held before the first and after the last.

use serde::{Deserialize, Serialize};

/// Temperature against time, piecewise linear.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TemperatureSchedule {
    /// (seconds from the start, kelvin), in increasing time.
    pub points: Vec<(f64, f32)>,
}

impl TemperatureSchedule {
    /// The problem with the points, if any: out of order, or not a temperature.
    pub fn problem(&self) -> Option<String> {
        for (i, &(t, k)) in self.points.iter().enumerate() {
            if !(t.is_finite() && t >= 0.0) {
                return Some(format!("point {i}: time {t} s, expected ≥ 0"));
            }
            if !(k.is_finite() && k > 0.0) {
                return Some(format!("point {i}: temperature {k} K, expected > 0"));
            }
            if i > 0 && t <= self.points[i - 1].0 {
                return Some(format!(
                    "point {i}: time {t} s does not come after the previous point's {} s",
                    self.points[i - 1].0
                ));
            }
        }
        None
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// K at `time` s; None without points.
    pub fn at(&self, time: f64) -> Option<f32> {
        let (first, last) = (self.points.first()?, self.points.last()?);
        if time <= first.0 {
            return Some(first.1);
        }
        if time >= last.0 {
            return Some(last.1);
        }
        let k = self.points.partition_point(|p| p.0 <= time);
        let ((t0, k0), (t1, k1)) = (self.points[k - 1], self.points[k]);
        let f = ((time - t0) / (t1 - t0)) as f32;
        Some(k0 + (k1 - k0) * f)
    }

    /// The first point strictly after `time`, s: where the slope changes.
    pub fn next_knot(&self, time: f64) -> Option<f64> {
        self.points.iter().map(|p| p.0).find(|&t| t > time)
    }
}
