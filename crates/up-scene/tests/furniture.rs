//! Furniture in the room (`[[furniture]]`), run: balloons let go under a
//! table stop under its top and never pass through it, not even thrown at
//! it; a balloon tied to a chair's back floats its ribbon's length above the
//! anchor, pulling with its net lift; the birthday table runs the same on
//! one, two and four threads; and a scene without furniture steps as it did.

mod common;
use common::asset;

use glam::Vec3;
use up_geom::Sphere;
use up_scene::build::furniture::YawBox;
use up_scene::build::{build_world, BuiltScene};
use up_scene::scene::Scene;

/// Balloons of `built`, each as its leaf spheres in the world frame now.
fn leaf_spheres(built: &BuiltScene) -> Vec<Vec<Sphere>> {
    let world = &built.world;
    let group = |body| up_scene::build::group_index(world.user_data(body).unwrap());
    world
        .body_ids()
        .iter()
        .map(|&body| {
            let pose = world.pose(body).unwrap();
            let scale = world.body_scale(body).unwrap_or(1.0);
            let tree = &built.balloon_models[group(body)].shape.tree;
            tree.leaf_spheres()
                .map(|s| Sphere::new(pose.transform_point(s.center * scale), s.radius * scale))
                .collect()
        })
        .collect()
}

/// How deep a sphere reaches into a box, m (≤ 0: clear of it).
fn depth_into(s: &Sphere, b: &YawBox) -> f32 {
    let local = glam::Quat::from_rotation_y(-b.yaw) * (s.center - b.center);
    let outside = (local.abs() - b.half).max(Vec3::ZERO).length();
    let inside = (local.abs() - b.half).max_element().min(0.0);
    s.radius - (outside + inside)
}

/// The deepest any balloon's leaf reaches into any piece's box now, m.
fn deepest_into_furniture(built: &BuiltScene) -> f32 {
    let boxes: Vec<&YawBox> = built.furniture.iter().flat_map(|p| &p.boxes).collect();
    leaf_spheres(built)
        .iter()
        .flatten()
        .flat_map(|s| boxes.iter().map(move |b| depth_into(s, b)))
        .fold(f32::NEG_INFINITY, f32::max)
}

fn build(text: &str) -> BuiltScene {
    let scene = Scene::from_toml_str(text, "furniture.toml").unwrap_or_else(|e| panic!("{e}"));
    build_world(&scene).unwrap_or_else(|e| panic!("{e}"))
}

/// A 2.0 m × 1.2 m table, its top from 0.71 to 0.75 m, in the original room:
/// room between its legs for two rows of balloons laid out as the builder
/// lays them (an 11″ balloon's cell is 0.4 m, its neck and knot included).
const TABLE: &str =
    "[[furniture]]\nkind = \"table\"\nposition = [0, 0, 0]\nsize = [2.0, 0.75, 1.2]\n";
/// The top's half width and half depth, m.
const HALF_TOP: [f32; 2] = [1.0, 0.6];
const UNDERSIDE: f32 = 0.71;

#[test]
fn balloons_let_go_under_a_table_stop_under_its_top_and_never_pass_through() {
    let text = format!(
        "{TABLE}[[balloons]]\ncount = 6\n\
         spawn = {{ min = [-0.85, 0.02, -0.45], max = [0.85, 0.02, 0.45] }}\n\
         [balloons.ribbon]\nlength_m = 0.4\n"
    );
    let mut built = build(&text);
    assert_eq!(built.world.body_count(), 6);
    let top = built.furniture[0].boxes[0];
    assert!((top.center.y + top.half.y - 0.75).abs() < 1e-6, "{top:?}");
    let mut deepest = f32::NEG_INFINITY;
    for step in 0..600 {
        built.world.step();
        let depth = deepest_into_furniture(&built);
        deepest = deepest.max(depth);
        // Passing through the 4 cm top means reaching into it first.
        assert!(
            depth < 0.01,
            "step {step}: a balloon {depth} m into the table"
        );
        for leaves in leaf_spheres(&built) {
            let centre = leaves.iter().map(|s| s.center).sum::<Vec3>() / leaves.len() as f32;
            let over_top = centre.x.abs() < HALF_TOP[0] && centre.z.abs() < HALF_TOP[1];
            assert!(
                !(over_top && centre.y > UNDERSIDE && centre.y < 1.2),
                "step {step}: a balloon at {centre} went up through the table"
            );
        }
    }
    // The ones still under the top touch its underside.
    let mut gaps = Vec::new();
    for leaves in leaf_spheres(&built) {
        let centre = leaves.iter().map(|s| s.center).sum::<Vec3>() / leaves.len() as f32;
        if centre.x.abs() < HALF_TOP[0] && centre.z.abs() < HALF_TOP[1] {
            let highest = leaves
                .iter()
                .map(|s| s.center.y + s.radius)
                .fold(f32::NEG_INFINITY, f32::max);
            gaps.push(UNDERSIDE - highest);
        }
    }
    println!("deepest into the table {deepest:.4} m; gaps under its top after 10 s: {gaps:?}");
    assert!(!gaps.is_empty(), "every balloon left from under the table");
    for gap in gaps {
        assert!(gap.abs() < 0.01, "a balloon {gap} m under the table's top");
    }
}

