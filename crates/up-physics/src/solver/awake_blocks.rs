//! The awake bodies ordered by zone (`zones`) and cut into blocks for the
//! body passes of a substep run in stages (`fused`): a stage's blocks are
//! shared among the threads in order (`staged`), as a colour's are, whose
//! constraints are ordered by the same zones, so that the thread that
//! solves a part of the room's constraints also integrates its bodies, and
//! their states stay in its core's cache.

use super::coloring::ZONES;
use crate::threading::spare::{release_spare, BUFFER_FLOOR};

/// Most bodies a block holds: integrating one costs tens of nanoseconds,
/// so a block is a few microseconds of work.
const BLOCK_BODIES: usize = 256;

#[derive(Clone, Debug, Default)]
pub(crate) struct AwakeBlocks {
    /// The awake bodies (dense indices), zone after zone, each zone's in
    /// the awake list's order.
    order: Vec<u32>,
    /// Block k is `order[block_end[k - 1]..block_end[k]]` (from 0 for k = 0).
    block_end: Vec<u32>,
    /// Each zone's next place in `order` while sorting.
    next: Vec<u32>,
}

impl AwakeBlocks {
    /// Orders `awake` by `zones` (each body's; empty: the awake order as it
    /// is) and cuts it into a multiple of `threads` equal blocks of at most
    /// `BLOCK_BODIES`, so that each thread's share is as long as the others'.
    pub fn cut(&mut self, awake: &[u32], zones: &[u8], threads: usize) {
        self.order.clear();
        if zones.is_empty() {
            self.order.extend_from_slice(awake);
        } else {
            // A counting sort: stable, in two passes over the awake bodies.
            self.next.clear();
            self.next.resize(ZONES + 1, 0);
            for &i in awake {
                self.next[zones[i as usize] as usize + 1] += 1;
            }
            for z in 1..=ZONES {
                self.next[z] += self.next[z - 1];
            }
            self.order.resize(awake.len(), 0);
            for &i in awake {
                let next = &mut self.next[zones[i as usize] as usize];
                self.order[*next as usize] = i;
                *next += 1;
            }
        }
        let (n, threads) = (awake.len(), threads.max(1));
        let blocks = threads * n.div_ceil(threads * BLOCK_BODIES);
        self.block_end.clear();
        self.block_end
            .extend((1..=blocks).map(|b| (n * b / blocks) as u32));
    }

    /// Blocks in all (none without awake bodies).
    pub fn blocks(&self) -> usize {
        self.block_end.len()
    }

    /// The bodies of block `k`.
    pub fn block(&self, k: usize) -> &[u32] {
        let start = if k == 0 { 0 } else { self.block_end[k - 1] };
        &self.order[start as usize..self.block_end[k] as usize]
    }

    /// Gives back the capacity this step left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.order, BUFFER_FLOOR);
        release_spare(&mut self.block_end, BUFFER_FLOOR);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every awake body is in exactly one block, zone after zone, each
    /// zone's in the given order; the blocks are as many as a multiple of
    /// the threads and differ in length by at most one.
    #[test]
    fn blocks_hold_every_awake_body_once_by_zone() {
        let zones: Vec<u8> = (0..2000u32)
            .map(|i| ((i * 7919) % ZONES as u32) as u8)
            .collect();
        let awake: Vec<u32> = (0..2000).filter(|i| i % 3 != 0).collect();
        for threads in [1, 2, 3, 4] {
            let mut blocks = AwakeBlocks::default();
            blocks.cut(&awake, &zones, threads);
            assert_eq!(blocks.blocks() % threads, 0);
            let all: Vec<u32> = (0..blocks.blocks())
                .flat_map(|k| blocks.block(k).to_vec())
                .collect();
            let mut expected = awake.clone();
            expected.sort_by_key(|&i| zones[i as usize]);
            assert_eq!(all, expected, "{threads} threads");
            let lengths: Vec<usize> = (0..blocks.blocks())
                .map(|k| blocks.block(k).len())
                .collect();
            let (min, max) = (lengths.iter().min(), lengths.iter().max());
            assert!(max.unwrap() - min.unwrap() <= 1);
            assert!(*max.unwrap() <= BLOCK_BODIES);
        }
        let mut blocks = AwakeBlocks::default();
        blocks.cut(&awake, &[], 2);
        let all: Vec<u32> = (0..blocks.blocks())
            .flat_map(|k| blocks.block(k).to_vec())
            .collect();
        assert_eq!(all, awake);
        blocks.cut(&[], &zones, 2);
        assert_eq!(blocks.blocks(), 0);
    }
}
