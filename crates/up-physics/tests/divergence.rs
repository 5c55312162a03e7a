//! `up_physics::divergence` names where two runs part: the step, the body
//! and what of it, however small the difference.

mod common;

use common::*;
use glam::Vec3;
use up_physics::divergence::{
    body_hash_header, body_hash_line, compare, lockstep, lockstep_with, Divergence, Field,
};
use up_physics::{BodyId, World};

/// The next float after `x`: the smallest change there is.
fn next_up(x: f32) -> f32 {
    f32::from_bits(x.to_bits() + 1)
}

/// Moves `id`'s x velocity by one unit in the last place.
fn nudge(world: &mut World, id: BodyId) {
    let v = world.linear_velocity(id).unwrap();
    let w = world.angular_velocity(id).unwrap();
    world
        .set_velocity(id, Vec3::new(next_up(v.x), v.y, v.z), w)
        .unwrap();
}

#[test]
fn a_nudge_at_step_k_is_named_at_step_k_and_its_body() {
    const K: u64 = 40;
    let (mut a, mut b) = (sixty_released(), sixty_released());
    let victim = a.body_ids()[17];
    let parted = lockstep_with(&mut a, &mut b, 100, World::step, |w| {
        w.step();
        if w.step_count() == K {
            nudge(w, victim);
        }
    });
    let parted = parted.expect("a nudged world parts from the other");
    assert_eq!(
        parted,
        Divergence {
            step: K,
            body: Some(victim),
            user_data: Some(a.user_data(victim).unwrap()),
            field: Field::LinearVelocity,
        }
    );
    let text = parted.to_string();
    assert!(
        text.contains(&format!("step {K}"))
            && text.contains(&format!("body {}", victim.index))
            && text.contains("linear_velocity"),
        "{text}"
    );
}

#[test]
fn the_same_world_stepped_twice_does_not_part() {
    let (mut a, mut b) = (sixty_released(), sixty_released());
    assert_eq!(lockstep(&mut a, &mut b, 120), None);
    assert_eq!(a.state_hash(), b.state_hash());
}

#[test]
fn a_missing_body_is_named() {
    let (a, mut b) = (sixty_released(), sixty_released());
    let gone = a.body_ids()[5];
    b.remove_body(gone).unwrap();
    let parted = compare(&a, &b).expect("one body less");
    assert_eq!((parted.step, parted.field), (0, Field::Bodies));
    assert_eq!(parted.body, Some(gone));
}

#[test]
fn the_lines_of_two_runs_part_at_the_nudged_body_and_field() {
    let (mut a, mut b) = (sixty_released(), sixty_released());
    for _ in 0..30 {
        a.step();
        b.step();
    }
    assert_eq!(body_hash_line(&a), body_hash_line(&b));
    let victim = a.body_ids()[9];
    nudge(&mut b, victim);
    let (la, lb) = (body_hash_line(&a), body_hash_line(&b));
    let (ta, tb): (Vec<&str>, Vec<&str>) = (la.split(' ').collect(), lb.split(' ').collect());
    assert_eq!(
        ta.len(),
        2 + a.body_count(),
        "step, state hash, one token a body"
    );
    assert_eq!(ta[0], "30");
    assert_ne!(ta[1], tb[1], "the state hash differs");
    let differing: Vec<usize> = (2..ta.len()).filter(|&k| ta[k] != tb[k]).collect();
    assert_eq!(differing, [2 + 9], "only the victim's token differs");
    let token = |t: &str| -> (String, Vec<String>) {
        let (who, hashes) = t.split_once(':').unwrap();
        (
            who.to_string(),
            hashes.split(',').map(str::to_string).collect(),
        )
    };
    let ((who_a, ha), (who_b, hb)) = (token(ta[11]), token(tb[11]));
    let user_data = a.user_data(victim).unwrap();
    assert_eq!(
        who_a,
        format!("{}.{}/{user_data}", victim.index, victim.generation)
    );
    assert_eq!(who_a, who_b);
    let fields: Vec<usize> = (0..ha.len()).filter(|&k| ha[k] != hb[k]).collect();
    assert_eq!(ha.len(), Field::HASHED.len());
    assert_eq!(
        fields.iter().map(|&k| Field::HASHED[k]).collect::<Vec<_>>(),
        [Field::LinearVelocity]
    );
    assert!(body_hash_header()
        .ends_with("position,rotation,linear_velocity,angular_velocity,awake,ribbon,gas"));
}
