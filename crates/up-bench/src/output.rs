//! The JSON lines `up-bench --json` prints: one per engine, then the ratio.

use serde::{Deserialize, Serialize};

/// One engine's result over a run. Times are wall-clock ms per step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EngineResult {
    /// `"up"` or `"rapier"`.
    pub engine: String,
    /// `"native"`, or `"wasm-node"` for web/bench.
    pub runtime: String,
    pub balloons: u64,
    pub steps: u64,
    /// Threads the engine ran on (Rapier: always 1).
    pub threads: usize,
    pub ms_per_step_median: f64,
    pub ms_per_step_p95: f64,
    pub ms_per_step_mean: f64,
    /// Median over the last third of the steps.
    pub settled_ms_per_step_median: f64,
    /// m: deepest overlap over the recorded steps (all of them up to `measure::POSE_BUDGET` poses; UP's geometry on the poses).
    pub max_penetration_m: f32,
    /// m: the same at the last step.
    pub final_penetration_m: f32,
    /// Balloons whose centre of mass ended outside the room.
    pub escaped: usize,
    /// Balloons awake after the last step.
    pub awake_at_end: usize,
    /// MB: peak resident set of a child process running this engine alone for the same steps.
    pub peak_rss_mb: Option<f64>,
    /// Bytes per balloon: that peak less the child's peak before the scene was built, over N.
    pub rss_bytes_per_balloon: Option<f64>,
    /// m: the benchmark room's side.
    pub room_width_m: f32,
    /// Rapier only: `"compound"` or `"balls"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rapier_shape: Option<String>,
    /// Ribbons tied to the balloons (`--ribbons`; 0: none).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub ribbons: usize,
    /// The largest relative stretch of any ribbon after any step (length
    /// along the chain from the knot over the ribbon's length, less one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_ribbon_stretch: Option<f32>,
    /// The step that stretch was measured after (1 is the first).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_ribbon_stretch_step: Option<u64>,
    /// The same after the start (`run::RIBBON_START_S`): the steps after the
    /// first second.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_ribbon_stretch_after_start: Option<f32>,
    /// Rapier with ribbons: `"impulse"` or `"multibody"` joints.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rapier_joints: Option<String>,
    /// UP: its own stage timers (`World::counters`), ms per step over the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stage_ms_mean: Option<Vec<(String, f64)>>,
    /// UP with `--thread-times`: each thread's busy, barrier and idle time
    /// in each stage, ms per step over the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stage_threads_mean: Option<Vec<up_physics::StageThreadMeans>>,
    /// UP with `--thread-times` on several threads: a cache line's round
    /// trip between two cores just before the run and just after, ns
    /// (`core_probe`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub core_round_trip_ns: Option<[f64; 2]>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// The last line: Rapier's whole-run median over UP's, and its mean (total
/// time) over UP's. Over a run of phases (rising, arriving, settling, asleep)
/// the sorted step times climb steeply through the middle, so the median
/// swings from run to run on a busy host; the mean does not.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RatioLine {
    pub ratio_rapier_over_up: f64,
    pub ratio_rapier_over_up_mean: f64,
    /// With ribbons: UP with them over UP without, median and mean.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio_up_ribbons_over_up: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio_up_ribbons_over_up_mean: Option<f64>,
}

/// Rapier's `stat` over UP's, when both ran (with ribbons: both with them).
pub fn ratio(results: &[EngineResult], stat: fn(&EngineResult) -> f64) -> Option<f64> {
    let rapier = results.iter().find(|r| r.engine == "rapier")?;
    let up = results
        .iter()
        .find(|r| r.engine == "up" && (r.ribbons > 0) == (rapier.ribbons > 0))?;
    Some(stat(rapier) / stat(up))
}

/// UP's `stat` with ribbons over its `stat` without, when both ran.
pub fn ribbon_ratio(results: &[EngineResult], stat: fn(&EngineResult) -> f64) -> Option<f64> {
    let up = |ribbons: bool| {
        results
            .iter()
            .find(|r| r.engine == "up" && (r.ribbons > 0) == ribbons)
            .map(stat)
    };
    Some(up(true)? / up(false)?)
}

/// The whole-run median ms per step.
pub fn median(r: &EngineResult) -> f64 {
    r.ms_per_step_median
}

/// The whole-run mean ms per step: total time over steps.
pub fn mean(r: &EngineResult) -> f64 {
    r.ms_per_step_mean
}

