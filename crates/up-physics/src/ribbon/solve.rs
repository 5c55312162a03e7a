//! The ribbons' part of each substep, run after the bodies have moved and the
//! joints have been projected, before the contacts' relax pass:
//!
//! 1. each point falls under gravity, the world's force fields
//!    (`ForceField::force_on_point`, when there are any) and air drag (drag
//!    taken implicitly, as the bodies' is, across and along the ribbon
//!    apart, viscous when slow);
//! 2. points are pushed out of the balloons near the ribbon and out of the room;
//! 3. the chain, knot included, is brought back to its lengths by direct
//!    solves (`chain`; follow-the-leader if a jerk outruns them), and the
//!    room's push repeated for what that moved;
//! 4. each point's velocity is what it moved over the substep (less any
//!    bounce off a balloon).
//!
//! The solver runs it as its `ribbons` part (`RibbonSubsteps`, a
//! `solver::SubstepPart`). The ribbons read the bodies' states and write
//! only their own points, so
//! they run on rayon's threads in any split; their pulls on their balloons
//! (one ribbon a balloon) and the pushes back of the balloons they touched
//! are then applied in ribbon order. A pull moves its balloon's centre but
//! turns it only through its angular velocity (`BodyState::apply_pull`); the
//! pushes back are impulses on the velocities: what the contacts' relax pass
//! and friction see, where a direct turn would slip past friction and let a
//! pile of balloons on ribbons creep for ever.

use std::ops::Range;

use glam::Vec3;
use up_geom::norm::Norm;
use up_geom::Sphere;

use super::chain::{solve_chain, KnotBody};
use super::collide::{push_out_of_balloons, push_out_of_room, NearBalloon, NearTriangle};
use super::nearby::NearbyBodies;
use super::{
    Ribbon, AIR_VISCOSITY, BALLOON_FRICTION, NORMAL_DRAG_COEFFICIENT, RIBBON_WIDTH, ROOM_FRICTION,
    TANGENT_DRAG_COEFFICIENT, WEIGHT_DRAG_COEFFICIENT, WEIGHT_RADIUS,
};
use crate::body::{BodySize, ShapeData};
use crate::forces::field::{ForceFields, PointSample};
use crate::solver::body_state::BodyState;
use crate::solver::SubstepPart;
use crate::threading::tasks::fill_chunks;

/// Most direct solves of a ribbon's chain a substep. Each takes out what the
/// last one's linearisation left (a taut ribbon whose light points swing
/// across it, jerked by its balloon, needs several; left alone, that error
/// grows into a stretched ribbon); a calm ribbon needs one or two.
const CHAIN_ITERATIONS: usize = 8;
/// A solve that started within this fraction of the segment length of every
/// length ends them: what it leaves is of the order of its square.
const CHAIN_TOLERANCE: f32 = 2e-3;

/// Ribbons one task takes.
const RIBBON_CHUNK: usize = 64;

/// An awake ribbon during the step, its points taken from the world's.
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
    pub points: Vec<Vec3>,
    pub velocities: Vec<Vec3>,
    /// Per point: inverse mass (0 for a held point; unused at the knot).
    pub inv_mass: Vec<f32>,
    /// Per point: drag across and along the ribbon (½·ρ·C∞·A, kg/m), and
    /// across at low Reynolds numbers: the drag factor times the speed is
    /// `drag[0]·|v| + drag[2]` (a viscous force, linear in the speed).
    pub drag: Vec<[f32; 3]>,
    /// Per point: its radius, m.
    pub radius: Vec<f32>,
    /// Where each point began the substep.
    start: Vec<Vec3>,
    /// Room triangles and balloons near it this step, in the stage's lists.
    pub triangles: Range<u32>,
    pub bodies: Range<u32>,
    /// A grabbed point and where it is carried, and how fast, m/s.
    pub grab: Option<(usize, Vec3)>,
    pub grab_speed: f32,
    /// This substep's position impulse on the balloon (kg·m) and the knot's
    /// arm it acts at, world frame, m.
    pub impulse: Vec3,
    pub arm: Vec3,
    /// The knot's position impulses on the balloon summed over the step's
    /// substeps so far (kg·m), and those substeps' count and length (s).
    step_impulse: Vec3,
    substeps: u32,
    h: f32,
    pub segment_length: f32,
    /// This substep's pushes back on the balloons its points touched: the
    /// balloon's state, the position impulse (kg·m) and its arm (m).
    reactions: Vec<(u32, Vec3, Vec3)>,
    /// Per point: the normal of the balloon that pushed it this substep (zero
    /// if none), and that balloon's velocity.
    touched: Vec<(Vec3, Vec3)>,
    /// The balloons near it and their leaf spheres, at this substep's poses.
    near: Vec<NearBalloon>,
    spheres: Vec<Sphere>,
}

