//! The teaching scenes (`assets/scenes/learn-*.toml`) do what their captions
//! say, and the `[about]` table that carries the captions is checked.

mod common;
use common::asset;

use glam::Vec3;
use up_physics::{BodyId, ForceProbe, World};
use up_scene::build::{build_world, BuiltScene};
use up_scene::scene::Scene;

fn build(name: &str) -> BuiltScene {
    let scene = Scene::from_path(asset(name)).unwrap_or_else(|e| panic!("{e}"));
    let about = scene.about.as_ref().expect("a teaching scene has [about]");
    assert!(
        !about.title.is_empty() && about.caption.len() > 200,
        "{about:?}"
    );
    assert!(scene.to_json_string().unwrap().contains("\"about\""));
    build_world(&scene).unwrap_or_else(|e| panic!("{e}"))
}

fn run(world: &mut World, seconds: f32) {
    let steps = (seconds / world.def().dt).round() as usize;
    for _ in 0..steps {
        world.step();
    }
}

fn height(world: &World, id: BodyId) -> f32 {
    world.center_of_mass(id).unwrap().y
}

#[test]
fn every_learn_scene_has_a_caption_and_the_menu_finds_five() {
    let dir = asset("");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("learn-") && n.ends_with(".toml"))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "learn-cold-room.toml",
            "learn-fan-hover.toml",
            "learn-helium-and-air.toml",
            "learn-terminal-speed.toml",
            "learn-throw.toml"
        ]
    );
    for name in names {
        build(&name);
    }
}

#[test]
fn the_single_balloon_climbs_at_its_terminal_speed() {
    let mut built = build("learn-terminal-speed.toml");
    let world = &mut built.world;
    let id = world.body_ids()[0];
    run(world, 4.0);
    let y0 = height(world, id);
    run(world, 4.0);
    let measured = (height(world, id) - y0) / 4.0;
    let predicted = world.terminal_speed(id).unwrap();
    println!("terminal: {measured} m/s, predicted {predicted} m/s");
    assert!(
        (measured - predicted).abs() <= 0.02 * predicted,
        "rose at {measured} m/s, terminal speed {predicted} m/s"
    );
}

