//! Where balloons start: spread out on a jittered grid, never overlapping.
//!
//! Each balloon is reduced to its bounding sphere (radius `r`), which any
//! rotation leaves inside a cube of side `2r`. A grid cell is at least that
//! cube plus a small gap, so balloons in different cells never touch. A layer
//! of cells lies over the region's x–z footprint; the coarsest grid that still
//! holds the layer's share of balloons is used, so a few balloons spread over
//! the whole floor instead of huddling in a corner. Cells are jittered within
//! their slack, and chosen by a seeded shuffle when there are more than needed.
//! A cell is usable when its eight corners and centre are inside the room and
//! it overlaps no balloon placed before (other groups). Layers that fill up
//! stack upward until the top of the room.

use std::collections::HashMap;

use glam::Vec3;

use up_geom::SplitMix64;

use super::ribbon_path::WeightedRibbon;

/// Gap between neighbouring balloons' bounding cubes: 5 % of the diameter plus 5 mm.
pub(crate) fn cell_size(radius: f32) -> f32 {
    2.0 * radius * 1.05 + 0.005
}

/// Where one group goes.
#[derive(Clone, Copy, Debug)]
pub struct SpawnRegion {
    /// Lower corner: x–z footprint start, and the bottom of the first layer, m.
    pub min: Vec3,
    /// Upper corner: x–z footprint end; layers below `max.y` share the balloons
    /// evenly, further layers stack above it, m.
    pub max: Vec3,
    /// No layer may reach above this, m (the top of the room).
    pub top: f32,
}

/// Bounding spheres already placed, bucketed for overlap queries (lookups only:
/// the map's iteration order never affects the result).
#[derive(Clone, Default)]
pub struct Occupancy {
    spheres: Vec<(Vec3, f32)>,
    /// Parallel to `spheres`: a weighted ribbon's path (`insert_path`),
    /// which other ribbons may cross, rather than a balloon.
    paths: Vec<bool>,
    buckets: HashMap<(i32, i32, i32), Vec<u32>>,
}

/// Bucket edge, m.
const BUCKET: f32 = 1.0;

fn bucket_range(min: Vec3, max: Vec3) -> impl Iterator<Item = (i32, i32, i32)> {
    let lo = (min / BUCKET).floor().as_ivec3();
    let hi = (max / BUCKET).floor().as_ivec3();
    (lo.x..=hi.x)
        .flat_map(move |x| (lo.y..=hi.y).flat_map(move |y| (lo.z..=hi.z).map(move |z| (x, y, z))))
}

impl Occupancy {
    pub fn insert(&mut self, center: Vec3, radius: f32) {
        self.insert_kind(center, radius, false);
    }

    /// A piece of a weighted ribbon's path: balloons keep out of it, other
    /// ribbons' paths may cross it (laid crossing, ribbons that touch are
    /// eased apart; by default they pass through each other).
    pub(crate) fn insert_path(&mut self, center: Vec3, radius: f32) {
        self.insert_kind(center, radius, true);
    }

    fn insert_kind(&mut self, center: Vec3, radius: f32, path: bool) {
        let index = self.spheres.len() as u32;
        self.spheres.push((center, radius));
        self.paths.push(path);
        for key in bucket_range(center - Vec3::splat(radius), center + Vec3::splat(radius)) {
            self.buckets.entry(key).or_default().push(index);
        }
    }

    /// Whether a sphere of `radius` at `center` comes within `radius` of any
    /// placed sphere (their true distance, not their boxes).
    pub(crate) fn overlaps_sphere(&self, center: Vec3, radius: f32) -> bool {
        let reach = Vec3::splat(radius);
        self.any_near(center - reach, center + reach, |c, r| {
            c.distance_squared(center) < (r + radius) * (r + radius)
        })
    }

    /// Whether a sphere of `radius` at `center` comes within `radius` of any
    /// placed balloon (ribbons' paths left out).
    pub(crate) fn overlaps_balloon(&self, center: Vec3, radius: f32) -> bool {
        let reach = Vec3::splat(radius);
        self.any_near_kind(center - reach, center + reach, false, |c, r| {
            c.distance_squared(center) < (r + radius) * (r + radius)
        })
    }

    /// Whether a vertical cylinder of `radius` about `x`–`z`, from `y_lo` to
    /// `y_hi`, comes within `radius` of any placed sphere.
    pub(crate) fn overlaps_column(
        &self,
        x: f32,
        z: f32,
        y_lo: f32,
        y_hi: f32,
        radius: f32,
    ) -> bool {
        let min = Vec3::new(x - radius, y_lo, z - radius);
        let max = Vec3::new(x + radius, y_hi, z + radius);
        self.any_near(min, max, |c, r| {
            let (dx, dz) = (c.x - x, c.z - z);
            c.y + r > y_lo && c.y - r < y_hi && dx * dx + dz * dz < (r + radius) * (r + radius)
        })
    }

