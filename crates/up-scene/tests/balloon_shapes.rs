//! Balloon shapes against physics: each shape's volume against its closed
//! form where one exists, its lift, foil shapes floating upright, two foil
//! balloons face to face at their drawn thickness, and meshes of one's own,
//! refused when broken and floating with their volume's lift when whole.
//! The fitted trees' tightness is printed for every shape (`--nocapture`).

use std::path::PathBuf;

use glam::{Quat, Vec3};
use up_geom::fit::mesh_integrals::solid_integrals;
use up_geom::Pose;
use up_physics::{BodyDef, BodyId, World};
use up_scene::balloon::foil_shape::{PAULSEN_A, PAULSEN_B};
use up_scene::balloon::BalloonModel;
use up_scene::build::{build_world, BuiltScene};
use up_scene::scene::Scene;

const GRAVITY: f32 = 9.81;

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "balloon_shapes.rs").unwrap_or_else(|e| panic!("{e}"))
}

fn built(text: &str) -> BuiltScene {
    build_world(&scene(text)).unwrap_or_else(|e| panic!("{e}"))
}

/// A tall still room with one group of `count` balloons described by `group`.
fn room_with(group: &str, count: u32) -> String {
    format!(
        "[room]\nwidth = 8.0\ndepth = 8.0\nwall_height = 40.0\nceiling = \"flat\"\n\
         [[balloons]]\ncount = {count}\n{group}\n"
    )
}

fn run(world: &mut World, seconds: f32) {
    for _ in 0..(seconds / world.def().dt).round() as usize {
        world.step();
    }
}

/// Angle between the body's +Y and the vertical, degrees.
fn tilt_deg(rotation: Quat) -> f32 {
    (rotation * Vec3::Y).y.clamp(-1.0, 1.0).acos().to_degrees()
}

fn add(world: &mut World, model: &BalloonModel, pose: Pose) -> BodyId {
    let shape = world.add_shape(model.shape.clone()).unwrap();
    world.add_body(&BodyDef::new(shape, pose)).unwrap()
}

const SHAPES: [(&str, &str); 6] = [
    ("latex 11″ round", "kind = \"latex\"\nsize_in = 11"),
    ("foil 18″ pillow", "kind = \"foil\"\nsize_in = 18"),
    (
        "foil 18″ heart",
        "kind = \"foil\"\nshape = \"heart\"\nsize_in = 18",
    ),
    (
        "foil 20″ star",
        "kind = \"foil\"\nshape = \"star\"\nsize_in = 20",
    ),
    (
        "foil 34″ digit 3",
        "kind = \"foil\"\nshape = \"digit\"\ntext = \"3\"\nsize_in = 34",
    ),
    (
        "foil 34″ digit 0",
        "kind = \"foil\"\nshape = \"digit\"\ntext = \"0\"\nsize_in = 34",
    ),
];

#[test]
fn every_shape_lifts_what_its_volume_displaces_less_its_weight() {
    for (name, group) in SHAPES {
        let b = built(&room_with(group, 0));
        let m = &b.balloon_models[0];
        let v = solid_integrals(&m.mesh.positions, &m.mesh.indices).volume;
        assert_eq!(v, m.shape.volume, "{name}");
        let lift = m.air_density * v - m.shape.mass;
        assert!((m.free_lift_kg() - lift).abs() < 1e-9, "{name}");
        println!(
            "{name}: V = {:.2} L, mass {:.1} g (film {:.1} g), free lift {:.1} g = {:.3} N, \
             tree of {} leaves, tightness {:.2}, coverage {:.3}",
            v * 1e3,
            m.shape.mass * 1e3,
            m.parts.envelope_kg * 1e3,
            lift * 1e3,
            lift * GRAVITY,
            m.fit.tree.leaves().len(),
            m.fit.tightness,
            m.fit.coverage
        );
        assert_eq!(m.fit.coverage, 1.0, "{name}");
        // Every foil shape's tree lies over its face.
        if name.starts_with("foil") {
            assert!(m.fit.axis.dot(Vec3::Z).abs() > 0.999, "{name}");
        }
        assert!(
            m.fit.tightness <= TIGHTNESS_BOUND,
            "{name}: tightness {}",
            m.fit.tightness
        );
        assert!(lift > 0.0, "{name} sinks");
    }
}

/// Union of the leaves over the volume, at most: as tight as the latex
/// balloon's tree, near enough (1.09; 1.5 for every shape).
const TIGHTNESS_BOUND: f32 = 1.5;

fn digit(d: u8) -> String {
    format!("kind = \"foil\"\nshape = \"digit\"\ntext = \"{d}\"\nsize_in = 34")
}

