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

use up_physics::divergence::lockstep_with;
use up_scene::build::build_world;
use up_scene::scene::Scene;

/// The original room: 50 balloons on 1.5 m ribbons released from the floor, seed 1.
const DEFAULT_SCENE: &str = "default.toml";
/// Four simulated seconds at 1/60 s: the crowd rises, meets the pyramid
/// ceiling and starts to settle, so contacts, sleep and the solver all count.
const STEPS: u32 = 240;
/// `World::state_hash()` of `DEFAULT_SCENE` after `STEPS` steps.
const DEFAULT_SCENE_HASH: u64 = 0x852e_01bc_a7d3_8b60;
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
const BOUQUET_HASH: u64 = 0xc765_c2fc_537b_0c93;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

/// The scene built and stepped `steps` times on a pool of `threads` threads.
fn scene_hash_after(scene: &Scene, steps: u32, threads: usize) -> u64 {
    pool(threads).install(|| {
        let mut built = build_world(scene).unwrap_or_else(|e| panic!("{e}"));
        for _ in 0..steps {
            built.world.step();
        }
        built.world.state_hash()
    })
}

/// Where the scene on `threads` threads parts from it on one, stepped side
/// by side, in words: what a failing pinned hash on several threads says
/// beside the hashes.
fn parting_from_one_thread(scene: &Scene, steps: u32, threads: usize) -> String {
    let (one, many) = (pool(1), pool(threads));
    let build = || build_world(scene).unwrap_or_else(|e| panic!("{e}")).world;
    let (mut a, mut b) = (one.install(build), many.install(build));
    let parted = lockstep_with(
        &mut a,
        &mut b,
        u64::from(steps),
        |w| one.install(|| w.step()),
        |w| many.install(|| w.step()),
    );
    match parted {
        Some(parted) => format!("on {threads} threads against one, {parted}"),
        None => format!("{threads} threads and one agree at every step"),
    }
}

/// The scene's hash after `steps` steps on `threads` threads is `pinned`;
/// where not, on several threads, the message says where they part from one.
fn assert_pinned(name: &str, scene: &Scene, steps: u32, threads: usize, pinned: u64) {
    let hash = scene_hash_after(scene, steps, threads);
    if hash != pinned {
        let parting = if threads > 1 {
            parting_from_one_thread(scene, steps, threads)
        } else {
            String::from("one thread")
        };
        panic!("{name}: state hash {hash:#018x}, pinned {pinned:#018x}: the results changed ({parting})");
    }
}

fn load(name: &str) -> Scene {
    Scene::from_path(asset(name)).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn default_scene_after_four_seconds_on_one_thread() {
    assert_pinned(
        DEFAULT_SCENE,
        &load(DEFAULT_SCENE),
        STEPS,
        1,
        DEFAULT_SCENE_HASH,
    );
}

#[test]
fn default_scene_after_four_seconds_on_three_threads() {
    assert_pinned(
        DEFAULT_SCENE,
        &load(DEFAULT_SCENE),
        STEPS,
        3,
        DEFAULT_SCENE_HASH,
    );
}

#[test]
fn default_scene_without_ribbons() {
    let mut scene = load(DEFAULT_SCENE);
    assert!(scene.balloons[0].ribbon.take().is_some());
    assert_pinned(
        "the default scene without ribbons",
        &scene,
        STEPS,
        3,
        DEFAULT_SCENE_WITHOUT_RIBBONS_HASH,
    );
}

#[test]
fn party_hall_after_three_seconds_on_one_thread() {
    assert_pinned(
        PARTY_HALL,
        &load(PARTY_HALL),
        PARTY_HALL_STEPS,
        1,
        PARTY_HALL_HASH,
    );
}

#[test]
fn party_hall_after_three_seconds_on_three_threads() {
    assert_pinned(
        PARTY_HALL,
        &load(PARTY_HALL),
        PARTY_HALL_STEPS,
        3,
        PARTY_HALL_HASH,
    );
}

#[test]
fn bouquet_after_three_seconds_on_one_thread() {
    assert_pinned(BOUQUET, &load(BOUQUET), BOUQUET_STEPS, 1, BOUQUET_HASH);
}

#[test]
fn bouquet_after_three_seconds_on_three_threads() {
    assert_pinned(BOUQUET, &load(BOUQUET), BOUQUET_STEPS, 3, BOUQUET_HASH);
}
