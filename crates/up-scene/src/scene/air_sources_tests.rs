//! `[[fans]]`, `[[vents]]` and `[[draughts]]`: read from TOML and JSON, the
//! kinds' defaults, and every range error with its key path and line.

use super::test_support::{json_err, toml_err};
use super::*;
use crate::error::SceneError;

/// The scene format's example of every key.
const FULL: &str = "\
[room]
width = 8.0
depth = 6.0
wall_height = 3.0
ceiling = \"flat\"

[[fans]]
position = [0.0, 0.3, -2.5]
direction = [0.0, 0.2, 1.0]
diameter_m = 0.4
speed_m_s = 3.0
sweep_deg = 90
sweep_period_s = 12
on = [[0.0, 1e9]]

[[vents]]
position = [1.0, 3.0, 0.0]

[[draughts]]
min = [-0.5, 0.0, 2.9]
max = [0.5, 2.0, 3.0]
velocity_m_s = [0.0, 0.0, -0.8]
on = [[5.0, 15.0]]
";

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test.toml").unwrap_or_else(|e| panic!("{e}"))
}

/// A flat 6 m × 6 m × 3 m room with `rest` after it.
fn in_room(rest: &str) -> String {
    format!("[room]\nceiling = \"flat\"\n{rest}")
}

#[test]
fn fans_vents_and_draughts_are_read_as_written() {
    let s = scene(FULL);
    assert!(s.has_moving_air());
    let fan = &s.fans[0];
    assert_eq!(fan.position, [0.0, 0.3, -2.5]);
    assert_eq!(fan.direction, Some([0.0, 0.2, 1.0]));
    assert_eq!((fan.diameter_m, fan.speed_m_s), (Some(0.4), Some(3.0)));
    assert_eq!((fan.sweep_deg, fan.sweep_period_s), (90.0, 12.0));
    assert_eq!(fan.on, vec![[0.0, 1e9]]);
    let door = &s.draughts[0];
    assert_eq!((door.min, door.max), ([-0.5, 0.0, 2.9], [0.5, 2.0, 3.0]));
    assert_eq!(door.velocity_m_s, [0.0, 0.0, -0.8]);
    assert_eq!(door.on, vec![[5.0, 15.0]]);
    let jets: Vec<(String, JetSource)> = s.jets().map(|(at, kind, _)| (at, kind)).collect();
    assert_eq!(
        jets,
        [
            ("fans[0]".to_string(), JetSource::Fan),
            ("vents[0]".to_string(), JetSource::Vent)
        ]
    );
}

#[test]
fn a_fan_and_a_vent_take_their_kinds_defaults() {
    let s = scene(&in_room(
        "[[fans]]\nposition = [0, 0.5, 0]\n[[vents]]\nposition = [0, 3, 0]\n",
    ));
    let fan = s.fans[0].resolved(JetSource::Fan);
    assert_eq!(fan.direction, [0.0, 0.0, 1.0]);
    assert_eq!((fan.diameter_m, fan.speed_m_s), (0.4, 3.0));
    let vent = s.vents[0].resolved(JetSource::Vent);
    assert_eq!(vent.direction, [0.0, -1.0, 0.0]);
    assert_eq!((vent.diameter_m, vent.speed_m_s), (0.25, 2.0));
    for jet in [&s.fans[0], &s.vents[0]] {
        assert_eq!(jet.sweep_deg, 0.0);
        assert_eq!(jet.sweep_period_s, DEFAULT_SWEEP_PERIOD_S);
        assert!(jet.on.is_empty());
    }
    // What a file gives wins over the kind's default.
    let s = scene(&in_room(
        "[[vents]]\nposition = [0, 3, 0]\ndiameter_m = 0.5\n",
    ));
    assert_eq!(s.vents[0].resolved(JetSource::Vent).diameter_m, 0.5);
    // A scene without sources has still air, and writes no source out.
    let still = scene("[room]\nwidth = 5\n");
    assert!(!still.has_moving_air());
    let text = still.to_toml_string().unwrap();
    assert!(
        !text.contains("fans") && !text.contains("draughts"),
        "{text}"
    );
}

