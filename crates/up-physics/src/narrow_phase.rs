//! Narrowphase: contact points for the broadphase's pairs (sphere tree
//! against sphere tree) and for every awake body against the room (sphere
//! tree against triangle mesh). Contacts are speculative, found up to a
//! margin so that fast bodies meet what lies in their way this step. Against
//! the room it is the speculative distance plus the body's motion. Between two
//! bodies it is a speculative distance for each (either may be struck towards
//! the other within the step) plus the most their gap can close, from their
//! relative motion: balloons rising side by side are to each other as if at
//! rest.
//!
//! With the `parallel` feature and more than one thread, the tests are split
//! into tasks of consecutive bodies and pairs, each with its own list, joined
//! in task order afterwards (`tasks::collect_in_order`): the contacts come
//! out in the same order, so the step's results are bit-identical whatever
//! the number of threads.

use glam::Vec3;
use up_geom::query::contact_tree_tree::contact_tree_tree;
use up_geom::query::contact_tree_trimesh::contact_tree_trimesh;
use up_geom::{Contact, PlacedTree, TriMesh};

use crate::body::ShapeData;
use crate::contact::{pair_key, ContactPoint, STATIC_BODY};
use crate::tasks::{collect_in_order, TaskList};

/// Room tests and pairs handed to one task.
const TASK_ITEMS: usize = 256;

/// How far a body moves in this step: its displacement v·dt and the arc
/// |ω|·r·dt its bounding sphere's surface turns through.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct StepMotion {
    pub linear: Vec3,
    pub spin: f32,
}

impl StepMotion {
    /// The farthest any point of the body moves, m.
    pub fn reach(self) -> f32 {
        self.linear.length() + self.spin
    }

    /// The most the gap between a point of this body and one of `other` can
    /// close, m: their relative displacement and both spins.
    pub fn closing(self, other: StepMotion) -> f32 {
        (self.linear - other.linear).length() + self.spin + other.spin
    }
}

/// What the narrowphase reads about the bodies (all dense-indexed).
pub(crate) struct NarrowInput<'a> {
    pub shapes: &'a [ShapeData],
    pub shape: &'a [u32],
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
    fn placed(&self, i: usize) -> PlacedTree<'_> {
        let tree = &self.shapes[self.shape[i] as usize].tree;
        let start = self.node_start[i] as usize;
        PlacedTree {
            tree,
            centers: &self.node_centers[start..start + tree.nodes().len()],
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
}

impl ContactList {
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
                let margin = input.speculative_distance + input.motion[a as usize].reach();
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
            let closing = input.motion[a as usize].closing(input.motion[b as usize]);
            let margin = 2.0 * input.speculative_distance + closing;
            scratch.clear();
            contact_tree_tree(
                input.placed(a as usize),
                input.placed(b as usize),
                margin,
                &mut scratch,
            );
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
                feature: ((c.feature_a as u64) << 32) | c.feature_b as u64,
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
