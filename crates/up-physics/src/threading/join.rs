//! The tasks' lists joined into one on rayon's threads: each list's items
//! copied into a stretch of the output of its own, where the lists before it
//! end. The output is the same as joining the lists one after another.
//!
//! A pass whose tasks each push into a list (`tasks::collect_in_order`) ends
//! with one list: the narrowphase's contacts (tens of thousands of 56-byte
//! points in a crowd), the broadphase's pairs. Copied on the step's thread
//! alone, the copy would hold the pool's other threads idle.

use std::mem::MaybeUninit;

use crate::threading::tasks::{for_each_run, Runs};

/// Items below which the lists are joined on the calling thread: fewer cost
/// less to copy than to hand out.
const ITEMS_IN_TASKS: usize = 4_096;

/// Appends the items of `lists` (`items(list)`) to `out`, list after list,
/// each item through `map(k, item)`, `k` being its list's index in `lists`:
/// copied on rayon's threads when there are enough of them.
pub(crate) fn append_lists<L, U, T, I, M>(out: &mut Vec<T>, lists: &[L], items: I, map: M)
where
    L: Sync,
    U: Sync,
    T: Send,
    I: Fn(&L) -> &[U] + Sync,
    M: Fn(usize, &U) -> T + Sync,
{
    let total: usize = lists.iter().map(|list| items(list).len()).sum();
    out.reserve(total);
    if total < ITEMS_IN_TASKS {
        for (k, list) in lists.iter().enumerate() {
            out.extend(items(list).iter().map(|item| map(k, item)));
        }
        return;
    }
    let stretches = Stretches {
        lists,
        slots: &mut out.spare_capacity_mut()[..total],
        items: &items,
    };
    for_each_run(lists.len(), 1, stretches, |first, run| {
        let mut slots = run.slots.iter_mut();
        for (k, list) in run.lists.iter().enumerate() {
            // The list's items first: `zip` then stops without taking a slot.
            for (item, slot) in items(list).iter().zip(slots.by_ref()) {
                slot.write(map(first + k, item));
            }
        }
        // Every slot written: `items` gave each list the length it was cut by.
        assert!(slots.next().is_none(), "a list changed length while joined");
    });
    let joined = out.len() + total;
    // SAFETY: the `total` slots past the length were split into one stretch
    // per list, as long as its items, and every stretch was written above.
    unsafe { out.set_len(joined) };
}

/// Consecutive lists and the output's slots for their items, cut between
/// lists (at the sum of the lengths before the cut).
struct Stretches<'a, L, T, I> {
    lists: &'a [L],
    slots: &'a mut [MaybeUninit<T>],
    items: &'a I,
}

impl<L, U, T, I> Runs for Stretches<'_, L, T, I>
where
    L: Sync,
    U: Sync,
    T: Send,
    I: Fn(&L) -> &[U] + Sync,
{
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (lists_before, lists_after) = self.lists.split_at(mid);
        let cut = lists_before
            .iter()
            .map(|list| (self.items)(list).len())
            .sum();
        let (slots_before, slots_after) = self.slots.split_at_mut(cut);
        let items = self.items;
        (
            Stretches {
                lists: lists_before,
                slots: slots_before,
                items,
            },
            Stretches {
                lists: lists_after,
                slots: slots_after,
                items,
            },
        )
    }
}

#[cfg(all(test, feature = "parallel"))]
mod tests {
    use super::*;

    /// Lists of every length from 0 to 299 (one run copies nothing),
    /// joined after what the output held, on 1 to 4 threads: the output is
    /// the lists one after another, each item mapped with its list's index.
    #[test]
    fn lists_joined_in_tasks_come_out_in_order() {
        let lists: Vec<Vec<u32>> = (0..300u32)
            .map(|k| (0..(k * 7) % 300).map(|i| 1_000 * k + i).collect())
            .collect();
        let mut want = vec![u64::MAX];
        for (k, list) in lists.iter().enumerate() {
            want.extend(list.iter().map(|&i| (k as u64) << 32 | i as u64));
        }
        assert!(want.len() > ITEMS_IN_TASKS, "the lists are joined in tasks");
        for threads in 1..=4 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = vec![u64::MAX];
            pool.install(|| {
                append_lists(
                    &mut out,
                    &lists,
                    |list| &list[..],
                    |k, &i| (k as u64) << 32 | i as u64,
                )
            });
            assert!(
                out == want,
                "{threads} threads: the lists joined out of order"
            );
        }
    }

    /// A few items, under the threshold, are joined the same way.
    #[test]
    fn a_few_items_are_joined_on_the_calling_thread_alike() {
        let lists = vec![vec![1u8, 2], vec![], vec![3]];
        let mut out = vec![0u8];
        append_lists(
            &mut out,
            &lists,
            |list| &list[..],
            |k, &i| (k as u8) * 10 + i,
        );
        assert_eq!(out, [0, 1, 2, 23]);
    }
}
