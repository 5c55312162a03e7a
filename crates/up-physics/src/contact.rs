//! Contact points as the narrowphase hands them to the solver, and the
//! impulses kept from one step to the next for warm starting.

use std::ops::Range;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::threading::spare::{release_spare, BUFFER_FLOOR};

/// Stands for the static room in a contact's `body_b`.
pub(crate) const STATIC_BODY: u32 = u32::MAX;

/// One contact point between body A and body B (or the room). 56 bytes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ContactPoint {
    /// Dense body indices; `body_b == STATIC_BODY` for the room.
    pub body_a: u32,
    pub body_b: u32,
    /// Unit, from A to B.
    pub normal: Vec3,
    /// Surface points, world frame, at the start of the step.
    pub point_a: Vec3,
    pub point_b: Vec3,
    /// Negative when overlapping, m.
    pub separation: f32,
    pub feature: ContactFeature,
}

/// Which parts of the two bodies touched: the same feature in two steps is
/// the same contact, which warm-starts from the last one's impulses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct ContactFeature {
    /// Leaf sphere of body A (index among its tree's nodes).
    pub leaf_a: u32,
    /// Leaf sphere of body B, or the room's triangle.
    pub part_b: u32,
}

/// The impulses a contact point ended the last step with.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
pub(crate) struct StoredImpulse {
    pub feature: ContactFeature,
    /// N·s per substep, along the normal.
    pub normal: f32,
    /// N·s per substep, tangential, as a world vector (so that a new tangent basis can take it).
    pub tangent: Vec3,
}

/// Warm-start memory: per body pair, the impulses of its contact points last step.
///
/// Pairs are keyed by the handle indices of their bodies (stable across
/// removals, unlike dense indices). An open-addressing table maps a key to a
/// run of `impulses`; it is rebuilt each step into reused buffers, so a warm
/// step does not allocate.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct WarmStartCache {
    /// (pair key, first impulse, count), in the order the narrowphase found them.
    pub runs: Vec<(u64, u32, u32)>,
    pub impulses: Vec<StoredImpulse>,
    #[serde(skip)]
    table: Vec<u32>,
}

const EMPTY_SLOT: u32 = u32::MAX;

/// The open-addressing table of `runs`' keys: each run's index at its key's
/// hash, or the next free slot after it; twice as many slots as runs.
fn index_runs(table: &mut Vec<u32>, runs: &[(u64, u32, u32)]) {
    let capacity = (runs.len() * 2).next_power_of_two().max(16);
    table.clear();
    table.resize(capacity, EMPTY_SLOT);
    let mask = capacity - 1;
    for (run, &(key, _, _)) in runs.iter().enumerate() {
        let mut slot = crate::hash::mix64(key) as usize & mask;
        while table[slot] != EMPTY_SLOT {
            slot = (slot + 1) & mask;
        }
        table[slot] = run as u32;
    }
}

impl WarmStartCache {
    /// Gives back the capacity its pairs left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.runs, BUFFER_FLOOR);
        release_spare(&mut self.impulses, BUFFER_FLOOR);
        release_spare(&mut self.table, BUFFER_FLOOR);
    }

    pub fn clear(&mut self) {
        self.runs.clear();
        self.impulses.clear();
    }

    /// Appends a pair's impulses (call `index` once done).
    pub fn push_run(&mut self, key: u64, impulses: &[StoredImpulse]) {
        let start = self.impulses.len() as u32;
        self.runs.push((key, start, impulses.len() as u32));
        self.impulses.extend_from_slice(impulses);
    }

    /// Drops the pairs of the body with handle index `handle` (removed: its
    /// index may be handed to a new body).
    pub fn forget(&mut self, handle: u32) {
        let involves = |key: u64| (key >> 32) as u32 == handle || key as u32 == handle;
        if !self.runs.iter().any(|&(key, _, _)| involves(key)) {
            return;
        }
        // Compacted in place: the runs lie in order, so each moves down.
        let (mut kept, mut end) = (0, 0u32);
        for r in 0..self.runs.len() {
            let (key, start, count) = self.runs[r];
            if involves(key) {
                continue;
            }
            let from = start as usize..(start + count) as usize;
            self.impulses.copy_within(from, end as usize);
            self.runs[kept] = (key, end, count);
            (kept, end) = (kept + 1, end + count);
        }
        self.runs.truncate(kept);
        self.impulses.truncate(end as usize);
        self.index();
    }

    /// Rebuilds the lookup table after `runs` changed.
    pub fn index(&mut self) {
        index_runs(&mut self.table, &self.runs);
    }

    /// Calls `fill` on the impulses (as many as `runs` covers) while the
    /// lookup table is rebuilt from `runs`: on two threads when there are
    /// several, since the table needs only the runs (built serially, it
    /// would hold the pool's other threads idle).
    pub fn fill_and_index(&mut self, fill: impl FnOnce(&mut [StoredImpulse]) + Send) {
        let (impulses, table, runs) = (&mut self.impulses[..], &mut self.table, &self.runs);
        #[cfg(feature = "parallel")]
        if crate::threading::tasks::threads_here() > 1 {
            use crate::threading::thread_times;
            let index = || thread_times::task(|| index_runs(table, runs));
            let fill = || thread_times::task(|| fill(impulses));
            thread_times::pass(|| rayon::join(index, fill));
            return;
        }
        fill(impulses);
        index_runs(table, runs);
    }

    /// The stored impulses of a pair, if it had contacts last step.
    pub fn find(&self, key: u64) -> &[StoredImpulse] {
        self.find_run(key).map_or(&[], |run| self.impulses_of(run))
    }

    /// Which run holds the pair `key`, if it had contacts last step.
    fn find_run(&self, key: u64) -> Option<usize> {
        if self.table.is_empty() {
            return None;
        }
        let mask = self.table.len() - 1;
        let mut slot = crate::hash::mix64(key) as usize & mask;
        loop {
            let run = self.table[slot];
            if run == EMPTY_SLOT {
                return None;
            }
            if self.runs[run as usize].0 == key {
                return Some(run as usize);
            }
            slot = (slot + 1) & mask;
        }
    }

    /// As `find_run`, trying run `guess` first: the pairs come in much the
    /// same order step after step, so the run after the last one found is
    /// most often the next one wanted, read in order instead of hashed.
    fn find_run_from(&self, key: u64, guess: usize) -> Option<usize> {
        // Without its table (not `index`ed yet) the cache finds nothing, guessed or not.
        if self.table.is_empty() {
            return None;
        }
        match self.runs.get(guess) {
            Some(&(k, _, _)) if k == key => Some(guess),
            _ => self.find_run(key),
        }
    }

    fn impulses_of(&self, run: usize) -> &[StoredImpulse] {
        let (_, start, count) = self.runs[run];
        &self.impulses[start as usize..(start + count) as usize]
    }
}

