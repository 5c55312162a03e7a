//! The gas model against closed forms and the published float times
//! (`../shared/docs/physics-reference.md`, "Helium loss and temperature").

use super::envelope::*;
use super::model::*;
use crate::forces::atmosphere::Atmosphere;

/// The default 11″ latex balloon (`up-scene`'s model, which its own tests
/// check against these): m³, kg, kg, m².
const VOLUME: f64 = 0.0142;
const ENVELOPE: f32 = 0.003;
const SOLID: f32 = 0.0035;
const AREA: f32 = 0.289;
/// kg: the default 1.5 m ribbon at 0.25 g/m, all hanging from the ceiling.
const RIBBON: f64 = 0.000_375;
/// An 18″ foil balloon: m³ and kg (a 46 cm disc 12.6 cm thick, 10 g).
const FOIL_VOLUME: f64 = 0.014;
const FOIL_SOLID: f32 = 0.010;

const HOUR: f64 = 3600.0;

fn latex(treatment: f64, helium_fraction: f32) -> EnvelopeDef {
    EnvelopeDef::latex(SOLID, ENVELOPE, AREA, treatment, helium_fraction)
}

/// Hours until `falls` says so, a minute at a time.
fn hours_until(mut gas: Gas, air: &Atmosphere, falls: impl Fn(&Gas) -> bool) -> f64 {
    let mut t = 0.0;
    while !falls(&gas) {
        gas.advance(60.0, air);
        t += 60.0;
        assert!(t < 1e4 * HOUR, "never happened");
    }
    t / HOUR
}

fn hours_afloat(gas: Gas, air: &Atmosphere) -> f64 {
    hours_until(gas, air, |g| g.free_lift_kg(air) < RIBBON)
}

#[test]
fn helium_alone_follows_the_closed_form() {
    // Without air coming in, dn/dt = −K·p·(n/n₀)^{4/3}: n = n₀/(1 + t/τ)³
    // with τ = 3·n₀/(K·p), and the gas's lift follows n.
    let air = Atmosphere::default();
    let mut def = latex(1.0, 1.0);
    def.air_ratio = 0.0;
    let mut gas = Gas::fill(def, VOLUME, &air);
    let (n0, lift0) = (gas.moles(), gas.gas_lift_kg(&air));
    let p = f64::from(air.pressure_pa + def.overpressure_pa);
    let tau = 3.0 * n0 / (def.helium_permeance * p);
    let mut worst: f64 = 0.0;
    for hour in 1..=24 {
        gas.advance(HOUR, &air);
        let expected = lift0 / (1.0 + f64::from(hour) * HOUR / tau).powi(3);
        let error = (gas.gas_lift_kg(&air) - expected).abs() / expected;
        worst = worst.max(error);
    }
    assert!(worst < 1e-6, "lift off the closed form by {worst}");
}

#[test]
fn an_untreated_11_inch_balloon_comes_down_after_12_to_18_hours() {
    let air = Atmosphere::default();
    let gas = Gas::fill(latex(1.0, 1.0), VOLUME, &air);
    let lift = gas.free_lift_kg(&air);
    assert!(
        (0.010..0.0125).contains(&lift),
        "free lift {lift} kg at fill"
    );
    let hours = hours_afloat(gas, &air);
    assert!((12.0..18.0).contains(&hours), "afloat {hours} h");
    // What it has lost by then: the charts' 70–75 % of its lift.
    let mut at_fall = gas;
    at_fall.advance(hours * HOUR, &air);
    let lost = 1.0 - at_fall.lift_fraction(&air);
    println!("untreated: afloat {hours:.2} h, {lost:.3} of its lift lost");
    assert!((0.65..0.8).contains(&lost), "lost {lost} of its lift");
}

#[test]
fn a_treated_balloon_floats_two_to_four_days() {
    let air = Atmosphere::default();
    let gas = Gas::fill(latex(HI_FLOAT_FACTOR, 1.0), VOLUME, &air);
    let hours = hours_afloat(gas, &air);
    println!("treated: afloat {hours:.1} h");
    assert!((48.0..96.0).contains(&hours), "afloat {hours} h");
}

#[test]
fn a_foil_balloon_stays_taut_for_days_and_afloat_for_weeks() {
    let air = Atmosphere::default();
    let gas = Gas::fill(EnvelopeDef::foil(FOIL_SOLID, 1.0, 1.0), FOIL_VOLUME, &air);
    let lift = gas.free_lift_kg(&air);
    assert!(
        (0.003..0.006).contains(&lift),
        "free lift {lift} kg at fill"
    );
    let taut = hours_until(gas, &air, |g| g.volume(&air) < 0.999 * FOIL_VOLUME) / 24.0;
    assert!((3.0..5.0).contains(&taut), "taut {taut} days");
    let afloat = hours_afloat(gas, &air) / 24.0;
    println!("foil: taut {taut:.1} days, afloat {afloat:.1} days");
    assert!(afloat >= 14.0, "afloat {afloat} days");
}

#[test]
fn volume_follows_charles_law_from_5_to_30_celsius() {
    let warm = Atmosphere {
        temperature_k: 303.15,
        ..Atmosphere::default()
    };
    let cold = Atmosphere {
        temperature_k: 278.15,
        ..Atmosphere::default()
    };
    let gas = Gas::fill(latex(1.0, 1.0), VOLUME, &cold);
    let ratio = gas.volume(&warm) / gas.volume(&cold);
    let expected = 303.15 / 278.15;
    assert!(
        (ratio / expected - 1.0).abs() < 1e-6,
        "{ratio} against {expected}"
    );
    // A foil balloon filled taut cannot grow: its pressure rises instead.
    let foil = Gas::fill(EnvelopeDef::foil(FOIL_SOLID, 1.0, 1.0), FOIL_VOLUME, &cold);
    assert_eq!(foil.volume(&warm), FOIL_VOLUME);
    assert!(foil.pressure(&warm) > foil.pressure(&cold));
}

#[test]
fn an_air_filled_balloon_neither_gains_nor_loses_much() {
    let air = Atmosphere::default();
    let mut gas = Gas::fill(latex(1.0, 0.0), VOLUME, &air);
    let m0 = gas.moles();
    gas.advance(24.0 * HOUR, &air);
    // Only the overpressure pushes air out: ≈ 2 % of it, slowly.
    let change = gas.moles() / m0 - 1.0;
    assert!((-0.03..=0.0).contains(&change), "{change}");
}

#[test]
fn long_steps_agree_with_short_ones() {
    let air = Atmosphere::default();
    let mut coarse = Gas::fill(latex(1.0, 1.0), VOLUME, &air);
    let mut fine = coarse;
    coarse.advance(10.0 * HOUR, &air);
    for _ in 0..36_000 {
        fine.advance(1.0, &air);
    }
    let error = (coarse.helium_mol - fine.helium_mol).abs() / fine.helium_mol;
    assert!(error < 1e-9, "{error}");
}
