//! Broadphase: candidate body pairs from a uniform grid.
//!
//! Balloons are similar in size, so a grid whose cells are as wide as the
//! largest ordinary bounding sphere finds every overlapping pair by looking at
//! the 27 cells around each body: linear in the number of bodies. Each body
//! sits in the one cell holding its centre; the cells' buckets (`Buckets`)
//! are filled by a counting sort, so nothing is allocated once the buffers
//! have grown.
//!
//! The lookups are the cost, so the table is laid out for them. Where the
//! bodies' cells fill a box of not many more cells than bodies (a room's
//! crowd), each cell of the box, with one more all round, has a bucket of its
//! own, z fastest (`Buckets`): the cells around a body and their entries lie
//! in a few runs of memory, which the lookups of the bodies beside it read
//! again. Otherwise (bodies strewn far apart) a column of cells along z
//! hashes to consecutive buckets (one hash, three buckets side by side).
//! Either way the buckets are filled in body order and a lookup keeps a
//! bucket's entries of its cell: the same pairs in the same order. Each
//! bucket entry carries its body's cell, sphere and wakefulness, so a scan
//! reads memory in order instead of jumping between the bodies' arrays. A lookup skips the cells (and whole columns) lying
//! farther from the body's centre than its radius plus the largest radius in
//! the grid: the cells are sized for a brisk ascent, a settling pile's bodies
//! reach about half of the 27.
//!
//! Most steps move few bodies (a pile asleep, one balloon awake among them),
//! so the table is kept between steps: a body that stays in its cell is
//! updated in place (the sleepers, unchanged, are passed over), and only a
//! body changing cells, the count or the cell size changing, or a large body
//! rebuilds the table. Kept or rebuilt, it gives the same pairs.
//!
//! A fast body (thrown by the user) has a bounding sphere swollen by its
//! motion this step. It would blow up the cell size for everyone, so such
//! "large" bodies stay out of the grid: each one queries the cells its sphere
//! covers, and large bodies meet each other by sweep and prune along x.
//!
//! Pairs come out in a fixed order (by body, then cell, then body) so the
//! step is deterministic, also when the bodies' lookups run in tasks on
//! several threads (`parallel` feature).

use glam::Vec3;

use crate::hash::mix64;
use crate::threading::spare::{release_spare, release_spare_each, BUFFER_FLOOR};
use crate::threading::tasks::collect_in_order;

/// Bodies whose neighbours one task looks up.
const BODY_CHUNK: usize = 512;

/// Updates after a refresh of the kept table failed among bodies most of
/// which had moved (a crowd on the move, whose bodies change cells every
/// step) that rebuild it without trying one: a refresh that fails has read
/// the entries before the failing body for nothing, and the table rebuilt
/// gives the same pairs.
const REFRESH_SKIPS: u32 = 7;

#[derive(Clone, Debug, Default)]
pub(crate) struct BroadPhase {
    cell_of: Vec<[i32; 3]>,
    /// Bucket b holds `items[start[b]..start[b + 1]]`.
    start: Vec<u32>,
    cursor: Vec<u32>,
    items: Vec<GridItem>,
    large: Vec<u32>,
    /// The cells' size and how far their bodies reach, as `update` left them.
    scale: GridScale,
    /// Which bucket each cell's bodies are in.
    buckets: Buckets,
    /// Each ordinary body's place in `items` (`LARGE` for a large one).
    slot_of: Vec<u32>,
    /// Each body's bucket (`LARGE` for a large one), and the body of each
    /// entry of `items`: `rebuild`'s counting sort.
    bucket_of: Vec<u32>,
    body_at: Vec<u32>,
    /// The box of each task's bodies' cells, for `rebuild`.
    task_boxes: Vec<CellBox>,
    /// The cell radius the table was built for (`f32::NAN`: none built).
    built_for: f32,
    /// Updates left that rebuild the table without trying to refresh it.
    skip_refresh: u32,
    /// Output: dense index pairs (a < b), at least one of them awake.
    pub pairs: Vec<(u32, u32)>,
    /// Each task's pairs (kept between steps for their buffers).
    task_pairs: Vec<Vec<(u32, u32)>>,
}

