//! Order statistics of per-step wall times.

/// The `q`-quantile (0–1) of `samples` by the nearest-rank method; `NaN` when empty.
pub fn quantile(samples: &[f64], q: f64) -> f64 {
    if samples.is_empty() {
        return f64::NAN;
    }
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    let rank = (q.clamp(0.0, 1.0) * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

pub fn median(samples: &[f64]) -> f64 {
    quantile(samples, 0.5)
}

pub fn mean(samples: &[f64]) -> f64 {
    if samples.is_empty() {
        return f64::NAN;
    }
    samples.iter().sum::<f64>() / samples.len() as f64
}

/// The settled part of a run: its last third (at least one step).
pub fn settled(samples: &[f64]) -> &[f64] {
    let start = samples.len() - samples.len().div_ceil(3);
    &samples[start..]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_by_nearest_rank() {
        let s: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(median(&s), 50.0);
        assert_eq!(quantile(&s, 0.95), 95.0);
        assert_eq!(quantile(&[3.0], 0.95), 3.0);
        assert!(median(&[]).is_nan());
        assert_eq!(mean(&[1.0, 2.0, 6.0]), 3.0);
    }

    #[test]
    fn settled_is_the_last_third() {
        let s: Vec<f64> = (0..9).map(f64::from).collect();
        assert_eq!(settled(&s), &[6.0, 7.0, 8.0]);
        assert_eq!(settled(&s[..1]), &[0.0]);
        assert_eq!(settled(&s[..4]).len(), 2);
    }
}
