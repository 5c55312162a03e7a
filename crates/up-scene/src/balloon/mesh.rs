//! A procedural latex balloon: a surface of revolution about +Y.
//!
//! Body frame (the mesh frame, also the physics body frame): origin at the
//! centre of the head's widest circle, +Y up along the axis, the knot at
//! negative Y; metres. The profile, from the top down, with R = diameter / 2:
//!
//! - head: the upper half of an ellipse, semi-axes R (across) and R (up);
//! - body: `ρ = R (1 − s³)` for `s = −y / (1.52 R)` in 0..1 — full near the
//!   widest circle, then a blunt cone into the neck (a balloon is taller than
//!   wide: 11″ comes out 28 cm across, 38.7 cm from top to knot, 14.1 L);
//! - neck: a short cylinder of radius 0.045 R, joined to the body by a smooth
//!   maximum so the body flows into it;
//! - knot: a small ball of radius 0.08 R under the neck, closing the surface.
//!
//! Everything scales with the diameter. The mesh is closed and watertight
//! (one vertex per pole, rings share their seam vertex), wound
//! counter-clockwise seen from outside (outward normals), with smooth
//! per-vertex normals for rendering: 2,736 triangles.

use glam::{Vec2, Vec3};
use thiserror::Error;

/// (cos a, sin a) through glam, which uses libm: the same bits natively and in wasm.
pub(crate) fn cos_sin(a: f32) -> (f32, f32) {
    let v = Vec2::from_angle(a);
    (v.x, v.y)
}

/// Vertices around each ring.
pub const SEGMENTS: u32 = 36;
/// Head height above the widest circle, in units of R.
const HEAD_HEIGHT: f32 = 0.85;
/// Body length below the widest circle down to the neck, in units of R
/// (tuned so the 11″ balloon holds about 14 L).
const BODY_LENGTH: f32 = 1.70;
/// Neck radius and length, in units of R.
const NECK_RADIUS: f32 = 0.045;
const NECK_LENGTH: f32 = 0.1;
/// Knot radius, in units of R.
const KNOT_RADIUS: f32 = 0.08;
/// Rings in each part of the profile (poles not counted).
const HEAD_RINGS: usize = 12;
const BODY_RINGS: usize = 18;
const NECK_RINGS: usize = 2;
const KNOT_RINGS: usize = 6;

#[derive(Clone, Debug, Error, PartialEq)]
pub enum BalloonMeshError {
    #[error("balloon diameter_m: expected a finite number of metres > 0, got {0}")]
    BadDiameter(f32),
}

/// Landmarks of the balloon's shape, body frame, metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BalloonDimensions {
    /// Widest diameter (the head's widest circle, at y = 0); 0.28 for 11″.
    pub diameter: f32,
    /// y of the top pole.
    pub top_y: f32,
    /// y where the body meets the neck.
    pub neck_top_y: f32,
    /// y where the neck meets the knot.
    pub neck_bottom_y: f32,
    /// Centre of the knot ball (on the axis).
    pub knot_center: Vec3,
    /// Radius of the knot ball.
    pub knot_radius: f32,
    /// y of the bottom pole (the tip of the knot).
    pub bottom_y: f32,
}

impl BalloonDimensions {
    /// Top to knot tip, m.
    pub fn height(&self) -> f32 {
        self.top_y - self.bottom_y
    }
}

/// Triangle mesh of a balloon, body frame (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct BalloonMesh {
    pub positions: Vec<Vec3>,
    /// Unit, per vertex, smooth (area-weighted face normals).
    pub normals: Vec<Vec3>,
    /// Counter-clockwise seen from outside.
    pub indices: Vec<[u32; 3]>,
    pub dimensions: BalloonDimensions,
}

impl BalloonMesh {
    /// The balloon of widest diameter `diameter_m` (m; 0.28 for 11″).
    pub fn new(diameter_m: f32) -> Result<Self, BalloonMeshError> {
        if !(diameter_m.is_finite() && diameter_m > 0.0) {
            return Err(BalloonMeshError::BadDiameter(diameter_m));
        }
        let (profile, dimensions) = profile(diameter_m);
        let (positions, indices) = revolve(&profile, SEGMENTS);
        let normals = vertex_normals(&positions, &indices);
        Ok(Self {
            positions,
            normals,
            indices,
            dimensions,
        })
    }
}

