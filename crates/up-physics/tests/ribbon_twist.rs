//! Twist holds: two balloons on ribbons tied to one weight, their ribbons
//! twisted round each other, stay twisted while pulled apart: ribbons that
//! cannot pass through each other keep their linking number
//! (`up_physics::ribbon::linking`), whatever the pull does to where the
//! twist sits.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::crossings::crossings;
use up_physics::ribbon::linking::{closed_pair, linking_number};
use up_physics::ribbon::{RibbonDef, RIBBON_RADIUS};
use up_physics::{BodyId, RibbonId, World, WorldDef};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);
const LENGTH: f32 = 1.5;
const SEGMENTS: u32 = 32;
const TURNS: f32 = 3.0;
/// The weight on the floor, and the two ribbons' ends tied to it 6 mm
/// apart (a knot round a weight has a size; tied at one point the two
/// would meet there), on the floor (a ribbon cannot pass under the weight
/// round the other's end).
const WEIGHT: Vec3 = Vec3::new(0.0, 0.003, 0.0);
const TIED_APART: f32 = 0.003;
/// The pull apart on each balloon, N.
const PULL: f32 = 0.1;
/// How stiffly each balloon is held toward its point, N/m, and damped,
/// N·s/m (a hand's hold).
const HOLD: f32 = 1.0;
const HOLD_DAMPING: f32 = 0.1;

/// Points `length / segments` apart along the curve `curve(u)`, u from 0
/// at the tied end on (up to 1.5), the knot last: walked in fine steps, a point wherever the chord from the last
/// reaches the segment length.
fn along(curve: impl Fn(f32) -> Vec3, length: f32, segments: u32) -> Vec<Vec3> {
    let chord = length / segments as f32;
    let mut points = vec![curve(0.0)];
    let steps = 200_000;
    for k in 1..=steps {
        let p = curve(1.5 * k as f32 / steps as f32);
        let last = *points.last().unwrap();
        if p.distance(last) >= chord {
            points.push(last + (p - last).normalize() * chord);
            if points.len() == segments as usize + 1 {
                return points;
            }
        }
    }
    panic!("the curve is shorter than the ribbon");
}

/// Strand `phase` (0 or π) of a double helix about the y axis through the
/// weight, `TURNS` turns, `height` m high: the two strands touching (a
/// ribbon's width apart, `TIED_APART` from the axis) up to four fifths of
/// the way, then opening to 14 cm from it (the balloons side by side).
fn strand(phase: f32, height: f32) -> impl Fn(f32) -> Vec3 {
    move |u: f32| {
        let angle = phase + u.min(1.0) * TURNS * std::f32::consts::TAU;
        let open = ((u - 0.8) / 0.2).clamp(0.0, 1.0);
        let radius = TIED_APART + (0.14 - TIED_APART) * open * open;
        WEIGHT + Vec3::new(radius * angle.cos(), height * u, radius * angle.sin())
    }
}

