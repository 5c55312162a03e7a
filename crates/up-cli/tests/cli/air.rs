//! `up air`: the moving air a scene's fans make, printed at points, checked
//! against the round free jet of the literature; and its bad input.

use super::*;

/// A fan 20 cm across blowing 5 m/s along +z from near the back wall of a
/// 10 m room, 1.5 m up; and one that sweeps 90° every 12 s.
const FAN_SCENE: &str = "\
[room]
width = 10.0
depth = 10.0
wall_height = 3.0
ceiling = \"flat\"

[[balloons]]
count = 1

[[fans]]
position = [0.0, 1.5, -4.5]
direction = [0.0, 0.0, 1.0]
diameter_m = 0.2
speed_m_s = 5.0
";

const OUTLET: [f64; 3] = [0.0, 1.5, -4.5];
const D: f64 = 0.2;
const U0: f64 = 5.0;
/// B in U_c = U₀·B·D/x, the ends of the measured range (Pope, *Turbulent
/// Flows*, table 5.1: 5.8 Hussein, Capp & George 1994; 6.1 Wygnanski &
/// Fiedler 1969).
const B_MEASURED: [f64; 2] = [5.8, 6.1];
/// r½ / x, where the speed across the jet is half the centreline's
/// (Hussein, Capp & George 1994: 0.094).
const SPREAD_S: f64 = 0.094;

fn write_scene(dir: &TempDir, name: &str, text: &str) -> String {
    let path = dir.path(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// `up air SCENE --at ... --t T --json`: (point, speed) for each point.
fn speeds_at(scene: &str, points: &[[f64; 3]], t: f64) -> Vec<([f64; 3], f64)> {
    let mut args = vec!["air".to_string(), scene.to_string()];
    for p in points {
        args.push(format!("--at={},{},{}", p[0], p[1], p[2]));
    }
    args.extend(["--t".to_string(), t.to_string(), "--json".to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let j = last_json(&up_ok(&args));
    j["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let at: Vec<f64> = p["at_m"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let u: Vec<f64> = p["velocity_m_s"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let speed = p["speed_m_s"].as_f64().unwrap();
            let norm = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
            assert!((speed - norm).abs() < 1e-5, "{p}");
            ([at[0], at[1], at[2]], speed)
        })
        .collect()
}

#[test]
fn a_fans_jet_decays_as_one_over_distance_and_spreads_as_measured() {
    let dir = TempDir::new("air-jet");
    let scene = write_scene(&dir, "fan.toml", FAN_SCENE);
    let diameters = [8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0];
    let along = |x_d: f64| [OUTLET[0], OUTLET[1], OUTLET[2] + x_d * D];
    let axis: Vec<[f64; 3]> = diameters.iter().map(|&n| along(n)).collect();
    // At the half-width the literature measured, to the side.
    let side: Vec<[f64; 3]> = diameters
        .iter()
        .map(|&n| {
            let [x, y, z] = along(n);
            [x + SPREAD_S * n * D, y, z]
        })
        .collect();
    let centre = speeds_at(&scene, &axis, 0.0);
    let edge = speeds_at(&scene, &side, 0.0);

    eprintln!("the fan's jet along its axis: U₀ = {U0} m/s, D = {D} m");
    eprintln!(
        "{:>6} {:>10} {:>14} {:>14} {:>8} {:>12}",
        "x/D", "speed m/s", "law B=5.8 m/s", "law B=6.1 m/s", "ratio", "at r½ / axis"
    );
    for (k, &n) in diameters.iter().enumerate() {
        let x = n * D;
        let speed = centre[k].1;
        let laws = B_MEASURED.map(|b| U0 * b * D / x);
        let half = edge[k].1 / speed;
        eprintln!(
            "{n:>6.0} {speed:>10.4} {:>14.4} {:>14.4} {:>8.3} {half:>12.3}",
            laws[0],
            laws[1],
            speed / laws[0]
        );
        for law in laws {
            assert!(
                (speed - law).abs() <= 0.25 * law,
                "{n} D: {speed} m/s against U₀·B·D/x = {law} m/s"
            );
        }
        assert!(
            (half - 0.5).abs() <= 0.2 * 0.5,
            "{n} D: at the half-width {} m/s, the centreline's {speed} m/s",
            edge[k].1
        );
    }
    // It decays: each point downstream is slower.
    assert!(centre.windows(2).all(|w| w[1].1 < w[0].1), "{centre:?}");
}

#[test]
fn a_sweeping_fan_turns_its_jet_and_an_interval_switches_it() {
    let dir = TempDir::new("air-sweep");
    let text = FAN_SCENE.replace(
        "speed_m_s = 5.0\n",
        "speed_m_s = 5.0\nsweep_deg = 90\nsweep_period_s = 12\non = [[0.0, 20.0]]\n",
    );
    let scene = write_scene(&dir, "sweep.toml", &text);
    let ahead = [OUTLET[0], OUTLET[1], OUTLET[2] + 10.0 * D];
    let at_start = speeds_at(&scene, &[ahead], 0.0)[0].1;
    // A quarter period on, it points 45° aside: the point ahead is out of the jet.
    let turned = speeds_at(&scene, &[ahead], 3.0)[0].1;
    // After its interval (and its run-down) it is still.
    let off = speeds_at(&scene, &[ahead], 30.0)[0].1;
    assert!(at_start > 2.0, "{at_start}");
    assert!(turned < 0.1 * at_start, "{turned} against {at_start}");
    assert_eq!(off, 0.0);
    // The table names the sources and prints one row per point.
    let text = up_ok(&["air", &scene, "--at", "-1,1.5,0", "--at", "1,1.5,0"]);
    assert!(text.starts_with("up air: "), "{text}");
    assert!(text.contains("1 fan, no vents, no draughts"), "{text}");
    assert_eq!(text.lines().count(), 4, "{text}");
}

#[test]
fn bad_points_times_and_scenes_exit_2_naming_the_flag() {
    let dir = TempDir::new("air-bad");
    let scene = write_scene(&dir, "fan.toml", FAN_SCENE);
    for at in ["1,2", "1,2,3,4", "a,b,c", "1,nan,0", ""] {
        let err = up_err(&["air", &scene, &format!("--at={at}")]);
        assert!(err.contains("--at"), "{at}: {err}");
    }
    let err = up_err(&["air", &scene, "--at", "0,1,9"]);
    assert!(
        err.contains("--at 0,1,9") && err.contains("inside the room"),
        "{err}"
    );
    for t in ["-1", "nan", "inf"] {
        let err = up_err(&["air", &scene, "--at", "0,1,0", "--t", t]);
        assert!(err.contains("--t"), "{t}: {err}");
    }
    let err = up_err(&["air", &scene]);
    assert!(err.contains("--at"), "{err}");
    let bad = write_scene(
        &dir,
        "bad.toml",
        "[[fans]]\nposition = [0.0, 1.0, 0.0]\nspeed_m_s = 45\n",
    );
    let err = up_err(&["air", &bad, "--at", "0,1,0"]);
    assert!(err.contains("bad.toml:3: fans[0].speed_m_s"), "{err}");
    up_err(&["air", &dir.str("absent.toml"), "--at", "0,1,0"]);
}
