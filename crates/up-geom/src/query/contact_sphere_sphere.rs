//! Sphere against sphere: the distance between centres minus the radii.

use crate::norm::try_unit;
use glam::Vec3;

use crate::{Contact, Sphere};

/// Contact between two spheres, if their surfaces are closer than `margin`
/// (m, ≥ 0; 0 for touching or overlapping only). Features are 0.
///
/// The normal points from A's centre to B's; for coincident centres it is +Y,
/// so the result is deterministic.
#[inline]
pub fn contact_sphere_sphere(a: Sphere, b: Sphere, margin: f32) -> Option<Contact> {
    let delta = b.center - a.center;
    let reach = a.radius + b.radius + margin;
    let distance2 = delta.length_squared();
    if distance2 > reach * reach {
        return None;
    }
    let distance = distance2.sqrt();
    let normal = if distance > 0.0 {
        try_unit(delta / distance)
    } else {
        None
    };
    let normal = normal.unwrap_or(Vec3::Y);
    Some(Contact {
        point_a: a.center + normal * a.radius,
        point_b: b.center - normal * b.radius,
        normal,
        separation: distance - a.radius - b.radius,
        feature_a: 0,
        feature_b: 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exactly_touching_spheres_have_zero_separation() {
        let c = contact_sphere_sphere(
            Sphere::new(Vec3::ZERO, 0.5),
            Sphere::new(Vec3::new(1.0, 0.0, 0.0), 0.5),
            0.0,
        )
        .unwrap();
        assert_eq!(c.separation, 0.0);
        assert_eq!(c.normal, Vec3::X);
        assert_eq!(c.point_a, Vec3::new(0.5, 0.0, 0.0));
        assert_eq!(c.point_b, Vec3::new(0.5, 0.0, 0.0));
    }

    #[test]
    fn overlap_gives_negative_separation_and_gap_needs_the_margin() {
        let a = Sphere::new(Vec3::ZERO, 1.0);
        let c = contact_sphere_sphere(a, Sphere::new(Vec3::new(0.0, 1.5, 0.0), 1.0), 0.0).unwrap();
        assert!((c.separation + 0.5).abs() < 1e-6);
        assert_eq!(c.depth(), c.separation.abs());
        assert_eq!(c.normal, Vec3::Y);
        let far = Sphere::new(Vec3::new(0.0, 0.0, 2.1), 1.0);
        assert!(contact_sphere_sphere(a, far, 0.0).is_none());
        let c = contact_sphere_sphere(a, far, 0.2).unwrap();
        assert!((c.separation - 0.1).abs() < 1e-6);
        assert!(c.normal.distance(Vec3::Z) < 1e-6);
    }

    #[test]
    fn coincident_centres_push_along_y() {
        let c = contact_sphere_sphere(
            Sphere::new(Vec3::ONE, 1.0),
            Sphere::new(Vec3::ONE, 0.5),
            0.0,
        )
        .unwrap();
        assert_eq!(c.normal, Vec3::Y);
        assert_eq!(c.separation, -1.5);
        assert!(c.point_a.is_finite() && c.point_b.is_finite());
    }

    #[test]
    fn flipped_swaps_the_roles() {
        let a = Sphere::new(Vec3::ZERO, 1.0);
        let b = Sphere::new(Vec3::new(1.0, 1.0, 0.0), 1.0);
        let ab = contact_sphere_sphere(a, b, 0.0).unwrap();
        let ba = contact_sphere_sphere(b, a, 0.0).unwrap();
        let f = ab.flipped();
        assert!(f.normal.distance(ba.normal) < 1e-6);
        assert!((f.separation - ba.separation).abs() < 1e-6);
        assert!(f.point_a.distance(ba.point_a) < 1e-6);
    }
}
