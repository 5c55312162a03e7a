//! Measuring how well spheres cover a surface: points spread over the
//! triangles (every vertex, plus points drawn uniformly by area with a fixed
//! seed) and, for each, how far it lies outside the nearest sphere.

use glam::Vec3;

use crate::shape::sphere::Sphere;
use crate::split_mix::SplitMix64;

/// A point counts as covered when it lies at most this far outside a sphere (m).
pub const COVERAGE_TOLERANCE_M: f32 = 0.001;

/// The result of a coverage measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coverage {
    /// Share of sample points covered within `COVERAGE_TOLERANCE_M`, 0..=1.
    pub covered: f32,
    /// m: the largest distance of a sample point outside every sphere (0 when all are inside).
    pub max_uncovered_distance: f32,
    /// Number of sample points.
    pub samples: usize,
}

/// Points on the surface: all vertices used by a triangle, then about
/// `random_points` more, drawn uniformly over the area with `seed`.
pub fn surface_samples(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    random_points: usize,
    seed: u64,
) -> Vec<Vec3> {
    let mut used = vec![false; vertices.len()];
    for t in triangles {
        for &i in t {
            used[i as usize] = true;
        }
    }
    let mut points: Vec<Vec3> = vertices
        .iter()
        .zip(&used)
        .filter(|(_, &u)| u)
        .map(|(&p, _)| p)
        .collect();
    // Cumulative areas, then inverse-CDF picks: uniform over the surface.
    let mut cumulative = Vec::with_capacity(triangles.len());
    let mut total = 0.0f64;
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize].as_dvec3());
        total += 0.5 * (b - a).cross(c - a).length();
        cumulative.push(total);
    }
    if total <= 0.0 {
        return points;
    }
    let mut rng = SplitMix64::new(seed);
    for _ in 0..random_points {
        let pick = rng.unit_f64() * total;
        let k = cumulative
            .partition_point(|&c| c <= pick)
            .min(triangles.len() - 1);
        let [a, b, c] = triangles[k].map(|i| vertices[i as usize].as_dvec3());
        let (mut u, mut v) = (rng.unit_f64(), rng.unit_f64());
        if u + v > 1.0 {
            (u, v) = (1.0 - u, 1.0 - v);
        }
        points.push((a + (b - a) * u + (c - a) * v).as_vec3());
    }
    points
}

/// How well `spheres` cover `points`.
pub fn measure_coverage(points: &[Vec3], spheres: &[Sphere]) -> Coverage {
    let mut covered = 0usize;
    let mut max_out = 0.0f32;
    for &p in points {
        let outside = spheres
            .iter()
            .map(|s| p.distance(s.center) - s.radius)
            .fold(f32::INFINITY, f32::min)
            .max(0.0);
        if outside <= COVERAGE_TOLERANCE_M {
            covered += 1;
        }
        max_out = max_out.max(outside);
    }
    let share = if points.is_empty() {
        0.0
    } else {
        covered as f32 / points.len() as f32
    };
    Coverage {
        covered: share,
        max_uncovered_distance: max_out,
        samples: points.len(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_deterministic_and_on_the_triangle() {
        let v = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let t = [[0u32, 1, 2]];
        let a = surface_samples(&v, &t, 100, 7);
        assert_eq!(a, surface_samples(&v, &t, 100, 7));
        assert_eq!(a.len(), 103);
        assert!(a
            .iter()
            .all(|p| p.z == 0.0 && p.x >= 0.0 && p.y >= 0.0 && p.x + p.y <= 1.0 + 1e-6));
    }

    #[test]
    fn coverage_counts_points_outside_beyond_tolerance() {
        let points = [
            Vec3::ZERO,
            Vec3::new(1.0005, 0.0, 0.0),
            Vec3::new(1.1, 0.0, 0.0),
        ];
        let c = measure_coverage(&points, &[Sphere::new(Vec3::ZERO, 1.0)]);
        assert!((c.covered - 2.0 / 3.0).abs() < 1e-6);
        assert!((c.max_uncovered_distance - 0.1).abs() < 1e-5);
    }
}
