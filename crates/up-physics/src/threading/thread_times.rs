//! Where each thread's time goes in a step, when asked for (`set_timing`):
//! the time each of the pool's threads spends running the passes' tasks
//! (busy), waiting at a stage's barrier for the other threads' blocks
//! (`staged`), and the rest (looking for work, or the step's thread waiting
//! for a fork to join); and the barriers the step crosses. Off, each hook
//! costs one relaxed load; on, two clock reads a task.
//!
//! Each thread adds to its own slot (by its index in rayon's pool); the
//! step's clock (`counters::StageClock`) reads the slots at every stage's end
//! and keeps each stage's difference. The step's own thread counts as busy
//! outside the passes too (the step's serial parts), inside a pass only
//! while it runs a task. The slots are shared by every world stepping in the
//! process: the figures are only meaningful for one world stepping at a time.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use crate::counters::now_ms;

/// Threads timed: those of a pool's threads with a lower index (the others
/// are left out of the figures).
pub const TIMED_THREADS: usize = 16;

static TIMING: AtomicBool = AtomicBool::new(false);

/// One thread's running totals, ns, alone on its cache line.
#[derive(Debug)]
#[repr(align(128))]
struct Slot {
    /// Running tasks of a pass.
    task: AtomicU64,
    /// Waiting at a stage's barrier.
    barrier: AtomicU64,
    /// Inside a pass it started (the step's thread).
    pass: AtomicU64,
}

#[allow(clippy::declare_interior_mutable_const)] // only to fill the array below
const EMPTY_SLOT: Slot = Slot {
    task: AtomicU64::new(0),
    barrier: AtomicU64::new(0),
    pass: AtomicU64::new(0),
};

static SLOTS: [Slot; TIMED_THREADS] = [EMPTY_SLOT; TIMED_THREADS];

/// Barriers crossed (stages waited for), and passes forked, by every thread.
static BARRIERS: AtomicU64 = AtomicU64::new(0);
static PASSES: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// This thread runs a step (its serial parts count as busy).
    static STEPPING: Cell<bool> = const { Cell::new(false) };
    /// This thread is inside a pass it started.
    static IN_PASS: Cell<bool> = const { Cell::new(false) };
    /// This thread runs a task (nested passes and tasks are part of it).
    static IN_TASK: Cell<bool> = const { Cell::new(false) };
}

/// Turns the per-thread timing on or off for every world in the process.
pub fn set_timing(on: bool) {
    TIMING.store(on, Ordering::Relaxed);
}

/// Whether the per-thread timing is on.
pub fn timing() -> bool {
    TIMING.load(Ordering::Relaxed)
}

fn slot_index() -> usize {
    #[cfg(feature = "parallel")]
    let index = rayon::current_thread_index().unwrap_or(0);
    #[cfg(not(feature = "parallel"))]
    let index = 0;
    index
}

fn slot() -> Option<&'static Slot> {
    SLOTS.get(slot_index())
}

fn add(counter: &AtomicU64, since_ms: f64) {
    let ns = ((now_ms() - since_ms) * 1e6).max(0.0) as u64;
    counter.fetch_add(ns, Ordering::Relaxed);
}

/// Marks this thread as running a step until the guard drops.
pub(crate) struct Stepping(bool);

impl Stepping {
    pub fn enter() -> Stepping {
        Stepping(STEPPING.replace(true))
    }
}

impl Drop for Stepping {
    fn drop(&mut self) {
        STEPPING.set(self.0);
    }
}

/// Runs `pass`, a parallel pass started on this thread, timed as such when
/// it is the step's thread and not already inside a pass or task.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) fn pass<R>(pass: impl FnOnce() -> R) -> R {
    if !timing() || !STEPPING.get() || IN_PASS.get() || IN_TASK.get() {
        return pass();
    }
    PASSES.fetch_add(1, Ordering::Relaxed);
    let start = now_ms();
    IN_PASS.set(true);
    let _restore = Restore(&IN_PASS);
    let result = pass();
    if let Some(slot) = slot() {
        add(&slot.pass, start);
    }
    result
}

/// Runs `task`, one task of a parallel pass, timed as busy unless this
/// thread's time is already counted so (its serial part of the step, or an
/// enclosing task).
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) fn task<R>(task: impl FnOnce() -> R) -> R {
    if !timing() || IN_TASK.get() || (STEPPING.get() && !IN_PASS.get()) {
        return task();
    }
    let start = now_ms();
    IN_TASK.set(true);
    let _restore = Restore(&IN_TASK);
    let result = task();
    if let Some(slot) = slot() {
        add(&slot.task, start);
    }
    result
}

/// The clock's reading before a barrier wait, if timing (`barrier_waited` after it).
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) fn barrier_start() -> Option<f64> {
    timing().then(now_ms)
}

