//! Rapier's side: the same room, balloons, masses and forces, built from the
//! scene UP built (see docs/benchmarks.md for how each quantity is matched).
//!
//! - Room: one static triangle mesh with `TriMeshFlags::FIX_INTERNAL_EDGES`
//!   (one-sided, normals into the room, as UP's).
//! - Balloon: a dynamic body whose frame is UP's mesh frame, carrying the leaf
//!   spheres of UP's sphere tree at the same local positions, either as one
//!   compound collider or as one ball collider each (`RapierShape`). Colliders
//!   have zero density; the mass properties are set explicitly.
//! - Added mass: UP adds C_a·ρ·V to the translational mass only (momentum and
//!   contacts), never to the weight or the rotational inertia. Rapier gets the
//!   same: mass m + C_a·ρ·V with UP's inertia tensor, world gravity zero, and
//!   the weight m·g applied as a force each step. The net acceleration
//!   (m·g + buoyancy + drag)/(m + m_a), the rotation and the contact response
//!   are then those of UP.
//! - Forces each step, through the force API (reset, then add): the weight at
//!   the centre of mass; buoyancy plus quadratic drag at the centre of
//!   buoyancy (as UP applies drag there). Drag is taken from the velocity at
//!   the start of the step (UP takes it implicitly per substep): the terminal
//!   speed is the same, the approach to it 1–2 % brisker. Angular damping is Rapier's own
//!   (ω ← ω/(1 + h·c) per substep, UP's formula). Sleeping bodies are left
//!   alone (their forces stay set and are not integrated).
//! - Ribbons (`--ribbons`, `with_ribbons`): each a chain of small dynamic
//!   balls (radius `RIBBON_RADIUS`, one per UP point after the knot, each of
//!   UP's point mass), started at UP's start points. Spherical joints tie
//!   each ball to the one before at the segment's length (anchor at the
//!   previous ball's centre, and one segment up the ball's own axis), the
//!   first to the balloon's knot: impulse joints, or multibody joints
//!   (`RapierJoints`). Their weight is a constant force (world gravity is
//!   zero); linear damping stands in for the quadratic drag across the
//!   ribbon, matched at its terminal speed (`ribbons::matched_linear_damping`).
//!   Collision groups let the balls meet the room and the balloons but not
//!   one another, as UP's ribbon points do.

use anyhow::{anyhow, Result};
use glam::{Mat3, Quat, Vec3};
use rapier3d::glamx;
use rapier3d::prelude::*;
use up_geom::Pose as UpPose;

use up_physics::ribbon::{NORMAL_DRAG_COEFFICIENT, RIBBON_RADIUS, RIBBON_WIDTH, ROOM_FRICTION};

use crate::engine::Engine;
use crate::ribbons::{matched_linear_damping, stretch, BenchRibbons};
use crate::scene_data::SceneData;

type RVec = rapier3d::math::Vector;
type RPose = rapier3d::math::Pose;

/// How a balloon's spheres are given to Rapier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RapierShape {
    /// One compound collider holding the balls.
    Compound,
    /// One ball collider per leaf sphere, all on the same body.
    Balls,
}

impl RapierShape {
    pub fn parse(name: &str) -> Option<RapierShape> {
        match name {
            "compound" => Some(RapierShape::Compound),
            "balls" => Some(RapierShape::Balls),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            RapierShape::Compound => "compound",
            RapierShape::Balls => "balls",
        }
    }
}

/// The forces of one balloon, constant but for drag.
#[derive(Clone, Copy, Debug)]
struct AirForces {
    /// N, at the centre of mass.
    weight: RVec,
    /// N, at the centre of buoyancy.
    buoyancy: RVec,
    /// Body frame, m.
    center_of_buoyancy: RVec,
    /// kg/m: ½·ρ·C_D·A.
    drag_factor: f32,
}

/// How a ribbon's balls are jointed in Rapier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RapierJoints {
    /// `ImpulseJointSet`: each joint a constraint solved with the contacts.
    Impulse,
    /// `MultibodyJointSet`: each balloon and its balls one articulation in
    /// reduced coordinates (the balloon its root).
    Multibody,
}

