//! How balloons stand against a ceiling, checked against the lift-centre
//! criterion (`BalloonModel::ceiling_upright_margin_m`, docs/physics.md):
//! pressed against a flat ceiling a balloon rocks on its head sphere, and
//! upright is stable only when the net lift acts above that sphere's centre.

use glam::{Quat, Vec3};
use up_geom::Pose;
use up_physics::{BodyDef, BodyId, World};
use up_scene::build::build_world;
use up_scene::scene::Scene;

/// Angle between the balloon's axis and the vertical, degrees.
fn tilt_deg(rotation: Quat) -> f32 {
    (rotation * Vec3::Y).y.clamp(-1.0, 1.0).acos().to_degrees()
}

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "ceiling_tilt.rs").expect("test scene parses")
}

fn run(world: &mut World, seconds: f32) {
    let steps = (seconds / world.def().dt).round() as usize;
    for _ in 0..steps {
        world.step();
    }
}

/// One balloon of the scene's single group, placed tilted by `tilt` degrees
/// about z with its head touching the flat ceiling at `ceiling_y`.
fn tilted_under_ceiling(text: &str, ceiling_y: f32, tilt: f32) -> (World, BodyId, f32) {
    let built = build_world(&scene(text)).expect("test scene builds");
    let mut world = built.world;
    let model = &built.balloon_models[0];
    let margin = model
        .ceiling_upright_margin_m()
        .expect("a helium balloon has a lift centre and a head sphere");
    let shape = world.add_shape(model.shape.clone()).unwrap();
    let rotation = Quat::from_rotation_z(tilt.to_radians());
    let top = model
        .shape
        .tree
        .leaves()
        .iter()
        .map(|&leaf| {
            let node = &model.shape.tree.nodes()[leaf as usize];
            (rotation * node.center).y + node.radius
        })
        .fold(f32::MIN, f32::max);
    let pose = Pose {
        position: Vec3::new(0.0, ceiling_y - top - 0.001, 0.0),
        rotation,
    };
    let id = world.add_body(&BodyDef::new(shape, pose)).unwrap();
    (world, id, margin)
}

const FLAT_ROOM: &str = "[room]\nceiling = \"flat\"\n";

#[test]
fn a_nudged_balloon_rights_itself_under_a_flat_ceiling_only_if_lift_acts_above_its_head() {
    // The default balloon: the lift centre lies 8 mm below the head sphere's
    // centre, so resting on its head is a balanced pencil.
    let default = format!("{FLAT_ROOM}[[balloons]]\ncount = 0\n");
    // A 3 g knot (or a ribbon of that weight) lowers the centre of mass far
    // enough to lift the lift centre above the head sphere's centre.
    let weighted = format!("{FLAT_ROOM}[[balloons]]\ncount = 0\nknot_mass_g = 3\n");

    let (mut world, id, margin) = tilted_under_ceiling(&default, 3.0, 25.0);
    assert!(margin < -0.004, "default margin {margin} m");
    run(&mut world, 15.0);
    let tipped = tilt_deg(world.pose(id).unwrap().rotation);
    assert!(
        tipped > 45.0,
        "the default balloon should roll over, ends at {tipped}°"
    );

    let (mut world, id, margin) = tilted_under_ceiling(&weighted, 3.0, 25.0);
    assert!(margin > 0.004, "weighted margin {margin} m");
    run(&mut world, 15.0);
    let righted = tilt_deg(world.pose(id).unwrap().rotation);
    assert!(
        righted < 5.0,
        "the weighted balloon should right itself, ends at {righted}°"
    );
}

#[test]
fn a_crowd_under_a_flat_ceiling_stays_upright() {
    // Balloons that rise upright and meet a flat ceiling squarely have nothing
    // to roll them over: the crowd ends upright even though each balloon alone
    // is only balanced there.
    let built = build_world(&scene(&format!("{FLAT_ROOM}[[balloons]]\ncount = 50\n"))).unwrap();
    let mut world = built.world;
    run(&mut world, 30.0);
    let tilts: Vec<f32> = world.poses().map(|(_, p)| tilt_deg(p.rotation)).collect();
    let upright = tilts.iter().filter(|&&t| t < 20.0).count();
    assert!(
        upright * 10 >= tilts.len() * 9,
        "{upright} of {} upright; tilts {tilts:?}",
        tilts.len()
    );
}

#[test]
fn a_lone_balloon_rolls_up_the_pyramid_and_rights_itself_in_the_apex() {
    // On the 26.6° slopes the balloon rolls (it may turn over on the way: the
    // slope needs far more margin than any balloon has), then settles in the
    // four-sided apex, where the walls of the cone hold it near upright.
    let built = build_world(&scene("[[balloons]]\ncount = 1\n")).unwrap();
    let mut world = built.world;
    let id = world.body_ids()[0];
    let mut most_tilted = 0.0f32;
    for _ in 0..(20.0 / world.def().dt) as usize {
        world.step();
        most_tilted = most_tilted.max(tilt_deg(world.pose(id).unwrap().rotation));
    }
    let pose = world.pose(id).unwrap();
    let off_axis = Vec3::new(pose.position.x, 0.0, pose.position.z).length();
    assert!(
        off_axis < 0.1,
        "should end in the apex, ends {off_axis} m off the axis"
    );
    assert!(
        most_tilted > 60.0,
        "should roll on the slope, tilted at most {most_tilted}°"
    );
    let tilt = tilt_deg(pose.rotation);
    assert!(
        tilt < 30.0,
        "should right itself in the apex, ends at {tilt}°"
    );
}
