//! The broadphase's table built afresh: every ordinary body into its
//! cell's bucket by a counting sort (`BroadPhase::rebuild`).

use glam::Vec3;

use super::{cell_coords, cell_key, BroadPhase, Buckets, GridItem, GridScale, BODY_CHUNK};
use crate::threading::tasks::fill_chunks;

impl BroadPhase {
    /// Every ordinary body into its cell's bucket by a counting sort, in
    /// body order; the large ones listed apart. Each body's cell and
    /// bucket, each task's box of cells and the entries are found in
    /// tasks; the counts, the slots, the large list and the tasks' boxes
    /// joined are serial.
    pub(super) fn rebuild(
        &mut self,
        center: &[Vec3],
        radius: &[f32],
        awake: &[bool],
        cell_radius: f32,
    ) {
        let n = center.len();
        self.large.clear();
        let inv_cell = 0.5 / cell_radius;
        // A NaN radius is ordinary, as the comparisons below take it.
        let large = |i: usize| radius[i] > cell_radius;
        self.cell_of.resize(n, [0; 3]);
        fill_chunks(&mut self.cell_of, BODY_CHUNK, |first, cells| {
            for (k, cell) in cells.iter_mut().enumerate() {
                *cell = cell_coords(center[first + k], inv_cell);
            }
        });
        let cell_of = &self.cell_of;
        let tasks = n.div_ceil(BODY_CHUNK);
        self.task_boxes.resize(tasks, CellBox::EMPTY);
        fill_chunks(&mut self.task_boxes, 1, |first, boxes| {
            for (k, cells) in boxes.iter_mut().enumerate() {
                let task = first + k;
                let bodies = task * BODY_CHUNK..((task + 1) * BODY_CHUNK).min(n);
                *cells = bodies
                    .filter(|&i| !large(i))
                    .fold(CellBox::EMPTY, |b, i| b.with(cell_of[i], radius[i]));
            }
        });
        let cells = self
            .task_boxes
            .iter()
            .fold(CellBox::EMPTY, |a, &b| a.joined(b));
        let buckets = Buckets::for_box(cells.lo, cells.hi, n);
        self.bucket_of.resize(n, 0);
        fill_chunks(&mut self.bucket_of, BODY_CHUNK, |first, out| {
            for (k, bucket) in out.iter_mut().enumerate() {
                let i = first + k;
                *bucket = if large(i) {
                    LARGE
                } else {
                    buckets.of_ordinary(cell_of[i]) as u32
                };
            }
        });

        self.start.clear();
        self.start.resize(buckets.count() + 1, 0);
        for (i, &b) in self.bucket_of.iter().enumerate() {
            if b == LARGE {
                self.large.push(i as u32);
            } else {
                self.start[b as usize + 1] += 1;
            }
        }
        for b in 1..self.start.len() {
            self.start[b] += self.start[b - 1];
        }
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.start);
        // Every entry and slot is written below: kept ones are not cleared first.
        let entries = *self.start.last().unwrap_or(&0) as usize;
        self.body_at.resize(entries, 0);
        self.slot_of.resize(n, LARGE);
        for (i, &b) in self.bucket_of.iter().enumerate() {
            self.slot_of[i] = if b == LARGE {
                LARGE
            } else {
                let slot = self.cursor[b as usize];
                self.cursor[b as usize] += 1;
                self.body_at[slot as usize] = i as u32;
                slot
            };
        }

        self.items.resize(entries, GridItem::default());
        let body_at = &self.body_at;
        fill_chunks(&mut self.items, BODY_CHUNK, |first, items| {
            for (k, item) in items.iter_mut().enumerate() {
                let i = body_at[first + k] as usize;
                *item = GridItem {
                    center: center[i],
                    radius: radius[i],
                    cell: cell_key(cell_of[i]),
                    body: i as u32,
                    awake: awake[i],
                };
            }
        });
        self.scale = GridScale {
            inv_cell,
            item_radius: cells.radius,
        };
        self.buckets = buckets;
        self.built_for = cell_radius;
    }
}

/// A large body's bucket and slot: it has none.
pub(super) const LARGE: u32 = u32::MAX;

/// The box of some ordinary bodies' cells and their largest radius (a
/// task's share of `rebuild`'s bodies, or all of them).
#[derive(Clone, Copy, Debug)]
pub(super) struct CellBox {
    lo: [i32; 3],
    hi: [i32; 3],
    /// Largest radius, NaNs passed over (`f32::max`).
    radius: f32,
}

impl CellBox {
    /// No cell: `lo` above `hi`.
    pub(super) const EMPTY: CellBox = CellBox {
        lo: [i32::MAX; 3],
        hi: [i32::MIN; 3],
        radius: 0.0,
    };

    fn with(self, cell: [i32; 3], radius: f32) -> CellBox {
        CellBox {
            lo: std::array::from_fn(|a| self.lo[a].min(cell[a])),
            hi: std::array::from_fn(|a| self.hi[a].max(cell[a])),
            radius: self.radius.max(radius),
        }
    }

    /// Both boxes in one; the same whichever way round.
    fn joined(self, other: CellBox) -> CellBox {
        CellBox {
            lo: std::array::from_fn(|a| self.lo[a].min(other.lo[a])),
            hi: std::array::from_fn(|a| self.hi[a].max(other.hi[a])),
            radius: self.radius.max(other.radius),
        }
    }
}
