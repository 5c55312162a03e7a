//! How many times the other ribbons are twisted round one ribbon: its
//! linking number with each (`up_physics::ribbon::linking`), from the
//! ribbons' points as the page holds them (`write_ribbon_points` and the
//! offsets of `write_ribbons`), so that the page and the tests count turns
//! with the engine's one implementation. Each ribbon is taken from its free
//! end up to its knot and closed far above its balloon and far below its
//! end (`closed_pair`, Y up): untwisted ribbons give 0, each full turn of
//! one round the other adds one. Meant for ribbons whose free ends are held
//! near each other (a bouquet's weights on the floor); free ends apart or
//! loose give a number all the same, but not a count of turns.

use glam::Vec3;
use up_physics::ribbon::linking::{closed_pair, linking_number};
use wasm_bindgen::prelude::*;

use crate::error::{named, CallError, WasmError};
use crate::ribbons::RIBBON_POINT_FLOATS;

/// Ribbon `index`'s points, free end first (the page's order is knot first).
fn from_free_end(points: &[f32], offsets: &[u32], index: usize) -> Vec<Vec3> {
    let (first, end) = (offsets[index] as usize, offsets[index + 1] as usize);
    points[first * RIBBON_POINT_FLOATS..end * RIBBON_POINT_FLOATS]
        .chunks_exact(RIBBON_POINT_FLOATS)
        .rev()
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect()
}

/// The linking number of ribbon `ribbon` with each ribbon, in ribbon order
/// (0 with itself), from `points` (x, y, z a point, ribbon after ribbon,
/// the knot first) and `offsets` (each ribbon's first point, then the
/// total). Refused when the offsets do not describe the points, a ribbon
/// has no point, or `ribbon` is not one of them.
pub fn ribbon_links(points: &[f32], offsets: &[u32], ribbon: u32) -> Result<Vec<i32>, WasmError> {
    let count = offsets.len().saturating_sub(1);
    let total = offsets.last().copied().unwrap_or(0) as usize;
    if offsets.first().is_some_and(|&o| o != 0)
        || offsets.windows(2).any(|w| w[1] <= w[0])
        || total * RIBBON_POINT_FLOATS != points.len()
    {
        return Err(WasmError::BadArgument(format!(
            "ribbon offsets: expected 0, then rising to the {} points given",
            points.len() / RIBBON_POINT_FLOATS
        )));
    }
    if points.iter().any(|v| !v.is_finite()) {
        return Err(WasmError::BadArgument(
            "ribbon points: expected finite coordinates".into(),
        ));
    }
    let ribbon = ribbon as usize;
    if ribbon >= count {
        return Err(WasmError::OutOfRange(format!(
            "ribbon {ribbon}: there are {count} ribbons"
        )));
    }
    let this = from_free_end(points, offsets, ribbon);
    Ok((0..count)
        .map(|other| {
            if other == ribbon {
                return 0;
            }
            let (a, b) = closed_pair(&this, &from_free_end(points, offsets, other), Vec3::Y);
            linking_number(&a, &b).0
        })
        .collect())
}

/// The linking number of ribbon `ribbon` with each ribbon (`ribbon_links`),
/// from the points and offsets the engine wrote for the page; needs no world.
#[wasm_bindgen]
pub fn ribbon_linking(points: &[f32], offsets: &[u32], ribbon: u32) -> Result<Vec<i32>, CallError> {
    named("ribbon_linking", ribbon_links(points, offsets, ribbon))
}

#[cfg(test)]
#[path = "ribbon_links_tests.rs"]
mod tests;