/// The height at which a strand (u up to 1) is as long as the ribbon,
/// bisected: the ribbons laid taut, their balloons at the height they float
/// at (its chords cut the turns a little short: the last chords go on
/// straight up).
fn strand_height() -> f32 {
    let length = |height: f32| {
        let curve = strand(0.0, height);
        (1..=10_000)
            .map(|k| curve(k as f32 / 1e4).distance(curve((k - 1) as f32 / 1e4)))
            .sum::<f32>()
    };
    let (mut lo, mut hi) = (0.5f32, LENGTH);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if length(mid) < LENGTH {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// The two balloons on their twisted ribbons; each ribbon's points from
/// its knot to the weight.
fn twisted_pair(world: &mut World, shape: up_physics::ShapeId) -> [(BodyId, RibbonId); 2] {
    let height = strand_height();
    [0.0, std::f32::consts::PI].map(|phase| {
        let mut points = along(strand(phase, height), LENGTH, SEGMENTS);
        points.reverse();
        let knot = points[0];
        let body = add(world, shape, knot - KNOT, Quat::IDENTITY);
        let ribbon = world
            .add_ribbon(&RibbonDef {
                anchor: Some(*points.last().unwrap()),
                ..RibbonDef::new(body, KNOT, LENGTH, SEGMENTS)
            })
            .unwrap();
        world.set_ribbon_points(ribbon, &points).unwrap();
        (body, ribbon)
    })
}

/// The two ribbons' linking number, each closed from its tied end round
/// far above its balloon (`closed_pair`), and how far the Gauss integral was
/// from it.
fn linking(world: &World, pair: &[(BodyId, RibbonId); 2]) -> (i32, f64) {
    let from_weight = |id: RibbonId| {
        let mut p = world.ribbon_points(id).unwrap().to_vec();
        p.reverse();
        p
    };
    let (a, b) = closed_pair(&from_weight(pair[0].1), &from_weight(pair[1].1), Vec3::Y);
    linking_number(&a, &b)
}

/// What a twisted pair pulled apart came to.
struct Pulled {
    /// The linking number at the start and at the end, each with how far
    /// the Gauss integral was from it.
    start: (i32, f64),
    end: (i32, f64),
    /// When the linking number first differed from the start's, s.
    first_change: Option<f32>,
    /// Segments of one ribbon that passed through the other's, counted
    /// every step (`crossings`, at the ribbons' thickness).
    crossings: usize,
    /// The balloons' distance apart at the end, m.
    apart: f32,
}

/// The pair twisted in a world of `substeps` substeps a step, then
/// `seconds` of each balloon held toward a point beyond it, away from the
/// other (`PULL` where it starts), the hold growing over the first second.
fn twist_and_pull(contacts: bool, substeps: u32, seconds: f32) -> Pulled {
    let def = WorldDef {
        room: Some(room(5.0, 5.0, 3.0, None)),
        ribbon_contacts: contacts,
        substeps,
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let pair = twisted_pair(&mut world, shape);
    let start = linking(&world, &pair);
    let centre = |w: &World, b: BodyId| w.pose(b).unwrap().position;
    let points = |w: &World| pair.map(|(_, r)| w.ribbon_points(r).unwrap().to_vec());
    // Held apart as two hands would hold them: each pulled level toward a
    // point `PULL / HOLD` m beyond where it starts, away from the other (so
    // `PULL` at the start), with some damping; held so, the balloons cannot
    // turn round each other, which would untwist ribbons whose far ends
    // are free.
    let (a0, b0) = (centre(&world, pair[0].0), centre(&world, pair[1].0));
    let apart = (a0 - b0).with_y(0.0).normalize();
    let targets = [a0 + apart * (PULL / HOLD), b0 - apart * (PULL / HOLD)];
    let (mut first_change, mut crossed) = (None, 0);
    let mut before = points(&world);
    for step in 0..(seconds * 60.0) as u32 {
        let ramp = (step as f32 / 60.0).min(1.0);
        for (k, &(body, _)) in pair.iter().enumerate() {
            let (p, v) = (centre(&world, body), world.linear_velocity(body).unwrap());
            let force = (HOLD * (targets[k] - p) - HOLD_DAMPING * v).with_y(0.0) * ramp;
            world.apply_force_at_point(body, force, p).unwrap();
        }
        world.step();
        let now = points(&world);
        crossed += crossings(&before, &now, 2.0 * RIBBON_RADIUS);
        before = now;
        if first_change.is_none() && linking(&world, &pair).0 != start.0 {
            first_change = Some((step + 1) as f32 / 60.0);
        }
    }
    let (a, b) = (centre(&world, pair[0].0), centre(&world, pair[1].0));
    Pulled {
        start,
        end: linking(&world, &pair),
        first_change,
        crossings: crossed,
        apart: a.distance(b),
    }
}

/// The pair twisted and pulled at `substeps` substeps a step, with the
/// contacts on and off, each printed.
fn pulled_on_and_off(substeps: u32) -> (Pulled, Pulled) {
    let (on, off) = (
        twist_and_pull(true, substeps, 60.0),
        twist_and_pull(false, substeps, 60.0),
    );
    println!(
        "{substeps} substeps: linking {} at the start (off an integer by {:.4}), {} after 60 s of {PULL} N apart (by {:.4}), first changed at {:?} s, {} crossings, the balloons {:.3} m apart; without contacts {} (first changed at {:?} s, {} crossings, {:.3} m apart)",
        on.start.0, on.start.1, on.end.0, on.end.1, on.first_change, on.crossings, on.apart,
        off.end.0, off.first_change, off.crossings, off.apart
    );
    (on, off)
}

/// Twisted 3 turns at the start (the Gauss linking integral of the two
/// ribbons closed into loops: ±3, the closed form for a two-strand braid of
/// three full turns), the linking number is the same after 60 s of 0.1 N
/// pulling the balloons apart, and the integral still within 0.05 of an
/// integer (the ribbons did not end through each other). With the contacts
/// off the ribbons untwist through each other, which shows that the count
/// sees it.
fn assert_twist_held(on: &Pulled, off: &Pulled) {
    assert_eq!(
        on.start.0.abs(),
        TURNS as i32,
        "the twist as laid: {:?}",
        on.start
    );
    assert_eq!(on.end.0, on.start.0, "the twist came undone: {:?}", on.end);
    assert_eq!(on.first_change, None, "the twist came undone on the way");
    assert!(on.end.1 < 0.05, "ended off an integer by {}", on.end.1);
    assert_ne!(off.end.0, on.start.0, "without contacts the twist held too");
}

/// At the world's 4 substeps a step (`WorldDef::default`).
#[test]
#[ignore = "fails at 4 substeps a step: the linking number goes from −3 to −1 in the 10th step (0.17 s) and to 0 in the 12th: as the balloons draw apart the strands spin round each other, the side of a pair of segments 0.7–0.9 m up (read from the line between their closest points, the segments nearly parallel) turning 5–20° at every pass, and there they pass through each other (the linked solve, `touch::held`, not converging in its 8 iterations; with no contact in it they go in the same step); with the balloons' rise held to 0.1 or 0.02 m/s, the ribbons not yet taut, it goes at 0.47 or 0.73 s; at 32–64 substeps it holds (the test below); see docs/perf-log.md"]
fn ribbons_twisted_three_turns_stay_twisted_under_a_pull() {
    let (on, off) = pulled_on_and_off(WorldDef::default().substeps);
    assert_twist_held(&on, &off);
}

/// The same at 48 substeps a step (a 0.35 ms substep): the contacts keep
/// the twist through the balloons' going taut and the 60 s of pull, no
/// segment through the other; what the default's 4 substeps lack is time
/// resolution while the turns run together (24 substeps fail, 32 to 64
/// hold). The crossings count sees segments pass through each other at
/// an angle, not two strands untwisting side by side (without contacts it
/// counts 0 to 2 while the linking number goes from 3 to 0): the linking
/// number is the test.
#[test]
fn ribbons_twisted_three_turns_stay_twisted_in_short_substeps() {
    let (on, off) = pulled_on_and_off(48);
    assert_twist_held(&on, &off);
    assert_eq!(on.crossings, 0, "segments passed through each other");
}