/// Where this step's contacts find the impulses they resume from: the last
/// step's, or for a pair of sleepers (or a sleeper and the room) just woken,
/// those kept from when it fell asleep.
pub(crate) struct ResumeFrom<'a> {
    pub fresh: &'a WarmStartCache,
    pub kept: &'a WarmStartCache,
}

impl ResumeFrom<'_> {
    /// The stored impulses of a pair, and the run of `fresh` to try first
    /// for the next pair (see `find_run_from`).
    fn find(&self, key: u64, guess: usize) -> (&[StoredImpulse], usize) {
        match self.fresh.find_run_from(key, guess) {
            Some(run) => match self.fresh.impulses_of(run) {
                [] => (self.kept.find(key), run + 1),
                found => (found, run + 1),
            },
            None => (self.kept.find(key), guess),
        }
    }

    /// Calls `visit(i, previous)` for each contact `i` of `contacts`, in
    /// order, with the stored impulses of its pair (`runs` cover the
    /// contacts in order, as the narrowphase gives them): one lookup a pair.
    pub fn each(
        &self,
        runs: &[(u64, u32, u32)],
        contacts: Range<usize>,
        mut visit: impl FnMut(usize, &[StoredImpulse]),
    ) {
        let mut run =
            runs.partition_point(|&(_, start, count)| (start + count) as usize <= contacts.start);
        let (mut i, mut guess) = (contacts.start, 0);
        while i < contacts.end {
            let (key, start, count) = runs[run];
            let previous;
            (previous, guess) = self.find(key, guess);
            let end = ((start + count) as usize).min(contacts.end);
            for i in i..end {
                visit(i, previous);
            }
            (i, run) = (end, run + 1);
        }
    }
}

/// Key of a body pair from the handle indices of its bodies (`u32::MAX` for the room).
#[inline]
pub(crate) fn pair_key(handle_a: u32, handle_b: u32) -> u64 {
    ((handle_a as u64) << 32) | handle_b as u64
}

