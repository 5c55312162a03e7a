//! Splitting a pass into tasks for rayon's threads (`parallel` feature), or
//! running it whole on the calling thread.

#[cfg(feature = "parallel")]
use std::cell::Cell;
use std::ops::Range;

use crate::threading::join::append_lists;

#[cfg(feature = "parallel")]
use rayon::prelude::*;

#[cfg(feature = "parallel")]
use crate::threading::thread_times;

#[cfg(feature = "parallel")]
thread_local! {
    /// Whether this thread runs work that keeps off rayon's pool (`alone`).
    static ALONE: Cell<bool> = const { Cell::new(false) };
}

/// Threads the passes run here may share: one inside `alone`, else
/// rayon's pool's (the current one, or the global one outside any).
#[cfg(feature = "parallel")]
pub(crate) fn threads_here() -> usize {
    if ALONE.get() {
        1
    } else {
        rayon::current_num_threads()
    }
}

/// Runs `work` on this thread with every pass in it run whole, as on a pool
/// of one thread: for work too small to pay a hand-over between threads (a
/// futex round trip, tens of microseconds on a virtual machine, per pass
/// handed out and per step moved onto the pool). Results are the same as on
/// any number of threads.
#[cfg(feature = "parallel")]
pub(crate) fn alone<R>(work: impl FnOnce() -> R) -> R {
    /// Puts back what `ALONE` was, however `work` ends.
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            ALONE.set(self.0);
        }
    }
    let _restore = Restore(ALONE.replace(true));
    work()
}

/// Whether `len` items are worth splitting into tasks of `chunk`: more than
/// one task, and more than one thread to take them (on one thread rayon's
/// splitting is pure overhead).
#[cfg(feature = "parallel")]
pub(crate) fn worth_splitting(len: usize, chunk: usize) -> bool {
    len > chunk && threads_here() > 1
}

/// Calls `fill(first, items)` on consecutive runs of `chunk` items, `first`
/// being the index of the run's first item: on rayon's threads when worth it,
/// else once with all of them.
pub(crate) fn fill_chunks<T, F>(items: &mut [T], chunk: usize, fill: F)
where
    T: Send,
    F: Fn(usize, &mut [T]) + Sync,
{
    for_each_run(items.len(), chunk, items, fill);
}

/// Per-item buffers that a pass over items `0..len` hands out in runs: a
/// slice (an element an item), `Ragged` (items of any length, back to back),
/// or a tuple of these, cut at the same item.
pub(crate) trait Runs: Sized + Send {
    /// The items before `mid` and those from `mid` on.
    // Without `parallel` nothing is split: a pass gets all the items at once.
    #[cfg_attr(not(feature = "parallel"), allow(dead_code))]
    fn split_at(self, mid: usize) -> (Self, Self);
}

impl<T: Send> Runs for &mut [T] {
    fn split_at(self, mid: usize) -> (Self, Self) {
        self.split_at_mut(mid)
    }
}

impl<T: Sync> Runs for &[T] {
    fn split_at(self, mid: usize) -> (Self, Self) {
        <[T]>::split_at(self, mid)
    }
}

macro_rules! runs_for_tuple {
    ($($part:ident),+) => {
        impl<$($part: Runs),+> Runs for ($($part,)+) {
            #[allow(non_snake_case)]
            fn split_at(self, mid: usize) -> (Self, Self) {
                let ($($part,)+) = self;
                $(let $part = $part.split_at(mid);)+
                (($($part.0,)+), ($($part.1,)+))
            }
        }
    };
}
runs_for_tuple!(A, B);
runs_for_tuple!(A, B, C);
runs_for_tuple!(A, B, C, D);
runs_for_tuple!(A, B, C, D, E);
runs_for_tuple!(A, B, C, D, E, F);

/// Items of varying lengths stored back to back (a body's sphere-tree nodes,
/// say): item `k` starts at `start[k]` (counted from where `start[0]` is)
/// and ends where the next starts, the last at the end of `items`.
pub(crate) struct Ragged<'a, T> {
    items: &'a mut [T],
    start: &'a [u32],
}

