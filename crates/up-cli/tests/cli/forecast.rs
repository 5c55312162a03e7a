//! `up forecast` and `up run --hours`: hours of simulated time as a time-lapse.
//! The scenes are small and their balloons were filled long before the run,
//! so they come down within the few hours simulated.

use super::*;

/// A 2 m × 2 m room, 2.4 m high with a flat ceiling: three untreated latex
/// balloons without ribbons filled 14.5 hours before the run, near the end
/// of their float time (they still rise, and leave the ceiling 1–2 h into the
/// run; 13.5 to 15.5 h would do on the present calibration), and one foil
/// balloon filled as long before (it keeps its lift for weeks).
const SCENE: &str = "\
[room]
width = 2.0
depth = 2.0
wall_height = 2.4
ceiling = \"flat\"

[[balloons]]
count = 3
kind = \"latex\"
treatment = \"none\"
filled_hours_before = 14.5

[[balloons]]
count = 1
kind = \"foil\"
filled_hours_before = 14.5

[sim]
seed = 7
";

/// Simulated hours of the forecast: long enough for the latex balloons above to land.
const HOURS: &str = "4";

fn write_scene(dir: &TempDir) -> String {
    let path = dir.path("late.toml");
    std::fs::write(&path, SCENE).unwrap();
    path.display().to_string()
}

