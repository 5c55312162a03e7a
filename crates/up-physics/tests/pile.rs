//! Hundreds of balloons released into the original room settle into a stable
//! pile under the pyramidal ceiling: none escapes, none sinks into another.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::WorldDef;

const WIDTH: f32 = 6.0;
const WALL: f32 = 3.0;
const APEX: f32 = 1.5;

#[test]
fn five_hundred_balloons_settle_under_the_ceiling_without_overlap() {
    let def = WorldDef {
        room: Some(room(WIDTH, WIDTH, WALL, Some(APEX))),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    // A jittered grid of 18 × 18 per layer near the floor, two layers.
    let spacing = 0.33;
    let mut ids = Vec::new();
    let mut seed = 7u32;
    let mut jitter = move || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        ((seed >> 8) as f32 / (1 << 24) as f32 - 0.5) * 0.02
    };
    'fill: for layer in 0..2 {
        for ix in 0..18 {
            for iz in 0..18 {
                if ids.len() == 500 {
                    break 'fill;
                }
                let x = -2.8 + ix as f32 * spacing + jitter();
                let z = -2.8 + iz as f32 * spacing + jitter();
                let y = 0.25 + layer as f32 * 0.42;
                let yaw = Quat::from_rotation_y(jitter() * 100.0);
                ids.push(add(&mut world, shape, Vec3::new(x, y, z), yaw));
            }
        }
    }
    assert_eq!(world.body_count(), 500);
    let limit = 0.01 * HEAD_RADIUS;
    let mut worst = 0.0f32;
    for step in 0..(60 * 60) {
        world.step();
        let p = world.stats().max_penetration;
        worst = worst.max(p);
        assert!(p <= limit, "step {step}: penetration {p} m > {limit} m");
    }
    let final_penetration = world.max_penetration_now();
    assert!(
        final_penetration <= limit,
        "final penetration {final_penetration}"
    );
    let mut fastest = 0.0f32;
    for &id in &ids {
        let c = world.center_of_mass(id).unwrap();
        assert!(
            inside_room(c, WIDTH, WIDTH, WALL, Some(APEX)),
            "escaped: {c}"
        );
        fastest = fastest.max(world.linear_velocity(id).unwrap().length());
        assert!(c.y > WALL - 1.0, "a balloon did not rise: {c}");
    }
    assert!(fastest < 0.01, "pile not at rest: {fastest} m/s");
    eprintln!(
        "worst penetration {worst} m, awake {}",
        world.stats().awake_count
    );
}