impl BroadPhase {
    /// Gives back the capacity this step's pairs left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.pairs, BUFFER_FLOOR);
        release_spare_each(&mut self.task_pairs);
    }

    /// Finds all pairs whose bounding spheres overlap.
    ///
    /// `radius[i]` is body i's bounding radius already expanded by its
    /// speculative margin; `cell_radius` is the largest radius an ordinary
    /// body may have (it sets the cell size); larger ones are "large".
    pub fn update(&mut self, center: &[Vec3], radius: &[f32], awake: &[bool], cell_radius: f32) {
        let n = center.len();
        self.pairs.clear();
        if n == 0 {
            self.large.clear();
            self.built_for = f32::NAN;
            return;
        }
        // A crowd on the move changes cells every step: after a refresh
        // that failed among bodies most of which moved, the next few
        // updates rebuild without trying one.
        if self.skip_refresh > 0 {
            self.skip_refresh -= 1;
            self.rebuild(center, radius, awake, cell_radius);
        } else if let Refreshed::Failed { most_moved } =
            self.refresh(center, radius, awake, cell_radius)
        {
            self.skip_refresh = if most_moved { REFRESH_SKIPS } else { 0 };
            self.rebuild(center, radius, awake, cell_radius);
        }
        let inv_cell = self.scale.inv_cell;

        // Awake ordinary bodies: the 27 cells around each. A pair of awake
        // bodies is found from the lower index, an awake-asleep pair from
        // the awake one; two sleepers make no pair, so a sleeping pile costs
        // only its place in the grid.
        // In tasks of consecutive bodies, joined in body order.
        let grid = Grid::of(
            &self.cell_of,
            &self.start,
            &self.items,
            self.scale,
            self.buckets,
        );
        collect_in_order(
            n,
            BODY_CHUNK,
            &mut self.task_pairs,
            &mut self.pairs,
            |bodies, pairs| {
                for i in bodies {
                    if radius[i] > cell_radius || !awake[i] {
                        continue;
                    }
                    let (ci, ri) = (center[i], radius[i]);
                    grid.near(i, ci, ri, |item| {
                        if item.body as usize > i || !item.awake {
                            let other = (item.body, item.center, item.radius);
                            push_if_overlapping(pairs, (i as u32, ci, ri), other);
                        }
                    });
                }
            },
        );

        // Large bodies against ordinary ones: every cell their sphere can reach.
        for &l in &self.large {
            let li = l as usize;
            let reach = radius[li] + cell_radius;
            let lo = cell_coords(center[li] - Vec3::splat(reach), inv_cell);
            let hi = cell_coords(center[li] + Vec3::splat(reach), inv_cell);
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        let key = cell_key([x, y, z]);
                        let Some(b) = grid.buckets.of_cell([x, y, z]) else {
                            continue;
                        };
                        for item in grid.bucket(b) {
                            if item.cell == key {
                                consider(&mut self.pairs, l, item.body, center, radius, awake);
                            }
                        }
                    }
                }
            }
        }

        // Large bodies against each other: sweep and prune along x.
        let large = &mut self.large;
        large.sort_unstable_by(|&a, &b| {
            let ka = center[a as usize].x - radius[a as usize];
            let kb = center[b as usize].x - radius[b as usize];
            ka.total_cmp(&kb).then(a.cmp(&b))
        });
        for (s, &a) in large.iter().enumerate() {
            let max_x = center[a as usize].x + radius[a as usize];
            for &b in &large[s + 1..] {
                if center[b as usize].x - radius[b as usize] > max_x {
                    break;
                }
                consider(&mut self.pairs, a, b, center, radius, awake);
            }
        }
    }
}

impl BroadPhase {
    /// Brings the table kept from the last step up to `center`, `radius` and
    /// `awake` in place, where no body changed cells, none is or was large,
    /// and the count and cell size are the same; says it failed otherwise
    /// (the table then needs `rebuild`). Only the bodies whose entries
    /// changed are written: a sleeper's are as it fell asleep.
    fn refresh(
        &mut self,
        center: &[Vec3],
        radius: &[f32],
        awake: &[bool],
        cell_radius: f32,
    ) -> Refreshed {
        let n = center.len();
        if self.built_for.to_bits() != cell_radius.to_bits()
            || self.slot_of.len() != n
            || !self.large.is_empty()
        {
            return Refreshed::Failed { most_moved: false };
        }
        let inv_cell = self.scale.inv_cell;
        // A bound on the ordinary radii: lookups skip only the cells
        // farther than it reaches, so the pairs are those of the exact
        // largest (which the next rebuild takes again).
        let mut item_radius = self.scale.item_radius;
        let mut moved = 0;
        for i in 0..n {
            let item = &mut self.items[self.slot_of[i] as usize];
            // Equal as numbers: a zero that changed sign moves nothing (the
            // same cell, the same distances); a NaN is written again.
            if item.center == center[i] && item.radius == radius[i] && item.awake == awake[i] {
                continue;
            }
            if radius[i] > cell_radius || cell_coords(center[i], inv_cell) != self.cell_of[i] {
                return Refreshed::Failed {
                    most_moved: 2 * moved > i,
                };
            }
            moved += 1;
            item.center = center[i];
            item.radius = radius[i];
            item.awake = awake[i];
            item_radius = item_radius.max(radius[i]);
        }
        self.scale.item_radius = item_radius;
        Refreshed::Kept
    }
}

