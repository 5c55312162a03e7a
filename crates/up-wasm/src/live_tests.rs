use super::*;
use crate::forces::FORCE_FLOATS;
use crate::state::State;

fn default_state() -> State {
    let mut s = State::default();
    s.load_default().expect("the default scene builds");
    s
}

/// Weight and buoyancy on body 0 in the last step, N (the force probe).
fn weight_and_buoyancy(s: &mut State) -> (Vec3, Vec3) {
    s.set_force_probe(0).unwrap();
    s.step(1).unwrap();
    assert_eq!(s.write_forces().unwrap(), 1);
    let f = &s.forces[..FORCE_FLOATS];
    (Vec3::new(f[1], f[2], f[3]), Vec3::new(f[4], f[5], f[6]))
}

#[test]
fn a_moon_room_s_gravity_scales_weight_buoyancy_and_net_lift() {
    let mut s = default_state();
    s.apply_live(LiveSetting::Gravity(1.62)).unwrap();
    let (weight, buoyancy) = weight_and_buoyancy(&mut s);
    let world = s.world().unwrap();
    let id = world.body_ids()[0];
    let (m, v) = (world.body_mass(id).unwrap(), world.body_volume(id).unwrap());
    let rho = world.air().air_density();
    let g = 1.62;
    // Weight m·g down, buoyancy ρ_air·V·g up; the net lift their sum.
    assert!(
        (weight - Vec3::new(0.0, -m * g, 0.0)).length() < 1e-6 * m * g.max(1.0),
        "{weight}"
    );
    assert!(
        (buoyancy - Vec3::new(0.0, rho * v * g, 0.0)).length() < 1e-4 * rho * v * g,
        "{buoyancy}"
    );
    let card = s.body_card(0).unwrap();
    let lift = rho * v * g - m * g;
    assert!(
        (card.net_lift_n - lift).abs() < 1e-3 * lift.abs(),
        "{} vs {lift}",
        card.net_lift_n
    );
    // The grams it holds up do not depend on g.
    s.apply_live(LiveSetting::Gravity(9.81)).unwrap();
    let earth = s.body_card(0).unwrap();
    assert!((earth.net_lift_n / card.net_lift_n - 9.81 / 1.62).abs() < 1e-3);
    assert!((earth.net_lift_g - card.net_lift_g).abs() < 1e-3 * earth.net_lift_g.abs());
}

#[test]
fn gravity_wakes_the_sleeping_balloons_and_the_scene_carries_it() {
    let mut s = State::default();
    s.load_toml(
        "[room]\nwidth = 1.5\ndepth = 1.5\nwall_height = 2.0\nceiling = \"flat\"\n\n\
         [[balloons]]\ncount = 6\n",
    )
    .unwrap();
    let asleep = |s: &State| {
        let w = s.world().unwrap();
        w.body_count() - w.stats().awake_count as usize
    };
    for _ in 0..600 {
        s.step(10).unwrap();
        if asleep(&s) > 0 {
            break;
        }
    }
    assert!(
        asleep(&s) > 0,
        "some balloons fell asleep under the ceiling"
    );
    s.apply_live(LiveSetting::Gravity(0.0)).unwrap();
    s.step(1).unwrap();
    assert_eq!(asleep(&s), 0, "every balloon feels the new gravity");
    assert_eq!(s.world().unwrap().def().gravity.y, 0.0);
    let scene: serde_json::Value = serde_json::from_str(&s.scene_json().unwrap()).unwrap();
    assert_eq!(scene["sim"]["gravity"], serde_json::json!([0.0, 0.0, 0.0]));
}

#[test]
fn settings_outside_their_range_are_refused_and_change_nothing() {
    let mut s = State::default();
    assert_eq!(
        s.apply_live(LiveSetting::Gravity(1.0)),
        Err(WasmError::NoWorld)
    );
    let mut s = default_state();
    for bad in [-0.1, MAX_LIVE_GRAVITY + 0.1] {
        assert!(matches!(
            s.apply_live(LiveSetting::Gravity(bad)),
            Err(WasmError::OutOfRange(_))
        ));
    }
    for bad in [f32::NAN, f32::INFINITY] {
        assert!(matches!(
            s.apply_live(LiveSetting::Gravity(bad)),
            Err(WasmError::BadArgument(_))
        ));
    }
    assert!(s.apply_live(LiveSetting::RibbonLength(-1.0)).is_err());
    assert_eq!(s.world().unwrap().def().gravity, Vec3::new(0.0, -9.81, 0.0));
    let before = s.world().unwrap().state_hash();
    s.step(1).unwrap();
    let mut fresh = default_state();
    fresh.step(1).unwrap();
    assert_ne!(before, 0);
    assert_eq!(
        s.world().unwrap().state_hash(),
        fresh.world().unwrap().state_hash()
    );
}

#[test]
fn each_setting_is_written_as_its_control_and_value() {
    for setting in LiveSetting::ALL {
        let json = serde_json::to_value(setting).unwrap();
        assert_eq!(json["control"], setting.control(), "{json}");
        assert_eq!(json["value"], 0.0);
        let back: LiveSetting = serde_json::from_value(json).unwrap();
        assert_eq!(back, setting);
    }
    let ranges = LiveSetting::ranges();
    assert_eq!(ranges.len(), LiveSetting::ALL.len());
    assert!(ranges
        .iter()
        .any(|r| r.control == "gravity" && r.min == 0.0 && r.max == MAX_LIVE_GRAVITY));
}
