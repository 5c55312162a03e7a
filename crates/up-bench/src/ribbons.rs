//! `--ribbons`: every balloon of the benchmark scene gets the default ribbon
//! (1.5 m of 0.25 g/m in 16 segments, no weight) tied at its knot, in UP
//! through `World::add_ribbon` and in Rapier as a chain of balls on spherical
//! joints (`rapier_engine`), both from the same start points. Stretch is
//! measured the same way on both: the length along the chain from the knot
//! over the ribbon's length, less one.

use anyhow::{Context, Result};
use glam::Vec3;
use up_physics::ribbon::{RibbonDef, DEFAULT_MASS_PER_LENGTH};
use up_physics::World;

/// m: the ribbon's length.
pub const LENGTH_M: f32 = 1.5;
/// Segments (points after the knot).
pub const SEGMENTS: u32 = 16;

/// The ribbons of a run: one kind, tied at one knot, and where each starts.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchRibbons {
    /// Body (mesh) frame, m: where the ribbon is tied.
    pub knot: Vec3,
    pub length: f32,
    pub segments: u32,
    /// kg/m.
    pub mass_per_length: f32,
    /// Per balloon, in creation order: its ribbon's points as UP laid them
    /// out (the knot first), world frame, m.
    pub starts: Vec<Vec<Vec3>>,
}

impl BenchRibbons {
    /// m: one segment.
    pub fn segment_length(&self) -> f32 {
        self.length / self.segments as f32
    }

    /// kg: one point after the knot (each carries the segment above it).
    pub fn point_mass(&self) -> f32 {
        self.mass_per_length * self.segment_length()
    }
}

/// Ties the default ribbon at `knot` (mesh frame) to every balloon of
/// `world`, in creation order, and returns them with their start points.
pub fn tie_ribbons(world: &mut World, knot: Vec3) -> Result<BenchRibbons> {
    let mut starts = Vec::with_capacity(world.body_count());
    for body in world.body_ids().to_vec() {
        let id = world
            .add_ribbon(&RibbonDef::new(body, knot, LENGTH_M, SEGMENTS))
            .with_context(|| format!("tying a ribbon to balloon {body:?}"))?;
        let points = world
            .ribbon_points(id)
            .context("a ribbon just tied has no points")?;
        starts.push(points.to_vec());
    }
    Ok(BenchRibbons {
        knot,
        length: LENGTH_M,
        segments: SEGMENTS,
        mass_per_length: DEFAULT_MASS_PER_LENGTH,
        starts,
    })
}

/// The relative stretch of a chain of `length` m through `points` (the knot
/// first): the sum of the distances between consecutive points over the
/// length, less one.
pub fn stretch(points: impl IntoIterator<Item = Vec3>, length: f32) -> f32 {
    let mut points = points.into_iter();
    let Some(mut last) = points.next() else {
        return 0.0;
    };
    let mut along = 0.0f32;
    for p in points {
        along += last.distance(p);
        last = p;
    }
    along / length - 1.0
}

/// 1/s: the linear damping c (dv/dt = −c·v) that gives a point of mass `m`
/// kg the terminal speed under gravity `g` m/s² that quadratic drag
/// F = −k·|v|·v (k kg/m) gives it: m·g = k·v² and m·g = m·c·v, so
/// c = g/v = √(g·k/m).
pub fn matched_linear_damping(m: f32, k: f32, g: f32) -> f32 {
    (g * k / m).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stretch_is_the_length_along_the_points_over_the_length() {
        let straight = (0..=4).map(|i| Vec3::new(0.0, -0.25 * i as f32, 0.0));
        assert!(stretch(straight, 1.0).abs() < 1e-6);
        // One segment of four 10 % long: 2.5 % in all.
        let long = [
            Vec3::ZERO,
            Vec3::new(0.0, -0.25, 0.0),
            Vec3::new(0.0, -0.525, 0.0),
            Vec3::new(0.0, -0.775, 0.0),
            Vec3::new(0.0, -1.025, 0.0),
        ];
        assert!((stretch(long, 1.0) - 0.025).abs() < 1e-6);
        // A folded chain is as long as a straight one.
        let folded = [Vec3::ZERO, Vec3::X, Vec3::ZERO];
        assert!(stretch(folded, 2.0).abs() < 1e-6);
        assert_eq!(stretch([], 1.0), 0.0);
    }

    #[test]
    fn the_damping_gives_the_drags_terminal_speed() {
        let (m, k, g) = (2.0e-5f32, 3.0e-4f32, 9.81f32);
        let c = matched_linear_damping(m, k, g);
        let terminal_quadratic = (m * g / k).sqrt();
        let terminal_linear = g / c;
        assert!((terminal_quadratic - terminal_linear).abs() < 1e-6 * terminal_quadratic);
    }
}
