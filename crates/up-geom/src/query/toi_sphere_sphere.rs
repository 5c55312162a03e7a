//! Time of impact of two linearly moving spheres, solved in closed form.
//!
//! With p = p_A − p_B, v = v_A − v_B and R = r_A + r_B, the centres are R
//! apart when |p + v·t|² = R², that is
//!
//! ```text
//! a·t² + 2b·t + c = 0,   a = v·v,  b = p·v,  c = p·p − R².
//! ```
//!
//! c < 0: already overlapping, t = 0. b ≥ 0: not approaching, no impact.
//! d = b² − a·c < 0: the paths miss. Otherwise the earliest root is
//! t = (−b − √d)/a = c / (−b + √d); the second form divides two quantities of
//! the same sign and does not cancel when c ≈ 0 (touching balloons in a
//! pile), while the first subtracts nearly equal numbers.
//!
//! Equation (4) of the original UP report writes the middle term as
//! `(2t‖V1‖‖V2‖cos θ)²`. Squared, it is no longer linear in t: the equation
//! loses its linear term and gains a wrong t² coefficient, so its roots are
//! symmetric about t = 0 and wrong by an amount that grows with the relative
//! speed. That, more than floating point, is why the report's analytic
//! solution "did not yield good results". The middle term is `2t (V1·V2)`.

use glam::Vec3;

use crate::Sphere;

/// Analytic time of impact of two spheres moving linearly over t ∈ [0, 1]:
/// centre A at `a.center + va·t`, centre B at `b.center + vb·t` (velocities
/// in m per unit step). `Some(0.0)` when they already overlap, `None` when
/// they do not touch before t = 1.
#[inline]
pub fn toi_sphere_sphere(a: Sphere, va: Vec3, b: Sphere, vb: Vec3) -> Option<f32> {
    toi_moving_point_sphere(a.center - b.center, va - vb, a.radius + b.radius)
}

