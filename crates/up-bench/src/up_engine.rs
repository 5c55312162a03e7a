//! UP's side: the world `up_scene::build` made, stepped in a rayon pool of
//! the requested size (the engine's own parallel stages use it).

use anyhow::{Context, Result};
use rayon::ThreadPool;
use up_geom::Pose;
use up_physics::World;

use crate::engine::Engine;

pub struct UpEngine {
    world: World,
    pool: ThreadPool,
}

impl UpEngine {
    /// Wraps `world`, to be stepped on `threads` threads (1: one thread).
    pub fn new(world: World, threads: usize) -> Result<UpEngine> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.max(1))
            .build()
            .context("creating the thread pool")?;
        Ok(UpEngine { world, pool })
    }

    pub fn world(&self) -> &World {
        &self.world
    }
}

impl Engine for UpEngine {
    fn name(&self) -> &'static str {
        "up"
    }

    fn step(&mut self) {
        let world = &mut self.world;
        self.pool.install(|| world.step());
    }

    fn poses(&self, out: &mut Vec<Pose>) {
        out.clear();
        out.extend(self.world.poses().map(|(_, pose)| pose));
    }

    fn body_count(&self) -> usize {
        self.world.body_count()
    }

    fn awake_count(&self) -> usize {
        self.world
            .body_ids()
            .iter()
            .filter(|&&id| self.world.is_awake(id) == Some(true))
            .count()
    }

    fn total_translational_mass(&self) -> f64 {
        self.world
            .body_ids()
            .iter()
            .filter_map(|&id| self.world.effective_mass(id))
            .map(f64::from)
            .sum()
    }
}
