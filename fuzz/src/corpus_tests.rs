//! Every committed corpus input through its target's `check`, on stable.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

/// Runs `check` on every file of `corpus/<target>`; fails naming each input
/// that panicked. An empty or missing corpus fails too (a test that checks
/// nothing would pass).
fn run_corpus(target: &str, check: fn(&[u8])) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("a corpus entry").path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{}: no inputs", dir.display());
    let mut failed = Vec::new();
    for file in &files {
        let data = std::fs::read(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        if catch_unwind(AssertUnwindSafe(|| check(&data))).is_err() {
            failed.push(file.display().to_string());
        }
    }
    assert!(
        failed.is_empty(),
        "{target}: {} of {} inputs fail (run one with `cargo +nightly fuzz run {target} FILE`):\n{}",
        failed.len(),
        files.len(),
        failed.join("\n")
    );
    println!("{target}: {} inputs pass", files.len());
}

#[test]
fn contacts_corpus() {
    run_corpus("contacts", crate::contacts::check);
}

#[test]
fn obj_corpus() {
    run_corpus("obj", crate::obj::check);
}

#[test]
fn scene_corpus() {
    run_corpus("scene", crate::scene::check);
}

#[test]
fn toi_corpus() {
    run_corpus("toi", crate::toi::check);
}

/// The dictionary's TOML keys (`"key = "` entries of scene.dict).
fn dictionary_keys() -> Vec<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scene.dict");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter_map(|line| line.strip_prefix('"')?.strip_suffix(" = \""))
        .map(str::to_string)
        .collect()
}

/// Every key of the scene format that the dictionary names is in a committed
/// TOML seed that reads as a scene: the target reaches each key's checks and
/// the building of a world with it, not only the parser's refusals.
#[test]
fn the_scene_corpus_reaches_every_key_of_the_dictionary() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus")
        .join("scene");
    let scenes: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|entry| {
            let data = std::fs::read(entry.ok()?.path()).ok()?;
            let (&kind, rest) = data.split_first()?;
            let text = std::str::from_utf8(rest).ok()?;
            let parsed = up_scene::scene::Scene::from_toml_str(text, "seed.toml");
            (kind % 2 == 0 && parsed.is_ok()).then(|| text.to_string())
        })
        .collect();
    let keys = dictionary_keys();
    assert!(
        keys.len() > 40,
        "too few keys read from scene.dict: {keys:?}"
    );
    let missing: Vec<&String> = keys
        .iter()
        .filter(|key| {
            !scenes.iter().any(|text| {
                text.lines()
                    .any(|line| line.trim_start().starts_with(&format!("{key} =")))
            })
        })
        .collect();
    assert!(missing.is_empty(), "no readable seed sets {missing:?}");
}
