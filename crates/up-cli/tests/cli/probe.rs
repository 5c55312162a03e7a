//! `up run --probe ID --probe-out FILE.csv`: one balloon's forces every step.

use super::*;

const HEADER: &str = "t,fx_weight,fy_weight,fz_weight,fx_buoyancy,fy_buoyancy,fz_buoyancy,\
fx_drag,fy_drag,fz_drag,fx_contact,fy_contact,fz_contact,fx_ribbon,fy_ribbon,fz_ribbon,\
fx_other,fy_other,fz_other,ux_air,uy_air,uz_air";

/// Column of force `k` (weight 0 … other 5; 6 is the air's velocity), axis
/// `axis` (0 x, 1 y, 2 z).
fn col(k: usize, axis: usize) -> usize {
    1 + 3 * k + axis
}

#[test]
fn a_probed_balloon_s_forces_are_written_every_step_and_balance_at_terminal_speed() {
    let dir = TempDir::new("probe");
    let out = dir.str("probe.csv");
    let scene = asset("terminal-velocity.toml");
    up_ok(&[
        "run",
        &scene,
        "--seconds",
        "5",
        "--probe",
        "0",
        "--probe-out",
        &out,
    ]);
    let rows = csv_rows(&out, HEADER);
    assert_eq!(rows.len(), 300, "one row a step");
    for pair in rows.windows(2) {
        assert!(pair[1][0] > pair[0][0], "time goes on");
    }
    // Still air: no velocity of the air at the balloon.
    for row in &rows {
        assert_eq!([row[col(6, 0)], row[col(6, 1)], row[col(6, 2)]], [0.0; 3]);
    }
    let first = &rows[0];
    assert!((first[0] - 1.0 / 60.0).abs() < 1e-9, "after the first step");
    let last = rows.last().unwrap();
    let (weight, buoyancy) = (last[col(0, 1)], last[col(1, 1)]);
    assert!(weight < 0.0 && buoyancy > -weight, "{last:?}");
    assert!(last[col(2, 1)] < 0.0, "drag holds the rise back");
    // Risen for five seconds: at its terminal speed, nothing left over.
    for axis in 0..3 {
        let net: f64 = (0..6).map(|k| last[col(k, axis)]).sum();
        assert!(net.abs() < 0.01 * weight.abs(), "axis {axis}: {net} N");
    }
}

#[test]
fn a_bad_probe_exits_2_naming_the_flag_and_the_range_and_writes_nothing() {
    let dir = TempDir::new("probe-bad");
    let (out, poses) = (dir.str("probe.csv"), dir.str("poses.csv"));
    let scene = asset("terminal-velocity.toml");
    for id in ["1", "-1", "40000000000"] {
        let err = up_err(&[
            "run",
            &scene,
            "--seconds",
            "0.1",
            "--out",
            &poses,
            "--probe",
            id,
            "--probe-out",
            &out,
        ]);
        assert!(err.contains(&format!("--probe {id}")), "{err}");
        assert!(err.contains("from 0 to 0"), "{err}");
        assert!(dir.files().is_empty(), "{id}: nothing written");
    }
    for args in [
        vec!["--seconds", "0.1", "--probe", "0"],
        vec!["--seconds", "0.1", "--probe-out", &out],
        vec!["--hours", "1", "--probe", "0", "--probe-out", &out],
    ] {
        let mut all = vec!["run", &scene];
        all.extend(args.iter().copied());
        let err = up_err(&all);
        assert!(err.contains("--probe"), "{args:?}: {err}");
        assert!(dir.files().is_empty(), "{args:?}: nothing written");
    }
}
