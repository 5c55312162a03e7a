//! Balloons against the room: sliding across a seam, thrown at walls.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::WorldDef;

#[test]
fn balloon_slides_across_wall_seam_without_bump() {
    // Gravity along +x makes buoyancy press the balloon onto the x = -2
    // wall; it slides along z and up, across the wall's diagonal seam.
    let def = WorldDef {
        gravity: Vec3::new(9.81, 0.0, 0.0),
        friction: 0.0,
        enable_sleep: false,
        room: Some(room(4.0, 4.0, 3.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let start = Vec3::new(-2.0 + HEAD_RADIUS + 0.002, 1.0, -1.5);
    let id = add(&mut world, shape, start, Quat::IDENTITY);
    world.set_velocity(id, Vec3::ZERO, Vec3::ZERO).unwrap();
    let mut room_contacts = 0;
    for step in 0..150 {
        // Keep it sliding diagonally along the wall.
        let v = world.linear_velocity(id).unwrap();
        world
            .set_velocity(id, Vec3::new(v.x, 0.6, 1.2), Vec3::ZERO)
            .unwrap();
        world.step();
        for c in world
            .contact_points()
            .filter(|c| c.body_b.is_none() && c.separation < 0.005)
        {
            room_contacts += 1;
            assert!(
                (c.normal - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-3,
                "step {step}: normal {} at {}",
                c.normal,
                c.point
            );
        }
        let vx = world.linear_velocity(id).unwrap().x;
        assert!(vx < 0.05, "step {step}: bumped off the wall, vx = {vx}");
    }
    assert!(
        room_contacts > 100,
        "the balloon did not stay on the wall: {room_contacts}"
    );
    let z = world.center_of_mass(id).unwrap().z;
    assert!(z > 1.0, "it did not slide across the wall: z = {z}");
}

/// Air drag would stop a balloon thrown at 30 m/s within a metre (as it
/// should), so the throws below are drag-free: they arrive at the full
/// 30 m/s, half a metre per step, more than three balloon radii.
#[test]
fn balloon_thrown_at_30_m_per_s_does_not_pass_through_a_wall() {
    for direction in [
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Z,
        Vec3::new(1.0, 0.3, 0.7).normalize(),
    ] {
        let room_mesh = room(6.0, 6.0, 3.0, Some(1.5));
        let def = WorldDef {
            room: Some(room_mesh),
            drag_coefficient: 0.0,
            ..WorldDef::default()
        };
        let (mut world, shape) = world_with(def);
        let start = Vec3::new(2.0 * direction.x, 1.5, 2.0 * direction.z);
        let id = add(&mut world, shape, start, Quat::IDENTITY);
        world
            .set_velocity(id, 30.0 * direction, Vec3::ZERO)
            .unwrap();
        let mut fastest_hit = 0.0f32;
        for step in 0..120 {
            let before = world.linear_velocity(id).unwrap().length();
            world.step();
            let c = world.center_of_mass(id).unwrap();
            assert!(
                inside_room(c, 6.0, 6.0, 3.0, Some(1.5)),
                "step {step}: escaped to {c}"
            );
            if world.contact_points().any(|c| c.body_b.is_none()) {
                fastest_hit = fastest_hit.max(before);
            }
        }
        assert!(
            fastest_hit > 20.0,
            "{direction}: met a wall at only {fastest_hit} m/s"
        );
    }
}

#[test]
fn balloon_thrown_at_30_m_per_s_does_not_pass_through_another() {
    let def = WorldDef {
        gravity: Vec3::ZERO,
        drag_coefficient: 0.0,
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let target = add(&mut world, shape, Vec3::new(0.0, 0.0, 0.0), Quat::IDENTITY);
    let thrown = add(&mut world, shape, Vec3::new(-1.3, 0.0, 0.0), Quat::IDENTITY);
    world
        .set_velocity(thrown, Vec3::new(30.0, 0.0, 0.0), Vec3::ZERO)
        .unwrap();
    for step in 0..60 {
        world.step();
        let a = world.center_of_mass(thrown).unwrap();
        let b = world.center_of_mass(target).unwrap();
        assert!(a.x < b.x, "step {step}: passed through ({a} vs {b})");
        let gap = a.distance(b) - 2.0 * HEAD_RADIUS;
        assert!(
            gap > -0.01 * HEAD_RADIUS,
            "step {step}: heads overlap by {}",
            -gap
        );
    }
    // Equal masses, restitution 0.4: the target leaves at (1 + e)/2 of 30 m/s.
    let vb = world.linear_velocity(target).unwrap().x;
    assert!((vb - 21.0).abs() < 2.0, "target leaves at {vb} m/s");
}

/// The sweep stops a fast body at its first new contact with the room; a
/// sphere already deep in the wall at the start of the step is the
/// solver's to push out. (Stopping there froze a spinning balloon wedged
/// under the eaves of the 10,000-balloon pile in place for good, velocity
/// and all, 20 mm into its neighbours.)
#[test]
fn spinning_balloon_deep_in_a_wall_is_pushed_out_not_frozen() {
    let def = WorldDef {
        room: Some(room(4.0, 4.0, 3.0, None)),
        enable_sleep: false,
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    // The head's centre 0.3 radius from the x = −2 wall: its core is in the wall.
    let start = Vec3::new(-2.0 + 0.3 * HEAD_RADIUS, 1.5, 0.0);
    let id = add(&mut world, shape, start, Quat::IDENTITY);
    for _ in 0..30 {
        // Spinning fast enough to be swept every step.
        world
            .set_velocity(id, Vec3::ZERO, Vec3::new(0.0, 20.0, 0.0))
            .unwrap();
        world.step();
    }
    let deepest = world
        .contact_points()
        .filter(|c| c.body_b.is_none())
        .map(|c| -c.separation)
        .fold(0.0f32, f32::max);
    assert!(
        deepest < 0.01 * HEAD_RADIUS,
        "still {deepest} m into the wall after half a second"
    );
}
