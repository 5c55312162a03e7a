//! Settled balloons sleep; contact or the user wakes them.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::WorldDef;

#[test]
fn settled_balloons_sleep_and_an_impulse_wakes_them() {
    let def = WorldDef {
        room: Some(room(2.0, 2.0, 2.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let ids: Vec<_> = (0..9)
        .map(|i| {
            let p = Vec3::new((i % 3) as f32 * 0.4 - 0.4, 0.3, (i / 3) as f32 * 0.4 - 0.4);
            add(&mut world, shape, p, Quat::IDENTITY)
        })
        .collect();
    for _ in 0..(15 * 60) {
        world.step();
    }
    assert!(
        ids.iter().all(|&id| world.is_awake(id) == Some(false)),
        "all asleep"
    );
    assert_eq!(world.stats().awake_count, 0);
    let before = world.state_hash();
    world.step();
    assert_eq!(world.stats().awake_count, 0, "sleeping bodies stay put");
    let p = world.center_of_mass(ids[4]).unwrap();
    world
        .apply_impulse_at_point(ids[4], Vec3::new(0.0, -0.01, 0.0), p)
        .unwrap();
    assert_eq!(world.is_awake(ids[4]), Some(true));
    world.step();
    assert!(world.stats().awake_count >= 1);
    assert_ne!(world.state_hash(), before);
}

/// A row of balloons under the ceiling of a room just long enough for them,
/// touching one another, falls asleep; then the last one is kept turning about the
/// vertical. It and its
/// neighbour stay awake, the far end of the row sleeps on: a restless
/// balloon does not keep a whole pile awake.
#[test]
fn a_restless_balloon_keeps_only_its_neighbours_awake() {
    const N: usize = 8;
    let def = WorldDef {
        // Frictionless, so the turning balloon does not drive its
        // neighbours like gears.
        friction: 0.0,
        // Just long enough for the row, head to head.
        room: Some(room(N as f32 * 2.0 * HEAD_RADIUS + 0.004, 0.4, 2.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let ids: Vec<_> = (0..N)
        .map(|i| {
            let x = (i as f32 - 0.5 * (N - 1) as f32) * 2.0 * HEAD_RADIUS;
            let p = Vec3::new(x, 1.7, 0.0);
            add(&mut world, shape, p, Quat::IDENTITY)
        })
        .collect();
    for _ in 0..(20 * 60) {
        world.step();
    }
    assert_eq!(world.stats().awake_count, 0, "the row fell asleep");
    for pair in ids.windows(2) {
        let gap = world.center_of_mass(pair[1]).unwrap().x
            - world.center_of_mass(pair[0]).unwrap().x
            - 2.0 * HEAD_RADIUS;
        assert!(gap < 0.002, "the row is not touching: gap {gap} m");
    }
    let last = ids[N - 1];
    for _ in 0..(3 * 60) {
        world
            .set_velocity(last, Vec3::ZERO, Vec3::new(0.0, 0.5, 0.0))
            .unwrap();
        world.step();
    }
    let awake: Vec<bool> = ids
        .iter()
        .map(|&id| world.is_awake(id) == Some(true))
        .collect();
    assert!(
        awake[N - 1] && awake[N - 2],
        "the turning one and its neighbour: {awake:?}"
    );
    assert!(
        awake[..N - 3].iter().all(|&a| !a),
        "the far end sleeps on: {awake:?}"
    );
}
