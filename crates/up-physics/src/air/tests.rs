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

/// The round jet as the module's documentation writes it, term by term in
/// f64: a reference for the evaluation's cheaper forms.
fn textbook_jet(jet: &Jet, p: Vec3) -> [f64; 3] {
    let (d, u0) = (f64::from(jet.diameter), f64::from(jet.speed));
    let (b, s, x0) = (
        f64::from(JET_DECAY_B),
        f64::from(JET_SPREAD_S),
        f64::from(JET_VIRTUAL_ORIGIN_D) * d,
    );
    let aim = jet.direction.as_dvec3();
    let offset = (p - jet.outlet).as_dvec3();
    let x = offset.dot(aim);
    if x <= 0.0 {
        return [0.0; 3];
    }
    let across = offset - x * aim;
    let r = across.length();
    let core = x0 + b * d;
    let r_half = if x >= core {
        s * (x - x0)
    } else {
        0.5 * d + (s * (core - x0) - 0.5 * d) * x / core
    };
    let inside = (-core::f64::consts::LN_2 * (r / r_half).powi(2)).exp();
    let centreline = if x <= core { u0 } else { u0 * b * d / (x - x0) };
    // (dQ/dx)/(2π·r), faded inside the jet; none on the axis itself.
    let flow_growth = 0.32 * u0 * (core::f64::consts::PI * d * d / 4.0) / d;
    let inflow = if r > 0.0 {
        flow_growth / (2.0 * core::f64::consts::PI * r) * (1.0 - inside) * across / r
    } else {
        across
    };
    (centreline * inside * aim - inflow).to_array()
}

#[test]
fn the_cheaper_evaluation_is_the_textbook_jet_to_within_rounding() {
    let jets = [
        fan(),
        Jet::new(
            JetKind::Vent,
            Vec3::new(1.0, 2.5, -0.5),
            Vec3::new(0.1, -1.0, 0.2),
            0.25,
            2.0,
        ),
        Jet::new(
            JetKind::Fan,
            Vec3::ZERO,
            Vec3::new(1.0, 0.25, 0.4),
            3.0,
            30.0,
        ),
    ];
    let mut checked = [0usize; 2];
    for jet in &jets {
        // A lattice through the core, the far jet, the bell's edge, beside and behind the outlet.
        for i in 0..41 {
            for j in 0..21 {
                for k in 0..21 {
                    let p = jet.outlet
                        + Vec3::new(
                            (i as f32 - 5.0) * 0.37,
                            (j as f32 - 10.0) * 0.23,
                            (k as f32 - 10.0) * 0.29,
                        );
                    let got = jet.velocity_at(p, 0.0).to_array();
                    let want = textbook_jet(jet, p);
                    let speed = want.iter().map(|c| c * c).sum::<f64>().sqrt();
                    for (g, w) in got.iter().zip(want) {
                        let error = (f64::from(*g) - w).abs();
                        assert!(
                            error <= 2e-6 * speed + 1e-6,
                            "at {p} of {jet:?}: {got:?} against {want:?}"
                        );
                    }
                    checked[usize::from(speed > 0.0)] += 1;
                }
            }
        }
    }
    assert!(checked[0] > 1000 && checked[1] > 10_000, "{checked:?}");
}