/// The lines to print: one JSON object per engine, then the ratios when both ran.
pub fn json_lines(results: &[EngineResult]) -> Result<Vec<String>, serde_json::Error> {
    let mut lines = results
        .iter()
        .map(serde_json::to_string)
        .collect::<Result<Vec<_>, _>>()?;
    if let (Some(by_median), Some(by_mean)) = (ratio(results, median), ratio(results, mean)) {
        lines.push(serde_json::to_string(&RatioLine {
            ratio_rapier_over_up: by_median,
            ratio_rapier_over_up_mean: by_mean,
            ratio_up_ribbons_over_up: ribbon_ratio(results, median),
            ratio_up_ribbons_over_up_mean: ribbon_ratio(results, mean),
        })?);
    }
    Ok(lines)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result(engine: &str, median: f64, mean: f64) -> EngineResult {
        EngineResult {
            engine: engine.into(),
            runtime: "native".into(),
            balloons: 1000,
            steps: 600,
            threads: 1,
            ms_per_step_median: median,
            ms_per_step_p95: median * 1.5,
            ms_per_step_mean: mean,
            settled_ms_per_step_median: median * 0.5,
            max_penetration_m: 0.001,
            final_penetration_m: 0.0005,
            escaped: 0,
            awake_at_end: 10,
            peak_rss_mb: Some(12.5),
            rss_bytes_per_balloon: Some(900.0),
            room_width_m: 5.3,
            rapier_shape: None,
            ribbons: 0,
            max_ribbon_stretch: None,
            max_ribbon_stretch_step: None,
            max_ribbon_stretch_after_start: None,
            rapier_joints: None,
            stage_ms_mean: None,
            stage_threads_mean: None,
            core_round_trip_ns: None,
        }
    }

    #[test]
    fn one_line_per_engine_with_the_required_keys_then_the_ratio() {
        let lines = json_lines(&[result("up", 2.0, 4.0), result("rapier", 7.0, 10.0)]).unwrap();
        assert_eq!(lines.len(), 3);
        for line in &lines[..2] {
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            for key in [
                "engine",
                "balloons",
                "steps",
                "ms_per_step_median",
                "ms_per_step_p95",
                "settled_ms_per_step_median",
                "max_penetration_m",
                "escaped",
                "peak_rss_mb",
            ] {
                assert!(v.get(key).is_some(), "{key} missing from {line}");
            }
            assert!(!line.contains('\n'));
        }
        let ratio: RatioLine = serde_json::from_str(&lines[2]).unwrap();
        assert_eq!(ratio.ratio_rapier_over_up, 3.5);
        assert_eq!(ratio.ratio_rapier_over_up_mean, 2.5);
        assert_eq!(
            lines[2],
            r#"{"ratio_rapier_over_up":3.5,"ratio_rapier_over_up_mean":2.5}"#
        );
        // A line reads back as it was written.
        let back: EngineResult = serde_json::from_str(&lines[0]).unwrap();
        assert_eq!(back, result("up", 2.0, 4.0));
    }

    #[test]
    fn with_ribbons_rapier_is_compared_with_up_with_ribbons() {
        let with = |mut r: EngineResult, stretch: f32| {
            r.ribbons = 1000;
            r.max_ribbon_stretch = Some(stretch);
            r
        };
        let results = [
            with(result("up", 2.4, 5.0), 0.001),
            with(result("rapier", 12.0, 20.0), 0.05),
            result("up", 2.0, 4.0),
        ];
        let lines = json_lines(&results).unwrap();
        assert_eq!(lines.len(), 4);
        let ratio: RatioLine = serde_json::from_str(&lines[3]).unwrap();
        assert_eq!(ratio.ratio_rapier_over_up, 5.0);
        assert_eq!(ratio.ratio_rapier_over_up_mean, 4.0);
        assert_eq!(ratio.ratio_up_ribbons_over_up, Some(1.2));
        assert_eq!(ratio.ratio_up_ribbons_over_up_mean, Some(1.25));
        let back: EngineResult = serde_json::from_str(&lines[1]).unwrap();
        assert_eq!(back, results[1]);
        // Without ribbons the line is as before.
        assert!(!lines[2].contains("ribbon"), "{}", lines[2]);
    }

    #[test]
    fn no_ratio_for_one_engine() {
        assert_eq!(json_lines(&[result("up", 2.0, 4.0)]).unwrap().len(), 1);
    }
}