impl BroadPhase {
    /// After bodies woke (`awake` now, `was_awake` at the last `update`, the
    /// grid and the bodies' spheres unchanged since): adds the pairs the
    /// update skipped because both bodies slept then, and one of them is now
    /// awake. Appended after the update's pairs, in the same fixed order.
    /// Returns false, doing nothing, when there are large bodies: their pairs
    /// need the whole `update` again.
    pub fn add_woken_pairs(
        &mut self,
        center: &[Vec3],
        radius: &[f32],
        was_awake: &[bool],
        awake: &[bool],
    ) -> bool {
        if !self.large.is_empty() {
            return false;
        }
        let grid = Grid::of(
            &self.cell_of,
            &self.start,
            &self.items,
            self.scale,
            self.buckets,
        );
        for i in 0..center.len() {
            if !awake[i] || was_awake[i] {
                continue;
            }
            grid.near(i, center[i], radius[i], |item| {
                let j = item.body as usize;
                // Slept at the update; two woken bodies meet once.
                if !was_awake[j] && (j > i || !awake[j]) {
                    consider(&mut self.pairs, i as u32, j as u32, center, radius, awake);
                }
            });
        }
        true
    }
}

/// What `BroadPhase::refresh` did.
enum Refreshed {
    Kept,
    /// The table needs a rebuild: a body changed cells or became large, or
    /// the body count, the cell size or the large bodies changed. Whether
    /// most of the bodies before the one that changed cells had moved.
    Failed {
        most_moved: bool,
    },
}

/// An ordinary body in the grid's table, with what its neighbours' scans read.
#[derive(Clone, Copy, Debug, Default)]
struct GridItem {
    center: Vec3,
    /// Bounding radius with the speculative margin.
    radius: f32,
    /// `cell_key` of its cell.
    cell: u64,
    body: u32,
    /// Awake at the update.
    awake: bool,
}

/// The grid's cells per metre, and the largest radius among its bodies.
#[derive(Clone, Copy, Debug, Default)]
struct GridScale {
    inv_cell: f32,
    item_radius: f32,
}

/// Slack, in cells, on a lookup's reach: more than the rounding of the
/// centres' cell coordinates where cells are skipped (`SKIP_WITHIN`).
const REACH_SLACK: f32 = 4.0e-3;
/// Cell coordinates beyond which a lookup skips nothing along that axis: out
/// there a coordinate's rounding nears `REACH_SLACK` (and the clamped
/// coordinates of far bodies say nothing of where they are).
const SKIP_WITHIN: f32 = 4096.0;

/// The grid as `update` left it, for looking up a body's neighbours.
struct Grid<'a> {
    cell_of: &'a [[i32; 3]],
    start: &'a [u32],
    items: &'a [GridItem],
    buckets: Buckets,
    scale: GridScale,
}

