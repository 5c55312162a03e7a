//! Time of impact by binary-search backtracking.
//!
//! The reference method of the original report, made safe: bisection needs
//! a bracket [t0, t1] with distance(t0) > 0 ≥ distance(t1), and the first
//! crossing must be the one bracketed. Sampling only the end points misses
//! grazing passes that touch and separate again before t = 1, so the first
//! crossing is bracketed by a forward scan first:
//! - `toi_bisect_conservative` takes a bound L on |d distance / dt| (for a
//!   sphere moving at v against static geometry, L = |v|). No crossing lies
//!   in [t, t + distance(t)/L] (conservative advancement), so the scan jumps
//!   by that much and never steps over one.
//! - `toi_bisect` knows no bound and scans in uniform steps; passes shorter
//!   than a step can be missed.
//!
//! The bracket is then halved until it is shorter than the tolerance; the
//! returned time is its upper end (touching or just overlapping, never
//! before the impact).

use glam::Vec3;

use super::closest_point_triangle::closest_point_triangle;
use super::contact_sphere_triangle::triangle_unit_normal;
use super::toi_sphere_triangle::BOUNDARY_SLACK;
use crate::Sphere;

/// Uniform steps of the unbounded scan in `toi_bisect`.
pub const SCAN_STEPS: u32 = 256;

/// First t ∈ [0, 1] where `distance(t)` (signed: negative when overlapping)
/// reaches 0, to within `tolerance` (in units of t), found by a uniform scan of
/// `SCAN_STEPS` steps and bisection. `Some(0.0)` when already touching.
pub fn toi_bisect(mut distance: impl FnMut(f32) -> f32, tolerance: f32) -> Option<f32> {
    let mut t0 = 0.0;
    if distance(t0) <= 0.0 {
        return Some(0.0);
    }
    for step in 1..=SCAN_STEPS {
        let t1 = step as f32 / SCAN_STEPS as f32;
        if distance(t1) <= 0.0 {
            return Some(bisect(&mut distance, t0, t1, tolerance));
        }
        t0 = t1;
    }
    None
}

/// Like `toi_bisect`, for a distance whose rate of change never exceeds
/// `max_rate` (distance units per unit t): the scan advances conservatively
/// by `distance(t) / max_rate`, at least `tolerance / 2`, so no pass deeper
/// than `max_rate · tolerance / 2` is missed.
pub fn toi_bisect_conservative(
    mut distance: impl FnMut(f32) -> f32,
    max_rate: f32,
    tolerance: f32,
) -> Option<f32> {
    let tolerance = tolerance.max(1e-7);
    let mut t0 = 0.0f32;
    let mut d0 = distance(t0);
    if d0 <= 0.0 {
        return Some(0.0);
    }
    if max_rate.is_nan() || max_rate <= 0.0 {
        return None;
    }
    while t0 < 1.0 {
        let t1 = (t0 + (d0 / max_rate).max(0.5 * tolerance)).min(1.0);
        let d1 = distance(t1);
        if d1 <= 0.0 {
            return Some(bisect(&mut distance, t0, t1, tolerance));
        }
        t0 = t1;
        d0 = d1;
    }
    None
}

/// Halves [lo, hi] (distance > 0 at lo, ≤ 0 at hi) down to `tolerance`.
fn bisect(distance: &mut impl FnMut(f32) -> f32, mut lo: f32, mut hi: f32, tolerance: f32) -> f32 {
    while hi - lo > tolerance {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if distance(mid) <= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// `toi_sphere_sphere` by bisection (the reference for the analytic one).
pub fn toi_sphere_sphere_bisect(
    a: Sphere,
    va: Vec3,
    b: Sphere,
    vb: Vec3,
    tolerance: f32,
) -> Option<f32> {
    let (p, v, r) = (a.center - b.center, va - vb, a.radius + b.radius);
    toi_bisect_conservative(|t| (p + v * t).length() - r, v.length(), tolerance)
}

/// `toi_sphere_triangle` by bisection: the signed distance from the sphere
/// to the one-sided triangle, counted only while the centre is in front of
/// (or on, within `BOUNDARY_SLACK`) its plane; behind it, the distance to
/// the plane shifted back by that slack stands in, so the scan stays
/// conservative until the centre comes round to the front.
pub fn toi_sphere_triangle_bisect(
    s: Sphere,
    v: Vec3,
    triangle: &[Vec3; 3],
    tolerance: f32,
) -> Option<f32> {
    let [a, b, c] = *triangle;
    let normal = triangle_unit_normal(a, b, c);
    let distance = |t: f32| {
        let center = s.center + v * t;
        if let Some(n) = normal {
            let height = (center - a).dot(n);
            if height < -BOUNDARY_SLACK {
                return -height - BOUNDARY_SLACK + f32::MIN_POSITIVE;
            }
        }
        let (closest, _) = closest_point_triangle(center, a, b, c);
        center.distance(closest) - s.radius
    };
    toi_bisect_conservative(distance, v.length(), tolerance)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_simple_root() {
        let t = toi_bisect(|t| 0.3 - t, 1e-6).unwrap();
        assert!((t - 0.3).abs() < 1e-6);
        let t = toi_bisect_conservative(|t| 0.3 - t, 1.0, 1e-6).unwrap();
        assert!((t - 0.3).abs() < 1e-6);
        assert_eq!(toi_bisect(|t| -t, 1e-6), Some(0.0));
        assert_eq!(toi_bisect(|t| 1.5 - t, 1e-6), None);
    }

    #[test]
    fn grazing_pass_that_separates_again_is_found() {
        // Dips below zero only for t in (0.4, 0.41).
        let f = |t: f32| (t - 0.405).abs() - 0.005;
        let t = toi_bisect(f, 1e-6).unwrap();
        assert!((t - 0.4).abs() < 1e-5, "{t}");
        let t = toi_bisect_conservative(f, 1.0, 1e-6).unwrap();
        assert!((t - 0.4).abs() < 1e-5, "{t}");
        // Narrower than a scan step: only the bounded scan sees it.
        let narrow = |t: f32| (t - 0.5001).abs() - 0.0001;
        let t = toi_bisect_conservative(narrow, 1.0, 1e-6).unwrap();
        assert!((t - 0.5).abs() < 1e-5, "{t}");
    }

    #[test]
    fn sphere_pair_by_bisection() {
        let a = Sphere::new(Vec3::ZERO, 0.5);
        let b = Sphere::new(Vec3::new(3.0, 0.0, 0.0), 0.5);
        let t = toi_sphere_sphere_bisect(a, Vec3::X * 4.0, b, Vec3::ZERO, 1e-6).unwrap();
        assert!((t - 0.5).abs() < 1e-5);
        assert_eq!(
            toi_sphere_sphere_bisect(a, Vec3::ZERO, b, Vec3::ZERO, 1e-6),
            None
        );
    }
}
