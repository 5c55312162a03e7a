//! Building scenes into worlds: placement, determinism, colours, errors.

use super::*;
use crate::scene::Scene;

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "build.toml").unwrap()
}

#[test]
fn default_scene_builds_fifty_balloons_inside_the_room_without_overlap() {
    let mut built = build_world(&Scene::default()).unwrap();
    assert_eq!(built.world.body_count(), 50);
    assert_eq!(built.balloon_models.len(), 1);
    assert_eq!(built.colors.len(), 6);
    assert_eq!(built.group_bodies[0].len(), 50);
    for (_, pose) in built.world.poses() {
        assert!(built.room.contains_point(pose.position), "{pose:?} outside");
        // Released from the floor: the whole layer sits low.
        assert!(pose.position.y < 0.6, "{pose:?}");
        let tilt = (pose.rotation * Vec3::Y)
            .angle_between(Vec3::Y)
            .to_degrees();
        assert!(tilt <= 3.0 + 1e-3, "tilt {tilt}");
    }
    assert_eq!(
        built.world.max_penetration_now(),
        0.0,
        "balloons overlap at spawn"
    );
}

#[test]
fn colours_cycle_within_a_group_and_groups_are_recorded() {
    let s = scene(
        "[[balloons]]\ncount = 4\ncolors = [\"red\", \"blue\"]\n\
         [[balloons]]\ncount = 2\ncolors = [\"blue\", \"#102030\"]\n",
    );
    let built = build_world(&s).unwrap();
    assert_eq!(built.color_names, vec!["red", "blue", "#102030"]);
    let data: Vec<u32> = built
        .group_bodies
        .iter()
        .flatten()
        .map(|&id| built.world.user_data(id).unwrap())
        .collect();
    let colours: Vec<usize> = data.iter().map(|&d| color_index(d)).collect();
    let groups: Vec<usize> = data.iter().map(|&d| group_index(d)).collect();
    assert_eq!(colours, vec![0, 1, 0, 1, 1, 2]);
    assert_eq!(groups, vec![0, 0, 0, 0, 1, 1]);
}

#[test]
fn same_seed_gives_the_same_world_and_another_seed_another() {
    let hash = |seed: u64| {
        let mut s = Scene::default();
        s.sim.seed = seed;
        build_world(&s).unwrap().world.state_hash()
    };
    assert_eq!(hash(7), hash(7));
    assert_ne!(hash(7), hash(8));
}

#[test]
fn more_balloons_than_the_floor_holds_stack_in_layers() {
    let s = scene("[[balloons]]\ncount = 400\n");
    let mut built = build_world(&s).unwrap();
    assert_eq!(built.world.body_count(), 400);
    let top = built
        .world
        .poses()
        .map(|(_, p)| p.position.y)
        .fold(f32::MIN, f32::max);
    assert!(top > 0.6, "a second layer exists: top {top}");
    assert_eq!(built.world.max_penetration_now(), 0.0);
}

#[test]
fn a_count_that_does_not_fit_the_room_names_the_group() {
    let s = scene(
        "[room]\nwidth = 1.0\ndepth = 1.0\nwall_height = 1.0\nceiling = \"flat\"\n\
         [[balloons]]\ncount = 2\n[[balloons]]\ncount = 500\n",
    );
    let e = build_world(&s).err().expect("does not fit");
    assert!(
        matches!(e, SceneError::DoesNotFit { requested: 500, .. }),
        "{e}"
    );
    assert_eq!(e.key(), Some("balloons[1].count"));
    assert_eq!(e.line(), Some(9));
    assert!(
        e.to_string()
            .starts_with("build.toml:9: balloons[1].count: 500 balloons do not fit"),
        "{e}"
    );
}

#[test]
fn spawn_box_and_initial_velocity_are_honoured() {
    let s = scene(
        "[room]\nceiling = \"flat\"\n[[balloons]]\ncount = 1\nvelocity = [30.0, 0.0, 0.0]\n\
         tilt_deg = 0\nyaw_deg = 0\nspawn = { min = [-2.0, 1.0, -0.5], max = [-1.0, 2.0, 0.5] }\n",
    );
    let built = build_world(&s).unwrap();
    let id = built.group_bodies[0][0];
    let pose = built.world.pose(id).unwrap();
    let root = built.balloon_models[0].shape.tree.root().sphere();
    let centre = pose.transform_point(root.center);
    assert!(
        centre.x - root.radius >= -2.0 && centre.x + root.radius <= -1.0,
        "{centre}"
    );
    assert!(centre.y - root.radius >= 1.0, "{centre}");
    assert_eq!(pose.rotation, Quat::IDENTITY);
    assert_eq!(
        built.world.linear_velocity(id).unwrap(),
        Vec3::new(30.0, 0.0, 0.0)
    );
}

#[test]
fn missing_room_mesh_names_the_key_and_the_path() {
    let mut s = scene("[room]\nmesh = \"no-such-hall.obj\"\n");
    s.source.dir = Some(std::path::PathBuf::from("/nonexistent-dir"));
    let e = build_world(&s).err().expect("no mesh");
    let text = e.to_string();
    assert!(
        text.starts_with("build.toml:2: room.mesh: cannot build the room"),
        "{text}"
    );
    assert!(text.contains("/nonexistent-dir/no-such-hall.obj"), "{text}");
}

#[test]
fn world_def_carries_the_sim_settings() {
    let s = scene(
        "[sim]\ndt = 0.01\nsubsteps = 8\nfriction = 0.2\nsleep = false\n[air]\ntemperature_c = 0\n",
    );
    let def = world_def(&s);
    assert_eq!(
        (def.dt, def.substeps, def.friction, def.enable_sleep),
        (0.01, 8, 0.2, false)
    );
    assert!((def.atmosphere.temperature_k - 273.15).abs() < 1e-4);
}

#[test]
fn user_data_packs_group_and_colour() {
    let d = user_data_for(3, 5);
    assert_eq!((group_index(d), color_index(d)), (3, 5));
}

#[test]
fn default_group_matches_the_default_balloon_spec() {
    let spec = crate::balloon::BalloonSpec::default();
    let group = &Scene::default().balloons[0];
    assert_eq!(group.diameter(), spec.diameter_m);
    assert!((group.envelope_mass_kg() - spec.envelope_mass_kg).abs() < 1e-9);
    assert!((group.knot_mass_kg() - spec.knot_mass_kg).abs() < 1e-9);
}

#[test]
fn example_scenes_build() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes");
    // Name, balloons, ribbons.
    let expected = [
        ("default.toml", 50, 50),
        ("bouquet.toml", 6, 6),
        ("terminal-velocity.toml", 1, 0),
        ("party-hall.toml", 1000, 0),
        ("thrown.toml", 1, 0),
        ("two-gases.json", 18, 0),
    ];
    for (name, count, ribbons) in expected {
        let scene = Scene::from_path(dir.join(name)).unwrap();
        let mut built = build_world(&scene).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(built.world.body_count(), count, "{name}");
        assert_eq!(built.world.ribbon_count(), ribbons, "{name}");
        assert_eq!(
            built.world.max_penetration_now(),
            0.0,
            "{name}: overlap at spawn"
        );
    }
}