impl RapierJoints {
    pub fn parse(name: &str) -> Option<RapierJoints> {
        match name {
            "impulse" => Some(RapierJoints::Impulse),
            "multibody" => Some(RapierJoints::Multibody),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            RapierJoints::Impulse => "impulse",
            RapierJoints::Multibody => "multibody",
        }
    }
}

/// `user_data` of a balloon's body (a ribbon's balls have 0): the air forces
/// are for balloons only.
const BALLOON: u128 = 1;

/// The ribbons as Rapier holds them.
struct RapierRibbons {
    /// Balloon `b`'s balls are `balls[b·segments..(b+1)·segments]`, knot end first.
    balls: Vec<RigidBodyHandle>,
    segments: usize,
    /// Body frame, m.
    knot: Vec3,
    length: f32,
}

pub struct RapierEngine {
    world: PhysicsWorld,
    bodies: Vec<RigidBodyHandle>,
    ribbons: Option<RapierRibbons>,
    forces: AirForces,
    /// Reused list of the awake bodies.
    active: Vec<RigidBodyHandle>,
    /// Whether the world has taken a step.
    stepped: bool,
}

pub fn rvec(v: Vec3) -> RVec {
    RVec::new(v.x, v.y, v.z)
}

fn uvec(v: RVec) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}

fn rquat(q: Quat) -> glamx::Rot3 {
    glamx::Rot3::from_xyzw(q.x, q.y, q.z, q.w)
}

fn rmat(m: Mat3) -> rapier3d::math::Matrix {
    rapier3d::math::Matrix::from_cols_array(&m.to_cols_array())
}

/// The mass properties Rapier gets: mass + added mass, UP's centre of mass and inertia tensor.
pub fn mass_properties(data: &SceneData) -> MassProperties {
    MassProperties::with_inertia_matrix(
        rvec(data.shape.center_of_mass),
        data.shape.mass + data.added_mass,
        rmat(data.shape.inertia),
    )
}

/// Rapier's integration parameters closest to UP's `WorldDef`:
/// substeps → `num_solver_iterations` (Rapier's TGS-soft solver substeps this
/// many times per step), Gauss-Seidel passes → `num_internal_pgs_iterations`,
/// contact stiffness and damping → `contact_softness` (and the same for
/// contacts with the room, which Rapier otherwise makes twice as stiff).
pub fn integration_parameters(data: &SceneData) -> IntegrationParameters {
    let def = &data.def;
    let softness = SpringCoefficients::new(def.contact_hertz, def.contact_damping_ratio);
    IntegrationParameters {
        dt: def.dt,
        num_solver_iterations: def.substeps as usize,
        num_internal_pgs_iterations: def.solve_iterations.max(1) as usize,
        contact_softness: softness,
        static_contact_softness: softness,
        max_ccd_substeps: usize::from(def.enable_continuous),
        ..IntegrationParameters::default()
    }
}

/// m/s: Rapier's sleep test looks at the fastest point of a body: UP's linear
/// threshold plus its angular threshold times the balloon's reach from its centre of mass.
pub fn sleep_speed(data: &SceneData) -> f32 {
    let reach = data
        .leaves
        .iter()
        .map(|s| (s.center - data.shape.center_of_mass).length() + s.radius)
        .fold(0.0f32, f32::max);
    data.def.sleep_linear_speed + data.def.sleep_angular_speed * reach
}

impl RapierEngine {
    pub fn new(data: &SceneData, shape: RapierShape) -> Result<RapierEngine> {
        Self::build(data, shape, None)
    }

    /// The balloons with `ribbons` tied to them, jointed as `joints` says.
    pub fn with_ribbons(
        data: &SceneData,
        shape: RapierShape,
        ribbons: &BenchRibbons,
        joints: RapierJoints,
    ) -> Result<RapierEngine> {
        Self::build(data, shape, Some((ribbons, joints)))
    }