impl<'a, T> Ragged<'a, T> {
    /// `items[start[0]..]`, cut by `start`.
    pub fn new(items: &'a mut [T], start: &'a [u32]) -> Self {
        let first = start.first().map_or(items.len(), |&s| s as usize);
        Ragged {
            items: &mut items[first..],
            start,
        }
    }

    /// Item `k` of this run.
    pub fn item(&mut self, k: usize) -> &mut [T] {
        let offset = |s: u32| (s - self.start[0]) as usize;
        let end = self
            .start
            .get(k + 1)
            .map_or(self.items.len(), |&s| offset(s));
        &mut self.items[offset(self.start[k])..end]
    }
}

impl<T: Send> Runs for Ragged<'_, T> {
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (start_before, start_after) = self.start.split_at(mid);
        let cut = start_after
            .first()
            .map_or(self.items.len(), |&s| (s - self.start[0]) as usize);
        let (before, after) = self.items.split_at_mut(cut);
        (
            Ragged {
                items: before,
                start: start_before,
            },
            Ragged {
                items: after,
                start: start_after,
            },
        )
    }
}

/// Calls `run(first, parts)` on runs of consecutive items of `parts`
/// (`first` being the index of the run's first item, of `len`): split in
/// halves on rayon's threads down to runs of at most `chunk` when worth it,
/// else once with all of them. Each item's work must depend on no other
/// item's, so that any split gives the same results.
pub(crate) fn for_each_run<P, F>(len: usize, chunk: usize, parts: P, run: F)
where
    P: Runs,
    F: Fn(usize, P) + Sync,
{
    debug_assert!(chunk > 0, "runs of no items");
    #[cfg(feature = "parallel")]
    if worth_splitting(len, chunk) {
        return thread_times::pass(|| split_runs(0, len, chunk, parts, &run));
    }
    let _ = (len, chunk);
    run(0, parts);
}

/// `for_each_run`'s splitting: halves (at a multiple of `chunk`) forked
/// until a run is at most `chunk` long.
#[cfg(feature = "parallel")]
fn split_runs<P, F>(first: usize, len: usize, chunk: usize, parts: P, run: &F)
where
    P: Runs,
    F: Fn(usize, P) + Sync,
{
    if len <= chunk {
        return thread_times::task(|| run(first, parts));
    }
    let mid = len.div_ceil(chunk) / 2 * chunk;
    let (before, after) = parts.split_at(mid);
    rayon::join(
        || split_runs(first, mid, chunk, before, run),
        || split_runs(first + mid, len - mid, chunk, after, run),
    );
}

/// A list a task pushes into, joined after the lists of the tasks before it.
// Without `parallel` there are no tasks: only the list itself is used.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) trait TaskList: Default + Send {
    /// Empties the list, keeping its buffers.
    fn reset(&mut self);
    /// Appends `lists` one after another, copied in tasks when long
    /// (`join::append_lists`).
    fn join_all(&mut self, lists: &[Self]);
}

impl<T: Copy + Send + Sync> TaskList for Vec<T> {
    fn reset(&mut self) {
        self.clear();
    }

    fn join_all(&mut self, lists: &[Self]) {
        append_lists(self, lists, |list| &list[..], |_, &item| item);
    }
}

/// Appends to `out` what `collect(range, out)` pushes for `0..len`: split
/// into runs of `chunk` on rayon's threads when worth it, each pushing into a
/// list of its own (from `lists`, kept for their buffers), joined in order,
/// so `out` ends the same as with one call over `0..len`.
// Without `parallel` (the wasm build) `lists` is only reset, never grown.
#[cfg_attr(not(feature = "parallel"), allow(clippy::ptr_arg))]
pub(crate) fn collect_in_order<L, F>(
    len: usize,
    chunk: usize,
    lists: &mut Vec<L>,
    out: &mut L,
    collect: F,
) where
    L: TaskList,
    F: Fn(Range<usize>, &mut L) + Sync,
{
    #[cfg(feature = "parallel")]
    if worth_splitting(len, chunk) {
        let tasks = len.div_ceil(chunk);
        if lists.len() < tasks {
            lists.resize_with(tasks, L::default);
        }
        thread_times::pass(|| {
            lists[..tasks]
                .par_iter_mut()
                .enumerate()
                .for_each(|(k, list)| {
                    thread_times::task(|| {
                        list.reset();
                        collect(k * chunk..((k + 1) * chunk).min(len), list);
                    })
                })
        });
        out.join_all(&lists[..tasks]);
        // Lists this step left idle hold nothing, so `spare` can free them.
        lists[tasks..].iter_mut().for_each(L::reset);
        return;
    }
    lists.iter_mut().for_each(L::reset);
    let _ = chunk;
    collect(0..len, out);
}

