//! Speculative contacts: a pair of balloons gets contacts up to twice the
//! speculative distance (2 cm) plus the most their gap can close in the step
//! (their relative motion and both spins), so balloons rising side by side
//! make none while a balloon closing in at the same gap meets the other
//! without sinking into it; and a knock (a collision within the step that
//! throws one of them towards the other) widens it.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::{BodyId, World};

/// Gap between the two heads, m: beyond twice the speculative distance,
/// within the 2.8 cm a balloon covers in a step at 1.7 m/s.
const GAP: f32 = 0.025;

/// Two reference balloons side by side along x, `GAP` apart.
fn pair() -> (World, BodyId, BodyId) {
    let (mut world, shape) = world_with(free_space());
    let left = add(&mut world, shape, Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY);
    let right = Vec3::new(2.0 * HEAD_RADIUS + GAP, 1.0, 0.0);
    let right = add(&mut world, shape, right, Quat::IDENTITY);
    (world, left, right)
}

#[test]
fn balloons_moving_together_make_no_contacts() {
    let (mut world, left, right) = pair();
    let rise = Vec3::new(0.0, 1.7, 0.0);
    for _ in 0..10 {
        world.set_velocity(left, rise, Vec3::ZERO).unwrap();
        world.set_velocity(right, rise, Vec3::ZERO).unwrap();
        world.step();
        assert_eq!(world.stats().contact_count, 0, "their gap cannot close");
    }
}

#[test]
fn a_balloon_closing_in_meets_the_other_before_it_overlaps() {
    let (mut world, left, right) = pair();
    world
        .set_velocity(left, Vec3::new(1.7, 0.0, 0.0), Vec3::ZERO)
        .unwrap();
    world.step();
    assert!(
        world.stats().contact_count > 0,
        "no speculative contact for a gap that closes this step"
    );
    let mut deepest: f32 = 0.0;
    for _ in 0..30 {
        world.step();
        deepest = deepest.max(world.max_penetration_now());
    }
    // 1 % of the head's radius, the soak's bound.
    assert!(deepest < 0.01 * HEAD_RADIUS, "overlapped {deepest} m");
    let (vl, vr) = (
        world.linear_velocity(left).unwrap(),
        world.linear_velocity(right).unwrap(),
    );
    assert!(vr.x > vl.x, "they did not part: {vl} {vr}");
}

#[test]
fn a_spinning_balloon_gets_contacts_at_the_same_gap() {
    let (mut world, left, _) = pair();
    // 10 rad/s about z: the bounding sphere's surface turns through ≈ 3 cm a step.
    world
        .set_velocity(left, Vec3::ZERO, Vec3::new(0.0, 0.0, 10.0))
        .unwrap();
    world.step();
    assert!(
        world.stats().contact_count > 0,
        "spin not counted as closing"
    );
}

#[test]
fn a_balloon_knocked_back_within_the_step_meets_the_one_behind() {
    // A row thrown together at 4 m/s at a balloon at rest: the first meets
    // it this step and is thrown back onto the second, whose gap to it (GAP)
    // their velocities at the step's start could not close. Without the
    // knock in the pair's margin they sank 8.1 mm into each other.
    let (mut world, shape) = world_with(free_space());
    let at_rest = add(&mut world, shape, Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY);
    let first_x = 2.0 * HEAD_RADIUS;
    let first = add(
        &mut world,
        shape,
        Vec3::new(first_x, 1.0, 0.0),
        Quat::IDENTITY,
    );
    let second_x = first_x + 2.0 * HEAD_RADIUS + GAP;
    let second = add(
        &mut world,
        shape,
        Vec3::new(second_x, 1.0, 0.0),
        Quat::IDENTITY,
    );
    let towards = Vec3::new(-4.0, 0.0, 0.0);
    world.set_velocity(first, towards, Vec3::ZERO).unwrap();
    world.set_velocity(second, towards, Vec3::ZERO).unwrap();
    let mut deepest: f32 = 0.0;
    for _ in 0..30 {
        world.step();
        deepest = deepest.max(world.max_penetration_now());
    }
    // 1 % of the head's radius, the soak's bound.
    assert!(deepest < 0.01 * HEAD_RADIUS, "overlapped {deepest} m");
    let v = |id| world.linear_velocity(id).unwrap().x;
    assert!(v(at_rest) < 0.0, "the balloon at rest was never struck");
    assert!(
        v(second) > v(first),
        "the second did not part from the first"
    );
}
