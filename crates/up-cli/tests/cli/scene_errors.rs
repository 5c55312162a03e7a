//! Bad scenes and inputs: exit 2, naming the file, the key, the line and the range.

use super::*;

#[test]
fn run_rejects_bad_scenes_with_file_key_and_line() {
    let dir = TempDir::new("bad");
    let missing = dir.str("missing.toml");
    let err = up_err(&["run", &missing]);
    assert!(
        err.contains(&missing) && err.contains("cannot read the scene file"),
        "{err}"
    );

    std::fs::write(dir.path("typo.toml"), "[room]\nwidth = 6\nwidht = 5\n").unwrap();
    let err = up_err(&["run", &dir.str("typo.toml")]);
    assert!(
        err.contains("typo.toml:3: room.widht: unknown field `widht`"),
        "{err}"
    );

    std::fs::write(dir.path("nan.toml"), "[sim]\ndt = nan\n").unwrap();
    let err = up_err(&["run", &dir.str("nan.toml")]);
    assert!(
        err.contains("nan.toml:2: sim.dt: expected a finite number"),
        "{err}"
    );

    std::fs::write(dir.path("scene.yaml"), "room: {}\n").unwrap();
    up_err(&["run", &dir.str("scene.yaml")]);

    let err = up_err(&["run", "--balloons", "1000000000"]);
    assert!(err.contains("balloons[0].count"), "{err}");
    let err = up_err(&["run", "--seconds=-1"]);
    assert!(err.contains("--seconds"), "{err}");
    let err = up_err(&["run", "--seconds", "0"]);
    assert!(err.contains("--seconds"), "{err}");
    up_err(&["run", "--seconds", "NaN"]);
}

#[test]
fn a_wrong_type_names_its_key_and_writes_no_output() {
    let dir = TempDir::new("wrong-type");
    let out = dir.str("out.csv");
    let state = dir.str("end.upsnap");
    std::fs::write(
        dir.path("room.json"),
        r#"{"room": {"width": [1,2], "depth": 6, "wall_height": 3, "ceiling": "flat"}}"#,
    )
    .unwrap();
    let err = up_err(&[
        "run",
        &dir.str("room.json"),
        "--out",
        &out,
        "--save-state",
        &state,
    ]);
    assert!(
        err.contains("room.json:1: room.width: invalid type: sequence, expected f32"),
        "{err}"
    );
    assert!(!err.contains("room.ceiling"), "{err}");

    std::fs::write(
        dir.path("room.toml"),
        "[room]\ndepth = 6\nwidth = [1, 2]\nceiling = \"flat\"\n",
    )
    .unwrap();
    let err = up_err(&["run", &dir.str("room.toml"), "--out", &out]);
    assert!(
        err.contains("room.toml:3: room.width: invalid type: sequence, expected f32"),
        "{err}"
    );
    assert_eq!(
        dir.files(),
        vec!["room.json", "room.toml"],
        "no output written"
    );
}

#[test]
fn empty_scene_files_are_refused_by_every_command() {
    let dir = TempDir::new("empty");
    std::fs::write(dir.path("zero.toml"), "").unwrap();
    std::fs::write(dir.path("zero.json"), "").unwrap();
    std::fs::write(dir.path("blank.toml"), " \n\t\n").unwrap();
    std::fs::write(dir.path("blank.json"), "\n   \n").unwrap();
    let out = dir.str("out.csv");
    let obj = dir.str("obj");
    for name in ["zero.toml", "zero.json", "blank.toml", "blank.json"] {
        let scene = dir.str(name);
        let expected = format!("{scene}: the scene is empty");
        let commands: [&[&str]; 5] = [
            &["run", &scene, "--out", &out, "--seconds", "0.1"],
            &["validate", &scene],
            &["bench", &scene, "--steps", "1"],
            &["soak", &scene, "--balloons", "2", "--seconds", "0.1"],
            &["export-obj", &obj, "--scene", &scene],
        ];
        for args in commands {
            let err = up_err(args);
            assert!(err.contains(&expected), "up {args:?}: {err}");
        }
    }
    assert_eq!(
        dir.files(),
        vec!["blank.json", "blank.toml", "zero.json", "zero.toml"],
        "no output written"
    );
}

