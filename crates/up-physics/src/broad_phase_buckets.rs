//! Which bucket of the broadphase's table holds a cell's bodies: a bucket
//! a cell over the box the bodies fill, or hashed by column (`Buckets`).

use super::column_hash;

/// Most cells a table gives a bucket each, per body: past that, hashed
/// buckets (twice the bodies, rounded up to a power of two) are fewer.
const DENSE_CELLS_PER_BODY: u64 = 4;
/// A table of fewer cells than this is laid out cell by cell whatever the
/// body count (a few balloons in a room).
const DENSE_CELLS_ANYWAY: u64 = 4096;

/// Which bucket of the table holds a cell's bodies: cell by cell over the
/// box of the ordinary bodies' cells, one cell wider all round (so that the
/// 27 cells around any of them are in it), z fastest; or, where that box
/// holds too many cells, hashed by column. Either way the cells of a column
/// along z have consecutive buckets, and a cell is found as its column's
/// number plus its z.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Buckets {
    /// Hashed: the bucket count less one (a power of two less one); dense:
    /// every bit set, the column number plus z being the bucket itself.
    pub(super) mask: usize,
    /// Dense: the box's lowest cell and its cells along each axis.
    pub(super) dense: Option<([i32; 3], [i32; 3])>,
}

impl Buckets {
    /// The buckets for `n` bodies whose ordinary ones' cells fill the box
    /// from `lo` to `hi` (`lo` above `hi` where there are none).
    pub(super) fn for_box(lo: [i32; 3], hi: [i32; 3], n: usize) -> Buckets {
        let hashed = Buckets {
            mask: (2 * n).next_power_of_two() - 1,
            dense: None,
        };
        if lo[0] > hi[0] {
            return hashed;
        }
        // One cell more below and above (the clamped coordinates are within ±10⁶).
        let origin = lo.map(|c| c - 1);
        let dims: [i32; 3] = std::array::from_fn(|a| hi[a] - lo[a] + 3);
        let cells: u64 = dims.iter().map(|&d| d as u64).product();
        if cells > (DENSE_CELLS_PER_BODY * n as u64).max(DENSE_CELLS_ANYWAY) {
            return hashed;
        }
        Buckets {
            mask: usize::MAX,
            dense: Some((origin, dims)),
        }
    }

    /// Buckets in the table.
    pub(super) fn count(&self) -> usize {
        match self.dense {
            Some((_, d)) => d.iter().map(|&d| d as usize).product(),
            None => self.mask + 1,
        }
    }

    /// The number of the column of cells at (x, y), all z: a cell's bucket
    /// is `in_column` of it and the cell's z. Dense, (x, y) must be within
    /// the box.
    #[inline]
    pub(super) fn column(&self, x: i32, y: i32) -> u64 {
        match self.dense {
            Some((o, d)) => {
                let column = ((x - o[0]) as i64 * d[1] as i64 + (y - o[1]) as i64) * d[2] as i64;
                (column - o[2] as i64) as u64
            }
            None => column_hash(x, y),
        }
    }

    /// Bucket of cell z of a column: consecutive along z, so that the three
    /// cells a lookup needs in a column sit side by side in the table.
    #[inline]
    pub(super) fn in_column(&self, column: u64, z: i32) -> usize {
        column.wrapping_add(z as i64 as u64) as usize & self.mask
    }

    /// The bucket of an ordinary body's cell (within the box, dense).
    #[inline]
    pub(super) fn of_ordinary(&self, [x, y, z]: [i32; 3]) -> usize {
        self.in_column(self.column(x, y), z)
    }

    /// The bucket of any cell; None for a cell outside the dense box, which
    /// holds no body.
    #[inline]
    pub(super) fn of_cell(&self, cell: [i32; 3]) -> Option<usize> {
        if let Some((o, d)) = self.dense {
            if (0..3).any(|a| cell[a] < o[a] || cell[a] >= o[a] + d[a]) {
                return None;
            }
        }
        Some(self.of_ordinary(cell))
    }
}