/// The profile as (distance from the axis, y) from the top pole to the bottom
/// pole, both poles on the axis.
fn profile(diameter: f32) -> (Vec<(f32, f32)>, BalloonDimensions) {
    use std::f32::consts::FRAC_PI_2;
    let r = 0.5 * diameter;
    let (head, body) = (HEAD_HEIGHT * r, BODY_LENGTH * r);
    let (neck_r, neck_len, knot_r) = (NECK_RADIUS * r, NECK_LENGTH * r, KNOT_RADIUS * r);
    let mut points = vec![(0.0, head)];
    // Head: quarter ellipse from the pole to the widest circle (included).
    for i in 1..=HEAD_RINGS {
        let (cos, sin) = cos_sin(FRAC_PI_2 * i as f32 / HEAD_RINGS as f32);
        points.push((r * sin, head * cos));
    }
    // Body: s runs 0..1 downwards, spaced densely near the neck where it bends.
    for i in 1..=BODY_RINGS {
        let s = cos_sin(FRAC_PI_2 * i as f32 / BODY_RINGS as f32).1;
        let cone = r * (1.0 - s * s * s);
        // Smooth maximum with the neck radius: a fillet instead of a crease.
        let quartic = |x: f32| (x * x) * (x * x);
        let rho = (quartic(cone) + quartic(neck_r)).sqrt().sqrt();
        points.push((rho, -body * s));
    }
    let neck_top = -body;
    let neck_bottom = neck_top - neck_len;
    for i in 1..=NECK_RINGS {
        points.push((neck_r, neck_top - neck_len * i as f32 / NECK_RINGS as f32));
    }
    // Knot: a ball whose upper side passes through the neck's bottom ring.
    let knot_rise = (knot_r * knot_r - neck_r * neck_r).sqrt();
    let knot_y = neck_bottom - knot_rise;
    // Polar angle of the junction on the ball, from its top: atan2(ρ, rise).
    let start = Vec2::new(knot_rise, neck_r).to_angle();
    let from_top = std::f32::consts::PI - start;
    for i in 1..=KNOT_RINGS {
        // Polar angle measured from the knot ball's top, past the junction.
        let a = std::f32::consts::PI - from_top * (1.0 - i as f32 / (KNOT_RINGS + 1) as f32);
        let (cos, sin) = cos_sin(a);
        points.push((knot_r * sin, knot_y + knot_r * cos));
    }
    let bottom = knot_y - knot_r;
    points.push((0.0, bottom));
    let dimensions = BalloonDimensions {
        diameter,
        top_y: head,
        neck_top_y: neck_top,
        neck_bottom_y: neck_bottom,
        knot_center: Vec3::new(0.0, knot_y, 0.0),
        knot_radius: knot_r,
        bottom_y: bottom,
    };
    (points, dimensions)
}

/// Sweeps a pole-to-pole profile around +Y: one vertex per pole, `segments`
/// per ring, counter-clockwise seen from outside.
fn revolve(profile: &[(f32, f32)], segments: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let rings = &profile[1..profile.len() - 1];
    let mut positions = Vec::with_capacity(rings.len() * segments as usize + 2);
    positions.push(Vec3::new(0.0, profile[0].1, 0.0));
    for &(rho, y) in rings {
        for j in 0..segments {
            let (cos, sin) = cos_sin(std::f32::consts::TAU * j as f32 / segments as f32);
            positions.push(Vec3::new(rho * cos, y, -rho * sin));
        }
    }
    positions.push(Vec3::new(0.0, profile[profile.len() - 1].1, 0.0));
    let indices = pole_to_pole_triangles(rings.len(), segments);
    (positions, indices)
}

