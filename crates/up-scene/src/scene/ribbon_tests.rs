//! The `[balloons.ribbon]` table: defaults, round trips, bad values.

use super::test_support::{json_err, toml_err};
use super::*;
use crate::error::SceneError;

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
fn an_anchor_round_trips_through_toml_and_json_and_is_left_out_when_absent() {
    let text =
        "[[balloons]]\ncount = 3\n[balloons.ribbon]\nlength_m = 1\nanchor = [0.5, 0.9, -1]\n";
    let scene = Scene::from_toml_str(text, "r.toml").unwrap();
    let ribbon = scene.balloons[0].tied_ribbon().unwrap();
    assert_eq!(ribbon.anchor, Some([0.5, 0.9, -1.0]));
    let toml = scene.to_toml_string().unwrap();
    assert_eq!(Scene::from_toml_str(&toml, "rt.toml").unwrap(), scene);
    let json = scene.to_json_string().unwrap();
    assert_eq!(Scene::from_json_str(&json, "rt.json").unwrap(), scene);
    // JSON may write it out as null: no anchor.
    let none = "{\"balloons\": [{\"ribbon\": {\"anchor\": null}}]}";
    let scene = Scene::from_json_str(none, "n.json").unwrap();
    assert_eq!(scene.balloons[0].ribbon.as_ref().unwrap().anchor, None);
    // Without one, the written scene does not mention it.
    let toml = Scene::default().to_toml_string().unwrap();
    assert!(!toml.contains("anchor"), "{toml}");
    assert_eq!(RibbonSpec::default().anchor, None);
}

#[test]
fn bad_anchors_name_their_key_line_and_range() {
    // The default room: 6 m × 6 m, walls 3 m, apex 4.5 m.
    let room = "from [-3.0, 0.0, -3.0] to [3.0, 4.5, 3.0] m";
    let cases = [
        ("anchor = [3.5, 1, 0]", room),
        ("anchor = [0, -0.1, 0]", room),
        ("anchor = [0, 4.6, 0]", room),
        ("anchor = [0, 1, -3.01]", room),
        ("anchor = [nan, 1, 0]", room),
        ("anchor = [0, inf, 0]", room),
        (
            "length_m = 0\nanchor = [0, 1, 0]",
            "no anchor on a group without a ribbon",
        ),
    ];
    for (lines, expected) in cases {
        let text = format!("[[balloons]]\ncount = 1\n\n[[balloons]]\n[balloons.ribbon]\n{lines}\n");
        let e = toml_err(&text);
        assert!(matches!(e, SceneError::Invalid { .. }), "{lines}: {e}");
        assert_eq!(e.key(), Some("balloons[1].ribbon.anchor"), "{lines}: {e}");
        let line = 5 + lines.lines().count();
        assert_eq!(e.line(), Some(line), "{lines}: {e}");
        assert!(e.to_string().contains(expected), "{lines}: {e}");
    }
    // A flat ceiling lowers the top of the room's box.
    let text =
        "[room]\nceiling = \"flat\"\n[[balloons]]\n[balloons.ribbon]\nanchor = [0, 3.2, 0]\n";
    let e = toml_err(text);
    assert!(e.to_string().contains("to [3.0, 3.0, 3.0] m"), "{e}");
    // Not three numbers, in TOML and JSON alike.
    for (points, found) in [("[1, 2]", 2), ("[1, 2, 3, 4]", 4), ("[]", 0)] {
        let e = toml_err(&format!(
            "[[balloons]]\n[balloons.ribbon]\nanchor = {points}\n"
        ));
        assert!(matches!(e, SceneError::Parse { .. }), "{points}: {e}");
        assert_eq!(e.key(), Some("balloons[0].ribbon.anchor"), "{points}: {e}");
        assert_eq!(e.line(), Some(3), "{points}: {e}");
        let message = format!("expected [x, y, z], three numbers, found {found}");
        assert!(e.to_string().contains(&message), "{e}");
        let json = format!("{{\"balloons\": [{{\"ribbon\": {{\"anchor\": {points}}}}}]}}");
        let e = json_err(&json);
        assert_eq!(e.key(), Some("balloons[0].ribbon.anchor"), "{points}: {e}");
        assert!(e.to_string().contains(&message), "{e}");
    }
    let e = json_err("{\"balloons\": [{\"ribbon\": {\"anchor\": \"chair\"}}]}");
    assert_eq!(e.key(), Some("balloons[0].ribbon.anchor"), "{e}");
}
