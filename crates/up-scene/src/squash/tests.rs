use super::*;
use crate::build::{build_world, BuiltScene};
use crate::scene::Scene;
use glam::Vec3;

/// The default 11″ balloon: radius 0.14 m; 5.9 g with 8.5 g of added mass.
const RADIUS: f32 = 0.14;
const MASS: f32 = 0.0144;
const DT: f32 = 1.0 / 60.0;

fn balloon() -> Membrane {
    Membrane {
        stiffness: membrane_stiffness(RADIUS, MEMBRANE_OVERPRESSURE_PA),
        mass: MASS,
    }
}

#[test]
fn stiffness_is_two_pi_r_times_the_overpressure() {
    // Physics reference: 0.9–2.6 kN/m for R = 0.14 m at 1–3 kPa.
    assert!((membrane_stiffness(0.14, 1000.0) - 879.6).abs() < 0.1);
    assert!((membrane_stiffness(0.14, 3000.0) - 2638.9).abs() < 0.1);
}

#[test]
fn a_throw_into_a_wall_dents_by_the_speed_times_the_membrane_time() {
    // The step's impulse (1 + e)·m·v, all in one substep with the bounce (or
    // m·v in one, below): a mass m on a spring k met at v compresses by
    // v·√(m/k), whatever e is.
    let k = balloon().stiffness;
    for (v, e) in [(5.0_f32, 0.4_f32), (5.0, 0.0), (2.0, 0.8), (10.0, 0.4)] {
        let depth = contact_depth(
            MASS * (1.0 + e) * v,
            MASS * (1.0 + e) * v,
            e,
            DT,
            balloon(),
            None,
        );
        let closed = v * (MASS / k).sqrt();
        assert!(
            (depth - closed).abs() < 1e-6,
            "v {v} e {e}: {depth} vs {closed}"
        );
        let spread = contact_depth(MASS * v, MASS * (1.0 + e) * v, e, DT, balloon(), None);
        assert!((spread - closed).abs() < 1e-6, "{spread} vs {closed}");
    }
    // The reference's figure: ≈ 2 cm at 5 m/s (1 kPa); 1.4 cm at the 2 kPa used here.
    let five = contact_depth(MASS * 5.0, MASS * 7.0, 0.4, DT, balloon(), None);
    assert!((0.013..0.015).contains(&five), "{five}");
    let soft = Membrane {
        stiffness: membrane_stiffness(RADIUS, 1000.0),
        mass: MASS,
    };
    let five_soft = contact_depth(MASS * 5.0, MASS * 7.0, 0.4, DT, soft, None);
    assert!((0.019..0.021).contains(&five_soft), "{five_soft}");
}

#[test]
fn two_balloons_meeting_share_the_dent_by_their_stiffness() {
    // Equal balloons closing at v: reduced mass m/2, springs in series k/2;
    // the peak force (m/2)·v·√(k/m) dents each by half of v·√(m/k).
    let v = 4.0_f32;
    let peak = 0.5 * MASS * v;
    let a = contact_depth(peak, 1.4 * peak, 0.4, DT, balloon(), Some(balloon()));
    let closed = 0.5 * v * (MASS / balloon().stiffness).sqrt();
    assert!((a - closed).abs() < 1e-6, "{a} vs {closed}");
    // A stiffer partner (a smaller, tighter balloon) leaves more of the dent to the softer one.
    let stiff = Membrane {
        stiffness: 4.0 * balloon().stiffness,
        mass: MASS,
    };
    let soft_side = contact_depth(peak, peak, 0.0, DT, balloon(), Some(stiff));
    let stiff_side = contact_depth(peak, peak, 0.0, DT, stiff, Some(balloon()));
    assert!(
        (soft_side / stiff_side - 4.0).abs() < 1e-4,
        "{soft_side} {stiff_side}"
    );
}

#[test]
fn a_steady_load_dents_by_force_over_stiffness_and_a_pile_stays_round() {
    // 3 N held over the step and spread over its substeps: at 16 substeps
    // (h·ω < 1) F/k; at 4, the substep's share read as an impact wins,
    // F·h·√(k/m) over k, 1.46 times as much.
    let k = balloon().stiffness;
    let omega = (k / MASS).sqrt();
    let force = 3.0;
    let fine = contact_depth(force * DT / 16.0, force * DT, 0.4, DT, balloon(), None);
    assert!(
        (fine - force / k).abs() < 1e-4 * force / k,
        "{fine} vs {}",
        force / k
    );
    let coarse = contact_depth(force * DT / 4.0, force * DT, 0.4, DT, balloon(), None);
    let h_omega = DT / 4.0 * omega;
    assert!((1.4..1.5).contains(&h_omega), "{h_omega}");
    assert!(
        (coarse - h_omega * force / k).abs() < 1e-4 * force / k,
        "{coarse}"
    );
    // A balloon in a pile bears about its neighbours' lift, 0.1 N: the reference's ≈ 0.1 mm.
    let pile = contact_depth(
        0.1 * DT / 4.0,
        0.1 * DT,
        0.4,
        DT,
        balloon(),
        Some(balloon()),
    );
    assert!(pile < 0.3 * MIN_SQUASH_M, "{pile}");
    // Pressed into a wall by eight times its lift (0.9 N), still under the drawn threshold.
    let pressed = contact_depth(0.9 * DT / 4.0, 0.9 * DT, 0.4, DT, balloon(), None);
    assert!(pressed < MIN_SQUASH_M, "{pressed}");
    assert_eq!(contact_depth(0.0, 0.0, 0.4, DT, balloon(), None), 0.0);
    assert_eq!(
        contact_depth(f32::NAN, f32::NAN, 0.4, DT, balloon(), None),
        0.0
    );
}

