//! A foil balloon of any outline (a disc, a heart, a star, a digit): two flat
//! sheets of the outline sealed at the rim and filled.
//!
//! The construction generalises Paulsen's "Mylar balloon" (two discs of
//! radius a, inflated: radius r = a / A, A ≈ 1.31103; half-thickness at the
//! centre B·r, B ≈ 0.59907; volume (2/3)·π·a·r²; physics reference, "Foil
//! shapes"), exact for a disc and a model for the rest:
//!
//! - in its plane the film draws in as it fills (the rim crimps): the
//!   inflated outline is the flat one shrunk by 1/A about its centroid;
//! - across it each face stands off the mid-plane by Paulsen's profile,
//!   `z = w·P(1 − d/w)` with `P(x) = ∫ₓ¹ s²/√(1 − s⁴) ds`, d the point's
//!   distance inside the inflated outline and w the radius of the disc of
//!   the same area (the disc's r), but never more than a round tube as wide
//!   as the outline is where the point lies allows, `√(d (2ρ − d))`, ρ the
//!   radius of the largest disc inside the outline holding the point
//!   (`LocalWidth`): a stroke of a digit fills to a tube, a heart to about
//!   a disc of its area, and a star's narrow arms stay thinner than its
//!   middle, no thicker than they are wide.
//!
//! Mesh: the plane is cut into a grid of `GRID_CELLS` squares across the
//! larger extent, each split into two triangles; each triangle is clipped to
//! the outline (marching triangles: the rim vertices are found on the grid
//! edges by bisection of the distance, so the rim follows the outline) and
//! lifted to ±z, the two faces sharing their rim vertices. Closed,
//! watertight, wound outward, with smooth normals.
//!
//! Body frame as the pillow's: origin at the inflated outline's centroid on
//! the mid-plane, +Y up, faces towards ±Z; the valve on the outline's lower
//! edge below the centre of buoyancy, or where it balances the film's
//! weight (`foil_shape_balanced`), where the ribbon ties.

use std::collections::HashMap;

use glam::{Vec2, Vec3};

use up_geom::fit::mesh_integrals::{shell_integrals, solid_integrals};

use crate::balloon::local_width::LocalWidth;
use crate::balloon::mesh::{vertex_normals, BalloonDimensions, BalloonMesh, BalloonMeshError};
use crate::balloon::outline::{Outline, OutlineKind};

/// Paulsen's A: a flat disc's radius over its inflated radius.
pub const PAULSEN_A: f32 = 1.311_03;
/// Paulsen's B: the inflated half-thickness at the centre over its radius.
pub const PAULSEN_B: f32 = 0.599_07;
/// Grid squares across the larger extent of the outline.
pub const GRID_CELLS: usize = 96;
/// Radius of the valve's ball (its mass's place), in units of the height.
const VALVE_RADIUS: f32 = 0.015;

