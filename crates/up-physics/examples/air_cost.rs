//! What moving air costs the step: a room of balloons (half on ribbons)
//! stepped in still air and with two fans (one sweeping), alternately, the
//! mean step time of each and their ratio, and their stages'. With `awake`
//! no body sleeps in either; with `far` no body sleeps and the fans blow
//! 50 m below the floor, every body and ribbon point evaluated in air of a
//! millimetre a second: the ratio is the field's own cost, not that of the
//! motion the fans stir.
//!
//!   cargo run -p up-physics --release --example air_cost -- [BALLOONS] [STEPS] [awake|far]

use std::time::Instant;

use glam::{Mat3, Quat, Vec3};
use up_geom::{Pose, Sphere, SphereTree, TriMesh};
use up_physics::air::{AirFlow, Jet, JetKind, Sweep};
use up_physics::ribbon::RibbonDef;
use up_physics::{BalloonShape, BodyDef, World, WorldDef};

/// The reference 11″ balloon: a head, three fillers and a neck.
fn balloon() -> BalloonShape {
    let leaves = [
        Sphere::new(Vec3::ZERO, 0.14),
        Sphere::new(Vec3::new(0.0, -0.07, 0.0), 0.115),
        Sphere::new(Vec3::new(0.0, -0.12, 0.0), 0.075),
        Sphere::new(Vec3::new(0.0, -0.16, 0.0), 0.04),
        Sphere::new(Vec3::new(0.0, -0.19, 0.0), 0.015),
    ];
    let root = Sphere::new(Vec3::new(0.0, -0.03, 0.0), 0.175);
    let tree = SphereTree::from_root_and_leaves(root, &leaves).expect("valid tree");
    BalloonShape {
        tree,
        mass: 0.00586,
        center_of_mass: Vec3::new(0.0, -0.017, 0.0),
        inertia: Mat3::from_diagonal(Vec3::splat(7e-5)),
        volume: 0.0142,
        center_of_buoyancy: Vec3::ZERO,
        reference_area: 0.0708,
    }
}

/// A box room `w` square and `h` high, normals in.
fn room(w: f32, h: f32) -> TriMesh {
    let x = w / 2.0;
    let v = vec![
        Vec3::new(-x, 0.0, -x),
        Vec3::new(x, 0.0, -x),
        Vec3::new(x, 0.0, x),
        Vec3::new(-x, 0.0, x),
        Vec3::new(-x, h, -x),
        Vec3::new(x, h, -x),
        Vec3::new(x, h, x),
        Vec3::new(-x, h, x),
    ];
    let mut t: Vec<[u32; 3]> = Vec::new();
    for [a, b, c, d] in [
        [0, 1, 2, 3],
        [0, 4, 5, 1],
        [1, 5, 6, 2],
        [2, 6, 7, 3],
        [3, 7, 4, 0],
        [4, 7, 6, 5],
    ] {
        t.extend([[a, b, c], [a, c, d]]);
    }
    let inside = Vec3::new(0.0, h / 2.0, 0.0);
    for tri in &mut t {
        let [a, b, c] = tri.map(|i| v[i as usize]);
        if (b - a).cross(c - a).dot(inside - (a + b + c) / 3.0) < 0.0 {
            tri.swap(1, 2);
        }
    }
    TriMesh::new(v, t).expect("valid room")
}