    /// Whether `hit` holds for any placed sphere (centre, radius) that
    /// reaches into the box from `min` to `max`.
    fn any_near(&self, min: Vec3, max: Vec3, hit: impl Fn(Vec3, f32) -> bool) -> bool {
        self.any_near_kind(min, max, true, hit)
    }

    /// `any_near`, over paths too where `with_paths`.
    fn any_near_kind(
        &self,
        min: Vec3,
        max: Vec3,
        with_paths: bool,
        hit: impl Fn(Vec3, f32) -> bool,
    ) -> bool {
        // A sphere is in every bucket its box touches, so one that reaches
        // the query's box is in one of its buckets; one in several is tested again.
        bucket_range(min, max).any(|key| {
            self.buckets.get(&key).is_some_and(|list| {
                list.iter().any(|&i| {
                    let (c, r) = self.spheres[i as usize];
                    (with_paths || !self.paths[i as usize]) && hit(c, r)
                })
            })
        })
    }

    /// Whether the box overlaps any placed sphere's bounding box.
    fn overlaps_box(&self, min: Vec3, max: Vec3) -> bool {
        bucket_range(min, max).any(|key| {
            self.buckets.get(&key).is_some_and(|list| {
                list.iter().any(|&i| {
                    let (c, r) = self.spheres[i as usize];
                    (c + Vec3::splat(r)).cmpgt(min).all() && (c - Vec3::splat(r)).cmplt(max).all()
                })
            })
        })
    }
}

/// A grid over the footprint: `nx × nz` cells of `cell_x × cell_z`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Grid {
    pub nx: usize,
    pub nz: usize,
    pub cell_x: f32,
    pub cell_z: f32,
}

/// Places up to `count` bounding spheres of `radius`; returns their centres
/// (fewer than `count` when the room is full). `inside` says whether a point
/// is inside the room.
pub fn place_spheres(
    count: usize,
    radius: f32,
    region: &SpawnRegion,
    inside: &dyn Fn(Vec3) -> bool,
    occupied: &mut Occupancy,
    rng: &mut SplitMix64,
) -> Vec<Vec3> {
    place(count, radius, region, inside, occupied, rng, None)
}

/// `place_spheres` for balloons on weighted ribbons: a balloon goes only
/// where its bounding sphere and its ribbon's whole start path are clear of
/// everything placed (the balloons of its own layer, and the paths reserved
/// before it, included), and its path is reserved (`ribbon_path`). Where
/// nothing is in the way, the same layout as `place_spheres`.
pub(super) fn place_spheres_clear_of_ribbons(
    count: usize,
    radius: f32,
    region: &SpawnRegion,
    inside: &dyn Fn(Vec3) -> bool,
    occupied: &mut Occupancy,
    rng: &mut SplitMix64,
    ribbon: &WeightedRibbon,
) -> Vec<Vec3> {
    place(count, radius, region, inside, occupied, rng, Some(ribbon))
}

