//! Parsing and validation of scene files: every error path names the file,
//! the key and (where known) the line.

use super::*;

fn toml_err(text: &str) -> SceneError {
    match Scene::from_toml_str(text, "test.toml") {
        Ok(scene) => panic!("expected an error, got {scene:?}"),
        Err(e) => e,
    }
}

fn json_err(text: &str) -> SceneError {
    match Scene::from_json_str(text, "test.json") {
        Ok(scene) => panic!("expected an error, got {scene:?}"),
        Err(e) => e,
    }
}

#[test]
fn empty_table_and_comment_are_the_default_scene() {
    let scene = Scene::from_toml_str("# the original\n", "comment.toml").unwrap();
    assert_eq!(scene, Scene::default());
    let scene = Scene::from_json_str("{}", "empty.json").unwrap();
    assert_eq!(scene, Scene::default());
}

#[test]
fn empty_and_whitespace_only_files_are_errors_that_say_so() {
    for text in ["", " ", "\n\n", " \t\r\n  \n"] {
        let e = toml_err(text);
        assert!(matches!(e, SceneError::Empty { .. }), "{text:?}: {e}");
        assert!(
            e.to_string().starts_with("test.toml: the scene is empty"),
            "{e}"
        );
        let e = json_err(text);
        assert!(matches!(e, SceneError::Empty { .. }), "{text:?}: {e}");
        assert!(
            e.to_string().starts_with("test.json: the scene is empty"),
            "{e}"
        );
    }
    // Read from a file, the message names the file.
    let dir = std::env::temp_dir().join(format!("up-scene-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["zero.toml", "zero.json", "blank.toml"] {
        let path = dir.join(name);
        let text = if name.starts_with("blank") {
            "  \n\t\n"
        } else {
            ""
        };
        std::fs::write(&path, text).unwrap();
        let e = Scene::from_path(&path).unwrap_err();
        assert_eq!(
            e.to_string().split(':').next(),
            Some(path.display().to_string().as_str()),
            "{e}"
        );
        assert!(e.to_string().contains("the scene is empty"), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_wrong_type_in_json_names_its_own_key_not_the_last_one_on_the_line() {
    let text = r#"{"room": {"width": [1,2], "depth": 6, "wall_height": 3, "ceiling": "flat"}}"#;
    let e = json_err(text);
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
    assert_eq!(e.key(), Some("room.width"), "{e}");
    assert_eq!(e.line(), Some(1));
    assert!(
        e.to_string()
            .starts_with("test.json:1: room.width: invalid type: sequence, expected f32"),
        "{e}"
    );
    // Spread over lines, the line is the value's.
    let text = "{\n \"sim\": {\"dt\": 0.01,\n  \"substeps\": 4},\n \"balloons\": [\n  {\"count\": 2},\n  {\"count\": 3, \"colors\": [\"red\",\n   7]}\n ]\n}";
    let e = json_err(text);
    assert_eq!(e.key(), Some("balloons[1].colors[1]"), "{e}");
    assert_eq!(e.line(), Some(7), "{e}");
}

#[test]
fn a_wrong_type_in_toml_names_its_key_and_line() {
    let text = "[room]\nwidth = [1, 2]\ndepth = 6\nwall_height = 3\nceiling = \"flat\"\n";
    let e = toml_err(text);
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
    assert_eq!(e.key(), Some("room.width"), "{e}");
    assert_eq!(e.line(), Some(2), "{e}");
    assert!(
        e.to_string()
            .starts_with("test.toml:2: room.width: invalid type: sequence, expected f32"),
        "{e}"
    );
    let text =
        "[[balloons]]\ncount = 1\n\n[[balloons]]\ncount = 2\ncolors = [\n  \"red\",\n  7,\n]\n";
    let e = toml_err(text);
    assert_eq!(e.key(), Some("balloons[1].colors[1]"), "{e}");
    assert_eq!(e.line(), Some(8), "{e}");
}

#[test]
fn default_scene_is_the_original_room_and_fifty_balloons() {
    let scene = Scene::default();
    assert_eq!(
        (scene.room.width, scene.room.depth, scene.room.wall_height),
        (6.0, 6.0, 3.0)
    );
    assert_eq!(scene.room.ceiling, CeilingKind::Pyramid);
    assert_eq!(scene.room.apex_height, 1.5);
    assert_eq!(scene.total_balloons(), 50);
    assert_eq!(
        scene.balloons[0].colors,
        DEFAULT_COLORS.map(String::from).to_vec()
    );
    assert!(scene.balloons[0].spawn.is_none(), "released from the floor");
    assert_eq!(scene.source.name, DEFAULT_SOURCE_NAME);
    scene.validate().unwrap();
}

#[test]
fn default_scene_round_trips_through_toml_and_json() {
    let scene = Scene::default();
    let toml_text = scene.to_toml_string().unwrap();
    assert_eq!(
        Scene::from_toml_str(&toml_text, "rt.toml").unwrap(),
        scene,
        "{toml_text}"
    );
    let json_text = scene.to_json_string().unwrap();
    assert_eq!(
        Scene::from_json_str(&json_text, "rt.json").unwrap(),
        scene,
        "{json_text}"
    );
}

#[test]
fn full_scene_parses_every_key() {
    let text = r##"
[room]
width = 8
depth = 7.5
wall_height = 4.0
ceiling = "flat"

[[balloons]]
count = 3
colors = ["red", "#00ff80"]
size_in = 16
gas = "air"
envelope_mass_g = 6.5
knot_mass_g = 1.0
spawn = { min = [-1.0, 0.5, -1.0], max = [1.0, 1.5, 1.0] }
velocity = [30.0, 0.0, 0.0]
angular_velocity = [0.0, 1.0, 0.0]
tilt_deg = 0
yaw_deg = 0
leaves = 7

[air]
temperature_c = 25.0
pressure_kpa = 95.0

[sim]
seed = 42
dt = 0.01
substeps = 8
duration_s = 2.5
gravity = [0.0, -9.81, 0.0]
friction = 0.3
restitution = 0.5
drag_coefficient = 0.5
added_mass_coefficient = 0.5
angular_damping = 1.0
contact_hertz = 60
contact_damping_ratio = 5
sleep = false
continuous = false
"##;
    let scene = Scene::from_toml_str(text, "full.toml").unwrap();
    assert_eq!(scene.room.ceiling, CeilingKind::Flat);
    let g = &scene.balloons[0];
    assert!((g.diameter() - 16.0 * METRES_PER_INCH).abs() < 1e-6);
    assert_eq!(g.gas, GasKind::Air);
    assert!((g.envelope_mass_kg() - 0.0065).abs() < 1e-9);
    assert_eq!(g.spawn.unwrap().max, [1.0, 1.5, 1.0]);
    assert_eq!(scene.sim.seed, 42);
    assert!(!scene.sim.sleep);
    assert!((scene.air.atmosphere().pressure_pa - 95_000.0).abs() < 1e-2);
    // The same scene written as JSON reads back identical.
    let json = scene.to_json_string().unwrap();
    assert_eq!(Scene::from_json_str(&json, "full.json").unwrap(), scene);
}

#[test]
fn unknown_key_is_rejected_with_file_key_and_line() {
    let e = toml_err("[room]\nwidth = 6.0\nwidht = 5.0\n");
    let text = e.to_string();
    assert!(text.starts_with("test.toml:3: room.widht: "), "{text}");
    assert!(text.contains("unknown field `widht`"), "{text}");
    assert_eq!(e.line(), Some(3));

    let e = toml_err("[[balloons]]\ncount = 2\ncolour = \"red\"\n");
    assert_eq!(e.key(), Some("balloons[0].colour"), "{e}");

    let e = toml_err("[lights]\nbrightness = 1\n");
    assert!(e.to_string().contains("unknown field `lights`"), "{e}");
    assert_eq!(e.line(), Some(1));
}

#[test]
fn unknown_key_in_json_names_key_and_line() {
    let e = json_err("{\n  \"sim\": {\n    \"dt\": 0.01,\n    \"stepz\": 3\n  }\n}");
    let text = e.to_string();
    assert!(
        text.starts_with("test.json:4: sim.stepz: unknown field `stepz`"),
        "{text}"
    );
}

#[test]
fn wrong_type_is_rejected_with_what_was_expected() {
    let e = toml_err("[[balloons]]\ncount = \"ten\"\n");
    let text = e.to_string();
    assert!(
        text.starts_with("test.toml:2: balloons[0].count: "),
        "{text}"
    );
    assert!(text.contains("invalid type: string \"ten\""), "{text}");
    assert!(text.contains("expected u64"), "{text}");

    let e = json_err("{\"room\": {\"width\": \"wide\"}}");
    assert!(
        e.to_string()
            .starts_with("test.json:1: room.width: invalid type"),
        "{e}"
    );

    let e = toml_err("[room]\nceiling = \"dome\"\n");
    assert!(
        e.to_string().contains("expected `pyramid` or `flat`"),
        "{e}"
    );
    assert_eq!(e.key(), Some("room.ceiling"));
}

#[test]
fn syntax_error_names_the_line() {
    let e = toml_err("[room]\nwidth = = 3\n");
    assert_eq!(e.line(), Some(2), "{e}");
    let e = json_err("{\n\"room\": {\"width\": 6,}\n}");
    assert_eq!(e.line(), Some(2), "{e}");
}

#[test]
fn nan_and_infinity_are_rejected() {
    let e = toml_err("[room]\nwidth = nan\n");
    let text = e.to_string();
    assert!(
        text.starts_with("test.toml:2: room.width: expected a finite number in [0.5, 1000] m"),
        "{text}"
    );
    assert!(text.ends_with("found NaN"), "{text}");

    let e = toml_err("[sim]\ndt = inf\n");
    assert!(
        e.to_string()
            .contains("sim.dt: expected a finite number in (0, 0.1] s, found inf"),
        "{e}"
    );

    let e = toml_err("[[balloons]]\nvelocity = [0.0, -inf, 0.0]\n");
    assert_eq!(e.key(), Some("balloons[0].velocity"), "{e}");
    assert_eq!(e.line(), Some(2));
}

#[test]
fn negative_and_zero_sizes_are_rejected() {
    let e = toml_err("[room]\ndepth = -6.0\n");
    assert_eq!(e.key(), Some("room.depth"), "{e}");
    let e = toml_err("[[balloons]]\ndiameter_m = 0.0\n");
    assert_eq!(e.key(), Some("balloons[0].diameter_m"), "{e}");
    let e = json_err("{\"balloons\": [{\"count\": -3}]}");
    assert!(
        e.to_string()
            .contains("balloons[0].count: invalid value: integer `-3`"),
        "{e}"
    );
}

#[test]
fn a_billion_balloons_are_rejected() {
    let e = toml_err("[[balloons]]\ncount = 1000000000\n");
    let text = e.to_string();
    assert!(
        text.starts_with("test.toml:2: balloons[0].count: expected at most 200000"),
        "{text}"
    );
    // The limit is over all groups.
    let e = toml_err("[[balloons]]\ncount = 150000\n[[balloons]]\ncount = 60000\n");
    assert_eq!(e.key(), Some("balloons[1].count"));
    assert_eq!(e.line(), Some(4));
}

#[test]
fn balloon_bigger_than_the_room_is_rejected() {
    let e = toml_err("[room]\nwall_height = 1.0\n[[balloons]]\ndiameter_m = 1.5\n");
    let text = e.to_string();
    assert!(
        text.starts_with("test.toml:4: balloons[0].diameter_m: expected a balloon smaller"),
        "{text}"
    );
}

#[test]
fn spawn_region_outside_the_room_is_rejected() {
    let e = toml_err("[[balloons]]\nspawn = { min = [2.0, 0.0, -1.0], max = [4.0, 1.0, 1.0] }\n");
    let text = e.to_string();
    assert!(
        text.starts_with("test.toml:2: balloons[0].spawn: expected a region inside the room"),
        "{text}"
    );

    let e =
        toml_err("[[balloons]]\n[balloons.spawn]\nmin = [1.0, 0.0, 0.0]\nmax = [0.0, 1.0, 1.0]\n");
    assert_eq!(e.key(), Some("balloons[0].spawn.max"), "{e}");
    assert_eq!(e.line(), Some(4));

    let e = toml_err("[[balloons]]\nspawn = { min = [0.0, 0.0, 0.0], max = [0.1, 1.0, 1.0] }\n");
    assert!(e.to_string().contains("at least one balloon"), "{e}");
}

#[test]
fn other_ranges_are_checked() {
    let cases = [
        ("[sim]\ndt = 0.5\n", "sim.dt"),
        ("[sim]\nsubsteps = 0\n", "sim.substeps"),
        ("[sim]\nsubsteps = 65\n", "sim.substeps"),
        ("[sim]\nrestitution = 1.5\n", "sim.restitution"),
        ("[sim]\nseed = 9007199254740992\n", "sim.seed"),
        ("[air]\ntemperature_c = -300\n", "air.temperature_c"),
        (
            "[room]\nceiling = \"pyramid\"\napex_height = 0\n",
            "room.apex_height",
        ),
        ("[[balloons]]\ncolors = []\n", "balloons[0].colors"),
        (
            "[[balloons]]\ncolors = [\"red\", \"plaid\"]\n",
            "balloons[0].colors[1]",
        ),
        (
            "[[balloons]]\ndiameter_m = 0.3\nsize_in = 11\n",
            "balloons[0].size_in",
        ),
        ("[[balloons]]\ntilt_deg = 100\n", "balloons[0].tilt_deg"),
        ("[[balloons]]\nleaves = 0\n", "balloons[0].leaves"),
        ("[[balloons]]\nleaves = 33\n", "balloons[0].leaves"),
        (
            "[[balloons]]\nvelocity = [400.0, 0.0, 0.0]\n",
            "balloons[0].velocity",
        ),
        ("[room]\nmesh = \"\"\n", "room.mesh"),
    ];
    for (text, key) in cases {
        let e = toml_err(text);
        assert_eq!(e.key(), Some(key), "{text}: {e}");
        assert!(e.to_string().contains("expected"), "{e}");
    }
}

#[test]
fn flat_ceiling_ignores_apex_height() {
    let scene = Scene::from_toml_str("[room]\nceiling = \"flat\"\napex_height = 0\n", "f.toml");
    assert!(scene.is_ok(), "{scene:?}");
}

#[test]
fn missing_file_names_the_path() {
    let e = Scene::from_path("/no/such/dir/scene.toml").unwrap_err();
    let text = e.to_string();
    assert!(
        text.starts_with("/no/such/dir/scene.toml: cannot read the scene file"),
        "{text}"
    );
    let e = Scene::from_path("scene.yaml").unwrap_err();
    assert!(
        e.to_string()
            .contains("expected a `.toml` or `.json` extension"),
        "{e}"
    );
}

#[test]
fn files_are_read_by_extension_and_mesh_paths_resolve_against_them() {
    let dir = std::env::temp_dir().join(format!("up-scene-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let toml_path = dir.join("a.toml");
    std::fs::write(&toml_path, "[room]\nmesh = \"hall.obj\"\n").unwrap();
    let scene = Scene::from_path(&toml_path).unwrap();
    assert_eq!(scene.room_mesh_path(), Some(dir.join("hall.obj")));
    assert_eq!(scene.source.name, toml_path.display().to_string());

    let json_path = dir.join("b.JSON");
    std::fs::write(&json_path, "{\"sim\": {\"dt\": 0.2}}").unwrap();
    let e = Scene::from_path(&json_path).unwrap_err();
    assert!(
        e.to_string()
            .starts_with(&format!("{}:1: sim.dt: expected", json_path.display())),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn total_balloons_are_spread_over_groups() {
    let scene = Scene::from_toml_str(
        "[[balloons]]\ncount = 1\n[[balloons]]\ncount = 1\n[[balloons]]\ncount = 1\n",
        "g.toml",
    )
    .unwrap();
    let scene = scene.with_total_balloons(10).unwrap();
    let counts: Vec<u64> = scene.balloons.iter().map(|g| g.count).collect();
    assert_eq!(counts, vec![4, 3, 3]);
    let e = scene.with_total_balloons(1_000_000).unwrap_err();
    assert_eq!(e.key(), Some("balloons[0].count"));
    let none = Scene {
        balloons: vec![],
        ..Scene::default()
    };
    assert_eq!(none.with_total_balloons(2).unwrap().total_balloons(), 2);
}

#[test]
fn hex_colours_parse() {
    assert_eq!(parse_color("#ff0000"), Some([1.0, 0.0, 0.0]));
    assert_eq!(parse_color("#ff00"), None);
    assert_eq!(parse_color("#gg0000"), None);
}

fn asset(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes")
        .join(name)
}

#[test]
fn example_scenes_parse_and_validate() {
    let names = [
        "default.toml",
        "bouquet.toml",
        "terminal-velocity.toml",
        "party-hall.toml",
        "thrown.toml",
        "two-gases.json",
        "evening.toml",
    ];
    for name in names {
        let scene = Scene::from_path(asset(name)).unwrap_or_else(|e| panic!("{e}"));
        scene.validate().unwrap();
    }
    let party = Scene::from_path(asset("party-hall.toml")).unwrap();
    assert_eq!(party.total_balloons(), 1000);
    let thrown = Scene::from_path(asset("thrown.toml")).unwrap();
    assert_eq!(thrown.balloons[0].velocity, [30.0, 0.0, 0.0]);
}

#[test]
fn default_scene_file_is_the_default_scene() {
    assert_eq!(
        Scene::from_path(asset("default.toml")).unwrap(),
        Scene::default()
    );
}

#[test]
fn documented_full_example_parses_the_same_in_toml_and_json() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let example = &doc[doc.find("## A full example").unwrap()..];
    let block = |lang: &str| {
        let start = example.find(&format!("```{lang}\n")).unwrap() + lang.len() + 4;
        let len = example[start..].find("```").unwrap();
        example[start..start + len].to_string()
    };
    let from_toml = Scene::from_toml_str(&block("toml"), "doc.toml").unwrap();
    let from_json = Scene::from_json_str(&block("json"), "doc.json").unwrap();
    assert_eq!(from_toml, from_json);
    assert_eq!(from_toml.total_balloons(), 41);
    assert_eq!(
        from_toml.balloons[0].tied_ribbon(),
        Some(&RibbonSpec::default())
    );
}

#[test]
fn json_gets_the_same_checks_as_toml() {
    // JSON has no NaN literal; a number beyond f32 becomes infinite and is caught.
    let e = json_err("{\"room\": {\"width\": 1e39}}");
    assert!(
        e.to_string().starts_with(
            "test.json:1: room.width: expected a finite number in [0.5, 1000] m, found inf"
        ),
        "{e}"
    );
    let e = json_err("{\"sim\": {\"dt\": NaN}}");
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
    let e = json_err("{\n\"balloons\": [\n{\"count\": 1000000000}\n]\n}");
    assert!(
        e.to_string()
            .starts_with("test.json:3: balloons[0].count: expected at most 200000"),
        "{e}"
    );
    let e = json_err("{\"balloons\": [{\"diameter_m\": -0.3}]}");
    assert_eq!(e.key(), Some("balloons[0].diameter_m"), "{e}");
    let e = json_err("{\"room\": {\"wall_height\": 1}, \"balloons\": [{\"diameter_m\": 2}]}");
    assert!(e.to_string().contains("smaller than the room"), "{e}");
    let e = json_err("{\"balloons\": [{\"spawn\": {\"min\": [-1, 0, -1], \"max\": [1, 9, 1]}}]}");
    assert!(e.to_string().contains("a region inside the room"), "{e}");
    let e = json_err("{\"balloons\": [{\"spawn\": {\"min\": [0, 0, 0]}}]}");
    assert!(e.to_string().contains("missing field `max`"), "{e}");
    let e = json_err("{\"balloons\": {\"count\": 3}}");
    assert!(
        e.to_string()
            .contains("invalid type: map, expected a sequence"),
        "{e}"
    );
    let e = json_err("{\"sim\": {\"sleep\": \"yes\"}}");
    assert_eq!(e.key(), Some("sim.sleep"), "{e}");
    // serde reads a struct from an array field by field: the first is the room.
    let e = json_err("[1, 2]");
    assert!(
        e.to_string()
            .starts_with("test.json:1: [0]: invalid type: integer `1`, expected struct RoomSpec"),
        "{e}"
    );
    let e = json_err("{\"sim\": {}} {}");
    assert!(e.to_string().contains("trailing characters"), "{e}");
}

#[test]
fn wrong_types_in_toml_name_the_key() {
    let cases = [
        ("[sim]\nsleep = 1\n", "sim.sleep"),
        ("[sim]\ngravity = [0.0, -9.81]\n", "sim.gravity"),
        ("[sim]\nseed = -1\n", "sim.seed"),
        ("[sim]\nsubsteps = 2.5\n", "sim.substeps"),
        ("[room]\nmesh = 3\n", "room.mesh"),
        ("[[balloons]]\ngas = \"hydrogen\"\n", "balloons[0].gas"),
        ("[[balloons]]\ncolors = \"red\"\n", "balloons[0].colors"),
    ];
    for (text, key) in cases {
        let e = toml_err(text);
        assert!(matches!(e, SceneError::Parse { .. }), "{text}: {e}");
        assert_eq!(e.key(), Some(key), "{text}: {e}");
        assert_eq!(e.line(), Some(2), "{text}: {e}");
    }
    // A value too large for the integer type is a parse error, not a wrap.
    let e = toml_err("[[balloons]]\ncount = 99999999999999999999\n");
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
}

#[test]
fn every_absurd_count_names_its_key_and_limit() {
    let mut text = String::new();
    for _ in 0..=MAX_BALLOON_GROUPS {
        text.push_str("[[balloons]]\ncount = 1\n");
    }
    let e = toml_err(&text);
    assert_eq!(e.key(), Some("balloons[64]"), "{e}");
    assert_eq!(e.line(), Some(129), "{e}");
    assert!(e
        .to_string()
        .contains("expected at most 64 balloon groups, found 65 groups"));

    let colors = vec!["\"red\""; MAX_GROUP_COLORS + 1].join(", ");
    let e = toml_err(&format!("[[balloons]]\ncolors = [{colors}]\n"));
    assert_eq!(e.key(), Some("balloons[0].colors"), "{e}");
    assert!(
        e.to_string().contains("expected 1 to 64 colours, found 65"),
        "{e}"
    );

    let e = toml_err("[[balloons]]\ncount = 18446744073709551615\n");
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
    // The limit over all groups stays within what the engine holds.
    assert!(MAX_TOTAL_BALLOONS <= up_physics::MAX_BODIES as u64);
    let e = toml_err("[[balloons]]\ncount = 200001\n");
    assert!(
        e.to_string().contains("expected at most 200000 balloons"),
        "{e}"
    );
    assert!(Scene::from_toml_str("[[balloons]]\ncount = 200000\n", "max.toml").is_ok());
}

#[test]
fn oversized_scene_files_are_refused_before_parsing() {
    let dir = std::env::temp_dir().join(format!("up-scene-big-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let big = dir.join("big.toml");
    let mut text = "# padding\n".repeat((MAX_SCENE_BYTES / 10) as usize + 1);
    text.push_str("[room]\nwidth = 6\n");
    std::fs::write(&big, &text).unwrap();
    let e = Scene::from_path(&big).unwrap_err();
    assert!(matches!(e, SceneError::TooLarge { .. }), "{e}");
    assert_eq!(
        e.to_string(),
        format!(
            "{}: too large: expected a scene file of at most 1048576 bytes",
            big.display()
        )
    );
    // A device that never ends stops at the cap too.
    let endless = dir.join("endless.toml");
    let _ = std::fs::remove_file(&endless);
    std::os::unix::fs::symlink("/dev/zero", &endless).unwrap();
    assert!(matches!(
        Scene::from_path(&endless),
        Err(SceneError::TooLarge { .. })
    ));
    let binary = dir.join("binary.json");
    std::fs::write(&binary, [0x7b, 0xff, 0xfe, 0x7d]).unwrap();
    let e = Scene::from_path(&binary).unwrap_err();
    assert!(e.to_string().contains("not UTF-8 text"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn ribbon_table_defaults_and_the_default_scene_ribbon() {
    let scene = Scene::from_toml_str("[[balloons]]\n[balloons.ribbon]\n", "r.toml").unwrap();
    let ribbon = scene.balloons[0].ribbon.as_ref().unwrap();
    assert_eq!(*ribbon, RibbonSpec::default());
    assert_eq!(ribbon.length_m, 1.5);
    assert_eq!(ribbon.segments, 16);
    assert_eq!(ribbon.color, "white");
    assert_eq!(ribbon.weight_g, 0.0);
    // The default mass per metre is the engine's.
    let engine = up_physics::ribbon::DEFAULT_MASS_PER_LENGTH * 1e3;
    assert!((ribbon.mass_per_m_g - engine).abs() < 1e-6);
    // No table, or length 0: no ribbon.
    let scene = Scene::from_toml_str("[[balloons]]\ncount = 2\n", "r.toml").unwrap();
    assert!(scene.balloons[0].tied_ribbon().is_none());
    let text = "[[balloons]]\n[balloons.ribbon]\nlength_m = 0\n";
    let scene = Scene::from_toml_str(text, "r.toml").unwrap();
    assert!(scene.balloons[0].ribbon.is_some());
    assert!(scene.balloons[0].tied_ribbon().is_none());
    // The original room has one, and keeps it through --balloons.
    let scene = Scene::default().with_total_balloons(7).unwrap();
    assert_eq!(
        scene.balloons[0].tied_ribbon(),
        Some(&RibbonSpec::default())
    );
}

#[test]
fn ribbon_tables_round_trip_through_toml_and_json() {
    let text = "[[balloons]]\ncount = 2\n[balloons.ribbon]\nlength_m = 2.5\nmass_per_m_g = 10\n\
                segments = 32\ncolor = \"#ff00aa\"\nweight_g = 15\n";
    let scene = Scene::from_toml_str(text, "r.toml").unwrap();
    let back = Scene::from_toml_str(&scene.to_toml_string().unwrap(), "rt.toml").unwrap();
    assert_eq!(back, scene);
    let json = scene.to_json_string().unwrap();
    assert!(json.contains("\"weight_g\": 15.0"), "{json}");
    assert_eq!(Scene::from_json_str(&json, "rt.json").unwrap(), scene);
}

#[test]
fn bad_ribbon_values_name_their_key_line_and_range() {
    let cases = [
        ("length_m = -1", "length_m", "(0, 20] m, or 0 for no ribbon"),
        (
            "length_m = 20.5",
            "length_m",
            "(0, 20] m, or 0 for no ribbon",
        ),
        ("length_m = nan", "length_m", "(0, 20] m"),
        ("mass_per_m_g = 0", "mass_per_m_g", "(0, 1000] g/m"),
        ("mass_per_m_g = 1001", "mass_per_m_g", "(0, 1000] g/m"),
        ("segments = 1", "segments", "an integer in [2, 128]"),
        ("segments = 129", "segments", "an integer in [2, 128]"),
        ("color = \"tartan\"", "color", "a colour name (red,"),
        ("color = \"#12345\"", "color", "\"#rrggbb\""),
        ("weight_g = -0.1", "weight_g", "[0, 1000] g"),
        ("weight_g = inf", "weight_g", "[0, 1000] g"),
    ];
    for (line, key, expected) in cases {
        let text = format!("[[balloons]]\ncount = 1\n\n[[balloons]]\n[balloons.ribbon]\n{line}\n");
        let e = toml_err(&text);
        assert!(matches!(e, SceneError::Invalid { .. }), "{line}: {e}");
        let path = format!("balloons[1].ribbon.{key}");
        assert_eq!(e.key(), Some(path.as_str()), "{line}: {e}");
        assert_eq!(e.line(), Some(6), "{line}: {e}");
        assert!(
            e.to_string()
                .starts_with(&format!("test.toml:6: {path}: expected ")),
            "{e}"
        );
        assert!(e.to_string().contains(expected), "{line}: {e}");
    }
    // Unknown keys and wrong types are refused, in TOML and JSON alike.
    let e = toml_err("[[balloons]]\n[balloons.ribbon]\nlenght_m = 1\n");
    assert_eq!(e.key(), Some("balloons[0].ribbon.lenght_m"), "{e}");
    assert!(e.to_string().contains("unknown field `lenght_m`"), "{e}");
    let e = json_err("{\"balloons\": [{\"ribbon\": {\"segments\": 2.5}}]}");
    assert_eq!(e.key(), Some("balloons[0].ribbon.segments"), "{e}");
    let e = json_err("{\"balloons\": [{\"ribbon\": {\"weight_g\": 1e39}}]}");
    assert_eq!(e.key(), Some("balloons[0].ribbon.weight_g"), "{e}");
    assert!(e.to_string().contains("found inf"), "{e}");
}

#[test]
fn documented_ribbon_table_is_the_default_ribbon() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let section = &doc[doc.find("### `[balloons.ribbon]`").unwrap()..];
    let start = section.find("```toml\n").unwrap() + 8;
    let len = section[start..].find("```").unwrap();
    let scene = Scene::from_toml_str(&section[start..start + len], "doc.toml").unwrap();
    assert_eq!(scene.balloons[0].count, 50);
    assert_eq!(scene.balloons[0].ribbon, Some(RibbonSpec::default()));
}

#[test]
fn gas_keys_parse_default_and_round_trip() {
    let plain = Scene::from_toml_str("[[balloons]]\n", "d.toml").unwrap();
    let g = &plain.balloons[0];
    assert_eq!(
        (g.kind, g.treatment, g.filled_hours_before),
        (BalloonKind::Latex, Treatment::Untreated, 0.0)
    );
    assert!(plain.air.temperature_schedule.is_empty());
    assert!(plain.air.temperature_schedule().points.is_empty());

    let text =
        "[[balloons]]\nkind = \"latex\"\ntreatment = \"hi-float\"\nfilled_hours_before = 6.5\n\n\
                [[balloons]]\nkind = \"foil\"\nfilled_hours_before = 2000\n\n\
                [air]\ntemperature_schedule = [[0.0, 12.0], [2.0, 22.0], [30, -5]]\n";
    let scene = Scene::from_toml_str(text, "g.toml").unwrap();
    let (latex, foil) = (&scene.balloons[0], &scene.balloons[1]);
    assert_eq!(latex.treatment, Treatment::HiFloat);
    assert_eq!(latex.filled_hours_before, 6.5);
    assert_eq!(
        (foil.kind, foil.treatment),
        (BalloonKind::Foil, Treatment::Untreated)
    );
    // A foil balloon is 18″ unless sized, its envelope 9 g and valve 1 g.
    assert!((foil.diameter() - 0.4572).abs() < 1e-6);
    assert!((foil.envelope_mass_kg() - 0.009).abs() < 1e-9);
    assert!((foil.knot_mass_kg() - 0.001).abs() < 1e-9);
    // The schedule sets the start: temperature_c follows its first point.
    assert_eq!(scene.air.temperature_c, 12.0);
    assert_eq!(scene.air.atmosphere().temperature_k, 12.0 + 273.15);
    let engine = scene.air.temperature_schedule();
    assert_eq!(
        engine.points,
        vec![(0.0, 285.15), (7200.0, 295.15), (108_000.0, 268.15)]
    );
    assert_eq!(engine.problem(), None);

    let toml = scene.to_toml_string().unwrap();
    assert!(toml.contains("treatment = \"hi-float\""), "{toml}");
    assert!(toml.contains("kind = \"foil\""), "{toml}");
    assert_eq!(Scene::from_toml_str(&toml, "rt.toml").unwrap(), scene);
    let json = scene.to_json_string().unwrap();
    assert!(json.contains("\"temperature_schedule\""), "{json}");
    assert_eq!(Scene::from_json_str(&json, "rt.json").unwrap(), scene);

    // temperature_c given and equal to the first point is accepted; a scene
    // built in code with another temperature_c writes the schedule's.
    let same = "[air]\ntemperature_c = 12\ntemperature_schedule = [[0, 12], [1, 20]]\n";
    assert_eq!(
        Scene::from_toml_str(same, "s.toml")
            .unwrap()
            .air
            .temperature_c,
        12.0
    );
    let mut coded = Scene::default();
    coded.air.temperature_schedule = vec![[0.5, 15.0], [1.0, 25.0]];
    let back = Scene::from_toml_str(&coded.to_toml_string().unwrap(), "c.toml").unwrap();
    assert_eq!(back.air.temperature_c, 15.0);
    assert_eq!(
        back.air.temperature_schedule,
        coded.air.temperature_schedule
    );
}

#[test]
fn bad_gas_keys_name_their_key_and_range() {
    let cases = [
        (
            "[[balloons]]\nfilled_hours_before = -1\n",
            "balloons[0].filled_hours_before",
            "[0, 2000] h",
            2,
        ),
        (
            "[[balloons]]\nfilled_hours_before = 2000.5\n",
            "balloons[0].filled_hours_before",
            "[0, 2000] h",
            2,
        ),
        (
            "[[balloons]]\nfilled_hours_before = nan\n",
            "balloons[0].filled_hours_before",
            "[0, 2000] h",
            2,
        ),
        (
            "[[balloons]]\nkind = \"foil\"\ntreatment = \"hi-float\"\n",
            "balloons[0].treatment",
            "\"none\" for a foil balloon",
            3,
        ),
        (
            "[air]\ntemperature_schedule = [[0, 12], [2, 22], [1, 20]]\n",
            "air.temperature_schedule[2][0]",
            "hours after the previous point's 2",
            2,
        ),
        (
            "[air]\ntemperature_schedule = [[0, 12], [0, 22]]\n",
            "air.temperature_schedule[1][0]",
            "hours after the previous point's 0",
            2,
        ),
        (
            "[air]\ntemperature_schedule = [[-1, 12]]\n",
            "air.temperature_schedule[0][0]",
            "[0, 2000] h",
            2,
        ),
        (
            "[air]\ntemperature_schedule = [[0, 12], [2, 61]]\n",
            "air.temperature_schedule[1][1]",
            "[-60, 60] °C",
            2,
        ),
        (
            "[air]\ntemperature_schedule = [[0, -70]]\n",
            "air.temperature_schedule[0][1]",
            "[-60, 60] °C",
            2,
        ),
        (
            "[air]\ntemperature_c = 20\ntemperature_schedule = [[0, 12], [2, 22]]\n",
            "air.temperature_c",
            "the schedule's first temperature (12 °C)",
            2,
        ),
    ];
    for (text, key, expected, line) in cases {
        let e = toml_err(text);
        assert!(matches!(e, SceneError::Invalid { .. }), "{text}: {e}");
        assert_eq!(e.key(), Some(key), "{text}: {e}");
        assert_eq!(e.line(), Some(line), "{text}: {e}");
        assert!(
            e.to_string()
                .starts_with(&format!("test.toml:{line}: {key}: expected ")),
            "{e}"
        );
        assert!(e.to_string().contains(expected), "{text}: {e}");
    }
    // Unknown names and malformed pairs are parse errors naming the key.
    let e = toml_err("[[balloons]]\nkind = \"rubber\"\n");
    assert_eq!(e.key(), Some("balloons[0].kind"), "{e}");
    assert!(e.to_string().contains("unknown variant `rubber`"), "{e}");
    let e = toml_err("[[balloons]]\ntreatment = \"gel\"\n");
    assert_eq!(e.key(), Some("balloons[0].treatment"), "{e}");
    let e = json_err("{\"balloons\": [{\"kind\": \"mylar\"}]}");
    assert_eq!(e.key(), Some("balloons[0].kind"), "{e}");
    let e = toml_err("[air]\ntemperature_schedule = [[0, 12, 3]]\n");
    assert_eq!(e.key(), Some("air.temperature_schedule"), "{e}");
    assert!(
        e.to_string().contains("point 0: expected [hours, °C]"),
        "{e}"
    );
    let e = json_err("{\"air\": {\"temperature_schedule\": [[1]]}}");
    assert_eq!(e.key(), Some("air.temperature_schedule"), "{e}");
    let e = json_err("{\"air\": {\"temperature_schedule\": [[0, 1e39]]}}");
    assert_eq!(e.key(), Some("air.temperature_schedule[0][1]"), "{e}");
    assert!(e.to_string().contains("found inf"), "{e}");
}

#[test]
fn finish_defaults_to_the_kind_and_round_trips() {
    let scene = Scene::from_toml_str(
        "[[balloons]]\n\n[[balloons]]\nkind = \"foil\"\n\n\
         [[balloons]]\nfinish = \"pearl\"\n\n[[balloons]]\nfinish = \"foil\"\n\n\
         [[balloons]]\nkind = \"foil\"\nfinish = \"foil\"\n\n[[balloons]]\nfinish = \"latex\"\n",
        "f.toml",
    )
    .unwrap();
    let finishes: Vec<Finish> = scene.balloons.iter().map(|g| g.finish()).collect();
    assert_eq!(
        finishes,
        [
            Finish::Latex,
            Finish::Foil,
            Finish::Pearl,
            Finish::Foil,
            Finish::Foil,
            Finish::Latex
        ]
    );
    // Left out, it stays out of the written scene; given, it is written back.
    assert_eq!(scene.balloons[0].finish, None);
    let toml = scene.to_toml_string().unwrap();
    assert_eq!(toml.matches("finish = ").count(), 4, "{toml}");
    assert_eq!(Scene::from_toml_str(&toml, "rt.toml").unwrap(), scene);
    let json = scene.to_json_string().unwrap();
    assert!(json.contains("\"finish\": \"pearl\""), "{json}");
    assert_eq!(Scene::from_json_str(&json, "rt.json").unwrap(), scene);
    let json_scene =
        Scene::from_json_str("{\"balloons\": [{\"finish\": \"pearl\"}]}", "f.json").unwrap();
    assert_eq!(json_scene.balloons[0].finish(), Finish::Pearl);
    assert_eq!(
        Finish::ALL.map(Finish::name),
        ["latex", "pearl", "foil"],
        "the names scene files use"
    );
}

#[test]
fn bad_finish_names_its_key_and_the_allowed_values() {
    let e = toml_err("[[balloons]]\ncount = 2\nfinish = \"glitter\"\n");
    assert!(matches!(e, SceneError::Parse { .. }), "{e}");
    assert_eq!(e.key(), Some("balloons[0].finish"), "{e}");
    assert_eq!(e.line(), Some(3), "{e}");
    let text = e.to_string();
    assert!(text.starts_with("test.toml:3: balloons[0].finish: "), "{e}");
    assert!(text.contains("unknown variant `glitter`"), "{e}");
    for name in ["latex", "pearl", "foil"] {
        assert!(text.contains(&format!("`{name}`")), "{name} in {e}");
    }
    let e = json_err("{\"balloons\": [{}, {\"finish\": 3}]}");
    assert_eq!(e.key(), Some("balloons[1].finish"), "{e}");

    // A foil balloon's film is metal: a latex finish on it is refused.
    for finish in ["latex", "pearl"] {
        let e = toml_err(&format!(
            "[[balloons]]\n\n[[balloons]]\nkind = \"foil\"\nfinish = \"{finish}\"\n"
        ));
        assert!(matches!(e, SceneError::Invalid { .. }), "{e}");
        assert_eq!(e.key(), Some("balloons[1].finish"), "{e}");
        assert_eq!(e.line(), Some(5), "{e}");
        assert!(
            e.to_string().starts_with(
                "test.toml:5: balloons[1].finish: expected \"foil\" for a foil balloon"
            ),
            "{e}"
        );
        assert!(e.to_string().contains(&format!("\"{finish}\"")), "{e}");
    }
}
