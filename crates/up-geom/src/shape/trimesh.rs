//! Static triangle meshes with a BVH and edge adjacency.
//!
//! Built once from vertices and indices: face normals, a BVH over the
//! triangles, and for every triangle edge the triangle across it and whether
//! that edge is convex, flat or concave seen from the front. The contact
//! queries use the adjacency to drop contacts with internal edges (a sphere
//! sliding over the seam of two coplanar triangles must feel one flat face).
//!
//! Zero-area triangles are kept (indices stay as given) but have a zero
//! normal and no neighbours; the contact and time-of-impact queries skip
//! them, since their edges coincide with their neighbours' edges.

use glam::Vec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::aabb::Aabb;
use super::bvh::Bvh;

#[derive(Clone, Debug, Error, PartialEq)]
pub enum TriMeshError {
    #[error("a triangle mesh needs at least one triangle")]
    Empty,
    #[error("vertex {index} has a non-finite coordinate")]
    NonFiniteVertex { index: usize },
    #[error("triangle {triangle} refers to vertex {vertex}, but there are only {count} vertices")]
    IndexOutOfRange {
        triangle: usize,
        vertex: u32,
        count: usize,
    },
}

/// Two adjacent faces whose normals differ by less than this angle (rad,
/// about 0.06°) share a flat edge.
pub const FLAT_EDGE_ANGLE: f32 = 1e-3;

/// Below this squared double area (m⁴) relative to the squared longest edge
/// (m²)², a triangle counts as zero-area: `|n|² ≤ 1e-12 · L⁴`.
const DEGENERATE_RATIO: f32 = 1e-12;

/// What an edge looks like from the front side of its triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EdgeKind {
    /// No usable triangle across the edge (mesh border, non-manifold or
    /// mis-oriented neighbour, or a zero-area neighbour).
    Boundary,
    /// The surface bends away from the front (a ridge, the outside of a box).
    Convex,
    /// The neighbour is coplanar within `FLAT_EDGE_ANGLE`.
    Flat,
    /// The surface bends towards the front (a valley, a room's corner seen
    /// from inside).
    Concave,
}

/// The triangle across one edge of a triangle, and the edge's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct EdgeAdjacency {
    pub neighbor: Option<u32>,
    pub kind: EdgeKind,
}

/// A static, one-sided triangle mesh. Front faces wind counter-clockwise seen
/// from the front: the face normal is `(b - a) × (c - a)` normalised. For a room
/// the normals point into the room.
///
/// Serialised as its vertices and triangles only; deserialising validates
/// them and rebuilds the rest.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(try_from = "TriMeshData", into = "TriMeshData")]
pub struct TriMesh {
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    /// Unit face normals; zero for zero-area triangles.
    normals: Vec<Vec3>,
    /// Per triangle, per edge k (vertex k to k + 1).
    edges: Vec<[EdgeAdjacency; 3]>,
    /// Vertex one-rings in compressed rows: the neighbours of vertex v are
    /// `ring[ring_start[v]..ring_start[v + 1]]`, sorted.
    ring_start: Vec<u32>,
    ring: Vec<u32>,
    /// Whether a vertex touches a convex or boundary edge (else it is flat or
    /// concave all round, and never a contact feature of its own).
    vertex_convex: Vec<bool>,
    closed: bool,
    bvh: Bvh,
}

/// The serialised form of a `TriMesh`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TriMeshData {
    pub vertices: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

impl TryFrom<TriMeshData> for TriMesh {
    type Error = TriMeshError;
    fn try_from(data: TriMeshData) -> Result<Self, Self::Error> {
        TriMesh::new(data.vertices, data.triangles)
    }
}

impl From<TriMesh> for TriMeshData {
    fn from(mesh: TriMesh) -> Self {
        TriMeshData {
            vertices: mesh.vertices,
            triangles: mesh.triangles,
        }
    }
}