fn place(
    count: usize,
    radius: f32,
    region: &SpawnRegion,
    inside: &dyn Fn(Vec3) -> bool,
    occupied: &mut Occupancy,
    rng: &mut SplitMix64,
    ribbon: Option<&WeightedRibbon>,
) -> Vec<Vec3> {
    let mut placed = Vec::with_capacity(count);
    let c = cell_size(radius);
    let (width, depth) = (region.max.x - region.min.x, region.max.z - region.min.z);
    let (fine_nx, fine_nz) = ((width / c).floor() as usize, (depth / c).floor() as usize);
    if fine_nx == 0 || fine_nz == 0 || count == 0 {
        return placed;
    }
    let region_layers = (((region.max.y - region.min.y) / c).floor() as usize).max(1);
    let fine = Grid {
        nx: fine_nx,
        nz: fine_nz,
        cell_x: width / fine_nx as f32,
        cell_z: depth / fine_nz as f32,
    };
    let mut layer = 0usize;
    loop {
        let bottom = region.min.y + layer as f32 * c;
        let remaining = count - placed.len();
        if remaining == 0 || bottom + c > region.top {
            break;
        }
        // Layers inside the region share what is left evenly; above it, fill.
        let target = if layer < region_layers {
            remaining.div_ceil(region_layers - layer)
        } else {
            remaining
        };
        let usable = |grid: &Grid| usable_cells(grid, region, bottom, c, inside, occupied);
        let mut chosen: Option<(Grid, Vec<usize>)> = None;
        if target < fine.nx * fine.nz {
            for grid in coarse_grids(target, width, depth, c) {
                let cells = usable(&grid);
                if cells.len() >= target {
                    chosen = Some((grid, cells));
                    break;
                }
            }
        }
        let (grid, mut cells) = chosen.unwrap_or_else(|| (fine, usable(&fine)));
        // Cells beyond the layer's share, in the shuffle's order: where a
        // ribbon's path is in the way of a chosen cell, the next spare is tried.
        let mut spares = Vec::new();
        if cells.len() > target {
            rng.shuffle(&mut cells);
            if ribbon.is_some() {
                spares = cells.split_off(target);
            } else {
                cells.truncate(target);
            }
            cells.sort_unstable();
        }
        let before = placed.len();
        for cell in cells.into_iter().chain(spares) {
            if placed.len() - before == target {
                break;
            }
            let (ix, iz) = (cell % grid.nx, cell / grid.nx);
            let slack_x = (grid.cell_x - 2.0 * radius) * 0.5;
            let slack_z = (grid.cell_z - 2.0 * radius) * 0.5;
            let center = Vec3::new(
                region.min.x + (ix as f32 + 0.5) * grid.cell_x + rng.range(-slack_x, slack_x) * 0.9,
                bottom + 0.5 * c,
                region.min.z + (iz as f32 + 0.5) * grid.cell_z + rng.range(-slack_z, slack_z) * 0.9,
            );
            if let Some(ribbon) = ribbon {
                if occupied.overlaps_sphere(center, radius) || !ribbon.clear(center, occupied) {
                    continue;
                }
                occupied.insert(center, radius);
                ribbon.reserve(center, occupied);
            } else {
                occupied.insert(center, radius);
            }
            placed.push(center);
        }
        layer += 1;
    }
    placed
}

/// Lattice steps per cell edge in `fill_gaps`: candidates every sixth of a cell.
const GAP_STEPS_PER_CELL: f32 = 6.0;
/// m between a balloon laid in the gaps and anything placed before it.
const GAP_CLEARANCE: f32 = 0.005;

/// Where the layers leave no whole cell free but the room still has room
/// (a second group above a first, among the columns of weighted ribbons, a
/// pyramid's slopes): up to `count` more bounding spheres of `radius` at
/// points of a lattice a sixth of a cell apart, lowest first, each
/// `GAP_CLEARANCE` clear of everything placed and inside the room with its
/// bounding cube. Deterministic, no draws: what the layers
/// placed stays as it was, so a scene that fits its layers lays out as
/// before. A weighted ribbon's path is kept clear and reserved as `place`
/// does.
pub(super) fn fill_gaps(
    count: usize,
    radius: f32,
    region: &SpawnRegion,
    inside: &dyn Fn(Vec3) -> bool,
    occupied: &mut Occupancy,
    ribbon: Option<&WeightedRibbon>,
) -> Vec<Vec3> {
    let mut placed = Vec::new();
    let c = cell_size(radius);
    // Clear of every placed sphere by `GAP_CLEARANCE`: true distances, so the
    // next level settles into the hollows of the one below.
    let reach = radius + GAP_CLEARANCE;
    let step = c / GAP_STEPS_PER_CELL;
    let lo = region.min + Vec3::splat(radius);
    let (hi_x, hi_z, hi_y) = (
        region.max.x - radius,
        region.max.z - radius,
        region.top - radius,
    );
    if count == 0 || lo.x > hi_x || lo.z > hi_z {
        return placed;
    }
    let n = |from: f32, to: f32| ((to - from) / step).floor() as usize + 1;
    let (nx, nz) = (n(lo.x, hi_x), n(lo.z, hi_z));
    let cube_inside = |p: Vec3| {
        (0..8).all(|k| {
            let corner = |bit: usize| if k & bit == 0 { -radius } else { radius };
            inside(p + Vec3::new(corner(1), corner(2), corner(4)))
        }) && inside(p)
    };
    let mut y = lo.y;
    while y <= hi_y && placed.len() < count {
        for iz in 0..nz {
            for ix in 0..nx {
                if placed.len() == count {
                    return placed;
                }
                let p = Vec3::new(lo.x + ix as f32 * step, y, lo.z + iz as f32 * step);
                if occupied.overlaps_sphere(p, reach) || !cube_inside(p) {
                    continue;
                }
                if let Some(ribbon) = ribbon {
                    if !ribbon.clear(p, occupied) {
                        continue;
                    }
                    occupied.insert(p, radius);
                    ribbon.reserve(p, occupied);
                } else {
                    occupied.insert(p, radius);
                }
                placed.push(p);
            }
        }
        y += step;
    }
    placed
}

