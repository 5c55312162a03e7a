use super::*;
use crate::state::State;
use crate::state::POSE_FLOATS;

fn default_state() -> State {
    let mut s = State::default();
    s.load_default().expect("the default scene builds");
    s
}

/// Advances `seconds` in calls of at most `chunk` s and `max_steps` steps, as the page's ticks do.
fn lapse(s: &mut State, seconds: f64, chunk: f64, max_steps: u32) -> (u64, u64) {
    let (mut steps, mut jumps) = (0, 0);
    let end = s.sim_time() + seconds;
    let mut calls = 0;
    while s.sim_time() < end - 1e-9 {
        let done = s.advance(chunk.min(end - s.sim_time()), max_steps).unwrap();
        steps += done.steps as u64;
        jumps += done.jumps as u64;
        calls += 1;
        assert!(calls < 1_000_000, "the clock moves");
    }
    (steps, jumps)
}

#[test]
fn advance_refuses_what_is_not_a_span_or_a_step_budget_and_keeps_the_world() {
    let mut s = State::default();
    assert_eq!(s.advance(1.0, 10), Err(WasmError::NoWorld));
    let mut s = default_state();
    let hash = s.world().unwrap().state_hash();
    for (seconds, steps) in [
        (f64::NAN, 10),
        (-1.0, 10),
        (f64::INFINITY, 10),
        (MAX_ADVANCE_S * 2.0, 10),
        (1.0, 0),
        (1.0, MAX_STEPS_PER_CALL + 1),
    ] {
        let e = s.advance(seconds, steps).unwrap_err();
        assert_eq!(e.kind(), "BadArgument", "{seconds} s, {steps} steps: {e}");
    }
    assert_eq!(s.world().unwrap().state_hash(), hash);
    assert_eq!(s.sim_time(), 0.0);
}

#[test]
fn an_hour_of_time_lapse_shrinks_every_balloon_and_the_clock_reads_an_hour() {
    let mut s = default_state();
    let n = s.body_count();
    s.write_body_scales().unwrap();
    assert_eq!(s.scales.len(), n);
    for &k in &s.scales {
        assert!((k - 1.0).abs() < 0.02, "filled to its shape's size: {k}");
    }
    // A tick at ×3 600 asks a minute of a frame's budget of steps.
    let (steps, jumps) = lapse(&mut s, 3600.0, 60.0, 200);
    assert!((s.sim_time() - 3600.0).abs() < 1e-6, "{}", s.sim_time());
    assert!(
        jumps > 0,
        "the pile slept and the gas jumped ({steps} steps)"
    );
    s.write_body_scales().unwrap();
    for &k in &s.scales {
        assert!(k < 1.0 && k > 0.5, "an hour of helium loss: {k}");
    }
    let t = s.air_temperature_c().unwrap();
    assert!((t - 20.0).abs() < 0.01, "the default room is at 20 °C: {t}");
}

#[test]
fn time_lapse_is_deterministic() {
    let run = || {
        let mut s = default_state();
        lapse(&mut s, 1800.0, 37.0, 50);
        s.world().unwrap().state_hash()
    };
    assert_eq!(run(), run());
}

#[test]
fn the_balloons_rise_to_the_ceiling_and_are_counted_there() {
    let mut s = default_state();
    let n = s.body_count() as u32;
    let start = s.float_counts().unwrap();
    assert_eq!(start.ceiling + start.hovering + start.floor, n);
    assert_eq!(start.ceiling, 0, "none has risen yet");
    for _ in 0..20 {
        s.step(60).unwrap();
        s.float_counts().unwrap();
    }
    let up = s.float_counts().unwrap();
    assert_eq!(up.ceiling + up.hovering + up.floor, n);
    assert!(up.ceiling >= n * 9 / 10, "{up:?}");
    assert_eq!(up.groups.len(), 1);
    assert!(
        up.mean_lift_fraction > 0.95 && up.mean_lift_fraction <= 1.01,
        "{up:?}"
    );
    assert!((up.time_s - s.sim_time()).abs() < 1e-9);
    // A new world starts a new census.
    s.load_default().unwrap();
    assert_eq!(s.float_counts().unwrap().ceiling, 0);
}

#[test]
fn a_balloon_the_page_adds_carries_its_groups_gas_and_shrinks_too() {
    let mut s = default_state();
    let n = s.body_count();
    s.add_balloon_on_floor(0.5, 0.5, 0).unwrap();
    let id = s.world().unwrap().body_ids()[n];
    let world = s.world().unwrap();
    let gas = world.gas(id).expect("the added balloon carries gas");
    assert!(gas.helium_mol > 0.0);
    assert!(world.free_lift(id).unwrap() > 0.0, "it floats");
    s.write_poses().unwrap();
    let y0 = s.poses[n * POSE_FLOATS + 1];
    lapse(&mut s, 3600.0, 60.0, 200);
    s.write_poses().unwrap();
    assert!(s.poses[n * POSE_FLOATS + 1] > y0 + 1.0, "it rose");
    s.write_body_scales().unwrap();
    assert!(s.scales[n] < 1.0, "{}", s.scales[n]);
}
