//! Splitting a pass into tasks for rayon's threads (`parallel` feature), or
//! running it whole on the calling thread.

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
