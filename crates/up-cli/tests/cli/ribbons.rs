//! Ribbons through the CLI: the scene table's errors, `--ribbons-out`, and
//! the ribbon and tilt figures of `--json`.

use super::*;

/// A scene file in `dir` with one group of `count` balloons and `ribbon` as
/// its `[balloons.ribbon]` table.
fn ribbon_scene(dir: &TempDir, count: u32, ribbon: &str) -> String {
    let path = dir.str("ribbons.toml");
    let text = format!("[[balloons]]\ncount = {count}\n\n[balloons.ribbon]\n{ribbon}\n");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn bad_ribbon_keys_exit_2_naming_the_key_and_write_nothing() {
    let cases = [
        ("segments = 500", "balloons[0].ribbon.segments", "[2, 128]"),
        ("length_m = 25", "balloons[0].ribbon.length_m", "(0, 20] m"),
        (
            "mass_per_m_g = 0",
            "balloons[0].ribbon.mass_per_m_g",
            "(0, 1000] g/m",
        ),
        (
            "weight_g = -3",
            "balloons[0].ribbon.weight_g",
            "[0, 1000] g",
        ),
        ("color = \"mauve\"", "balloons[0].ribbon.color", "#rrggbb"),
        (
            "lenght_m = 1",
            "balloons[0].ribbon.lenght_m",
            "unknown field",
        ),
    ];
    for (line, key, expected) in cases {
        let dir = TempDir::new("bad-ribbon");
        let scene = ribbon_scene(&dir, 2, line);
        let (out, ribbons) = (dir.str("t.csv"), dir.str("r.csv"));
        let err = up_err(&[
            "run",
            &scene,
            "--seconds",
            "0.1",
            "--out",
            &out,
            "--ribbons-out",
            &ribbons,
        ]);
        assert!(err.contains(&format!(":5: {key}: ")), "{line}: {err}");
        assert!(err.contains(expected), "{line}: {err}");
        assert_eq!(dir.files(), vec!["ribbons.toml"], "{line}: nothing written");
        let err = up_err(&["validate", &scene]);
        assert!(err.contains(key), "{line}: {err}");
    }
}

#[test]
fn ribbons_out_writes_every_point_of_every_ribbon_every_k_steps() {
    let dir = TempDir::new("ribbons-out");
    let scene = ribbon_scene(&dir, 3, "length_m = 1.0\nsegments = 8\nweight_g = 2");
    let (out, ribbons) = (dir.str("t.csv"), dir.str("r.csv"));
    up_ok(&[
        "run",
        &scene,
        "--seconds",
        "0.25",
        "--every",
        "5",
        "--out",
        &out,
        "--ribbons-out",
        &ribbons,
    ]);
    let rows = csv_rows(&ribbons, "t,balloon,point,x,y,z");
    // 15 steps: the start, steps 5, 10, 15; three ribbons of 9 points each.
    assert_eq!(rows.len(), 4 * 3 * 9, "{rows:?}");
    assert!(rows.iter().all(|r| r.len() == 6));
    // The balloons are numbered as in --out.
    let poses = csv_rows(&out, "t,id,x,y,z,qx,qy,qz,qw");
    let mut ids: Vec<u64> = poses.iter().take(3).map(|r| r[1] as u64).collect();
    ids.sort();
    let mut balloons: Vec<u64> = rows.iter().map(|r| r[1] as u64).collect();
    balloons.sort();
    balloons.dedup();
    assert_eq!(balloons, ids);
    for ribbon in rows.chunks(9) {
        // One ribbon at one time, its points in order from the knot.
        assert!(ribbon
            .iter()
            .all(|r| r[0] == ribbon[0][0] && r[1] == ribbon[0][1]));
        let points: Vec<u64> = ribbon.iter().map(|r| r[2] as u64).collect();
        assert_eq!(points, (0..9).collect::<Vec<_>>());
        // Inextensible: each segment an eighth of a metre, within 1 %.
        for pair in ribbon.windows(2) {
            let d = ((pair[1][3] - pair[0][3]).powi(2)
                + (pair[1][4] - pair[0][4]).powi(2)
                + (pair[1][5] - pair[0][5]).powi(2))
            .sqrt();
            assert!(
                (d / 0.125 - 1.0).abs() < 0.01,
                "segment {d} m in {ribbon:?}"
            );
        }
        // Inside the 6 m x 6 m room, above its floor.
        assert!(ribbon
            .iter()
            .all(|r| r[3].abs() < 3.0 && r[5].abs() < 3.0 && r[4] > 0.0));
    }
    assert_eq!(rows[0][0], 0.0);
    assert!((rows.last().unwrap()[0] - 0.25).abs() < 1e-3);
    assert_eq!(dir.files(), vec!["r.csv", "ribbons.toml", "t.csv"]);
}

#[test]
fn ribbons_out_in_a_missing_directory_fails_before_running() {
    let dir = TempDir::new("ribbons-missing");
    let path = dir.path("no/such/r.csv").display().to_string();
    let err = up_err(&[
        "run",
        "--balloons",
        "1",
        "--seconds",
        "0.1",
        "--ribbons-out",
        &path,
    ]);
    assert!(err.contains("r.csv"), "{err}");
    assert!(dir.files().is_empty());
}

#[test]
fn run_json_reports_the_ribbons_their_stretch_and_the_tilts() {
    // The original room: every balloon on a 1.5 m ribbon.
    let j = last_json(&up_ok(&[
        "run",
        "--balloons",
        "6",
        "--seconds",
        "2",
        "--json",
    ]));
    assert_eq!(j["ribbons"], 6, "{j}");
    let stretch = j["ribbon_max_stretch"].as_f64().unwrap();
    assert!((0.0..0.01).contains(&stretch), "{j}");
    let (median, p90, max) = (
        j["median_tilt_deg"].as_f64().unwrap(),
        j["p90_tilt_deg"].as_f64().unwrap(),
        j["max_tilt_deg"].as_f64().unwrap(),
    );
    assert!((0.0..=180.0).contains(&median), "{j}");
    assert!(median <= p90 && p90 <= max + 1e-3 && max <= 180.0, "{j}");
    // No ribbon table: none, and nothing stretched.
    let dir = TempDir::new("no-ribbons");
    let scene = dir.str("plain.toml");
    std::fs::write(&scene, "[[balloons]]\ncount = 2\n").unwrap();
    let j = last_json(&up_ok(&["run", &scene, "--seconds", "0.5", "--json"]));
    assert_eq!(j["ribbons"], 0, "{j}");
    assert_eq!(j["ribbon_max_stretch"], 0.0, "{j}");
    // The bouquet.
    let j = last_json(&up_ok(&[
        "run",
        &asset("bouquet.toml"),
        "--seconds",
        "1",
        "--json",
    ]));
    assert_eq!(j["ribbons"], 6, "{j}");
    assert!(j["ribbon_max_stretch"].as_f64().unwrap() < 0.01, "{j}");
}

#[test]
fn export_obj_writes_the_scene_with_a_strip_a_ribbon_in_its_colour() {
    let dir = TempDir::new("export-ribbons");
    let out = dir.path("blender");
    let listed = up_ok(&[
        "export-obj",
        &out.display().to_string(),
        "--scene",
        &asset("bouquet.toml"),
        "--seconds",
        "0.5",
    ]);
    let scene_obj = out.join("scene.obj");
    assert!(
        listed.lines().any(|l| Path::new(l) == scene_obj),
        "{listed}"
    );
    assert!(listed.lines().all(|l| Path::new(l).exists()), "{listed}");
    let obj = std::fs::read_to_string(&scene_obj).unwrap();
    let objects = |prefix: &str| obj.lines().filter(|l| l.starts_with(prefix)).count();
    assert_eq!(objects("o balloon_"), 6, "six balloons");
    assert_eq!(objects("o ribbon_"), 6, "six ribbons");
    assert_eq!(objects("usemtl ribbon_d4af37"), 6);
    let mtl = std::fs::read_to_string(out.join("scene.mtl")).unwrap();
    assert!(
        mtl.contains("newmtl ribbon_d4af37\nKa 0.000 0.000 0.000\nKd 0.831 0.686 0.216"),
        "{mtl}"
    );
    assert!(obj.contains("mtllib scene.mtl"));
    // Every vertex inside the bouquet's 5 m x 5 m x 2.6 m room.
    for line in obj.lines().filter(|l| l.starts_with("v ")) {
        let v: Vec<f64> = line[2..].split(' ').map(|f| f.parse().unwrap()).collect();
        assert!(
            v[0].abs() <= 2.5 && v[2].abs() <= 2.5 && (0.0..=2.6).contains(&v[1]),
            "{line}"
        );
    }
    // The original room by default: fifty balloons on fifty ribbons.
    let out = dir.path("original");
    up_ok(&["export-obj", &out.display().to_string()]);
    let obj = std::fs::read_to_string(out.join("scene.obj")).unwrap();
    assert_eq!(
        obj.lines().filter(|l| l.starts_with("o ribbon_")).count(),
        50
    );
    // Bad input: exit 2, nothing written.
    let bad = dir.path("bad");
    up_err(&["export-obj", &bad.display().to_string(), "--seconds", "-1"]);
    let scene = ribbon_scene(&dir, 1, "segments = 1");
    let err = up_err(&["export-obj", &bad.display().to_string(), "--scene", &scene]);
    assert!(err.contains("balloons[0].ribbon.segments"), "{err}");
    assert!(!bad.exists());
}

#[test]
fn validate_shows_each_groups_ribbon() {
    let text = up_ok(&["validate", &asset("bouquet.toml")]);
    assert!(
        text.contains("ribbon 1.2 m of 16 segments, 0.300 g, #d4af37, a 35 g weight"),
        "{text}"
    );
    let text = up_ok(&["validate", &asset("default.toml")]);
    assert!(
        text.contains("ribbon 1.5 m of 16 segments, 0.375 g, white"),
        "{text}"
    );
    assert!(!text.contains("weight"), "{text}");
}