/// The tightness of every shape's tree, the ten digits among them
/// (`--nocapture` prints them).
#[test]
fn every_shapes_tree_is_tight() {
    let mut groups: Vec<(String, String)> = SHAPES
        .iter()
        .map(|(n, g)| (n.to_string(), g.to_string()))
        .collect();
    groups.extend((0..10).map(|d| (format!("foil 34″ digit {d}"), digit(d))));
    for (name, group) in groups {
        let b = built(&room_with(&group, 0));
        let fit = &b.balloon_models[0].fit;
        let widest = fit
            .tree
            .leaf_spheres()
            .map(|s| s.radius)
            .fold(0.0, f32::max);
        println!(
            "{name}: tightness {:.2}, {} leaves, root {:.3} m, widest leaf {:.3} m",
            fit.tightness,
            fit.tree.leaves().len(),
            fit.tree.root().sphere().radius,
            widest
        );
        assert_eq!(fit.coverage, 1.0, "{name}");
        assert!(
            fit.tightness <= TIGHTNESS_BOUND,
            "{name}: {}",
            fit.tightness
        );
    }
}

#[test]
fn a_round_foil_has_paulsens_volume_and_thickness() {
    // The flat sheet's radius a; Paulsen: r = a / A, V = (2/3) π a r²,
    // thickness 2 B r.
    let a = 0.5 * 18.0 * 0.0254;
    let r = a / PAULSEN_A;
    let disc = up_scene::balloon::foil_shape::foil_shape(
        up_scene::balloon::outline::OutlineKind::Disc,
        2.0 * a,
    )
    .unwrap();
    let v = solid_integrals(&disc.mesh.positions, &disc.mesh.indices).volume;
    let paulsen = 2.0 / 3.0 * std::f32::consts::PI * a * r * r;
    assert!((v / paulsen - 1.0).abs() < 0.01, "{v} vs {paulsen}");
    let thick = up_geom::Aabb::from_points(&disc.mesh.positions).extents().z;
    assert!(
        (thick / (2.0 * PAULSEN_B * r) - 1.0).abs() < 0.01,
        "{thick}"
    );
}

#[test]
fn an_icosphere_of_ones_own_has_the_volume_of_its_sphere() {
    let (v, t) = icosphere(0.15, 4);
    let volume = solid_integrals(&v, &t).volume;
    // The inscribed polyhedron holds a little less than the sphere: 1280
    // faces come within 1 %.
    let ball = 4.0 / 3.0 * std::f32::consts::PI * 0.15f32.powi(3);
    assert!((volume / ball - 1.0).abs() < 0.01, "{volume} vs {ball}");
}

/// A foil heart, a star and every digit let go tilted by 30° right
/// themselves, valve down, in still air: the valve sits on the lower edge
/// where it hangs the film's weight straight below the centre of buoyancy.
#[test]
fn a_foil_heart_a_star_and_every_digit_float_upright() {
    let mut groups = vec![
        "kind = \"foil\"\nshape = \"heart\"\nsize_in = 18".to_string(),
        "kind = \"foil\"\nshape = \"star\"\nsize_in = 20".to_string(),
    ];
    groups.extend((0..10).map(digit));
    for group in groups {
        let b = built(&room_with(&group, 0));
        let mut world = b.world;
        let m = &b.balloon_models[0];
        let pose = Pose {
            position: Vec3::new(0.0, 1.5, 0.0),
            rotation: Quat::from_rotation_z(30f32.to_radians()),
        };
        let id = add(&mut world, m, pose);
        run(&mut world, 12.0);
        let p = world.pose(id).unwrap();
        let tilt = tilt_deg(p.rotation);
        let valve = m.mesh.dimensions.knot_center;
        println!(
            "{group:?}: tilt {tilt:.1}° after 12 s, at y = {:.1} m; valve at x = {:+.3} m",
            p.position.y, valve.x
        );
        assert!(tilt < 10.0, "{group}: {tilt}° from upright");
        assert!(p.position.y > 3.0, "{group}: it did not rise");
    }
}

/// Two air-filled foil balloons laid flat, one on the other on the floor,
/// rest with their centres at the drawn thickness within 1 cm: two pillows,
/// two hearts, two stars (each fitted over its face).
#[test]
fn foil_balloons_face_to_face_rest_at_their_drawn_thickness() {
    for group in [
        "kind = \"foil\"\nsize_in = 18\ngas = \"air\"",
        "kind = \"foil\"\nshape = \"heart\"\nsize_in = 18\ngas = \"air\"",
        "kind = \"foil\"\nshape = \"star\"\nsize_in = 20\ngas = \"air\"",
    ] {
        face_to_face(group, 0.01);
    }
}

fn face_to_face(group: &str, within: f32) {
    let b = built(&room_with(group, 0));
    let mut world = b.world;
    let m = &b.balloon_models[0];
    let thickness = up_geom::Aabb::from_points(&m.mesh.positions).extents().z;
    // Faces up: the body's +Z to the world's +Y.
    let flat = Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2);
    let bottom = add(
        &mut world,
        m,
        Pose {
            position: Vec3::new(0.0, 0.5 * thickness + 0.03, 0.0),
            rotation: flat,
        },
    );
    let top = add(
        &mut world,
        m,
        Pose {
            position: Vec3::new(0.0, 1.5 * thickness + 0.08, 0.0),
            rotation: flat,
        },
    );
    run(&mut world, 20.0);
    let (a, b) = (world.pose(bottom).unwrap(), world.pose(top).unwrap());
    let gap = (b.position - a.position).dot(Vec3::Y);
    let along = (a.rotation * Vec3::Z).dot(Vec3::Y);
    println!(
        "{group:?} face to face: centres {gap:.4} m apart, drawn thickness {thickness:.4} m, \
         tree tightness {:.2}",
        m.fit.tightness
    );
    assert!(
        along > 0.95,
        "{group}: the bottom one turned on edge ({along})"
    );
    assert!(
        (gap - thickness).abs() <= within,
        "{group}: centres {gap} m apart against a drawn thickness of {thickness} m"
    );
}

