//! The rest pass, after the step has moved the bodies: rest clocks, then the
//! rested bodies that fall asleep, in groups.

use glam::Vec3;
use up_geom::norm::Norm;

use super::{SleepBuffers, SleepInput, SleepingIslands};
use crate::body::Bodies;
use crate::contact::{WarmStartCache, STATIC_BODY};
use crate::threading::tasks::fill_chunks;
use crate::world::{roots_within, PLACE_CHUNK};

/// The share of the sleep speed under which a balloon hanging on its
/// ribbon, touching nothing, must move along gravity to be slow (across it,
/// the sleep speed). Such a balloon whose lift has passed what its ribbon
/// holds up starts down slowly before the knot drops a segment: at the
/// sleep speed it would rest in that creep and wake only once its gas has
/// moved on by the wake threshold, to come down two segments at once. Its
/// swing across the ribbon after a drop, a few mm/s and lightly damped,
/// is no creep, and under the finer speed kept it awake for tens of
/// seconds more a segment.
pub(crate) const HOVER_REST_SHARE: f32 = 0.2;

/// Marks in `hovering` (per body) the balloons whose ribbons were solved
/// this step that touch nothing.
fn mark_hovering<'a>(input: &SleepInput, n: usize, hovering: &'a mut Vec<bool>) -> &'a [bool] {
    hovering.clear();
    hovering.resize(n, false);
    if input.awake_ribbons.is_empty() {
        return hovering;
    }
    for r in input.awake_ribbons {
        hovering[r.state as usize] = true;
    }
    for c in input.contacts {
        hovering[c.body_a as usize] = false;
        if c.body_b != STATIC_BODY {
            hovering[c.body_b as usize] = false;
        }
    }
    hovering
}

