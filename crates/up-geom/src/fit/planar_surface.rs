//! A flat surface in its mid-plane's frame for the planar fitter
//! (`planar_cover`): its vertices, its triangles by vertex number and by
//! corners, and the same surface split finer.

use std::collections::HashMap;

use glam::DVec3;

/// A surface in the plane's frame: its vertices, and its triangles both as
/// vertex numbers (to gather a sphere's corners once each: neighbouring
/// triangles share theirs) and as corners.
pub(super) struct Surface {
    pub(super) ids: Vec<[u32; 3]>,
    pub(super) points: Vec<DVec3>,
    pub(super) tris: Vec<[DVec3; 3]>,
}

impl Surface {
    pub(super) fn new(ids: Vec<[u32; 3]>, points: Vec<DVec3>) -> Self {
        let tris = ids.iter().map(|t| t.map(|i| points[i as usize])).collect();
        Surface { ids, points, tris }
    }

    /// Each triangle split in four at its edges' midpoints, shared between
    /// the two triangles of an edge. The pieces tile each triangle, so a
    /// sphere that holds a triangle's pieces holds the triangle.
    pub(super) fn split(&self) -> Surface {
        let mut points = self.points.clone();
        let mut middles = HashMap::new();
        let mut middle = |a: u32, b: u32, points: &mut Vec<DVec3>| {
            *middles.entry((a.min(b), a.max(b))).or_insert_with(|| {
                points.push(0.5 * (points[a as usize] + points[b as usize]));
                (points.len() - 1) as u32
            })
        };
        let mut ids = Vec::with_capacity(4 * self.ids.len());
        for &[a, b, c] in &self.ids {
            let (ab, bc, ca) = (
                middle(a, b, &mut points),
                middle(b, c, &mut points),
                middle(c, a, &mut points),
            );
            ids.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        Surface::new(ids, points)
    }

    /// The corners of the triangles `owner` gives sphere `k`, each once, in
    /// the order first met; `seen` marks vertices already taken (reset here).
    pub(super) fn corners_of(&self, owner: &[usize], k: usize, seen: &mut Vec<bool>) -> Vec<DVec3> {
        seen.clear();
        seen.resize(self.points.len(), false);
        let mut corners = Vec::new();
        for (ids, _) in self.ids.iter().zip(owner).filter(|(_, &o)| o == k) {
            for &i in ids {
                if !std::mem::replace(&mut seen[i as usize], true) {
                    corners.push(self.points[i as usize]);
                }
            }
        }
        corners
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_split_surface_tiles_each_triangle_and_shares_its_edges_midpoints() {
        let points = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.2),
            DVec3::new(0.0, 1.0, 0.4),
            DVec3::new(1.0, 1.0, 0.0),
        ];
        let surface = Surface::new(vec![[0, 1, 2], [1, 3, 2]], points);
        let fine = surface.split();
        assert_eq!(fine.tris.len(), 8);
        // 4 corners and 5 edges' midpoints (the shared edge once).
        assert_eq!(fine.points.len(), 9);
        let area = |t: &[DVec3; 3]| 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
        let whole: f64 = surface.tris.iter().map(area).sum();
        let pieces: f64 = fine.tris.iter().map(area).sum();
        assert!((whole - pieces).abs() < 1e-12, "{whole} against {pieces}");
        for t in &fine.tris {
            let normal = (t[1] - t[0]).cross(t[2] - t[0]);
            let before = (surface.tris[0][1] - surface.tris[0][0])
                .cross(surface.tris[0][2] - surface.tris[0][0]);
            assert!(normal.z * before.z > 0.0, "a piece turned over");
        }
    }
}