/// Runs 3 balloons for 0.5 s, then again for 0.25 s saving the state in
/// `dir`; returns the whole run's output and the state file.

#[test]
fn validate_accepts_every_example_and_rejects_bad_files() {
    for name in [
        "default.toml",
        "terminal-velocity.toml",
        "party-hall.toml",
        "party-fans.toml",
        "learn-fan-hover.toml",
        "thrown.toml",
        "two-gases.json",
        "mixed-room.toml",
    ] {
        let text = up_ok(&["validate", &asset(name)]);
        assert!(text.contains("valid"), "{name}: {text}");
    }
    let dir = TempDir::new("validate");
    std::fs::write(
        dir.path("crowded.toml"),
        "[room]\nwidth = 1\ndepth = 1\nwall_height = 1\n[[balloons]]\ncount = 900\n",
    )
    .unwrap();
    let err = up_err(&["validate", &dir.str("crowded.toml")]);
    assert!(
        err.contains("balloons[0].count") && err.contains("do not fit"),
        "{err}"
    );
    std::fs::write(dir.path("bad.json"), "{\"sim\": {\"substeps\": 100}}").unwrap();
    let err = up_err(&["validate", &dir.str("bad.json")]);
    assert!(err.contains("bad.json:1: sim.substeps"), "{err}");
    up_err(&["validate", &dir.str("absent.toml")]);
    up_err(&["validate"]);
}

#[test]
fn bad_inputs_exit_2_naming_file_key_and_range() {
    let dir = TempDir::new("ranges");
    let cases = [
        (
            "count.toml",
            "[[balloons]]\ncount = 1000000000\n",
            "count.toml:2: balloons[0].count: expected at most 200000",
        ),
        (
            "big.json",
            "{\"balloons\": [{\"diameter_m\": 4.0}], \"room\": {\"wall_height\": 3}}",
            "big.json:1: balloons[0].diameter_m: expected a balloon smaller than the room",
        ),
        (
            "spawn.toml",
            "[[balloons]]\nspawn = { min = [-9, 0, -1], max = [1, 1, 1] }\n",
            "spawn.toml:2: balloons[0].spawn: expected a region inside the room",
        ),
        (
            "type.json",
            "{\"sim\": {\"dt\": \"fast\"}}",
            "type.json:1: sim.dt: invalid type: string \"fast\", expected f32",
        ),
        (
            "leaves.toml",
            "[[balloons]]\nleaves = 64\n",
            "leaves.toml:2: balloons[0].leaves: expected an integer in [1, 32], found 64",
        ),
        (
            "mesh.toml",
            "[room]\nmesh = \"absent.obj\"\n",
            "mesh.toml:2: room.mesh: cannot build the room",
        ),
    ];
    for (name, text, expected) in cases {
        std::fs::write(dir.path(name), text).unwrap();
        let path = dir.str(name);
        for command in ["run", "validate"] {
            let err = up_err(&[command, &path]);
            assert!(
                err.contains(&format!("{}{}", dir.0.display(), "/")),
                "{err}"
            );
            assert!(err.contains(expected), "{command} {name}: {err}");
        }
    }
    // An open room mesh is refused with the file and the edge.
    std::fs::write(dir.path("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.path("room.toml"), "[room]\nmesh = \"open.obj\"\n").unwrap();
    let err = up_err(&["validate", &dir.str("room.toml")]);
    assert!(
        err.contains("open.obj") && err.contains("not closed"),
        "{err}"
    );
    // A huge OBJ (a device that never ends) is refused by its size.
    let err = up_err(&["fit-spheres", "/dev/zero"]);
    assert!(err.contains("/dev/zero: too large"), "{err}");
}