impl ActiveRibbon {
    /// Takes `ribbon`'s points for the step (`give_back` returns them).
    pub fn take(&mut self, ribbon: &mut Ribbon, air_density: f32) {
        self.step_impulse = Vec3::ZERO;
        self.substeps = 0;
        self.segment_length = ribbon.segment_length;
        let n = ribbon.segments();
        self.inv_mass.clear();
        self.drag.clear();
        self.radius.clear();
        for i in 0..=n {
            let m = if i == 0 { 0.0 } else { ribbon.mass(i) };
            self.inv_mass.push(if m > 0.0 { 1.0 / m } else { 0.0 });
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
            self.drag.push([across, along, viscous]);
            self.radius.push(ribbon.radius(i));
        }
        // Last: a ribbon without its points has no segments to ask about.
        self.points = std::mem::take(&mut ribbon.points);
        self.velocities = std::mem::take(&mut ribbon.velocities);
    }

    /// Returns the points to `ribbon`, with its mean pull over the step: the
    /// impulses' sum over h² per substep (a single substep's swings as the
    /// weight on the floor takes turns with gravity).
    pub fn give_back(&mut self, ribbon: &mut Ribbon) {
        ribbon.points = std::mem::take(&mut self.points);
        ribbon.velocities = std::mem::take(&mut self.velocities);
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
}

/// The ribbons' buffers for a step.
#[derive(Clone, Debug, Default)]
pub(crate) struct RibbonStage {
    /// The awake ribbons are the first `awake`; the rest keep their buffers
    /// for the steps in which more are awake (no allocation a step).
    pub active: Vec<ActiveRibbon>,
    pub awake: usize,
    /// Room triangles and balloons near each active ribbon, back to back.
    pub triangles: Vec<NearTriangle>,
    pub bodies: Vec<u32>,
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
}

/// The awake ribbons as the solver's `ribbons` part of each substep.
pub(crate) struct RibbonSubsteps<'a> {
    pub active: &'a mut [ActiveRibbon],
    pub input: SubstepInput<'a>,
}

impl SubstepPart for RibbonSubsteps<'_> {
    fn substep(&mut self, states: &mut [BodyState]) {
        substep(self.active, &self.input, states);
    }
}

/// One substep of every active ribbon; then their pulls on their balloons.
fn substep(active: &mut [ActiveRibbon], input: &SubstepInput, states: &mut [BodyState]) {
    let read: &[BodyState] = states;
    fill_chunks(active, RIBBON_CHUNK, |_, ribbons| {
        for r in ribbons {
            substep_one(r, input, read);
        }
    });
    let inv_h = 1.0 / input.h;
    for r in active.iter() {
        states[r.state as usize].apply_pull(r.impulse, r.arm, inv_h);
        for &(state, impulse, arm) in &r.reactions {
            states[state as usize].apply_impulse(impulse * inv_h, arm);
        }
    }
}

