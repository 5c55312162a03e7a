//! The ribbons' part of each substep, run after the bodies have moved and the
//! joints have been projected, before the contacts' relax pass:
//!
//! 1. each point falls under gravity, the world's force fields
//!    (`ForceField::force_on_point`, when there are any) and air drag (drag
//!    taken implicitly, as the bodies' is, across and along the ribbon
//!    apart, viscous when slow) on its velocity relative to the moving air
//!    (`crate::air`, sampled at each point once a step, at the first
//!    substep);
//! 2. points are pushed out of the balloons near the ribbon and out of the
//!    room; where segments of ribbons may touch this step, the pairs are
//!    projected apart (`touch`), on one thread, between this and 3, and
//!    again between 3 and 4;
//! 3. the chain, knot included, is brought back to its lengths by direct
//!    solves (`chain`; follow-the-leader if a jerk outruns them), those of
//!    ribbons a contact just pushed apart together with those contacts
//!    (`touch::held`; no follow-the-leader there: it would pull a caught
//!    strand back through the other), and the room's push repeated for what
//!    that moved;
//! 4. each point's velocity is what it moved over the substep (less any
//!    bounce off a balloon).
//!
//! The awake ribbons are solved four at a time, a ribbon a SIMD lane, in
//! groups of one segment count (`lane_group`, `lane_substep`,
//! `lane_pushes`). The solver runs them as its `ribbons` part
//! (`RibbonSubsteps`, a `solver::SubstepPart`). The ribbons read the bodies'
//! states and write only their own points, so the groups run on rayon's
//! threads in any split; their pulls on their balloons
//! (one ribbon a balloon) and the pushes back of the balloons they touched
//! are then applied in ribbon order. A pull moves its balloon's centre but
//! turns it only through its angular velocity (`BodyState::apply_pull`); the
//! pushes back are impulses on the velocities: what the contacts' relax pass
//! and friction see, where a direct turn would slip past friction and let a
//! pile of balloons on ribbons creep for ever.

use std::ops::Range;

use glam::Vec3;
use up_geom::Aabb;

use super::collide::NearTriangle;
use super::lane_group::RibbonLanes;
use super::lane_pushes::NearInput;
use super::nearby::{NearFound, NearbyBodies};
use super::touch::RibbonTouch;
use super::{
    Ribbon, AIR_VISCOSITY, NORMAL_DRAG_COEFFICIENT, RIBBON_WIDTH, TANGENT_DRAG_COEFFICIENT,
    WEIGHT_DRAG_COEFFICIENT, WEIGHT_RADIUS,
};
use crate::air::AirNow;
use crate::body::{BodySize, ShapeData};
use crate::forces::field::ForceFields;
use crate::solver::body_state::BodyState;
use crate::solver::SubstepPart;
use crate::threading::tasks::fill_chunks;

/// Most direct solves of a ribbon's chain a substep. Each takes out what the
/// last one's linearisation left (a taut ribbon whose light points swing
/// across it, jerked by its balloon, needs several; left alone, that error
/// grows into a stretched ribbon); a calm ribbon needs one or two.
pub(super) const CHAIN_ITERATIONS: usize = 8;
/// A solve that started within this fraction of the segment length of every
/// length ends them: what it leaves is of the order of its square.
pub(super) const CHAIN_TOLERANCE: f32 = 2e-3;

/// Lane groups one task takes (64 ribbons).
const GROUP_CHUNK: usize = 16;

/// An awake ribbon during the step: what its lane in a
/// `lane_group::LaneGroup` is packed with besides its points (which go
/// straight from the world's ribbon into the lanes and back).
#[derive(Clone, Debug, Default)]
pub(crate) struct ActiveRibbon {
    /// Its slot in the world's ribbons.
    pub slot: u32,
    /// Its balloon's solver state (dense index).
    pub state: u32,
    /// Its balloon's `BodyDef::user_data`, for the force fields.
    pub user_data: u32,
    /// The balloon's centre of mass at the step's start, m.
    pub origin: Vec3,
    /// The knot from the centre of mass, world frame at the step's start, m.
    pub arm0: Vec3,
    /// Inverse mass of the points between the ends and of the end (0: a
    /// point of no mass), kg⁻¹; a held point's is 0 in the lanes.
    pub(super) inv_point_mass: f32,
    pub(super) inv_end_mass: f32,
    /// Where the end is tied (`Ribbon::anchor`): held there.
    pub(super) anchor: Option<Vec3>,
    /// Drag across and along the ribbon (½·ρ·C∞·A, kg/m), and across at low
    /// Reynolds numbers: the drag factor times the speed is
    /// `drag[0]·|v| + drag[2]` (a viscous force, linear in the speed); of
    /// each point between the ends, and of the end.
    pub(super) drag_mid: [f32; 3],
    pub(super) drag_end: [f32; 3],
    /// The end's radius, m (the other points': `RIBBON_RADIUS`).
    pub(super) end_radius: f32,
    /// Room triangles and balloons near it this step, in the stage's lists.
    pub triangles: Range<u32>,
    pub bodies: Range<u32>,
    /// A grabbed point and where it is carried, and how fast, m/s.
    pub grab: Option<(usize, Vec3)>,
    pub grab_speed: f32,
    /// The knot's position impulses on the balloon summed over the step's
    /// substeps (kg·m), and those substeps' count and length (s).
    pub(super) step_impulse: Vec3,
    pub(super) substeps: u32,
    pub(super) h: f32,
    pub segment_length: f32,
    /// The fastest air at any of its points this step, m/s (0 in still air).
    pub air_speed: f32,
    /// Its last points that rest this step (`lane_group::Rest::tail`).
    pub rest_tail: u32,
    /// As the step left it: moving as a whole (its balloon may not sleep
    /// yet), its points all finite, and its stretch (`World::finish_ribbons`).
    pub moving: bool,
    pub finite: bool,
    pub stretch: f32,
}

