//! How far collisions within the step may throw each body (`StepMotion::knock`),
//! from the broadphase's pairs, for the narrowphase's margins.
//!
//! With several threads the pairs' knocks are found in tasks and listed in
//! pair order, and each thread then sums them for a range of bodies of its
//! own, reading the whole list: every body adds its knocks up in pair order,
//! as one thread does, so the sums are the same bit for bit.

use glam::Vec3;

use crate::narrow_phase::StepMotion;
use crate::threading::spare::{release_spare, TASK_LIST_FLOOR};

/// Broadphase pairs whose knocks one task finds.
#[cfg(feature = "parallel")]
const KNOCK_CHUNK: usize = 2048;

/// Bodies a task calls `add_knocks`' `then` on, when the knocks were summed
/// on one thread.
const THEN_CHUNK: usize = 512;

/// What a pair's collision may throw its bodies by: `a` by `-to_a`, `b` by `to_b`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Thrown {
    a: u32,
    b: u32,
    to_a: Vec3,
    to_b: Vec3,
}

/// Each task's knocking pairs, in pair order, in a step whose knocks are
/// found in tasks (empty otherwise), kept for their buffers.
#[derive(Clone, Debug, Default)]
pub(crate) struct KnockLists {
    tasks: Vec<Vec<Thrown>>,
}

impl KnockLists {
    /// Gives back the capacity the lists left unused (`spare`).
    pub fn release_spare(&mut self) {
        for list in &mut self.tasks {
            release_spare(list, TASK_LIST_FLOOR);
        }
    }

    /// The knocking pairs listed, in pair order.
    #[cfg(feature = "parallel")]
    fn thrown(&self) -> impl Iterator<Item = &Thrown> {
        self.tasks.iter().flatten()
    }
}

/// Sets each body's `knock`: for every neighbour it may meet this step (root
/// spheres within twice the speculative distance and their closing:
/// `towards_within(a, b, gap)` gives the unit vector from a to b then), the
/// most that collision can change its velocity in the step (the closing
/// times `share`, (1 + e)·m_other / (m + m_other)), pointing away from that
/// neighbour, summed. The margins were set from the velocities at the step's
/// start: a column rising together, whose top balloon is stopped, throws the
/// next one down onto the one below, which had no contact with it (balloons
/// moving together have none), 2.4 mm deep in one step. Only pairs that a
/// knock throws together get a wider margin: balloons arriving side by side
/// under a pile that stops them do not. Then `then(i, motion)` once a body,
/// its knock summed.
pub(crate) fn add_knocks(
    motion: &mut [StepMotion],
    pairs: &[(u32, u32)],
    lists: &mut KnockLists,
    towards_within: impl Fn(usize, usize, f32) -> Option<Vec3> + Sync,
    share: impl Fn(usize, usize) -> f32 + Sync,
    speculative_distance: f32,
    then: impl Fn(usize, &mut StepMotion) + Sync,
) {
    let knocks = |motion: &[StepMotion], (a, b): (u32, u32)| {
        let (i, j) = (a as usize, b as usize);
        let closing = motion[i].closing(motion[j]);
        if closing <= 0.0 {
            return None;
        }
        let towards_b = towards_within(i, j, 2.0 * speculative_distance + closing)?;
        Some(Thrown {
            a,
            b,
            to_a: share(i, j) * closing * towards_b,
            to_b: share(j, i) * closing * towards_b,
        })
    };
    #[cfg(feature = "parallel")]
    if crate::threading::tasks::worth_splitting(pairs.len(), KNOCK_CHUNK) {
        let read: &[StepMotion] = motion;
        let tasks = pairs.len().div_ceil(KNOCK_CHUNK);
        if lists.tasks.len() < tasks {
            lists.tasks.resize_with(tasks, Vec::new);
        }
        // Not joined: the sums read the tasks' lists one after another.
        let (found, idle) = lists.tasks.split_at_mut(tasks);
        crate::threading::tasks::fill_chunks(found, 1, |first, lists| {
            for (k, list) in lists.iter_mut().enumerate() {
                let task = first + k;
                let run = task * KNOCK_CHUNK..((task + 1) * KNOCK_CHUNK).min(pairs.len());
                list.clear();
                list.extend(pairs[run].iter().filter_map(|&p| knocks(read, p)));
            }
        });
        idle.iter_mut().for_each(Vec::clear);
        sum_by_body_range(motion, lists, then);
        return;
    }
    // Unused this step: their lengths must say so (`spare`).
    lists.tasks.iter_mut().for_each(Vec::clear);
    for m in motion.iter_mut() {
        m.knock = Vec3::ZERO;
    }
    for &pair in pairs {
        if let Some(t) = knocks(motion, pair) {
            motion[t.a as usize].knock -= t.to_a;
            motion[t.b as usize].knock += t.to_b;
        }
    }
    crate::threading::tasks::fill_chunks(motion, THEN_CHUNK, |first, motions| {
        for (k, m) in motions.iter_mut().enumerate() {
            then(first + k, m);
        }
    });
}

