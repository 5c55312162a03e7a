//! Where a balloon's surface comes from: the kind's own (the latex balloon,
//! the foil pillow), a foil outline (heart, star, digit, disc), or a closed
//! mesh of one's own; and which sphere fitter suits it.
//!
//! A mesh of one's own is taken as it is, in metres with +Y up, its knot at
//! its lowest point or where given; it is refused, with what is wrong, when
//! it is open, not manifold, wound inconsistently or inside out (it encloses
//! a negative volume), when it encloses (almost) nothing, or when a vertex
//! is not a finite number.

use glam::Vec3;
use thiserror::Error;
use up_geom::fit::check_closed;
use up_geom::fit::mesh_integrals::solid_integrals;
use up_geom::fit::planar_cover::plane_of;
use up_geom::fit::{
    fit_flat_sphere_tree, fit_sphere_tree, FitError, FitOptions, FitReport, FLAT_THINNESS,
};

use crate::balloon::mesh::{vertex_normals, BalloonDimensions, BalloonMesh};
use crate::balloon::outline::OutlineKind;

/// Leaves of a flat shape's tree: spread over its face, fewer leave each one
/// far thicker than the shape where it sits (`planar_cover`; the 18″
/// pillow is 1.32 with 64).
pub const FLAT_LEAVES: usize = 64;

/// Radius of a custom mesh's knot ball (its mass's place), in units of the
/// mesh's largest extent.
const CUSTOM_KNOT_RADIUS: f32 = 0.02;

/// The surface of a balloon model.
#[derive(Clone, Debug, PartialEq)]
pub enum BalloonSurface {
    /// The kind's own: the latex balloon or the foil pillow (`foil_mesh`).
    Standard,
    /// A foil balloon cut in this outline (`foil_shape`), sized by the spec's
    /// `diameter_m` taken as its height as sold.
    FoilOutline(OutlineKind),
    /// A closed mesh (`custom_mesh`), with the name errors give it.
    Custom { name: String, mesh: BalloonMesh },
}

/// Why a mesh of one's own cannot be a balloon; each names the file.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CustomMeshError {
    #[error("{name}: {problem}")]
    Bad { name: String, problem: String },
}

/// Whether a mesh is flat enough for spheres over its mid-surface.
pub fn is_flat(positions: &[Vec3], indices: &[[u32; 3]]) -> bool {
    let shell = up_geom::fit::mesh_integrals::shell_integrals(positions, indices);
    let (_, thinness) = plane_of(positions, shell.area, shell.centroid, shell.second_moment);
    thinness <= FLAT_THINNESS
}

/// The sphere tree of a balloon: over the mid-surface with `FLAT_LEAVES`
/// leaves when `flat`, else along the axis with `leaves`. `up fit-spheres`
/// fits a mesh with this (and `is_flat`), as a scene's `mesh` is fitted.
pub fn fit_balloon_tree(
    positions: &[Vec3],
    indices: &[[u32; 3]],
    flat: bool,
    leaves: usize,
) -> Result<FitReport, FitError> {
    if flat {
        fit_flat_sphere_tree(positions, indices, &FitOptions::with_leaves(FLAT_LEAVES))
    } else {
        fit_sphere_tree(positions, indices, &FitOptions::with_leaves(leaves))
    }
}

/// A balloon mesh from `vertices` and `triangles` (m, +Y up), its knot at
/// `knot` or at its lowest vertex; `name` (the file) goes into every error.
pub fn custom_mesh(
    name: &str,
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    knot: Option<Vec3>,
) -> Result<BalloonMesh, CustomMeshError> {
    let bad = |problem: String| CustomMeshError::Bad {
        name: name.to_string(),
        problem,
    };
    if let Some(i) = vertices.iter().position(|p| !p.is_finite()) {
        return Err(bad(format!(
            "vertex {} is not a finite point ({}); expected numbers",
            i + 1,
            vertices[i]
        )));
    }
    check_closed(&vertices, &triangles).map_err(|e| bad(e.to_string()))?;
    let volume = solid_integrals(&vertices, &triangles).volume;
    let (lo, hi) = vertices
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(l, h), &p| (l.min(p), h.max(p)));
    let extent = (hi - lo).max_element();
    if volume.is_nan() || volume.abs() <= 1e-6 * extent * extent * extent {
        return Err(bad(format!(
            "degenerate: it encloses {volume} m³ (expected a solid, its faces not all in a plane)"
        )));
    }
    if volume < 0.0 {
        return Err(bad(format!(
            "inside out: its faces wind clockwise seen from outside (it encloses {volume} m³); \
             expected counter-clockwise, outward normals"
        )));
    }
    if let Some(k) = knot.filter(|k| !k.is_finite()) {
        return Err(bad(format!("knot {k} is not a finite point")));
    }
    let radius = CUSTOM_KNOT_RADIUS * extent;
    let tip = knot.unwrap_or_else(|| {
        vertices
            .iter()
            .copied()
            .min_by(|a, b| a.y.total_cmp(&b.y).then(a.x.total_cmp(&b.x)))
            .unwrap_or(Vec3::ZERO)
    });
    let normals = vertex_normals(&vertices, &triangles);
    Ok(BalloonMesh {
        dimensions: BalloonDimensions {
            diameter: (hi.x - lo.x).max(hi.z - lo.z),
            top_y: hi.y,
            neck_top_y: tip.y,
            neck_bottom_y: tip.y,
            knot_center: tip + Vec3::Y * radius,
            knot_radius: radius,
            bottom_y: lo.y,
        },
        positions: vertices,
        normals,
        indices: triangles,
    })
}

/// m²: a custom mesh's frontal area for drag: the ellipse of its horizontal
/// extents (x and z), a fair stand-in for its largest horizontal section.
pub fn custom_frontal_area(mesh: &BalloonMesh) -> f32 {
    let b = up_geom::Aabb::from_points(&mesh.positions).extents();
    std::f32::consts::FRAC_PI_4 * b.x * b.z
}
