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

/// A pile pressed against the ceiling falls asleep; woken whole, it goes on
/// from the contact forces that held it: no jolt. (Woken without them, the
/// first substeps let buoyancy lift it unopposed, at centimetres a second,
/// which used to wake the next groups of a big pile in a chain.) A snapshot
/// of the sleeping pile keeps those forces too.
#[test]
fn a_woken_pile_resumes_without_a_jolt() {
    let def = WorldDef {
        room: Some(room(0.9, 0.9, 2.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let ids: Vec<_> = (0..18)
        .map(|i| {
            let layer = (i / 9) as f32;
            let p = Vec3::new(
                (i % 3) as f32 * 0.3 - 0.3,
                1.0 - 0.35 * layer,
                ((i / 3) % 3) as f32 * 0.3 - 0.3,
            );
            add(&mut world, shape, p, Quat::IDENTITY)
        })
        .collect();
    for _ in 0..(20 * 60) {
        world.step();
    }
    assert_eq!(world.stats().awake_count, 0, "the pile fell asleep");
    let heights: Vec<f32> = ids
        .iter()
        .map(|&id| world.center_of_mass(id).unwrap().y)
        .collect();
    let low = heights.iter().copied().fold(f32::INFINITY, f32::min);
    let high = heights.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    assert!(
        high - low > 0.2,
        "two layers, one pressed by the other: {heights:?}"
    );

    let mut restored = up_physics::World::restore(&world.snapshot()).unwrap();
    for w in [&mut world, &mut restored] {
        for &id in &ids {
            w.wake(id).unwrap();
        }
        w.step();
    }
    assert_eq!(
        world.state_hash(),
        restored.state_hash(),
        "the snapshot kept the impulses"
    );
    let fastest = ids
        .iter()
        .map(|&id| world.linear_velocity(id).unwrap().length())
        .fold(0.0f32, f32::max);
    // A tenth of the sleep threshold; woken without its impulses this pile
    // starts at 1.4 mm/s (a big one at 10-30 mm/s), with them at 3 µm/s.
    assert!(fastest < 0.0005, "woken, the pile jolts at {fastest} m/s");
}

/// A balloon thrown at a sleeping one wakes it before they meet, in the step
/// it will reach it (its motion plus the speculative distance), so that the
/// struck one gives way at once instead of standing still, static, for a step.
/// A slow one wakes only what it touches.
#[test]
fn a_thrown_balloon_wakes_what_it_will_reach_this_step() {
    for (speed, wakes) in [(1.0, true), (0.05, false)] {
        let def = WorldDef {
            room: Some(room(2.0, 2.0, 2.0, None)),
            ..WorldDef::default()
        };
        let (mut world, shape) = world_with(def);
        let root = world.shape(shape).unwrap().tree.root().radius;
        // Root spheres 5 mm apart: not touching, within a 1 m/s step's reach (27 mm).
        let gap = 0.005;
        let struck = add(&mut world, shape, Vec3::new(0.0, 1.5, 0.0), Quat::IDENTITY);
        let x = -(2.0 * root + gap);
        let thrown = add(&mut world, shape, Vec3::new(x, 1.5, 0.0), Quat::IDENTITY);
        for _ in 0..(10 * 60) {
            world.step();
        }
        assert_eq!(world.stats().awake_count, 0, "both asleep");
        let apart = world.center_of_mass(struck).unwrap() - world.center_of_mass(thrown).unwrap();
        assert!(
            (apart.length() - (2.0 * root + gap)).abs() < 1e-3,
            "still {apart} apart"
        );

        world
            .set_velocity(thrown, Vec3::new(speed, 0.0, 0.0), Vec3::ZERO)
            .unwrap();
        world.step();
        assert_eq!(
            world.is_awake(struck),
            Some(wakes),
            "thrown at {speed} m/s, the sleeper {}",
            if wakes { "stayed asleep" } else { "woke" }
        );
    }
}

/// Steps until `id` sleeps (at most `limit`); the steps taken.
fn steps_to_sleep(world: &mut up_physics::World, id: up_physics::BodyId, limit: usize) -> usize {
    (1..=limit)
        .find(|_| {
            world.step();
            world.is_awake(id) == Some(false)
        })
        .unwrap_or(limit + 1)
}

#[test]
fn a_hovering_balloon_rests_from_a_swing_but_not_from_a_creep_down() {
    // A balloon hovering on a heavy ribbon lying partly on the floor (11 g
    // of lift, 10 g/m): set swinging across at 4 mm/s (under the sleep
    // speed), it rests as any slow body does; set moving down at the same
    // speed, as a balloon creeps down its ribbon when its gas has gone, it
    // does not rest until it has stopped (the finer hover speed along
    // gravity: asleep mid-creep, it would come down a segment late).
    use up_physics::ribbon::RibbonDef;
    let def = WorldDef {
        room: Some(room(6.0, 6.0, 3.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let id = add(&mut world, shape, Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY);
    let knot = Vec3::new(0.0, -0.2, 0.0);
    world
        .add_ribbon(&RibbonDef {
            mass_per_length: 0.010,
            ..RibbonDef::new(id, knot, 2.0, 16)
        })
        .unwrap();
    let settled = steps_to_sleep(&mut world, id, 60 * 60);
    assert!(settled <= 60 * 60, "never slept settling");
    let sleep = world.def().time_to_sleep;
    let rest_steps = (sleep / world.def().dt).ceil() as usize;
    let mut kick = |v: Vec3| {
        world.set_velocity(id, v, Vec3::ZERO).unwrap();
        steps_to_sleep(&mut world, id, 60 * 60)
    };
    let across = kick(Vec3::new(0.004, 0.0, 0.0));
    let down = kick(Vec3::new(0.0, -0.004, 0.0));
    println!("asleep {across} steps after a swing across, {down} after a push down");
    assert!(
        across <= rest_steps + 2,
        "swinging at 4 mm/s: asleep after {across} steps"
    );
    assert!(
        down > 2 * rest_steps,
        "moving down at 4 mm/s: asleep after {down} steps"
    );
}
