//! Sphere (A) against one one-sided triangle (B).
//!
//! The closest point and its Voronoi region decide the case, so the face is
//! never mistaken for an edge (the original report tested edges in a fixed
//! order and could hit "an edge before the surface"):
//! - face region: the normal is minus the face normal and the separation is
//!   the plane distance minus the radius. A centre behind the plane by less
//!   than the radius is pushed back to the front; further behind, nothing.
//! - edge or vertex region, centre in front of the plane: the normal points
//!   from the centre to the closest point (a rounded edge or corner).
//! - edge or vertex region, centre behind the plane: nothing (one-sided).
//!
//! A zero-area triangle has no front; it acts as its segment or point.

use crate::norm::Norm;
use glam::Vec3;

use crate::{closest_point_triangle, Contact, Sphere, TriangleRegion};

/// Distance from the centre to the closest point below which the direction
/// is meaningless and the face normal is used instead (m).
pub(crate) const CENTER_ON_SURFACE: f32 = 1e-6;

/// Unit normal of the triangle (a, b, c) by the right-hand rule, or `None`
/// for a zero-area one. A cross product whose squared length is subnormal
/// counts as zero: normalising it gives a vector visibly shorter than 1.
#[inline]
pub(crate) fn triangle_unit_normal(a: Vec3, b: Vec3, c: Vec3) -> Option<Vec3> {
    let cross = (b - a).cross(c - a);
    (cross.length_squared() >= f32::MIN_POSITIVE).then(|| cross.unit())
}