    fn build(
        data: &SceneData,
        shape: RapierShape,
        ribbons: Option<(&BenchRibbons, RapierJoints)>,
    ) -> Result<RapierEngine> {
        let def = &data.def;
        let mut world = PhysicsWorld::new();
        // Gravity acts through the explicit weight force (it must not act on the added mass).
        world.gravity = RVec::ZERO;
        world.integration_parameters = integration_parameters(data);

        let vertices = data.room.vertices().iter().map(|&v| rvec(v)).collect();
        let room = ColliderBuilder::trimesh_with_flags(
            vertices,
            data.room.triangles().to_vec(),
            TriMeshFlags::FIX_INTERNAL_EDGES,
        )
        .map_err(|e| anyhow!("the room as a Rapier triangle mesh: {e:?}"))?
        .friction(def.friction)
        .restitution(def.restitution)
        .build();
        // With ribbons the room goes in last. Rapier looks a new contact pair
        // up among the edges of its lower-handle collider; the room first
        // would have one edge per ball lying on the floor, and the first step
        // at 1,000 balloons with ribbons would take 4 s instead of 0.2.
        let mut room = Some(room);
        if ribbons.is_none() {
            if let Some(room) = room.take() {
                world.colliders.insert(room);
            }
        }

        let mass = mass_properties(data);
        let sleep_speed = sleep_speed(data);
        let balls: Vec<(RPose, SharedShape)> = data
            .leaves
            .iter()
            .map(|s| {
                (
                    RPose::from_translation(rvec(s.center)),
                    SharedShape::ball(s.radius),
                )
            })
            .collect();
        let collider = |builder: ColliderBuilder| {
            builder
                .density(0.0)
                .friction(def.friction)
                .restitution(def.restitution)
                .build()
        };
        let mut bodies = Vec::with_capacity(data.start_poses.len());
        for pose in &data.start_poses {
            let body = RigidBodyBuilder::dynamic()
                .pose(RPose::from_parts(rvec(pose.position), rquat(pose.rotation)))
                .additional_mass_properties(mass)
                .angular_damping(def.angular_damping)
                .ccd_enabled(def.enable_continuous)
                .can_sleep(def.enable_sleep)
                .user_data(BALLOON)
                .build();
            let handle = world.bodies.insert(body);
            if let Some(b) = world.bodies.get_mut(handle) {
                let activation = b.activation_mut();
                activation.normalized_linear_threshold = sleep_speed;
                activation.time_until_sleep = def.time_to_sleep;
            }
            match shape {
                RapierShape::Compound => {
                    let c = collider(ColliderBuilder::compound(balls.clone()));
                    world
                        .colliders
                        .insert_with_parent(c, handle, &mut world.bodies);
                }
                RapierShape::Balls => {
                    for (local, ball) in &balls {
                        let c = collider(ColliderBuilder::new(ball.clone()).position(*local));
                        world
                            .colliders
                            .insert_with_parent(c, handle, &mut world.bodies);
                    }
                }
            }
            // Mass properties now, not at the first step (for checks before it).
            if let Some(b) = world.bodies.get_mut(handle) {
                b.recompute_mass_properties_from_colliders(&world.colliders);
            }
            bodies.push(handle);
        }
        let ribbons = match ribbons {
            Some((r, joints)) => Some(add_ribbons(&mut world, data, &bodies, r, joints)?),
            None => None,
        };
        if let Some(room) = room.take() {
            world.colliders.insert(room);
        }
        let forces = AirForces {
            weight: rvec(data.weight()),
            buoyancy: rvec(data.buoyancy()),
            center_of_buoyancy: rvec(data.shape.center_of_buoyancy),
            drag_factor: data.drag_factor(),
        };
        Ok(RapierEngine {
            world,
            bodies,
            ribbons,
            forces,
            active: Vec::new(),
            stepped: false,
        })
    }

