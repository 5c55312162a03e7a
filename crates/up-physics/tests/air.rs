//! Moving air against physics (`up_physics::air`): an air-filled balloon
//! hovering above a fan where the jet's speed is its sinking speed, a
//! balloon on a weighted ribbon leaning downstream as its drag and lift
//! say, a ribbon streaming further the faster the air, a balloon turned by
//! a jet and upright again once it stops, the sleepers a fan wakes, and the
//! state with a fan: the same on any number of threads, kept by snapshots,
//! and still air the same as none.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::air::{AirFlow, Draught, Jet, JetKind, Schedule, Sweep, RESTLESS_AIR_SPEED};
use up_physics::forces::buoyancy::buoyancy_force;
use up_physics::forces::drag::drag_factor;
use up_physics::forces::gravity::gravity_force;
use up_physics::ribbon::{
    RibbonDef, AIR_VISCOSITY, DEFAULT_MASS_PER_LENGTH, NORMAL_DRAG_COEFFICIENT, RIBBON_WIDTH,
};
use up_physics::{
    BodyId, DistanceJointDef, DistanceLimit, EnvelopeDef, ForceProbe, JointAnchor, RibbonId,
    SnapshotError, World, WorldDef,
};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);
const STEPS_PER_S: usize = 60;

fn steps(world: &mut World, seconds: f32) {
    for _ in 0..(seconds * STEPS_PER_S as f32).round() as usize {
        world.step();
    }
}

/// A uniform stream of `velocity` over the whole of a room up to 10 m
/// across: inside a draught's opening the air moves at its set velocity.
fn stream(velocity: Vec3) -> AirFlow {
    AirFlow {
        jets: Vec::new(),
        draughts: vec![Draught {
            min: Vec3::new(-10.0, -1.0, -10.0),
            max: Vec3::new(10.0, 10.0, 10.0),
            velocity,
            schedule: Schedule::always(),
        }],
    }
}

/// The reference balloon filled with room air (a 3.5 g latex envelope and
/// knot), in a world with no room.
fn air_filled_balloon(at: Vec3) -> (World, BodyId) {
    let (mut world, shape) = world_with(WorldDef::default());
    let id = add(&mut world, shape, at, Quat::IDENTITY);
    let envelope = EnvelopeDef::latex(0.0035, 0.003, 0.289, 1.0, 0.0);
    world.fill(id, &envelope, 0.0).expect("valid envelope");
    (world, id)
}

/// The mean of `sample` over `seconds` of stepping.
fn mean_over(world: &mut World, seconds: f32, sample: impl Fn(&World) -> Vec3) -> Vec3 {
    let n = (seconds * STEPS_PER_S as f32).round() as usize;
    let mut sum = Vec3::ZERO;
    for _ in 0..n {
        world.step();
        sum += sample(world);
    }
    sum / n as f32
}