fn icosphere(radius: f32, subdivisions: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut v: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::new();
        let mut middle = |a: u32, b: u32, v: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a as usize] + v[b as usize]) * 0.5).normalize());
                v.len() as u32 - 1
            })
        };
        for [a, b, c] in f {
            let (ab, bc, ca) = (
                middle(a, b, &mut v),
                middle(b, c, &mut v),
                middle(c, a, &mut v),
            );
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    (v.into_iter().map(|p| p * radius).collect(), f)
}

fn write_obj(name: &str, v: &[Vec3], t: &[[u32; 3]]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("up-shapes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let mut text = String::new();
    for p in v {
        text += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for f in t {
        text += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    std::fs::write(&path, text).unwrap();
    path
}

fn mesh_scene(path: &std::path::Path) -> String {
    room_with(
        &format!("kind = \"latex\"\nmesh = {:?}", path.display().to_string()),
        1,
    )
}

#[test]
fn a_broken_mesh_is_refused_naming_the_file_and_the_problem() {
    let (v, t) = icosphere(0.15, 2);
    let open = write_obj("open.obj", &v, &t[1..]);
    let inside_out: Vec<[u32; 3]> = t.iter().map(|&[a, b, c]| [a, c, b]).collect();
    let inverted = write_obj("inside-out.obj", &v, &inside_out);
    let mut nan = v.clone();
    nan[3].y = f32::NAN;
    let not_a_number = write_obj("nan.obj", &nan, &t);
    // Two faces of one triangle, back to back: closed, but nothing inside.
    let sheet = [Vec3::ZERO, Vec3::X * 0.3, Vec3::Z * 0.3];
    let degenerate = write_obj("sheet.obj", &sheet, &[[0, 1, 2], [0, 2, 1]]);
    for (path, problem) in [
        (&open, "not closed"),
        (&inverted, "inside out"),
        (&not_a_number, "finite"),
        (&degenerate, "degenerate"),
    ] {
        let error = build_world(&scene(&mesh_scene(path)))
            .err()
            .expect("refused");
        let text = error.to_string();
        println!("{text}");
        assert!(text.contains(&path.display().to_string()), "{text}");
        assert!(text.contains(problem), "{text}");
        assert!(text.contains("balloons[0].mesh"), "{text}");
    }
}

/// A sphere of one's own rises at the speed its volume's lift gives:
/// `sqrt(2 g (ρV − m) / (ρ C_D A))` (A its section).
#[test]
fn a_mesh_of_ones_own_floats_with_the_lift_its_volume_gives() {
    let (v, t) = icosphere(0.15, 3);
    let path = write_obj("sphere.obj", &v, &t);
    let b = built(&mesh_scene(&path));
    let m = &b.balloon_models[0];
    let volume = solid_integrals(&v, &t).volume;
    assert_eq!(m.shape.volume, volume);
    // The knot at the lowest point.
    let lowest = v.iter().map(|p| p.y).fold(f32::MAX, f32::min);
    assert!(
        (m.mesh.dimensions.knot_center.y - m.mesh.dimensions.knot_radius - lowest).abs() < 1e-6
    );
    let mut world = b.world;
    let id = b.group_bodies[0][0];
    run(&mut world, 6.0);
    let rising = world.linear_velocity(id).unwrap().y;
    let expected = m.terminal_velocity(GRAVITY, world.def().drag_coefficient);
    println!(
        "sphere of one's own: V = {:.2} L, free lift {:.1} g, rises at {rising:.3} m/s \
         (expected {expected:.3})",
        volume * 1e3,
        m.free_lift_kg() * 1e3
    );
    assert!(expected > 0.5, "{expected}");
    assert!(
        (rising / expected - 1.0).abs() < 0.05,
        "{rising} vs {expected}"
    );
}

/// The mixed room (1,500 latex balloons, 200 on weighted ribbons, 300 foil
/// pillows in a 10 m room) lays every balloon it asks for: what its layers
/// cannot hold goes in the gaps between them.
#[test]
fn the_mixed_room_lays_every_balloon() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/scenes/mixed-room.toml"
    );
    let scene = Scene::from_path(path).unwrap_or_else(|e| panic!("{e}"));
    let b = build_world(&scene).unwrap_or_else(|e| panic!("{e}"));
    for (group, bodies) in scene.balloons.iter().zip(&b.group_bodies) {
        assert_eq!(bodies.len() as u64, group.count);
    }
    // Nothing starts inside anything else.
    let mut world = b.world;
    let deepest = world.max_penetration_now();
    assert!(deepest <= 0.0, "{deepest} m");
}
