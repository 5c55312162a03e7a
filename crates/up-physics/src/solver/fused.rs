//! A substep's passes as the stages of one staged run (`staged`) on several
//! threads (the idea of Box2D v3's solver stages, which span the step):
//! integrate velocities, warm start, the solve iterations, integrate
//! positions, the joints, and the relax pass, each colour a stage, in one
//! fork-join instead of one a pass. The body passes' blocks are the awake
//! bodies by zone (`awake_blocks`), shared among the threads in the order
//! the colours' are, so that a thread integrates the bodies whose
//! constraints it solves. The same work in the same order per body and per
//! constraint as the passes one by one: the same results, bit for bit.
//!
//! The position passes that always run after the solve (`Solver::stabilize`'s
//! `min_passes`) are one staged run likewise, colour after colour, pass after pass.

use super::coloring::ColourBlocks;
use super::contact_constraint::{self, Bias};
use super::integrate::integrate_velocity;
use super::parallel::{run_colour_block, SharedSlice, SharedStates};
use super::{on_velocities, position_group, relax_group, Solver, Stabilization};
use crate::threading::spare::{release_spare, BUFFER_FLOOR};
use crate::threading::staged::{run_in_stages, Stages};
use crate::threading::tasks::threads_here;
use crate::threading::thread_times;
use std::sync::atomic::{AtomicBool, Ordering};

/// What a span of a substep's blocks runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Segment {
    IntegrateVelocities,
    WarmStart,
    Solve,
    IntegratePositions,
    Joints,
    Relax,
    /// A position pass (`Solver::stabilize`) but the last.
    Position,
    /// The last position pass, which says whether another must run.
    LastPosition,
}

/// A substep's blocks, segment after segment, laid out once a step.
#[derive(Clone, Debug, Default)]
pub(crate) struct SubstepStages {
    /// Each segment's first block, and what it runs.
    segments: Vec<(u32, Segment)>,
    /// The first block of each block's stage (`Stages::lay_out`).
    stage_first: Vec<u32>,
    stages: Stages,
}

impl SubstepStages {
    /// The segment block `k` belongs to, and its index within it.
    #[inline]
    fn locate(&self, k: usize) -> (Segment, usize) {
        let k = k as u32;
        let &(first, segment) = self
            .segments
            .iter()
            .rev()
            .find(|&&(first, _)| first <= k)
            .expect("a block before the first segment");
        (segment, (k - first) as usize)
    }

    fn push_colours(&mut self, segment: Segment, colours: &ColourBlocks) {
        let first = self.stage_first.len() as u32;
        self.segments.push((first, segment));
        let colour_first = &colours.stage_first;
        self.stage_first
            .extend(colour_first.iter().map(|&f| first + f));
    }

    /// A segment of `blocks` blocks in one stage.
    fn push_stage(&mut self, segment: Segment, blocks: usize) {
        let first = self.stage_first.len() as u32;
        self.segments.push((first, segment));
        self.stage_first.extend(std::iter::repeat_n(first, blocks));
    }

    /// Gives back the capacity this step left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.stage_first, BUFFER_FLOOR);
        self.stages.release_spare();
    }
}

/// What the fused substep needs besides the solver's own buffers.
pub(crate) struct SubstepKernels<'a> {
    pub h: f32,
    pub angular_damping: f32,
    pub push: &'a Bias,
    pub relax: &'a Bias,
}

impl Solver {
    /// Lays out this step's substep as one staged run, if it is worth it:
    /// several threads, colours cut into more than one block. Without
    /// `with_relax` the run ends after the joints (the caller runs the
    /// ribbons, then the relax pass). Returns whether to use it.
    pub(super) fn lay_out_substep(&mut self, iterations: u32, with_relax: bool) -> bool {
        let colours = &self.coloring.blocks;
        if threads_here() < 2 || colours.stages.blocks() < 2 || self.awake_blocks.blocks() == 0 {
            return false;
        }
        let layout = &mut self.substep;
        layout.segments.clear();
        layout.stage_first.clear();
        let bodies = self.awake_blocks.blocks();
        layout.push_stage(Segment::IntegrateVelocities, bodies);
        layout.push_colours(Segment::WarmStart, colours);
        for _ in 0..iterations {
            layout.push_colours(Segment::Solve, colours);
        }
        layout.push_stage(Segment::IntegratePositions, bodies);
        if !self.joints.is_empty() {
            layout.push_stage(Segment::Joints, 1);
        }
        if with_relax {
            layout.push_colours(Segment::Relax, colours);
        }
        layout.stages.lay_out(&layout.stage_first);
        true
    }

