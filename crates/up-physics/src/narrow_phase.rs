//! Narrowphase: contact points for the broadphase's pairs (sphere tree
//! against sphere tree) and for every awake body against the room (sphere
//! tree against triangle mesh). Contacts are speculative, found up to a
//! margin so that fast bodies meet what lies in their way this step. Against
//! the room it is the speculative distance plus the body's motion. Between two
//! bodies it is a speculative distance for each (either may be struck towards
//! the other within the step) plus the most their gap can close, from their
//! relative motion: balloons rising side by side are to each other as if at
//! rest. A body that a collision may throw further within the step than a
//! speculative distance (`knocks::add_knocks`) widens the margins of the pairs it is
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

/// Room tests and pairs handed to one task.
const TASK_ITEMS: usize = 256;

/// How far a body moves in this step: its displacement v·dt, the angle |ω|·dt
/// it turns through and the arc |ω|·r·dt its bounding sphere's surface
/// travels; how much farther collisions within the step may throw it, and
/// which way (`knock`, see `knocks::add_knocks`), and how far that may turn it
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

    /// A task's list: `runs` pairs from body `first` on, each body's run
    /// 1 to 3 contacts of its own, keyed by the body.
    fn task_list(first: u32, runs: u32) -> ContactList {
        let mut list = ContactList::default();
        for body in first..first + runs {
            let (start, count) = (list.contacts.len() as u32, 1 + body % 3);
            let point = ContactPoint {
                body_a: body,
                body_b: STATIC_BODY,
                normal: Vec3::Z,
                point_a: Vec3::ZERO,
                point_b: Vec3::ZERO,
                separation: -1e-6 * body as f32,
                feature: ContactFeature::default(),
            };
            list.contacts
                .extend(std::iter::repeat_n(point, count as usize));
            list.runs.push((body as u64, start, count));
            list.max_penetration = list.max_penetration.max(1e-6 * body as f32);
        }
        list
    }

    /// Lists joined on three threads (some empty), after a run the list
    /// already held: the runs come in the lists' order, back to back, each
    /// on its own contacts, and the deepest overlap is the deepest of all.
    #[test]
    fn contact_lists_joined_in_tasks_keep_each_run_on_its_contacts() {
        let lists: Vec<ContactList> = (0..40)
            .map(|k| task_list(1 + 200 * k, if k % 5 == 2 { 0 } else { 200 }))
            .collect();
        let mut joined = task_list(0, 1);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        pool.install(|| joined.join_all(&lists));
        assert!(joined.runs.len() > 4_096, "the runs are joined in tasks");
        let keys = joined.runs.iter().map(|&(key, _, _)| key);
        let want = std::iter::once(0).chain(lists.iter().flat_map(|l| l.runs.iter().map(|r| r.0)));
        assert!(keys.eq(want), "runs in the lists' order");
        let mut end = 0;
        for &(key, start, count) in &joined.runs {
            assert_eq!((start, count), (end, 1 + key as u32 % 3), "run {key}");
            let own = &joined.contacts[start as usize..(start + count) as usize];
            assert!(own.iter().all(|c| c.body_a as u64 == key), "run {key}");
            end = start + count;
        }
        assert_eq!(end as usize, joined.contacts.len());
        let deepest = lists.iter().map(|l| l.max_penetration).fold(0.0, f32::max);
        assert_eq!(joined.max_penetration, deepest);
    }
}