/// Paulsen's profile: the half-thickness of an inflated disc of radius 1 at
/// distance `x` (0..=1) from its centre; `P(0) = B`. With s = 1 − u² the
/// integrand has no singularity at the rim: Simpson's rule in u.
pub fn paulsen_profile(x: f64) -> f64 {
    let top = (1.0 - x.clamp(0.0, 1.0)).sqrt();
    let f = |u: f64| {
        let s = 1.0 - u * u;
        2.0 * s * s / ((1.0 + s) * (1.0 + s * s)).sqrt()
    };
    let n = 48;
    let h = top / n as f64;
    let mut sum = f(0.0) + f(top);
    for i in 1..n {
        sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// A foil balloon's mesh and what its outline gives besides.
#[derive(Clone, Debug)]
pub struct FoilShape {
    pub mesh: BalloonMesh,
    /// m²: one flat sheet as cut (the film is two of them).
    pub sheet_area_m2: f32,
    /// m²: the largest section across the vertical, for drag.
    pub frontal_area_m2: f32,
}

/// The inflated outline: signed distance (positive inside) and the profile.
struct Inflated {
    flat: Outline,
    /// The flat outline's centroid, m (the body frame's origin maps to it).
    flat_centroid: Vec2,
    /// Shrink from flat to inflated: 1/A.
    shrink: f32,
    /// m: the largest distance inside the inflated outline.
    reach: f32,
    /// m: the radius of the disc of the inflated outline's area.
    area_radius: f32,
}

impl Inflated {
    fn distance(&self, p: Vec2) -> f32 {
        self.shrink * self.flat.distance(self.flat_centroid + p / self.shrink)
    }

    /// Paulsen's profile of the disc of the same area at distance `d`
    /// inside, no thicker than a tube as wide as the outline is there (the
    /// largest disc inside holding the point has radius `local`): a disc is
    /// Paulsen's balloon, a stroke of a digit a tube.
    fn half_thickness(&self, d: f32, local: f32) -> f32 {
        if d <= 0.0 {
            return 0.0;
        }
        let (d, w) = (f64::from(d), f64::from(self.area_radius));
        // Never narrower than the point's own distance (a width read between
        // nodes next to the rim mixes in the outside's 0).
        let local = f64::from(local).max(d);
        let tube = (d * (2.0 * local - d)).max(0.0).sqrt();
        (w * paulsen_profile(1.0 - d / w)).min(tube) as f32
    }
}

/// The foil balloon of outline `kind`, `size_m` tall as sold (flat; the
/// disc's diameter), its valve on the lower edge straight below the centre
/// of buoyancy (`foil_shape_balanced` with a weightless film).
pub fn foil_shape(kind: OutlineKind, size_m: f32) -> Result<FoilShape, BalloonMeshError> {
    foil_shape_balanced(kind, size_m, 0.0)
}

/// `foil_shape` with the valve where the balloon hangs upright: a film
/// `film_per_valve` times as heavy as the valve (the 18″ heart's 8 g film
/// on its 1 g valve: 8) has its centre where the surface's is, which on an
/// outline without a mirror line (a "3", a "7") lies to one side of the
/// centre of buoyancy; the valve goes as far to the other side as puts the
/// whole mass straight below the centre of buoyancy, as number balloons
/// are made to hang. It stays on the bottom of the outline (`valve_point`):
/// the nearest such place when the balance point is off it.
pub fn foil_shape_balanced(
    kind: OutlineKind,
    size_m: f32,
    film_per_valve: f32,
) -> Result<FoilShape, BalloonMeshError> {
    if !(size_m.is_finite() && size_m > 0.0) {
        return Err(BalloonMeshError::BadDiameter(size_m));
    }
    let flat = Outline::new(kind, size_m);
    let (lo, hi) = flat.bounds();
    let (sheet_area_m2, flat_centroid) = flat_sheet(&flat);
    let mut inflated = Inflated {
        flat,
        flat_centroid,
        shrink: 1.0 / PAULSEN_A,
        reach: 0.0,
        area_radius: (sheet_area_m2 / std::f32::consts::PI).sqrt() / PAULSEN_A,
    };
    let (lo, hi) = (
        (lo - flat_centroid) * inflated.shrink,
        (hi - flat_centroid) * inflated.shrink,
    );
    let g = (hi - lo).max_element() / GRID_CELLS as f32;
    // Grid nodes at whole multiples of g: the origin is one.
    let (i0, j0) = ((lo.x / g).floor() as i32 - 1, (lo.y / g).floor() as i32 - 1);
    let (i1, j1) = ((hi.x / g).ceil() as i32 + 1, (hi.y / g).ceil() as i32 + 1);
    let (nx, ny) = ((i1 - i0 + 1) as usize, (j1 - j0 + 1) as usize);
    let node = |i: usize, j: usize| Vec2::new((i0 + i as i32) as f32, (j0 + j as i32) as f32) * g;
    let mut d = vec![0.0f32; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            d[j * nx + i] = inflated.distance(node(i, j));
        }
    }
    inflated.reach = deepest(&inflated, &d, nx, &node, g);
    inflated.area_radius = inflated.area_radius.max(inflated.reach);
    let width = LocalWidth::from_distances(&d, nx, node(0, 0), g, inflated.reach);
    let eps = 1e-6 * g;
    let inside = |k: usize| d[k] > eps;

    let mut positions: Vec<Vec3> = Vec::new();
    let mut top: HashMap<usize, u32> = HashMap::new();
    let mut bottom: HashMap<usize, u32> = HashMap::new();
    let mut rim: HashMap<(usize, usize), u32> = HashMap::new();
    let mut indices: Vec<[u32; 3]> = Vec::new();
    let at = |k: usize| node(k % nx, k / nx);
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let k = j * nx + i;
            for tri in [[k, k + 1, k + nx + 1], [k, k + nx + 1, k + nx]] {
                let flags = tri.map(inside);
                let count = flags.iter().filter(|&&f| f).count();
                if count == 0 {
                    continue;
                }
                // Rotate (keeping the winding) so the pattern is canonical:
                // one inside → it first; two → the outside one last.
                let r = (0..3)
                    .find(|&r| match count {
                        1 => flags[r],
                        2 => !flags[(r + 2) % 3],
                        _ => r == 0,
                    })
                    .unwrap_or(0);
                let [a, b, c] = [tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]];
                // Polygon in the plane, counter-clockwise: node or rim points.
                let polygon: Vec<Corner> = match count {
                    3 => vec![Corner::Node(a), Corner::Node(b), Corner::Node(c)],
                    2 => vec![
                        Corner::Node(a),
                        Corner::Node(b),
                        Corner::Rim(b, c),
                        Corner::Rim(a, c),
                    ],
                    _ => vec![Corner::Node(a), Corner::Rim(a, b), Corner::Rim(a, c)],
                };
                for side in [1.0f32, -1.0] {
                    let ids: Vec<u32> = polygon
                        .iter()
                        .map(|corner| match *corner {
                            Corner::Node(n) => {
                                let map = if side > 0.0 { &mut top } else { &mut bottom };
                                *map.entry(n).or_insert_with(|| {
                                    let p = at(n);
                                    let z = inflated.half_thickness(d[n], width.at_node(n));
                                    positions.push(Vec3::new(p.x, p.y, side * z));
                                    positions.len() as u32 - 1
                                })
                            }
                            Corner::Rim(inner, outer) => {
                                *rim.entry((inner, outer)).or_insert_with(|| {
                                    let p = rim_point(&inflated, at(inner), at(outer));
                                    positions.push(p.extend(0.0));
                                    positions.len() as u32 - 1
                                })
                            }
                        })
                        .collect();
                    for t in 1..ids.len() - 1 {
                        indices.push(if side > 0.0 {
                            [ids[0], ids[t], ids[t + 1]]
                        } else {
                            [ids[0], ids[t + 1], ids[t]]
                        });
                    }
                }
            }
        }
    }
    let normals = vertex_normals(&positions, &indices);

    let solid = solid_integrals(&positions, &indices);
    let shell = shell_integrals(&positions, &indices);
    let ratio = if film_per_valve.is_finite() {
        film_per_valve.max(0.0)
    } else {
        0.0
    };
    let balance_x = solid.centroid.x - ratio * (shell.centroid.x - solid.centroid.x);
    let valve = valve_point(&inflated, lo, hi, balance_x, solid.centroid.y);
    let valve_radius = VALVE_RADIUS * size_m;
    let (mlo, mhi) = positions
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(l, h), &p| (l.min(p), h.max(p)));
    let dimensions = BalloonDimensions {
        diameter: (mhi.x - mlo.x).max(mhi.y - mlo.y),
        top_y: mhi.y,
        neck_top_y: valve.y,
        neck_bottom_y: valve.y,
        knot_center: Vec3::new(valve.x, valve.y + valve_radius, 0.0),
        knot_radius: valve_radius,
        bottom_y: mlo.y,
    };
    let frontal_area_m2 = frontal_area(&inflated, &width, lo.x, hi.x);
    Ok(FoilShape {
        mesh: BalloonMesh {
            positions,
            normals,
            indices,
            dimensions,
        },
        sheet_area_m2,
        frontal_area_m2,
    })
}

