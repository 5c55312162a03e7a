//! Each thread's part of each stage summed over several steps and read as
//! means a step: what `up-bench` prints after a run and the page's `stats`
//! hands over between two reads. Fixed arrays: adding a step allocates
//! nothing, so a page can sum every step it takes.

use serde::{Deserialize, Serialize};

use crate::counters::{Counters, Stage};
use crate::threading::thread_times::TIMED_THREADS;

/// One stage's figures, ms (or counts) a step, the step's thread first.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StageThreadMeans {
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

/// One stage's sums over the steps added.
#[derive(Clone, Copy, Debug, Default)]
struct StageSum {
    wall_ms: f64,
    busy_ms: [f64; TIMED_THREADS],
    barrier_ms: [f64; TIMED_THREADS],
    idle_ms: [f64; TIMED_THREADS],
    barriers: f64,
    passes: f64,
}

impl StageSum {
    fn add(&mut self, other: &StageSum) {
        self.wall_ms += other.wall_ms;
        self.barriers += other.barriers;
        self.passes += other.passes;
        for t in 0..TIMED_THREADS {
            self.busy_ms[t] += other.busy_ms[t];
            self.barrier_ms[t] += other.barrier_ms[t];
            self.idle_ms[t] += other.idle_ms[t];
        }
    }

    fn mean(&self, stage: &str, threads: usize, per_step: f64) -> StageThreadMeans {
        let scale = |v: &[f64; TIMED_THREADS]| v[..threads].iter().map(|x| x * per_step).collect();
        StageThreadMeans {
            stage: stage.to_string(),
            wall_ms: self.wall_ms * per_step,
            busy_ms: scale(&self.busy_ms),
            barrier_ms: scale(&self.barrier_ms),
            idle_ms: scale(&self.idle_ms),
            barriers: self.barriers * per_step,
            passes: self.passes * per_step,
        }
    }
}

/// Each stage's per-thread sums over the timed steps added.
#[derive(Clone, Debug)]
pub struct ThreadSums {
    stages: [StageSum; Stage::COUNT],
    /// Most threads any summed step was timed on (a small step run alone
    /// leaves the others' figures at zero).
    threads: usize,
    steps: u64,
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
        let n = timed.threads();
        if n == 0 {
            return;
        }
        self.threads = self.threads.max(n);
        for (sum, stage) in self.stages.iter_mut().zip(Stage::ALL) {
            sum.wall_ms += counters.ms(stage);
            sum.barriers += f64::from(timed.barriers(stage));
            sum.passes += f64::from(timed.passes(stage));
            for (t, time) in timed.times(stage).iter().enumerate() {
                sum.busy_ms[t] += time.busy_ms;
                sum.barrier_ms[t] += time.barrier_ms;
                sum.idle_ms[t] += time.idle_ms;
            }
        }
        self.steps += 1;
    }

    /// Timed steps added.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Each stage's means a step (the stages that took any time, in step
    /// order), then "total" (every stage summed); empty when no step was
    /// timed.
    pub fn means(&self) -> Vec<StageThreadMeans> {
        if self.steps == 0 {
            return Vec::new();
        }
        let per_step = 1.0 / self.steps as f64;
        let mut total = StageSum::default();
        let mut rows = Vec::new();
        for (sum, stage) in self.stages.iter().zip(Stage::ALL) {
            total.add(sum);
            if sum.wall_ms > 0.0 {
                rows.push(sum.mean(stage.name(), self.threads, per_step));
            }
        }
        rows.push(total.mean("total", self.threads, per_step));
        rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn untimed_steps_give_no_figures() {
        let mut sums = ThreadSums::default();
        sums.add(&Counters::default());
        assert_eq!(sums.steps(), 0);
        assert!(sums.means().is_empty());
    }
}
