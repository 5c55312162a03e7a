//! The ribbons keep a sleeping balloon's sphere as they found it while it
//! sleeps (`world::ribbons_step`). A balloon that woke, moved and fell asleep
//! again while every ribbon slept must be found where it is now, not where
//! it slept before: a ribbon then swept into it is pushed around it, not
//! passed through it.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::{RibbonDef, RIBBON_RADIUS};
use up_physics::{BodyId, World, WorldDef};

const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);

/// Steps until `body` sleeps (at most a minute); false if it never did.
fn step_until_asleep(world: &mut World, body: BodyId, hold: Option<Vec3>) -> bool {
    for _ in 0..60 * 60 {
        if let Some(target) = hold {
            world.set_grab_target(target).unwrap();
        }
        world.step();
        if !world.is_awake(body).unwrap() {
            return true;
        }
    }
    false
}

/// How deep any of the ribbon's free points lay within the other balloon's
/// leaves at a step's end, at most, m, while the ribbon's end is dragged
/// through where that balloon fell asleep the second time.
fn deepest_in_the_moved_sleeper() -> f32 {
    // No gravity: everything stays where it is put, and sleeps there.
    let def = WorldDef {
        gravity: Vec3::ZERO,
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let held_at = Vec3::new(0.0, 2.0, 0.0);
    let hanging = add(&mut world, shape, held_at, Quat::IDENTITY);
    let ribbon = world
        .add_ribbon(&RibbonDef::new(hanging, KNOT, 1.5, 16))
        .unwrap();
    let first = Vec3::new(3.0, 2.0, 0.0);
    let other = add(&mut world, shape, first, Quat::IDENTITY);
    // The other balloon falls asleep far away while the ribbon is awake
    // (its balloon held): the ribbons find its sphere there, asleep.
    world.grab(hanging, held_at).unwrap();
    assert!(step_until_asleep(&mut world, other, Some(held_at)));
    for _ in 0..10 {
        world.set_grab_target(held_at).unwrap();
        world.step();
    }
    world.release_grab();
    assert!(step_until_asleep(&mut world, hanging, None));
    // Every ribbon asleep, the other balloon is moved beside the ribbon's
    // lower half, clear of it, and falls asleep there.
    let points = world.ribbon_points(ribbon).unwrap().to_vec();
    let beside = Vec3::new(0.45, points[10].y, 0.0);
    // (Pushed by hand: a grab pulls by the body's weight, none here.)
    for _ in 0..240 {
        let to = beside - world.center_of_mass(other).unwrap();
        let velocity = (to * 2.0).clamp_length_max(1.0);
        world.set_velocity(other, velocity, Vec3::ZERO).unwrap();
        world.step();
    }
    world.set_velocity(other, Vec3::ZERO, Vec3::ZERO).unwrap();
    assert!(step_until_asleep(&mut world, other, None));
    assert!(
        !world.is_awake(hanging).unwrap(),
        "the moved balloon woke the ribbon"
    );
    let at = world.center_of_mass(other).unwrap();
    assert!(at.distance(beside) < 0.05, "moved to {at}, not {beside}");
    // The ribbon's end is dragged through where the other balloon sleeps.
    let end = points.len() - 1;
    let start = points[end];
    world.grab_ribbon(ribbon, end, start).unwrap();
    let tree = world.shape(shape).unwrap().tree.clone();
    let mut deepest = 0.0f32;
    for k in 0..=180 {
        let target = start + Vec3::new(1.2 * k as f32 / 180.0, 0.0, 0.0);
        world.set_grab_target(target).unwrap();
        world.step();
        let pose = world.pose(other).unwrap();
        let points = world.ribbon_points(ribbon).unwrap();
        for leaf in tree.leaf_spheres() {
            let center = pose.transform_point(leaf.center);
            for p in &points[1..end] {
                deepest = deepest.max(leaf.radius + RIBBON_RADIUS - p.distance(center));
            }
        }
    }
    deepest
}

#[test]
fn a_balloon_moved_while_every_ribbon_slept_is_found_where_it_sleeps_now() {
    let deepest = deepest_in_the_moved_sleeper();
    println!("deepest {deepest:.4} m");
    // Passed through, a point would lie centimetres inside a leaf.
    assert!(
        deepest < 0.01,
        "a point {deepest} m inside the moved balloon"
    );
}
