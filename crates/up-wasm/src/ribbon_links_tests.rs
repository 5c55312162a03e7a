use std::f32::consts::{PI, TAU};

use up_physics::ribbon::crossings::crossings;
use up_physics::ribbon::RIBBON_RADIUS;

use super::*;
use crate::state::State;

/// Strands from (±1 cm, 0, 0) up 1.2 m, wound `turns` times round each
/// other, in the page's layout: points knot first (the top), offsets.
fn twisted(turns: f32) -> (Vec<f32>, Vec<u32>) {
    const POINTS: u32 = 49;
    let strand = |phase: f32| {
        (0..POINTS).rev().flat_map(move |k| {
            let s = k as f32 / (POINTS - 1) as f32;
            let t = phase + s * turns * TAU;
            let r = 0.01 + 0.02 * (PI * s).sin();
            [r * t.cos(), 1.2 * s, r * t.sin()]
        })
    };
    let points = strand(0.0).chain(strand(PI)).collect();
    (points, vec![0, POINTS, 2 * POINTS])
}

#[test]
fn strands_twisted_n_turns_link_n_times_and_not_with_themselves() {
    for turns in [0.0f32, 1.0, 2.0, -3.0] {
        let (points, offsets) = twisted(turns);
        let links = ribbon_links(&points, &offsets, 0).unwrap();
        assert_eq!(links[0], 0, "{turns} turns: with itself");
        assert_eq!(
            links[1].abs(),
            turns.abs() as i32,
            "{turns} turns: {links:?}"
        );
        assert_eq!(ribbon_links(&points, &offsets, 1).unwrap(), [links[1], 0]);
    }
    let (a, offsets) = twisted(2.0);
    let (b, _) = twisted(-2.0);
    assert_eq!(
        ribbon_links(&a, &offsets, 0).unwrap()[1],
        -ribbon_links(&b, &offsets, 0).unwrap()[1],
        "the sign is the turns' sense"
    );
}

#[test]
fn offsets_that_do_not_describe_the_points_are_refused() {
    let (points, offsets) = twisted(1.0);
    let refused = |points: &[f32], offsets: &[u32], ribbon: u32| {
        ribbon_links(points, offsets, ribbon).unwrap_err().kind()
    };
    assert_eq!(refused(&points, &offsets, 2), "OutOfRange");
    assert_eq!(refused(&points, &[0, 49, 97], 0), "BadArgument");
    assert_eq!(refused(&points, &[1, 49, 98], 0), "BadArgument");
    assert_eq!(refused(&points, &[0, 49, 49, 98], 0), "BadArgument");
    assert_eq!(refused(&points[1..], &offsets, 0), "BadArgument");
    let mut nan = points.clone();
    nan[7] = f32::NAN;
    assert_eq!(refused(&nan, &offsets, 0), "BadArgument");
    assert_eq!(refused(&[], &[0], 0), "OutOfRange");
}

/// The bouquet scene, its balloons risen and settled over their weights.
fn settled_bouquet() -> State {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/scenes/bouquet.toml"
    );
    let text = std::fs::read_to_string(path).expect("the bouquet scene");
    let mut state = State::default();
    state.load_toml(&text).expect("the bouquet loads");
    state.step(600).unwrap();
    state
}

/// Ribbon `ribbon`'s links with the others now, as the page reads them.
fn links_now(state: &mut State, ribbon: u32) -> Vec<i32> {
    state.write_ribbon_points().unwrap();
    state.write_ribbon_tables().unwrap();
    let tables = &state.ribbons;
    ribbon_links(&tables.points, &tables.offsets, ribbon).unwrap()
}

#[test]
fn a_settled_bouquet_is_untwisted() {
    let mut state = settled_bouquet();
    let count = state.ribbon_count() as u32;
    assert_eq!(count, 6);
    for ribbon in 0..count {
        assert_eq!(links_now(&mut state, ribbon), [0; 6], "ribbon {ribbon}");
    }
}

