//! Integrals over a closed triangle mesh: surface area, enclosed volume, their
//! centroids and second moments.
//!
//! Solid integrals use the divergence theorem: every triangle forms a signed
//! tetrahedron with a reference point, and the signed pieces add up to the
//! enclosed solid (outward winding gives a positive volume). Shell integrals
//! treat the surface as a thin sheet of uniform areal density. Sums run in f64
//! about the mesh's box centre so that thousands of small terms do not lose
//! digits; results come back in f32.
//!
//! Second moments are `∫ x xᵀ` about the origin of the mesh frame; the inertia
//! tensor of a body of density ρ is then `ρ (tr(S)·I − S)`.

use glam::{DMat3, DVec3, Mat3, Vec3};

use crate::shape::aabb::Aabb;

/// Integrals over the solid a closed mesh encloses, unit density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidIntegrals {
    /// m³; signed: positive when the triangles wind counter-clockwise seen
    /// from outside (normals pointing out), negative when they point in.
    pub volume: f32,
    /// m, mesh frame: the centroid of the enclosed solid (zero when the volume is zero).
    pub centroid: Vec3,
    /// m⁵: `∫ x xᵀ dV` about the mesh origin, signed like `volume`.
    pub second_moment: Mat3,
}

/// Integrals over the surface of a mesh, unit areal density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellIntegrals {
    /// m².
    pub area: f32,
    /// m, mesh frame: the area-weighted centroid of the surface.
    pub centroid: Vec3,
    /// m⁴: `∫ x xᵀ dA` about the mesh origin.
    pub second_moment: Mat3,
}

/// Triangles whose indices repeat a vertex are skipped (they have no area);
/// indices must be in range (the caller checks).
fn corners(vertices: &[Vec3], t: &[u32; 3], reference: DVec3) -> Option<[DVec3; 3]> {
    if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
        return None;
    }
    let p = |i: u32| vertices[i as usize].as_dvec3() - reference;
    Some([p(t[0]), p(t[1]), p(t[2])])
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// `Σ vᵢ vᵢᵀ + s sᵀ` with `s = Σ vᵢ`: the common factor of the simplex moments.
fn simplex_moment(v: &[DVec3; 3]) -> DMat3 {
    let s = v[0] + v[1] + v[2];
    outer(v[0], v[0]) + outer(v[1], v[1]) + outer(v[2], v[2]) + outer(s, s)
}

/// Moves a second moment taken about `reference` (with zeroth moment `m0` and
/// first moment `m1`, both about `reference`) to the mesh origin.
fn shift_to_origin(s: DMat3, m0: f64, m1: DVec3, reference: DVec3) -> DMat3 {
    // ∫ (y + r)(y + r)ᵀ = S + m1 rᵀ + r m1ᵀ + m0 r rᵀ.
    s + outer(m1, reference) + outer(reference, m1) + outer(reference, reference) * m0
}

fn reference_point(vertices: &[Vec3]) -> DVec3 {
    let b = Aabb::from_points(vertices);
    if b.is_empty() {
        DVec3::ZERO
    } else {
        b.center().as_dvec3()
    }
}

/// Volume, centroid and second moment of the solid a closed mesh encloses.
pub fn solid_integrals(vertices: &[Vec3], triangles: &[[u32; 3]]) -> SolidIntegrals {
    let reference = reference_point(vertices);
    let mut volume = 0.0f64;
    let mut first = DVec3::ZERO;
    let mut second = DMat3::ZERO;
    for t in triangles {
        let Some(v) = corners(vertices, t, reference) else {
            continue;
        };
        // Signed tetrahedron (reference, a, b, c): det / 6.
        let det = v[0].dot(v[1].cross(v[2]));
        volume += det / 6.0;
        first += (v[0] + v[1] + v[2]) * (det / 24.0);
        second += simplex_moment(&v) * (det / 120.0);
    }
    let centroid = if volume != 0.0 {
        first / volume + reference
    } else {
        reference
    };
    SolidIntegrals {
        volume: volume as f32,
        centroid: centroid.as_vec3(),
        second_moment: shift_to_origin(second, volume, first, reference).as_mat3(),
    }
}

/// Area, area centroid and second moment of a mesh's surface.
pub fn shell_integrals(vertices: &[Vec3], triangles: &[[u32; 3]]) -> ShellIntegrals {
    let reference = reference_point(vertices);
    let mut area = 0.0f64;
    let mut first = DVec3::ZERO;
    let mut second = DMat3::ZERO;
    for t in triangles {
        let Some(v) = corners(vertices, t, reference) else {
            continue;
        };
        let a = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).length();
        area += a;
        first += (v[0] + v[1] + v[2]) * (a / 3.0);
        second += simplex_moment(&v) * (a / 12.0);
    }
    let centroid = if area > 0.0 {
        first / area + reference
    } else {
        reference
    };
    ShellIntegrals {
        area: area as f32,
        centroid: centroid.as_vec3(),
        second_moment: shift_to_origin(second, area, first, reference).as_mat3(),
    }
}

