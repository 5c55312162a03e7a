//! One sphere (A) against a static one-sided mesh (B).
//!
//! Candidates come from the BVH; each triangle's closest point gives a face,
//! edge or vertex contact, and `mesh_feature` keeps only genuine features (no
//! internal-edge bumps). Contacts of this sphere whose normals agree within
//! `FLAT_EDGE_ANGLE` are merged, keeping the deepest: a sphere right over the
//! seam of two coplanar triangles touches both faces but gets one contact.

use glam::Vec3;

use super::mesh_feature::mesh_contact_direction;
use crate::shape::trimesh::FLAT_EDGE_ANGLE;
use crate::{closest_point_triangle, Aabb, Contact, Sphere, TriMesh, TriangleRegion};

/// Appends the contacts between `sphere` and `mesh` closer than `margin` (m)
/// to `out`, with `feature_a` set to `feature_a` and `feature_b` to the
/// triangle index. Does not allocate beyond `out`'s growth.
pub fn contact_sphere_trimesh(
    sphere: Sphere,
    mesh: &TriMesh,
    margin: f32,
    feature_a: u32,
    out: &mut Vec<Contact>,
) {
    let first = out.len();
    let reach = sphere.radius + margin;
    let bounds = Aabb::from_sphere(sphere.center, reach);
    let same_normal_cos = FLAT_EDGE_ANGLE.cos();
    mesh.query_aabb(&bounds, |tri| {
        let Some(contact) = sphere_mesh_triangle(sphere, mesh, tri, margin, feature_a) else {
            return;
        };
        match out[first..]
            .iter_mut()
            .find(|c| c.normal.dot(contact.normal) >= same_normal_cos)
        {
            Some(existing) => {
                if contact.separation < existing.separation {
                    *existing = contact;
                }
            }
            None => out.push(contact),
        }
    });
}

/// The contact of `sphere` with triangle `tri` as part of `mesh`, if any.
#[inline]
pub(crate) fn sphere_mesh_triangle(
    sphere: Sphere,
    mesh: &TriMesh,
    tri: u32,
    margin: f32,
    feature_a: u32,
) -> Option<Contact> {
    let normal = mesh.normal(tri);
    if normal == Vec3::ZERO {
        return None;
    }
    let [a, b, c] = mesh.triangle(tri);
    let center = sphere.center;
    let reach = sphere.radius + margin;
    let height = (center - a).dot(normal);
    if height < -sphere.radius || height > reach {
        return None;
    }
    let (closest, region) = closest_point_triangle(center, a, b, c);
    if region != TriangleRegion::Face && (center - closest).length_squared() > reach * reach {
        return None;
    }
    let (m, distance) = mesh_contact_direction(mesh, tri, region, center, closest)?;
    let separation = distance - sphere.radius;
    if separation > margin {
        return None;
    }
    Some(Contact {
        point_a: center - m * sphere.radius,
        point_b: center - m * distance,
        normal: -m,
        separation,
        feature_a,
        feature_b: tri,
    })
}

/// True when some triangle of `mesh` lies within `reach` (m) of `center`.
pub(crate) fn mesh_within(mesh: &TriMesh, center: Vec3, reach: f32) -> bool {
    let bounds = Aabb::from_sphere(center, reach);
    mesh.query_aabb_until(&bounds, |tri| {
        let [a, b, c] = mesh.triangle(tri);
        let (closest, _) = closest_point_triangle(center, a, b, c);
        (center - closest).length_squared() <= reach * reach
    })
}
