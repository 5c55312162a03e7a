//! Which contacts with a mesh triangle are real: internal edges and vertices.
//!
//! A triangle reports the closest point on itself, but a sphere touches the
//! whole mesh. An edge or vertex of a triangle is a genuine contact feature
//! only if the direction from it to the sphere's centre lies in the
//! feature's normal cone on the mesh surface (compare parry's
//! `FIX_INTERNAL_EDGES` pseudo-normals and Jolt's active edges):
//! - an edge's cone is the arc from one face normal to the other; it is a
//!   single direction for a flat edge and empty (from the front) for a
//!   concave one. Outside the cone a neighbouring face is closer and reports
//!   its own contact, so this one is dropped. Within `SEAM_TOLERANCE` of the
//!   cone (a centre right over the seam of two coplanar triangles, where both
//!   may report the shared edge) the direction is clamped into the cone: the
//!   face normal for flat edges.
//! - a vertex is the closest point of its one-ring only if the centre does
//!   not project onto any edge leaving it: `(c - v)·ê ≤ 0` for each.
//!   A vertex that is flat or concave all round gets the face normal.
//!
//! The caller deduplicates equal normals (both triangles of a seam).

use glam::Vec3;

use crate::shape::trimesh::EdgeKind;
use crate::{TriMesh, TriangleRegion};

use super::contact_sphere_triangle::CENTER_ON_SURFACE;

/// How far (m) a centre may sit outside a feature's normal cone and still be
/// clamped onto it rather than dropped: well above f32 rounding of room-sized
/// coordinates (≈ 1e-6 m), far below anything visible.
pub const SEAM_TOLERANCE: f32 = 1e-5;

/// For triangle `tri` of `mesh`, with closest point `closest` in `region` to
/// the sphere centre `center`: the contact direction `m` (unit, from the mesh
/// to the centre) and the distance along it, or `None` when the contact
/// belongs to another feature (or lies behind this one-sided triangle).
/// `tri` must not be degenerate.
#[inline]
pub fn mesh_contact_direction(
    mesh: &TriMesh,
    tri: u32,
    region: TriangleRegion,
    center: Vec3,
    closest: Vec3,
) -> Option<(Vec3, f32)> {
    let normal = mesh.normal(tri);
    let corners = mesh.triangle(tri);
    let height = (center - corners[0]).dot(normal);
    let delta = center - closest;
    let distance = delta.length();
    if region == TriangleRegion::Face || distance <= CENTER_ON_SURFACE {
        return Some((normal, height));
    }
    if height < 0.0 {
        return None;
    }
    let m = delta / distance;
    match region {
        // Handled above; kept so the match stays exhaustive.
        TriangleRegion::Face => Some((normal, height)),
        TriangleRegion::Edge(k) => {
            let k = k as usize;
            let adjacency = mesh.edge(tri, k);
            let Some(neighbor) = adjacency.neighbor else {
                return Some((m, distance));
            };
            let edge = corners[(k + 1) % 3] - corners[k];
            // In-plane directions pointing away from each triangle across the edge.
            let out_here = edge.cross(normal).normalize_or_zero();
            let out_there = mesh.normal(neighbor).cross(edge).normalize_or_zero();
            let beyond_neighbor = delta.dot(out_there);
            match adjacency.kind {
                EdgeKind::Boundary => Some((m, distance)),
                EdgeKind::Flat => (beyond_neighbor >= -SEAM_TOLERANCE).then_some((normal, height)),
                EdgeKind::Concave => None,
                EdgeKind::Convex => {
                    if beyond_neighbor < -SEAM_TOLERANCE {
                        None
                    } else if beyond_neighbor < 0.0 {
                        Some((mesh.normal(neighbor), distance))
                    } else if delta.dot(out_here) < 0.0 {
                        Some((normal, distance))
                    } else {
                        Some((m, distance))
                    }
                }
            }
        }
        TriangleRegion::Vertex(k) => {
            let vertex = mesh.triangles()[tri as usize][k as usize];
            let position = mesh.vertices()[vertex as usize];
            let projects_onto_an_edge = mesh.vertex_neighbors(vertex).iter().any(|&w| {
                let along = (mesh.vertices()[w as usize] - position).normalize_or_zero();
                delta.dot(along) > SEAM_TOLERANCE
            });
            if projects_onto_an_edge {
                None
            } else if mesh.is_vertex_convex(vertex) {
                Some((m, distance))
            } else {
                Some((normal, height))
            }
        }
    }
}