fn world(balloons: usize, fans: bool, sleep: bool, below: f32) -> World {
    let side = (balloons as f32).sqrt().ceil() as usize;
    let w = side as f32 * 0.34 + 1.0;
    let def = WorldDef {
        room: Some(room(w, 3.0)),
        enable_sleep: sleep,
        ..WorldDef::default()
    };
    let mut world = World::new(def).expect("valid world");
    let shape = world.add_shape(balloon()).expect("valid shape");
    for i in 0..balloons {
        let (x, z) = (
            (i % side) as f32 * 0.34 - w / 2.0 + 0.5,
            (i / side) as f32 * 0.34 - w / 2.0 + 0.5,
        );
        let pose = Pose::new(Vec3::new(x, 0.4, z), Quat::from_rotation_y(i as f32));
        let id = world.add_body(&BodyDef::new(shape, pose)).expect("body");
        if i % 2 == 0 {
            let ribbon = RibbonDef::new(id, Vec3::new(0.0, -0.2, 0.0), 1.0, 16);
            world.add_ribbon(&ribbon).expect("ribbon");
        }
    }
    if fans {
        let mut swept = Jet::new(
            JetKind::Fan,
            Vec3::new(0.0, 0.3 - below, -w / 2.0 + 0.2),
            Vec3::new(0.0, 0.3 * (below == 0.0) as u8 as f32, 1.0),
            0.4,
            3.0,
        );
        swept.sweep = Sweep {
            angle_rad: 1.5,
            period_s: 12.0,
        };
        let vent = if below == 0.0 {
            Jet::new(JetKind::Vent, Vec3::new(1.0, 2.9, 1.0), -Vec3::Y, 0.3, 2.0)
        } else {
            let outlet = Vec3::new(-w / 2.0 - 1.0, -below, 0.0);
            Jet::new(JetKind::Vent, outlet, Vec3::X, 0.3, 2.0)
        };
        world.set_air_flow(AirFlow {
            jets: vec![swept, vent],
            draughts: Vec::new(),
        });
    }
    world
}

fn main() {
    let mut args = std::env::args().skip(1);
    let balloons: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(2000);
    let steps: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(300);
    let mode = args.next();
    let sleep = mode.is_none();
    let below = if mode.as_deref() == Some("far") {
        50.0
    } else {
        0.0
    };
    let mut worlds = [
        world(balloons, false, sleep, below),
        world(balloons, true, sleep, below),
    ];
    // Risen and settled first, then timed in turns of 30 steps.
    for w in &mut worlds {
        for _ in 0..240 {
            w.step();
        }
    }
    let mut ms = [0.0f64; 2];
    let mut stages: [Vec<(&str, f64)>; 2] = Default::default();
    for _ in 0..steps / 30 {
        for ((w, ms), stages) in worlds.iter_mut().zip(&mut ms).zip(&mut stages) {
            let start = Instant::now();
            for _ in 0..30 {
                w.step();
                let now = w.counters().stages();
                if stages.is_empty() {
                    *stages = now.iter().map(|&(name, _)| (name, 0.0)).collect();
                }
                for (sum, (_, ms)) in stages.iter_mut().zip(now) {
                    sum.1 += ms;
                }
            }
            *ms += start.elapsed().as_secs_f64() * 1000.0;
        }
    }
    let n = (steps / 30 * 30) as f64;
    let [still, fans] = ms.map(|m| m / n);
    // The field alone: every body centre and ribbon point, sampled as a
    // step samples them (`AirFlow::velocity_at` adds each sweep's sine).
    let flow = worlds[1].air_flow().clone();
    let mut points: Vec<Vec3> = Vec::new();
    for id in worlds[1].body_ids() {
        points.push(worlds[1].center_of_mass(*id).unwrap());
    }
    for r in worlds[1].ribbon_ids() {
        points.extend_from_slice(&worlds[1].ribbon_points(r).unwrap()[1..]);
    }
    let start = Instant::now();
    let mut sum = Vec3::ZERO;
    for k in 0..20 {
        for &p in &points {
            sum += flow.velocity_at(p, k as f64);
        }
    }
    let field_ns = start.elapsed().as_secs_f64() * 1e9 / (20 * points.len()) as f64;
    println!(
        "field: {} points, {field_ns:.1} ns a point for {} sources ({:.3} ms a step's worth; {sum})",
        points.len(),
        flow.jets.len() + flow.draughts.len(),
        field_ns * points.len() as f64 * 1e-6,
    );
    let awake = worlds.map(|w| w.stats().awake_count);
    println!("stage: still air | two fans, ms a step");
    for ((name, a), (_, b)) in stages[0].iter().zip(&stages[1]) {
        let n = (steps / 30 * 30) as f64;
        println!("stage: {name} | {:.3} | {:.3}", a / n, b / n);
    }
    println!(
        "{balloons} balloons ({} on ribbons, sleep {}), {n} steps: still air {still:.3} ms \
         a step ({} awake at the end), two fans {fans:.3} ms ({} awake): ratio {:.3}",
        balloons.div_ceil(2),
        if sleep { "on" } else { "off" },
        awake[0],
        awake[1],
        fans / still
    );
}
