//! Narrowphase: contact points for the broadphase's pairs (sphere tree
//! against sphere tree) and for every awake body against the room (sphere
//! tree against triangle mesh). Contacts are speculative, found up to a
//! margin so that fast bodies meet what lies in their way this step. Against
//! the room it is the speculative distance plus the body's motion. Between two
//! bodies it is a speculative distance for each (either may be struck towards
//! the other within the step) plus the most their gap can close, from their
//! relative motion: balloons rising side by side are to each other as if at
//! rest. A body that a collision may throw further within the step than a
//! speculative distance (`add_knocks`) widens the margins of the pairs it is
//! thrown towards, and its margin with the room. Of the several leaf pairs two
//! trees meet at, the gaps a shallower contact shadows are dropped
//! (`prune_shadowed`), by the motion the margin stands for: the gaps that
//! cannot close this step before that contact has.
//!
//! With the `parallel` feature and more than one thread, the tests are split
//! into tasks of consecutive bodies and pairs, each with its own list, joined
//! in task order afterwards (`tasks::collect_in_order`): the contacts come
//! out in the same order, so the step's results are bit-identical whatever
//! the number of threads.

use glam::Vec3;
use up_geom::norm::{unit_or_zero, Norm};
use up_geom::query::contact_tree_tree::contact_tree_tree;
use up_geom::query::contact_tree_trimesh::contact_tree_trimesh;
use up_geom::{prune_shadowed, Contact, PlacedTree, RelativeMotion, TriMesh};

use crate::body::{BodySize, ShapeData};
use crate::contact::{pair_key, ContactFeature, ContactPoint, STATIC_BODY};
use crate::threading::join::append_lists;
use crate::threading::spare::{release_spare, BUFFER_FLOOR, TASK_LIST_FLOOR};
use crate::threading::tasks::{collect_in_order, TaskList};

/// Broadphase pairs whose knocks one task finds.
#[cfg(feature = "parallel")]
const KNOCK_CHUNK: usize = 2048;

/// Room tests and pairs handed to one task.
const TASK_ITEMS: usize = 256;

/// How far a body moves in this step: its displacement v·dt, the angle |ω|·dt
/// it turns through and the arc |ω|·r·dt its bounding sphere's surface
/// travels; how much farther collisions within the step may throw it, and
/// which way (`knock`, see `add_knocks`), and how far that may turn it
/// (`knock_turn`: the knock struck off the centre, `ShapeData::turn_per_knock`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct StepMotion {
    pub linear: Vec3,
    pub spin: f32,
    pub turn: f32,
    pub knock: Vec3,
    pub knock_turn: f32,
}

impl StepMotion {
    /// The most the body can turn this step, rad: as it spins, and as its
    /// knock may turn it.
    pub fn most_turn(self) -> f32 {
        self.turn + self.knock_turn
    }

    /// The farthest any point of the body moves, m.
    pub fn reach(self) -> f32 {
        self.linear.norm() + self.spin
    }

    /// The most the gap between a point of this body and one of `other` can
    /// close, m: their relative displacement and both spins.
    pub fn closing(self, other: StepMotion) -> f32 {
        (self.linear - other.linear).norm() + self.spin + other.spin
    }

    /// How much farther than `closing` the gap may close when the bodies'
    /// knocks throw them along `towards` (unit, from this body to `other`),
    /// beyond the `allowance` each already has for that.
    pub fn knocked_closer(self, other: StepMotion, towards: Vec3, allowance: f32) -> f32 {
        (self.knock.dot(towards) - allowance).max(0.0)
            + (other.knock.dot(-towards) - allowance).max(0.0)
    }
}