impl TriMesh {
    /// Validates the mesh (at least one triangle, finite vertices, indices in
    /// range) and builds normals, adjacency and the BVH.
    pub fn new(vertices: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Result<Self, TriMeshError> {
        validate_indices(&vertices, &triangles)?;
        let normals: Vec<Vec3> = triangles
            .iter()
            .map(|t| {
                face_normal(
                    vertices[t[0] as usize],
                    vertices[t[1] as usize],
                    vertices[t[2] as usize],
                )
            })
            .collect();
        let (edges, closed) = build_edge_adjacency(&vertices, &triangles, &normals);
        let (ring_start, ring) = build_vertex_rings(vertices.len(), &triangles);
        let mut vertex_convex = vec![false; vertices.len()];
        for (t, tri) in triangles.iter().enumerate() {
            if normals[t] == Vec3::ZERO {
                continue;
            }
            for k in 0..3 {
                if matches!(edges[t][k].kind, EdgeKind::Convex | EdgeKind::Boundary) {
                    vertex_convex[tri[k] as usize] = true;
                    vertex_convex[tri[(k + 1) % 3] as usize] = true;
                }
            }
        }
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| Aabb::from_points(&t.map(|i| vertices[i as usize])))
            .collect();
        let bvh = Bvh::build(&boxes);
        Ok(Self {
            vertices,
            triangles,
            normals,
            edges,
            ring_start,
            ring,
            vertex_convex,
            closed,
            bvh,
        })
    }

    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    #[inline]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The three corners of triangle `i`.
    #[inline]
    pub fn triangle(&self, i: u32) -> [Vec3; 3] {
        let t = self.triangles[i as usize];
        [
            self.vertices[t[0] as usize],
            self.vertices[t[1] as usize],
            self.vertices[t[2] as usize],
        ]
    }

    /// Unit front normal of triangle `i`, or zero if it has no area.
    #[inline]
    pub fn normal(&self, i: u32) -> Vec3 {
        self.normals[i as usize]
    }

    /// True for a zero-area triangle (collinear or coincident corners).
    #[inline]
    pub fn is_degenerate(&self, i: u32) -> bool {
        self.normals[i as usize] == Vec3::ZERO
    }

    /// The triangle across edge `k` (vertex k to k + 1) of triangle `i`.
    #[inline]
    pub fn edge(&self, i: u32, k: usize) -> EdgeAdjacency {
        self.edges[i as usize][k]
    }

    /// The vertices that share an edge with vertex `v`, sorted.
    #[inline]
    pub fn vertex_neighbors(&self, v: u32) -> &[u32] {
        let v = v as usize;
        &self.ring[self.ring_start[v] as usize..self.ring_start[v + 1] as usize]
    }

    /// Whether vertex `v` touches a convex or boundary edge.
    #[inline]
    pub fn is_vertex_convex(&self, v: u32) -> bool {
        self.vertex_convex[v as usize]
    }

    /// True when every edge is shared by exactly two triangles with opposite
    /// orientation (a watertight, consistently wound surface).
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Signed volume enclosed (m³): positive when the normals point out,
    /// negative for a room whose normals point in. Meaningful for closed meshes.
    pub fn signed_volume(&self) -> f32 {
        let sum: f64 = (0..self.triangles.len() as u32)
            .map(|i| {
                let [a, b, c] = self.triangle(i).map(|v| v.as_dvec3());
                a.dot(b.cross(c))
            })
            .sum();
        (sum / 6.0) as f32
    }

    /// Total area of the triangles (m²).
    pub fn area(&self) -> f32 {
        let sum: f64 = (0..self.triangles.len() as u32)
            .map(|i| {
                let [a, b, c] = self.triangle(i).map(|v| v.as_dvec3());
                (b - a).cross(c - a).length() * 0.5
            })
            .sum();
        sum as f32
    }

    pub fn aabb(&self) -> Aabb {
        Aabb::from_points(&self.vertices)
    }

