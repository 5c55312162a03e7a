//! Scene files: the first byte picks TOML (even) or JSON (odd), the rest is
//! the text, parsed by `Scene::from_toml_str` / `from_json_str` (what
//! `Scene::from_path`, and so the CLI and the web app, call). A parsed scene
//! must write back and read back equal, and, cut down to a few balloons and
//! cheap fits, build into a world that steps without non-finite poses.
//! Errors must name the source.

use up_scene::build::build_world;
use up_scene::scene::Scene;

/// Balloons per group and groups kept for the build (spawning and fitting
/// cost, measured elsewhere, must not slow the fuzzer down).
const MAX_COUNT: u64 = 8;
const MAX_GROUPS: usize = 3;
const MAX_LEAVES: u32 = 2;
const STEPS: u32 = 4;

/// One input: panics when a property fails.
pub fn check(data: &[u8]) {
    let Some((&kind, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let (parsed, name) = if kind % 2 == 0 {
        (Scene::from_toml_str(text, "fuzz.toml"), "fuzz.toml")
    } else {
        (Scene::from_json_str(text, "fuzz.json"), "fuzz.json")
    };
    let mut scene = match parsed {
        Ok(scene) => scene,
        Err(e) => {
            let message = e.to_string();
            assert!(message.starts_with(name), "{message}");
            if let Some(line) = e.line() {
                assert!(line >= 1 && line <= text.split('\n').count(), "{message}");
            }
            return;
        }
    };

    // What is written can be read back as the same scene.
    let toml_text = scene
        .to_toml_string()
        .expect("a valid scene writes as TOML");
    let back = Scene::from_toml_str(&toml_text, "back.toml")
        .unwrap_or_else(|e| panic!("written TOML does not read back: {e}\n{toml_text}"));
    assert!(
        back == scene,
        "TOML round trip changed the scene:\n{toml_text}"
    );
    let json_text = scene
        .to_json_string()
        .expect("a valid scene writes as JSON");
    let back = Scene::from_json_str(&json_text, "back.json")
        .unwrap_or_else(|e| panic!("written JSON does not read back: {e}\n{json_text}"));
    assert!(
        back == scene,
        "JSON round trip changed the scene:\n{json_text}"
    );

    // Cut down, in a box room (no file system access), and build.
    scene.room.mesh = None;
    scene.balloons.truncate(MAX_GROUPS);
    for group in &mut scene.balloons {
        group.count = group.count.min(MAX_COUNT);
        group.leaves = group.leaves.min(MAX_LEAVES);
    }
    if scene.validate().is_err() {
        return;
    }
    let Ok(mut built) = build_world(&scene) else {
        return;
    };
    for _ in 0..STEPS {
        built.world.step();
    }
    for (id, pose) in built.world.poses() {
        assert!(
            pose.position.is_finite() && pose.rotation.is_finite(),
            "body {id:?} not finite after {STEPS} steps: {pose:?}\n{toml_text}"
        );
    }
}
