use glam::Vec3;

use super::*;

fn fan() -> Jet {
    Jet::new(JetKind::Fan, Vec3::new(0.0, 1.0, 0.0), Vec3::Z, 0.4, 3.0)
}

#[test]
fn still_air_is_zero_everywhere() {
    let air = AirFlow::default();
    assert!(air.is_still());
    assert_eq!(air.velocity_at(Vec3::new(1.0, 2.0, 3.0), 5.0), Vec3::ZERO);
}

#[test]
fn the_core_keeps_the_outlet_speed_then_the_axis_speed_falls_as_one_over_x() {
    let jet = fan();
    let on_axis = |x: f32| jet.velocity_at(jet.outlet + x * Vec3::Z, 0.0);
    assert!((on_axis(0.5).z - 3.0).abs() < 1e-5);
    for diameters in [8.0_f32, 10.0, 14.0, 20.0] {
        let x = diameters * jet.diameter;
        let expected = 3.0 * JET_DECAY_B * jet.diameter / x;
        let u = on_axis(x);
        assert!(
            (u.z - expected).abs() < 1e-4 * expected,
            "{diameters} D: {u} against {expected}"
        );
        assert!(u.x.abs() < 1e-6 && u.y.abs() < 1e-6);
    }
}

#[test]
fn at_the_half_width_the_speed_is_half_the_centrelines() {
    let jet = fan();
    let x = 12.0 * jet.diameter;
    let r = jet.half_width(x);
    assert!((r - JET_SPREAD_S * x).abs() < 1e-5);
    let centre = jet.velocity_at(jet.outlet + x * Vec3::Z, 0.0).z;
    let side = jet
        .velocity_at(jet.outlet + x * Vec3::Z + r * Vec3::X, 0.0)
        .z;
    assert!((side / centre - 0.5).abs() < 1e-4, "{side} / {centre}");
}

#[test]
fn air_flows_in_from_the_side_and_nothing_blows_behind_the_outlet() {
    let jet = fan();
    let beside = jet.velocity_at(jet.outlet + Vec3::new(1.5, 0.0, 2.0), 0.0);
    assert!(
        beside.x < 0.0,
        "entrainment draws air toward the axis: {beside}"
    );
    assert!(beside.x.abs() < 0.1, "and gently: {beside}");
    assert_eq!(jet.velocity_at(jet.outlet - Vec3::Z, 0.0), Vec3::ZERO);
}

#[test]
fn a_sweeping_fan_swings_about_the_vertical_within_its_angle() {
    let mut jet = fan();
    jet.sweep = Sweep {
        angle_rad: 90f32.to_radians(),
        period_s: 12.0,
    };
    assert!((jet.aim_at(0.0) - Vec3::Z).length() < 1e-6);
    let quarter = jet.aim_at(3.0);
    let angle = quarter.x.atan2(quarter.z).to_degrees();
    assert!((angle - 45.0).abs() < 1e-3, "{angle}");
    assert!(quarter.y.abs() < 1e-6 && (quarter.length() - 1.0).abs() < 1e-6);
}

#[test]
fn a_schedule_spins_up_and_down_smoothly() {
    let s = Schedule {
        on: vec![[5.0, 15.0]],
    };
    assert_eq!(s.level_at(4.0), 0.0);
    assert!((s.level_at(5.5) - 0.5).abs() < 1e-6);
    assert_eq!(s.level_at(10.0), 1.0);
    assert!((s.level_at(15.5) - 0.5).abs() < 1e-6);
    assert_eq!(s.level_at(17.0), 0.0);
    assert_eq!(
        Schedule {
            on: vec![[0.0, 1e9]]
        }
        .level_at(0.0),
        1.0
    );
    assert_eq!(Schedule::always().level_at(123.0), 1.0);
}

#[test]
fn a_draught_moves_air_through_its_opening_then_spreads_as_a_jet() {
    let door = Draught {
        min: Vec3::new(-0.5, 0.0, 2.9),
        max: Vec3::new(0.5, 2.0, 3.0),
        velocity: Vec3::new(0.0, 0.0, -0.8),
        schedule: Schedule {
            on: vec![[0.0, 10.0]],
        },
    };
    assert_eq!(
        door.velocity_at(Vec3::new(0.0, 1.0, 2.95), 2.0),
        door.velocity
    );
    let inside_room = door.velocity_at(Vec3::new(0.0, 1.0, 2.0), 2.0);
    assert!((inside_room.z + 0.8).abs() < 0.05, "{inside_room}");
    assert_eq!(door.velocity_at(Vec3::new(0.0, 1.0, 2.0), 20.0), Vec3::ZERO);
}

#[test]
fn validation_names_the_bad_key() {
    let mut air = AirFlow::default();
    let mut jet = fan();
    jet.diameter = 5.0;
    air.jets.push(jet);
    let err = air.validate().unwrap_err();
    assert!(err.starts_with("jets[0].diameter_m"), "{err}");
}

#[test]
fn the_steps_frozen_sources_give_the_fields_velocity_bit_for_bit() {
    let mut swept = fan();
    swept.sweep = Sweep {
        angle_rad: 1.2,
        period_s: 7.0,
    };
    swept.schedule = Schedule {
        on: vec![[2.0, 6.0]],
    };
    let flow = AirFlow {
        jets: vec![swept, fan()],
        draughts: vec![Draught {
            min: Vec3::new(-0.5, 0.0, 2.9),
            max: Vec3::new(0.5, 2.0, 3.0),
            velocity: Vec3::new(0.0, 0.0, -0.8),
            schedule: Schedule {
                on: vec![[1.0, 4.0]],
            },
        }],
    };
    let mut now = AirNow::default();
    for t in [0.0, 1.5, 2.5, 3.3, 6.4, 9.0] {
        now.refresh(&flow, t);
        for k in 0..200 {
            let p = Vec3::new(
                (k % 7) as f32 * 0.4 - 1.2,
                (k % 5) as f32 * 0.5,
                (k / 7) as f32 * 0.3 - 2.0,
            );
            let (a, b) = (now.velocity_at(p), flow.velocity_at(p, t));
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits)
            );
        }
    }
}
