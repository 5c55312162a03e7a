//! Where each of UP's threads spends each stage (`Counters::threads`,
//! timed with `up_physics::set_thread_timing`): busy, waiting at a staged
//! pass's barriers, and idle (looking for work, or the step's thread waiting
//! for a pass to join), ms a step over the run, and the barriers and
//! parallel passes each stage crosses a step.

use serde::{Deserialize, Serialize};
use up_physics::{Counters, Stage};

/// One stage's figures, ms (or counts) a step, the step's thread first.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StageThreads {
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

/// The run's sums, stage by stage (`Stage::ALL` order), then a total row.
#[derive(Clone, Debug, Default)]
pub struct ThreadTotals {
    stages: Vec<StageThreads>,
    steps: u64,
}

impl ThreadTotals {
    /// Adds a step's figures; a step without them (timing off) adds nothing.
    pub fn add(&mut self, counters: &Counters) {
        let threads = counters.threads();
        let n = threads.threads();
        if n == 0 {
            return;
        }
        if self.stages.is_empty() {
            self.stages = Stage::ALL
                .iter()
                .map(|s| s.name())
                .chain(["total"])
                .map(|name| StageThreads {
                    stage: name.to_string(),
                    wall_ms: 0.0,
                    busy_ms: vec![0.0; n],
                    barrier_ms: vec![0.0; n],
                    idle_ms: vec![0.0; n],
                    barriers: 0.0,
                    passes: 0.0,
                })
                .collect();
        }
        // A step run on fewer threads (a small one, alone) leaves the rest at zero.
        for row in &mut self.stages {
            for v in [&mut row.busy_ms, &mut row.barrier_ms, &mut row.idle_ms] {
                if v.len() < n {
                    v.resize(n, 0.0);
                }
            }
        }
        let (rows, total) = self.stages.split_at_mut(Stage::COUNT);
        let total = &mut total[0];
        for (row, stage) in rows.iter_mut().zip(Stage::ALL) {
            let wall = counters.ms(stage);
            let (barriers, passes) = (threads.barriers(stage), threads.passes(stage));
            for sum in [&mut *row, &mut *total] {
                sum.wall_ms += wall;
                sum.barriers += f64::from(barriers);
                sum.passes += f64::from(passes);
                for (t, time) in threads.times(stage).iter().enumerate() {
                    sum.busy_ms[t] += time.busy_ms;
                    sum.barrier_ms[t] += time.barrier_ms;
                    sum.idle_ms[t] += time.idle_ms;
                }
            }
        }
        self.steps += 1;
    }

    /// Each stage's means a step (the stages that took any time), then
    /// the total; none if no step was timed.
    pub fn means(&self) -> Option<Vec<StageThreads>> {
        if self.steps == 0 {
            return None;
        }
        let per_step = 1.0 / self.steps as f64;
        let scale = |v: &[f64]| v.iter().map(|x| x * per_step).collect();
        Some(
            self.stages
                .iter()
                .filter(|s| s.wall_ms > 0.0)
                .map(|s| StageThreads {
                    stage: s.stage.clone(),
                    wall_ms: s.wall_ms * per_step,
                    busy_ms: scale(&s.busy_ms),
                    barrier_ms: scale(&s.barrier_ms),
                    idle_ms: scale(&s.idle_ms),
                    barriers: s.barriers * per_step,
                    passes: s.passes * per_step,
                })
                .collect(),
        )
    }
}

/// The figures as a text table: a row a stage (those over 1 % of the step,
/// and the total), busy / barrier / idle for each thread.
pub fn table(stages: &[StageThreads]) -> String {
    let total = stages.last().map_or(0.0, |s| s.wall_ms);
    let threads = stages.first().map_or(0, |s| s.busy_ms.len());
    let mut out = format!(
        "{:<16} {:>8} {:>9} {:>7}",
        "stage, ms/step", "wall", "barriers", "passes"
    );
    for t in 0..threads {
        let who = if t == 0 {
            "step's".into()
        } else {
            format!("t{t}")
        };
        out += &format!("  {:>22}", format!("{who} busy/barrier/idle"));
    }
    out.push('\n');
    for s in stages
        .iter()
        .filter(|s| s.stage == "total" || s.wall_ms >= 0.01 * total)
    {
        out += &format!(
            "{:<16} {:>8.3} {:>9.1} {:>7.1}",
            s.stage, s.wall_ms, s.barriers, s.passes
        );
        for t in 0..threads {
            let cell = format!(
                "{:.2}/{:.2}/{:.2}",
                s.busy_ms[t], s.barrier_ms[t], s.idle_ms[t]
            );
            out += &format!("  {cell:>22}");
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn untimed_steps_give_no_figures() {
        let mut totals = ThreadTotals::default();
        totals.add(&Counters::default());
        assert_eq!(totals.means(), None);
    }

    #[test]
    fn a_table_lists_the_total_and_each_thread() {
        let row = |stage: &str, wall| StageThreads {
            stage: stage.into(),
            wall_ms: wall,
            busy_ms: vec![wall, 0.5 * wall],
            barrier_ms: vec![0.0, 0.25 * wall],
            idle_ms: vec![0.0, 0.25 * wall],
            barriers: 8.0,
            passes: 2.0,
        };
        let text = table(&[row("solve", 4.0), row("gas", 0.001), row("total", 4.0)]);
        assert!(text.contains("solve"), "{text}");
        assert!(!text.contains("gas"), "{text}");
        assert!(text.contains("2.00/1.00/1.00"), "{text}");
        assert_eq!(text.lines().count(), 3);
    }
}