/// An impulse along the normal alone, for tests.
#[cfg(test)]
pub(crate) fn impulse(normal: f32) -> StoredImpulse {
    StoredImpulse {
        normal,
        ..StoredImpulse::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_contact_resumes_from_its_pair_this_step_or_when_it_fell_asleep() {
        let mut fresh = WarmStartCache::default();
        fresh.push_run(pair_key(0, 1), &[impulse(1.0), impulse(2.0)]);
        fresh.index();
        let mut kept = WarmStartCache::default();
        kept.push_run(pair_key(0, 1), &[impulse(9.0)]); // older: not used
        kept.push_run(pair_key(2, 3), &[impulse(3.0)]);
        kept.index();
        let resume = ResumeFrom {
            fresh: &fresh,
            kept: &kept,
        };
        // Three pairs over six contacts: (0, 1) ×3, (2, 3) ×1, (4, 5) ×2.
        let runs = [
            (pair_key(0, 1), 0, 3),
            (pair_key(2, 3), 3, 1),
            (pair_key(4, 5), 4, 2),
        ];
        let visited = |range| {
            let mut seen = Vec::new();
            resume.each(&runs, range, |i, previous| {
                seen.push((i, previous.iter().map(|p| p.normal).collect::<Vec<_>>()));
            });
            seen
        };
        let all = visited(0..6);
        assert_eq!(
            all.iter().map(|(i, _)| *i).collect::<Vec<_>>(),
            [0, 1, 2, 3, 4, 5]
        );
        assert_eq!(all[0].1, [1.0, 2.0]);
        assert_eq!(all[2].1, [1.0, 2.0]);
        assert_eq!(all[3].1, [3.0]);
        assert!(all[4].1.is_empty() && all[5].1.is_empty());
        // A task's range may start and end inside a pair's run.
        assert_eq!(visited(2..5), all[2..5]);
    }

    /// The pairs in last step's order, shuffled, thinned and with new ones
    /// among them: each finds its own impulses, whether the run tried first
    /// (`find_run_from`) is the one or not.
    #[test]
    fn each_pair_finds_its_impulses_in_any_order() {
        let mut fresh = WarmStartCache::default();
        for p in 0..40u32 {
            fresh.push_run(pair_key(p, p + 1), &[impulse(p as f32)]);
        }
        fresh.index();
        let kept = WarmStartCache::default();
        let resume = ResumeFrom {
            fresh: &fresh,
            kept: &kept,
        };
        // In order with gaps, a pair new this step, then back to front.
        let order: Vec<u32> = (0..40)
            .filter(|p| p % 7 != 3)
            .chain([100])
            .chain((0..40).rev().step_by(3))
            .collect();
        let runs: Vec<(u64, u32, u32)> = order
            .iter()
            .enumerate()
            .map(|(i, &p)| (pair_key(p, p + 1), i as u32, 1))
            .collect();
        let mut seen = Vec::new();
        resume.each(&runs, 0..runs.len(), |i, previous| {
            seen.push((i, previous.iter().map(|p| p.normal).collect::<Vec<_>>()));
        });
        for (i, &p) in order.iter().enumerate() {
            let want: &[f32] = if p < 40 { &[p as f32] } else { &[] };
            assert_eq!(seen[i], (i, want.to_vec()), "pair {p}");
        }
    }

    /// The impulses filled while the table is rebuilt, on one thread or on
    /// three: every pair finds the impulses filled for it, through a table
    /// laid out as `index` lays it.
    #[cfg(feature = "parallel")]
    #[test]
    fn impulses_filled_while_the_table_is_built_are_found_by_their_pairs() {
        let mut serial = WarmStartCache::default();
        for p in 0..3_000u32 {
            serial.push_run(pair_key(p, 3 * p + 1), &[impulse(p as f32); 2]);
        }
        serial.index();
        for threads in [1, 3] {
            let mut cache = WarmStartCache {
                runs: serial.runs.clone(),
                impulses: vec![StoredImpulse::default(); serial.impulses.len()],
                table: vec![7; 5],
            };
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                cache.fill_and_index(|impulses| {
                    for (k, stored) in impulses.iter_mut().enumerate() {
                        *stored = impulse((k / 2) as f32);
                    }
                })
            });
            assert_eq!(cache.table, serial.table, "{threads} threads");
            for p in 0..3_000u32 {
                let normals: Vec<f32> = cache
                    .find(pair_key(p, 3 * p + 1))
                    .iter()
                    .map(|i| i.normal)
                    .collect();
                assert_eq!(normals, [p as f32; 2], "{threads} threads, pair {p}");
            }
        }
    }

    /// Runs without their table (a cache deserialized, not yet `index`ed)
    /// are not found, guessed or hashed: the pairs start cold, as before guessing.
    #[test]
    fn a_cache_without_its_table_finds_nothing() {
        let mut fresh = WarmStartCache::default();
        fresh.push_run(pair_key(0, 1), &[impulse(1.0)]);
        let kept = WarmStartCache::default();
        let resume = ResumeFrom {
            fresh: &fresh,
            kept: &kept,
        };
        let mut seen = Vec::new();
        resume.each(&[(pair_key(0, 1), 0, 1)], 0..1, |_, previous| {
            seen.push(previous.len())
        });
        assert_eq!(seen, [0]);
    }

    #[test]
    fn forgetting_a_body_keeps_the_other_pairs_whole() {
        let mut cache = WarmStartCache::default();
        cache.push_run(pair_key(0, 1), &[impulse(1.0), impulse(2.0)]);
        cache.push_run(pair_key(1, 2), &[impulse(3.0)]);
        cache.push_run(pair_key(0, 2), &[impulse(4.0), impulse(5.0)]);
        cache.push_run(pair_key(2, u32::MAX), &[impulse(6.0)]);
        cache.index();

        cache.forget(1);

        let normals = |key| cache.find(key).iter().map(|i| i.normal).collect::<Vec<_>>();
        assert!(cache.find(pair_key(0, 1)).is_empty());
        assert!(cache.find(pair_key(1, 2)).is_empty());
        assert_eq!(normals(pair_key(0, 2)), [4.0, 5.0]);
        assert_eq!(normals(pair_key(2, u32::MAX)), [6.0]);
        assert_eq!(cache.impulses.len(), 3);
    }
}
