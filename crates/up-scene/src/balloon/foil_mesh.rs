//! A procedural round foil balloon: two discs of metallised nylon sealed at
//! the rim and filled, a flat pillow standing on edge.
//!
//! Body frame (as `balloon_mesh`'s): origin at the centre of the disc, +Y up,
//! the faces towards ±Z, the valve at the bottom of the rim; metres. With
//! R = diameter / 2, a face at distance ρ = t·R(φ) from the centre, along the
//! direction φ in the x–y plane, stands `z = ±H·√(1 − t²)` off the rim's
//! plane (H = 0.274 R): an 18″ balloon comes out 45.7 cm across and 12.5 cm
//! thick, as filled ones measure (12–13 cm), holding 14.1 L. R(φ) is R except
//! near the bottom, where the rim runs out to a point 12 % of R further down:
//! the valve strip, where the ribbon ties.
//!
//! Its surface, 0.39 m² at 18″, is more than the 0.33 m² of the two flat
//! discs a real one is cut from: filled, the film cannot stretch, and its rim
//! crimps into the small wrinkles this smooth mesh leaves out.
//!
//! The shape is a surface of revolution about Z but for that point, so
//! `BalloonDimensions` describe it as a latex balloon's: the valve is its
//! "knot", a small ball at the tip (its mass, not its shape). The sphere
//! tree is the planar fitter's (`up_geom::fit::planar_cover`), 64 leaves
//! over its face: those over the middle each hold a patch about 4 cm across
//! and stand up to 4 mm past the face, so two pillows face to face rest
//! within 1 cm of their drawn thickness; the tops drop away from the middle
//! (3 mm lower 10 cm out), so a pillow lying on a ceiling rests on its
//! middle and rights itself when tipped.
//! Everything scales with the diameter. Closed and watertight (one vertex per face
//! centre, rings share their seam vertex), wound counter-clockwise seen from
//! outside, smooth per-vertex normals: 2,400 triangles.

use glam::Vec3;

use crate::balloon::mesh::{
    cos_sin, pole_to_pole_triangles, vertex_normals, BalloonDimensions, BalloonMesh,
    BalloonMeshError,
};

/// Vertices around each ring (a multiple of 4: one lands on the valve's tip).
pub const FOIL_SEGMENTS: u32 = 48;
/// Half the thickness at the centre, in units of R: 12.5 cm through an 18″.
pub const HALF_THICKNESS: f32 = 0.274;
/// How far the rim runs out at the valve, in units of R.
pub const VALVE_POINT: f32 = 0.12;
/// Radius of the valve's ball (its mass's place), in units of R.
const VALVE_RADIUS: f32 = 0.03;
/// Rings on each face between its centre and the rim (the rim not counted).
const FACE_RINGS: usize = 12;

/// The rim's distance from the centre along the direction whose sine
/// (towards +Y) is `phi_sin`, in units of R: 1, running out to
/// 1 + `VALVE_POINT` at the bottom as cos⁸ of the angle from straight down
/// (half of it within ±23°).
fn rim(phi_sin: f32) -> f32 {
    // cos of the angle between the direction and straight down.
    let down = (-phi_sin).max(0.0);
    let c2 = down * down;
    let c8 = (c2 * c2) * (c2 * c2);
    1.0 + VALVE_POINT * c8
}

/// The foil balloon of diameter `diameter_m` (m; 0.457 for 18″).
pub fn foil_mesh(diameter_m: f32) -> Result<BalloonMesh, BalloonMeshError> {
    if !(diameter_m.is_finite() && diameter_m > 0.0) {
        return Err(BalloonMeshError::BadDiameter(diameter_m));
    }
    let r = 0.5 * diameter_m;
    let h = HALF_THICKNESS * r;
    // Profile from the front centre to the back centre: (t, z), t the
    // share of the rim's distance; dense near the rim, where it curves.
    let mut profile = vec![(0.0f32, h)];
    for i in 1..FACE_RINGS + 1 {
        let t = cos_sin(std::f32::consts::FRAC_PI_2 * i as f32 / (FACE_RINGS + 1) as f32).1;
        profile.push((t, h * (1.0 - t * t).sqrt()));
    }
    profile.push((1.0, 0.0));
    for i in (1..FACE_RINGS + 1).rev() {
        let (t, z) = profile[i];
        profile.push((t, -z));
    }
    profile.push((0.0, -h));

    let directions: Vec<(f32, f32, f32)> = (0..FOIL_SEGMENTS)
        .map(|j| {
            let (cos, sin) = cos_sin(std::f32::consts::TAU * j as f32 / FOIL_SEGMENTS as f32);
            (cos, sin, r * rim(sin))
        })
        .collect();
    let rings = &profile[1..profile.len() - 1];
    let mut positions = Vec::with_capacity(rings.len() * FOIL_SEGMENTS as usize + 2);
    positions.push(Vec3::new(0.0, 0.0, h));
    for &(t, z) in rings {
        for &(cos, sin, reach) in &directions {
            positions.push(Vec3::new(t * reach * cos, t * reach * sin, z));
        }
    }
    positions.push(Vec3::new(0.0, 0.0, -h));
    // Seen from +Z, φ runs counter-clockwise: the front face's triangles go
    // centre → ring j → ring j + 1.
    let indices = pole_to_pole_triangles(rings.len(), FOIL_SEGMENTS);
    let normals = vertex_normals(&positions, &indices);

    let tip = -r * (1.0 + VALVE_POINT);
    let valve_radius = VALVE_RADIUS * r;
    let dimensions = BalloonDimensions {
        diameter: diameter_m,
        top_y: r,
        neck_top_y: -r,
        neck_bottom_y: tip,
        knot_center: Vec3::new(0.0, tip + valve_radius, 0.0),
        knot_radius: valve_radius,
        bottom_y: tip,
    };
    Ok(BalloonMesh {
        positions,
        normals,
        indices,
        dimensions,
    })
}

