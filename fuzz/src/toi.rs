//! Time-of-impact queries from arbitrary finite inputs (positions within
//! ±64 m, displacements within ±64 m per step, radii 1 mm to 8 m): t is in
//! [0, 1]; at the analytic t the shapes touch; nothing overlaps before it;
//! the bisection reference agrees where the crossing is not a graze.

use crate::numbers::{distance64, face_normal, is_sliver, Numbers};
use up_geom::{
    closest_point_triangle, toi_sphere_sphere, toi_sphere_sphere_bisect, toi_sphere_triangle,
    toi_sphere_triangle_bisect, Sphere,
};

const SPAN: f32 = 64.0;
const MAX_RADIUS: f32 = 8.0;
const MIN_RADIUS: f32 = 1e-3;
const RELATIVE_TOLERANCE: f64 = 1e-4;
/// Bisection tolerance, in units of t.
const BISECT_TOLERANCE: f32 = 1e-5;
/// Samples checked for an earlier overlap before the analytic t.
const SAMPLES: u32 = 32;

/// One input: panics when a property fails.
pub fn check(data: &[u8]) {
    let mut n = Numbers::new(data);
    if n.byte().is_multiple_of(2) {
        sphere_sphere(&mut n);
    } else {
        sphere_triangle(&mut n);
    }
}

fn sphere_sphere(n: &mut Numbers) {
    let a = Sphere::new(n.vec3(SPAN), n.radius(MIN_RADIUS, MAX_RADIUS));
    let b = Sphere::new(n.vec3(SPAN), n.radius(MIN_RADIUS, MAX_RADIUS));
    let (va, vb) = (n.vec3(SPAN), n.vec3(SPAN));
    let (p, v) = ((a.center - b.center).as_dvec3(), (va - vb).as_dvec3());
    let r = f64::from(a.radius) + f64::from(b.radius);
    let scale = p.abs().max_element() + v.abs().max_element() + r;
    let tolerance = RELATIVE_TOLERANCE * scale.max(1.0);
    // Signed gap along the path, in f64: convex in t.
    let gap = |t: f64| (p + v * t).length() - r;
    // The deepest point over [0, 1].
    let t_closest = if v.length_squared() > 0.0 {
        (-p.dot(v) / v.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let deepest = gap(t_closest).min(gap(0.0)).min(gap(1.0));

    let analytic = toi_sphere_sphere(a, va, b, vb);
    let bisected = toi_sphere_sphere_bisect(a, va, b, vb, BISECT_TOLERANCE);
    if let Some(t) = analytic {
        assert!((0.0..=1.0).contains(&t), "t = {t}");
        let t = f64::from(t);
        assert!(
            gap(t) <= tolerance,
            "not touching at t = {t}: gap {} for {a:?} {va} {b:?} {vb}",
            gap(t)
        );
        if t > 0.0 {
            assert!(
                gap(t).abs() <= tolerance,
                "t = {t} is not a root: {}",
                gap(t)
            );
        }
    } else {
        assert!(
            deepest >= -tolerance,
            "missed an impact: deepest gap {deepest}"
        );
    }
    if let Some(tb) = bisected {
        assert!((0.0..=1.0).contains(&tb), "bisection t = {tb}");
        let tb64 = f64::from(tb);
        if gap(tb64) < -tolerance {
            let t = analytic.expect("the bisection found an overlap the analytic query missed");
            // Both bracket the first root of a convex gap: they agree to the
            // bisection tolerance plus the rounding of the gap over its slope.
            let slope = (p + v * f64::from(t)).normalize_or_zero().dot(v).abs();
            let allowed = 2.0 * f64::from(BISECT_TOLERANCE) + tolerance / slope.max(1e-12);
            assert!(
                (f64::from(t) - tb64).abs() <= allowed,
                "analytic {t} vs bisection {tb} (allowed {allowed})"
            );
        }
    } else if analytic.is_some() {
        // Bisection misses only passes shallower than its step guarantee.
        let graze = v.length() * f64::from(BISECT_TOLERANCE) + tolerance;
        assert!(deepest >= -graze, "bisection missed a pass {deepest} deep");
    }
}

fn sphere_triangle(n: &mut Numbers) {
    let s = Sphere::new(n.vec3(SPAN), n.radius(MIN_RADIUS, MAX_RADIUS));
    let v = n.vec3(SPAN);
    let tri = [n.vec3(SPAN), n.vec3(SPAN), n.vec3(SPAN)];
    let scale = tri
        .iter()
        .fold(s.center.abs(), |m, p| m.max(p.abs()))
        .max_element()
        + v.abs().max_element()
        + s.radius;
    let tolerance = RELATIVE_TOLERANCE * f64::from(scale).max(1.0);
    let normal = face_normal(&tri);
    // A sliver has a normal too rounded to measure heights against: only
    // t's range is checked there.
    let sliver = is_sliver(&tri);
    // (distance from the centre to the triangle − r, height over the plane) at t.
    let state = |t: f32| {
        let center = s.center + v * t;
        let (closest, _) = closest_point_triangle(center, tri[0], tri[1], tri[2]);
        let height = normal.map_or(0.0, |n| f64::from((center - tri[0]).dot(n)));
        (distance64(center, closest) - f64::from(s.radius), height)
    };

    let analytic = toi_sphere_triangle(s, v, &tri);
    let bisected = toi_sphere_triangle_bisect(s, v, &tri, BISECT_TOLERANCE);
    if sliver {
        let times = analytic.map(|(t, _)| t).into_iter().chain(bisected);
        for t in times {
            assert!((0.0..=1.0).contains(&t), "t = {t}");
        }
        return;
    }
    if let Some((t, _)) = analytic {
        assert!((0.0..=1.0).contains(&t), "t = {t}");
        let (gap, height) = state(t);
        assert!(gap <= tolerance, "not touching at t = {t}: gap {gap}");
        assert!(
            height >= -tolerance,
            "touching from behind at t = {t}: height {height}, {s:?} {v} {tri:?}"
        );
        // Nothing overlaps from the front earlier.
        for k in 0..SAMPLES {
            let earlier = t * k as f32 / SAMPLES as f32;
            if earlier >= t {
                break;
            }
            let (gap, height) = state(earlier);
            assert!(
                gap >= -tolerance || height < tolerance,
                "overlap at {earlier} before t = {t}: gap {gap}"
            );
        }
    }
    if let Some(tb) = bisected {
        assert!((0.0..=1.0).contains(&tb), "bisection t = {tb}");
        let (gap, height) = state(tb);
        if gap < -tolerance && height > tolerance {
            let (t, _) =
                analytic.expect("the bisection found an overlap the analytic query missed");
            assert!(
                t <= tb + BISECT_TOLERANCE,
                "analytic {t} after bisection {tb}"
            );
        }
    }
}