/// Grids that hold at least `target` cells, coarsest (largest cells) first.
pub(crate) fn coarse_grids(target: usize, width: f32, depth: f32, c: f32) -> Vec<Grid> {
    let max_nx = (width / c).floor() as usize;
    let max_nz = (depth / c).floor() as usize;
    let mut grids: Vec<Grid> = (1..=max_nx)
        .filter_map(|nx| {
            let nz = target.div_ceil(nx).max(1);
            (nz <= max_nz).then(|| Grid {
                nx,
                nz,
                cell_x: width / nx as f32,
                cell_z: depth / nz as f32,
            })
        })
        .collect();
    // Largest smallest side first; ties keep the order of nx (stable sort).
    grids.sort_by(|a, b| b.cell_x.min(b.cell_z).total_cmp(&a.cell_x.min(a.cell_z)));
    grids
}

/// Indices (`ix + iz·nx`) of the cells of one layer that are inside the room and free.
fn usable_cells(
    grid: &Grid,
    region: &SpawnRegion,
    bottom: f32,
    c: f32,
    inside: &dyn Fn(Vec3) -> bool,
    occupied: &Occupancy,
) -> Vec<usize> {
    let mut cells = Vec::new();
    for iz in 0..grid.nz {
        for ix in 0..grid.nx {
            let min = Vec3::new(
                region.min.x + ix as f32 * grid.cell_x,
                bottom,
                region.min.z + iz as f32 * grid.cell_z,
            );
            let max = min + Vec3::new(grid.cell_x, c, grid.cell_z);
            let corners_inside = (0..8).all(|k| {
                let pick = |bit: usize, lo: f32, hi: f32| if k & bit == 0 { lo } else { hi };
                inside(Vec3::new(
                    pick(1, min.x, max.x),
                    pick(2, min.y, max.y),
                    pick(4, min.z, max.z),
                ))
            });
            if corners_inside && inside((min + max) * 0.5) && !occupied.overlaps_box(min, max) {
                cells.push(ix + iz * grid.nx);
            }
        }
    }
    cells
}

#[cfg(test)]
mod tests {
    use super::*;

    fn box_inside(half: Vec3, height: f32) -> impl Fn(Vec3) -> bool {
        move |p: Vec3| p.x.abs() <= half.x && p.z.abs() <= half.z && p.y >= 0.0 && p.y <= height
    }

    fn floor_region(half: f32, top: f32) -> SpawnRegion {
        SpawnRegion {
            min: Vec3::new(-half, 0.01, -half),
            max: Vec3::new(half, 0.01, half),
            top,
        }
    }

    fn assert_apart(centres: &[Vec3], radius: f32) {
        for (i, a) in centres.iter().enumerate() {
            for b in &centres[i + 1..] {
                assert!(a.distance(*b) > 2.0 * radius, "{a} and {b} overlap");
            }
        }
    }

    #[test]
    fn fifty_balloons_spread_over_the_floor_without_overlap() {
        let inside = box_inside(Vec3::new(3.0, 0.0, 3.0), 3.0);
        let mut occ = Occupancy::default();
        let mut rng = SplitMix64::new(1);
        let r = 0.2;
        let c = place_spheres(50, r, &floor_region(2.99, 3.0), &inside, &mut occ, &mut rng);
        assert_eq!(c.len(), 50);
        assert_apart(&c, r);
        assert!(
            c.iter()
                .all(|p| (p.y - (0.01 + 0.5 * cell_size(r))).abs() < 1e-5),
            "one layer"
        );
        // Spread out: they reach near every wall.
        let max_x = c.iter().map(|p| p.x).fold(f32::MIN, f32::max);
        let min_z = c.iter().map(|p| p.z).fold(f32::MAX, f32::min);
        assert!(max_x > 2.0 && min_z < -2.0, "{max_x} {min_z}");
    }

    #[test]
    fn too_many_for_one_layer_stack_upward_and_stop_at_the_top() {
        let inside = box_inside(Vec3::new(1.0, 0.0, 1.0), 1.5);
        let mut occ = Occupancy::default();
        let mut rng = SplitMix64::new(3);
        let r = 0.3; // cell 0.635 m: 3 × 3 per layer, 2 layers below 1.5 m
        let c = place_spheres(
            100,
            r,
            &floor_region(0.99, 1.5),
            &inside,
            &mut occ,
            &mut rng,
        );
        assert_eq!(c.len(), 18);
        assert_apart(&c, r);
        assert!(c.iter().all(|p| p.y + r <= 1.5));
    }