/// First t ∈ [0, 1] at which `p + v·t` is at distance `radius` from the
/// origin (see the module docs).
#[inline]
pub(crate) fn toi_moving_point_sphere(p: Vec3, v: Vec3, radius: f32) -> Option<f32> {
    let c = p.length_squared() - radius * radius;
    if c < 0.0 {
        return Some(0.0);
    }
    let b = p.dot(v);
    if b >= 0.0 {
        return None;
    }
    let a = v.length_squared();
    // b² − a·c, rewritten (Lagrange's identity) as a·r² − |p × v|²: the
    // direct form subtracts two nearly equal large numbers when the path is
    // nearly head-on and the radius small against the distance.
    let d = a * radius * radius - p.cross(v).length_squared();
    if d < 0.0 {
        return None;
    }
    let t = c / (-b + d.sqrt());
    (t <= 1.0).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::toi_bisect::toi_sphere_sphere_bisect;
    use proptest::prelude::*;

    fn s(x: f32, r: f32) -> Sphere {
        Sphere::new(Vec3::new(x, 0.0, 0.0), r)
    }

    #[test]
    fn head_on() {
        let t = toi_sphere_sphere(s(0.0, 0.5), Vec3::X * 2.0, s(3.0, 0.5), Vec3::ZERO).unwrap();
        assert!((t - 1.0).abs() < 1e-6);
        let t = toi_sphere_sphere(s(0.0, 0.5), Vec3::X, s(3.0, 0.5), -Vec3::X).unwrap();
        assert!((t - 1.0).abs() < 1e-6);
        let t = toi_sphere_sphere(s(0.0, 0.5), Vec3::X * 4.0, s(3.0, 0.5), Vec3::ZERO).unwrap();
        assert!((t - 0.5).abs() < 1e-6);
    }

    #[test]
    fn overlapping_separating_missing_and_too_late() {
        assert_eq!(
            toi_sphere_sphere(s(0.0, 1.0), Vec3::ZERO, s(1.0, 1.0), Vec3::ZERO),
            Some(0.0)
        );
        assert_eq!(
            toi_sphere_sphere(s(0.0, 0.5), -Vec3::X, s(2.0, 0.5), Vec3::ZERO),
            None
        );
        assert_eq!(
            toi_sphere_sphere(s(0.0, 0.5), Vec3::Y * 5.0, s(2.0, 0.5), Vec3::ZERO),
            None
        );
        assert_eq!(
            toi_sphere_sphere(s(0.0, 0.5), Vec3::X, s(3.0, 0.5), Vec3::ZERO),
            None
        );
        assert_eq!(
            toi_sphere_sphere(s(0.0, 0.5), Vec3::ZERO, s(3.0, 0.5), Vec3::ZERO),
            None
        );
    }

    #[test]
    fn exactly_touching_and_approaching_is_an_impact_now() {
        let t = toi_sphere_sphere(s(0.0, 0.5), Vec3::X, s(1.0, 0.5), Vec3::ZERO);
        assert_eq!(t, Some(0.0));
    }

    #[test]
    fn nearly_touching_pile_does_not_cancel() {
        // Gap of 1e-6 m closing at 1 m per step: t = 1e-6 to f32 precision.
        let t = toi_sphere_sphere(s(0.0, 0.15), Vec3::X, s(0.300001, 0.15), Vec3::ZERO).unwrap();
        assert!((t - 1e-6).abs() < 1e-7, "{t}");
    }

    /// Found by fuzzing: 2 mm spheres 27 m apart, head-on. b² − a·c lost
    /// every digit of the discriminant and put the impact 7 mm early.
    #[test]
    fn small_spheres_far_apart_head_on() {
        let a = Sphere::new(Vec3::new(0.0, 0.0, 27.033705), 0.001);
        let b = Sphere::new(Vec3::ZERO, 0.001);
        let vb = Vec3::new(0.0, 0.0, 27.068855);
        let t = toi_sphere_sphere(a, Vec3::ZERO, b, vb).unwrap();
        let expected = (27.033705f64 - 0.002) / 27.068855;
        assert!((f64::from(t) - expected).abs() < 1e-6, "{t} vs {expected}");
    }

    fn unit(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range)
            .prop_map(|(x, y, z)| Vec3::new(x, y, z).try_normalize().unwrap_or(Vec3::X))
    }

    /// Smallest f64 distance between the surfaces over t ∈ [0, 1].
    fn min_gap(p: Vec3, v: Vec3, r: f32) -> f64 {
        let (p, v) = (p.as_dvec3(), v.as_dvec3());
        let t = if v.length_squared() > 0.0 {
            (-p.dot(v) / v.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p + v * t).length() - r as f64
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// Random, grazing (closest approach a little inside the sum of the
        /// radii) and touching (starting at contact, approaching) pairs.
        #[test]
        fn analytic_agrees_with_bisection(
            centre_a in (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0),
            ra in 0.05f32..1.0, rb in 0.05f32..1.0,
            u in unit(1.0), w in unit(1.0), speed in 0.1f32..6.0,
            random_v in (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0), random_p in (-4.0f32..4.0, -4.0f32..4.0, -4.0f32..4.0),
            mode in 0usize..3, eps in 1e-3f32..0.1, when in 0.1f32..0.9, vb in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
        ) {
            let r = ra + rb;
            let side = (w - u * w.dot(u)).try_normalize().unwrap_or(u.any_orthonormal_vector());
            let (p, v) = match mode {
                0 => (Vec3::from(random_p), Vec3::from(random_v)),
                1 => {
                    let v = u * speed;
                    (side * r * (1.0 - eps) - v * when, v)
                }
                _ => (u * r * (1.0 + eps * 1e-3), -u * speed + side * speed * 0.5),
            };
            let a = Sphere::new(Vec3::from(centre_a), ra);
            let vb = Vec3::from(vb);
            let b = Sphere::new(a.center - p, rb);
            let va = v + vb;
            let analytic = toi_sphere_sphere(a, va, b, vb);
            let bisected = toi_sphere_sphere_bisect(a, va, b, vb, 1e-6);
            match (analytic, bisected) {
                (Some(ta), Some(tb)) => prop_assert!((ta - tb).abs() <= 1e-4, "analytic {} bisect {}", ta, tb),
                (None, None) => {}
                _ => prop_assert!(min_gap(p, v, r).abs() < 1e-5, "{:?} vs {:?}", analytic, bisected),
            }
            if mode == 1 && when < 0.85 {
                prop_assert!(analytic.is_some());
            }
        }
    }
}
