//! Giving back what a busy moment took. The step's buffers that scale with
//! the contacts (the narrowphase's lists, the constraints, the warm-start
//! caches, the pairs) keep their capacity from step to step so that a warm
//! step does not allocate; but a stir of a pile, or a crowd's arrival, needs
//! several times what the pile needs asleep. Without a way back, a world holds
//! the capacity of its busiest step forever, and a long run's memory creeps up
//! with every new busiest step, even with the pile asleep (the stirred hour's
//! figures: docs/perf-log.md).

/// Use below which one of the step's buffers is treated as using this many
/// bytes, so that it keeps up to twice this whatever its use: below that,
/// giving memory back is not worth the reallocation.
pub(crate) const BUFFER_FLOOR: usize = 64 << 10;

/// The same for one task's list (`tasks`): small, since a busy step splits
/// its work into hundreds of tasks and a floor for each adds up (measured
/// with 64 KiB each: docs/perf-log.md).
pub(crate) const TASK_LIST_FLOOR: usize = 4 << 10;

/// Shrinks `v` to twice its length when it holds more than four times that
/// (and more than twice `floor_bytes`). Growing at need (by doubling) and
/// shrinking only at a fourfold surplus leaves a gap, so a buffer whose use
/// swings by less than four times from step to step is not reallocated back
/// and forth. Call it when the length is this step's use (at the step's end).
pub(crate) fn release_spare<T>(v: &mut Vec<T>, floor_bytes: usize) {
    let floor = floor_bytes / size_of::<T>().max(1);
    let keep = (2 * v.len()).max(floor);
    if v.capacity() > 2 * keep {
        v.shrink_to(keep);
    }
}

/// `release_spare` for each task's list of a stage.
pub(crate) fn release_spare_each<T>(lists: &mut [Vec<T>]) {
    for list in lists {
        release_spare(list, TASK_LIST_FLOOR);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_a_floor_and_twice_the_use_and_shrinks_only_at_four_times() {
        let floor = BUFFER_FLOOR / size_of::<u64>();
        let mut small: Vec<u64> = Vec::with_capacity(floor);
        release_spare(&mut small, BUFFER_FLOOR);
        assert_eq!(small.capacity(), floor, "empty but within the floor: kept");

        let mut v: Vec<u64> = Vec::with_capacity(16 * floor);
        v.resize(4 * floor, 0);
        release_spare(&mut v, BUFFER_FLOOR);
        assert_eq!(v.capacity(), 16 * floor, "four times the use: kept");

        v.truncate(2 * floor);
        release_spare(&mut v, BUFFER_FLOOR);
        assert!(
            v.capacity() >= 4 * floor && v.capacity() < 16 * floor,
            "{}",
            v.capacity()
        );
        assert_eq!(v.len(), 2 * floor, "the contents stay");

        v.clear();
        release_spare(&mut v, BUFFER_FLOOR);
        assert!(
            v.capacity() >= floor && v.capacity() < 2 * floor,
            "{}",
            v.capacity()
        );
    }

    #[test]
    fn an_idle_task_list_keeps_only_a_small_floor() {
        let floor = TASK_LIST_FLOOR / size_of::<u32>();
        let mut lists = vec![vec![0u32; 100 * floor], Vec::with_capacity(100 * floor)];
        release_spare_each(&mut lists);
        assert_eq!(lists[0].capacity(), 100 * floor, "in use: kept");
        assert!(
            lists[1].capacity() < 2 * floor,
            "idle: {}",
            lists[1].capacity()
        );
    }
}
