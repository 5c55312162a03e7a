//! The float times the gas model is calibrated to, in the world: one
//! untreated 11″ latex balloon, one Hi-Float treated and one 18″ foil
//! balloon, each on the default 1.5 m ribbon, released in a flat-ceilinged
//! room at 20 °C and run by the time-lapse until each has left the
//! ceiling (`FloatCensus`). The figures (retail charts, physics reference):
//! untreated 12–18 h, treated 2–4 days, foil at least 2 weeks.

use up_physics::World;
use up_scene::build::{build_world, group_index};
use up_scene::float_census::{FloatCensus, FloatState};
use up_scene::scene::Scene;

const ROOM: &str = r#"
[room]
width = 6.0
depth = 6.0
wall_height = 2.7
ceiling = "flat"

[[balloons]]
count = 1
spawn = { min = [-2.5, 0.2, -2.5], max = [-1.0, 1.0, -1.0] }
[balloons.ribbon]

[[balloons]]
count = 1
treatment = "hi-float"
spawn = { min = [1.0, 0.2, 1.0], max = [2.5, 1.0, 2.5] }
[balloons.ribbon]

[[balloons]]
count = 1
kind = "foil"
spawn = { min = [0.5, 0.2, -2.5], max = [2.5, 1.2, -0.5] }
[balloons.ribbon]

[air]
temperature_c = 20.0
"#;

const HOUR: f64 = 3600.0;
/// Steps the 30 days may take: about 115,000 when each balloon sleeps
/// between the gas's wakes. One that never settles steps every 1/60 s (a
/// day in 5 million), and fails here in seconds instead of running for hours.
const STEP_BUDGET: u64 = 1_000_000;

/// Hours at which each group's balloon was last seen leaving the ceiling,
/// looking every simulated minute for `hours`.
fn leave_times(world: &mut World, hours: f64) -> [Option<f64>; 3] {
    let mut census = FloatCensus::new();
    let mut was_up = [false; 3];
    let mut left = [None; 3];
    // Seen first on the floor: the census measures the rise from there.
    census.observe(world);
    let mut steps = 0u64;
    while world.time() < hours * HOUR {
        steps += world.advance(60.0, STEP_BUDGET - steps).steps;
        assert!(
            steps < STEP_BUDGET,
            "{STEP_BUDGET} steps by {:.1} h: a balloon never settles",
            world.time() / HOUR
        );
        census.observe(world);
        for &id in world.body_ids() {
            let group = group_index(world.user_data(id).unwrap());
            let up = census.state(id) == Some(FloatState::Ceiling);
            if was_up[group] && !up {
                left[group] = Some(world.time() / HOUR);
            }
            was_up[group] = up;
        }
        if left.iter().all(Option::is_some) {
            break;
        }
    }
    left
}

#[test]
fn untreated_treated_and_foil_balloons_come_down_when_the_charts_say() {
    let scene = Scene::from_toml_str(ROOM, "float-times.toml").unwrap();
    let mut built = build_world(&scene).unwrap();
    // The foil's weeks are jumps while all three sleep: cheap.
    let [untreated, treated, foil] = leave_times(&mut built.world, 24.0 * 30.0);
    println!("left the ceiling: untreated {untreated:?} h, treated {treated:?} h, foil {foil:?} h");
    let untreated = untreated.expect("the untreated balloon came down");
    assert!(
        (12.0..18.0).contains(&untreated),
        "untreated: {untreated} h"
    );
    let treated = treated.expect("the treated balloon came down");
    assert!((48.0..96.0).contains(&treated), "treated: {treated} h");
    let foil = foil.unwrap_or(f64::INFINITY);
    assert!(foil >= 14.0 * 24.0, "foil: {foil} h");
}