/// Where the page's grab takes balloon `body`: the top of its root sphere.
fn top_of(state: &State, body: u32) -> Vec3 {
    let loaded = state.loaded.as_ref().unwrap();
    let world = &loaded.built.world;
    let id = world.body_ids()[body as usize];
    let pose = world.pose(id).unwrap();
    let root = *loaded.built.balloon_models[0].shape.tree.root();
    pose.position + pose.rotation * root.center + Vec3::Y * root.radius * 0.9
}

/// The middle of the bouquet's weights (the ribbons' free ends), m.
fn weights_middle(state: &mut State) -> Vec3 {
    let ribbons = ribbons_now(state);
    ribbons.iter().map(|p| *p.last().unwrap()).sum::<Vec3>() / ribbons.len() as f32
}

/// Every ribbon's points now, knot first.
fn ribbons_now(state: &mut State) -> Vec<Vec<Vec3>> {
    state.write_ribbon_points().unwrap();
    state.write_ribbon_tables().unwrap();
    let t = &state.ribbons;
    let point = |i: usize| Vec3::from_slice(&t.points[i * RIBBON_POINT_FLOATS..]);
    t.offsets
        .windows(2)
        .map(|w| (w[0] as usize..w[1] as usize).map(point).collect())
        .collect()
}

/// The page's gesture (e2e/bouquetTwist.spec.ts), natively: balloon 0 held
/// by its top from above (a level drag plane) and carried twice round the
/// weights' middle, 0.25 m out (within its ribbon's reach, so that its
/// weight stays on the floor), a turn in 4 s, then let go: wrapped every
/// half second for two seconds after, and no ribbon passed through another
/// on the way (a link made by passing through is no wrap).
#[test]
#[ignore = "the carried ribbon catches on another (a link for half a second) and is pulled through it while they touch (ribbons wound round each other under a pull pass through: docs/physics.md): unwrapped after the release, with ribbons passing through each other on the way"]
fn a_balloon_carried_twice_round_the_bouquet_leaves_its_ribbon_wrapped() {
    const RADIUS: f32 = 0.25;
    const TURN_S: f32 = 4.0;
    let mut state = settled_bouquet();
    let middle = weights_middle(&mut state);
    let ribbon = state.ribbons.bodies.iter().position(|&b| b == 0).unwrap() as u32;
    assert_eq!(
        links_now(&mut state, ribbon),
        [0; 6],
        "untwisted at the start"
    );
    let top = top_of(&state, 0);
    state.grab(0, top).unwrap();
    let start = (top.z - middle.z).atan2(top.x - middle.x);
    let aim = |a: f32| {
        Vec3::new(
            middle.x + RADIUS * a.cos(),
            top.y,
            middle.z + RADIUS * a.sin(),
        )
    };
    let steps = (2.0 * TURN_S * 60.0) as u32;
    let mut before = ribbons_now(&mut state);
    let mut crossed = 0;
    // Linking numbers every half second for two seconds after it is let go.
    let mut after = Vec::new();
    for k in 1..=steps + 120 {
        if k < steps {
            state
                .drag_to(aim(start + 2.0 * TAU * k as f32 / steps as f32))
                .unwrap();
        } else if k == steps {
            state.release().unwrap();
        }
        state.step(1).unwrap();
        let now = ribbons_now(&mut state);
        crossed += crossings(&before, &now, 2.0 * RIBBON_RADIUS);
        before = now;
        if k > steps && (k - steps).is_multiple_of(30) {
            after.push(links_now(&mut state, ribbon));
        }
    }
    println!("links every half second after the release: {after:?}; {crossed} crossings");
    assert!(
        after.iter().all(|links| links.iter().any(|&l| l != 0)) && crossed == 0,
        "links every half second after {after:?}; ribbons passed through each other {crossed} times"
    );
}
