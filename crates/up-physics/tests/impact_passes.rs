//! The position passes double after an impact (a contact that closed faster
//! than the speculative distance in a step and pushed), and only then: fast
//! bodies that move together, or pass by, do not count.

mod common;

use common::*;
use glam::{Quat, Vec3};

#[test]
fn balloons_rising_side_by_side_are_no_impact() {
    let (mut world, shape) = world_with(free_space());
    let base = world.def().stabilization_iterations;
    // A row 5 mm apart: within the speculative distance, so in contact.
    let ids: Vec<_> = (0..5)
        .map(|i| {
            add(
                &mut world,
                shape,
                Vec3::new((2.0 * HEAD_RADIUS + 0.005) * i as f32, 1.0, 0.0),
                Quat::IDENTITY,
            )
        })
        .collect();
    let mut contacts = 0;
    for _ in 0..30 {
        for &id in &ids {
            world
                .set_velocity(id, Vec3::new(0.0, 1.7, 0.0), Vec3::ZERO)
                .unwrap();
        }
        world.step();
        contacts += world.stats().contact_count;
        assert_eq!(world.stats().position_passes, base);
    }
    assert!(
        contacts > 0,
        "the row was never within the speculative distance"
    );
}

#[test]
fn a_thrown_balloon_hitting_another_doubles_the_passes() {
    let (mut world, shape) = world_with(free_space());
    let base = world.def().stabilization_iterations;
    let thrown = add(&mut world, shape, Vec3::new(-0.6, 1.0, 0.0), Quat::IDENTITY);
    add(&mut world, shape, Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY);
    world
        .set_velocity(thrown, Vec3::new(3.0, 0.0, 0.0), Vec3::ZERO)
        .unwrap();
    let mut passes = Vec::new();
    for _ in 0..30 {
        world.step();
        passes.push(world.stats().position_passes);
    }
    assert!(passes.contains(&(2 * base)), "no impact seen: {passes:?}");
    assert_eq!(
        passes.last(),
        Some(&base),
        "the impact never ended: {passes:?}"
    );
}
