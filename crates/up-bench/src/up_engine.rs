//! UP's side: the world `up_scene::build` made, stepped in a rayon pool of
//! the requested size (the engine's own parallel stages use it).

use anyhow::{Context, Result};
use glam::Vec3;
use rayon::ThreadPool;
use up_geom::Pose;
use up_physics::{Counters, World};

use crate::engine::Engine;
use crate::ribbons::stretch;

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

    fn ribbon_count(&self) -> usize {
        self.world.ribbon_count()
    }

    fn max_ribbon_stretch(&self, _scratch: &mut Vec<Vec3>) -> Option<f32> {
        let world = &self.world;
        let ids = world.ribbon_ids();
        if ids.is_empty() {
            return None;
        }
        let mut worst = f32::NEG_INFINITY;
        for id in ids {
            let (Some(points), Some((length, _))) =
                (world.ribbon_points(id), world.ribbon_length_and_mass(id))
            else {
                continue;
            };
            let s = stretch(points.iter().copied(), length);
            if s.is_nan() {
                return Some(s);
            }
            worst = worst.max(s);
        }
        Some(worst)
    }

    fn counters(&self) -> Option<Counters> {
        Some(*self.world.counters())
    }
}
