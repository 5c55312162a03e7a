//! The ribbons' candidate balloons are kept over several steps within a
//! margin (`ribbon::nearby`): a balloon thrown fast at a hanging ribbon, so
//! that it leaves that margin within a step, must still be one of the
//! ribbon's candidates when it reaches it, and push the ribbon aside instead
//! of passing through it, whether the ribbon's balloon was awake or asleep.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::{RibbonDef, RIBBON_RADIUS};
use up_physics::WorldDef;

const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);

/// A balloon on a 1.5 m ribbon settles under the ceiling while another is
/// held beside the ribbon; then the held one is thrown at the ribbon at
/// `speed`. Returns how far along the throw the ribbon's points at the
/// thrown balloon's height went at most, m, how deep any point lay within
/// the thrown balloon's leaves at the end of a step, m, and whether the
/// ribbon's balloon slept before the throw.
fn ribbon_pushed_by_a_throw(speed: f32, wait_for_sleep: bool) -> (f32, f32, bool) {
    let def = WorldDef {
        room: Some(room(6.0, 6.0, 3.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let hanging = add(&mut world, shape, Vec3::new(0.0, 2.0, 0.0), Quat::IDENTITY);
    let ribbon = world
        .add_ribbon(&RibbonDef::new(hanging, KNOT, 1.5, 16))
        .unwrap();
    let held_at = Vec3::new(-1.0, 1.7, 0.0);
    let thrown = add(&mut world, shape, held_at, Quat::IDENTITY);
    world.grab(thrown, held_at).unwrap();
    // Awake: a third of a second after the start, still rising.
    let mut steps = 0;
    while steps < 20 || (wait_for_sleep && world.is_awake(hanging).unwrap()) {
        assert!(steps < 60 * 60, "the hanging balloon never slept");
        world.set_grab_target(held_at).unwrap();
        world.step();
        steps += 1;
    }
    let slept = !world.is_awake(hanging).unwrap();
    let y = world.center_of_mass(thrown).unwrap().y;
    let before: Vec<Vec3> = world.ribbon_points(ribbon).unwrap().to_vec();
    world.release_grab();
    world
        .set_velocity(thrown, Vec3::new(speed, 0.0, 0.0), Vec3::ZERO)
        .unwrap();
    let tree = world.shape(shape).unwrap().tree.clone();
    let (mut pushed, mut deepest) = (0.0f32, 0.0f32);
    for _ in 0..30 {
        world.step();
        let points = world.ribbon_points(ribbon).unwrap();
        for (p, b) in points.iter().zip(&before) {
            if (b.y - y).abs() < 0.15 {
                pushed = pushed.max(p.x - b.x);
            }
        }
        let pose = world.pose(thrown).unwrap();
        for leaf in tree.leaf_spheres() {
            let center = pose.transform_point(leaf.center);
            for p in &points[1..] {
                let depth = leaf.radius + RIBBON_RADIUS - p.distance(center);
                deepest = deepest.max(depth);
            }
        }
    }
    (pushed, deepest, slept)
}

#[test]
fn a_balloon_thrown_fast_at_a_hanging_ribbon_pushes_it_aside() {
    for speed in [15.0, 30.0, 60.0] {
        for wait_for_sleep in [false, true] {
            let (pushed, deepest, slept) = ribbon_pushed_by_a_throw(speed, wait_for_sleep);
            println!(
                "{speed} m/s, asleep before: {slept}: pushed {pushed:.3} m, deepest {deepest:.4} m"
            );
            assert_eq!(slept, wait_for_sleep);
            assert!(
                pushed > 0.1,
                "thrown at {speed} m/s (asleep before: {slept}), the ribbon went {pushed} m"
            );
            // Passed through, a point would lie centimetres inside a leaf.
            assert!(
                deepest < 0.03,
                "a point {deepest} m inside the thrown balloon"
            );
        }
    }
}
