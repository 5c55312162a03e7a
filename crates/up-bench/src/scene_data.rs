//! The benchmark scene, built once by UP's scene builder and handed to both
//! engines: the room mesh, the balloon shape and every balloon's start pose.

use anyhow::{Context, Result};
use glam::Vec3;
use up_geom::{Pose, Sphere};
use up_physics::forces::buoyancy::buoyancy_force;
use up_physics::forces::drag::drag_factor;
use up_physics::forces::gravity::gravity_force;
use up_physics::{BalloonShape, WorldDef};
use up_scene::bench_scene::{bench_scene, BenchLayout};
use up_scene::build::{build_world, BuiltScene};
use up_scene::room::RoomMesh;
use up_scene::scene::Scene;

/// Everything both engines are built from.
pub struct SceneData {
    pub scene: Scene,
    pub layout: BenchLayout,
    /// The world definition (dt, substeps, contact, air, room) UP uses.
    pub def: WorldDef,
    pub room: RoomMesh,
    /// The one balloon model of the scene.
    pub shape: BalloonShape,
    /// kg: added mass C_a·ρ_air·V of one balloon in the scene's air.
    pub added_mass: f32,
    /// Leaf spheres of the balloon's sphere tree, body frame: the collision shape.
    pub leaves: Vec<Sphere>,
    /// Start pose of each balloon's body frame.
    pub start_poses: Vec<Pose>,
    /// Body frame, m: where a ribbon is tied, the bottom of the knot that
    /// closes the neck (on the axis, `knot_radius` below the knot ball's centre).
    pub knot: Vec3,
}

impl SceneData {
    /// The benchmark scene for `balloons` balloons from `seed`, and UP's world built from it.
    pub fn build(balloons: u64, seed: u64) -> Result<(SceneData, BuiltScene)> {
        let (scene, layout) = bench_scene(balloons, seed).context("benchmark scene")?;
        let built = build_world(&scene).context("building the benchmark scene")?;
        let world = &built.world;
        let first = *world
            .body_ids()
            .first()
            .context("the benchmark scene has no balloon")?;
        let shape_id = world.shape_of(first).context("balloon without a shape")?;
        let mut shape = world.shape(shape_id).context("missing shape")?.clone();
        // The scene fills its balloons (`World::fill`: 2 kPa over the room,
        // so 2 % more helium than the shape's own figure); Rapier's balloons
        // get the filled mass, and an inertia scaled with it as UP's is. Over
        // a benchmark's seconds the gas changes by parts in a million.
        if let Some(gas) = world.gas(first) {
            let filled = gas.mass() as f32;
            shape.inertia *= filled / shape.mass;
            shape.mass = filled;
        }
        let added_mass = world.added_mass(shape_id).context("missing shape")?;
        let leaves = shape.tree.leaf_spheres().collect();
        let start_poses = world.poses().map(|(_, pose)| pose).collect();
        let model = built
            .balloon_models
            .first()
            .context("the benchmark scene has no balloon model")?;
        let dims = &model.mesh.dimensions;
        let knot = dims.knot_center - Vec3::Y * dims.knot_radius;
        let data = SceneData {
            def: world.def().clone(),
            room: built.room.clone(),
            shape,
            added_mass,
            leaves,
            start_poses,
            knot,
            scene,
            layout,
        };
        Ok((data, built))
    }

    /// kg/m³ of the scene's air.
    pub fn air_density(&self) -> f32 {
        self.def.atmosphere.air_density()
    }

    /// N: the weight of one balloon (gravity on its own mass, not the added mass).
    pub fn weight(&self) -> Vec3 {
        gravity_force(self.shape.mass, self.def.gravity)
    }

    /// N: the buoyancy of one balloon (the displaced air's weight, upward).
    pub fn buoyancy(&self) -> Vec3 {
        buoyancy_force(self.air_density(), self.shape.volume, self.def.gravity)
    }

    /// kg/m: k in the quadratic drag F = −k·|v|·v, ½·ρ·C_D·A.
    pub fn drag_factor(&self) -> f32 {
        drag_factor(
            self.air_density(),
            self.def.drag_coefficient,
            self.shape.reference_area,
        )
    }
}