#[test]
fn forecast_says_when_the_balloons_leave_the_ceiling_and_draws_it() {
    let dir = TempDir::new("forecast");
    let scene = write_scene(&dir);
    let plot = dir.str("float.svg");
    let started = std::time::Instant::now();
    let text = up_ok(&[
        "forecast", &scene, "--hours", HOURS, "--json", "--plot", &plot,
    ]);
    eprintln!("forecast took {:.1} s", started.elapsed().as_secs_f64());
    assert!(text.starts_with("up forecast"), "{text}");
    assert!(text.contains("0 (latex none)"), "{text}");
    assert!(text.contains("1 (foil none)"), "{text}");

    let j = last_json(&text);
    assert_eq!(j["hours"], 4.0);
    assert!(j["steps"].as_u64().unwrap() > 0, "{j}");
    assert!(j["jumps"].as_u64().is_some(), "{j}");
    assert!(j["wall_s"].as_f64().unwrap() > 0.0, "{j}");
    let groups = j["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 2, "{j}");

    let latex = &groups[0];
    assert_eq!(
        (
            &latex["group"],
            &latex["count"],
            &latex["kind"],
            &latex["treatment"]
        ),
        (&0.into(), &3.into(), &"latex".into(), &"none".into()),
        "{latex}"
    );
    let first = latex["leaves_ceiling_h"]["first"].as_f64();
    let median = latex["leaves_ceiling_h"]["median"].as_f64();
    let landed = latex["on_floor_h"]["median"].as_f64();
    let (Some(first), Some(median), Some(landed)) = (first, median, landed) else {
        panic!(
            "the late latex balloons should leave the ceiling and land within {HOURS} h: {latex}"
        );
    };
    assert!(0.0 < first && first <= median, "{latex}");
    // Without ribbons they fall straight down: leaving and landing may
    // fall in the same sample.
    assert!(median <= landed && landed <= 4.0, "{latex}");
    let lift = latex["mean_lift_fraction_end"].as_f64().unwrap();
    assert!((0.0..0.5).contains(&lift), "{latex}");

    let foil = &groups[1];
    assert_eq!((&foil["count"], &foil["kind"]), (&1.into(), &"foil".into()));
    assert!(foil["leaves_ceiling_h"]["first"].is_null(), "{foil}");
    assert!(foil["on_floor_h"]["median"].is_null(), "{foil}");
    assert!(
        foil["mean_lift_fraction_end"].as_f64().unwrap() > 0.9,
        "{foil}"
    );

    let svg = std::fs::read_to_string(&plot).unwrap();
    assert!(
        svg.trim_start().starts_with("<svg"),
        "{}",
        &svg[..svg.len().min(200)]
    );
    assert!(svg.trim_end().ends_with("</svg>"));
    for label in [
        "at the ceiling",
        "hovering",
        "on the floor",
        "simulated time (h)",
    ] {
        assert!(svg.contains(label), "no {label} in the plot");
    }
    // Only the plot and the scene: no temporary file left beside it.
    assert_eq!(dir.files(), vec!["float.svg", "late.toml"]);
}

#[test]
fn forecast_rejects_bad_hours_samples_and_plot_paths() {
    let dir = TempDir::new("forecast-bad");
    let scene = dir.str("late.toml");
    std::fs::write(&scene, "[[balloons]]\ncount = 2\n").unwrap();
    for hours in ["0", "-1", "nan", "inf", "2000.5"] {
        let err = up_err(&["forecast", &scene, "--hours", hours]);
        assert!(err.contains("--hours"), "{hours}: {err}");
    }
    for minutes in ["0", "-2", "nan", "61"] {
        let err = up_err(&["forecast", &scene, "--sample-minutes", minutes]);
        assert!(err.contains("--sample-minutes"), "{minutes}: {err}");
    }
    let missing = dir.str("no-such-dir/float.svg");
    let err = up_err(&["forecast", &scene, "--hours", "0.01", "--plot", &missing]);
    assert!(err.contains("--plot") && err.contains("float.svg"), "{err}");
    assert_eq!(dir.files(), vec!["late.toml"], "nothing written");
    up_err(&["forecast", &dir.str("absent.toml")]);
}

#[test]
fn run_hours_is_a_time_lapse_with_the_lift_left() {
    let started = std::time::Instant::now();
    let text = up_ok(&["run", "--balloons", "3", "--hours", "0.05", "--json"]);
    eprintln!("run --hours took {:.1} s", started.elapsed().as_secs_f64());
    let j = last_json(&text);
    let simulated = j["sim_time_s"].as_f64().unwrap();
    assert!((simulated - 180.0).abs() < 0.05, "{j}");
    assert!((j["sim_seconds"].as_f64().unwrap() - simulated).abs() < 1e-9);
    assert!(j["jumps"].as_u64().is_some(), "{j}");
    // Three minutes take fewer steps than stepping every frame would once
    // the balloons sleep under the ceiling.
    let steps = j["steps"].as_u64().unwrap();
    assert!(steps > 0 && steps <= 10_800, "{j}");
    let lift = j["mean_lift_fraction"]
        .as_f64()
        .expect("the balloons carry gas");
    assert!(lift > 0.95 && lift <= 1.0 + 1e-9, "{j}");
    assert_eq!(j["escaped"], 0);
    assert_eq!(j["nan_bodies"], 0);

    // A stepped run reports the same keys, no jumps.
    let stepped = last_json(&up_ok(&[
        "run",
        "--balloons",
        "3",
        "--seconds",
        "0.5",
        "--json",
    ]));
    assert_eq!(stepped["jumps"], 0);
    assert!((stepped["sim_time_s"].as_f64().unwrap() - 0.5).abs() < 1e-3);
    assert!(
        stepped["mean_lift_fraction"].as_f64().is_some(),
        "{stepped}"
    );
}

#[test]
fn run_hours_rejects_bad_values_and_seconds_beside_it() {
    for hours in ["0", "-3", "nan", "inf", "2001"] {
        let err = up_err(&["run", "--balloons", "1", "--hours", hours]);
        assert!(err.contains("--hours"), "{hours}: {err}");
    }
    let err = up_err(&["run", "--hours", "1", "--seconds", "5"]);
    assert!(
        err.contains("--hours") && err.contains("--seconds"),
        "{err}"
    );
}

#[test]
fn run_hours_writes_a_row_set_every_k_simulated_minutes() {
    let dir = TempDir::new("run-hours-csv");
    let out = dir.str("t.csv");
    up_ok(&[
        "run",
        "--balloons",
        "2",
        "--hours",
        "0.1",
        "--every",
        "2",
        "--out",
        &out,
    ]);
    let mut times: Vec<f64> = csv_rows(&out, "t,id,x,y,z,qx,qy,qz,qw")
        .iter()
        .map(|r| r[0])
        .collect();
    times.dedup();
    // Start, then every second minute of the six: 0, 2, 4, 6 min.
    assert_eq!(times.len(), 4, "{times:?}");
    for (k, t) in times.iter().enumerate() {
        assert!((t - 120.0 * k as f64).abs() < 0.05, "{times:?}");
    }
}

/// `late.toml` (`SCENE`) as it is, and with a ceiling vent 0.6 m across
/// over its balloons switched on a minute into the run.
fn still_and_vented(dir: &TempDir) -> (String, String) {
    let still = write_scene(dir);
    let vented = dir.path("vented.toml");
    let vent = "\n[[vents]]\nposition = [0.0, 2.4, 0.0]\ndiameter_m = 0.6\nspeed_m_s = 3.0\n\
                on = [[60.0, 1e9]]\n";
    std::fs::write(&vented, format!("{SCENE}{vent}")).unwrap();
    (still, vented.display().to_string())
}

/// A short forecast's output and its JSON.
fn short_forecast(scene: &str) -> (String, serde_json::Value) {
    let text = up_ok(&["forecast", scene, "--hours", "0.05", "--json"]);
    let json = last_json(&text);
    (text, json)
}

#[test]
fn forecast_says_which_moving_air_it_runs_with() {
    let dir = TempDir::new("forecast-air");
    let (still, vented) = still_and_vented(&dir);
    let (text, still) = short_forecast(&still);
    assert!(text.contains("air ") && text.contains("still"), "{text}");
    assert_eq!(
        still["air"],
        serde_json::json!({"fans": 0, "vents": 0, "draughts": 0})
    );
    let (text, blown) = short_forecast(&vented);
    assert!(
        text.contains("no fans, 1 vent, no draughts (as the scene switches them)"),
        "{text}"
    );
    assert_eq!(
        blown["air"],
        serde_json::json!({"fans": 0, "vents": 1, "draughts": 0})
    );
}

/// Still, the balloons sleep under the ceiling and the run jumps; once the
/// vent blows, the balloon under it is blown down and stepped.
#[test]
fn forecast_with_a_vent_switched_on_blows_a_balloon_off_the_ceiling() {
    let dir = TempDir::new("forecast-vent");
    let (still, vented) = still_and_vented(&dir);
    let (_, still) = short_forecast(&still);
    let (_, blown) = short_forecast(&vented);
    eprintln!(
        "forecast steps and jumps: still {} and {}, with the vent {} and {}",
        still["steps"], still["jumps"], blown["steps"], blown["jumps"]
    );
    let steps = |j: &serde_json::Value| j["steps"].as_u64().unwrap();
    assert!(steps(&blown) > 2 * steps(&still), "{still}\n{blown}");
}
