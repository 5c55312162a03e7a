//! Sphere-tree fitting from a closed triangle mesh, in the layout of the
//! original report's Figure 2: a root that bounds everything, and leaves along
//! the mesh's principal axis — a large head sphere at one end, a thin neck
//! sphere at the other, and fillers between (five leaves by default).
//!
//! How: the axis is the principal axis of the surface (PCA of its
//! area-weighted covariance) through the surface centroid. The axis range is
//! cut into one slab per leaf and each leaf is the smallest sphere centred on
//! the axis that holds the part of the surface inside its slab, exactly (see
//! `axial_cover`). The cuts are moved to make the union of the leaves as small
//! as possible. Coverage is then measured on surface samples drawn with a
//! fixed seed, and tightness is the exact union volume over the mesh volume.
//!
//! A flat mesh (a foil balloon, at most half as thick as wide) is fitted
//! over its mid-plane instead (`fit_flat_sphere_tree`, `planar_cover`):
//! along an axis its middle spheres would span its width.
//!
//! Pure and deterministic: the same mesh and options give the same tree.

pub mod axial_cover;
pub mod coverage;
pub mod mesh_check;
pub mod mesh_integrals;
mod planar_capped;
pub mod planar_cover;
mod planar_excess;
mod planar_surface;
pub mod principal_axis;
pub mod union_volume;

use glam::Vec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::shape::sphere::Sphere;
use crate::shape::sphere_tree::{SphereTree, SphereTreeError};
use crate::shape::trimesh::TriMesh;
use axial_cover::{fit_axial_spheres, AxialSurface};
pub use coverage::COVERAGE_TOLERANCE_M;
pub use mesh_check::{check_closed, MeshCheck, MeshCheckError};

/// Leaves of the report's Figure 2: head, neck and three fillers.
pub const DEFAULT_LEAVES: usize = 5;
/// Most leaves a fit may ask for.
pub const MAX_LEAVES: usize = 64;

/// What to fit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitOptions {
    /// Number of leaf spheres, 1..=64; default 5 (head + neck + 3 fillers).
    pub leaves: usize,
    /// Random surface points used to measure coverage (the vertices are always
    /// used too); default 20 000.
    pub coverage_samples: usize,
    /// Seed for those points; default 1.
    pub seed: u64,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            leaves: DEFAULT_LEAVES,
            coverage_samples: 20_000,
            seed: 1,
        }
    }
}

impl FitOptions {
    pub fn with_leaves(leaves: usize) -> Self {
        Self {
            leaves,
            ..Self::default()
        }
    }
}

/// The part a leaf plays in the Figure 2 layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LeafRole {
    /// The sphere at the broad end of the axis (the balloon's head).
    Head,
    /// A sphere between head and neck.
    Filler,
    /// The sphere at the narrow end (the balloon's neck and knot).
    Neck,
}

/// A fitted tree and how good it is.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitReport {
    /// Root first, then the leaves from the head end to the neck end; mesh frame.
    pub tree: SphereTree,
    /// Share of surface sample points inside some leaf within 1 mm, 0..=1 (target 1).
    pub coverage: f32,
    /// m: the farthest any sample point lies outside every leaf.
    pub max_uncovered_distance_m: f32,
    /// Union volume of the leaves ÷ mesh volume (≥ about 1; lower is tighter).
    pub tightness: f32,
    /// Role of each leaf, in the order of `tree.leaves()`.
    pub roles: Vec<LeafRole>,
    /// Unit axis the leaves sit on, mesh frame, pointing from the neck end to the head end.
    pub axis: Vec3,
    /// m³ enclosed by the mesh (absolute value).
    pub mesh_volume_m3: f32,
    /// m³ of the union of the leaves.
    pub union_volume_m3: f32,
    /// Surface points the coverage was measured on.
    pub samples: usize,
}

