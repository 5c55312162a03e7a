//! Range checks: every bad value names its key path, line and range.

use super::test_support::{json_err, toml_err};
use super::*;
use crate::error::SceneError;

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
