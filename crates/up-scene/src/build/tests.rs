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
        ("party-fans.toml", 1000, 0),
        ("thrown.toml", 1, 0),
        ("two-gases.json", 18, 0),
        ("evening.toml", 43, 43),
        ("tied.toml", 6, 6),
        ("mixed-room.toml", 2000, 1700),
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

#[test]
fn every_balloon_is_filled_with_its_groups_envelope_and_its_own_factor() {
    use up_physics::gas::{envelope::HI_FLOAT_FACTOR, EnvelopeKind};
    let text = "[[balloons]]\ncount = 20\n\
                [[balloons]]\ncount = 10\ntreatment = \"hi-float\"\n\
                [[balloons]]\ncount = 3\nkind = \"foil\"\n\
                [[balloons]]\ncount = 4\ngas = \"air\"\n";
    let built = build_world(&scene(text)).unwrap();
    assert_eq!(built.envelopes.len(), 4);
    let base: Vec<_> = built.envelopes.iter().map(|e| e.unwrap()).collect();
    let factors = |built: &BuiltScene| -> Vec<f64> {
        built
            .group_bodies
            .iter()
            .zip(&base)
            .flat_map(|(bodies, envelope)| {
                bodies.iter().map(move |&id| {
                    let gas = built.world.gas(id).expect("every balloon has gas");
                    assert_eq!(
                        EnvelopeDef {
                            helium_permeance: envelope.helium_permeance,
                            ..gas.envelope
                        },
                        *envelope
                    );
                    gas.envelope.helium_permeance / envelope.helium_permeance
                })
            })
            .collect()
    };
    let f = factors(&built);
    assert_eq!(f.len(), 37);
    assert!(f.iter().all(|f| (0.9..=1.1).contains(f)), "{f:?}");
    // Each balloon its own: no two alike within a group.
    let mut sorted = f.clone();
    sorted.sort_by(f64::total_cmp);
    assert!(sorted.windows(2).all(|w| w[0] != w[1]));
    // The same scene gives the same factors; another seed others.
    assert_eq!(factors(&build_world(&scene(text)).unwrap()), f);
    let permeances = |built: &BuiltScene| -> Vec<f64> {
        built
            .group_bodies
            .iter()
            .flatten()
            .map(|&id| built.world.gas(id).unwrap().envelope.helium_permeance)
            .collect()
    };
    let mut other = scene(text);
    other.sim.seed = 2;
    assert_ne!(
        permeances(&build_world(&other).unwrap()),
        permeances(&built)
    );

    // Hi-Float leaks at the treatment's share of the same balloon untreated.
    assert_eq!(base[0].kind, EnvelopeKind::Latex);
    let treated = base[1].helium_permeance / base[0].helium_permeance;
    assert!((treated - HI_FLOAT_FACTOR).abs() < 1e-12, "{treated}");
    // The 18″ foil: the engine's foil at area ratio 1, its 9 g film and 1 g valve.
    let foil = EnvelopeDef::foil(base[2].solid_mass, 1.0, 1.0);
    assert_eq!(base[2], foil);
    assert!((foil.solid_mass - 0.010).abs() < 1e-7, "{foil:?}");
    // Air-filled: no helium.
    assert_eq!(base[3].helium_fraction, 0.0);
    let air_balloon = built.group_bodies[3][0];
    assert_eq!(built.world.gas(air_balloon).unwrap().helium_mol, 0.0);
    assert!(built.world.free_lift(air_balloon).unwrap() < 0.0);
    // Filled now, every helium balloon has its model's lift.
    for (g, bodies) in built.group_bodies.iter().enumerate().take(3) {
        let model_lift = built.balloon_models[g].free_lift_kg();
        for &id in bodies {
            let lift = built.world.free_lift(id).unwrap();
            assert!(lift > 0.0, "group {g}: {lift}");
            assert!(
                (lift / model_lift - 1.0).abs() < 0.1,
                "group {g}: {lift} vs {model_lift}"
            );
            let scale = built.world.body_scale(id).unwrap();
            assert!((scale - 1.0).abs() < 1e-3, "group {g}: scale {scale}");
        }
    }
}

#[test]
fn balloons_filled_ten_hours_before_lift_less() {
    // Per balloon: (free lift kg, helium mol), filled `hours` before.
    let filled = |hours: f32, kind: &str| -> Vec<(f32, f64)> {
        let text =
            format!("[[balloons]]\ncount = 6\nkind = \"{kind}\"\nfilled_hours_before = {hours}\n");
        let built = build_world(&scene(&text)).unwrap();
        built.group_bodies[0]
            .iter()
            .map(|&id| {
                let gas = built.world.gas(id).unwrap();
                (built.world.free_lift(id).unwrap(), gas.helium_mol)
            })
            .collect()
    };
    // Balloon by balloon (the same factors: same seed, same order). Latex
    // loses a good share of its lift in 10 h, and shrinks with its gas.
    let (fresh, aged) = (filled(0.0, "latex"), filled(10.0, "latex"));
    for (f, a) in fresh.iter().zip(&aged) {
        assert!(a.0 < 0.9 * f.0, "{} kg after 10 h, {} kg fresh", a.0, f.0);
        assert!(a.1 < f.1);
    }
    // Foil loses helium too, but slowly, and while it stays taut its
    // lift even rises (its volume holds, its gas weighs less).
    let (fresh, aged) = (filled(0.0, "foil"), filled(10.0, "foil"));
    for (f, a) in fresh.iter().zip(&aged) {
        assert!(
            a.1 < f.1 && a.1 > 0.99 * f.1,
            "{} mol after 10 h, {} fresh",
            a.1,
            f.1
        );
    }
    let text = "[[balloons]]\ncount = 1\nfilled_hours_before = 10\n";
    let built = build_world(&scene(text)).unwrap();
    let scale = built.world.body_scale(built.group_bodies[0][0]).unwrap();
    assert!(scale < 0.99, "scale {scale}");
}

#[test]
fn the_temperature_schedule_reaches_the_world() {
    let s = scene("[[balloons]]\ncount = 2\n[air]\ntemperature_schedule = [[0, 12], [2, 22]]\n");
    let def = world_def(&s);
    assert_eq!(
        def.temperature_schedule.points,
        vec![(0.0, 285.15), (7200.0, 295.15)]
    );
    assert!((def.atmosphere.temperature_k - 285.15).abs() < 1e-4);
    let mut built = build_world(&s).unwrap();
    assert!((built.world.air().temperature_k - 285.15).abs() < 1e-4);
    built.world.advance(3.0 * 3600.0, 10_000_000);
    let air = built.world.air();
    assert!((air.temperature_k - 295.15).abs() < 1e-3, "{air:?}");
}