/// Adds a barrier wait that began at `start` (`barrier_start`).
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) fn barrier_waited(start: Option<f64>) {
    if let (Some(start), Some(slot)) = (start, slot()) {
        add(&slot.barrier, start);
    }
}

/// Counts `stages` barriers crossed by a staged run.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) fn crossed(stages: usize) {
    if timing() {
        BARRIERS.fetch_add(stages as u64, Ordering::Relaxed);
    }
}

/// Puts a flag back to false when dropped, however the work ends.
struct Restore(&'static std::thread::LocalKey<Cell<bool>>);

impl Drop for Restore {
    fn drop(&mut self) {
        self.0.set(false);
    }
}

/// The slots' totals at one moment, ns.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Reading {
    task: [u64; TIMED_THREADS],
    barrier: [u64; TIMED_THREADS],
    pass: [u64; TIMED_THREADS],
    barriers: u64,
    passes: u64,
}

impl Reading {
    pub fn now() -> Reading {
        let mut r = Reading::default();
        for (k, slot) in SLOTS.iter().enumerate() {
            r.task[k] = slot.task.load(Ordering::Relaxed);
            r.barrier[k] = slot.barrier.load(Ordering::Relaxed);
            r.pass[k] = slot.pass.load(Ordering::Relaxed);
        }
        r.barriers = BARRIERS.load(Ordering::Relaxed);
        r.passes = PASSES.load(Ordering::Relaxed);
        r
    }
}

/// One thread's time in one stage of a step, ms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ThreadTime {
    /// Running the stage's work: tasks of its passes, and on the step's
    /// thread its serial parts too.
    pub busy_ms: f64,
    /// Waiting at the barriers between a staged pass's stages (colours).
    pub barrier_ms: f64,
    /// The rest of the stage: looking for work (spinning) or, on the
    /// step's thread, waiting for a pass's other tasks to finish.
    pub idle_ms: f64,
}

/// Each timed thread's time in each stage of the last step, and the
/// barriers and passes each stage crossed; empty unless timing was on
/// (`set_timing`) through the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreadCounters {
    /// Threads of the pool the step ran on (up to `TIMED_THREADS` timed).
    threads: usize,
    times: [[ThreadTime; TIMED_THREADS]; crate::counters::Stage::COUNT],
    barriers: [u32; crate::counters::Stage::COUNT],
    passes: [u32; crate::counters::Stage::COUNT],
}

impl Default for ThreadCounters {
    fn default() -> Self {
        ThreadCounters {
            threads: 0,
            times: [[ThreadTime::default(); TIMED_THREADS]; crate::counters::Stage::COUNT],
            barriers: [0; crate::counters::Stage::COUNT],
            passes: [0; crate::counters::Stage::COUNT],
        }
    }
}

impl ThreadCounters {
    /// Threads timed (0 when timing was off).
    pub fn threads(&self) -> usize {
        self.threads.min(TIMED_THREADS)
    }

    /// Each timed thread's time in `stage`, the step's thread first.
    pub fn times(&self, stage: crate::counters::Stage) -> &[ThreadTime] {
        &self.times[stage as usize][..self.threads()]
    }

    /// Barriers (a staged pass's stages, colour after colour) `stage` crossed.
    pub fn barriers(&self, stage: crate::counters::Stage) -> u32 {
        self.barriers[stage as usize]
    }

    /// Parallel passes (fork-joins) `stage` started.
    pub fn passes(&self, stage: crate::counters::Stage) -> u32 {
        self.passes[stage as usize]
    }

    /// Starts a step's figures on `threads` threads, the step's own thread
    /// (whose slot is listed first) being the current one.
    pub(crate) fn begin(threads: usize) -> (ThreadCounters, usize) {
        let counters = ThreadCounters {
            threads,
            ..ThreadCounters::default()
        };
        (counters, slot_index())
    }

