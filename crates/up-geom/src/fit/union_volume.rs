//! The exact volume of a union of spheres whose centres lie on one line.
//!
//! Along the line, the union's cross-section at `t` is a disc of area
//! `π · maxᵢ (rᵢ² − (t − cᵢ)²)`. Two of these parabolas differ by a linear
//! function of `t`, so the winner changes only where two of them cross or
//! where one reaches zero; between those breakpoints a single sphere wins and
//! its slice integrates in closed form.

use super::axial_cover::AxialSphere;

/// m³: the volume of the union of the spheres (all centred on one axis).
pub fn union_volume_on_axis(spheres: &[AxialSphere]) -> f64 {
    let mut breaks: Vec<f64> = Vec::with_capacity(spheres.len() * (spheres.len() + 1));
    for (i, a) in spheres.iter().enumerate() {
        breaks.push(a.t - a.radius);
        breaks.push(a.t + a.radius);
        for b in &spheres[i + 1..] {
            if a.t != b.t {
                // r_a² − (t − c_a)² = r_b² − (t − c_b)²  ⇒  linear in t.
                let t = (a.radius * a.radius - b.radius * b.radius + b.t * b.t - a.t * a.t)
                    / (2.0 * (b.t - a.t));
                breaks.push(t);
            }
        }
    }
    breaks.retain(|t| t.is_finite());
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let slice = |s: &AxialSphere, t: f64| s.radius * s.radius - (t - s.t) * (t - s.t);
    let mut volume = 0.0;
    for w in breaks.windows(2) {
        let (u, v) = (w[0], w[1]);
        let mid = 0.5 * (u + v);
        let winner = spheres
            .iter()
            .max_by(|a, b| slice(a, mid).total_cmp(&slice(b, mid)));
        let Some(s) = winner else { continue };
        if slice(s, mid) <= 0.0 {
            continue;
        }
        let cube = |x: f64| x * x * x;
        volume += s.radius * s.radius * (v - u) - (cube(v - s.t) - cube(u - s.t)) / 3.0;
    }
    volume * std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn one_sphere() {
        let v = union_volume_on_axis(&[AxialSphere {
            t: 3.0,
            radius: 2.0,
        }]);
        assert!((v - 4.0 / 3.0 * PI * 8.0).abs() < 1e-9);
    }

    #[test]
    fn nested_spheres_count_once() {
        let s = [
            AxialSphere {
                t: 0.0,
                radius: 1.0,
            },
            AxialSphere {
                t: 0.2,
                radius: 0.5,
            },
        ];
        assert!((union_volume_on_axis(&s) - 4.0 / 3.0 * PI).abs() < 1e-9);
    }

    #[test]
    fn two_equal_overlapping_spheres_subtract_the_lens() {
        // Unit spheres 1 apart: the lens has volume π (4r + d)(2r − d)² / 12.
        let s = [
            AxialSphere {
                t: 0.0,
                radius: 1.0,
            },
            AxialSphere {
                t: 1.0,
                radius: 1.0,
            },
        ];
        let lens = PI * (4.0 + 1.0) * 1.0 / 12.0;
        let expected = 2.0 * 4.0 / 3.0 * PI - lens;
        assert!((union_volume_on_axis(&s) - expected).abs() < 1e-9);
    }

    #[test]
    fn disjoint_spheres_add() {
        let s = [
            AxialSphere {
                t: 0.0,
                radius: 1.0,
            },
            AxialSphere {
                t: 5.0,
                radius: 0.5,
            },
        ];
        let expected = 4.0 / 3.0 * PI * (1.0 + 0.125);
        assert!((union_volume_on_axis(&s) - expected).abs() < 1e-9);
    }
}