fn substep_one(r: &mut ActiveRibbon, input: &SubstepInput, states: &[BodyState]) {
    let h = input.h;
    let s = &states[r.state as usize];
    r.arm = s.dq * r.arm0;
    r.points[0] = r.origin + s.dp + r.arm;
    let n = r.points.len() - 1;
    r.start.clear();
    r.start.extend_from_slice(&r.points);
    fall(r, input, h);
    if let Some((k, target)) = r.grab {
        // Carried at the speed that reaches the target by the step's end.
        let to = target - r.start[k];
        let len = to.norm();
        let reach = (r.grab_speed * h).min(len);
        if len > 0.0 {
            r.points[k] = r.start[k] + to * (reach / len);
        }
    }
    place_near_spheres(r, input, states);
    let place = |b: &NearBalloon, out: &mut Vec<Sphere>| {
        let tree = &input.shapes[b.tree as usize].tree;
        let (nodes, scale) = (tree.nodes(), input.size[b.state as usize].scale);
        for &leaf in tree.leaves() {
            let node = &nodes[leaf as usize];
            out.push(Sphere::new(
                b.center + b.rotation * (node.center * scale),
                node.radius * scale,
            ));
        }
    };
    r.reactions.clear();
    r.touched.clear();
    r.touched.resize(n + 1, (Vec3::ZERO, Vec3::ZERO));
    for i in (1..=n).filter(|&i| r.inv_mass[i] > 0.0) {
        let (start, radius, mass) = (r.start[i], r.radius[i], 1.0 / r.inv_mass[i]);
        let (reactions, touched) = (&mut r.reactions, &mut r.touched[i]);
        // The point's momentum change, the other way, where it touched.
        let push_back = |b: &NearBalloon, moved: Vec3, at: Vec3| {
            reactions.push((b.state, -mass * moved, at - b.center));
            *touched = (moved.normalize_or_zero(), b.moved / h);
        };
        let (point, near, leaves) = (&mut r.points[i], &mut r.near, &mut r.spheres);
        let mu = BALLOON_FRICTION;
        push_out_of_balloons(point, start, radius, mu, near, leaves, place, push_back);
    }
    let triangles = &input.triangles[r.triangles.start as usize..r.triangles.end as usize];
    push_out_of_room_all(r, triangles);
    let knot = KnotBody {
        inv_mass: s.inv_mass,
        inv_inertia: s.inv_inertia,
        arm: r.arm,
    };
    r.impulse = Vec3::ZERO;
    let mut converged = false;
    for _ in 0..CHAIN_ITERATIONS {
        let (impulse, worst) = solve_chain(&mut r.points, &r.inv_mass, r.segment_length, &knot);
        // The knot moves with its body's share before the next solve.
        r.points[0] += knot.point_motion(impulse);
        r.impulse += impulse;
        if worst < CHAIN_TOLERANCE * r.segment_length {
            converged = true;
            break;
        }
    }
    if !converged {
        follow_the_leader(&mut r.points, &r.inv_mass, r.segment_length);
    }
    push_out_of_room_all(r, triangles);
    r.step_impulse += r.impulse;
    r.substeps += 1;
    r.h = h;
    let inv_h = 1.0 / h;
    for i in 1..=n {
        let mut v = (r.points[i] - r.start[i]) * inv_h;
        // A push out of a balloon stops the point going in; it does not
        // throw it off (no bounce: a ribbon against latex is inelastic).
        let (normal, balloon) = r.touched.get(i).copied().unwrap_or_default();
        let off = (v - balloon).dot(normal);
        if off > 0.0 {
            v -= off * normal;
        }
        r.velocities[i] = v;
    }
    r.velocities[0] = s.point_velocity(r.arm);
}

