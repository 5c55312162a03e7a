//! The wake pass: what a restless body reaches, or pulls on through a
//! joint, wakes before the step's contacts are found.

use up_geom::norm::distance;

use super::{SleepBuffers, SleepInput, SleepingIslands};
use crate::body::{Bodies, HandleMap, ShapeData};
use crate::world::roots_within;

/// Wakes what a restless body's root sphere reaches; returns whether any
/// body woke. A body whose surface moves faster than the restitution
/// threshold is an impact, whose push must travel through the pile at once:
/// it wakes the whole island of every body it can reach this step, as a user
/// action does, and so does a restless body's pull on a joint. A slower one
/// wakes only the bodies it touches, and they keep their rest time, so they
/// fall asleep again as soon as nothing restless reaches them
/// (`update_sleep`): a sleeping body is static to its awake neighbours, and a
/// slow shuffle in a big pile wakes only what it moves.
pub(crate) fn wake_touched_bodies(
    input: &SleepInput,
    bodies: &mut Bodies,
    sleeping: &mut SleepingIslands,
    buffers: &mut SleepBuffers,
) -> bool {
    let rules = &input.rules;
    buffers.was_awake.clone_from(&bodies.awake);
    let mut woken = std::mem::take(&mut buffers.wake);
    woken.clear();
    let mut islands = std::mem::take(&mut buffers.wake_islands);
    islands.clear();
    // A surface point at the speed from which contacts bounce: anything
    // slower is a shuffle, which a sleeping neighbour may take standing.
    let impact_motion = rules.restitution_threshold * rules.dt;
    // Which of a pair is awake and restless, and which asleep, if so.
    let restless_and_asleep = |a: usize, b: usize| {
        if bodies.awake[a] == bodies.awake[b] {
            return None;
        }
        let (awake, asleep) = if bodies.awake[a] { (a, b) } else { (b, a) };
        (bodies.sleep_time[awake] < rules.time_to_sleep).then_some((awake, asleep))
    };
    for &(a, b) in input.pairs {
        let Some((awake, asleep)) = restless_and_asleep(a as usize, b as usize) else {
            continue;
        };
        let motion = input.motion[awake].reach();
        let impact = motion > impact_motion;
        // A slow body wakes what it touches (root spheres overlap); an
        // impact whatever it can reach this step, which would otherwise
        // stand still for a step as it is struck.
        let reach = if impact {
            rules.speculative_distance + motion
        } else {
            0.0
        };
        let centers = input.bound_center;
        if !roots_within(input.shapes, bodies, centers, awake, asleep, reach) {
            continue;
        }
        if impact {
            islands.push(bodies.island[asleep]);
        } else {
            woken.push(asleep as u32);
        }
    }
    for &(a, b) in input.joined {
        if let Some((_, asleep)) = restless_and_asleep(a as usize, b as usize) {
            islands.push(bodies.island[asleep]);
        }
    }
    islands.sort_unstable();
    islands.dedup();
    for &island in &islands {
        wake_island(bodies, input.handles, sleeping, island);
    }
    // Bodies of islands woken whole are awake already.
    woken.retain(|&i| !bodies.awake[i as usize]);
    // Awake first; then each island they left keeps only its sleepers.
    for &i in &woken {
        bodies.awake[i as usize] = true;
    }
    for w in woken.iter_mut() {
        let i = *w as usize;
        *w = std::mem::replace(&mut bodies.island[i], u32::MAX);
    }
    woken.sort_unstable();
    woken.dedup();
    for &island in &woken {
        let (handles, awake) = (input.handles, &bodies.awake);
        sleeping.retain_members(island, |id| handles.dense(id).is_some_and(|i| !awake[i]));
    }
    let any = !woken.is_empty() || !islands.is_empty();
    buffers.wake = woken;
    buffers.wake_islands = islands;
    any
}

/// Wakes every body of a sleeping island, with its rest time reset.
pub(crate) fn wake_island(
    bodies: &mut Bodies,
    handles: &HandleMap,
    sleeping: &mut SleepingIslands,
    island: u32,
) {
    if island == u32::MAX || island as usize >= sleeping.members.len() {
        return;
    }
    for id in sleeping.take(island) {
        if let Some(i) = handles.dense(id) {
            bodies.awake[i] = true;
            bodies.island[i] = u32::MAX;
            bodies.sleep_time[i] = 0.0;
        }
    }
}

/// Wakes the islands of the sleeping bodies whose bounding spheres come
/// within `gap` of body `i`'s (before it is removed, say).
pub(crate) fn wake_neighbours_of(
    i: usize,
    gap: f32,
    shapes: &[ShapeData],
    bodies: &mut Bodies,
    handles: &HandleMap,
    sleeping: &mut SleepingIslands,
    buffers: &mut SleepBuffers,
) {
    let ri = shapes[bodies.shape[i] as usize].bound_radius * bodies.size[i].scale;
    let ci = bodies.center[i];
    let reach = ri + gap;
    let mut islands = std::mem::take(&mut buffers.wake);
    islands.clear();
    for j in 0..bodies.len() {
        if j == i || bodies.awake[j] {
            continue;
        }
        let rj = shapes[bodies.shape[j] as usize].bound_radius * bodies.size[j].scale;
        if distance(bodies.center[j], ci) <= reach + rj {
            islands.push(bodies.island[j]);
        }
    }
    for &island in &islands {
        wake_island(bodies, handles, sleeping, island);
    }
    buffers.wake = islands;
}