    #[test]
    fn later_groups_avoid_earlier_ones() {
        let inside = box_inside(Vec3::new(2.0, 0.0, 2.0), 3.0);
        let mut occ = Occupancy::default();
        let mut rng = SplitMix64::new(5);
        let region = floor_region(1.99, 3.0);
        let mut all = place_spheres(20, 0.15, &region, &inside, &mut occ, &mut rng);
        all.extend(place_spheres(
            20, 0.15, &region, &inside, &mut occ, &mut rng,
        ));
        assert_eq!(all.len(), 40);
        assert_apart(&all, 0.15);
    }

    #[test]
    fn layout_is_deterministic_for_a_seed() {
        let inside = box_inside(Vec3::new(3.0, 0.0, 3.0), 3.0);
        let run = |seed| {
            let mut occ = Occupancy::default();
            let mut rng = SplitMix64::new(seed);
            place_spheres(
                30,
                0.14,
                &floor_region(2.99, 3.0),
                &inside,
                &mut occ,
                &mut rng,
            )
        };
        assert_eq!(run(9), run(9));
        assert_ne!(run(9), run(10));
    }

    #[test]
    fn sphere_and_column_queries_measure_true_distance() {
        let mut occ = Occupancy::default();
        occ.insert(Vec3::new(0.0, 1.0, 0.0), 0.2);
        // Inside the placed sphere's box but 0.43 m from its centre: clear.
        assert!(!occ.overlaps_sphere(Vec3::new(0.25, 1.25, 0.25), 0.1));
        assert!(occ.overlaps_sphere(Vec3::new(0.25, 1.0, 0.0), 0.1));
        // A column beside it, one through its edge, one that stops below it.
        assert!(!occ.overlaps_column(0.3, 0.0, 0.0, 2.0, 0.05));
        assert!(occ.overlaps_column(0.2, 0.0, 0.0, 2.0, 0.05));
        assert!(!occ.overlaps_column(0.0, 0.0, 0.0, 0.7, 0.05));
        // A sphere across a bucket's edge is found from the next bucket.
        occ.insert(Vec3::new(0.99, 0.5, 0.0), 0.05);
        assert!(occ.overlaps_sphere(Vec3::new(1.05, 0.5, 0.0), 0.02));
        assert!(!occ.overlaps_sphere(Vec3::new(1.08, 0.5, 0.0), 0.02));
    }

    #[test]
    fn the_gaps_take_what_the_layers_leave_without_overlap() {
        // A round room 1 m across: no whole cell of a layer fits inside it,
        // but balls do, at the lattice's points.
        let inside = |p: Vec3| p.x * p.x + p.z * p.z <= 0.25 && p.y >= 0.0 && p.y <= 1.5;
        let mut occ = Occupancy::default();
        let mut rng = SplitMix64::new(3);
        let region = floor_region(0.49, 1.5);
        let r = 0.2;
        let mut c = place_spheres(10, r, &region, &inside, &mut occ, &mut rng);
        assert!(c.is_empty());
        c.extend(fill_gaps(10, r, &region, &inside, &mut occ, None));
        assert!(c.len() >= 3, "{c:?}");
        assert_apart(&c, r);
        for p in &c {
            for k in 0..8 {
                let corner = |bit: usize| if k & bit == 0 { -r } else { r };
                assert!(
                    inside(*p + Vec3::new(corner(1), corner(2), corner(4))),
                    "{p}"
                );
            }
        }
        // None when nothing is missing; the same twice over.
        assert!(fill_gaps(0, r, &region, &inside, &mut occ, None).is_empty());
        let again = || fill_gaps(10, r, &region, &inside, &mut Occupancy::default(), None);
        assert_eq!(again(), again());
    }

    #[test]
    fn region_narrower_than_a_balloon_places_nothing() {
        let inside = box_inside(Vec3::new(3.0, 0.0, 3.0), 3.0);
        let region = SpawnRegion {
            min: Vec3::ZERO,
            max: Vec3::new(0.1, 1.0, 1.0),
            top: 3.0,
        };
        let c = place_spheres(
            1,
            0.2,
            &region,
            &inside,
            &mut Occupancy::default(),
            &mut SplitMix64::new(1),
        );
        assert!(c.is_empty());
    }
}
