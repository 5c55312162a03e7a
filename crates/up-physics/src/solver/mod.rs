//! The soft-step solver (Box2D v3, Box3D, Rapier ≥ 0.29), in named stages:
//!
//! 1. prepare: forces for each body; the contacts are coloured (`coloring`)
//!    and prepared into groups of four (`lanes`), warm-started from the last
//!    step, so that each pass solves four constraints with one stream of SIMD
//!    instructions and can run a colour's groups on several threads
//!    (`parallel`; there a substep's passes, and the position passes that
//!    always run, are each one staged run, `fused`);
//! 2. per substep: integrate velocities (forces), warm start, solve (soft
//!    push-out of overlap), integrate positions, project the joints to their
//!    lengths (`joint_constraint`, position level), the ribbons (a
//!    `SubstepPart` in `SubstepParts::ribbons`, `ribbon::solve`), relax (no push-out, so the
//!    push-out's velocity does not linger as jitter; each contact's separation
//!    is first brought to the new positions in the same pass);
//! 3. restitution (bounces), and store impulses for the next step;
//! 4. stabilise: overlap beyond a slop is removed from the positions directly.

#[cfg(feature = "parallel")]
pub(crate) mod awake_blocks;
pub(crate) mod body_lanes;
pub(crate) mod body_state;
pub(crate) mod coloring;
pub(crate) mod contact_constraint;
#[cfg(feature = "parallel")]
pub(crate) mod fused;
pub(crate) mod integrate;
pub(crate) mod joint_constraint;
pub(crate) mod lanes;
#[cfg(test)]
mod one_sided_tests;
#[cfg(test)]
mod overflow_tests;
pub(crate) mod parallel;
pub(crate) mod position_skips;
pub(crate) mod probe;
#[cfg(all(test, feature = "parallel"))]
mod scatter_tests;
pub(crate) mod softness;
#[cfg(test)]
mod stabilize_tests;
#[cfg(test)]
mod test_support;
pub(crate) mod zones;

use std::sync::atomic::{AtomicBool, Ordering};

use body_lanes::{Displacements, Poses, Velocities};
use body_state::BodyState;
use coloring::{Coloring, Moving};
use contact_constraint::{
    Bias, ContactGroup, ContactTotals, GroupAnchors, GroupRecords, PreparedContact,
};
use integrate::GrabSpring;
use joint_constraint::{JointColouring, PreparedJoint};
use lanes::LANES;
use parallel::{for_each_body, for_each_colored, for_each_group, GroupStates};
use position_skips::PositionSkips;

use crate::contact::StoredImpulse;
use crate::forces::BodyForces;
use crate::threading::spare::{release_spare, BUFFER_FLOOR};
use crate::threading::tasks::fill_chunks;

/// Constraints whose impulses one task stores.
const STORE_CHUNK: usize = 1024;

/// Buffers reused from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Solver {
    /// One per body (dense order), then the static room's at `room`.
    pub states: Vec<BodyState>,
    /// The room's state: fixed ends of contacts and joints.
    pub room: u32,
    pub forces: Vec<BodyForces>,
    /// The contact constraints, `LANES` to a group, colour by colour
    /// (`coloring.slot` says where each went), in three parts: what the
    /// velocity passes use, the anchors the position passes use, and records.
    groups: Vec<ContactGroup>,
    anchors: Vec<GroupAnchors>,
    records: Vec<GroupRecords>,
    coloring: Coloring,
    /// Which groups the position passes can skip.
    skips: PositionSkips,
    /// This step's joints, colour after colour (`joint_constraint`).
    pub joints: Vec<PreparedJoint>,
    joint_colouring: JointColouring,
    /// Dense indices of the awake bodies.
    pub awake: Vec<u32>,
    /// Each body's zone, a slab of the room that orders the constraints
    /// within their colours (`coloring`): set on several threads, empty on one.
    pub zones: Vec<u8>,
    /// The awake bodies by zone, in blocks for the substep's body passes.
    #[cfg(feature = "parallel")]
    awake_blocks: awake_blocks::AwakeBlocks,
    /// This step's substep as one staged run (`fused`).
    #[cfg(feature = "parallel")]
    substep: fused::SubstepStages,
    /// The position passes that always run, as one staged run (`fused`).
    #[cfg(feature = "parallel")]
    position_passes: fused::SubstepStages,
}

