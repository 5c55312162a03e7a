//! Splitting a pass into tasks for rayon's threads (`parallel` feature), or
//! running it whole on the calling thread.

use std::ops::Range;

#[cfg(feature = "parallel")]
use rayon::prelude::*;

/// Whether `len` items are worth splitting into tasks of `chunk`: more than
/// one task, and more than one thread to take them (on one thread rayon's
/// splitting is pure overhead).
#[cfg(feature = "parallel")]
pub(crate) fn worth_splitting(len: usize, chunk: usize) -> bool {
    len > chunk && rayon::current_num_threads() > 1
}

/// Calls `fill(first, items)` on consecutive runs of `chunk` items, `first`
/// being the index of the run's first item: on rayon's threads when worth it,
/// else once with all of them.
pub(crate) fn fill_chunks<T, F>(items: &mut [T], chunk: usize, fill: F)
where
    T: Send,
    F: Fn(usize, &mut [T]) + Sync,
{
    #[cfg(feature = "parallel")]
    if worth_splitting(items.len(), chunk) {
        items
            .par_chunks_mut(chunk)
            .enumerate()
            .for_each(|(k, run)| fill(k * chunk, run));
        return;
    }
    let _ = chunk;
    fill(0, items);
}

/// A list a task pushes into, joined after the lists of the tasks before it.
// Without `parallel` there are no tasks: only the list itself is used.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) trait TaskList: Default + Send {
    /// Empties the list, keeping its buffers.
    fn reset(&mut self);
    /// Appends `other` after what this list holds.
    fn join(&mut self, other: &Self);
}

impl<T: Copy + Send> TaskList for Vec<T> {
    fn reset(&mut self) {
        self.clear();
    }

    fn join(&mut self, other: &Self) {
        self.extend_from_slice(other);
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
        lists[..tasks]
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, list)| {
                list.reset();
                collect(k * chunk..((k + 1) * chunk).min(len), list);
            });
        for list in &lists[..tasks] {
            out.join(list);
        }
        // Lists this step left idle hold nothing, so `spare` can free them.
        lists[tasks..].iter_mut().for_each(L::reset);
        return;
    }
    lists.iter_mut().for_each(L::reset);
    let _ = chunk;
    collect(0..len, out);
}
