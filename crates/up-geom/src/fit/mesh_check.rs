//! Checks that a triangle mesh is closed, manifold and consistently wound:
//! every edge is shared by exactly two triangles that traverse it in opposite
//! directions. Such a mesh bounds a solid, so its volume and the coverage of
//! its surface mean something.
//!
//! Triangles that repeat a vertex index have no area and no proper edges; they
//! are skipped (tolerated), and counted so callers can report them.

use glam::Vec3;
use thiserror::Error;

use crate::shape::trimesh::{validate_indices, TriMeshError};

#[derive(Clone, Debug, Error, PartialEq)]
pub enum MeshCheckError {
    /// No triangles, a non-finite vertex or an index out of range.
    #[error(transparent)]
    Indices(#[from] TriMeshError),
    #[error(
        "the mesh is not closed: edge between vertices {a} and {b} belongs to only one triangle \
         (expected exactly two)"
    )]
    OpenEdge { a: u32, b: u32 },
    #[error(
        "the mesh is not manifold: edge between vertices {a} and {b} belongs to {count} \
         triangles (expected exactly two)"
    )]
    NonManifoldEdge { a: u32, b: u32, count: usize },
    #[error(
        "the mesh is not consistently wound: the two triangles at edge {a}-{b} both run it the \
         same way (expected opposite directions)"
    )]
    InconsistentWinding { a: u32, b: u32 },
}

/// What a successful check found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshCheck {
    /// Triangles skipped because they repeat a vertex index.
    pub degenerate_triangles: usize,
    /// Distinct undirected edges.
    pub edges: usize,
}

/// Valid indices, and every edge shared by exactly two oppositely wound triangles.
pub fn check_closed(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
) -> Result<MeshCheck, MeshCheckError> {
    validate_indices(vertices, triangles)?;
    // Directed edges as (low, high, runs low→high); sorted, so groups are
    // contiguous and the first reported problem is deterministic.
    let mut edges: Vec<(u32, u32, bool)> = Vec::with_capacity(triangles.len() * 3);
    let mut degenerate_triangles = 0;
    for t in triangles {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            degenerate_triangles += 1;
            continue;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b), a < b));
        }
    }
    if edges.is_empty() {
        return Err(MeshCheckError::Indices(TriMeshError::Empty));
    }
    edges.sort_unstable();
    let mut distinct = 0;
    for group in edges.chunk_by(|x, y| x.0 == y.0 && x.1 == y.1) {
        distinct += 1;
        let (a, b) = (group[0].0, group[0].1);
        let forward = group.iter().filter(|e| e.2).count();
        match group.len() {
            1 => return Err(MeshCheckError::OpenEdge { a, b }),
            2 if forward == 1 => {}
            2 => return Err(MeshCheckError::InconsistentWinding { a, b }),
            count => return Err(MeshCheckError::NonManifoldEdge { a, b, count }),
        }
    }
    Ok(MeshCheck {
        degenerate_triangles,
        edges: distinct,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetrahedron() -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let v = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        (v, t)
    }

    #[test]
    fn closed_tetrahedron_passes() {
        let (v, t) = tetrahedron();
        assert_eq!(
            check_closed(&v, &t),
            Ok(MeshCheck {
                degenerate_triangles: 0,
                edges: 6
            })
        );
    }

    #[test]
    fn missing_face_is_an_open_edge() {
        let (v, mut t) = tetrahedron();
        t.pop();
        assert!(matches!(
            check_closed(&v, &t),
            Err(MeshCheckError::OpenEdge { .. })
        ));
    }

    #[test]
    fn flipped_face_is_inconsistent_winding() {
        let (v, mut t) = tetrahedron();
        t[3].swap(0, 1);
        assert!(matches!(
            check_closed(&v, &t),
            Err(MeshCheckError::InconsistentWinding { .. })
        ));
    }

    #[test]
    fn third_triangle_on_an_edge_is_non_manifold() {
        let (mut v, mut t) = tetrahedron();
        v.push(Vec3::new(-1.0, -1.0, -1.0));
        t.push([0, 1, 4]);
        assert!(matches!(
            check_closed(&v, &t),
            Err(MeshCheckError::NonManifoldEdge { count: 3, .. })
        ));
    }

    #[test]
    fn degenerate_triangles_are_tolerated_and_counted() {
        let (v, mut t) = tetrahedron();
        t.push([1, 1, 2]);
        assert_eq!(check_closed(&v, &t).map(|c| c.degenerate_triangles), Ok(1));
    }

    #[test]
    fn bad_indices_and_coordinates_are_reported() {
        let (mut v, mut t) = tetrahedron();
        t.push([0, 1, 9]);
        assert!(matches!(
            check_closed(&v, &t),
            Err(MeshCheckError::Indices(TriMeshError::IndexOutOfRange {
                triangle: 4,
                vertex: 9,
                count: 4
            }))
        ));
        t.pop();
        v[2].y = f32::NAN;
        assert_eq!(
            check_closed(&v, &t),
            Err(MeshCheckError::Indices(TriMeshError::NonFiniteVertex {
                index: 2
            }))
        );
        assert_eq!(
            check_closed(&v, &[]),
            Err(MeshCheckError::Indices(TriMeshError::Empty))
        );
    }
}
