//! Ribbons tied down (`[balloons.ribbon] anchor`), run: a balloon floats at
//! its ribbon's length above the point it is tied to, pulling on it with
//! its net lift, and the example scene's balloons all end on taut ribbons.

mod common;
use common::asset;

use glam::Vec3;
use up_scene::build::{build_world, BuiltScene};
use up_scene::scene::Scene;

fn run(built: &mut BuiltScene, seconds: f32) {
    let steps = (seconds / built.world.def().dt).round() as usize;
    for _ in 0..steps {
        built.world.step();
    }
}

#[test]
fn a_balloon_tied_to_a_point_floats_its_ribbons_length_above_it_pulling_with_its_net_lift() {
    let text = "[room]\nceiling = \"flat\"\n[[balloons]]\ncount = 1\n\
                [balloons.ribbon]\nlength_m = 1.0\nanchor = [0.4, 0.5, -0.3]\n";
    let scene = Scene::from_toml_str(text, "tied.toml").unwrap();
    let mut built = build_world(&scene).unwrap();
    run(&mut built, 20.0);

    let world = &built.world;
    let anchor = Vec3::new(0.4, 0.5, -0.3);
    let rope = built.group_tethers[0][0];
    let [knot, fixed] = world.joint_ends(rope).unwrap();
    assert_eq!(fixed, anchor);
    // Straight above the point at the ribbon's length, within one segment.
    let segment = 1.0 / scene.balloons[0].ribbon.as_ref().unwrap().segments as f32;
    let above = anchor + Vec3::Y;
    assert!(
        knot.distance(above) <= segment,
        "knot at {knot}, {above} expected (off by {} m)",
        knot.distance(above)
    );

    // Taut: the rope and the ribbon (its end tied to the same point) hold
    // the balloon down together against its free lift; a free ribbon would
    // hang its own weight from the knot instead, the same law.
    let body = built.group_bodies[0][0];
    let g = world.def().gravity.length();
    let lift = world.free_lift(body).unwrap() * g;
    let ribbon = world.ribbon_of(body).unwrap();
    let pull = -world.ribbon_pull(ribbon).unwrap().y;
    let tension = world.joint_tension(rope).unwrap();
    assert!(tension > 0.0, "slack: {tension} N");
    assert!(pull > 0.0, "the ribbon pushes the knot up: {pull} N");
    assert!(
        (tension + pull - lift).abs() <= 0.03 * lift,
        "rope {tension} N + ribbon {pull} N, free lift {lift} N"
    );
}

#[test]
fn the_tied_example_ends_with_every_balloon_on_a_taut_ribbon_over_its_point() {
    let scene = Scene::from_path(asset("tied.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut built = build_world(&scene).unwrap_or_else(|e| panic!("{e}"));
    run(&mut built, 15.0);
    let world = &built.world;
    for (group, spec) in scene.balloons.iter().enumerate() {
        let ribbon = spec.ribbon.as_ref().unwrap();
        let anchor = Vec3::from_array(ribbon.anchor.unwrap());
        let segment = ribbon.length_m / ribbon.segments as f32;
        assert_eq!(built.group_tethers[group].len() as u64, spec.count);
        for &rope in &built.group_tethers[group] {
            let [knot, _] = world.joint_ends(rope).unwrap();
            let distance = knot.distance(anchor);
            assert!(
                (distance - ribbon.length_m).abs() <= segment,
                "group {group}: knot {distance} m from its anchor, ribbon {} m",
                ribbon.length_m
            );
            assert!(
                knot.y > anchor.y,
                "group {group}: knot {knot} below {anchor}"
            );
            assert!(
                world.joint_tension(rope).unwrap() > 0.0,
                "group {group}: slack"
            );
        }
    }
}