/// The fan's jet rises as fast as the balloon falls through still air at
/// the height on its axis the caption says it hovers at, and faster where
/// it starts.
/// (That it then hovers there is the drag's to show: the physics tests'.)
#[test]
fn the_fan_blows_up_as_fast_as_the_balloon_falls_where_the_caption_says_it_hovers() {
    let built = build("learn-fan-hover.toml");
    let world = &built.world;
    let id = world.body_ids()[0];
    let sinks_at = world.terminal_speed(id).unwrap();
    let start = world.center_of_mass(id).unwrap();
    let fan = &world.air_flow().jets[0];
    let rising = |y: f32| {
        world
            .air_velocity_at(Vec3::new(fan.outlet.x, y, fan.outlet.z))
            .y
    };
    assert!(
        rising(start.y) > 1.5 * sinks_at,
        "it starts where the air lifts it"
    );
    // Bisection up the axis: the air slows with height past the core.
    let (mut lo, mut hi) = (start.y, built.room.bounds().max.y);
    assert!(
        rising(hi) < sinks_at,
        "the jet is slower than that under the ceiling"
    );
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if rising(mid) > sinks_at {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let hover = 0.5 * (lo + hi);
    println!(
        "fan hover: sinks at {sinks_at:.3} m/s in still air; the jet rises that fast \
         {hover:.3} m up, {:.3} m above the outlet",
        hover - fan.outlet.y
    );
    let caption = &built_caption("learn-fan-hover.toml");
    let said = format!("{:.2} m/s", sinks_at);
    assert!(
        caption.contains(&said),
        "the caption gives {said}: {caption}"
    );
    let said = format!("{:.1} m up", hover);
    assert!(
        caption.contains(&said),
        "the caption gives {said}: {caption}"
    );
    let radius = 0.5 * 0.28;
    assert!(
        hover + radius < built.room.bounds().max.y - 0.5,
        "clear of the ceiling"
    );
}

fn built_caption(name: &str) -> String {
    let scene = Scene::from_path(asset(name)).unwrap();
    scene.about.unwrap().caption
}

#[test]
fn the_helium_balloon_rises_and_the_air_balloon_falls() {
    let mut built = build("learn-helium-and-air.toml");
    let world = &mut built.world;
    let (helium, air) = (world.body_ids()[0], world.body_ids()[1]);
    assert_eq!(world.gas(helium).unwrap().air_mol, 0.0);
    assert_eq!(world.gas(air).unwrap().helium_mol, 0.0);
    let (h0, a0) = (height(world, helium), height(world, air));
    world.set_force_probe(ForceProbe::All);
    run(world, 0.5);
    for (id, sign) in [(helium, 1.0), (air, -1.0)] {
        let f = world.probed_forces(id).unwrap();
        assert!(sign * (f.weight + f.buoyancy).y > 0.0, "{f:?}");
    }
    run(world, 3.0);
    assert!(height(world, helium) > h0 + 1.0, "the helium balloon rose");
    assert!(height(world, air) < a0 - 0.8, "the air balloon fell");
}

#[test]
fn the_cold_room_shrinks_every_balloon_by_the_ratio_of_temperatures() {
    let mut built = build("learn-cold-room.toml");
    let world = &mut built.world;
    let ids = world.body_ids().to_vec();
    let (warm, cold) = (40.0 + 273.15, -40.0 + 273.15);
    assert!((world.air().temperature_k - warm).abs() < 1e-3);
    run(world, 10.0);
    let volume =
        |w: &World| -> Vec<f32> { ids.iter().map(|&id| w.body_volume(id).unwrap()).collect() };
    let lift = |w: &World| -> Vec<f32> { ids.iter().map(|&id| w.free_lift(id).unwrap()).collect() };
    let heights = |w: &World| -> Vec<f32> { ids.iter().map(|&id| height(w, id)).collect() };
    let (v0, l0, y0) = (volume(world), lift(world), heights(world));
    let t0 = world.air().temperature_k;
    run(world, 60.0);
    assert!((world.air().temperature_k - cold).abs() < 1e-3);
    let (v1, l1, y1) = (volume(world), lift(world), heights(world));
    let ceiling = built.room.bounds().max.y;
    for k in 0..ids.len() {
        let ratio = v1[k] / v0[k];
        let charles = cold / t0;
        assert!(
            (ratio - charles).abs() <= 0.01 * charles,
            "balloon {k}: volume × {ratio}, T₁/T₀ = {charles}"
        );
        assert!(
            (l1[k] - l0[k]).abs() <= 0.01 * l0[k].abs(),
            "balloon {k}: lift {} kg then {} kg",
            l0[k],
            l1[k]
        );
        if l0[k] > 0.0 {
            assert!(y1[k] > ceiling - 0.3, "helium {k} stays up: {}", y1[k]);
        } else {
            assert!(
                y1[k] < y0[k] - 0.01,
                "air {k} settles lower: {} to {}",
                y0[k],
                y1[k]
            );
        }
    }
}

#[test]
fn the_thrown_balloon_hits_the_wall_hard_and_bounces() {
    let mut built = build("learn-throw.toml");
    let world = &mut built.world;
    let id = world.body_ids()[0];
    let weight = world.body_mass(id).unwrap() * 9.81;
    let dt = world.def().dt;
    let (mut hardest, mut normal) = (0.0f32, Vec3::ZERO);
    for _ in 0..30 {
        world.step();
        for c in world
            .contact_points()
            .filter(|c| c.body_a == id && c.body_b.is_none())
        {
            if c.normal_impulse / dt > hardest {
                (hardest, normal) = (c.normal_impulse / dt, c.normal);
            }
        }
    }
    println!(
        "throw: the wall pushed {hardest} N ({} weights)",
        hardest / weight
    );
    assert!(
        hardest > 20.0 * weight,
        "{hardest} N against a weight of {weight} N"
    );
    assert!(normal.x > 0.9, "the wall at +x: {normal}");
    assert!(
        world.linear_velocity(id).unwrap().x < 0.0,
        "it bounced back"
    );
}

#[test]
fn about_is_checked_like_every_other_key() {
    let cases = [
        ("title = \"\"\ncaption = \"c\"", "about.title", "one line"),
        (
            "title = \"a\\nb\"\ncaption = \"c\"",
            "about.title",
            "one line",
        ),
        (
            "title = \"t\"\ncaption = \"one\\n\\ntwo\"",
            "about.caption",
            "one paragraph",
        ),
        ("title = \"t\"", "about", "caption"),
        (
            "title = \"t\"\ncaption = \"c\"\nauthor = \"x\"",
            "about.author",
            "unknown field",
        ),
    ];
    for (table, key, says) in cases {
        let text = format!("[about]\n{table}\n");
        let e = Scene::from_toml_str(&text, "about.toml").unwrap_err();
        assert_eq!(e.key(), Some(key), "{table}: {e}");
        assert!(e.to_string().contains(says), "{table}: {e}");
    }
    let long = "x".repeat(up_scene::scene::MAX_CAPTION_CHARS + 1);
    let text = format!("[about]\ntitle = \"t\"\ncaption = \"{long}\"\n");
    let e = Scene::from_toml_str(&text, "about.toml").unwrap_err();
    assert_eq!(e.key(), Some("about.caption"));
    let ok = Scene::from_toml_str("[about]\ntitle = \"t\"\ncaption = \"c\"\n", "ok.toml").unwrap();
    assert_eq!(ok.about.unwrap().title, "t");
}