    /// Lays out the first `passes` position passes as one staged run, if it
    /// is worth it (as `lay_out_substep`); returns whether to use it.
    pub(super) fn lay_out_position_passes(&mut self, passes: u32) -> bool {
        let colours = &self.coloring.blocks;
        if threads_here() < 2 || colours.stages.blocks() < 2 {
            return false;
        }
        let layout = &mut self.position_passes;
        layout.segments.clear();
        layout.stage_first.clear();
        for pass in 1..=passes {
            let last = pass == passes;
            let segment = if last {
                Segment::LastPosition
            } else {
                Segment::Position
            };
            layout.push_colours(segment, colours);
        }
        layout.stages.lay_out(&layout.stage_first);
        true
    }

    /// The position passes laid out by `lay_out_position_passes`; only the
    /// last sets `beyond_target`, as the passes one by one leave it.
    pub(super) fn fused_position_passes(&mut self, s: &Stabilization, beyond_target: &AtomicBool) {
        let states = SharedStates::new(&mut self.states);
        let groups = SharedSlice::new(&mut self.groups);
        let (anchors, skips, colours) = (&self.anchors, &self.skips, &self.coloring.blocks);
        let layout = &self.position_passes;
        // What the passes before the last find is not asked for.
        let ignored = AtomicBool::new(false);
        let run = |block: usize| {
            let (segment, b) = layout.locate(block);
            let beyond = if segment == Segment::LastPosition {
                beyond_target
            } else {
                &ignored
            };
            // SAFETY: as `fused_substep`'s colour blocks.
            unsafe {
                run_colour_block(colours, b, groups, states, &|i, g, sides| {
                    position_group(g, &anchors[i], sides, (i, skips), s, beyond)
                })
            }
        };
        beyond_target.store(false, Ordering::Relaxed);
        thread_times::pass(|| run_in_stages(&layout.stages, run));
    }

    /// One substep as laid out by `lay_out_substep`.
    pub(super) fn fused_substep(&mut self, k: &SubstepKernels) {
        let states = SharedStates::new(&mut self.states);
        let groups = SharedSlice::new(&mut self.groups);
        let joints = SharedSlice::new(&mut self.joints);
        let (anchors, forces) = (&self.anchors, &self.forces);
        let (bodies, colours) = (&self.awake_blocks, &self.coloring.blocks);
        let layout = &self.substep;
        // SAFETY (the colour blocks): each block is run by one task, and the
        // blocks that run at once belong to one stage (`run_in_stages`). The
        // kernels are written out in each arm, not passed as `dyn`: inlined
        // into `on_velocities`, what they compute for a fixed side is left out.
        let run = |block: usize| match layout.locate(block) {
            (Segment::IntegrateVelocities, b) => {
                for &i in bodies.block(b) {
                    // SAFETY: a body is in one block, run by one task.
                    let s = unsafe { states.get(i) };
                    integrate_velocity(s, &forces[i as usize], k.angular_damping, k.h);
                }
            }
            (Segment::IntegratePositions, b) => {
                for &i in bodies.block(b) {
                    // SAFETY: as above.
                    unsafe { states.get(i) }.integrate_position(k.h);
                }
            }
            (Segment::WarmStart, b) => unsafe {
                run_colour_block(colours, b, groups, states, &|_, g, sides| {
                    on_velocities(g, sides, contact_constraint::warm_start)
                })
            },
            (Segment::Solve, b) => unsafe {
                run_colour_block(colours, b, groups, states, &|_, g, sides| {
                    on_velocities(g, sides, |c, x, y| {
                        contact_constraint::solve(c, x, y, k.push)
                    })
                })
            },
            (Segment::Relax, b) => unsafe {
                run_colour_block(colours, b, groups, states, &|i, g, sides| {
                    relax_group(g, &anchors[i], sides, k.relax)
                })
            },
            (Segment::Position | Segment::LastPosition, _) => {
                unreachable!("a position pass in a substep's layout")
            }
            (Segment::Joints, _) => {
                // SAFETY: the joints' stage is one block: no other task runs.
                let (states, joints) = unsafe { (states.all(), joints.all()) };
                for joint in joints {
                    joint.project(states, k.h);
                }
            }
        };
        thread_times::pass(|| run_in_stages(&layout.stages, run));
    }
}