impl<'a> Grid<'a> {
    /// The grid of `BroadPhase`'s fields (borrowed apart, so that `pairs` stays free).
    fn of(
        cell_of: &'a [[i32; 3]],
        start: &'a [u32],
        items: &'a [GridItem],
        scale: GridScale,
        buckets: Buckets,
    ) -> Grid<'a> {
        Grid {
            cell_of,
            start,
            items,
            buckets,
            scale,
        }
    }

    #[inline]
    fn bucket(&self, b: usize) -> &'a [GridItem] {
        &self.items[self.start[b] as usize..self.start[b + 1] as usize]
    }

    /// Calls `visit` with each ordinary body in the 27 cells around body
    /// `i`'s cell: cell by cell (x, then y, then z), each cell's bodies in
    /// body order; but not in the cells that body i's sphere (`center`,
    /// `radius`) cannot reach, whose bodies it cannot overlap.
    #[inline]
    fn near(&self, i: usize, center: Vec3, radius: f32, mut visit: impl FnMut(&GridItem)) {
        let [x, y, z] = self.cell_of[i];
        let gaps = self.gaps(self.cell_of[i], center);
        let reach = (radius + self.scale.item_radius) * self.scale.inv_cell + REACH_SLACK;
        let reach_sq = reach * reach;
        for dx in -1..=1 {
            let gap_x = gaps[0][(dx + 1) as usize];
            if gap_x > reach_sq {
                continue;
            }
            for dy in -1..=1 {
                let gap_xy = gap_x + gaps[1][(dy + 1) as usize];
                if gap_xy > reach_sq {
                    continue;
                }
                let column = self.buckets.column(x + dx, y + dy);
                for dz in -1..=1 {
                    if gap_xy + gaps[2][(dz + 1) as usize] > reach_sq {
                        continue;
                    }
                    let target = cell_key([x + dx, y + dy, z + dz]);
                    for item in self.bucket(self.buckets.in_column(column, z + dz)) {
                        if item.cell == target {
                            visit(item);
                        }
                    }
                }
            }
        }
    }

    /// Along each axis, the squared distance in cells from `center` (in
    /// `cell`) to the neighbouring cells below, alike and above: 0 for its
    /// own cell and wherever the cell coordinates are too coarse to tell.
    #[inline]
    fn gaps(&self, cell: [i32; 3], center: Vec3) -> [[f32; 3]; 3] {
        let scaled = (center * self.scale.inv_cell).to_array();
        std::array::from_fn(|axis| {
            let f = scaled[axis];
            let t = f - cell[axis] as f32;
            if f.abs() < SKIP_WITHIN && (0.0..=1.0).contains(&t) {
                [t * t, 0.0, (1.0 - t) * (1.0 - t)]
            } else {
                [0.0; 3]
            }
        })
    }
}

#[inline]
fn consider(
    pairs: &mut Vec<(u32, u32)>,
    a: u32,
    b: u32,
    center: &[Vec3],
    radius: &[f32],
    awake: &[bool],
) {
    let (ia, ib) = (a as usize, b as usize);
    if awake[ia] || awake[ib] {
        push_if_overlapping(
            pairs,
            (a, center[ia], radius[ia]),
            (b, center[ib], radius[ib]),
        );
    }
}

/// Adds the pair of bodies `a` and `b` (index, centre, radius) if their spheres overlap.
#[inline]
fn push_if_overlapping(pairs: &mut Vec<(u32, u32)>, a: (u32, Vec3, f32), b: (u32, Vec3, f32)) {
    let r = a.2 + b.2;
    if a.1.distance_squared(b.1) <= r * r {
        pairs.push((a.0.min(b.0), a.0.max(b.0)));
    }
}

/// Grid cell of a point. Clamped so that a body far outside the room cannot
/// overflow the cast (it then shares an edge cell; pairs are still exact).
#[inline]
fn cell_coords(c: Vec3, inv_cell: f32) -> [i32; 3] {
    let f = (c * inv_cell).floor();
    let clamp = |v: f32| {
        if v.is_nan() {
            0
        } else {
            v.clamp(-1.0e6, 1.0e6) as i32
        }
    };
    [clamp(f.x), clamp(f.y), clamp(f.z)]
}

/// A cell as one number. `cell_coords` clamps coordinates to ±10⁶, so
/// they and their neighbours lie in [−2²⁰, 2²⁰): 21 bits each tell them apart.
#[inline]
fn cell_key([x, y, z]: [i32; 3]) -> u64 {
    const BITS: u64 = (1 << 21) - 1;
    (x as u64 & BITS) | ((y as u64 & BITS) << 21) | ((z as u64 & BITS) << 42)
}

/// Hash of the column of cells at (x, y), all z.
#[inline]
fn column_hash(x: i32, y: i32) -> u64 {
    mix64((x as u32 as u64) | ((y as u32 as u64) << 32))
}

#[path = "broad_phase_buckets.rs"]
mod buckets;
use buckets::Buckets;

#[path = "broad_phase_rebuild.rs"]
mod rebuild;
use rebuild::CellBox;

#[cfg(test)]
#[path = "broad_phase_tests.rs"]
mod tests;