/// m² and centroid of one flat sheet, on a grid 4 × `GRID_CELLS` across.
fn flat_sheet(flat: &Outline) -> (f32, Vec2) {
    let (lo, hi) = flat.bounds();
    let n = 4 * GRID_CELLS;
    let step = (hi - lo).max_element() / n as f32;
    let (mut area, mut moment) = (0.0f64, glam::DVec2::ZERO);
    for i in 0..n {
        for j in 0..n {
            let p = lo + Vec2::new(i as f32 + 0.5, j as f32 + 0.5) * step;
            if p.x <= hi.x && p.y <= hi.y && flat.distance(p) > 0.0 {
                area += 1.0;
                moment += p.as_dvec2();
            }
        }
    }
    (
        (area * f64::from(step * step)) as f32,
        (moment / area.max(1.0)).as_vec2(),
    )
}

/// m²: one flat sheet of outline `kind` at `size_m` (the film is two).
pub fn sheet_area_m2(kind: OutlineKind, size_m: f32) -> f32 {
    flat_sheet(&Outline::new(kind, size_m)).0
}

enum Corner {
    Node(usize),
    /// On the grid edge from an inside node to an outside one.
    Rim(usize, usize),
}

/// The largest distance inside the outline: the best grid node, then a
/// pattern search around it.
fn deepest(
    shape: &Inflated,
    d: &[f32],
    nx: usize,
    node: &dyn Fn(usize, usize) -> Vec2,
    g: f32,
) -> f32 {
    let (k, mut best) =
        d.iter().enumerate().fold(
            (0, f32::NEG_INFINITY),
            |b, (k, &v)| if v > b.1 { (k, v) } else { b },
        );
    let mut p = node(k % nx, k / nx);
    let mut h = 0.5 * g;
    while h > 1e-4 * g {
        let mut moved = false;
        for dir in [Vec2::X, Vec2::NEG_X, Vec2::Y, Vec2::NEG_Y] {
            let v = shape.distance(p + dir * h);
            if v > best {
                (best, p, moved) = (v, p + dir * h, true);
            }
        }
        if !moved {
            h *= 0.5;
        }
    }
    best
}

