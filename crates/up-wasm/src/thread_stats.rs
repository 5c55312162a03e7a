//! Each thread's part of each stage as the page reads it
//! (`up_physics::Counters::threads`, timed while `set_thread_timing` is on):
//! busy, waiting at a staged pass's barriers, and idle (looking for work, or
//! the step's thread waiting for a pass to join), summed over the steps
//! between two `stats` calls and averaged when read, as the stage times are.
//! Fixed arrays: adding a step allocates nothing.

use serde::Serialize;
use tsify_next::Tsify;
use up_physics::{Counters, Stage};
use wasm_bindgen::prelude::*;

/// Threads whose figures are kept (the step's thread first); the pool's
/// others are left out.
const KEPT_THREADS: usize = 16;

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

/// One stage's sums over the steps taken since the last `take`.
#[derive(Clone, Copy, Default)]
struct StageSum {
    wall_ms: f64,
    busy_ms: [f64; KEPT_THREADS],
    barrier_ms: [f64; KEPT_THREADS],
    idle_ms: [f64; KEPT_THREADS],
    barriers: f64,
    passes: f64,
}

/// Each stage's per-thread sums since the last `take`.
pub struct ThreadSums {
    stages: [StageSum; Stage::COUNT],
    /// Most threads any summed step was timed on.
    threads: usize,
    steps: u32,
}

impl Default for ThreadSums {
    fn default() -> Self {
        ThreadSums {
            stages: [StageSum::default(); Stage::COUNT],
            threads: 0,
            steps: 0,
        }
    }
}

impl ThreadSums {
    /// Adds a step's figures; a step without them (timing off) adds nothing.
    pub fn add(&mut self, counters: &Counters) {
        let timed = counters.threads();
        let n = timed.threads().min(KEPT_THREADS);
        if n == 0 {
            return;
        }
        self.threads = self.threads.max(n);
        for (sum, stage) in self.stages.iter_mut().zip(Stage::ALL) {
            sum.wall_ms += counters.ms(stage);
            sum.barriers += f64::from(timed.barriers(stage));
            sum.passes += f64::from(timed.passes(stage));
            for (t, time) in timed.times(stage).iter().take(n).enumerate() {
                sum.busy_ms[t] += time.busy_ms;
                sum.barrier_ms[t] += time.barrier_ms;
                sum.idle_ms[t] += time.idle_ms;
            }
        }
        self.steps += 1;
    }

    /// Each stage's means a step (the stages that took any time, in step
    /// order), then "total" (every stage summed); empty when no step was
    /// timed. The sums start afresh.
    pub fn take(&mut self) -> Vec<StageThreadTimes> {
        if self.steps == 0 {
            return Vec::new();
        }
        let per_step = 1.0 / f64::from(self.steps);
        let threads = self.threads;
        let mut total = StageSum::default();
        let mut rows = Vec::new();
        for (sum, stage) in self.stages.iter().zip(Stage::ALL) {
            total.wall_ms += sum.wall_ms;
            total.barriers += sum.barriers;
            total.passes += sum.passes;
            for t in 0..threads {
                total.busy_ms[t] += sum.busy_ms[t];
                total.barrier_ms[t] += sum.barrier_ms[t];
                total.idle_ms[t] += sum.idle_ms[t];
            }
            if sum.wall_ms > 0.0 {
                rows.push(mean_row(stage.name(), sum, threads, per_step));
            }
        }
        rows.push(mean_row("total", &total, threads, per_step));
        *self = ThreadSums::default();
        rows
    }
}

fn mean_row(name: &str, sum: &StageSum, threads: usize, per_step: f64) -> StageThreadTimes {
    let scale = |v: &[f64; KEPT_THREADS]| v[..threads].iter().map(|x| x * per_step).collect();
    StageThreadTimes {
        stage: name.to_string(),
        wall_ms: sum.wall_ms * per_step,
        busy_ms: scale(&sum.busy_ms),
        barrier_ms: scale(&sum.barrier_ms),
        idle_ms: scale(&sum.idle_ms),
        barriers: sum.barriers * per_step,
        passes: sum.passes * per_step,
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