#[test]
fn the_same_sources_read_from_json_and_written_back() {
    let json = r#"{
  "room": { "width": 8.0, "depth": 6.0, "wall_height": 3.0, "ceiling": "flat" },
  "fans": [ { "position": [0.0, 0.3, -2.5], "direction": [0.0, 0.2, 1.0], "diameter_m": 0.4,
              "speed_m_s": 3.0, "sweep_deg": 90, "sweep_period_s": 12, "on": [[0.0, 1e9]] } ],
  "vents": [ { "position": [1.0, 3.0, 0.0] } ],
  "draughts": [ { "min": [-0.5, 0.0, 2.9], "max": [0.5, 2.0, 3.0],
                  "velocity_m_s": [0.0, 0.0, -0.8], "on": [[5.0, 15.0]] } ]
}"#;
    let from_json = Scene::from_json_str(json, "test.json").unwrap();
    let from_toml = scene(FULL);
    assert_eq!(from_json, from_toml);
    let back = Scene::from_toml_str(&from_toml.to_toml_string().unwrap(), "back.toml").unwrap();
    assert_eq!(back, from_toml);
    let back = Scene::from_json_str(&from_toml.to_json_string().unwrap(), "back.json").unwrap();
    assert_eq!(back, from_toml);
    // The page's scene JSON names the keys as files do.
    let written = from_toml.to_json_string().unwrap();
    for key in ["\"fans\"", "\"sweep_period_s\"", "\"velocity_m_s\""] {
        assert!(written.contains(key), "{key} in {written}");
    }
}

/// `toml_err(text)` names `key` on `line` and says what it expected.
fn assert_invalid(text: &str, key: &str, line: usize, expected: &str) {
    let e = toml_err(text);
    assert!(matches!(e, SceneError::Invalid { .. }), "{text}: {e}");
    assert_eq!(e.key(), Some(key), "{text}: {e}");
    assert_eq!(e.line(), Some(line), "{text}: {e}");
    let prefix = format!("test.toml:{line}: {key}: expected {expected}");
    assert!(e.to_string().starts_with(&prefix), "{e}\nnot {prefix}");
}

#[test]
fn every_range_names_its_key_path_line_and_range() {
    let fan = |key: &str| in_room(&format!("[[fans]]\nposition = [0, 0.5, 0]\n{key}\n"));
    // Line 5: the key after `[room]`, `ceiling`, `[[fans]]` and `position`.
    let cases = [
        (
            "diameter_m = 0.05",
            "diameter_m",
            "a finite number in (0.05, 3] m",
        ),
        (
            "diameter_m = 3.5",
            "diameter_m",
            "a finite number in (0.05, 3] m",
        ),
        (
            "diameter_m = nan",
            "diameter_m",
            "a finite number in (0.05, 3] m",
        ),
        (
            "speed_m_s = -1",
            "speed_m_s",
            "a finite number in [0, 30] m/s",
        ),
        (
            "speed_m_s = 31",
            "speed_m_s",
            "a finite number in [0, 30] m/s",
        ),
        (
            "sweep_deg = 190",
            "sweep_deg",
            "a finite number in [0, 180] °",
        ),
        (
            "sweep_deg = -5",
            "sweep_deg",
            "a finite number in [0, 180] °",
        ),
        (
            "sweep_period_s = 0",
            "sweep_period_s",
            "a finite number in (0, 600] s",
        ),
        (
            "sweep_period_s = 601",
            "sweep_period_s",
            "a finite number in (0, 600] s",
        ),
        (
            "direction = [0, 0, 0]",
            "direction",
            "a finite, non-zero [x, y, z]",
        ),
        (
            "direction = [0, inf, 1]",
            "direction",
            "a finite, non-zero [x, y, z]",
        ),
    ];
    for (line, key, expected) in cases {
        assert_invalid(&fan(line), &format!("fans[0].{key}"), 5, expected);
    }
    // Vents are checked alike, under their own key.
    let vent = in_room("[[vents]]\nposition = [0, 3, 0]\nspeed_m_s = 40\n");
    assert_invalid(
        &vent,
        "vents[0].speed_m_s",
        5,
        "a finite number in [0, 30] m/s",
    );
    // The second of two intervals, on its own line.
    let on = in_room("[[fans]]\nposition = [0, 0.5, 0]\non = [\n  [0, 5],\n  [9, 2],\n]\n");
    assert_invalid(
        &on,
        "fans[0].on[1]",
        7,
        "[start, end] in s, finite, with start ≤ end",
    );
}