    /// Sets this step's forces on every awake balloon.
    fn apply_air_forces(&mut self) {
        let f = self.forces;
        self.active.clear();
        if self.stepped {
            self.active.extend(self.world.islands.active_bodies());
        } else {
            // Rapier registers the bodies with its islands during the first step.
            self.active.extend_from_slice(&self.bodies);
        }
        for &handle in &self.active {
            let Some(body) = self.world.bodies.get_mut(handle) else {
                continue;
            };
            if body.user_data != BALLOON {
                continue;
            }
            let v = body.linvel();
            let drag = -f.drag_factor * v.length() * v;
            let center_of_buoyancy = body.position() * f.center_of_buoyancy;
            body.reset_forces(false);
            body.reset_torques(false);
            body.add_force(f.weight, false);
            body.add_force_at_point(f.buoyancy + drag, center_of_buoyancy, false);
        }
    }

    pub fn body(&self, i: usize) -> Option<&RigidBody> {
        self.world.bodies.get(*self.bodies.get(i)?)
    }

    /// Balloon `i`'s ribbon: the knot, then its balls' centres, world frame.
    pub fn ribbon_points(&self, i: usize, out: &mut Vec<Vec3>) {
        out.clear();
        let (Some(r), Some(balloon)) = (&self.ribbons, self.body(i)) else {
            return;
        };
        out.push(uvec(balloon.position() * rvec(r.knot)));
        let balls = r.balls.get(i * r.segments..(i + 1) * r.segments);
        for &h in balls.unwrap_or_default() {
            if let Some(ball) = self.world.bodies.get(h) {
                out.push(uvec(ball.translation()));
            }
        }
    }

    /// kg: the mass of balloon `i`'s ribbon (its balls).
    pub fn ribbon_mass(&self, i: usize) -> f32 {
        let Some(r) = &self.ribbons else {
            return 0.0;
        };
        r.balls
            .get(i * r.segments..(i + 1) * r.segments)
            .unwrap_or_default()
            .iter()
            .filter_map(|&h| self.world.bodies.get(h))
            .map(|b| b.mass())
            .sum()
    }

    /// Bodies and impulse and multibody joints in the world.
    pub fn counts(&self) -> (usize, usize, usize) {
        (
            self.world.bodies.len(),
            self.world.impulse_joints.len(),
            self.world.multibody_joints.multibodies().count(),
        )
    }
}