/// Contact between sphere A and one-sided triangle B, if closer than `margin`.
pub fn contact_sphere_triangle(
    sphere: Sphere,
    triangle: &[Vec3; 3],
    margin: f32,
) -> Option<(Contact, TriangleRegion)> {
    let [a, b, c] = *triangle;
    let center = sphere.center;
    let face_normal = triangle_unit_normal(a, b, c);
    let (closest, region) = closest_point_triangle(center, a, b, c);
    let delta = center - closest;
    // `m` points from the triangle to the centre; `distance` is measured along it.
    let (m, distance) = match face_normal {
        Some(n) => {
            let height = (center - a).dot(n);
            if height < -sphere.radius {
                return None;
            }
            let distance = delta.norm();
            if region == TriangleRegion::Face || distance <= CENTER_ON_SURFACE {
                // On a sliver the normal is rounded enough to put the plane
                // above the closest point; the centre is never farther from
                // the triangle than from that point.
                (n, height.min(distance))
            } else if height < 0.0 {
                return None;
            } else {
                (delta / distance, distance)
            }
        }
        None => {
            let distance = delta.norm();
            let m = if distance > CENTER_ON_SURFACE {
                delta / distance
            } else {
                Vec3::Y
            };
            (m, distance)
        }
    };
    let separation = distance - sphere.radius;
    if separation > margin {
        return None;
    }
    let contact = Contact {
        point_a: center - m * sphere.radius,
        point_b: center - m * distance,
        normal: -m,
        separation,
        feature_a: 0,
        feature_b: 0,
    };
    Some((contact, region))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// CCW seen from +Z: normal +Z.
    const TRI: [Vec3; 3] = [
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    ];

    fn contact(center: Vec3, radius: f32) -> Option<(Contact, TriangleRegion)> {
        contact_sphere_triangle(Sphere::new(center, radius), &TRI, 0.0)
    }

    #[test]
    fn face_contact_from_the_front() {
        let (c, r) = contact(Vec3::new(0.5, 0.5, 0.4), 0.5).unwrap();
        assert_eq!(r, TriangleRegion::Face);
        assert_eq!(c.normal, -Vec3::Z);
        assert!((c.separation + 0.1).abs() < 1e-6);
        assert!(c.point_b.distance(Vec3::new(0.5, 0.5, 0.0)) < 1e-6);
        assert!(c.point_a.distance(Vec3::new(0.5, 0.5, -0.1)) < 1e-6);
    }

    #[test]
    fn exactly_touching_face_has_zero_separation() {
        let (c, _) = contact(Vec3::new(0.5, 0.5, 0.5), 0.5).unwrap();
        assert_eq!(c.separation, 0.0);
    }

    #[test]
    fn centre_behind_the_plane_is_pushed_to_the_front() {
        let (c, r) = contact(Vec3::new(0.5, 0.5, -0.2), 0.5).unwrap();
        assert_eq!(r, TriangleRegion::Face);
        // A→B normal is minus the face normal: solving pushes A along +Z.
        assert_eq!(c.normal, -Vec3::Z);
        assert!((c.separation + 0.7).abs() < 1e-6);
        assert!(contact(Vec3::new(0.5, 0.5, -0.6), 0.5).is_none());
    }

    #[test]
    fn edge_and_vertex_contacts_are_rounded() {
        let (c, r) = contact(Vec3::new(1.0, -0.3, 0.4), 0.6).unwrap();
        assert_eq!(r, TriangleRegion::Edge(0));
        assert!(c.normal.distance(Vec3::new(0.0, 0.6, -0.8)) < 1e-6);
        assert!((c.separation + 0.1).abs() < 1e-6);
        let (c, r) = contact(Vec3::new(-0.3, -0.4, 0.0), 0.6).unwrap();
        assert_eq!(r, TriangleRegion::Vertex(0));
        assert!(c.normal.distance(Vec3::new(0.6, 0.8, 0.0)) < 1e-6);
        assert!(contact(Vec3::new(-0.3, -0.4, 0.0), 0.4).is_none());
    }

    #[test]
    fn edge_contact_from_behind_is_ignored() {
        assert!(contact(Vec3::new(1.0, -0.3, -0.1), 0.6).is_none());
    }

    #[test]
    fn margin_gives_speculative_contacts() {
        let s = Sphere::new(Vec3::new(0.5, 0.5, 0.7), 0.5);
        assert!(contact_sphere_triangle(s, &TRI, 0.1).is_none());
        let (c, _) = contact_sphere_triangle(s, &TRI, 0.25).unwrap();
        assert!((c.separation - 0.2).abs() < 1e-6);
    }

    #[test]
    fn zero_area_triangle_acts_as_a_segment() {
        let seg = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        let (c, _) =
            contact_sphere_triangle(Sphere::new(Vec3::new(1.5, 0.0, 0.3), 0.5), &seg, 0.0).unwrap();
        assert!(c.normal.distance(-Vec3::Z) < 1e-6);
        assert!((c.separation + 0.2).abs() < 1e-6);
        let point = [Vec3::ONE; 3];
        let (c, _) = contact_sphere_triangle(Sphere::new(Vec3::ONE, 0.5), &point, 0.0).unwrap();
        assert!(c.normal.is_finite() && c.separation == -0.5);
    }

    /// Found by fuzzing: a cross product of ~1e-22 (squared: subnormal)
    /// normalised to a "unit" normal 0.4 % short.
    #[test]
    fn tiny_triangle_normal_is_unit_or_absent() {
        let tri = [
            Vec3::new(1.6687409e-38, 1.6134235e-38, 1.1612822e-16),
            Vec3::new(-1.6987044e-6, 6.493e-41, 0.0),
            Vec3::ZERO,
        ];
        let sphere = Sphere::new(Vec3::new(5.288444e-9, 0.0, 4.135903e-25), 0.001000478);
        let (c, _) = contact_sphere_triangle(sphere, &tri, 0.0).unwrap();
        assert!((c.normal.length() - 1.0).abs() < 1e-6, "{c:?}");
        assert!(c.separation <= 0.0, "{c:?}");
    }

    fn brute_force_distance(p: Vec3, t: &[Vec3; 3]) -> f32 {
        const N: usize = 150;
        let mut best = f32::INFINITY;
        for i in 0..=N {
            for j in 0..=(N - i) {
                let (u, v) = (i as f32 / N as f32, j as f32 / N as f32);
                best = best.min(p.distance(t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v));
            }
        }
        best
    }

    fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn depth_matches_brute_force_in_front(
            center in vec3(2.0), radius in 0.05f32..1.5, a in vec3(1.0), b in vec3(1.0), c in vec3(1.0)
        ) {
            let tri = [a, b, c];
            let n = (b - a).cross(c - a);
            prop_assume!(n.length() > 1e-3);
            let n = n.normalize();
            // Mirror a centre behind the plane to the front (no rejections).
            let height = (center - a).dot(n);
            let center = if height < 0.0 { center - n * (2.0 * height) } else { center };
            let brute = brute_force_distance(center, &tri);
            let result = contact_sphere_triangle(Sphere::new(center, radius), &tri, 0.0);
            // Grid spacing ≤ ~2/150 · √2: the brute force overestimates by at most that.
            let slack = 0.02;
            match result {
                Some((contact, _)) => {
                    prop_assert!(contact.separation <= 1e-6);
                    prop_assert!(contact.separation <= brute - radius + 1e-4);
                    prop_assert!(contact.separation >= brute - radius - slack);
                    prop_assert!((contact.normal.length() - 1.0).abs() < 1e-4);
                    // The normal points from the centre to the closest point.
                    prop_assert!(contact.point_b.distance(center + contact.normal * (contact.separation + radius)) < 1e-4);
                }
                None => prop_assert!(brute - radius > -1e-4),
            }
        }
    }
}
