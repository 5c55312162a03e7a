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

use anyhow::{anyhow, Result};
use glam::{Mat3, Quat, Vec3};
use rapier3d::glamx;
use rapier3d::prelude::*;
use up_geom::Pose as UpPose;

use crate::engine::Engine;
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

pub struct RapierEngine {
    world: PhysicsWorld,
    bodies: Vec<RigidBodyHandle>,
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
        world.colliders.insert(room);

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
        let forces = AirForces {
            weight: rvec(data.weight()),
            buoyancy: rvec(data.buoyancy()),
            center_of_buoyancy: rvec(data.shape.center_of_buoyancy),
            drag_factor: data.drag_factor(),
        };
        Ok(RapierEngine {
            world,
            bodies,
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
        self.world.islands.num_active_bodies()
    }

    fn total_translational_mass(&self) -> f64 {
        self.bodies
            .iter()
            .filter_map(|&h| self.world.bodies.get(h))
            .map(|b| f64::from(b.mass()))
            .sum()
    }
}
