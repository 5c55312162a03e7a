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
