//! The gas keys (`treatment`, `filled_hours_before`, the air's temperature
//! schedule) and `finish`: defaults, round trips, bad values.

use super::test_support::{json_err, toml_err};
use super::*;
use crate::error::SceneError;

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
