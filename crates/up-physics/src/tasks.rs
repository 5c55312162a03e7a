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

/// Appends to `out` what `collect(range, out)` pushes for `0..len`: split
/// into runs of `chunk` on rayon's threads when worth it, each pushing into a
/// list of its own (from `lists`, kept for their buffers), joined in order,
/// so `out` ends the same as with one call over `0..len`.
pub(crate) fn collect_in_order<T, F>(
    len: usize,
    chunk: usize,
    lists: &mut Vec<Vec<T>>,
    out: &mut Vec<T>,
    collect: F,
) where
    T: Copy + Send,
    F: Fn(Range<usize>, &mut Vec<T>) + Sync,
{
    #[cfg(feature = "parallel")]
    if worth_splitting(len, chunk) {
        let tasks = len.div_ceil(chunk);
        if lists.len() < tasks {
            lists.resize_with(tasks, Vec::new);
        }
        lists[..tasks]
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, list)| {
                list.clear();
                collect(k * chunk..((k + 1) * chunk).min(len), list);
            });
        out.reserve(lists[..tasks].iter().map(Vec::len).sum());
        for list in &lists[..tasks] {
            out.extend_from_slice(list);
        }
        return;
    }
    let _ = (chunk, lists);
    collect(0..len, out);
}