/// Where the outline crosses the segment from `inner` (inside) to `outer`.
fn rim_point(shape: &Inflated, inner: Vec2, outer: Vec2) -> Vec2 {
    let (mut a, mut b) = (0.0f32, 1.0f32);
    for _ in 0..30 {
        let m = 0.5 * (a + b);
        if shape.distance(inner.lerp(outer, m)) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    inner.lerp(outer, (0.5 * (a + b)).clamp(1e-3, 1.0 - 1e-3))
}

/// Where the vertical at `x` first meets the outline going up from `lo.y`.
fn lower_edge(shape: &Inflated, x: f32, lo: Vec2, hi: Vec2) -> Option<Vec2> {
    let steps = 4 * GRID_CELLS;
    let h = (hi.y - lo.y) / steps as f32;
    (0..steps).find_map(|i| {
        let (below, above) = (
            Vec2::new(x, lo.y + i as f32 * h),
            Vec2::new(x, lo.y + (i + 1) as f32 * h),
        );
        (shape.distance(above) > 0.0).then(|| rim_point(shape, above, below))
    })
}

/// The valve: on the lower edge of the outline at the `x` nearest `target`
/// where that edge lies well below the centre of buoyancy (at `centre_y`):
/// at least half as far below it as the outline's lowest point, so a "7"
/// keeps it under its stem, not under its bar, and a star between its two
/// lower points.
fn valve_point(shape: &Inflated, lo: Vec2, hi: Vec2, target: f32, centre_y: f32) -> Vec2 {
    let n = 4 * GRID_CELLS;
    let edges: Vec<Vec2> = (0..=n)
        .filter_map(|i| lower_edge(shape, lo.x + (hi.x - lo.x) * i as f32 / n as f32, lo, hi))
        .collect();
    let bottom = edges.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
    let deep = centre_y - 0.5 * (centre_y - bottom);
    let nearest = edges
        .iter()
        .filter(|p| p.y <= deep)
        .min_by(|a, b| (a.x - target).abs().total_cmp(&(b.x - target).abs()))
        .copied()
        .unwrap_or(Vec2::new(0.0, lo.y));
    // On the sampled edge the best x is within a sample of `target`: the
    // edge at `target` itself where that is deep enough too.
    lower_edge(shape, target, lo, hi)
        .filter(|p| p.y <= deep && (p.x - nearest.x).abs() <= (hi.x - lo.x) / n as f32)
        .unwrap_or(nearest)
}

/// m²: the largest section by a horizontal plane, `∫ 2 z dx` along rows.
fn frontal_area(shape: &Inflated, width: &LocalWidth, x0: f32, x1: f32) -> f32 {
    let n = 4 * GRID_CELLS;
    let dx = (x1 - x0) / n as f32;
    (-8..=8)
        .map(|row| {
            let y = row as f32 * 0.1 * shape.reach;
            (0..n)
                .map(|i| {
                    let p = Vec2::new(x0 + (i as f32 + 0.5) * dx, y);
                    2.0 * shape.half_thickness(shape.distance(p), width.at(p)) * dx
                })
                .sum::<f32>()
        })
        .fold(0.0, f32::max)
}

#[cfg(test)]
#[path = "foil_shape_tests.rs"]
mod tests;
