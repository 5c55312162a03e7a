use glam::Vec3;

use super::*;
use crate::state::State;

fn default_state() -> State {
    let mut s = State::default();
    s.load_default().expect("the default scene builds");
    s
}

/// An empty default room: time runs on in jumps (`advance`) with nothing to step.
fn empty_room() -> State {
    let mut s = State::default();
    s.load_json(r#"{"balloons": [{"count": 0}]}"#)
        .expect("an empty room builds");
    s
}

fn fan(position: [f32; 3], direction: [f32; 3]) -> AirCommand {
    AirCommand::AddFan {
        fan: FanDef {
            position,
            direction,
            diameter_m: 0.4,
            speed_m_s: 3.0,
            sweep_deg: 0.0,
            sweep_period_s: 12.0,
        },
    }
}

fn sources(s: &mut State) -> Vec<Vec<f32>> {
    let n = s.write_air_sources().unwrap();
    assert_eq!(s.air.sources.len(), n * AIR_SOURCE_FLOATS);
    s.air
        .sources
        .chunks(AIR_SOURCE_FLOATS)
        .map(<[f32]>::to_vec)
        .collect()
}

#[test]
fn a_placed_fan_is_a_jet_of_the_world_and_a_row_of_its_sources() {
    let mut s = default_state();
    assert!(
        sources(&mut s).is_empty(),
        "the default room's air is still"
    );
    s.apply_air(fan([0.5, 1.0, -2.0], [0.0, 0.0, 2.0])).unwrap();
    let world = s.world().unwrap();
    assert_eq!(world.air_flow().jets.len(), 1);
    let jet = &world.air_flow().jets[0];
    assert_eq!(jet.kind, JetKind::Fan);
    assert_eq!(jet.direction, Vec3::Z, "normalised");
    let rows = sources(&mut s);
    assert_eq!(
        rows,
        vec![vec![
            SOURCE_FAN, 0.5, 1.0, -2.0, 0.0, 0.0, 1.0, 3.0, 3.0, 0.4, 0.0, 12.0
        ]]
    );
    // Its air blows where it points, as the engine's field says.
    let ahead = Vec3::new(0.5, 1.0, -1.0);
    let u = s.world().unwrap().air_velocity_at(ahead);
    assert!((u - Vec3::new(0.0, 0.0, 3.0)).length() < 1e-4, "{u}");
}

#[test]
fn a_fan_s_speed_is_set_and_it_is_removed_by_its_index() {
    let mut s = default_state();
    s.apply_air(fan([0.0, 1.0, -2.0], [0.0, 0.0, 1.0])).unwrap();
    s.apply_air(fan([1.0, 1.0, -2.0], [0.0, 0.0, 1.0])).unwrap();
    s.apply_air(AirCommand::SetFanSpeed {
        fan: 1,
        speed_m_s: 5.5,
    })
    .unwrap();
    let speeds: Vec<f32> = sources(&mut s).iter().map(|r| r[8]).collect();
    assert_eq!(speeds, vec![3.0, 5.5]);
    s.apply_air(AirCommand::RemoveFan { fan: 0 }).unwrap();
    let rows = sources(&mut s);
    assert_eq!(rows.len(), 1);
    assert_eq!(
        (rows[0][1], rows[0][8]),
        (1.0, 5.5),
        "the later fan moved down"
    );
}

#[test]
fn bad_fan_commands_are_refused_and_change_nothing() {
    let mut s = default_state();
    s.apply_air(fan([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])).unwrap();
    let before = s.world().unwrap().air_flow().clone();
    let refused = |s: &mut State, c: AirCommand| s.apply_air(c).unwrap_err().kind();
    assert_eq!(
        refused(&mut s, fan([0.0, 1.0, 50.0], [1.0, 0.0, 0.0])),
        "OutOfRange"
    );
    assert_eq!(
        refused(&mut s, fan([0.0, 1.0, 0.0], [0.0, 0.0, 0.0])),
        "OutOfRange"
    );
    assert_eq!(
        refused(&mut s, fan([f32::NAN, 1.0, 0.0], [1.0, 0.0, 0.0])),
        "BadArgument"
    );
    let mut wide = fan([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
    if let AirCommand::AddFan { fan } = &mut wide {
        fan.diameter_m = MAX_FAN_DIAMETER_M + 0.1;
    }
    assert_eq!(refused(&mut s, wide), "OutOfRange");
    let set = |fan, speed_m_s| AirCommand::SetFanSpeed { fan, speed_m_s };
    assert_eq!(
        refused(&mut s, set(0, MAX_FAN_SPEED_M_S + 1.0)),
        "OutOfRange"
    );
    assert_eq!(refused(&mut s, set(0, -1.0)), "OutOfRange");
    assert_eq!(refused(&mut s, set(3, 1.0)), "OutOfRange");
    assert_eq!(
        refused(&mut s, AirCommand::RemoveFan { fan: 1 }),
        "OutOfRange"
    );
    assert_eq!(
        refused(&mut s, AirCommand::OpenDoor { seconds: 0.0 }),
        "OutOfRange"
    );
    assert_eq!(
        refused(
            &mut s,
            AirCommand::OpenDoor {
                seconds: MAX_DOOR_S + 1.0
            }
        ),
        "OutOfRange"
    );
    assert_eq!(s.world().unwrap().air_flow(), &before);
}

#[test]
fn the_page_s_limits_are_the_scene_s() {
    let mut s = default_state();
    let mut limit = fan([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
    if let AirCommand::AddFan { fan } = &mut limit {
        fan.speed_m_s = MAX_FAN_SPEED_M_S;
        fan.diameter_m = MAX_FAN_DIAMETER_M;
        fan.sweep_deg = MAX_FAN_SWEEP_DEG;
    }
    s.apply_air(limit).unwrap();
    let mut thin = fan([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
    if let AirCommand::AddFan { fan } = &mut thin {
        fan.diameter_m = MIN_FAN_DIAMETER_M;
    }
    assert_eq!(s.apply_air(thin).unwrap_err().kind(), "OutOfRange");
    let mut swept = fan([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
    if let AirCommand::AddFan { fan } = &mut swept {
        fan.sweep_deg = MAX_FAN_SWEEP_DEG + 1.0;
    }
    assert_eq!(s.apply_air(swept).unwrap_err().kind(), "OutOfRange");
}

#[test]
fn the_room_holds_at_most_max_air_sources() {
    let mut s = default_state();
    for _ in 0..MAX_AIR_SOURCES {
        s.apply_air(fan([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])).unwrap();
    }
    let more = s.apply_air(fan([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]));
    assert_eq!(more.unwrap_err().kind(), "Full");
}

#[test]
fn the_door_lets_air_in_for_its_seconds_and_a_closed_door_is_forgotten() {
    let mut s = empty_room();
    // A source on from time 0 blows at full speed from the start (`Schedule`): open it later.
    s.advance(1.0, 1000).unwrap();
    s.apply_air(AirCommand::OpenDoor { seconds: 10.0 }).unwrap();
    let rows = sources(&mut s);
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0][0], SOURCE_DRAUGHT);
    assert_eq!(rows[0][7], 0.0, "it spins up from nothing");
    assert_eq!(rows[0][8], DOOR_SPEED_M_S);
    assert_eq!(&rows[0][4..7], &[0.0, 0.0, -1.0], "into the room");
    s.advance(5.0, 1000).unwrap();
    let world = s.world().unwrap();
    let inside = Vec3::new(0.0, 1.0, 2.0);
    let u = world.air_velocity_at(inside);
    assert!(u.z < -0.5 * DOOR_SPEED_M_S, "{u}");
    assert_eq!(sources(&mut s)[0][7], DOOR_SPEED_M_S, "full speed");
    s.advance(20.0, 1000).unwrap();
    assert_eq!(s.world().unwrap().air_velocity_at(inside), Vec3::ZERO);
    // Opened again: the closed draught goes, the new one comes.
    s.apply_air(AirCommand::OpenDoor { seconds: 10.0 }).unwrap();
    let draughts = &s.world().unwrap().air_flow().draughts;
    assert_eq!(draughts.len(), 1);
    assert!(draughts[0].schedule.on[0][0] > 20.0);
}

#[test]
fn the_grid_holds_the_field_at_its_cells_centres() {
    let mut s = default_state();
    let still = s.write_air_grid([4, 3, 5]).unwrap();
    assert!(!still.moving);
    assert_eq!(s.air.grid.len(), 4 * 3 * 5 * AIR_GRID_FLOATS);
    assert!(s.air.grid.iter().all(|&v| v == 0.0));
    s.apply_air(fan([0.0, 1.0, -2.5], [0.0, 0.0, 1.0])).unwrap();
    let grid = s.write_air_grid([4, 3, 5]).unwrap();
    assert!(grid.moving);
    let (min, max) = (Vec3::from(grid.min), Vec3::from(grid.max));
    assert_eq!(grid.dims, [4, 3, 5]);
    assert!(
        min.y <= 0.0 && max.y >= 3.0,
        "the room's bounds: {min} {max}"
    );
    let world = s.world().unwrap();
    let cell = (max - min) / Vec3::new(4.0, 3.0, 5.0);
    let mut blowing = 0;
    for (n, c) in s.air.grid.chunks(AIR_GRID_FLOATS).enumerate() {
        let (i, j, k) = (n % 4, (n / 4) % 3, n / 12);
        let centre = min + (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * cell;
        let u = world.air_velocity_at(centre);
        assert_eq!(&c[..3], &u.to_array(), "cell {i} {j} {k}");
        assert!((c[3] - u.length()).abs() < 1e-6);
        blowing += usize::from(c[2] > 0.1);
    }
    assert!(blowing > 0, "the jet crosses some cells");
    assert_eq!(
        s.write_air_grid([0, 3, 5]).unwrap_err().kind(),
        "OutOfRange"
    );
    let too_fine = [MAX_AIR_GRID_AXIS + 1, 3, 5];
    assert_eq!(s.write_air_grid(too_fine).unwrap_err().kind(), "OutOfRange");
}

#[test]
fn points_are_sampled_as_the_engine_sees_them() {
    let mut s = default_state();
    s.apply_air(fan([0.0, 1.0, -2.5], [0.0, 0.0, 1.0])).unwrap();
    let points = [0.0, 1.0, -1.0, 2.0, 2.0, 2.0];
    assert_eq!(s.write_air_at(&points).unwrap(), 2);
    let world = s.world().unwrap();
    for (p, u) in points.chunks(3).zip(s.air.points.chunks(3)) {
        let expected = world.air_velocity_at(Vec3::new(p[0], p[1], p[2]));
        assert_eq!(u, &expected.to_array());
    }
    assert_eq!(
        s.write_air_at(&[1.0, 2.0]).unwrap_err().kind(),
        "BadArgument"
    );
    assert_eq!(
        s.write_air_at(&[1.0, 2.0, f32::INFINITY])
            .unwrap_err()
            .kind(),
        "BadArgument"
    );
}

#[test]
fn the_card_gives_the_air_at_the_balloon_and_its_speed_through_it() {
    let mut s = default_state();
    s.step(2).unwrap();
    let still = s.body_card(0).unwrap();
    assert_eq!(still.air_speed_m_s, 0.0);
    assert_eq!(still.speed_through_air_m_s, still.speed_m_s);
    let world = s.world().unwrap();
    let id = world.body_ids()[0];
    let centre = world.center_of_mass(id).unwrap();
    let v = world.linear_velocity(id).unwrap();
    // A fan a metre from it on the room's side, blowing at it.
    let inward = Vec3::new(-centre.x, 0.0, -centre.z).normalize();
    let outlet = centre + inward;
    s.apply_air(fan(outlet.to_array(), (-inward).to_array()))
        .unwrap();
    let card = s.body_card(0).unwrap();
    let u = Vec3::from(card.air_velocity_m_s);
    assert!(u.dot(-inward) > 2.5, "{u}");
    assert_eq!(card.air_speed_m_s, u.length());
    assert!((card.speed_through_air_m_s - (v - u).length()).abs() < 1e-6);
}

#[test]
fn commands_read_as_the_page_writes_them() {
    let add: AirCommand = serde_json::from_str(
        r#"{"command": "add_fan", "fan": {"position": [0, 1, 0], "direction": [1, 0, 0],
            "diameter_m": 0.4, "speed_m_s": 3, "sweep_deg": 90, "sweep_period_s": 12}}"#,
    )
    .unwrap();
    assert!(matches!(add, AirCommand::AddFan { fan } if fan.sweep_deg == 90.0));
    let set: AirCommand =
        serde_json::from_str(r#"{"command": "set_fan_speed", "fan": 2, "speed_m_s": 1.5}"#)
            .unwrap();
    assert_eq!(
        set,
        AirCommand::SetFanSpeed {
            fan: 2,
            speed_m_s: 1.5
        }
    );
    let door: AirCommand =
        serde_json::from_str(r#"{"command": "open_door", "seconds": 10}"#).unwrap();
    assert_eq!(door, AirCommand::OpenDoor { seconds: 10.0 });
    assert!(serde_json::from_str::<AirCommand>(r#"{"command": "open_window"}"#).is_err());
}

#[test]
fn the_scene_keeps_the_page_s_fans_so_a_rebuilt_world_has_the_same_air() {
    // A scene with a vent of its own: a placed fan goes among the fans, before it.
    let mut s = State::default();
    s.load_json(r#"{"balloons": [{"count": 3}], "vents": [{"position": [1.0, 3.0, 1.0]}]}"#)
        .expect("a room with a vent builds");
    s.apply_air(fan([0.0, 1.0, -2.0], [0.0, 0.0, 1.0])).unwrap();
    s.apply_air(fan([1.0, 1.0, -2.0], [1.0, 0.0, 1.0])).unwrap();
    s.apply_air(AirCommand::SetFanSpeed {
        fan: 1,
        speed_m_s: 5.5,
    })
    .unwrap();
    s.apply_air(AirCommand::SetFanSpeed {
        fan: 2,
        speed_m_s: 1.5,
    })
    .unwrap();
    s.apply_air(AirCommand::RemoveFan { fan: 0 }).unwrap();
    s.apply_air(AirCommand::OpenDoor { seconds: 10.0 }).unwrap();
    let flow = s.world().unwrap().air_flow().clone();
    assert_eq!(flow.jets.len(), 2);
    assert_eq!(flow.draughts.len(), 1);
    assert_eq!((flow.jets[0].kind, flow.jets[0].speed), (JetKind::Fan, 5.5));
    assert_eq!(
        (flow.jets[1].kind, flow.jets[1].speed),
        (JetKind::Vent, 1.5)
    );

    let json = s.scene_json().unwrap();
    let mut rebuilt = State::default();
    rebuilt.load_json(&json).expect("the page's scene builds");
    assert_eq!(rebuilt.world().unwrap().air_flow(), &flow);
}