#[test]
fn balloons_thrown_at_a_table_top_and_a_chair_back_bounce_off() {
    // Up at the top's underside at 12 m/s from the floor, and across at a
    // chair's 4 cm back at 20 m/s from 0.3 m before it: they meet them at
    // 6–10 m/s (air drag slows a balloon within a metre), 10–17 cm a step,
    // so the sweep has to stop them.
    let text = format!(
        "{TABLE}[[furniture]]\nkind = \"chair\"\nposition = [2.2, 0, 0]\n\
         [[balloons]]\ncount = 1\nvelocity = [0, 12, 0]\ntilt_deg = 0\n\
         spawn = {{ min = [0, 0.02, 0], max = [0.45, 0.02, 0.45] }}\n\
         [[balloons]]\ncount = 1\nvelocity = [0, 0, -20]\ntilt_deg = 0\n\
         spawn = {{ min = [1.95, 0.5, 0.0], max = [2.45, 0.5, 0.45] }}\n"
    );
    let mut built = build(&text);
    let ids = built.world.body_ids().to_vec();
    let boxes: Vec<YawBox> = built
        .furniture
        .iter()
        .flat_map(|p| p.boxes.clone())
        .collect();
    // Each balloon's deepest reach into any box over the run, m.
    let mut deepest = [f32::NEG_INFINITY; 2];
    for step in 0..120 {
        built.world.step();
        for (k, leaves) in leaf_spheres(&built).iter().enumerate() {
            let depth = leaves
                .iter()
                .flat_map(|s| boxes.iter().map(move |b| depth_into(s, b)))
                .fold(f32::NEG_INFINITY, f32::max);
            deepest[k] = deepest[k].max(depth);
            assert!(
                depth < 0.03,
                "step {step}: balloon {k} {depth} m into a piece"
            );
        }
    }
    let under = built.world.pose(ids[0]).unwrap().position;
    let before_back = built.world.pose(ids[1]).unwrap().position;
    println!(
        "deepest into the furniture {deepest:?} m; the upward one ends at {under}, \
         the one thrown at the back at {before_back}"
    );
    // Both reached what they were thrown at.
    assert!(deepest.iter().all(|&d| d > -0.005), "{deepest:?}");
    assert!(under.y < UNDERSIDE, "{under}: through the table's top");
    // The chair's back is its −z side, from z = −0.25 to −0.21 about its middle.
    assert!(
        before_back.z > -0.21,
        "{before_back}: through the chair's back"
    );
}