/// A run's own list, among the tasks' lists: split with the run's items
/// (at a multiple of the chunk, as `split_runs` splits), so each run gets
/// the list of its task.
#[cfg(feature = "parallel")]
struct TaskLists<'a, L> {
    lists: &'a mut [L],
    chunk: usize,
}

#[cfg(feature = "parallel")]
impl<L: Send> Runs for TaskLists<'_, L> {
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (before, after) = self.lists.split_at_mut(mid / self.chunk);
        let chunk = self.chunk;
        (
            TaskLists {
                lists: before,
                chunk,
            },
            TaskLists {
                lists: after,
                chunk,
            },
        )
    }
}

/// `for_each_run` that also collects: `run(first, parts, list)` changes
/// its run of `parts` in place and pushes into a list of its own (from
/// `lists`, kept for their buffers), the lists joined into `out` in order,
/// so `out` ends the same as with one run over everything.
// Without `parallel` (the wasm build) `lists` is only reset, never grown.
#[cfg_attr(not(feature = "parallel"), allow(clippy::ptr_arg))]
pub(crate) fn for_each_run_collect<P, L, F>(
    len: usize,
    chunk: usize,
    parts: P,
    lists: &mut Vec<L>,
    out: &mut L,
    run: F,
) where
    P: Runs,
    L: TaskList,
    F: Fn(usize, P, &mut L) + Sync,
{
    debug_assert!(chunk > 0, "runs of no items");
    #[cfg(feature = "parallel")]
    if worth_splitting(len, chunk) {
        let tasks = len.div_ceil(chunk);
        if lists.len() < tasks {
            lists.resize_with(tasks, L::default);
        }
        let own = TaskLists {
            lists: &mut lists[..tasks],
            chunk,
        };
        thread_times::pass(|| {
            split_runs(0, len, chunk, (parts, own), &|first, (parts, own)| {
                let list = &mut own.lists[0];
                list.reset();
                run(first, parts, list);
            })
        });
        out.join_all(&lists[..tasks]);
        lists[tasks..].iter_mut().for_each(L::reset);
        return;
    }
    lists.iter_mut().for_each(L::reset);
    let _ = (len, chunk);
    run(0, parts, out);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Run lengths the splitting tests cut 1000 items into: one item, odd,
    /// a power of two, one short, all and more than all.
    #[cfg(feature = "parallel")]
    const CHUNKS: [usize; 6] = [1, 7, 64, 999, 1000, 4096];

    /// Pools of 1 to 4 threads, with their sizes.
    #[cfg(feature = "parallel")]
    fn pools() -> impl Iterator<Item = (usize, rayon::ThreadPool)> {
        (1..=4).map(|threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            (threads, pool)
        })
    }

    /// Items of lengths 0 to 4 (item k holds k % 5 slots), cut into runs of
    /// every size on 1 to 4 threads: each item is handed out once, whole,
    /// with its own index, alongside its element of a plain slice.
    #[cfg(feature = "parallel")]
    #[test]
    fn runs_hand_out_every_item_once_with_its_index() {
        let len = 1000;
        let start: Vec<u32> = (0..len)
            .scan(0, |next, k| {
                let s = *next;
                *next += k % 5;
                Some(s)
            })
            .collect();
        let slots = (0..len).map(|k| k % 5).sum::<u32>() as usize;
        for (threads, pool) in pools() {
            for chunk in CHUNKS {
                let mut owner = vec![u32::MAX; slots];
                let mut index = vec![u32::MAX; len as usize];
                pool.install(|| {
                    let parts = (Ragged::new(&mut owner, &start), &mut index[..]);
                    for_each_run(len as usize, chunk, parts, |first, (mut items, index)| {
                        assert!(index.len() <= chunk || threads == 1);
                        for (k, slot) in index.iter_mut().enumerate() {
                            *slot = (first + k) as u32;
                            let item = items.item(k);
                            assert_eq!(item.len() as u32, (first + k) as u32 % 5);
                            item.fill((first + k) as u32);
                        }
                    });
                });
                assert!(index.iter().enumerate().all(|(k, &i)| i == k as u32));
                let expected = (0..len).flat_map(|k| std::iter::repeat_n(k, (k % 5) as usize));
                assert!(
                    owner.iter().copied().eq(expected),
                    "{threads} threads, chunk {chunk}"
                );
            }
        }
    }

    /// Inside `alone`, on a pool of four threads, a pass that would split
    /// runs whole on the calling thread, and so do the lists' collection;
    /// after it the pool is used again.
    #[cfg(feature = "parallel")]
    #[test]
    fn alone_runs_every_pass_whole_on_the_calling_thread() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        pool.install(|| {
            let me = rayon::current_thread_index();
            let runs = std::sync::Mutex::new(Vec::new());
            let mut items = vec![0u32; 1000];
            alone(|| {
                assert_eq!(threads_here(), 1);
                assert!(!worth_splitting(1000, 10));
                fill_chunks(&mut items, 10, |first, run| {
                    runs.lock()
                        .unwrap()
                        .push((first, run.len(), rayon::current_thread_index()));
                });
                let (mut lists, mut out) = (Vec::<Vec<u32>>::new(), Vec::new());
                collect_in_order(1000, 10, &mut lists, &mut out, |range, out| {
                    out.extend(range.map(|k| k as u32));
                });
                assert!(out.iter().enumerate().all(|(k, &v)| v == k as u32));
            });
            assert_eq!(runs.into_inner().unwrap(), vec![(0, 1000, me)]);
            assert_eq!(threads_here(), 4);
            assert!(worth_splitting(1000, 10));
        });
    }

    /// Runs of every size on 1 to 4 threads each double their items in
    /// place and push them, doubled, into their own lists: the items and
    /// the joined list come out as from one run over everything.
    #[cfg(feature = "parallel")]
    #[test]
    fn runs_that_collect_join_their_lists_in_order() {
        for (threads, pool) in pools() {
            for chunk in CHUNKS {
                let mut items: Vec<u32> = (0..1000).collect();
                let (mut lists, mut out) = (Vec::<Vec<u32>>::new(), vec![7]);
                pool.install(|| {
                    let parts = &mut items[..];
                    for_each_run_collect(
                        1000,
                        chunk,
                        parts,
                        &mut lists,
                        &mut out,
                        |first, run, list| {
                            for (k, item) in run.iter_mut().enumerate() {
                                assert_eq!(*item, (first + k) as u32);
                                *item *= 2;
                                list.extend([*item, *item]);
                            }
                        },
                    );
                });
                assert!(items.iter().enumerate().all(|(k, &v)| v == 2 * k as u32));
                let want: Vec<u32> = [7]
                    .into_iter()
                    .chain((0..1000).flat_map(|k| [2 * k, 2 * k]))
                    .collect();
                assert_eq!(out, want, "{threads} threads, chunk {chunk}");
            }
        }
    }

    /// A ragged buffer whose first item starts past 0 (a run's view) keeps
    /// its items where `start` says.
    #[test]
    fn a_ragged_buffer_counts_from_its_first_start() {
        let mut items = [9, 9, 1, 2, 2, 3, 3, 3];
        let start = [2u32, 3, 5];
        let mut ragged = Ragged::new(&mut items, &start);
        assert_eq!(ragged.item(0), &[1]);
        assert_eq!(ragged.item(2), &[3, 3, 3]);
        let (mut before, mut after) = ragged.split_at(1);
        assert_eq!(before.item(0), &[1]);
        assert_eq!(after.item(0), &[2, 2]);
        assert_eq!(after.item(1), &[3, 3, 3]);
    }
}
