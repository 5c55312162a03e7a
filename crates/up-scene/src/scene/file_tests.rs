//! Scene files: read by extension, refused when missing or too large; the
//! example scenes and the documented examples parse.

use super::test_support::asset;
use super::*;
use crate::error::SceneError;

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
fn example_scenes_parse_and_validate() {
    let names = [
        "default.toml",
        "bouquet.toml",
        "terminal-velocity.toml",
        "party-hall.toml",
        "party-fans.toml",
        "thrown.toml",
        "two-gases.json",
        "evening.toml",
        "tied.toml",
        "mixed-room.toml",
        "birthday.toml",
    ];
    for name in names {
        let scene = Scene::from_path(asset(name)).unwrap_or_else(|e| panic!("{e}"));
        scene.validate().unwrap();
    }
    let party = Scene::from_path(asset("party-hall.toml")).unwrap();
    assert_eq!(party.total_balloons(), 1000);
    assert!(!party.has_moving_air());
    // The same party with a sweeping fan and a ceiling vent.
    let fans = Scene::from_path(asset("party-fans.toml")).unwrap();
    assert_eq!(fans.balloons, party.balloons);
    assert_eq!((fans.fans.len(), fans.vents.len()), (1, 1));
    assert!(fans.fans[0].sweep_deg > 0.0);
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
    let sources = (from_toml.fans.len(), from_toml.vents.len());
    assert_eq!((sources, from_toml.draughts.len()), ((1, 1), 1));
    assert_eq!(
        from_toml.balloons[0].tied_ribbon(),
        Some(&RibbonSpec::default())
    );
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