    /// Bounding box of triangle `i`.
    #[inline]
    pub fn triangle_aabb(&self, i: u32) -> Aabb {
        Aabb::from_points(&self.triangle(i))
    }

    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// Calls `visit` with every triangle whose bounding box overlaps `aabb`.
    #[inline]
    pub fn query_aabb(&self, aabb: &Aabb, visit: impl FnMut(u32)) {
        self.bvh.query(aabb, visit);
    }

    /// Like `query_aabb`, but stops as soon as `visit` returns true; returns
    /// whether it did.
    #[inline]
    pub fn query_aabb_until(&self, aabb: &Aabb, visit: impl FnMut(u32) -> bool) -> bool {
        self.bvh.query_until(aabb, visit)
    }
}

/// At least one triangle, finite vertices and indices in range: what any
/// triangle mesh needs (`TriMesh::new`, and the fitter's closedness check).
pub fn validate_indices(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Result<(), TriMeshError> {
    if triangles.is_empty() {
        return Err(TriMeshError::Empty);
    }
    if let Some(index) = vertices.iter().position(|v| !v.is_finite()) {
        return Err(TriMeshError::NonFiniteVertex { index });
    }
    for (triangle, t) in triangles.iter().enumerate() {
        if let Some(&vertex) = t.iter().find(|&&v| v as usize >= vertices.len()) {
            return Err(TriMeshError::IndexOutOfRange {
                triangle,
                vertex,
                count: vertices.len(),
            });
        }
    }
    Ok(())
}

/// `(b - a) × (c - a)` normalised, or zero when the triangle has no area.
fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    let n = (b - a).cross(c - a);
    let longest2 = (b - a)
        .length_squared()
        .max((c - a).length_squared())
        .max((c - b).length_squared());
    // Below f32::MIN_POSITIVE the squared length is subnormal and normalising
    // loses precision (a "unit" normal 0.4 % short: found by fuzzing).
    let n2 = n.length_squared();
    if n2 <= DEGENERATE_RATIO * longest2 * longest2 || n2 < f32::MIN_POSITIVE {
        return Vec3::ZERO;
    }
    n.try_normalize().unwrap_or(Vec3::ZERO)
}

#[cfg(test)]
mod face_normal_tests {
    use super::*;

    #[test]
    fn a_triangle_whose_normal_would_be_subnormal_has_none() {
        // Edges of 1e-10 m: the cross product's squared length, 1e-40, is subnormal
        // but not zero, and the longest-edge ratio test alone lets it pass.
        let (a, b, c) = (
            Vec3::ZERO,
            Vec3::new(1e-10, 0.0, 0.0),
            Vec3::new(0.0, 1e-10, 0.0),
        );
        let n2 = (b - a).cross(c - a).length_squared();
        assert!(n2 > 0.0 && n2 < f32::MIN_POSITIVE);
        assert_eq!(face_normal(a, b, c), Vec3::ZERO);
        let n = face_normal(Vec3::ZERO, Vec3::X, Vec3::Y);
        assert!((n.length() - 1.0).abs() < 1e-6 && n.z > 0.0);
    }
}