#[test]
fn a_balloon_tied_to_a_chairs_back_floats_its_ribbon_above_it_pulling_with_its_lift() {
    // A chair's back reaches 0.9 m; its top middle is 2 cm in from its −z side.
    let anchor = Vec3::new(0.0, 0.9, -0.23);
    let text = "[[furniture]]\nkind = \"chair\"\nposition = [0, 0, 0]\n\
                [[balloons]]\ncount = 1\n[balloons.ribbon]\nlength_m = 1.0\n\
                anchor = [0.0, 0.9, -0.23]\n";
    let mut built = build(text);
    for _ in 0..(20 * 60) {
        built.world.step();
    }
    let world = &built.world;
    let rope = built.group_tethers[0][0];
    let [knot, fixed] = world.joint_ends(rope).unwrap();
    assert_eq!(fixed, anchor);
    let body = built.group_bodies[0][0];
    let ribbon = world.ribbon_of(body).unwrap();
    let points = world.ribbon_points(ribbon).unwrap();
    assert_eq!(*points.last().unwrap(), anchor, "the end left the chair");
    let segment = 1.0 / 16.0;
    let above = anchor + Vec3::Y;
    let g = world.def().gravity.length();
    let lift = world.free_lift(body).unwrap() * g;
    let pull = -world.ribbon_pull(ribbon).unwrap().y;
    let tension = world.joint_tension(rope).unwrap();
    println!(
        "knot {:.4} m from 1 m above the anchor, {:.4} m from it; rope {tension:.5} N + \
         ribbon {pull:.5} N against a free lift of {lift:.5} N",
        knot.distance(above),
        knot.distance(anchor)
    );
    assert!(knot.distance(above) <= segment, "knot at {knot}");
    assert!(
        tension > 0.0 && pull > 0.0,
        "slack: rope {tension} N, ribbon {pull} N"
    );
    assert!(
        (tension + pull - lift).abs() <= 0.05 * lift,
        "rope {tension} N + ribbon {pull} N, free lift {lift} N"
    );
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

#[test]
fn the_birthday_table_runs_the_same_on_one_two_and_four_threads() {
    let scene = Scene::from_path(asset("birthday.toml")).unwrap_or_else(|e| panic!("{e}"));
    let hashes: Vec<u64> = [1, 2, 4]
        .iter()
        .map(|&threads| {
            pool(threads).install(|| {
                let mut built = build_world(&scene).unwrap_or_else(|e| panic!("{e}"));
                for _ in 0..240 {
                    built.world.step();
                }
                built.world.state_hash()
            })
        })
        .collect();
    assert!(hashes.iter().all(|&h| h == hashes[0]), "{hashes:x?}");
}

#[test]
fn the_birthday_table_ends_with_its_tied_balloons_over_the_chairs_and_none_in_the_furniture() {
    let scene = Scene::from_path(asset("birthday.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut built = build_world(&scene).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(built.furniture.len(), 5);
    let mut deepest = f32::NEG_INFINITY;
    for _ in 0..(15 * 60) {
        built.world.step();
        deepest = deepest.max(deepest_into_furniture(&built));
    }
    println!("deepest any balloon reached into the furniture: {deepest:.4} m");
    assert!(deepest < 0.01, "{deepest} m into the furniture");
    let world = &built.world;
    for (group, spec) in scene.balloons.iter().enumerate() {
        let Some(anchor) = spec.ribbon.as_ref().and_then(|r| r.anchor) else {
            continue;
        };
        let ribbon = spec.ribbon.as_ref().unwrap();
        let segment = ribbon.length_m / ribbon.segments as f32;
        for &rope in &built.group_tethers[group] {
            let [knot, _] = world.joint_ends(rope).unwrap();
            let distance = knot.distance(Vec3::from_array(anchor));
            assert!(
                (distance - ribbon.length_m).abs() <= segment,
                "group {group}: knot {distance} m from its anchor on a {} m ribbon",
                ribbon.length_m
            );
        }
    }
}

#[test]
fn a_weighted_ribbon_let_down_onto_a_table_lies_on_its_top() {
    // A 40 g weight on a 0.25 m ribbon outweighs an 11″ balloon's lift: the
    // balloon sinks until the weight rests on the top, and stays there.
    let text = format!(
        "{TABLE}[[balloons]]\ncount = 1\ntilt_deg = 0\n\
         spawn = {{ min = [-0.2, 1.2, -0.2], max = [0.3, 1.2, 0.3] }}\n\
         [balloons.ribbon]\nlength_m = 0.25\nweight_g = 40\n"
    );
    let mut built = build(&text);
    let ribbon = built.world.ribbon_ids()[0];
    let start = *built.world.ribbon_points(ribbon).unwrap().last().unwrap();
    assert!(start.y > 0.8, "{start}: the weight starts over the top");
    let mut lowest = f32::INFINITY;
    for _ in 0..(8 * 60) {
        built.world.step();
        let end = *built.world.ribbon_points(ribbon).unwrap().last().unwrap();
        lowest = lowest.min(end.y);
    }
    let end = *built.world.ribbon_points(ribbon).unwrap().last().unwrap();
    let weight = up_physics::ribbon::WEIGHT_RADIUS;
    println!(
        "the weight ends at {end}, lowest {lowest:.4} m (the top at 0.75, its radius {weight})"
    );
    assert!(lowest > 0.75 + weight - 0.005, "through the top: {lowest}");
    assert!(
        (end.y - (0.75 + weight)).abs() < 0.005,
        "{end}: not resting on the top"
    );
}