/// Adds a chain of balls for each balloon's ribbon, from UP's start points.
fn add_ribbons(
    world: &mut PhysicsWorld,
    data: &SceneData,
    balloons: &[RigidBodyHandle],
    ribbons: &BenchRibbons,
    joints: RapierJoints,
) -> Result<RapierRibbons> {
    let def = &data.def;
    let segments = ribbons.segments as usize;
    if ribbons.starts.len() != balloons.len() {
        return Err(anyhow!(
            "{} ribbons for {} balloons",
            ribbons.starts.len(),
            balloons.len()
        ));
    }
    let segment = ribbons.segment_length();
    let mass = ribbons.point_mass();
    let weight = rvec(def.gravity * mass);
    let g = def.gravity.length();
    // UP's drag across the ribbon, ½·ρ·C·A on each point's share of ribbon
    // (the last point carries half a segment), as linear damping.
    let across = |share: f32| {
        0.5 * data.air_density() * NORMAL_DRAG_COEFFICIENT * share * segment * RIBBON_WIDTH
    };
    let damping_inner = matched_linear_damping(mass, across(1.0), g);
    let damping_end = matched_linear_damping(mass, across(0.5), g);
    // A 2.5 mm ball's own inertia, 2/5·m·r², is 1/1400 of the segment's as
    // a rod, m·ℓ²/12: with the joint's anchor a segment away, the joint then
    // turns the ball instead of moving it and the chain flies apart within a
    // second. Each ball gets the inertia of the segment it stands for.
    let inertia = mass * segment * segment / 12.0;
    let link = MassProperties::new(RVec::ZERO, mass, RVec::splat(inertia));
    let groups = InteractionGroups::new(Group::GROUP_2, Group::GROUP_1, InteractionTestMode::And);
    let mut balls = Vec::with_capacity(balloons.len() * segments);
    for (&balloon, start) in balloons.iter().zip(&ribbons.starts) {
        if start.len() != segments + 1 {
            return Err(anyhow!(
                "a ribbon of {} points, expected {}",
                start.len(),
                segments + 1
            ));
        }
        let mut previous = balloon;
        let mut anchor = rvec(ribbons.knot);
        for i in 1..=segments {
            // The ball's +Y points at the point before it: its joint anchor.
            let up = (start[i - 1] - start[i]).try_normalize().unwrap_or(Vec3::Y);
            let rotation = Quat::from_rotation_arc(Vec3::Y, up);
            let body = RigidBodyBuilder::dynamic()
                .pose(RPose::from_parts(rvec(start[i]), rquat(rotation)))
                .additional_mass_properties(link)
                .linear_damping(if i == segments {
                    damping_end
                } else {
                    damping_inner
                })
                .ccd_enabled(def.enable_continuous)
                .can_sleep(def.enable_sleep)
                .build();
            let handle = world.bodies.insert(body);
            let collider = ColliderBuilder::ball(RIBBON_RADIUS)
                .density(0.0)
                .friction(ROOM_FRICTION)
                .restitution(0.0)
                .collision_groups(groups)
                .build();
            world
                .colliders
                .insert_with_parent(collider, handle, &mut world.bodies);
            if let Some(b) = world.bodies.get_mut(handle) {
                b.recompute_mass_properties_from_colliders(&world.colliders);
                // Constant: the user force stays until reset.
                b.add_force(weight, false);
                let activation = b.activation_mut();
                activation.normalized_linear_threshold = def.sleep_linear_speed;
                activation.time_until_sleep = def.time_to_sleep;
            }
            let joint = SphericalJointBuilder::new()
                .local_anchor1(anchor)
                .local_anchor2(RVec::new(0.0, segment, 0.0))
                .build();
            match joints {
                RapierJoints::Impulse => {
                    world.impulse_joints.insert(previous, handle, joint, true);
                }
                RapierJoints::Multibody => {
                    world
                        .multibody_joints
                        .insert(previous, handle, joint, true)
                        .ok_or_else(|| anyhow!("Rapier refused a multibody joint"))?;
                }
            }
            balls.push(handle);
            previous = handle;
            anchor = RVec::ZERO;
        }
    }
    Ok(RapierRibbons {
        balls,
        segments,
        knot: ribbons.knot,
        length: ribbons.length,
    })
}

impl Engine for RapierEngine {
    fn name(&self) -> &'static str {
        "rapier"
    }

    fn step(&mut self) {
        self.apply_air_forces();
        self.world.step();
        self.stepped = true;
    }

    fn poses(&self, out: &mut Vec<UpPose>) {
        out.clear();
        out.extend(self.bodies.iter().filter_map(|&h| {
            let p = self.world.bodies.get(h)?.position();
            let q = p.rotation;
            Some(UpPose::new(
                uvec(p.translation),
                Quat::from_xyzw(q.x, q.y, q.z, q.w),
            ))
        }));
    }

    fn body_count(&self) -> usize {
        self.bodies.len()
    }

    fn awake_count(&self) -> usize {
        // Balloons only: a ribbon's balls are bodies too.
        self.bodies
            .iter()
            .filter_map(|&h| self.world.bodies.get(h))
            .filter(|b| !b.is_sleeping())
            .count()
    }

    fn total_translational_mass(&self) -> f64 {
        self.bodies
            .iter()
            .filter_map(|&h| self.world.bodies.get(h))
            .map(|b| f64::from(b.mass()))
            .sum()
    }

    fn ribbon_count(&self) -> usize {
        self.ribbons.as_ref().map_or(0, |_| self.bodies.len())
    }

    fn max_ribbon_stretch(&self, scratch: &mut Vec<Vec3>) -> Option<f32> {
        let length = self.ribbons.as_ref()?.length;
        let mut worst = f32::NEG_INFINITY;
        for i in 0..self.bodies.len() {
            self.ribbon_points(i, scratch);
            let s = stretch(scratch.iter().copied(), length);
            if s.is_nan() {
                return Some(s);
            }
            worst = worst.max(s);
        }
        Some(worst)
    }
}