#[test]
fn an_air_filled_balloon_hovers_above_a_fan_where_the_jet_is_as_fast_as_it_sinks() {
    // Its sinking speed, measured: dropped in still air.
    let (mut still, id) = air_filled_balloon(Vec3::new(0.0, 100.0, 0.0));
    steps(&mut still, 10.0);
    let velocity = |w: &World| w.linear_velocity(id).unwrap();
    let sinking = -mean_over(&mut still, 2.0, velocity).y;
    let closed_form = still.terminal_speed(id).unwrap();
    assert!(sinking > 0.3, "an air-filled balloon sinks: {sinking} m/s");

    // The same balloon above a fan blowing straight up.
    let fan = Jet::new(JetKind::Fan, Vec3::ZERO, Vec3::Y, 0.3, 2.0);
    let core = fan.core_length();
    let flow = AirFlow {
        jets: vec![fan],
        draughts: Vec::new(),
    };
    // Where the jet's axis speed is the sinking speed: its centreline falls
    // as 1/x, so bisect.
    let axis_speed = |y: f32| flow.velocity_at(Vec3::new(0.0, y, 0.0), 0.0).y;
    let (mut lo, mut hi) = (core, 30.0f32);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if axis_speed(mid) > sinking {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let predicted = 0.5 * (lo + hi);
    let (mut world, id) = air_filled_balloon(Vec3::new(0.0, predicted + 0.6, 0.0));
    world.set_air_flow(flow);
    steps(&mut world, 40.0);
    let center = |w: &World| w.center_of_mass(id).unwrap();
    let rest_velocity = mean_over(&mut world, 5.0, velocity);
    let height = center(&world).y;
    let off_axis = center(&world).x.hypot(center(&world).z);
    eprintln!(
        "hover: sinks at {sinking:.4} m/s in still air (closed form {closed_form:.4}); \
         above a 0.3 m fan at 2 m/s it rests at {height:.3} m, predicted {predicted:.3} m \
         ({:+.2} %), mean vertical speed over 5 s {:.4} m/s, {off_axis:.4} m off the axis, \
         air there {:.4} m/s",
        100.0 * (height - predicted) / predicted,
        rest_velocity.y,
        world.air_velocity_at(center(&world)).y,
    );
    assert!(world.is_awake(id).unwrap(), "the air keeps it awake");
    assert!(rest_velocity.y.abs() < 0.02, "at rest: {rest_velocity}");
    assert!(
        (height - predicted).abs() < 0.1 * predicted,
        "hovers at {height} m, predicted {predicted} m"
    );
}

/// Buoyancy less weight of the reference balloon in `def`'s air, N.
fn net_lift(def: &WorldDef) -> f32 {
    let b = reference_balloon();
    let air = def.atmosphere.air_density();
    (buoyancy_force(air, b.volume, def.gravity) + gravity_force(b.mass, def.gravity)).y
}

/// A helium balloon on a ribbon of `length` m in `segments` tied to a
/// weight of `weight` kg, in a room 8 m square and 4 m high.
fn balloon_on_weight(length: f32, segments: u32, weight: f32) -> (World, BodyId, RibbonId) {
    let def = WorldDef {
        room: Some(room(8.0, 8.0, 4.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let id = add(&mut world, shape, Vec3::new(0.0, 0.9, 0.0), Quat::IDENTITY);
    let ribbon = RibbonDef {
        end_mass: weight,
        ..RibbonDef::new(id, KNOT, length, segments)
    };
    let ribbon = world.add_ribbon(&ribbon).expect("valid ribbon");
    (world, id, ribbon)
}

#[test]
fn a_balloon_on_a_weight_leans_downstream_as_its_drag_over_its_lift() {
    let (length, segments, stream_speed) = (1.0, 10, 1.0);
    let (mut world, id, ribbon) = balloon_on_weight(length, segments, 0.040);
    let end = |w: &World| *w.ribbon_points(ribbon).unwrap().last().unwrap();
    steps(&mut world, 5.0);
    world.set_air_flow(stream(Vec3::new(stream_speed, 0.0, 0.0)));
    steps(&mut world, 25.0);
    let settled_weight = end(&world);
    // Averaged over 5 s: the knot and the weight, and the air where it hangs.
    let (mut knot, mut weight) = (Vec3::ZERO, Vec3::ZERO);
    let n = 5 * STEPS_PER_S;
    for _ in 0..n {
        world.step();
        let points = world.ribbon_points(ribbon).unwrap();
        knot += points[0] / n as f32;
        weight += *points.last().unwrap() / n as f32;
        for &p in points.iter().chain([&world.center_of_mass(id).unwrap()]) {
            let u = world.air_velocity_at(p);
            assert_eq!(u, Vec3::new(stream_speed, 0.0, 0.0), "uniform at {p}");
        }
    }
    let chord = knot - weight;
    let measured = chord.x.atan2(chord.y);
    // The weight's friction on the floor is at position level: it creeps
    // downstream under the sideways pull, slowly enough to leave the lean.
    let creep = (end(&world) - settled_weight).length() / 5.0;

    // The prediction: the moments about the weight of the balloon's pull
    // at the knot (its drag k·U² and net lift), the ribbon's drag across it
    // and its weight, for a straight ribbon at θ (solved by iteration).
    let def = world.def().clone();
    let (rho, g) = (def.atmosphere.air_density(), def.gravity.length());
    let balloon = reference_balloon();
    let k = drag_factor(rho, def.drag_coefficient, balloon.reference_area);
    let drag = k * stream_speed * stream_speed;
    let lift = net_lift(&def);
    let segment = length / segments as f32;
    let q = 0.5 * rho * segment * RIBBON_WIDTH;
    let (across, viscous) = (
        q * NORMAL_DRAG_COEFFICIENT,
        q * 10.0 * (AIR_VISCOSITY / rho) / RIBBON_WIDTH,
    );
    let point_weight = DEFAULT_MASS_PER_LENGTH * segment * g;
    // The points between the ends, at s from the weight.
    let s = |i: u32| (segments - i) as f32 * segment;
    let mut theta = (drag / lift).atan();
    let (mut ribbon_drag, mut ribbon_weight) = (0.0, 0.0);
    for _ in 0..50 {
        let u_n = stream_speed * theta.cos();
        let force = (across * u_n + viscous) * u_n;
        // Moments over the ribbon's length: each the share its top carries.
        ribbon_drag = (1..segments).map(|i| force * s(i)).sum::<f32>() / length;
        ribbon_weight = (1..segments).map(|i| point_weight * s(i)).sum::<f32>() / length;
        theta = ((drag + ribbon_drag) / (lift - ribbon_weight)).atan();
    }
    let (tan_measured, tan_predicted) = (measured.tan(), theta.tan());
    eprintln!(
        "lean: in a {stream_speed} m/s stream on a {length} m ribbon and a 40 g weight, \
         tan θ = {tan_measured:.4} ({:.2}°); predicted (drag {drag:.4} + ribbon {ribbon_drag:.5} N) \
         / (net lift {lift:.4} − ribbon {ribbon_weight:.5} N) = {tan_predicted:.4} ({:.2}°), \
         {:+.2} %; the weight creeps downstream at {:.2} mm/s",
        measured.to_degrees(),
        theta.to_degrees(),
        100.0 * (tan_measured - tan_predicted) / tan_predicted,
        1000.0 * creep,
    );
    assert!(weight.y < 0.03, "the weight stays on the floor: {weight}");
    assert!(creep < 0.01, "the weight creeps at {creep} m/s");
    assert!(chord.x > 0.0, "downstream: {chord}");
    assert!(
        (tan_measured - tan_predicted).abs() < 0.1 * tan_predicted,
        "tan θ {tan_measured}, predicted {tan_predicted}"
    );
}

/// The angle from the vertical of a ribbon hanging from a balloon held at
/// its head by a fixed point, a 2 g weight at its free end, in a stream of
/// `speed` m/s along +x in a room 6 m square: degrees, and whether every
/// point stayed in the room.
fn streaming_angle(speed: f32) -> (f32, bool) {
    let (width, height) = (6.0, 4.0);
    let def = WorldDef {
        room: Some(room(width, width, height, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let head = Vec3::new(1.5, 3.2, 0.0);
    let id = add(&mut world, shape, head, Quat::IDENTITY);
    world
        .add_distance_joint(&DistanceJointDef {
            a: JointAnchor::Body {
                body: id,
                point: Vec3::ZERO,
            },
            b: JointAnchor::Fixed(head),
            length: 1e-3,
            limit: DistanceLimit::Rope,
            compliance: 0.0,
        })
        .expect("valid joint");
    let ribbon = RibbonDef {
        end_mass: 0.002,
        ..RibbonDef::new(id, KNOT, 1.2, 16)
    };
    let ribbon = world.add_ribbon(&ribbon).expect("valid ribbon");
    world.set_air_flow(stream(Vec3::new(speed, 0.0, 0.0)));
    let mut inside = true;
    let mut chord = Vec3::ZERO;
    let n = 15 * STEPS_PER_S;
    for step in 0..n {
        world.step();
        let points = world.ribbon_points(ribbon).unwrap();
        inside &= points
            .iter()
            .all(|&p| inside_room(p, width, width, height, None));
        if step >= n - 3 * STEPS_PER_S {
            chord += *points.last().unwrap() - points[0];
        }
    }
    (chord.x.atan2(-chord.y).to_degrees(), inside)
}

#[test]
fn a_ribbon_streams_further_from_the_vertical_the_faster_the_air() {
    let table: Vec<(f32, f32, bool)> = [0.5f32, 1.0, 2.0]
        .iter()
        .map(|&speed| {
            let (angle, inside) = streaming_angle(speed);
            (speed, angle, inside)
        })
        .collect();
    eprintln!("stream: speed m/s | ribbon's angle from the vertical, degrees");
    for &(speed, angle, _) in &table {
        eprintln!("stream: {speed:>4} | {angle:.2}");
    }
    for &(speed, angle, inside) in &table {
        assert!(inside, "{speed} m/s: a point left the room");
        assert!(angle > 0.0, "{speed} m/s: downstream, {angle}°");
    }
    for pair in table.windows(2) {
        assert!(pair[1].1 > pair[0].1, "grows with the speed: {table:?}");
    }
}

#[test]
fn a_balloon_in_a_jet_aimed_off_its_centre_turns_and_stands_up_again_when_it_stops() {
    // Held by a ribbon tied to a point on the floor, the balloon floats 1 m
    // up; a fan 2 m to its side blows at it for 4 s, aimed 10 cm above its
    // centre.
    let def = WorldDef {
        room: Some(room(8.0, 8.0, 4.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let id = add(&mut world, shape, Vec3::new(0.0, 1.2, 0.0), Quat::IDENTITY);
    let ribbon = RibbonDef {
        anchor: Some(Vec3::new(0.0, 0.0, 0.0)),
        ..RibbonDef::new(id, KNOT, 1.0, 10)
    };
    world.add_ribbon(&ribbon).expect("valid ribbon");
    steps(&mut world, 5.0);
    let center = world.center_of_mass(id).unwrap();
    let upright = tilt_degrees(&world, id);
    let mut fan = Jet::new(
        JetKind::Fan,
        center + Vec3::new(-2.0, 0.1, 0.0),
        Vec3::X,
        0.3,
        2.0,
    );
    let on_at = world.time();
    fan.schedule = Schedule {
        on: vec![[on_at + 0.01, on_at + 4.0]],
    };
    world.set_air_flow(AirFlow {
        jets: vec![fan],
        draughts: Vec::new(),
    });
    let (mut fastest_turn, mut most_tilt) = (0.0f32, 0.0f32);
    for _ in 0..5 * STEPS_PER_S {
        world.step();
        fastest_turn = fastest_turn.max(world.angular_velocity(id).unwrap().length());
        most_tilt = most_tilt.max(tilt_degrees(&world, id));
    }
    let air_after = world.air_velocity_at(world.center_of_mass(id).unwrap());
    steps(&mut world, 20.0);
    let (tilt_after, turn_after) = (
        tilt_degrees(&world, id),
        world.angular_velocity(id).unwrap().length(),
    );
    eprintln!(
        "turning: upright {upright:.2}°; in the jet it turned at up to {fastest_turn:.3} rad/s \
         and tilted {most_tilt:.1}°; 20 s after the fan stopped {tilt_after:.2}° at \
         {turn_after:.4} rad/s (air at it once the fan stopped: {air_after})"
    );
    assert!(fastest_turn > 0.2, "it turns: {fastest_turn} rad/s");
    assert!(most_tilt > 5.0, "it tilts: {most_tilt}°");
    assert!(tilt_after < upright + 2.0, "upright again: {tilt_after}°");
}

/// Five balloons in a row in a room 4 m square, under a fan blowing up at
/// the middle one while `on`.
fn row_under_a_fan(on: [f64; 2]) -> (World, Vec<BodyId>) {
    let def = WorldDef {
        room: Some(room(4.0, 4.0, 2.5, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let ids: Vec<BodyId> = (0..5)
        .map(|k| {
            let at = Vec3::new(k as f32 * 0.4 - 0.8, 1.5, 0.0);
            add(&mut world, shape, at, Quat::IDENTITY)
        })
        .collect();
    let mut fan = Jet::new(JetKind::Fan, Vec3::new(0.0, 0.2, 0.0), Vec3::Y, 0.4, 2.0);
    fan.schedule = Schedule { on: vec![on] };
    world.set_air_flow(AirFlow {
        jets: vec![fan],
        draughts: Vec::new(),
    });
    (world, ids)
}

#[test]
fn a_fan_switched_on_wakes_the_balloons_it_reaches_and_keeps_them_awake_until_it_stops() {
    // Up at the ceiling and asleep; the fan comes on at 15 s and goes off
    // at 25 s.
    let (mut world, ids) = row_under_a_fan([15.0, 25.0]);
    let asleep = |w: &World| ids.iter().filter(|&&id| !w.is_awake(id).unwrap()).count();
    steps(&mut world, 14.0);
    assert_eq!(asleep(&world), ids.len(), "asleep at the ceiling");
    steps(&mut world, 2.0);
    let middle = ids[2];
    let air = world.air_velocity_at(world.center_of_mass(middle).unwrap());
    assert!(air.length() > RESTLESS_AIR_SPEED, "it blows there: {air}");
    assert!(world.is_awake(middle).unwrap(), "the fan woke it");
    let mut fell_asleep = false;
    for _ in 0..8 * STEPS_PER_S {
        world.step();
        fell_asleep |= !world.is_awake(middle).unwrap();
    }
    assert!(!fell_asleep, "no sleep while the air pushes it");
    steps(&mut world, 15.0);
    eprintln!(
        "sleep: {} of {} asleep 14 s after the fan stopped",
        asleep(&world),
        ids.len()
    );
    assert!(world.is_awake(middle).is_some_and(|a| !a), "asleep again");
}

#[test]
fn the_time_lapse_does_not_jump_over_a_puff_of_air() {
    // Asleep at the ceiling by 20 s; the fan blows from 33 s to 34 s, which
    // ten-second jumps from then would pass over.
    let (mut puffed, ids) = row_under_a_fan([33.0, 34.0]);
    let (mut calm, _) = row_under_a_fan([1e6, 1e6 + 1.0]);
    let middle = ids[2];
    let (a, b) = (puffed.advance(20.0, u64::MAX), calm.advance(20.0, u64::MAX));
    assert_eq!(a, b, "the same until the puff");
    assert!(!puffed.is_awake(middle).unwrap(), "asleep by then");
    // One call: its jumps stop where the puff starts and spins up.
    let steps_puffed = puffed.advance(40.0, u64::MAX).steps;
    let steps_calm = calm.advance(40.0, u64::MAX).steps;
    eprintln!(
        "time-lapse: 20 s to 60 s in {steps_puffed} steps with the puff, {steps_calm} without"
    );
    assert!(
        steps_puffed > steps_calm + 30,
        "the puff woke them, and they were stepped while it blew"
    );
    assert!(!puffed.is_awake(middle).unwrap(), "asleep again after it");
}

#[test]
fn the_probe_gives_the_air_at_the_balloon_and_the_drag_against_it() {
    let (mut world, id) = air_filled_balloon(Vec3::new(0.0, 3.0, 0.0));
    world.set_gravity(Vec3::ZERO).unwrap();
    world.set_air_flow(stream(Vec3::new(0.5, 0.0, 0.0)));
    world.set_force_probe(ForceProbe::One(id));
    steps(&mut world, 20.0);
    let f = world.probed_forces(id).unwrap();
    assert_eq!(f.air, Vec3::new(0.5, 0.0, 0.0));
    // Carried along toward the air's speed, the drag k·|u − v|·(u − v)
    // what is left of it.
    let def = world.def().clone();
    let k = drag_factor(
        def.atmosphere.air_density(),
        def.drag_coefficient,
        reference_balloon().reference_area * world.body_scale(id).unwrap().powi(2),
    );
    let slip = f.air - world.linear_velocity(id).unwrap();
    let expected = k * slip.length() * slip;
    assert!(
        slip.x > 0.0 && slip.x < 0.1,
        "carried along: slips by {slip}"
    );
    assert!(
        (f.drag - expected).length() < 0.1 * expected.length(),
        "drag {} against k·|u − v|·(u − v) = {expected}",
        f.drag
    );
    // Held still, the air drags it downstream with k·|u|·u.
    world.set_velocity(id, Vec3::ZERO, Vec3::ZERO).unwrap();
    world.step();
    let f = world.probed_forces(id).unwrap();
    let expected = k * 0.5 * 0.5;
    assert!(
        (f.drag.x - expected).abs() < 0.1 * expected && f.drag.y.abs() < 1e-6,
        "{f:?} against {expected} N"
    );
}

/// 200 balloons, every other on a ribbon, in a room with a fan sweeping
/// across them.
fn swept_crowd() -> World {
    let def = WorldDef {
        room: Some(room(5.0, 5.0, 2.5, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    for i in 0..200 {
        let (x, z) = (
            (i % 14) as f32 * 0.33 - 2.1,
            ((i / 14) % 14) as f32 * 0.33 - 2.1,
        );
        let q = Quat::from_rotation_y(i as f32) * Quat::from_rotation_x(0.05 * (i % 5) as f32);
        let id = add(&mut world, shape, Vec3::new(x, 0.4, z), q);
        if i % 2 == 0 {
            let ribbon = RibbonDef::new(id, KNOT, 0.5, 8);
            world.add_ribbon(&ribbon).expect("valid ribbon");
        }
    }
    let mut fan = Jet::new(
        JetKind::Fan,
        Vec3::new(0.0, 0.3, -2.4),
        Vec3::new(0.0, 0.4, 1.0),
        0.4,
        3.0,
    );
    fan.sweep = Sweep {
        angle_rad: 1.5,
        period_s: 2.0,
    };
    world.set_air_flow(AirFlow {
        jets: vec![fan],
        draughts: Vec::new(),
    });
    world
}

#[cfg(feature = "parallel")]
#[test]
fn a_sweeping_fan_gives_the_same_state_on_one_and_three_threads() {
    use up_physics::divergence::lockstep_with;
    let pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool")
    };
    let (one, three) = (pool(1), pool(3));
    let (mut a, mut b) = (one.install(swept_crowd), three.install(swept_crowd));
    let parted = lockstep_with(
        &mut a,
        &mut b,
        120,
        |w| one.install(|| w.step()),
        |w| three.install(|| w.step()),
    );
    if let Some(parted) = parted {
        panic!("three threads against one: {parted}");
    }
    assert!(a.stats().awake_count > 64, "enough awake to share the step");
}

#[test]
fn a_fan_is_kept_by_snapshots_and_in_the_hash_and_still_air_is_none() {
    let mut swept = swept_crowd();
    steps(&mut swept, 1.0);
    let mut restored = World::restore(&swept.snapshot()).expect("restores");
    assert_eq!(restored.air_flow(), swept.air_flow());
    assert_eq!(restored.state_hash(), swept.state_hash());
    for _ in 0..60 {
        swept.step();
        restored.step();
    }
    assert_eq!(restored.state_hash(), swept.state_hash());

    // The sources are in the hash, and the divergence names them.
    let mut calm = swept.clone();
    calm.set_air_flow(AirFlow::default());
    assert_ne!(calm.state_hash(), swept.state_hash());
    let parted = up_physics::divergence::compare(&calm, &swept).expect("they differ");
    assert_eq!(parted.field, up_physics::divergence::Field::Air);

    // A snapshot of the format before moving air is refused as such.
    let mut old = swept.snapshot();
    old[6..8].copy_from_slice(&8u16.to_le_bytes());
    assert_eq!(
        World::restore(&old).unwrap_err(),
        SnapshotError::Version { found: 8 }
    );

    // Still air set is a world that never had any, bit for bit.
    let mut never = sixty_released();
    let mut still = sixty_released();
    still.set_air_flow(AirFlow::default());
    assert_eq!(still.state_hash(), never.state_hash());
    for _ in 0..300 {
        never.step();
        still.step();
    }
    assert_eq!(still.state_hash(), never.state_hash());
    assert_eq!(still.snapshot(), never.snapshot());
}