/// Point `i`'s drag factors (`ActiveRibbon::drag_mid`) in air of `air_density`.
fn drag_at(ribbon: &Ribbon, i: usize, air_density: f32) -> [f32; 3] {
    let n = ribbon.segments();
    // The knot's and the end's half segments; the weight's cross-section.
    let share = if i == 0 || i == n { 0.5 } else { 1.0 };
    let q = 0.5 * air_density * share * ribbon.segment_length * RIBBON_WIDTH;
    let nu = AIR_VISCOSITY / air_density;
    let mut across = q * NORMAL_DRAG_COEFFICIENT;
    let along = q * TANGENT_DRAG_COEFFICIENT;
    // 10/Re·|v| = 10·ν/w.
    let mut viscous = q * 10.0 * nu / RIBBON_WIDTH;
    if i == n && ribbon.weight > 0.0 {
        let disc = 0.5 * air_density * std::f32::consts::PI * WEIGHT_RADIUS * WEIGHT_RADIUS;
        across += disc * WEIGHT_DRAG_COEFFICIENT;
        // 24/Re·|v| = 24·ν/D.
        viscous += disc * 24.0 * nu / (2.0 * WEIGHT_RADIUS);
    }
    [across, along, viscous]
}

/// `1 / m`, or 0 for no mass.
fn inverse(m: f32) -> f32 {
    if m > 0.0 {
        1.0 / m
    } else {
        0.0
    }
}

impl ActiveRibbon {
    /// Readies the step's figures of `ribbon` (its points are packed apart).
    pub fn take(&mut self, ribbon: &Ribbon, air_density: f32) {
        self.step_impulse = Vec3::ZERO;
        self.substeps = 0;
        self.air_speed = 0.0;
        self.segment_length = ribbon.segment_length;
        let n = ribbon.segments();
        self.inv_point_mass = inverse(ribbon.point_mass);
        self.inv_end_mass = inverse(ribbon.end_mass);
        self.anchor = ribbon.anchor;
        self.drag_mid = drag_at(ribbon, 1, air_density);
        self.drag_end = drag_at(ribbon, n, air_density);
        self.end_radius = ribbon.radius(n);
    }

    /// Point `i`'s inverse mass (0 at the knot, and for a held point).
    pub(super) fn inv_mass(&self, i: usize, n: usize) -> f32 {
        let held = (i == n && self.anchor.is_some()) || self.grab.is_some_and(|(k, _)| k == i);
        if i == 0 || held {
            0.0
        } else if i == n {
            self.inv_end_mass
        } else {
            self.inv_point_mass
        }
    }

    /// Sets `ribbon`'s mean pull over the step: the impulses' sum over h²
    /// per substep (a single substep's swings as the weight on the floor
    /// takes turns with gravity).
    pub fn give_back(&self, ribbon: &mut Ribbon) {
        if self.substeps > 0 {
            ribbon.pull = self.step_impulse / (self.h * self.h * self.substeps as f32);
        }
    }
}

/// What a substep of the ribbons reads.
pub(crate) struct SubstepInput<'a> {
    pub h: f32,
    pub gravity: Vec3,
    /// Every body's centre of mass at the step's start, and its shape.
    pub centers: &'a [Vec3],
    pub shape_of: &'a [u32],
    /// Each body's size (its tree's scale).
    pub size: &'a [BodySize],
    pub shapes: &'a [ShapeData],
    pub triangles: &'a [NearTriangle],
    pub bodies: &'a [u32],
    /// The world's force fields (their `force_on_point`), and the simulated
    /// seconds at the step's start.
    pub fields: &'a ForceFields,
    pub time: f64,
    /// The moving air as it blows this step; None in still air.
    pub air: Option<&'a AirNow>,
}

