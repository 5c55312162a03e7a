//! A uniform grid of bounding spheres, hashed into buckets and filled by a
//! counting sort (no ordering by value, so the same spheres come out in the
//! same order on any number of threads): which of them a box meets.

use glam::Vec3;
use up_geom::Aabb;

/// Bounding spheres hashed by the cells they overlap.
#[derive(Clone, Debug, Default)]
pub(crate) struct SphereGrid {
    cell: f32,
    mask: u32,
    /// Bucket `k`'s bodies are `bodies[start[k]..start[k + 1]]`.
    start: Vec<u32>,
    bodies: Vec<u32>,
    /// Each sphere's cell range, kept between the counting pass and the filling one.
    ranges: Vec<[[i32; 3]; 2]>,
    /// Each bucket's next free place while filling.
    next: Vec<u32>,
}

fn bucket(ix: i32, iy: i32, iz: i32, mask: u32) -> u32 {
    let h = (ix as u32).wrapping_mul(0x8da6_b343)
        ^ (iy as u32).wrapping_mul(0xd816_3841)
        ^ (iz as u32).wrapping_mul(0xcb1a_b31f);
    h & mask
}

impl SphereGrid {
    /// Hashes `centers[i]`, `radii[i]`.
    pub fn build(&mut self, centers: &[Vec3], radii: &[f32]) {
        let largest = radii.iter().copied().fold(0.0f32, f32::max);
        self.cell = (2.0 * largest).max(0.05);
        let buckets = (2 * centers.len()).next_power_of_two().max(16);
        self.mask = buckets as u32 - 1;
        self.start.clear();
        self.start.resize(buckets + 1, 0);
        self.ranges.clear();
        let inv = 1.0 / self.cell;
        for (c, &r) in centers.iter().zip(radii) {
            let lo = ((*c - r) * inv).floor().as_ivec3().to_array();
            let hi = ((*c + r) * inv).floor().as_ivec3().to_array();
            self.ranges.push([lo, hi]);
        }
        let each_cell = |[lo, hi]: [[i32; 3]; 2], f: &mut dyn FnMut(u32)| {
            for ix in lo[0]..=hi[0] {
                for iy in lo[1]..=hi[1] {
                    for iz in lo[2]..=hi[2] {
                        f(bucket(ix, iy, iz, self.mask));
                    }
                }
            }
        };
        for &range in &self.ranges {
            each_cell(range, &mut |b| self.start[b as usize + 1] += 1);
        }
        for k in 1..self.start.len() {
            self.start[k] += self.start[k - 1];
        }
        self.next.clear();
        self.next.extend_from_slice(&self.start);
        let next = &mut self.next;
        self.bodies.clear();
        self.bodies.resize(self.start[buckets] as usize, 0);
        for (i, &range) in self.ranges.iter().enumerate() {
            each_cell(range, &mut |b| {
                self.bodies[next[b as usize] as usize] = i as u32;
                next[b as usize] += 1;
            });
        }
    }

    /// Appends to `out` each sphere's index whose sphere overlaps `aabb`,
    /// once (in the first cell, by each axis, that both it and the box
    /// cover: not in another cell its bucket shares); reads the grid alone,
    /// so queries may run side by side.
    pub fn query(&self, aabb: &Aabb, centers: &[Vec3], radii: &[f32], out: &mut Vec<u32>) {
        if self.start.is_empty() {
            return;
        }
        let inv = 1.0 / self.cell;
        let lo = (aabb.min * inv).floor().as_ivec3();
        let hi = (aabb.max * inv).floor().as_ivec3();
        // A huge box would walk many empty cells: every body is cheaper then.
        let cells = (hi - lo + 1).as_vec3().element_product();
        if cells > self.start.len() as f32 {
            out.extend((0..centers.len() as u32).filter(|&i| {
                let i = i as usize;
                sphere_meets_box(centers[i], radii[i], aabb)
            }));
            return;
        }
        let lo = lo.to_array();
        for ix in lo[0]..=hi.x {
            for iy in lo[1]..=hi.y {
                for iz in lo[2]..=hi.z {
                    let b = bucket(ix, iy, iz, self.mask) as usize;
                    // A sphere whose cells share a bucket is in it once a
                    // cell, back to back (it is filled a sphere at a time).
                    let mut last = u32::MAX;
                    for &i in &self.bodies[self.start[b] as usize..self.start[b + 1] as usize] {
                        let first = self.ranges[i as usize][0];
                        let cell = [ix, iy, iz];
                        let first_shared = (0..3).all(|a| cell[a] == first[a].max(lo[a]));
                        if i != last
                            && first_shared
                            && sphere_meets_box(centers[i as usize], radii[i as usize], aabb)
                        {
                            out.push(i);
                        }
                        last = i;
                    }
                }
            }
        }
    }
}

pub(crate) fn sphere_meets_box(center: Vec3, radius: f32, aabb: &Aabb) -> bool {
    let closest = center.clamp(aabb.min, aabb.max);
    closest.distance_squared(center) <= radius * radius
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Many spheres, and a few in a grid of few buckets (so that a
    /// sphere's own cells share buckets): each query lists exactly the
    /// spheres that meet its box, each once.
    #[test]
    fn finds_exactly_the_spheres_that_meet_the_box_once() {
        let mut next = crate::hash::uniform(7);
        for count in [500u32, 5] {
            let centers: Vec<Vec3> = (0..count)
                .map(|_| Vec3::new(next(), next(), next()) * 8.0)
                .collect();
            let radii: Vec<f32> = (0..count).map(|_| 0.05 + 0.2 * next()).collect();
            let mut grid = SphereGrid::default();
            grid.build(&centers, &radii);
            for k in 0..200 {
                let lo = Vec3::new(next(), next(), next()) * 7.0;
                let aabb = Aabb::new(lo, lo + Vec3::splat(0.1 + 0.01 * k as f32));
                let mut found = Vec::new();
                grid.query(&aabb, &centers, &radii, &mut found);
                let listed = found.len();
                found.sort_unstable();
                found.dedup();
                assert_eq!(found.len(), listed, "a sphere listed twice");
                let expected: Vec<u32> = (0..count)
                    .filter(|&i| sphere_meets_box(centers[i as usize], radii[i as usize], &aabb))
                    .collect();
                assert_eq!(found, expected);
            }
        }
    }
}
