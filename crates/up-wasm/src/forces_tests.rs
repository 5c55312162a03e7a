use super::*;
use crate::state::State;

/// The two-gases scene: helium balloons, then air-filled ones.
const TWO_GASES: &str = include_str!("../../../assets/scenes/two-gases.json");

fn loaded() -> State {
    let mut s = State::default();
    s.load_json(TWO_GASES).expect("the two-gases scene builds");
    s
}

fn floats(s: &State, body: usize) -> &[f32] {
    &s.forces[body * FORCE_FLOATS..(body + 1) * FORCE_FLOATS]
}

fn vec(f: &[f32], k: usize) -> Vec3 {
    Vec3::new(f[1 + 3 * k], f[2 + 3 * k], f[3 + 3 * k])
}

#[test]
fn one_probed_body_s_forces_are_the_engine_s_packed_in_order() {
    let mut s = loaded();
    // Off by default: nothing written.
    s.step(5).unwrap();
    assert_eq!(s.write_forces().unwrap(), 0);
    s.set_force_probe(3).unwrap();
    s.step(2).unwrap();
    assert_eq!(s.write_forces().unwrap(), 1);
    let world = s.world().unwrap();
    let id = world.body_ids()[3];
    let f = world.probed_forces(id).unwrap();
    let out = floats(&s, 0);
    assert_eq!(out.len(), FORCE_FLOATS);
    assert_eq!(out[0], 3.0);
    let fields = [
        f.weight,
        f.buoyancy,
        f.drag,
        f.contact,
        f.ribbon,
        f.other,
        f.center_of_mass,
        f.center_of_buoyancy,
    ];
    for (k, v) in fields.iter().enumerate() {
        assert_eq!(vec(out, k), *v, "field {k}");
    }
    assert!(vec(out, 8).is_nan(), "no ribbon, no knot");
    s.set_force_probe(PROBE_OFF).unwrap();
    s.step(1).unwrap();
    assert_eq!(s.write_forces().unwrap(), 0);
}

#[test]
fn all_probed_a_helium_balloon_is_lifted_and_an_air_balloon_pulled_down() {
    let mut s = loaded();
    s.set_force_probe(PROBE_ALL).unwrap();
    s.step(3).unwrap();
    let n = s.write_forces().unwrap();
    assert_eq!(n, s.body_count());
    let (mut helium, mut air) = (0, 0);
    for b in 0..n {
        let out = floats(&s, b).to_vec();
        let (weight, buoyancy) = (vec(&out, 0), vec(&out, 1));
        assert!(weight.y < 0.0 && buoyancy.y > 0.0);
        let card = s.body_card(out[0] as u32).unwrap();
        assert_eq!(card.index, out[0] as u32);
        let lift = (weight + buoyancy).y;
        assert!(
            (card.net_lift_n - lift).abs() <= 1e-3 * lift.abs(),
            "{card:?}"
        );
        assert!((card.net_lift_g - lift / 9.81 * 1000.0).abs() <= 0.01 * card.net_lift_g.abs());
        match card.gas {
            BodyGas::Helium => {
                helium += 1;
                assert!(lift > 0.0 && card.helium_fraction > 0.99);
            }
            BodyGas::Air => {
                air += 1;
                assert!(lift < 0.0 && card.helium_fraction < 0.01);
            }
            BodyGas::Mixed => panic!("freshly filled: {card:?}"),
        }
        assert!(card.terminal_speed_m_s > 0.0 && card.height_m > 0.0);
        assert!(card.mass_kg > 0.0 && card.volume_m3 > 0.0);
    }
    assert_eq!((helium, air), (12, 6));
}

#[test]
fn bad_probes_and_cards_are_refused() {
    let mut s = State::default();
    assert_eq!(s.set_force_probe(PROBE_ALL), Err(WasmError::NoWorld));
    assert_eq!(s.write_forces(), Err(WasmError::NoWorld));
    assert_eq!(s.body_card(0), Err(WasmError::NoWorld));
    let mut s = loaded();
    let n = s.body_count() as i32;
    for which in [n, -3, i32::MIN] {
        let e = s.set_force_probe(which).unwrap_err();
        assert_eq!(e.kind(), "OutOfRange", "{which}: {e}");
    }
    assert_eq!(s.body_card(n as u32).unwrap_err().kind(), "OutOfRange");
    assert_eq!(s.body_card(0).unwrap().gas, BodyGas::Helium);
}

#[test]
fn each_teaching_scene_loads_in_the_page_s_engine_with_its_caption() {
    let scenes = [
        include_str!("../../../assets/scenes/learn-terminal-speed.toml"),
        include_str!("../../../assets/scenes/learn-helium-and-air.toml"),
        include_str!("../../../assets/scenes/learn-cold-room.toml"),
        include_str!("../../../assets/scenes/learn-throw.toml"),
    ];
    for text in scenes {
        let mut s = State::default();
        s.load_toml(text).expect("a teaching scene loads");
        s.set_force_probe(0).unwrap();
        s.step(10).unwrap();
        assert_eq!(s.write_forces().unwrap(), 1);
        let json = s.scene_json().unwrap();
        assert!(
            json.contains("\"about\"") && json.contains("\"caption\""),
            "{json}"
        );
        let card = s.body_card(0).unwrap();
        assert!(card.terminal_speed_m_s > 0.5, "{card:?}");
    }
}