/// Sets each body's `knock`: for every neighbour it may meet this step (root
/// spheres within twice the speculative distance and their closing, as
/// `roots_within(a, b, gap)` says), the
/// most that collision can change its velocity in the step (the closing
/// times `share`, (1 + e)·m_other / (m + m_other)), pointing away from that
/// neighbour, summed. The margins were set from the velocities at the step's
/// start: a column rising together, whose top balloon is stopped, throws the
/// next one down onto the one below, which had no contact with it (balloons
/// moving together have none), 2.4 mm deep in one step. Only pairs that a
/// knock throws together get a wider margin: balloons arriving side by side
/// under a pile that stops them do not.
///
/// With several threads each pair's two knocks are found in tasks (they read
/// only the step's motion, not the knocks), into `thrown`, then summed in
/// pair order: the same sums as one thread's, bit for bit.
pub(crate) fn add_knocks(
    motion: &mut [StepMotion],
    pairs: &[(u32, u32)],
    #[cfg_attr(not(feature = "parallel"), allow(unused_variables, clippy::ptr_arg))]
    thrown: &mut Vec<Option<[Vec3; 2]>>,
    centers: impl Fn(usize) -> Vec3 + Sync,
    roots_within: impl Fn(usize, usize, f32) -> bool + Sync,
    share: impl Fn(usize, usize) -> f32 + Sync,
    speculative_distance: f32,
) {
    // What a pair's collision may throw a and b by (a away from b, b away from a).
    let knocks = |motion: &[StepMotion], a: usize, b: usize| {
        let closing = motion[a].closing(motion[b]);
        if closing > 0.0 && roots_within(a, b, 2.0 * speculative_distance + closing) {
            let towards_b = unit_or_zero(centers(b) - centers(a));
            Some([
                share(a, b) * closing * towards_b,
                share(b, a) * closing * towards_b,
            ])
        } else {
            None
        }
    };
    let sum = |motion: &mut [StepMotion], (a, b): (u32, u32), knocks: Option<[Vec3; 2]>| {
        if let Some([to_a, to_b]) = knocks {
            motion[a as usize].knock -= to_a;
            motion[b as usize].knock += to_b;
        }
    };
    for m in motion.iter_mut() {
        m.knock = Vec3::ZERO;
    }
    #[cfg(feature = "parallel")]
    if crate::threading::tasks::worth_splitting(pairs.len(), KNOCK_CHUNK) {
        thrown.resize(pairs.len(), None);
        let read: &[StepMotion] = motion;
        crate::threading::tasks::fill_chunks(thrown, KNOCK_CHUNK, |first, out| {
            for (k, t) in out.iter_mut().enumerate() {
                let (a, b) = pairs[first + k];
                *t = knocks(read, a as usize, b as usize);
            }
        });
        for (&pair, &t) in pairs.iter().zip(thrown.iter()) {
            sum(motion, pair, t);
        }
        return;
    }
    // Unused this step: its length must say so (`spare`).
    #[cfg(feature = "parallel")]
    thrown.clear();
    for &(a, b) in pairs {
        let t = knocks(motion, a as usize, b as usize);
        sum(motion, (a, b), t);
    }
}

/// What the narrowphase reads about the bodies (all dense-indexed).
pub(crate) struct NarrowInput<'a> {
    pub shapes: &'a [ShapeData],
    pub shape: &'a [u32],
    /// Each body's size (its tree's scale).
    pub size: &'a [BodySize],
    pub node_centers: &'a [Vec3],
    pub node_start: &'a [u32],
    pub handle: &'a [u32],
    pub awake: &'a [bool],
    /// Each body's motion this step (zero for sleepers).
    pub motion: &'a [StepMotion],
    /// Gap up to which a body at rest gets contacts with the room (twice
    /// that with another body), m.
    pub speculative_distance: f32,
}

impl NarrowInput<'_> {
    fn root_center(&self, i: u32) -> Vec3 {
        self.node_centers[self.node_start[i as usize] as usize]
    }

    fn placed(&self, i: usize) -> PlacedTree<'_> {
        let tree = &self.shapes[self.shape[i] as usize].tree;
        let start = self.node_start[i] as usize;
        PlacedTree {
            tree,
            centers: &self.node_centers[start..start + tree.nodes().len()],
            scale: self.size[i].scale,
        }
    }
}