/// Each point pulled after the one before it, from the knot out, to at most
/// the segment length (Müller, Kim, Chentanez, "Fast simulation of
/// inextensible hair and fur", 2012): for a ribbon jerked harder than the
/// solves converge on in a substep (a balloon thrown at 25 m/s with a weight
/// on its ribbon), which bounds its length at the price of the momentum the
/// solves had not yet handed round. A held point stays.
fn follow_the_leader(points: &mut [Vec3], inv_mass: &[f32], segment_length: f32) {
    for i in 1..points.len() {
        let d = points[i] - points[i - 1];
        let len = d.norm();
        if len > segment_length && inv_mass[i] > 0.0 {
            points[i] = points[i - 1] + d * (segment_length / len);
        }
    }
}

/// Gravity, the fields' forces and drag on each point, then its move over
/// the substep.
fn fall(r: &mut ActiveRibbon, input: &SubstepInput, h: f32) {
    let n = r.points.len() - 1;
    let fields = (!input.fields.is_empty()).then_some(input.fields);
    for i in 1..=n {
        if r.inv_mass[i] == 0.0 {
            continue;
        }
        let mut v = r.velocities[i] + h * input.gravity;
        if let Some(fields) = fields {
            let force = fields.force_on_point(&PointSample {
                position: r.points[i],
                velocity: r.velocities[i],
                mass: 1.0 / r.inv_mass[i],
                end: i == n,
                drag_factor: r.drag[i][0],
                user_data: r.user_data,
                time: input.time,
            });
            v += h * r.inv_mass[i] * force;
        }
        // Along the ribbon: from the point before to the one after.
        let along = r.points[(i + 1).min(n)] - r.points[i - 1];
        let len = along.norm();
        let t = if len > 1e-9 { along / len } else { Vec3::ZERO };
        let v_along = v.dot(t) * t;
        let v_across = v - v_along;
        let [k_across, k_along, viscous] = r.drag[i];
        let w = h * r.inv_mass[i];
        let v_along = v_along / (1.0 + w * k_along * v_along.norm());
        let across = k_across * v_across.norm() + viscous;
        let v_across = v_across / (1.0 + w * across);
        r.velocities[i] = v_along + v_across;
        r.points[i] += h * r.velocities[i];
    }
}

/// The balloons near `r` whose roots reach its points' bounds, at this
/// substep's poses (their leaves are placed when a point comes near).
fn place_near_spheres(r: &mut ActiveRibbon, input: &SubstepInput, states: &[BodyState]) {
    r.spheres.clear();
    r.near.clear();
    let bodies = &input.bodies[r.bodies.start as usize..r.bodies.end as usize];
    if bodies.is_empty() {
        return;
    }
    let (mut lo, mut hi) = (r.points[1], r.points[1]);
    let mut reach = 0.0f32;
    for (p, &radius) in r.points[1..].iter().zip(&r.radius[1..]) {
        lo = lo.min(*p);
        hi = hi.max(*p);
        reach = reach.max(radius);
    }
    for &b in bodies {
        let s = &states[b as usize];
        let tree = &input.shapes[input.shape_of[b as usize] as usize].tree;
        let center = input.centers[b as usize] + s.dp;
        let (root, scale) = (tree.root(), input.size[b as usize].scale);
        let root_center = center + s.q * (root.center * scale);
        let root_radius = root.radius * scale;
        let closest = root_center.clamp(lo, hi);
        if closest.distance_squared(root_center) > (root_radius + reach).powi(2) {
            continue;
        }
        r.near.push(NearBalloon {
            state: b,
            bound: Sphere::new(root_center, root_radius),
            moved: s.v * input.h,
            center,
            rotation: s.q,
            tree: input.shape_of[b as usize],
            leaves: (0, 0),
        });
    }
}

fn push_out_of_room_all(r: &mut ActiveRibbon, triangles: &[NearTriangle]) {
    if triangles.is_empty() {
        return;
    }
    for i in 1..r.points.len() {
        if r.inv_mass[i] == 0.0 {
            continue;
        }
        let (start, radius) = (r.start[i], r.radius[i]);
        push_out_of_room(&mut r.points[i], start, radius, ROOM_FRICTION, triangles);
    }
}
