//! Reading scenes from TOML and JSON: defaults, round trips, and parse
//! errors that name the file, the key and the line.

use super::test_support::{json_err, toml_err};
use super::*;
use crate::error::SceneError;

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