/// One 11″ balloon 2 m from the +x wall, its buoyancy carrying it there:
/// gravity along −x at 80 m/s² gives a terminal speed of 5 m/s.
const WALL_SCENE: &str =
    "[room]\nwidth = 6.0\ndepth = 3.0\nwall_height = 3.0\nceiling = \"flat\"\n\n\
     [[balloons]]\ncount = 1\ntilt_deg = 0\nyaw_deg = 0\n\
     spawn = { min = [0.4, 1.0, -0.4], max = [1.0, 1.9, 0.4] }\n\n\
     [sim]\ngravity = [-80.0, 0.0, 0.0]\n";

/// A built scene that records its squash after every step, as the page does.
struct Squashed {
    built: BuiltScene,
    table: SquashTable,
    out: Vec<f32>,
}

impl Squashed {
    fn new(toml: &str) -> Squashed {
        let scene = Scene::from_toml_str(toml, "squash test").unwrap();
        Squashed {
            built: build_world(&scene).unwrap(),
            table: SquashTable::default(),
            out: Vec::new(),
        }
    }

    fn step(&mut self, n: usize) {
        for _ in 0..n {
            self.built.world.step();
            record_step(
                &mut self.table,
                &self.built.world,
                &self.built.balloon_models,
            );
        }
    }

    /// Reads the table (then cleared) into `out`.
    fn read(&mut self) {
        let count = self.built.world.body_count();
        self.table.take(count, &mut self.out);
    }

    fn dent(&self, body: usize) -> (Vec3, f32) {
        let v = &self.out[body * SQUASH_FLOATS..(body + 1) * SQUASH_FLOATS];
        (Vec3::new(v[0], v[1], v[2]), v[3])
    }
}

#[test]
fn a_balloon_flying_into_a_wall_dents_as_a_spring_of_the_membrane_stiffness() {
    let mut s = Squashed::new(WALL_SCENE);
    let id = s.built.world.body_ids()[0];
    let mut approach = 0.0;
    let mut dent = None;
    for _ in 0..600 {
        approach = s.built.world.linear_velocity(id).unwrap().x;
        s.step(1);
        s.read();
        let (n, reach) = s.dent(0);
        if n.length() > 0.0 {
            dent = Some((n, reach));
            break;
        }
    }
    let (n, reach) = dent.expect("the balloon reached the wall");
    let world = &s.built.world;
    let x = world.pose(id).unwrap().position.x;
    assert!(x > 2.7, "at the wall (x = 3 m): {x}");
    assert!((4.0..5.5).contains(&approach), "approach {approach} m/s");
    // Closed form: v·√(m/k), m the effective mass, k = 2π·R·Δp.
    let mass = world.effective_mass(id).unwrap();
    let radius = 0.14 * world.body_scale(id).unwrap();
    let k = membrane_stiffness(radius, MEMBRANE_OVERPRESSURE_PA);
    let closed = approach * (mass / k).sqrt();
    let depth = n.length();
    assert!(
        (depth / closed - 1.0).abs() < 0.25,
        "dent {depth} m against v·√(m/k) = {closed} m (v {approach} m/s, m {mass} kg, k {k} N/m)"
    );
    assert!((0.009..0.02).contains(&depth), "{depth}");
    // Along +x, toward the wall; the surface about a radius out.
    assert!(n.normalize().x > 0.95, "{n}");
    assert!((0.12..0.2).contains(&reach), "{reach}");
    // Read once: the table starts afresh.
    s.read();
    assert!(s.out.iter().all(|&v| v == 0.0));
}

#[test]
fn a_settled_pile_under_the_ceiling_is_not_dented() {
    let mut s = Squashed::new(
        "[room]\nwidth = 1.5\ndepth = 1.5\nwall_height = 2.0\nceiling = \"flat\"\n\n\
         [[balloons]]\ncount = 12\n",
    );
    // Rising at 1.75 m/s into the ceiling dents them by ≈ 5 mm: drawn.
    let mut rising = 0.0_f32;
    for _ in 0..120 {
        s.step(10);
        s.read();
        for b in 0..12 {
            rising = rising.max(s.dent(b).0.length());
        }
        if s.built.world.stats().awake_count == 0 {
            break;
        }
    }
    assert!(rising > MIN_SQUASH_M, "{rising}");
    // Settled, pressed together by their lift: nothing.
    s.step(60);
    s.read();
    assert!(s.out.iter().all(|&v| v == 0.0), "{:?}", s.out);
}