/// m²: the balloon's largest horizontal section, through its centre: the
/// frontal area it meets the air with rising (≈ 0.045 for 18″).
pub fn foil_frontal_area(mesh: &BalloonMesh) -> f32 {
    // The section at y = 0 is bounded by the rings' points along φ = 0 (+X,
    // where the rim is R): the front quarter's outline from the centre to the
    // rim, 4 ∫ z dx over it in all, by trapezoids.
    let mut points: Vec<(f32, f32)> = mesh
        .positions
        .iter()
        .filter(|p| p.y == 0.0 && p.x >= 0.0 && p.z >= 0.0)
        .map(|p| (p.x, p.z))
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let area: f32 = points
        .windows(2)
        .map(|w| (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
        .sum();
    // Each trapezoid term is twice its area: 2 · (2 ∫ z dx) = 4 ∫ z dx.
    2.0 * area
}

#[cfg(test)]
mod tests {
    use super::*;
    use up_geom::fit::check_closed;
    use up_geom::fit::mesh_integrals::{shell_integrals, solid_integrals};

    #[test]
    fn an_18_inch_foil_balloon_is_a_closed_pillow_of_about_14_litres() {
        let m = foil_mesh(18.0 * 0.0254).unwrap();
        assert!(check_closed(&m.positions, &m.indices).is_ok());
        let solid = solid_integrals(&m.positions, &m.indices);
        assert!(
            (0.0135..0.0145).contains(&solid.volume),
            "V = {} m³",
            solid.volume
        );
        let b = up_geom::Aabb::from_points(&m.positions);
        let e = b.extents();
        assert!((e.x - 0.4572).abs() < 1e-3, "width {}", e.x);
        assert!((0.12..=0.13).contains(&e.z), "thickness {}", e.z);
        assert!((b.min.y - m.dimensions.bottom_y).abs() < 1e-6);
        assert!((b.max.y - m.dimensions.top_y).abs() < 2e-3);
        // Two 46 cm discs of film, a little more for their bulge: ≈ 0.33 m²+.
        let area = shell_integrals(&m.positions, &m.indices).area;
        assert!((0.33..0.40).contains(&area), "area {area} m²");
        let frontal = foil_frontal_area(&m);
        // The section through the centre: π/4 · width · thickness for an ellipse.
        let ellipse = std::f32::consts::FRAC_PI_4 * e.x * e.z;
        assert!(
            (frontal / ellipse - 1.0).abs() < 0.02,
            "{frontal} vs {ellipse}"
        );
        assert_eq!(m.normals.len(), m.positions.len());
        assert_eq!(m.indices.len(), 2400);
    }

    #[test]
    fn faces_wind_outward() {
        let m = foil_mesh(0.4572).unwrap();
        let centre = solid_integrals(&m.positions, &m.indices).centroid;
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let face = (b - a).cross(c - a);
            if face.length() < 1e-9 {
                continue;
            }
            let middle = (a + b + c) / 3.0;
            assert!(face.dot(middle - centre) > 0.0, "inward face at {middle}");
        }
    }

    #[test]
    fn the_foil_scales_with_its_diameter() {
        let small = foil_mesh(0.2).unwrap();
        let big = foil_mesh(0.4).unwrap();
        let v = |m: &BalloonMesh| solid_integrals(&m.positions, &m.indices).volume;
        assert!((v(&big) / v(&small) - 8.0).abs() < 1e-3);
        assert_eq!(small.indices, big.indices);
        assert!(matches!(
            foil_mesh(-1.0),
            Err(BalloonMeshError::BadDiameter(_))
        ));
    }
}
