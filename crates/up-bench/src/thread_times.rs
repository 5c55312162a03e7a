//! Where each of UP's threads spends each stage, as a text table: the means
//! a step of `up_physics::ThreadSums` (timed with
//! `up_physics::set_thread_timing`): busy, waiting at a staged pass's
//! barriers, and idle (looking for work, or the step's thread waiting for a
//! pass to join), and the barriers and parallel passes each stage crosses.

use up_physics::StageThreadMeans;

/// The figures as a text table: a row a stage (those over 1 % of the step,
/// and the total), busy / barrier / idle for each thread.
pub fn table(stages: &[StageThreadMeans]) -> String {
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
    fn a_table_lists_the_total_and_each_thread() {
        let row = |stage: &str, wall| StageThreadMeans {
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