#[derive(Debug, Error, PartialEq)]
pub enum FitError {
    #[error("cannot fit spheres: {0}")]
    Mesh(#[from] MeshCheckError),
    #[error("leaves: expected 1 to {MAX_LEAVES}, got {0}")]
    BadLeafCount(usize),
    #[error("cannot fit spheres: the mesh encloses no volume ({volume} m³)")]
    NoVolume { volume: f32 },
    #[error("the fitted tree is invalid: {0}")]
    Tree(#[from] SphereTreeError),
}

/// The checks every fit starts with (a leaf count in range, a closed mesh,
/// a volume that is a number and not vanishing against the mesh's size),
/// and the mesh's solid integrals with its volume and largest extent.
fn checked_solid(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    options: &FitOptions,
) -> Result<(mesh_integrals::SolidIntegrals, f32, f32), FitError> {
    if !(1..=MAX_LEAVES).contains(&options.leaves) {
        return Err(FitError::BadLeafCount(options.leaves));
    }
    check_closed(vertices, triangles)?;
    let solid = mesh_integrals::solid_integrals(vertices, triangles);
    let extent = crate::Aabb::from_points(vertices).extents().max_element();
    let mesh_volume = solid.volume.abs();
    // Also catches a NaN volume.
    if mesh_volume.is_nan() || mesh_volume <= 1e-9 * extent * extent * extent {
        return Err(FitError::NoVolume {
            volume: solid.volume,
        });
    }
    Ok((solid, mesh_volume, extent))
}

/// Fits a sphere tree to a closed, consistently wound triangle mesh.
pub fn fit_sphere_tree(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    let (solid, mesh_volume, extent) = checked_solid(vertices, triangles, options)?;
    let shell = mesh_integrals::shell_integrals(vertices, triangles);
    let covariance = principal_axis::covariance(shell.second_moment, shell.area, shell.centroid);
    let axis = principal_axis::principal_axis(covariance);
    let origin = shell.centroid;
    // Point the axis at the broad end (the head): the end the enclosed volume
    // leans towards.
    let surface = AxialSurface::new(vertices, triangles, origin, axis);
    let (t0, t1) = surface.t_range();
    let lean = (solid.centroid - origin).dot(axis);
    let (surface, axis) = if f64::from(lean) < 0.5 * (t0 + t1) - 1e-9 * (t1 - t0) {
        (AxialSurface::new(vertices, triangles, origin, -axis), -axis)
    } else {
        (surface, axis)
    };
    // The fitter puts the head last (high end); the tree lists it first.
    let mut spheres = fit_axial_spheres(&surface, options.leaves);
    spheres.reverse();
    // A hair of margin so the f32 spheres still hold what the f64 ones did.
    let margin = f64::from(extent) * 2e-6 + 1e-7;
    for s in &mut spheres {
        s.radius += margin;
    }
    let leaves: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere::new(origin + axis * s.t as f32, s.radius as f32))
        .collect();
    let low = spheres
        .iter()
        .map(|s| s.t - s.radius)
        .fold(f64::INFINITY, f64::min);
    let high = spheres
        .iter()
        .map(|s| s.t + s.radius)
        .fold(f64::NEG_INFINITY, f64::max);
    let root_t = 0.5 * (low + high);
    let root = Sphere::new(
        origin + axis * root_t as f32,
        (0.5 * (high - low) + margin) as f32,
    );
    let tree = SphereTree::from_root_and_leaves(root, &leaves)?;

    let roles = (0..leaves.len())
        .map(|i| match i {
            0 => LeafRole::Head,
            i if i + 1 == leaves.len() => LeafRole::Neck,
            _ => LeafRole::Filler,
        })
        .collect();
    let samples =
        coverage::surface_samples(vertices, triangles, options.coverage_samples, options.seed);
    let measured = coverage::measure_coverage(&samples, &leaves);
    let union_volume = union_volume::union_volume_on_axis(&spheres) as f32;
    Ok(FitReport {
        tree,
        coverage: measured.covered,
        max_uncovered_distance_m: measured.max_uncovered_distance,
        tightness: union_volume / mesh_volume,
        roles,
        axis,
        mesh_volume_m3: mesh_volume,
        union_volume_m3: union_volume,
        samples: measured.samples,
    })
}

/// A surface at most this thick (across its plane of least spread, over its
/// largest extent in that plane) is flat: `fit_sphere_tree_auto` lays its
/// spheres over the plane. A foil pillow is 0.27, a latex balloon 1.4.
pub const FLAT_THINNESS: f32 = 0.5;

/// The fitter a mesh's shape calls for: spheres over the mid-surface
/// (`fit_flat_sphere_tree`) for a flat one, along the axis otherwise.
pub fn fit_sphere_tree_auto(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    check_closed(vertices, triangles)?;
    let shell = mesh_integrals::shell_integrals(vertices, triangles);
    let (_, thinness) =
        planar_cover::plane_of(vertices, shell.area, shell.centroid, shell.second_moment);
    if thinness <= FLAT_THINNESS {
        fit_flat_sphere_tree(vertices, triangles, options)
    } else {
        fit_sphere_tree(vertices, triangles, options)
    }
}

/// Fits a sphere tree to a closed flat mesh with every leaf centred on its
/// mid-plane (see `planar_cover`); `axis` in the report is the plane's
/// normal and every leaf a filler.
pub fn fit_flat_sphere_tree(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    let (_, mesh_volume, extent) = checked_solid(vertices, triangles, options)?;
    let shell = mesh_integrals::shell_integrals(vertices, triangles);
    let (frame, _) =
        planar_cover::plane_of(vertices, shell.area, shell.centroid, shell.second_moment);
    let mut spheres = planar_cover::fit_planar_spheres(vertices, triangles, &frame, options.leaves);
    let margin = f64::from(extent) * 2e-6 + 1e-7;
    for s in &mut spheres {
        s.radius += margin;
    }
    let leaves: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere::new(frame.point(s.center), s.radius as f32))
        .collect();
    // Root: around the leaves' bounding box centre, holding every leaf.
    let (lo, hi) = leaves.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), s| (lo.min(s.center - s.radius), hi.max(s.center + s.radius)),
    );
    let centre = 0.5 * (lo + hi);
    let reach = leaves
        .iter()
        .map(|s| s.center.distance(centre) + s.radius)
        .fold(0.0f32, f32::max);
    let root = Sphere::new(centre, reach * (1.0 + 1e-6) + margin as f32);
    let tree = SphereTree::from_root_and_leaves(root, &leaves)?;
    let samples =
        coverage::surface_samples(vertices, triangles, options.coverage_samples, options.seed);
    let measured = coverage::measure_coverage(&samples, &leaves);
    let union_volume = planar_cover::union_volume_on_plane(&spheres, 256) as f32;
    Ok(FitReport {
        tree,
        coverage: measured.covered,
        max_uncovered_distance_m: measured.max_uncovered_distance,
        tightness: union_volume / mesh_volume,
        roles: vec![LeafRole::Filler; leaves.len()],
        axis: frame.normal,
        mesh_volume_m3: mesh_volume,
        union_volume_m3: union_volume,
        samples: measured.samples,
    })
}

/// `fit_sphere_tree` on a `TriMesh`'s vertices and triangles.
pub fn fit_sphere_tree_to_trimesh(
    mesh: &TriMesh,
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    fit_sphere_tree(mesh.vertices(), mesh.triangles(), options)
}

#[cfg(test)]
mod tests;
