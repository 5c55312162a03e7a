//! The sleeping groups (islands), their kept impulses, and the union-find
//! that forms them.

use serde::{Deserialize, Serialize};

use crate::body::BodyId;
use crate::contact::WarmStartCache;

/// Union-find over dense body indices; reused buffers.
#[derive(Clone, Debug, Default)]
pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub fn reset(&mut self, n: usize) {
        self.parent.clear();
        self.parent.extend(0..n as u32);
    }

    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let grand = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = grand;
            x = grand;
        }
        x
    }

    /// Joins two sets; the smaller root wins, so the result is order-independent.
    pub fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.parent[hi as usize] = lo;
        }
    }
}

/// The groups of bodies asleep together, and the impulses that held them.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct SleepingIslands {
    /// Island index → its bodies (empty when the slot is free).
    pub members: Vec<Vec<BodyId>>,
    pub free: Vec<u32>,
    /// Warm-start impulses of the contacts between sleepers, and between a
    /// sleeper and the room, as they were when the bodies fell asleep. The
    /// narrowphase skips those pairs, so the step-to-step cache forgets them;
    /// a pile woken without them starts from no contact force at all, rises
    /// by a substep's lift before the solver catches it, and its 1–3 cm/s
    /// jolt wakes the next groups in turn.
    pub impulses: WarmStartCache,
    /// Whether membership changed since `impulses` was last sorted out.
    changed: bool,
    #[serde(skip)]
    spare: WarmStartCache,
}

impl SleepingIslands {
    /// Gives back the capacity its kept impulses left unused (`spare`). The
    /// second buffer holds the set kept before the last change (the two
    /// swap), so it follows the use one change late.
    pub fn release_spare(&mut self) {
        self.impulses.release_spare();
        self.spare.release_spare();
    }

    pub fn add(&mut self, bodies: Vec<BodyId>) -> u32 {
        self.changed = true;
        if let Some(slot) = self.free.pop() {
            self.members[slot as usize] = bodies;
            slot
        } else {
            self.members.push(bodies);
            self.members.len() as u32 - 1
        }
    }

    /// Keeps the members of `island` that `still_asleep`; frees it once empty.
    pub fn retain_members(&mut self, island: u32, still_asleep: impl Fn(BodyId) -> bool) {
        let Some(members) = self.members.get_mut(island as usize) else {
            return;
        };
        self.changed = true;
        members.retain(|&id| still_asleep(id));
        if members.is_empty() {
            self.free.push(island);
        }
    }

    /// Empties an island and returns its bodies.
    pub fn take(&mut self, island: u32) -> Vec<BodyId> {
        self.changed = true;
        let bodies = std::mem::take(&mut self.members[island as usize]);
        self.free.push(island);
        bodies
    }

    /// Once the sleepers changed, keeps the impulses of exactly the pairs
    /// whose bodies both sleep now (`asleep`, by handle index; the room
    /// counts as asleep): this step's (`warm`) for the pairs the narrowphase
    /// saw, the kept ones for the others. Bodies woken this step have
    /// already started from theirs. `fell_asleep` tells the sleepers that
    /// were awake this step: the narrowphase saw no pair of two others, so
    /// their kept impulses stay without a lookup in `warm`.
    pub fn keep_impulses(
        &mut self,
        warm: &WarmStartCache,
        asleep: impl Fn(u32) -> bool,
        fell_asleep: impl Fn(u32) -> bool,
    ) {
        if !self.changed {
            return;
        }
        self.changed = false;
        let sleeping_pair = |key: u64| asleep((key >> 32) as u32) && asleep(key as u32);
        let mut kept = std::mem::take(&mut self.spare);
        kept.clear();
        for &(key, start, count) in &warm.runs {
            if sleeping_pair(key) {
                kept.push_run(
                    key,
                    &warm.impulses[start as usize..(start + count) as usize],
                );
            }
        }
        let old = &self.impulses;
        for &(key, start, count) in &old.runs {
            let seen = fell_asleep((key >> 32) as u32) || fell_asleep(key as u32);
            if sleeping_pair(key) && (!seen || warm.find(key).is_empty()) {
                kept.push_run(key, &old.impulses[start as usize..(start + count) as usize]);
            }
        }
        kept.index();
        self.spare = std::mem::replace(&mut self.impulses, kept);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{impulse, pair_key};

    fn cache(runs: &[((u32, u32), f32)]) -> WarmStartCache {
        let mut cache = WarmStartCache::default();
        for &((a, b), normal) in runs {
            cache.push_run(pair_key(a, b), &[impulse(normal)]);
        }
        cache.index();
        cache
    }

    /// Balloons 1–5 sleep now, 3 and 4 fell asleep this step (so the
    /// narrowphase saw their pairs), 6 is awake. The pairs of two sleepers
    /// are kept: this step's impulses where the narrowphase saw the pair,
    /// the kept ones where it could not.
    #[test]
    fn kept_impulses_are_this_steps_where_seen_and_the_kept_ones_elsewhere() {
        let mut islands = SleepingIslands {
            impulses: cache(&[((1, 2), 12.0), ((3, 4), 0.34), ((2, 6), 26.0)]),
            ..SleepingIslands::default()
        };
        islands.add(Vec::new());
        let warm = cache(&[((3, 4), 34.0), ((4, 5), 45.0), ((5, 6), 56.0)]);
        islands.keep_impulses(&warm, |h| (1..=5).contains(&h), |h| h == 3 || h == 4);
        let kept: Vec<(u64, f32)> = islands
            .impulses
            .runs
            .iter()
            .map(|&(key, start, _)| (key, islands.impulses.impulses[start as usize].normal))
            .collect();
        let want = [
            (pair_key(3, 4), 34.0),
            (pair_key(4, 5), 45.0),
            (pair_key(1, 2), 12.0),
        ];
        assert_eq!(kept, want);
        assert_eq!(islands.impulses.find(pair_key(1, 2))[0].normal, 12.0);
    }
}