/// Contact points grouped by pair.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactList {
    pub contacts: Vec<ContactPoint>,
    /// (pair key, first contact, count), one per pair with contacts.
    pub runs: Vec<(u64, u32, u32)>,
    /// Deepest overlap, m.
    pub max_penetration: f32,
    /// A query's contacts, before they become points of the list.
    scratch: Vec<Contact>,
    /// Where each task's contacts start in this list, as `join_all` joins them.
    run_offsets: Vec<u32>,
}

impl ContactList {
    /// See `spare::release_spare`.
    fn release_spare(&mut self, floor_bytes: usize) {
        release_spare(&mut self.contacts, floor_bytes);
        release_spare(&mut self.runs, floor_bytes);
    }

    pub fn clear(&mut self) {
        self.contacts.clear();
        self.runs.clear();
        self.max_penetration = 0.0;
    }

    /// Appends the contacts of `bodies` with the room, then of `pairs`.
    fn collect(
        &mut self,
        input: &NarrowInput,
        room: Option<&TriMesh>,
        bodies: &[u32],
        pairs: &[(u32, u32)],
    ) {
        let mut scratch = std::mem::take(&mut self.scratch);
        if let Some(room) = room {
            for &a in bodies {
                scratch.clear();
                let m = input.motion[a as usize];
                let margin = input.speculative_distance + m.reach() + m.knock.norm();
                contact_tree_trimesh(input.placed(a as usize), room, margin, &mut scratch);
                let key = pair_key(input.handle[a as usize], STATIC_BODY);
                self.push_run(&scratch, key, a, STATIC_BODY);
            }
        }
        for &(i, j) in pairs {
            // Order each pair by handle index: the warm-start key must not
            // depend on dense order, which removal changes.
            let (a, b) = if input.handle[i as usize] < input.handle[j as usize] {
                (i, j)
            } else {
                (j, i)
            };
            let (ma, mb) = (input.motion[a as usize], input.motion[b as usize]);
            let towards_b = unit_or_zero(input.root_center(b) - input.root_center(a));
            let margin = 2.0 * input.speculative_distance
                + ma.closing(mb)
                + ma.knocked_closer(mb, towards_b, input.speculative_distance);
            scratch.clear();
            contact_tree_tree(
                input.placed(a as usize),
                input.placed(b as usize),
                margin,
                &mut scratch,
            );
            // Judged by the motion the margin stands for: what a gap between
            // the two may close this step. That is the margin's own model,
            // not a strict bound: a knock counts only along the line of
            // centres, and a turn the step brings otherwise (resting
            // contacts, buoyancy) not at all. Stricter bounds (the knocks'
            // whole lengths, their turns' arcs) keep most of the gaps; with
            // this one a few impacts close a dropped gap, within the soaks'
            // bound (docs/perf-log.md).
            let motion = RelativeMotion {
                displacement: margin,
                turn: ma.most_turn() + mb.most_turn(),
            };
            prune_shadowed(&mut scratch, motion);
            let key = pair_key(input.handle[a as usize], input.handle[b as usize]);
            self.push_run(&scratch, key, a, b);
        }
        self.scratch = scratch;
    }

    fn push_run(&mut self, found: &[Contact], key: u64, a: u32, b: u32) {
        if found.is_empty() {
            return;
        }
        let start = self.contacts.len() as u32;
        for c in found {
            self.max_penetration = self.max_penetration.max(c.depth());
            self.contacts.push(ContactPoint {
                body_a: a,
                body_b: b,
                normal: c.normal,
                point_a: c.point_a,
                point_b: c.point_b,
                separation: c.separation,
                feature: ContactFeature {
                    leaf_a: c.feature_a,
                    part_b: c.feature_b,
                },
            });
        }
        self.runs.push((key, start, found.len() as u32));
    }
}

impl TaskList for ContactList {
    fn reset(&mut self) {
        self.clear();
    }