/// The ribbons' buffers for a step.
#[derive(Clone, Debug, Default)]
pub(crate) struct RibbonStage {
    /// The awake ribbons are the first `awake`; the rest keep their buffers
    /// for the steps in which more are awake (no allocation a step).
    pub active: Vec<ActiveRibbon>,
    pub awake: usize,
    /// The awake ribbons laid out for the substeps (`RibbonLanes::pack`,
    /// `take_out`).
    pub lanes: RibbonLanes,
    /// Their slots, in slot order (as `active`).
    pub awake_slots: Vec<u32>,
    /// Room triangles and balloons near each active ribbon, back to back,
    /// and the lists they are found in, one a task.
    pub near: NearFound,
    pub near_tasks: Vec<NearFound>,
    pub nearby: NearbyBodies,
    /// The spheres hashed in `nearby`: per body, or per awake body
    /// (`awake_bodies` says which) when waking.
    pub bound_center: Vec<Vec3>,
    pub bound_radius: Vec<f32>,
    pub awake_bodies: Vec<u32>,
    /// The wake pass's buffers: balloons found near a ribbon, and the
    /// balloons to wake.
    pub found: Vec<u32>,
    pub touched: Vec<crate::body::BodyId>,
    /// Per body (dense): its ribbon still moves faster than the sleep speed.
    pub moving: Vec<bool>,
    /// The sleeping ribbons' boxes, for the wake pass.
    pub point_boxes: PointBoxes,
    /// The ribbons' contacts with each other.
    pub touch: RibbonTouch,
}

/// Per ribbon slot: its points' box as the last step it was solved left
/// them (None: not known), which stays right while its balloon sleeps.
#[derive(Clone, Debug, Default)]
pub(crate) struct PointBoxes(Vec<Option<Aabb>>);

impl PointBoxes {
    /// `ribbon`'s points' box, slot `slot`'s kept box or found and kept.
    pub fn of(&mut self, slot: u32, ribbon: &Ribbon) -> Aabb {
        let slot = slot as usize;
        if self.0.len() <= slot {
            self.0.resize(slot + 1, None);
        }
        *self.0[slot].get_or_insert_with(|| Aabb::from_points(&ribbon.points))
    }

    /// Forgets slot `slot`'s box: its ribbon's points changed.
    pub fn forget(&mut self, slot: u32) {
        if let Some(kept) = self.0.get_mut(slot as usize) {
            *kept = None;
        }
    }
}

/// The awake ribbons as the solver's `ribbons` part of each substep.
pub(crate) struct RibbonSubsteps<'a> {
    /// Packed in lane groups (`RibbonLanes::pack`).
    pub active: &'a mut RibbonLanes,
    /// The step's pairs of segments that may touch (`touch`).
    pub touch: &'a mut RibbonTouch,
    pub input: SubstepInput<'a>,
}

impl SubstepPart for RibbonSubsteps<'_> {
    fn substep(&mut self, states: &mut [BodyState]) {
        substep(self.active, self.touch, &self.input, states);
    }
}

/// One substep of every lane group; then the ribbons' pulls on their
/// balloons, in the ribbons' order.
fn substep(
    lanes: &mut RibbonLanes,
    touch: &mut RibbonTouch,
    input: &SubstepInput,
    states: &mut [BodyState],
) {
    let read: &[BodyState] = states;
    lanes.bodies.place(input, read);
    let near = NearInput {
        input,
        states: read,
        bodies: &lanes.bodies,
    };
    let groups = &mut lanes.groups[..lanes.used];
    if touch.is_empty() {
        fill_chunks(groups, GROUP_CHUNK, |_, groups| {
            for g in groups {
                g.substep(&near);
            }
        });
    } else {
        // The ribbons' contacts with each other between the pushes and the
        // chains' solve, taking turns with the solve, and again after the
        // last, on one thread in the pairs' order; a repeated solve only
        // for the groups the contacts moved.
        fill_chunks(groups, GROUP_CHUNK, |_, groups| {
            for g in groups {
                g.substep_before_solve(&near);
            }
        });
        touch.begin_substep(input.h);
        touch.project(groups, f32::MAX);
        fill_chunks(groups, GROUP_CHUNK, |_, groups| {
            for g in groups {
                g.substep_solve(&near);
            }
        });
        touch.solve_held(groups);
        for _ in 1..super::touch::SOLVES {
            touch.project(groups, f32::MAX);
            fill_chunks(groups, GROUP_CHUNK, |_, groups| {
                for g in groups {
                    g.substep_solve_again();
                }
            });
            touch.solve_held(groups);
        }
        touch.project(groups, super::touch::LAST_PASS_MOST);
        fill_chunks(groups, GROUP_CHUNK, |_, groups| {
            for g in groups {
                g.substep_finish(&near);
            }
        });
    }
    let inv_h = 1.0 / input.h;
    for &(g, l) in &lanes.order {
        let (group, l) = (&lanes.groups[g as usize], l as usize);
        let lane = &group.lanes[l];
        states[lane.state as usize].apply_pull(group.impulse.lane(l), group.arm.lane(l), inv_h);
        for &(state, impulse, arm) in &lane.reactions {
            states[state as usize].apply_impulse(impulse * inv_h, arm);
        }
    }
}
