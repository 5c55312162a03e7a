//! Each thread's part of each stage as the page reads it
//! (`up_physics::Counters::threads`, timed while `set_thread_timing` is on):
//! busy, waiting at a staged pass's barriers, and idle (looking for work, or
//! the step's thread waiting for a pass to join), summed over the steps
//! between two `stats` calls (`up_physics::ThreadSums`, which allocates
//! nothing a step) and averaged when read, as the stage times are.

use serde::Serialize;
use tsify_next::Tsify;
use up_physics::{Counters, StageThreadMeans};
use wasm_bindgen::prelude::*;

/// Turns the timing of each thread's part of every stage on or off for the
/// steps from now on (two clock reads per task of a parallel pass while on);
/// `stats` then carries `threads`.
#[wasm_bindgen]
pub fn set_thread_timing(on: bool) {
    up_physics::set_thread_timing(on);
}

/// One stage's figures, ms (or counts) a step, the step's thread first.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
pub struct StageThreadTimes {
    pub stage: String,
    /// The stage's own clock.
    pub wall_ms: f64,
    pub busy_ms: Vec<f64>,
    pub barrier_ms: Vec<f64>,
    pub idle_ms: Vec<f64>,
    /// Barriers crossed (a staged pass's stages after its first).
    pub barriers: f64,
    /// Parallel passes (fork-joins) started.
    pub passes: f64,
}

impl From<StageThreadMeans> for StageThreadTimes {
    fn from(m: StageThreadMeans) -> Self {
        StageThreadTimes {
            stage: m.stage,
            wall_ms: m.wall_ms,
            busy_ms: m.busy_ms,
            barrier_ms: m.barrier_ms,
            idle_ms: m.idle_ms,
            barriers: m.barriers,
            passes: m.passes,
        }
    }
}

/// Each stage's per-thread sums since the last `take`.
#[derive(Default)]
pub struct ThreadSums(up_physics::ThreadSums);

impl ThreadSums {
    /// Adds a step's figures; a step without them (timing off) adds nothing.
    pub fn add(&mut self, counters: &Counters) {
        self.0.add(counters);
    }

    /// Each stage's means a step (the stages that took any time, in step
    /// order), then "total"; empty when no step was timed. The sums start
    /// afresh.
    pub fn take(&mut self) -> Vec<StageThreadTimes> {
        std::mem::take(&mut self.0)
            .means()
            .into_iter()
            .map(StageThreadTimes::from)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn untimed_steps_give_no_figures() {
        let mut sums = ThreadSums::default();
        sums.add(&Counters::default());
        assert!(sums.take().is_empty());
    }

    /// On one thread the step's thread is busy through every stage: the
    /// total's busy time is the step's, with no barrier and no idle time,
    /// and a read starts the sums afresh.
    #[test]
    fn timed_steps_on_one_thread_are_all_busy() {
        // The tests' global pool may have several threads (up-physics'
        // `parallel` is on natively): this one steps on a pool of one.
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a one-thread pool");
        one.install(timed_steps_on_one_thread);
    }

    fn timed_steps_on_one_thread() {
        let mut state = crate::State::default();
        state.load_default().expect("the default scene builds");
        set_thread_timing(true);
        let stepped = state.step(4);
        set_thread_timing(false);
        stepped.unwrap();
        let stats = state.stats().unwrap();
        let total = stats.threads.last().expect("timed steps give figures");
        assert_eq!(total.stage, "total");
        assert!(
            stats.threads.iter().any(|s| s.stage == "solve"),
            "{stats:?}"
        );
        assert!(total.wall_ms > 0.0);
        assert!((total.busy_ms[0] - total.wall_ms).abs() < 1e-9, "{total:?}");
        assert_eq!(total.barrier_ms[0], 0.0);
        assert!(
            state.stats().unwrap().threads.is_empty(),
            "a read resets the sums"
        );
    }
}
