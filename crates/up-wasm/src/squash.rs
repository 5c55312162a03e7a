//! The squash table for the page: each balloon's deepest dent since the page
//! last read it (`SQUASH_FLOATS` per body, dense order), from up-scene's
//! membrane model (`up_scene::squash`, where the model and its tests live),
//! read after every step. Drawing only: the physics stays rigid.

use up_scene::squash::{record_step, SquashTable};

use crate::loaded::Loaded;

pub use up_scene::squash::{MEMBRANE_OVERPRESSURE_PA, SQUASH_FLOATS};

/// The table the steps fill, and the copy the page last read.
#[derive(Default)]
pub struct SquashBuffers {
    table: SquashTable,
    /// `SQUASH_FLOATS` per body, dense order: what `body_squash_ptr` shows.
    pub out: Vec<f32>,
}

impl SquashBuffers {
    /// Reads the last step's contacts into the table (after every step).
    pub fn record(&mut self, loaded: &Loaded) {
        let built = &loaded.built;
        record_step(&mut self.table, &built.world, &built.balloon_models);
    }

    /// Each of `body_count` bodies' deepest dent since the last call into
    /// `out`, then forgotten.
    pub fn write(&mut self, body_count: usize) {
        self.table.take(body_count, &mut self.out);
    }
}

#[cfg(test)]
#[path = "squash_tests.rs"]
mod tests;