/// Pairs each directed edge (u, v) with a triangle holding (v, u), classifies
/// it, and reports whether the mesh is closed.
fn build_edge_adjacency(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    normals: &[Vec3],
) -> (Vec<[EdgeAdjacency; 3]>, bool) {
    // Directed edges (from, to, triangle, k), sorted so that a lookup is a
    // binary search and ties resolve by triangle index (deterministic).
    let mut directed: Vec<(u32, u32, u32, u8)> = Vec::with_capacity(triangles.len() * 3);
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            directed.push((tri[k], tri[(k + 1) % 3], t as u32, k as u8));
        }
    }
    directed.sort_unstable();
    let count = |from: u32, to: u32| {
        let lo = directed.partition_point(|e| (e.0, e.1) < (from, to));
        let hi = directed.partition_point(|e| (e.0, e.1) <= (from, to));
        lo..hi
    };

    let boundary = EdgeAdjacency {
        neighbor: None,
        kind: EdgeKind::Boundary,
    };
    let mut edges = vec![[boundary; 3]; triangles.len()];
    let mut closed = true;
    let flat_cos = FLAT_EDGE_ANGLE.cos();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (from, to) = (tri[k], tri[(k + 1) % 3]);
            let same = count(from, to);
            let opposite = count(to, from);
            if same.len() != 1 || opposite.len() != 1 {
                closed = false;
            }
            if opposite.is_empty() {
                continue;
            }
            let n = directed[opposite.start].2;
            let (nt, nn) = (normals[t], normals[n as usize]);
            if nt == Vec3::ZERO || nn == Vec3::ZERO || n as usize == t {
                continue;
            }
            let kind = if nt.dot(nn) >= flat_cos {
                EdgeKind::Flat
            } else {
                let other = triangles[n as usize];
                let far = other
                    .iter()
                    .copied()
                    .find(|&v| v != from && v != to)
                    .unwrap_or(other[0]);
                let rise = (vertices[far as usize] - vertices[from as usize]).dot(nt);
                if rise > 0.0 {
                    EdgeKind::Concave
                } else {
                    EdgeKind::Convex
                }
            };
            edges[t][k] = EdgeAdjacency {
                neighbor: Some(n),
                kind,
            };
        }
    }
    (edges, closed)
}