/// Sums the listed knocks into the bodies' knocks, a range of bodies a
/// thread (each reads the whole list in order and adds what falls in its
/// range), then calls `then` on each of its bodies.
#[cfg(feature = "parallel")]
fn sum_by_body_range(
    motion: &mut [StepMotion],
    lists: &KnockLists,
    then: impl Fn(usize, &mut StepMotion) + Sync,
) {
    let range = motion
        .len()
        .div_ceil(crate::threading::tasks::threads_here())
        .max(1);
    crate::threading::tasks::fill_chunks(motion, range, |first, mine| {
        for m in mine.iter_mut() {
            m.knock = Vec3::ZERO;
        }
        let len = mine.len();
        let mine_at = |body: u32| (body as usize).checked_sub(first).filter(|&k| k < len);
        for t in lists.thrown() {
            if let Some(k) = mine_at(t.a) {
                mine[k].knock -= t.to_a;
            }
            if let Some(k) = mine_at(t.b) {
                mine[k].knock += t.to_b;
            }
        }
        for (k, m) in mine.iter_mut().enumerate() {
            then(first + k, m);
        }
    });
}

#[cfg(all(test, feature = "parallel"))]
mod tests {
    use up_geom::norm::unit_or_zero;

    use super::*;
    use crate::hash::uniform;

    /// Knocks found in tasks and summed a body range a task are the serial
    /// sums, bit for bit: random motions, over 5,000 pairs (split on two and
    /// three threads, whole on one), most bodies knocked by several neighbours.
    #[test]
    fn knocks_found_in_tasks_sum_as_on_one_thread() {
        let mut random = uniform(7);
        let n = 1500;
        let centers: Vec<Vec3> = (0..n)
            .map(|_| Vec3::new(random(), random(), random()) * 3.0)
            .collect();
        let inv_mass: Vec<f32> = (0..n).map(|_| 1.0 + 9.0 * random()).collect();
        let start: Vec<StepMotion> = (0..n)
            .map(|_| StepMotion {
                linear: (Vec3::new(random(), random(), random()) - 0.5) * 0.04,
                spin: 0.005 * random(),
                ..StepMotion::default()
            })
            .collect();
        let mut pairs: Vec<(u32, u32)> = (0..n as u32)
            .flat_map(|a| {
                let picks: Vec<u32> = (0..5).map(|_| (random() * n as f32) as u32).collect();
                picks
                    .into_iter()
                    .filter(move |&b| b > a)
                    .map(move |b| (a, b))
            })
            .collect();
        pairs.extend((0..n as u32 - 1).map(|a| (a, a + 1)));
        pairs.sort_unstable();
        assert!(pairs.len() > 2 * KNOCK_CHUNK, "{} pairs", pairs.len());
        let knocked = |threads: usize| {
            let mut motion = start.clone();
            let mut lists = KnockLists::default();
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                add_knocks(
                    &mut motion,
                    &pairs,
                    &mut lists,
                    |a, b, gap| {
                        (centers[a].distance(centers[b]) < 0.8 + gap)
                            .then(|| unit_or_zero(centers[b] - centers[a]))
                    },
                    |a, b| 1.4 * inv_mass[a] / (inv_mass[a] + inv_mass[b]),
                    0.01,
                    |i, m| m.knock_turn += 1.0 + i as f32,
                )
            });
            // `then` once a body, with its index.
            let once = motion.iter().enumerate();
            assert!(once.clone().all(|(i, m)| m.knock_turn == 1.0 + i as f32));
            // Split, only the knocking pairs are listed; whole, none are.
            let listed = lists.thrown().count();
            assert!(
                threads > 1 && listed > 0 && listed < pairs.len() || threads == 1 && listed == 0
            );
            motion
        };
        let serial = knocked(1);
        let bits = |m: &[StepMotion]| -> Vec<[u32; 3]> {
            m.iter()
                .map(|m| m.knock.to_array().map(f32::to_bits))
                .collect()
        };
        for threads in [2, 3] {
            assert_eq!(bits(&knocked(threads)), bits(&serial), "{threads} threads");
        }
        let knocked_thrice = (0..n)
            .filter(|&i| {
                let touches = |&&(a, b): &&(u32, u32)| a as usize == i || b as usize == i;
                pairs.iter().filter(touches).count() >= 3 && serial[i].knock != Vec3::ZERO
            })
            .count();
        assert!(
            knocked_thrice > n / 3,
            "{knocked_thrice} bodies in 3+ pairs knocked"
        );
    }
}
