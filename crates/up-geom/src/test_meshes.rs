//! Meshes the unit tests share (test builds only).

use glam::Vec3;

use crate::TriMesh;

/// A wall in the plane z = 0, x and y in [0, 2], normal +Z, made of two
/// triangles whose shared edge is the diagonal from (0,0) to (2,2).
pub(crate) fn wall() -> TriMesh {
    let v = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(2.0, 2.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    ];
    TriMesh::new(v, vec![[0, 1, 2], [0, 2, 3]]).unwrap()
}

/// An axis-aligned box [0, s] with normals pointing out (`inward` false)
/// or in (a room).
pub(crate) fn box_mesh(size: Vec3, inward: bool) -> TriMesh {
    let v = (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 != 0 { size.x } else { 0.0 },
                if i & 2 != 0 { size.y } else { 0.0 },
                if i & 4 != 0 { size.z } else { 0.0 },
            )
        })
        .collect();
    // Outward-facing quads, CCW seen from outside.
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut t = Vec::new();
    for q in quads {
        let (a, b) = ([q[0], q[1], q[2]], [q[0], q[2], q[3]]);
        if inward {
            t.push([a[0], a[2], a[1]]);
            t.push([b[0], b[2], b[1]]);
        } else {
            t.push(a);
            t.push(b);
        }
    }
    TriMesh::new(v, t).unwrap()
}