/// Vertex one-rings as compressed rows (see `TriMesh::ring`).
fn build_vertex_rings(vertex_count: usize, triangles: &[[u32; 3]]) -> (Vec<u32>, Vec<u32>) {
    let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(triangles.len() * 6);
    for tri in triangles {
        for k in 0..3 {
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            if u != v {
                pairs.push((u, v));
                pairs.push((v, u));
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut start = vec![0u32; vertex_count + 1];
    for &(u, _) in &pairs {
        start[u as usize + 1] += 1;
    }
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    (start, pairs.into_iter().map(|(_, v)| v).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_meshes::box_mesh;
    use proptest::prelude::*;

    #[test]
    fn validation_errors_name_the_problem() {
        assert_eq!(
            TriMesh::new(vec![Vec3::ZERO; 3], vec![]).unwrap_err(),
            TriMeshError::Empty
        );
        let bad = vec![Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X];
        assert_eq!(
            TriMesh::new(bad, vec![[0, 1, 2]]).unwrap_err(),
            TriMeshError::NonFiniteVertex { index: 1 }
        );
        assert_eq!(
            TriMesh::new(vec![Vec3::ZERO; 3], vec![[0, 1, 3]]).unwrap_err(),
            TriMeshError::IndexOutOfRange {
                triangle: 0,
                vertex: 3,
                count: 3
            }
        );
    }

    #[test]
    fn box_is_closed_and_its_volume_has_the_right_sign() {
        let outward = box_mesh(Vec3::new(1.0, 2.0, 3.0), false);
        assert!(outward.is_closed());
        assert!((outward.signed_volume() - 6.0).abs() < 1e-5);
        assert!((outward.area() - 22.0).abs() < 1e-5);
        let room = box_mesh(Vec3::new(1.0, 2.0, 3.0), true);
        assert!(room.is_closed());
        assert!((room.signed_volume() + 6.0).abs() < 1e-5);
        // The floor of the room faces up.
        for i in 0..room.triangle_count() as u32 {
            let tri = room.triangle(i);
            if tri.iter().all(|v| v.y == 0.0) {
                assert!(room.normal(i).distance(Vec3::Y) < 1e-6);
            }
        }
    }

    #[test]
    fn edge_kinds_of_a_box_and_a_room() {
        let outward = box_mesh(Vec3::ONE, false);
        let room = box_mesh(Vec3::ONE, true);
        for (mesh, corner_kind) in [(&outward, EdgeKind::Convex), (&room, EdgeKind::Concave)] {
            let (mut flat, mut corner) = (0, 0);
            for i in 0..12 {
                for k in 0..3 {
                    let e = mesh.edge(i, k);
                    assert!(e.neighbor.is_some());
                    if e.kind == EdgeKind::Flat {
                        flat += 1;
                    } else {
                        assert_eq!(e.kind, corner_kind);
                        corner += 1;
                    }
                }
            }
            // One diagonal per face (2 sides), 12 box edges (2 sides each).
            assert_eq!((flat, corner), (12, 24));
        }
        assert!((0..8).all(|v| outward.is_vertex_convex(v)));
        assert!((0..8).all(|v| !room.is_vertex_convex(v)));
        // Three box edges and three face diagonals meet at corner 0.
        assert_eq!(outward.vertex_neighbors(0), &[1, 2, 3, 4, 5, 6]);
    }

    #[test]
    fn open_and_mis_oriented_meshes_are_not_closed() {
        let v = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0)];
        let quad = TriMesh::new(v.clone(), vec![[0, 1, 2], [1, 3, 2]]).unwrap();
        assert!(!quad.is_closed());
        assert_eq!(
            quad.edge(0, 1),
            EdgeAdjacency {
                neighbor: Some(1),
                kind: EdgeKind::Flat
            }
        );
        assert_eq!(quad.edge(0, 0).kind, EdgeKind::Boundary);
        // The second triangle wound the same way as its neighbour: no adjacency.
        let flipped = TriMesh::new(v, vec![[0, 1, 2], [1, 2, 3]]).unwrap();
        assert_eq!(flipped.edge(0, 1).kind, EdgeKind::Boundary);
    }

    #[test]
    fn zero_area_triangles_are_kept_with_a_zero_normal() {
        let v = vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0, Vec3::Y];
        let mesh = TriMesh::new(v, vec![[0, 1, 2], [0, 1, 3]]).unwrap();
        assert!(mesh.is_degenerate(0));
        assert!(!mesh.is_degenerate(1));
        assert_eq!(mesh.normal(0), Vec3::ZERO);
        assert_eq!(mesh.edge(1, 0).kind, EdgeKind::Boundary);
    }

    #[test]
    fn serde_round_trip_rebuilds_and_validates() {
        let mesh = box_mesh(Vec3::ONE, true);
        let json = serde_json::to_string(&mesh).unwrap();
        let back: TriMesh = serde_json::from_str(&json).unwrap();
        assert_eq!(back.bvh(), mesh.bvh());
        assert_eq!(back.triangles(), mesh.triangles());
        assert_eq!(back.vertices(), mesh.vertices());
        let bad = r#"{"vertices":[[0,0,0]],"triangles":[[0,0,1]]}"#;
        let err = serde_json::from_str::<TriMesh>(bad)
            .unwrap_err()
            .to_string();
        assert!(err.contains("refers to vertex 1"), "{err}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn query_aabb_equals_brute_force(
            points in prop::collection::vec((-4.0f32..4.0, -4.0f32..4.0, -4.0f32..4.0), 3..90),
            q in ((-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0), 0.0f32..3.0)
        ) {
            let vertices: Vec<Vec3> = points.iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect();
            let n = vertices.len() as u32;
            let triangles: Vec<[u32; 3]> = (0..n / 3).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
            let mesh = TriMesh::new(vertices, triangles).unwrap();
            let query = Aabb::from_sphere(Vec3::new(q.0 .0, q.0 .1, q.0 .2), q.1);
            let mut found = Vec::new();
            mesh.query_aabb(&query, |t| found.push(t));
            found.sort_unstable();
            let expected: Vec<u32> = (0..mesh.triangle_count() as u32)
                .filter(|&t| mesh.triangle_aabb(t).overlaps(&query))
                .collect();
            prop_assert_eq!(found, expected);
        }
    }
}
