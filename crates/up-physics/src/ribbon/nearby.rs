//! What a ribbon may touch: the balloons and the room's triangles near it.
//!
//! Each ribbon keeps its candidates for as many steps as nothing has moved
//! past a margin (`near_lists`), so a step checks how far things moved and
//! filters short lists, instead of hashing every body again; the wake pass
//! hashes only the restless bodies, each step, if more than a few
//! (`sphere_grid`).

mod near_lists;
mod sphere_grid;

pub(crate) use near_lists::{NearFinder, NearLists, RibbonList, Spheres};
pub(crate) use sphere_grid::{sphere_meets_box, SphereGrid};

use crate::ribbon::collide::NearTriangle;
use crate::threading::join::append_lists;
use crate::threading::tasks::TaskList;

/// The balloons and room triangles near the step's awake ribbons, each
/// ribbon's back to back (`ActiveRibbon::bodies`, `triangles`), and how
/// many ribbons' lists were found again for them.
#[derive(Clone, Debug, Default)]
pub(crate) struct NearFound {
    pub bodies: Vec<u32>,
    pub triangles: Vec<NearTriangle>,
    pub found: u64,
}

impl TaskList for NearFound {
    fn reset(&mut self) {
        self.bodies.clear();
        self.triangles.clear();
        self.found = 0;
    }

    fn join_all(&mut self, lists: &[Self]) {
        append_lists(&mut self.bodies, lists, |l| &l.bodies[..], |_, &b| b);
        append_lists(&mut self.triangles, lists, |l| &l.triangles[..], |_, &t| t);
        self.found += lists.iter().map(|l| l.found).sum::<u64>();
    }
}

/// The ribbons' neighbour search, kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct NearbyBodies {
    /// The restless bodies' widened spheres, hashed by the wake pass.
    pub restless: SphereGrid,
    /// Each ribbon's candidate balloons and triangles.
    pub lists: NearLists,
    /// Every body's sphere widened by its reach this step and the ribbons'
    /// margin, as the lists test them (`World::prepare_ribbons`); a
    /// sleeper's is kept from the step it was found asleep in.
    pub centers: Vec<glam::Vec3>,
    pub radii: Vec<f32>,
    /// Per body: asleep when its sphere was found.
    pub asleep: Vec<bool>,
    /// The margin the spheres were widened by.
    pub margin: f32,
}
