//! `--ribbons`: the same ribbons in both engines, measured the same way.

use up_bench::engine::{Engine, EngineKind};
use up_bench::rapier_engine::{RapierEngine, RapierJoints, RapierShape};
use up_bench::ribbons::{stretch, tie_ribbons, BenchRibbons, LENGTH_M, SEGMENTS};
use up_bench::run::{run, RunOptions};
use up_bench::scene_data::SceneData;
use up_bench::up_engine::UpEngine;
use up_physics::ribbon::DEFAULT_MASS_PER_LENGTH;

fn engines(
    balloons: u64,
    joints: RapierJoints,
) -> (SceneData, BenchRibbons, UpEngine, RapierEngine) {
    let (data, mut built) = SceneData::build(balloons, 5).unwrap();
    let ribbons = tie_ribbons(&mut built.world, data.knot).unwrap();
    let up = UpEngine::new(built.world, 1).unwrap();
    let rapier =
        RapierEngine::with_ribbons(&data, RapierShape::Compound, &ribbons, joints).unwrap();
    (data, ribbons, up, rapier)
}

#[test]
fn the_knot_is_the_tip_of_the_balloons_knot() {
    let (data, _) = SceneData::build(1, 1).unwrap();
    // On the axis, at the bottom of the lowest leaf sphere (the knot's own),
    // well below the centre of mass (the balloon is 39 cm tall).
    assert_eq!((data.knot.x, data.knot.z), (0.0, 0.0));
    let lowest = data
        .leaves
        .iter()
        .map(|s| s.center.y - s.radius)
        .fold(f32::INFINITY, f32::min);
    assert!(
        (data.knot.y - lowest).abs() < 1e-4,
        "{} {lowest}",
        data.knot.y
    );
    let com = data.shape.center_of_mass;
    assert!(data.knot.y < com.y - 0.15, "{:?} {com:?}", data.knot);
}

#[test]
fn both_engines_start_with_the_same_ribbons_of_the_same_mass() {
    let (data, ribbons, up, rapier) = engines(40, RapierJoints::Impulse);
    let world = up.world();
    assert_eq!(world.ribbon_count(), 40);
    assert_eq!((up.ribbon_count(), rapier.ribbon_count()), (40, 40));
    let mut points = Vec::new();
    for (i, id) in world.ribbon_ids().into_iter().enumerate() {
        let ours = world.ribbon_points(id).unwrap();
        assert_eq!(ours.len(), SEGMENTS as usize + 1);
        assert_eq!(ours, &ribbons.starts[i][..]);
        // Tied at the knot of its balloon.
        let pose = data.start_poses[i];
        assert!(ours[0].distance(pose.transform_point(data.knot)) < 1e-5);
        rapier.ribbon_points(i, &mut points);
        assert_eq!(points.len(), ours.len());
        for (a, b) in points.iter().zip(ours) {
            assert!(a.distance(*b) < 1e-5, "balloon {i}: {a} {b}");
        }
        let (length, mass) = world.ribbon_length_and_mass(id).unwrap();
        assert!((length - LENGTH_M).abs() < 1e-6);
        let expected = DEFAULT_MASS_PER_LENGTH * LENGTH_M;
        assert!((mass - expected).abs() < 1e-3 * expected, "{mass}");
        assert!(
            (rapier.ribbon_mass(i) - mass).abs() < 1e-3 * mass,
            "{}",
            rapier.ribbon_mass(i)
        );
    }
    // 16 balls and 16 joints a balloon.
    let (bodies, impulse, multibodies) = rapier.counts();
    assert_eq!((bodies, impulse, multibodies), (40 * 17, 40 * 16, 0));
    let mut scratch = Vec::new();
    let (a, b) = (
        up.max_ribbon_stretch(&mut scratch).unwrap(),
        rapier.max_ribbon_stretch(&mut scratch).unwrap(),
    );
    assert!((a - b).abs() < 1e-5, "{a} {b}");
}

#[test]
fn the_chains_hold_and_stretch_is_measured_as_the_engine_does() {
    let (_, ribbons, mut up, mut rapier) = engines(40, RapierJoints::Impulse);
    let mut scratch = Vec::new();
    let (mut worst_up, mut worst_rapier) = (f32::MIN, f32::MIN);
    for _ in 0..90 {
        up.step();
        rapier.step();
        worst_up = worst_up.max(up.max_ribbon_stretch(&mut scratch).unwrap());
        worst_rapier = worst_rapier.max(rapier.max_ribbon_stretch(&mut scratch).unwrap());
    }
    // The world keeps the largest stretch any ribbon ended a step with.
    let own = up.world().ribbon_max_stretch();
    assert!(
        (worst_up - own).abs() < 1e-6,
        "measured {worst_up}, UP's own {own}"
    );
    // Rapier's chains hold: with the balls' own inertia instead of their
    // segments', they flew apart to 15 times their length within a second.
    assert!(
        worst_rapier.is_finite() && worst_rapier < 0.5,
        "{worst_rapier}"
    );
    let mut points = Vec::new();
    rapier.ribbon_points(0, &mut points);
    let now = stretch(points.iter().copied(), ribbons.length);
    assert!(now <= worst_rapier && now > -0.5, "{now}");
}

#[test]
fn multibody_chains_keep_their_length() {
    let (_, _, _, mut rapier) = engines(3, RapierJoints::Multibody);
    let (_, impulse, multibodies) = rapier.counts();
    assert_eq!((impulse, multibodies), (0, 3));
    let mut scratch = Vec::new();
    let mut worst = f32::MIN;
    for _ in 0..30 {
        rapier.step();
        worst = worst.max(rapier.max_ribbon_stretch(&mut scratch).unwrap());
    }
    // Reduced coordinates: the links cannot come apart.
    assert!(worst.abs() < 1e-3, "{worst}");
}

#[test]
fn a_run_with_ribbons_has_up_without_them_beside() {
    let results = run(&RunOptions {
        balloons: 20,
        steps: 70,
        seed: 2,
        threads: 1,
        engines: vec![EngineKind::Up, EngineKind::Rapier],
        rapier_shape: RapierShape::Compound,
        rss: false,
        step_times: None,
        ribbons: true,
        rapier_joints: RapierJoints::Impulse,
        thread_times: false,
    })
    .unwrap();
    assert_eq!(results.len(), 3);
    let (up, rapier, bare) = (&results[0], &results[1], &results[2]);
    assert_eq!((up.engine.as_str(), up.ribbons), ("up", 20));
    assert_eq!((rapier.engine.as_str(), rapier.ribbons), ("rapier", 20));
    assert_eq!(rapier.rapier_joints.as_deref(), Some("impulse"));
    assert_eq!((bare.engine.as_str(), bare.ribbons), ("up", 0));
    for r in [up, rapier] {
        let all = r.max_ribbon_stretch.unwrap();
        let late = r.max_ribbon_stretch_after_start.unwrap();
        assert!(all.is_finite() && late <= all, "{r:?}");
        assert!((1..=70).contains(&r.max_ribbon_stretch_step.unwrap()));
    }
    assert_eq!(bare.max_ribbon_stretch, None);
    assert!(up.stage_ms_mean.is_some() && bare.stage_ms_mean.is_some());
    assert!(rapier.stage_ms_mean.is_none());
    // The same balloons in all three.
    assert!(results.iter().all(|r| r.balloons == 20 && r.escaped == 0));
}