/// The triangles of a closed surface laid out as vertex 0 (the first pole),
/// then `rings` rings of `segments` vertices each, then the last pole; each
/// ring runs counter-clockwise seen from the first pole's side, so the
/// triangles face outward.
pub(crate) fn pole_to_pole_triangles(rings: usize, segments: u32) -> Vec<[u32; 3]> {
    let ring = |i: usize, j: u32| 1 + i as u32 * segments + j % segments;
    let last_pole = 1 + rings as u32 * segments;
    let mut indices = Vec::with_capacity(2 * segments as usize * rings);
    for j in 0..segments {
        indices.push([0, ring(0, j), ring(0, j + 1)]);
    }
    for i in 0..rings - 1 {
        for j in 0..segments {
            let (a, b) = (ring(i, j), ring(i, j + 1));
            let (c, d) = (ring(i + 1, j), ring(i + 1, j + 1));
            indices.push([a, c, d]);
            indices.push([a, d, b]);
        }
    }
    let last = rings - 1;
    for j in 0..segments {
        indices.push([last_pole, ring(last, j + 1), ring(last, j)]);
    }
    indices
}

/// Smooth normals: the area-weighted sum of the faces around each vertex.
pub(crate) fn vertex_normals(positions: &[Vec3], indices: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; positions.len()];
    for t in indices {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        // Twice the area times the unit normal.
        let n = (b - a).cross(c - a);
        for &i in t {
            sums[i as usize] += n;
        }
    }
    sums.iter().map(|n| n.normalize_or_zero()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use up_geom::fit::check_closed;
    use up_geom::fit::mesh_integrals::solid_integrals;

    #[test]
    fn default_balloon_is_closed_outward_and_about_14_litres() {
        let m = BalloonMesh::new(0.28).unwrap();
        assert!(check_closed(&m.positions, &m.indices).is_ok());
        let solid = solid_integrals(&m.positions, &m.indices);
        assert!(
            (0.0138..0.0144).contains(&solid.volume),
            "V = {} m³",
            solid.volume
        );
        assert!(
            (2000..3200).contains(&m.indices.len()),
            "{} triangles",
            m.indices.len()
        );
        // Taller than wide: 28 cm across at y = 0, 38.7 cm from top to knot tip.
        let b = up_geom::Aabb::from_points(&m.positions);
        assert!((b.extents().x - 0.28).abs() < 1e-3 && (b.extents().z - 0.28).abs() < 2e-3);
        assert!(
            b.extents().y > 0.3 && b.extents().y < 0.45,
            "height {}",
            b.extents().y
        );
        assert!((b.max.y - m.dimensions.top_y).abs() < 1e-6);
        assert!((b.min.y - m.dimensions.bottom_y).abs() < 1e-6);
        // The head is above the origin and the knot well below.
        assert!(m.dimensions.knot_center.y < -0.2);
    }

    #[test]
    fn normals_are_unit_and_point_outward() {
        let m = BalloonMesh::new(0.28).unwrap();
        assert_eq!(m.normals.len(), m.positions.len());
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let face = (b - a).cross(c - a);
            if face.length() < 1e-9 {
                continue;
            }
            // Every face agrees with its corners' smooth normals (no flipped faces).
            for &i in t {
                assert!(m.normals[i as usize].dot(face.normalize()) > 0.0);
            }
        }
        assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
        assert!(m.normals[0].dot(Vec3::Y) > 0.999);
        assert!(m.normals[m.normals.len() - 1].dot(Vec3::NEG_Y) > 0.999);
    }

    #[test]
    fn mesh_scales_with_the_diameter() {
        let small = BalloonMesh::new(0.14).unwrap();
        let big = BalloonMesh::new(0.28).unwrap();
        let v_small = solid_integrals(&small.positions, &small.indices).volume;
        let v_big = solid_integrals(&big.positions, &big.indices).volume;
        assert!((v_big / v_small - 8.0).abs() < 1e-3);
        assert_eq!(small.indices, big.indices);
    }

    #[test]
    fn bad_diameter_is_an_error() {
        for d in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(matches!(
                BalloonMesh::new(d),
                Err(BalloonMeshError::BadDiameter(_))
            ));
        }
    }
}
