//! Groups that hang weights over the floor (`hang`), alone and in a room of
//! every kind of balloon: laid clear of every balloon, in as many staggered
//! layers as they need, and clean from the first step.

use super::*;
use crate::scene::Scene;
use up_physics::ribbon::WEIGHT_RADIUS;

/// The example room of every kind of balloon: 1,500 free balloons on
/// ribbons that stack three layers deep, 200 on ribbons to 35 g weights,
/// 300 foil, in a 10 m × 10 m room.
fn mixed_room() -> Scene {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes");
    Scene::from_path(dir.join("mixed-room.toml")).unwrap()
}

/// The same room with `total` balloons spread evenly over its three groups,
/// as `up soak --balloons` spreads them: at 2,000, 667 hang weights, more
/// than the 529 the floor holds in one layer.
fn mixed_room_of(total: u64) -> Scene {
    mixed_room().with_total_balloons(total).unwrap()
}

/// `up soak`'s bound: 1 % of the smallest balloon's radius.
fn soak_bound(scene: &Scene) -> f32 {
    let radius = scene
        .balloons
        .iter()
        .map(|g| g.diameter() / 2.0)
        .fold(f32::INFINITY, f32::min);
    0.01 * radius
}

/// Every balloon's bounding sphere in the world: (group, body, centre, radius).
fn bounding_spheres(built: &BuiltScene) -> Vec<(usize, BodyId, Vec3, f32)> {
    let world = &built.world;
    (0..built.group_bodies.len())
        .flat_map(|group| {
            let root = built.balloon_models[group].shape.tree.root().sphere();
            built.group_bodies[group].iter().map(move |&b| {
                let pose = world.pose(b).unwrap();
                (group, b, pose.transform_point(root.center), root.radius)
            })
        })
        .collect()
}

/// Checks that every ribbon of weighted `group` hangs straight down from its
/// knot, its weight above the floor by at most `highest` m, and every point
/// of it (the weight's width about each) clear of every other balloon's
/// bounding sphere; returns the knots' heights.
fn assert_hung_clear(built: &BuiltScene, group: usize, highest: f32) -> Vec<f32> {
    let world = &built.world;
    let spheres = bounding_spheres(built);
    let floor = built.room.bounds().min.y;
    let mut knots = Vec::new();
    for &b in &built.group_bodies[group] {
        let points = world.ribbon_points(world.ribbon_of(b).unwrap()).unwrap();
        let weight = *points.last().unwrap();
        assert!(
            weight.y - floor > WEIGHT_RADIUS && weight.y - floor < highest,
            "a weight hangs at {weight} m"
        );
        assert!(
            (points[0].x - weight.x).abs() < 1e-4 && (points[0].z - weight.z).abs() < 1e-4,
            "not straight down: {points:?}"
        );
        for p in points {
            for &(_, other, centre, radius) in &spheres {
                if other != b {
                    assert!(
                        p.distance(centre) > radius + WEIGHT_RADIUS,
                        "ribbon point {p} of body {b:?} inside the balloon at {centre}"
                    );
                }
            }
        }
        knots.push(points[0].y);
    }
    knots
}

/// Builds `scene`, checks that nothing overlaps at step 0 (no two balloons,
/// no weighted ribbon or weight and another balloon), then steps it `steps`
/// times; returns the deepest overlap over those steps, m.
fn worst_overlap_from_the_start(scene: &Scene, steps: usize) -> f32 {
    let mut built = build_world(scene).unwrap();
    assert_eq!(built.world.max_penetration_now(), 0.0, "overlap at spawn");
    let floor_and_a_layer = 1.0;
    assert_hung_clear(&built, 1, floor_and_a_layer);
    let world = &mut built.world;
    let mut worst = 0.0f32;
    for _ in 0..steps {
        world.step();
        worst = worst.max(world.stats().max_penetration);
    }
    worst
}

#[test]
fn a_room_of_every_kind_of_balloon_starts_clean_and_stays_clean() {
    // Laid in the scene's order, the weighted balloons went above the free
    // ones, and their weights hung 1.2 m down among them: 101 mm of overlap
    // within six steps.
    assert_clean_from_the_start(&mixed_room(), 60);
}

