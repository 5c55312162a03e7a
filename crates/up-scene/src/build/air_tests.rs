//! The scene's fans, vents and draughts reach the world as its moving air.

use glam::Vec3;
use up_physics::air::JetKind;

use super::air::air_flow;
use super::build_world;
use crate::scene::Scene;

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "air.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn build_err(scene: &Scene) -> crate::error::SceneError {
    match build_world(scene) {
        Ok(_) => panic!("expected an error building {scene:?}"),
        Err(e) => e,
    }
}

const ROOM: &str = "[room]\nwidth = 8.0\ndepth = 8.0\nwall_height = 3.0\nceiling = \"flat\"\n\
                    [[balloons]]\ncount = 2\n";

#[test]
fn fans_then_vents_then_draughts_become_the_worlds_air() {
    let text = format!(
        "{ROOM}\
         [[vents]]\nposition = [1.0, 3.0, 1.0]\n\
         [[fans]]\nposition = [0.0, 0.3, -2.5]\ndirection = [0.0, 0.0, 2.0]\ndiameter_m = 0.3\n\
         speed_m_s = 4.0\nsweep_deg = 90\nsweep_period_s = 20\non = [[2.0, 8.0]]\n\
         [[draughts]]\nmin = [-0.5, 0.0, 3.9]\nmax = [0.5, 2.0, 4.0]\nvelocity_m_s = [0.0, 0.0, -0.8]\n"
    );
    let s = scene(&text);
    let air = air_flow(&s);
    assert_eq!(air.jets.len(), 2);
    let fan = &air.jets[0];
    assert_eq!(fan.kind, JetKind::Fan);
    assert_eq!(fan.outlet, Vec3::new(0.0, 0.3, -2.5));
    assert_eq!(fan.direction, Vec3::Z, "normalised");
    assert_eq!((fan.diameter, fan.speed), (0.3, 4.0));
    assert!((fan.sweep.angle_rad - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    assert_eq!(fan.sweep.period_s, 20.0);
    assert_eq!(fan.schedule.on, vec![[2.0, 8.0]]);
    let vent = &air.jets[1];
    assert_eq!(vent.kind, JetKind::Vent);
    assert_eq!(vent.direction, Vec3::NEG_Y);
    assert_eq!((vent.diameter, vent.speed), (0.25, 2.0));
    assert!(vent.schedule.on.is_empty(), "always on");
    assert_eq!(air.draughts.len(), 1);
    assert_eq!(air.draughts[0].velocity, Vec3::new(0.0, 0.0, -0.8));
    air.validate().unwrap();

    let built = build_world(&s).unwrap();
    assert_eq!(built.world.air_flow(), &air);
    // The world reads the same field, from its clock's start; the vent's
    // own jet blows down at its outlet speed just under it.
    let under_vent = Vec3::new(1.0, 2.5, 1.0);
    assert_eq!(
        built.world.air_velocity_at(under_vent),
        air.velocity_at(under_vent, 0.0)
    );
    let own = air.jets[1].velocity_at(under_vent, 0.0);
    assert!((own - Vec3::new(0.0, -2.0, 0.0)).length() < 1e-4, "{own}");
}

#[test]
fn a_scene_without_sources_builds_still_air() {
    let built = build_world(&scene(ROOM)).unwrap();
    assert!(built.world.air_flow().is_still());
    assert_eq!(
        built.world.air_velocity_at(Vec3::new(0.0, 1.0, 0.0)),
        Vec3::ZERO
    );
}

#[test]
fn an_outlet_must_be_inside_the_room_as_built() {
    // Inside the pyramid room's box, but above its slope near a corner.
    let e = build_err(&scene("[[vents]]\nposition = [2.9, 4.0, 2.9]\n"));
    assert_eq!(e.key(), Some("vents[0].position"), "{e}");
    assert_eq!(e.line(), Some(2), "{e}");
    assert!(
        e.to_string()
            .contains("an outlet in the room, blowing into it"),
        "{e}"
    );
    // A vent set in a flat ceiling, blowing down, is in the room.
    let flat = scene("[room]\nceiling = \"flat\"\n[[vents]]\nposition = [0.0, 3.0, 0.0]\n");
    build_world(&flat).unwrap();
    // But not one set in it blowing up, out of the room.
    let up = scene(
        "[room]\nceiling = \"flat\"\n[[vents]]\nposition = [0.0, 3.0, 0.0]\ndirection = [0, 1, 0]\n",
    );
    let e = build_err(&up);
    assert_eq!(e.key(), Some("vents[0].position"), "{e}");
}