/// Sleep timers, then the rested bodies that fall asleep.
///
/// A body is rested once it has been slow for `time_to_sleep`. Rested
/// bodies sleep in groups of touching or joined ones, except those a
/// restless body reaches (root spheres within the speculative distance) or
/// is joined to: they stay awake as the buffer through which a restless body
/// pushes, and would be woken at once by the next step's wake pass anyway.
/// So a big pile in which a few balloons still shuffle sleeps everywhere
/// else, where whole-island sleep would keep all of it awake. `grabbed`
/// never rests; `warm` holds the impulses the step stored. A balloon
/// hovering on its ribbon is slow only under a finer speed along gravity
/// (`HOVER_REST_SHARE`).
pub(crate) fn update_sleep(
    input: &SleepInput,
    grabbed: Option<usize>,
    warm: &WarmStartCache,
    bodies: &mut Bodies,
    sleeping: &mut SleepingIslands,
    buffers: &mut SleepBuffers,
) {
    let rules = &input.rules;
    let n = bodies.len();
    let dt = rules.dt;
    let (awake, linear_velocity, angular_velocity) = (
        &bodies.awake,
        &bodies.linear_velocity,
        &bodies.angular_velocity,
    );
    let kept_awake = input.kept_awake;
    let (linear_speed, angular_speed) = (rules.linear_speed, rules.angular_speed);
    let hover_speed = linear_speed * HOVER_REST_SHARE;
    let up = rules.up;
    let hovering = mark_hovering(input, n, &mut buffers.hovering);
    fill_chunks(&mut bodies.sleep_time, PLACE_CHUNK, |first, times| {
        for (k, time) in times.iter_mut().enumerate() {
            let i = first + k;
            if !awake[i] {
                continue;
            }
            let v = linear_velocity[i];
            let creep = if hovering[i] { v.dot(up).abs() } else { 0.0 };
            let slow = v.norm() < linear_speed
                && creep < hover_speed
                && angular_velocity[i].norm() < angular_speed
                && !kept_awake.get(i).copied().unwrap_or(false);
            if slow && grabbed != Some(i) {
                *time += dt;
            } else {
                *time = 0.0;
            }
        }
    });
    if !rules.enabled {
        return;
    }
    let time_to_sleep = rules.time_to_sleep;
    let awake = &bodies.awake;
    let sleep_time = &bodies.sleep_time;
    let restless = |i: usize| awake[i] && sleep_time[i] < time_to_sleep;
    let mut stays = std::mem::take(&mut buffers.stays_awake);
    stays.clear();
    // With no body rested nothing falls asleep (in a rising crowd, most
    // steps): the pairs, contacts and groups are not looked through.
    if (0..n).all(|i| !awake[i] || restless(i)) {
        stays.resize(n, false);
        keep_impulses(input, warm, bodies, sleeping, &stays);
        buffers.stays_awake = stays;
        return;
    }
    stays.extend((0..n).map(restless));
    // A rested body beside a restless one, or joined to it, stays awake.
    let mixed = |a: usize, b: usize| restless(a) != restless(b) && awake[a] && awake[b];
    let near = |a: usize, b: usize| {
        let (centers, gap) = (input.bound_center, rules.speculative_distance);
        roots_within(input.shapes, bodies, centers, a, b, gap)
    };
    let pairs = input.pairs.iter().filter(|&&(a, b)| {
        let (a, b) = (a as usize, b as usize);
        mixed(a, b) && near(a, b)
    });
    let joined = input
        .joined
        .iter()
        .filter(|&&(a, b)| mixed(a as usize, b as usize));
    for &(a, b) in pairs.chain(joined) {
        stays[a as usize] = true;
        stays[b as usize] = true;
    }
    // From here `stays` means "falls asleep now".
    for i in 0..n {
        stays[i] = bodies.awake[i] && !stays[i];
    }
    let falls_asleep = stays;
    buffers.islands.reset(n);
    for c in input.contacts {
        let (a, b) = (c.body_a as usize, c.body_b as usize);
        if c.body_b != STATIC_BODY
            && c.separation < rules.speculative_distance
            && falls_asleep[a]
            && falls_asleep[b]
        {
            buffers.islands.union(c.body_a, c.body_b);
        }
    }
    for &(a, b) in input.joined {
        if falls_asleep[a as usize] && falls_asleep[b as usize] {
            buffers.islands.union(a, b);
        }
    }
    // One pass: each group's root gets an island, each member joins its root's.
    let island_of_root = &mut buffers.island_of_root;
    island_of_root.clear();
    island_of_root.resize(n, u32::MAX);
    for i in 0..n {
        if !falls_asleep[i] {
            continue;
        }
        let root = buffers.islands.find(i as u32) as usize;
        if island_of_root[root] == u32::MAX {
            island_of_root[root] = sleeping.add(Vec::new());
        }
        let island = island_of_root[root];
        sleeping.members[island as usize].push(bodies.id[i]);
        bodies.island[i] = island;
        bodies.awake[i] = false;
        bodies.linear_velocity[i] = Vec3::ZERO;
        bodies.angular_velocity[i] = Vec3::ZERO;
    }
    keep_impulses(input, warm, bodies, sleeping, &falls_asleep);
    buffers.stays_awake = falls_asleep;
}

/// The sleeping pairs' impulses kept (`SleepingIslands::keep_impulses`),
/// once the bodies that `falls_asleep` marks have fallen asleep.
fn keep_impulses(
    input: &SleepInput,
    warm: &WarmStartCache,
    bodies: &Bodies,
    sleeping: &mut SleepingIslands,
    falls_asleep: &[bool],
) {
    let (handles, awake) = (input.handles, &bodies.awake);
    // The room (`STATIC_BODY`) has no dense index: asleep, never fallen asleep.
    sleeping.keep_impulses(
        warm,
        |handle| handle == STATIC_BODY || handles.dense_at(handle).is_some_and(|i| !awake[i]),
        |handle| handles.dense_at(handle).is_some_and(|i| falls_asleep[i]),
    );
}
