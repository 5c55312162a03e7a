//! Both engines hold the same balloons, and move them alike.

use up_bench::engine::Engine;
use up_bench::measure::{escaped, max_penetration};
use up_bench::rapier_engine::{RapierEngine, RapierShape};
use up_bench::scene_data::SceneData;
use up_bench::up_engine::UpEngine;
use up_geom::Pose;

fn engines(balloons: u64) -> (SceneData, UpEngine, RapierEngine) {
    let (data, built) = SceneData::build(balloons, 3).unwrap();
    let up = UpEngine::new(built.world, 1).unwrap();
    let rapier = RapierEngine::new(&data, RapierShape::Compound).unwrap();
    (data, up, rapier)
}

fn poses(engine: &dyn Engine) -> Vec<Pose> {
    let mut out = Vec::new();
    engine.poses(&mut out);
    out
}

#[test]
fn same_bodies_total_mass_and_start_poses() {
    let (data, up, rapier) = engines(60);
    assert_eq!(up.body_count(), 60);
    assert_eq!(rapier.body_count(), 60);
    let (m_up, m_rapier) = (
        up.total_translational_mass(),
        rapier.total_translational_mass(),
    );
    assert!((m_up - m_rapier).abs() < 1e-6 * m_up, "{m_up} {m_rapier}");
    let expected = 60.0 * f64::from(data.shape.mass + data.added_mass);
    assert!(
        (m_up - expected).abs() < 1e-6 * expected,
        "{m_up} {expected}"
    );
    let (a, b) = (poses(&up), poses(&rapier));
    for (p, q) in a.iter().zip(&b) {
        assert!(p.position.distance(q.position) < 1e-5, "{p:?} {q:?}");
        assert!(p.rotation.dot(q.rotation).abs() > 1.0 - 1e-6, "{p:?} {q:?}");
    }
    // One measurement for both: the same poses give the same numbers.
    assert_eq!(
        max_penetration(&data, &a).unwrap(),
        max_penetration(&data, &b).unwrap()
    );
    assert_eq!(escaped(&data, &a), 0);
}

#[test]
fn a_free_balloon_rises_alike_in_both() {
    let (data, mut up, mut rapier) = engines(1);
    // A quarter of a second: it speeds up toward ~1.7 m/s, still clear of the ceiling.
    for _ in 0..15 {
        up.step();
        rapier.step();
    }
    let start = data.start_poses[0].position.y;
    let (a, b) = (poses(&up)[0], poses(&rapier)[0]);
    let (rise_up, rise_rapier) = (a.position.y - start, b.position.y - start);
    assert!(rise_up > 0.1, "{rise_up}");
    assert!(
        (rise_up - rise_rapier).abs() < 0.03 * rise_up,
        "UP rose {rise_up} m, Rapier {rise_rapier} m"
    );
}