#[test]
fn outlets_and_openings_outside_the_room_are_refused() {
    let outside = in_room("[[fans]]\nposition = [0, 0.5, 3.5]\n");
    assert_invalid(
        &outside,
        "fans[0].position",
        4,
        "a point [x, y, z] inside the room, from [-3.0, 0.0, -3.0] to [3.0, 3.0, 3.0] m",
    );
    let above = in_room("[[vents]]\nposition = [0, 3.2, 0]\n");
    assert_invalid(
        &above,
        "vents[0].position",
        4,
        "a point [x, y, z] inside the room",
    );
    // The pyramid's apex is the box's top.
    assert!(Scene::from_toml_str("[[vents]]\nposition = [0, 4.5, 0]\n", "apex.toml").is_ok());
    let door = in_room(
        "[[draughts]]\nmin = [-0.5, 0, 2.9]\nmax = [0.5, 2, 3.1]\nvelocity_m_s = [0, 0, -1]\n",
    );
    assert_invalid(
        &door,
        "draughts[0].max",
        5,
        "a point [x, y, z] inside the room",
    );
    let flat = in_room(
        "[[draughts]]\nmin = [-0.5, 0, 2.9]\nmax = [0.5, 2, 2.9]\nvelocity_m_s = [0, 0, -1]\n",
    );
    assert_invalid(&flat, "draughts[0].max", 5, "a corner above min");
    let gale = in_room(
        "[[draughts]]\nmin = [-0.5, 0, 2.9]\nmax = [0.5, 2, 3]\nvelocity_m_s = [0, 0, -31]\n",
    );
    assert_invalid(
        &gale,
        "draughts[0].velocity_m_s",
        6,
        "finite [x, y, z] no longer than 30 m/s",
    );
}

#[test]
fn missing_and_malformed_keys_are_parse_errors_with_their_place() {
    let cases = [
        // No position: serde names the table.
        (
            "[[fans]]\ndiameter_m = 0.3\n",
            "fans[0]",
            "missing field `position`",
        ),
        (
            "[[fans]]\nposition = [0, 1]\n",
            "fans[0].position",
            "expected [x, y, z], three numbers, found 2",
        ),
        (
            "[[fans]]\nposition = [0, 1, 0]\non = [[1, 2, 3]]\n",
            "fans[0].on",
            "interval 0: expected [start, end] in s, two numbers, found 3",
        ),
        (
            "[[fans]]\nposition = [0, 1, 0]\nspeed = 3\n",
            "fans[0].speed",
            "unknown field `speed`",
        ),
        (
            "[[draughts]]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n",
            "draughts[0]",
            "missing field `velocity_m_s`",
        ),
    ];
    for (text, key, message) in cases {
        let e = toml_err(text);
        assert!(matches!(e, SceneError::Parse { .. }), "{text}: {e}");
        assert_eq!(e.key(), Some(key), "{text}: {e}");
        assert!(e.line().is_some(), "{text}: {e}");
        assert!(e.to_string().contains(message), "{text}: {e}");
    }
    let e = json_err(r#"{"vents": [{"position": [0, 1, 0], "diameter_m": "wide"}]}"#);
    assert_eq!(e.key(), Some("vents[0].diameter_m"), "{e}");
}

#[test]
fn too_many_sources_or_intervals_are_refused() {
    let fans = "[[fans]]\nposition = [0, 0.5, 0]\n".repeat(MAX_AIR_SOURCES + 1);
    let e = toml_err(&fans);
    assert_eq!(e.key(), Some("fans[64]"), "{e}");
    assert_eq!(e.line(), Some(129), "{e}");
    assert!(
        e.to_string().contains("expected at most 64 fans, found 65"),
        "{e}"
    );
    let intervals = vec!["[0, 1]"; MAX_ON_INTERVALS + 1].join(", ");
    let e = toml_err(&format!(
        "[[vents]]\nposition = [0, 3, 0]\non = [{intervals}]\n"
    ));
    assert_eq!(e.key(), Some("vents[0].on"), "{e}");
    assert!(
        e.to_string().contains("at most 64 [start, end] intervals"),
        "{e}"
    );
}