#[test]
fn a_room_with_more_weighted_balloons_than_a_layer_starts_clean_and_stays_clean() {
    // 667 of each kind: the weighted take two layers; the second's weights
    // drop a layer's rise to the floor when released.
    let scene = mixed_room_of(2000);
    assert_eq!(scene.balloons[1].count, 667);
    assert_clean_from_the_start(&scene, 90);
}

/// No two balloons of `scene` overlap by the soak's bound over its first
/// `steps` steps.
fn assert_clean_from_the_start(scene: &Scene, steps: usize) {
    let bound = soak_bound(scene);
    let worst = worst_overlap_from_the_start(scene, steps);
    assert!(
        worst < bound,
        "worst overlap {:.2} mm over the first {steps} steps, bound {:.2} mm",
        worst * 1e3,
        bound * 1e3
    );
}

#[test]
fn weighted_balloons_hang_their_weights_clear_of_every_balloon() {
    let built = build_world(&mixed_room()).unwrap();
    // One layer: each weight just clear of the floor.
    let knots = assert_hung_clear(&built, 1, 1.2 / 16.0);
    let spread = knots.iter().fold(0.0f32, |m, y| m.max(*y))
        - knots.iter().fold(f32::INFINITY, |m, y| m.min(*y));
    assert!(spread < 0.05, "one layer: knots {spread} m apart in height");
}

#[test]
fn more_weighted_balloons_than_a_layer_holds_hang_in_staggered_layers() {
    let scene = mixed_room_of(2000);
    let built = build_world(&scene).unwrap();
    let knots = assert_hung_clear(&built, 1, 1.0);
    let lowest = knots.iter().fold(f32::INFINITY, |m, y| m.min(*y));
    let (first, second): (Vec<f32>, Vec<f32>) = knots.iter().partition(|&&y| y < lowest + 0.05);
    let rise = second.iter().fold(f32::INFINITY, |m, y| m.min(*y)) - lowest;
    let top = second.iter().fold(0.0f32, |m, y| m.max(*y)) - lowest;
    assert!(
        first.len() <= 529 && first.len() + second.len() == 667,
        "{} in the first layer, {} in the second",
        first.len(),
        second.len()
    );
    // The second a layer's rise above the first, and no third.
    assert!(
        rise > 0.2 && top < rise + 0.05,
        "rise {rise} m, top {top} m"
    );
    // Filled from one side: the rest of the floor is left to the other groups,
    // whose balloons start under the weighted ones' knots as well as above.
    let floor = built.room.bounds().min.y;
    let under = bounding_spheres(&built)
        .iter()
        .filter(|&&(group, _, centre, radius)| group != 1 && centre.y + radius < floor + lowest)
        .count();
    assert!(
        under > 200,
        "{under} balloons start below the weighted layer"
    );
}

#[test]
fn weighted_balloons_the_room_cannot_hold_name_the_group_the_count_and_the_room() {
    let text = "[room]\nwidth = 2.0\ndepth = 2.0\nwall_height = 3.0\nceiling = \"flat\"\n\
                [[balloons]]\ncount = 5\n\
                [[balloons]]\ncount = 400\n[balloons.ribbon]\nlength_m = 1.2\nweight_g = 35\n";
    let scene = Scene::from_toml_str(text, "hang.toml").unwrap();
    let e = build_world(&scene).err().expect("does not fit");
    assert_eq!(e.key(), Some("balloons[1].count"));
    let text = e.to_string();
    assert!(
        text.contains("2.00 m × 2.00 m and 3.00 m high")
            && text.contains("staggered layers")
            && text.contains("found 400"),
        "{text}"
    );
    // How many fit: as many as the message says, and laid clean.
    let fit: u64 = text
        .split("at most ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{text}"));
    assert!(fit > 16 && fit < 400, "{text}");
    let scene = Scene::from_toml_str(
        &format!(
            "[room]\nwidth = 2.0\ndepth = 2.0\nwall_height = 3.0\nceiling = \"flat\"\n\
             [[balloons]]\ncount = 5\n\
             [[balloons]]\ncount = {fit}\n[balloons.ribbon]\nlength_m = 1.2\nweight_g = 35\n"
        ),
        "hang.toml",
    )
    .unwrap();
    let mut built = build_world(&scene).unwrap();
    assert_eq!(built.group_bodies[1].len() as u64, fit);
    assert_eq!(built.world.max_penetration_now(), 0.0);
    assert_hung_clear(&built, 1, 1.0);
}
