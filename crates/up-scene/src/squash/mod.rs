//! Squash on impact, for drawing only: how far each balloon's membrane is
//! dented by the hardest contact it had since the table was last read, and
//! along which normal. The physics stays rigid (docs/physics.md, "Squash is drawn");
//! nothing here feeds back into the world.
//!
//! A pressed membrane carries F ≈ Δp·π·a² over a patch of a² ≈ 2·R·δ: a
//! contact stiffness k = 2π·R·Δp (physics reference, "Latex contact and
//! squash"). Two loads dent it:
//!
//! - an impact: a mass m meeting a spring k at speed v compresses it by
//!   v·√(m/k), under a peak force v·√(k·m). The approach momentum m·v is
//!   read from the contact's impulses: over the step the impact gives
//!   J = (1 + e)·m·v (the approach and the bounce), so d = J / ((1 + e)·√(k·m)).
//!   A steady load gives J too, F·dt each step, which that would read as a
//!   far harder hit; but it spreads over the substeps, where an impact's
//!   approach is stopped within one: the largest impulse of one substep, P,
//!   is at least m·v in an impact (the bounce is counted in the last
//!   substep, so up to (1 + e)·m·v) and only F·dt/substeps under a load.
//!   The approach momentum is taken as the smaller of J/(1 + e) and P;
//! - a steady load F = J / dt (a balloon pressed into a pile or a wall):
//!   d = F / k.
//!
//! The dent is the larger of the two. m is the effective mass (with the added
//! mass: the air moves with the balloon). Against another balloon the two
//! membranes are springs in series (k_s = k_a·k_b/(k_a + k_b)) and m the
//! pair's reduced mass; the force dents each membrane by F/k_own. A steady
//! load also shows in P (F times the substep), as F·h·√(k/m): 1.5 times its
//! F/k at 4 substeps, a fraction of a millimetre for the tenth of a newton a
//! balloon in a pile bears, under `MIN_SQUASH_M`, so a pile at rest stays
//! round.
//!
//! Per body (dense order) the table holds `SQUASH_FLOATS` floats: the unit
//! normal times the dent depth (x, y, z, m, world frame, pointing from the
//! balloon toward what it touches) and the reach: how far the balloon's
//! surface (its model's mesh, at its size and pose now) extends from the
//! body's origin along that normal, m. A renderer flattens the drawn balloon
//! against the plane that far out less the depth. Zero: no dent. The reach
//! is the mesh's, not the contact point's: the collision spheres only
//! approximate the surface, and a plane set by them would cut the drawn
//! balloon too deep or not at all.
//! Each step keeps, per body, its deepest dent since the table was last read.

//!
//! `membrane.rs` holds the model (stiffness, the dent of one contact),
//! `table.rs` the per-body table, `world.rs` the reading of a built scene's
//! world after each step (radius and reach from the balloon models). The
//! page reads the table through up-wasm; the CLI or an exporter can do the
//! same with `record_step` and `SquashTable::take`.

mod membrane;
mod table;
mod world;

pub use membrane::{
    contact_depth, membrane_stiffness, Membrane, MAX_SQUASH_FRACTION, MEMBRANE_OVERPRESSURE_PA,
    MIN_SQUASH_M, SQUASH_FLOATS,
};
pub use table::{Impact, SquashTable};
pub use world::record_step;

#[cfg(test)]
mod tests;