/// The inertia tensor `tr(S)·I − S` of a second moment `S = ∫ x xᵀ dm`.
pub fn inertia_from_second_moment(second_moment: Mat3) -> Mat3 {
    let trace = second_moment.x_axis.x + second_moment.y_axis.y + second_moment.z_axis.z;
    Mat3::from_diagonal(Vec3::splat(trace)) - second_moment
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis-aligned box as 12 outward-wound triangles.
    fn cuboid(half: Vec3, offset: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let mut v = Vec::new();
        for i in 0..8u32 {
            let s = Vec3::new(
                if i & 1 == 0 { -1.0 } else { 1.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { -1.0 } else { 1.0 },
            );
            v.push(s * half + offset);
        }
        let t = vec![
            [0, 2, 3],
            [0, 3, 1], // -z
            [4, 5, 7],
            [4, 7, 6], // +z
            [0, 1, 5],
            [0, 5, 4], // -y
            [2, 6, 7],
            [2, 7, 3], // +y
            [0, 4, 6],
            [0, 6, 2], // -x
            [1, 3, 7],
            [1, 7, 5], // +x
        ];
        (v, t)
    }

    #[test]
    fn box_volume_centroid_and_inertia_match_closed_forms() {
        let half = Vec3::new(0.5, 1.0, 1.5);
        let offset = Vec3::new(3.0, -2.0, 1.0);
        let (v, t) = cuboid(half, offset);
        let s = solid_integrals(&v, &t);
        assert!((s.volume - 6.0).abs() < 1e-5, "{}", s.volume);
        assert!(s.centroid.distance(offset) < 1e-5);
        // Inertia about the centroid: m/12 (b² + c²) with full edge lengths.
        let about_origin = inertia_from_second_moment(s.second_moment);
        let shift = s.volume * (offset.length_squared() * Mat3::IDENTITY - outer_f32(offset));
        let i = about_origin - shift;
        let (a, b, c) = (1.0f32, 2.0, 3.0);
        let expected = Vec3::new(b * b + c * c, a * a + c * c, a * a + b * b) * (6.0 / 12.0);
        assert!((i.x_axis.x - expected.x).abs() < 1e-3, "{i}");
        assert!((i.y_axis.y - expected.y).abs() < 1e-3, "{i}");
        assert!((i.z_axis.z - expected.z).abs() < 1e-3, "{i}");
        assert!(i.x_axis.y.abs() < 1e-3 && i.x_axis.z.abs() < 1e-3 && i.y_axis.z.abs() < 1e-3);
    }

    fn outer_f32(a: Vec3) -> Mat3 {
        Mat3::from_cols(a * a.x, a * a.y, a * a.z)
    }

    #[test]
    fn inverted_winding_gives_negative_volume() {
        let (v, mut t) = cuboid(Vec3::ONE, Vec3::ZERO);
        for tri in &mut t {
            tri.swap(1, 2);
        }
        assert!((solid_integrals(&v, &t).volume + 8.0).abs() < 1e-5);
    }

    #[test]
    fn box_shell_area_and_second_moment() {
        let (v, t) = cuboid(Vec3::splat(0.5), Vec3::ZERO);
        let s = shell_integrals(&v, &t);
        assert!((s.area - 6.0).abs() < 1e-5);
        assert!(s.centroid.length() < 1e-6);
        // Thin-shell cube of side 1, unit areal density: I = 5/18 · m · a² per axis... with
        // m = 6: each axis gets 2 faces ⟂ (a²/6 each · 1) + 4 faces ∥ (a²/12 + a²/4 each).
        let i = inertia_from_second_moment(s.second_moment);
        let expected = 2.0 * (1.0 / 6.0) + 4.0 * (1.0 / 12.0 + 0.25);
        assert!(
            (i.x_axis.x - expected).abs() < 1e-4,
            "{} vs {expected}",
            i.x_axis.x
        );
    }

    #[test]
    fn degenerate_triangles_are_skipped() {
        let (v, mut t) = cuboid(Vec3::ONE, Vec3::ZERO);
        t.push([0, 0, 1]);
        let s = solid_integrals(&v, &t);
        assert!((s.volume - 8.0).abs() < 1e-5);
    }
}