/// The parameters of one step's solve.
pub(crate) struct SolveParams {
    pub dt: f32,
    pub substeps: u32,
    pub iterations: u32,
    pub contact_hertz: f32,
    pub contact_damping_ratio: f32,
    pub max_push_out: f32,
    pub friction: f32,
    pub angular_damping: f32,
}

/// A part of every substep that the world hands the solver in a named slot
/// of `SubstepParts`, which the solver runs at that slot's place: it reads
/// the bodies' states and may move them (impulses, pulls).
pub(crate) trait SubstepPart {
    /// One substep of this part.
    fn substep(&mut self, states: &mut [BodyState]);
}

/// What moves in the substeps besides the bodies, the contacts and the
/// joints that the solver holds itself, each in the slot that says where in
/// the substep it runs. An empty slot costs nothing.
#[derive(Default)]
pub(crate) struct SubstepParts<'a> {
    /// After the positions are integrated and the joints projected, before
    /// the relax pass: the ribbons (`ribbon::solve::RibbonSubsteps`).
    pub ribbons: Option<&'a mut dyn SubstepPart>,
}

/// How the position passes run after the solve (`Solver::stabilize`).
pub(crate) struct Stabilization {
    /// Overlap left alone, m.
    pub slop: f32,
    /// Overlap that calls for another pass, m.
    pub target: f32,
    pub min_passes: u32,
    pub max_passes: u32,
}

/// Runs a velocity pass's kernel on a group: gathers the bodies' velocities
/// into lanes, and scatters them back. A fixed side is the constant it would
/// gather, and nothing is written back to it: the kernel is inlined in each
/// case, so what it computes for that side alone is left out.
#[inline]
fn on_velocities(
    g: &mut ContactGroup,
    mut states: GroupStates,
    kernel: impl Fn(&mut ContactGroup, &mut Velocities, &mut Velocities),
) {
    match states.moving {
        Moving::Both => {
            let mut a = Velocities::gather(states.read(0));
            let mut b = Velocities::gather(states.read(1));
            kernel(g, &mut a, &mut b);
            states.write(0, a.scatter());
            states.write(1, b.scatter());
        }
        Moving::A => {
            let (mut a, mut b) = (Velocities::gather(states.read(0)), Velocities::FIXED);
            kernel(g, &mut a, &mut b);
            states.write(0, a.scatter());
        }
        Moving::B => {
            let (mut a, mut b) = (Velocities::FIXED, Velocities::gather(states.read(1)));
            kernel(g, &mut a, &mut b);
            states.write(1, b.scatter());
        }
    }
}

/// A position pass on group `i` (`Solver::stabilize`); sets `beyond_target`
/// if a contact is still deeper than the target.
#[inline]
fn position_group(
    g: &mut ContactGroup,
    anchors: &GroupAnchors,
    mut states: GroupStates,
    (i, skips): (usize, &PositionSkips),
    s: &Stabilization,
    beyond_target: &AtomicBool,
) {
    // Would move nothing (`position_skips`): what it found last time holds.
    let travel = skips.travel_of([&g.a, &g.b]);
    if skips.can_skip(i, travel) {
        return;
    }
    let displacements =
        |side| gather_side(&states, side, Displacements::FIXED, Displacements::gather);
    let (mut a, mut b) = (displacements(0), displacements(1));
    let push = contact_constraint::stabilize(g, anchors, &mut a, &mut b, s.slop, s.target);
    skips.ran(i, travel, push.room_left);
    if !push.moved {
        return;
    }
    if push.beyond_target {
        beyond_target.store(true, Ordering::Relaxed);
    }
    let sides = [(&a, g.a, push.distance[0]), (&b, g.b, push.distance[1])];
    for (side, (d, bodies, distance)) in sides.into_iter().enumerate() {
        if states.moving.fixes(side) {
            continue;
        }
        let scatter = d.scatter();
        states.write(side, |lane, state| {
            scatter(lane, state);
            skips.moved(bodies[lane], distance.as_array()[lane]);
        });
    }
}

/// The relax pass on one group (`Solver::refresh_and_relax`).
#[inline]
fn relax_group(g: &mut ContactGroup, anchors: &GroupAnchors, sides: GroupStates, relax: &Bias) {
    let poses = |side| gather_side(&sides, side, Poses::FIXED, Poses::gather);
    let (a, b) = (poses(0), poses(1));
    contact_constraint::refresh(g, anchors, &a, &b);
    on_velocities(g, sides, |c, a, b| {
        contact_constraint::solve(c, a, b, relax)
    });
    g.add_substep();
}

