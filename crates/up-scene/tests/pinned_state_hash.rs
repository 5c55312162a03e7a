//! The state hash of a fixed scene after a fixed number of steps, pinned.
//!
//! Every result of the engine feeds `World::state_hash`: the spawn layout
//! (the scene's seeded generator), the forces, the contacts, the solver. The
//! constants below are the hashes the engine gives today; a change of any of
//! them is a change of results. Editing one must be deliberate, and the
//! commit that does it says why the results changed (a bug fix, a new
//! model), never "to make the test pass".

mod common;
use common::asset;

use up_scene::build::build_world;
use up_scene::scene::Scene;

/// The original room: 50 balloons on 1.5 m ribbons released from the floor, seed 1.
const DEFAULT_SCENE: &str = "default.toml";
/// Four simulated seconds at 1/60 s: the crowd rises, meets the pyramid
/// ceiling and starts to settle, so contacts, sleep and the solver all count.
const STEPS: u32 = 240;
/// `World::state_hash()` of `DEFAULT_SCENE` after `STEPS` steps.
const DEFAULT_SCENE_HASH: u64 = 0x3b86_f2e4_47f4_ef0f;
/// The same without its ribbons.
const DEFAULT_SCENE_WITHOUT_RIBBONS_HASH: u64 = 0x81c7_a7b7_e416_55a9;
/// The party hall: 1,000 balloons of two sizes and nine colours (one a hex
/// code), seed 2024; enough bodies that the parallel passes split into tasks.
const PARTY_HALL: &str = "party-hall.toml";
/// Three simulated seconds: the crowd rises through the 5 m hall.
const PARTY_HALL_STEPS: u32 = 180;
/// `World::state_hash()` of `PARTY_HALL` after `PARTY_HALL_STEPS` steps.
const PARTY_HALL_HASH: u64 = 0x8bff_cb4d_ae3a_7d38;
/// The bouquet: six balloons on ribbons tied to weights on the floor, seed 7.
const BOUQUET: &str = "bouquet.toml";
/// Three simulated seconds: the balloons rise and their ribbons go taut.
const BOUQUET_STEPS: u32 = 180;
/// `World::state_hash()` of `BOUQUET` after `BOUQUET_STEPS` steps.
const BOUQUET_HASH: u64 = 0x5e0c_729c_8424_cb8f;

/// The scene file built and stepped `steps` times on a pool of `threads` threads.
fn hash_after(name: &str, steps: u32, threads: usize) -> u64 {
    let scene = Scene::from_path(asset(name)).unwrap_or_else(|e| panic!("{e}"));
    scene_hash_after(&scene, steps, threads)
}

fn scene_hash_after(scene: &Scene, steps: u32, threads: usize) -> u64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| {
        let mut built = build_world(scene).unwrap_or_else(|e| panic!("{e}"));
        for _ in 0..steps {
            built.world.step();
        }
        built.world.state_hash()
    })
}

#[test]
fn default_scene_after_four_seconds_on_one_thread() {
    let hash = hash_after(DEFAULT_SCENE, STEPS, 1);
    assert_eq!(
        hash, DEFAULT_SCENE_HASH,
        "state hash {hash:#018x}, pinned {DEFAULT_SCENE_HASH:#018x}: the results changed"
    );
}

#[test]
fn default_scene_after_four_seconds_on_three_threads() {
    let hash = hash_after(DEFAULT_SCENE, STEPS, 3);
    assert_eq!(
        hash, DEFAULT_SCENE_HASH,
        "state hash {hash:#018x}, pinned {DEFAULT_SCENE_HASH:#018x}: the results changed"
    );
}

#[test]
fn default_scene_without_ribbons() {
    let mut scene = Scene::from_path(asset(DEFAULT_SCENE)).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.balloons[0].ribbon.take().is_some());
    let hash = scene_hash_after(&scene, STEPS, 3);
    assert_eq!(
        hash, DEFAULT_SCENE_WITHOUT_RIBBONS_HASH,
        "state hash {hash:#018x}, pinned {DEFAULT_SCENE_WITHOUT_RIBBONS_HASH:#018x}: the results changed"
    );
}

#[test]
fn party_hall_after_three_seconds_on_one_thread() {
    let hash = hash_after(PARTY_HALL, PARTY_HALL_STEPS, 1);
    assert_eq!(
        hash, PARTY_HALL_HASH,
        "state hash {hash:#018x}, pinned {PARTY_HALL_HASH:#018x}: the results changed"
    );
}

#[test]
fn party_hall_after_three_seconds_on_three_threads() {
    let hash = hash_after(PARTY_HALL, PARTY_HALL_STEPS, 3);
    assert_eq!(
        hash, PARTY_HALL_HASH,
        "state hash {hash:#018x}, pinned {PARTY_HALL_HASH:#018x}: the results changed"
    );
}

#[test]
fn bouquet_after_three_seconds_on_one_thread() {
    let hash = hash_after(BOUQUET, BOUQUET_STEPS, 1);
    assert_eq!(
        hash, BOUQUET_HASH,
        "state hash {hash:#018x}, pinned {BOUQUET_HASH:#018x}: the results changed"
    );
}

#[test]
fn bouquet_after_three_seconds_on_three_threads() {
    let hash = hash_after(BOUQUET, BOUQUET_STEPS, 3);
    assert_eq!(
        hash, BOUQUET_HASH,
        "state hash {hash:#018x}, pinned {BOUQUET_HASH:#018x}: the results changed"
    );
}