    /// Appends another list (its runs moved past this one's contacts).
    fn join(&mut self, other: &ContactList) {
        let offset = self.contacts.len() as u32;
        self.contacts.extend_from_slice(&other.contacts);
        self.runs.extend(
            other
                .runs
                .iter()
                .map(|&(key, start, count)| (key, start + offset, count)),
        );
        self.max_penetration = self.max_penetration.max(other.max_penetration);
    }

    /// Appends the lists' contacts and runs in tasks (`join::append_lists`),
    /// each list's runs moved past the contacts before its own.
    fn join_all(&mut self, lists: &[Self]) {
        self.run_offsets.clear();
        let mut offset = self.contacts.len() as u32;
        for list in lists {
            self.run_offsets.push(offset);
            offset += list.contacts.len() as u32;
            self.max_penetration = self.max_penetration.max(list.max_penetration);
        }
        append_lists(&mut self.contacts, lists, |l| &l.contacts[..], |_, &c| c);
        let offsets = &self.run_offsets;
        append_lists(
            &mut self.runs,
            lists,
            |l| &l.runs[..],
            |k, &run| {
                let (key, start, count) = run;
                (key, start + offsets[k], count)
            },
        );
    }
}

#[derive(Clone, Debug, Default)]
pub(crate) struct NarrowPhase {
    /// Output: this step's contacts.
    pub found: ContactList,
    /// Awake bodies, tested against the room.
    room_tests: Vec<u32>,
    /// Each task's contacts (kept between steps for their buffers).
    tasks: Vec<ContactList>,
}

impl NarrowPhase {
    /// Gives back the capacity this step's contacts left unused (`spare`).
    pub fn release_spare(&mut self) {
        self.found.release_spare(BUFFER_FLOOR);
        for list in &mut self.tasks {
            list.release_spare(TASK_LIST_FLOOR);
        }
    }

    pub fn update(&mut self, input: &NarrowInput, pairs: &[(u32, u32)], room: Option<&TriMesh>) {
        self.found.clear();
        // The room first: it anchors the pile, and Gauss-Seidel converges
        // fastest from the anchor outwards.
        self.room_tests.clear();
        if room.is_some() {
            let awake = input.awake.iter().enumerate().filter(|(_, &awake)| awake);
            self.room_tests.extend(awake.map(|(a, _)| a as u32));
        }
        let (tests, n) = (&self.room_tests, self.room_tests.len());
        let items = n + pairs.len();
        collect_in_order(
            items,
            TASK_ITEMS,
            &mut self.tasks,
            &mut self.found,
            |range, list| {
                // Items: the room tests first, then the pairs.
                let room_tests = &tests[range.start.min(n)..range.end.min(n)];
                let pairs = &pairs[range.start.max(n) - n..range.end.max(n) - n];
                list.collect(input, room, room_tests, pairs);
            },
        );
    }
}

#[cfg(all(test, feature = "parallel"))]
mod tests {
    use super::*;
    use crate::hash::uniform;

    /// Knocks found in tasks and summed in pair order are the serial sums, bit
    /// for bit: random motions, over 5,000 pairs (split on three threads, whole on
    /// one), most bodies knocked by several neighbours.
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
            let mut thrown = Vec::new();
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                add_knocks(
                    &mut motion,
                    &pairs,
                    &mut thrown,
                    |i| centers[i],
                    |a, b, gap| centers[a].distance(centers[b]) < 0.8 + gap,
                    |a, b| 1.4 * inv_mass[a] / (inv_mass[a] + inv_mass[b]),
                    0.01,
                )
            });
            assert_eq!(thrown.len(), if threads > 1 { pairs.len() } else { 0 });
            motion
        };
        let (serial, split) = (knocked(1), knocked(3));
        let bits = |m: &[StepMotion]| -> Vec<[u32; 3]> {
            m.iter()
                .map(|m| m.knock.to_array().map(f32::to_bits))
                .collect()
        };
        assert_eq!(bits(&split), bits(&serial));
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