/// Side `side` of a group as `gather` reads it; for a fixed side, `fixed`
/// (what it would read) without reading.
#[inline]
fn gather_side<T>(
    states: &GroupStates,
    side: usize,
    fixed: T,
    gather: impl FnOnce([&BodyState; LANES]) -> T,
) -> T {
    if states.moving.fixes(side) {
        fixed
    } else {
        gather(states.read(side))
    }
}

impl Solver {
    /// Gives back the capacity this step's constraints left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.groups, BUFFER_FLOOR);
        release_spare(&mut self.anchors, BUFFER_FLOOR);
        release_spare(&mut self.records, BUFFER_FLOOR);
        self.coloring.release_spare();
        self.skips.release_spare();
        #[cfg(feature = "parallel")]
        {
            self.awake_blocks.release_spare();
            self.substep.release_spare();
            self.position_passes.release_spare();
        }
    }

    /// Colours the constraints of this step from their body pairs (state
    /// indices, in the narrowphase's order) and makes room for them; then
    /// `set_constraint` each, in the same order. Call after the states are in place.
    pub fn begin_constraints(&mut self, pairs: impl Iterator<Item = (u32, u32)>) {
        let (n, room) = self.colour(pairs);
        self.groups.clear();
        self.groups.resize(n, ContactGroup::empty(room));
        self.anchors.clear();
        self.anchors.resize(n, GroupAnchors::default());
        self.records.clear();
        self.records.resize(n, GroupRecords::default());
    }

    /// Colours the constraints; returns how many groups they fill and the
    /// room's state.
    fn colour(&mut self, pairs: impl Iterator<Item = (u32, u32)>) -> (usize, u32) {
        self.coloring.assign(pairs, &self.states, &self.zones);
        // Off the critical path too (`set_constraints`).
        #[cfg(feature = "parallel")]
        self.awake_blocks.cut(
            &self.awake,
            &self.zones,
            crate::threading::tasks::threads_here(),
        );
        (self.coloring.groups, self.room)
    }

    /// This step's joints, in the world's order; call after the states are
    /// in place. They are solved colour after colour, each colour in that order.
    pub fn set_joints(&mut self, joints: impl Iterator<Item = PreparedJoint>) {
        self.joints.clear();
        self.joints.extend(joints);
        self.joint_colouring.sort(&mut self.joints, &self.states);
    }

    /// Each joint moves its ends back to its length (once a substep).
    fn project_joints(&mut self, h: f32) {
        for joint in &mut self.joints {
            joint.project(&mut self.states, h);
        }
    }

    /// Puts the narrowphase's `i`-th contact, prepared, in its slot.
    pub fn set_constraint(&mut self, i: usize, c: &PreparedContact) {
        let slot = self.coloring.slot[i] as usize;
        let g = slot / LANES;
        let parts = (
            &mut self.groups[g],
            &mut self.anchors[g],
            &mut self.records[g],
        );
        contact_constraint::set_lane(parts, slot % LANES, c);
    }

    /// `begin_constraints` and `set_constraint` for all the constraints at
    /// once: `prepare` fills `prepared` (on rayon's threads) while this
    /// thread colours them, which needs only their pairs; then, on rayon's
    /// threads, the groups emptied and each constraint written into its
    /// lane, runs of them read in order (reading each group's lanes from
    /// their places in `prepared` would wait on every read).
    #[cfg(feature = "parallel")]
    pub fn set_constraints(
        &mut self,
        pairs: impl Iterator<Item = (u32, u32)> + Send,
        prepared: &mut [PreparedContact],
        prepare: impl FnOnce(&mut [PreparedContact]) + Send,
    ) {
        // The colouring is serial (greedy, in order): off the critical path.
        let ((n, room), ()) = rayon::join(|| self.colour(pairs), || prepare(prepared));
        let prepared = &*prepared;
        // Each group is emptied below: only the lengths matter here.
        self.groups.resize(n, ContactGroup::default());
        self.anchors.resize(n, GroupAnchors::default());
        self.records.resize(n, GroupRecords::default());
        let empty = (
            ContactGroup::empty(room),
            GroupAnchors::default(),
            GroupRecords::default(),
        );
        let parts = (
            &mut self.groups[..],
            &mut self.anchors[..],
            &mut self.records[..],
        );
        parallel::fill_groups(parts, |_, (group, anchors, records)| {
            (*group, *anchors, *records) = empty;
        });
        let parts = (
            &mut self.groups[..],
            &mut self.anchors[..],
            &mut self.records[..],
        );
        // SAFETY: the colouring gives each constraint a slot of its own
        // (`coloring_tests` checks it).
        unsafe { parallel::scatter_lanes(parts, &self.coloring.slot, prepared) };
    }

    /// What every constraint hands to the next step, in the narrowphase's
    /// order (`out` holds one per constraint).
    pub fn store_all(&self, out: &mut [StoredImpulse]) {
        fill_chunks(out, STORE_CHUNK, |first, out| {
            for (k, stored) in out.iter_mut().enumerate() {
                *stored = self.stored(first + k);
            }
        });
    }

    /// What the narrowphase's `i`-th contact hands to the next step.
    fn stored(&self, i: usize) -> StoredImpulse {
        let slot = self.coloring.slot[i] as usize;
        let g = slot / LANES;
        self.groups[g].stored(&self.records[g], slot % LANES)
    }

    /// What the narrowphase's `i`-th contact gave over the step, if the
    /// constraints are this step's `count` contacts.
    pub fn totals(&self, i: usize, count: usize) -> Option<ContactTotals> {
        if self.coloring.slot.len() != count {
            return None;
        }
        let slot = *self.coloring.slot.get(i)? as usize;
        let g = self.groups.get(slot / LANES)?;
        Some(g.totals(slot % LANES))
    }

    /// Runs the substeps over prepared `states`, `forces` and constraints,
    /// and the `parts` at their places in each.
    pub fn solve(
        &mut self,
        p: &SolveParams,
        grab: Option<&GrabSpring>,
        mut probe: Option<&mut probe::SubstepProbe>,
        parts: SubstepParts,
    ) {
        let SubstepParts { mut ribbons } = parts;
        let h = p.dt / p.substeps as f32;
        let inv_h = 1.0 / h;
        // Stiffer than a quarter of the substep rate would ring.
        let hertz = p.contact_hertz.min(0.25 * inv_h);
        let soft = softness::Softness::new(hertz, p.contact_damping_ratio, h);
        let bias = |use_bias| Bias {
            soft,
            inv_h,
            max_push_out: p.max_push_out,
            use_bias,
            friction: p.friction,
        };
        let (push, relax) = (bias(true), bias(false));
        for_each_group(
            &mut self.groups,
            &mut self.anchors,
            &self.states,
            |c, anchors, a, b| {
                contact_constraint::refresh(c, anchors, &Poses::gather(a), &Poses::gather(b));
                let (a, b) = (Velocities::gather(a), Velocities::gather(b));
                contact_constraint::prepare_masses(c, anchors, &a, &b);
            },
        );
        // With no probe or grab between its passes, a substep runs as one
        // staged run (`fused`) on several threads; the ribbons, which run
        // passes of their own, then come after it, and the relax pass after them.
        #[cfg(feature = "parallel")]
        let fused = probe.is_none()
            && grab.is_none()
            && self.lay_out_substep(p.iterations, ribbons.is_none());
        for _ in 0..p.substeps {
            #[cfg(feature = "parallel")]
            if fused {
                self.fused_substep(&fused::SubstepKernels {
                    h,
                    angular_damping: p.angular_damping,
                    push: &push,
                    relax: &relax,
                });
                if let Some(ribbons) = ribbons.as_deref_mut() {
                    ribbons.substep(&mut self.states);
                    self.refresh_and_relax(&relax);
                }
                continue;
            }
            if let Some(probe) = probe.as_deref_mut() {
                probe.before(&self.states, &self.forces);
            }
            integrate::integrate_velocities(
                &mut self.states,
                &self.forces,
                &self.awake,
                p.angular_damping,
                h,
            );
            if let Some(probe) = probe.as_deref_mut() {
                probe.after(&self.states, &self.forces, h);
            }
            if let Some(g) = grab {
                let impulse = integrate::apply_grab(&mut self.states, g, h);
                if let Some(probe) = probe.as_deref_mut() {
                    probe.grabbed(g.state, impulse);
                }
            }
            self.velocity_pass(contact_constraint::warm_start);
            for _ in 0..p.iterations {
                self.velocity_pass(|c, a, b| contact_constraint::solve(c, a, b, &push));
            }
            for_each_body(&self.awake, &mut self.states, |_, s| {
                s.integrate_position(h)
            });
            self.project_joints(h);
            if let Some(ribbons) = ribbons.as_deref_mut() {
                ribbons.substep(&mut self.states);
            }
            self.refresh_and_relax(&relax);
        }
    }

    /// The relax pass, each constraint's separation and lever arms first
    /// brought to the positions the substep just reached. One pass over the
    /// constraints instead of two, with the same results: relaxing changes
    /// only velocities, and a refresh reads only positions.
    fn refresh_and_relax(&mut self, relax: &Bias) {
        self.colour_pass(|g, anchors, sides| relax_group(g, anchors, sides, relax));
    }

    /// One pass of `kernel` over the constraints' velocities, colour after colour.
    fn velocity_pass<K>(&mut self, kernel: K)
    where
        K: Fn(&mut ContactGroup, &mut Velocities, &mut Velocities) + Sync,
    {
        self.colour_pass(|g, _, sides| on_velocities(g, sides, &kernel));
    }

    /// One pass of `kernel` over the groups, colour after colour, each with
    /// its anchors and its bodies' states.
    fn colour_pass<K>(&mut self, kernel: K)
    where
        K: Fn(&mut ContactGroup, &GroupAnchors, GroupStates) + Sync,
    {
        let anchors = &self.anchors;
        for_each_colored(
            &self.coloring,
            &mut self.groups,
            &mut self.states,
            |i, g, sides| kernel(g, &anchors[i], sides),
        );
    }

    /// Bounces at `restitution` for contacts that approached faster than `threshold`.
    pub fn restitution(&mut self, restitution: f32, threshold: f32) {
        if restitution == 0.0 {
            return;
        }
        // Most groups have nothing to bounce: test before gathering their bodies.
        self.colour_pass(|g, anchors, sides| {
            let bounces = contact_constraint::bounces(g, anchors, threshold);
            if bounces.any() {
                on_velocities(g, sides, |c, a, b| {
                    contact_constraint::apply_restitution(c, anchors, a, b, restitution, bounces)
                });
            }
        });
    }

    /// Whether some contact approached faster than `speed` and pushed this
    /// step (an impact, as opposed to bodies that only pass by or move together).
    pub fn any_impact(&self, speed: f32) -> bool {
        self.groups
            .iter()
            .zip(&self.anchors)
            .any(|(g, anchors)| contact_constraint::bounces(g, anchors, speed).any())
    }

    /// Removes overlap deeper than `slop` from the positions, pass after pass
    /// as `s` says; returns the passes run.
    pub fn stabilize(&mut self, s: &Stabilization) -> u32 {
        // The passes move the bodies, never turn them.
        for_each_group(
            &mut self.groups,
            &mut self.anchors,
            &self.states,
            |_, anchors, a, b| {
                contact_constraint::rotate_to_end(anchors, &Poses::gather(a), &Poses::gather(b))
            },
        );
        let max_passes = s.max_passes.max(s.min_passes);
        self.skips.begin(self.states.len(), self.groups.len());
        // Set by any group, whatever the thread: an OR, the same in any order.
        let beyond_target = AtomicBool::new(false);
        let mut passes = 0;
        // The passes that always run, as one staged run on several threads
        // (`fused`), only the last of them asked whether to go on.
        #[cfg(feature = "parallel")]
        if s.min_passes > 1 && self.lay_out_position_passes(s.min_passes) {
            self.fused_position_passes(s, &beyond_target);
            passes = s.min_passes;
            if !beyond_target.load(Ordering::Relaxed) {
                return passes;
            }
        }
        let anchors = &self.anchors;
        let skips = &self.skips;
        while passes < max_passes {
            beyond_target.store(false, Ordering::Relaxed);
            for_each_colored(
                &self.coloring,
                &mut self.groups,
                &mut self.states,
                |i, g, states| {
                    position_group(g, &anchors[i], states, (i, skips), s, &beyond_target)
                },
            );
            passes += 1;
            if passes >= s.min_passes && !beyond_target.load(Ordering::Relaxed) {
                break;
            }
        }
        passes
    }
}