    /// Records `stage`, `wall_ms` long, from the readings at its start and
    /// end; `owner` is the step's thread's slot.
    pub(crate) fn record(
        &mut self,
        stage: crate::counters::Stage,
        wall_ms: f64,
        owner: usize,
        before: &Reading,
        after: &Reading,
    ) {
        let ms = |a: u64, b: u64| a.saturating_sub(b) as f64 * 1e-6;
        let threads = self.threads();
        for t in 0..threads {
            // The step's thread first, then the others in the pool's order.
            let k = match t {
                0 => owner,
                t if t <= owner => t - 1,
                t => t,
            };
            if k >= TIMED_THREADS {
                continue;
            }
            let task = ms(after.task[k], before.task[k]);
            let barrier = ms(after.barrier[k], before.barrier[k]);
            let busy = if k == owner {
                let pass = ms(after.pass[k], before.pass[k]);
                (wall_ms - pass).max(0.0) + task
            } else {
                task
            };
            self.times[stage as usize][t] = ThreadTime {
                busy_ms: busy,
                barrier_ms: barrier,
                idle_ms: (wall_ms - busy - barrier).max(0.0),
            };
        }
        self.barriers[stage as usize] = after.barriers.saturating_sub(before.barriers) as u32;
        self.passes[stage as usize] = after.passes.saturating_sub(before.passes) as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counters::Stage;

    /// The step's thread is listed first, busy outside its passes and in
    /// its tasks; another thread only in its tasks; the rest of the stage
    /// is idle.
    #[test]
    fn the_steps_thread_comes_first_and_is_busy_outside_its_passes() {
        let before = Reading {
            barriers: 10,
            ..Reading::default()
        };
        let mut after = before;
        // Slot 1 runs the step: 6 ms in passes, 4 of them in tasks, 1 at barriers.
        after.pass[1] = 6_000_000;
        after.task[1] = 4_000_000;
        after.barrier[1] = 1_000_000;
        // Slot 0 ran 5 ms of tasks and waited 2 at barriers.
        after.task[0] = 5_000_000;
        after.barrier[0] = 2_000_000;
        after.barriers = 40;
        after.passes = 3;
        let (mut counters, _) = ThreadCounters::begin(2);
        counters.record(Stage::Solve, 10.0, 1, &before, &after);
        let times = counters.times(Stage::Solve);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        assert!(close(times[0].busy_ms, 4.0 + 4.0), "{times:?}");
        assert!(close(times[0].barrier_ms, 1.0) && close(times[0].idle_ms, 1.0));
        assert!(close(times[1].busy_ms, 5.0) && close(times[1].barrier_ms, 2.0));
        assert!(close(times[1].idle_ms, 3.0));
        assert_eq!(counters.barriers(Stage::Solve), 30);
        assert_eq!(counters.passes(Stage::Solve), 3);
        assert!(counters.times(Stage::Gas).iter().all(|t| t.busy_ms == 0.0));
    }

    /// Two steps' figures summed are read as their means, each stage's row
    /// (only those that took time) before the total.
    #[test]
    fn summed_steps_are_read_as_means_a_step() {
        use crate::threading::thread_sums::ThreadSums;
        let mut sums = ThreadSums::default();
        for (wall, task) in [(10.0, 4.0), (6.0, 2.0)] {
            let before = Reading::default();
            let mut after = before;
            // Slot 0 runs the step, all of it a pass; slot 1 runs tasks.
            after.pass[0] = (wall * 1e6) as u64;
            after.task[1] = (task * 1e6) as u64;
            after.passes = 1;
            let (mut timed, _) = ThreadCounters::begin(2);
            timed.record(Stage::Solve, wall, 0, &before, &after);
            sums.add(&crate::counters::Counters::made_up(
                Stage::Solve,
                wall,
                timed,
            ));
        }
        let means = sums.means();
        let names: Vec<&str> = means.iter().map(|m| m.stage.as_str()).collect();
        assert_eq!(names, ["solve", "total"]);
        for row in &means {
            assert!((row.wall_ms - 8.0).abs() < 1e-9, "{row:?}");
            assert_eq!(row.busy_ms, [0.0, 3.0]);
            assert_eq!(row.idle_ms, [8.0, 5.0]);
            assert_eq!(row.passes, 1.0);
        }
    }

    /// A staged pass on two threads, timed: its barriers are counted, the
    /// step's thread's time in it is a pass, and its blocks are tasks.
    #[cfg(feature = "parallel")]
    #[test]
    fn a_staged_pass_counts_its_barriers_and_its_tasks() {
        use crate::threading::staged::{run_in_stages, Stages};
        let stage_first: Vec<u32> = (0..32).map(|k| k / 4 * 4).collect();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        set_timing(true);
        pool.install(|| {
            let _stepping = Stepping::enter();
            let owner = slot_index();
            let mut stages = Stages::default();
            stages.lay_out(&stage_first);
            let before = Reading::now();
            pass(|| {
                run_in_stages(&stages, |_| {
                    (0..20_000).for_each(|_| std::hint::spin_loop());
                })
            });
            let after = Reading::now();
            // Other tests may add to the slots meanwhile: only lower bounds hold.
            assert!(after.barriers - before.barriers >= 7);
            assert!(after.passes > before.passes);
            assert!(after.pass[owner] > before.pass[owner]);
            let tasks: u64 = (0..TIMED_THREADS)
                .map(|k| after.task[k] - before.task[k])
                .sum();
            assert!(tasks > 0);
        });
        set_timing(false);
    }
}
