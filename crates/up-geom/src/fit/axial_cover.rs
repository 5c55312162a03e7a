//! Covering a surface with spheres centred on one axis.
//!
//! Design. Project the surface onto the axis: a point becomes `(t, d)`, its
//! position along the axis and its distance from it. A sphere centred on the
//! axis at `c` with radius `r` holds the point exactly when
//! `(t − c)² + d² ≤ r²`, so covering the surface is a 2-D problem in the
//! `(t, d)` half-plane, whatever the mesh looks like around the axis.
//!
//! The axis range is cut into consecutive slabs, one sphere per slab. The part
//! of the surface inside a slab is a set of convex polygons (triangles clipped
//! by two planes) whose corners are mesh vertices inside the slab or points
//! where an edge crosses one of the two planes. A sphere is convex, so holding
//! those corners means holding the whole piece: the cover is exact for every
//! point of the surface, not only for samples. For each slab the centre that
//! needs the smallest radius minimises a convex function (a maximum of
//! parabolas in `c`): golden-section search.
//!
//! The slab boundaries are then moved to minimise the volume of the union of
//! the spheres (computed exactly, see `union_volume`) by coordinate descent
//! (a coarse scan then a golden-section refinement per boundary), from a few
//! deterministic starting cuts; the best result wins. One constraint keeps the
//! report's layout: the sphere at the high end of the axis (the head) is the
//! largest. Without it the optimum for a balloon puts a small cap on top and
//! the big sphere lower down, which is tighter but no longer head/fillers/neck.

use glam::{DVec3, Vec3};

use super::union_volume::union_volume_on_axis;

/// A sphere centred on the axis: position `t` along it and radius, metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxialSphere {
    pub t: f64,
    pub radius: f64,
}

/// The surface projected onto the axis.
pub struct AxialSurface {
    /// Vertex positions along the axis, sorted, with their squared distance
    /// from the axis (same order).
    t: Vec<f64>,
    d2: Vec<f64>,
    /// Edges that span a range of `t`: (t_low, t_high, radial offset at the
    /// low end, radial offset at the high end).
    edges: Vec<(f64, f64, DVec3, DVec3)>,
}

const GOLDEN: f64 = 0.618_033_988_749_894_8;

impl AxialSurface {
    /// `origin` is a point on the axis, `axis` a unit vector.
    pub fn new(vertices: &[Vec3], triangles: &[[u32; 3]], origin: Vec3, axis: Vec3) -> Self {
        let (origin, axis) = (origin.as_dvec3(), axis.as_dvec3());
        let project = |p: Vec3| {
            let rel = p.as_dvec3() - origin;
            let t = rel.dot(axis);
            (t, rel - axis * t)
        };
        let projected: Vec<(f64, DVec3)> = vertices.iter().map(|&p| project(p)).collect();
        let mut used = vec![false; vertices.len()];
        let mut edge_keys: Vec<(u32, u32)> = Vec::with_capacity(triangles.len() * 3);
        for tri in triangles {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                used[a as usize] = true;
                if a != b {
                    edge_keys.push((a.min(b), a.max(b)));
                }
            }
        }
        edge_keys.sort_unstable();
        edge_keys.dedup();
        let mut points: Vec<(f64, f64)> = projected
            .iter()
            .zip(&used)
            .filter(|(_, &u)| u)
            .map(|(&(t, q), _)| (t, q.length_squared()))
            .collect();
        points.sort_by(|x, y| x.0.total_cmp(&y.0).then(y.1.total_cmp(&x.1)));
        // Several vertices at the same t (a ring of a surface of revolution):
        // only the farthest from the axis matters.
        points.dedup_by(|later, earlier| later.0 == earlier.0);
        let edges = edge_keys
            .iter()
            .filter_map(|&(a, b)| {
                let (pa, pb) = (projected[a as usize], projected[b as usize]);
                match pa.0.total_cmp(&pb.0) {
                    std::cmp::Ordering::Less => Some((pa.0, pb.0, pa.1, pb.1)),
                    std::cmp::Ordering::Greater => Some((pb.0, pa.0, pb.1, pa.1)),
                    std::cmp::Ordering::Equal => None,
                }
            })
            .collect();
        Self {
            t: points.iter().map(|p| p.0).collect(),
            d2: points.iter().map(|p| p.1).collect(),
            edges,
        }
    }

    pub fn t_range(&self) -> (f64, f64) {
        (self.t[0], self.t[self.t.len() - 1])
    }

    /// Largest squared distance from the axis of the surface's cross-section
    /// by the plane at `t` (edges crossing the plane, and vertices on it).
    fn cross_section_d2(&self, t: f64) -> f64 {
        let mut best = 0.0f64;
        for &(lo, hi, qa, qb) in &self.edges {
            if lo < t && t < hi {
                let s = (t - lo) / (hi - lo);
                best = best.max(qa.lerp(qb, s).length_squared());
            }
        }
        best
    }

    /// The smallest sphere on the axis that holds the surface between the
    /// planes at `lo` and `hi` (`lo < hi`).
    pub fn slab_sphere(&self, lo: f64, hi: f64) -> AxialSphere {
        let first = self.t.partition_point(|&t| t < lo);
        let last = self.t.partition_point(|&t| t <= hi);
        let mut pts: Vec<(f64, f64)> = (first..last).map(|i| (self.t[i], self.d2[i])).collect();
        pts.push((lo, self.cross_section_d2(lo)));
        pts.push((hi, self.cross_section_d2(hi)));
        let worst = |c: f64| {
            pts.iter()
                .fold(0.0f64, |m, &(t, d2)| m.max((t - c) * (t - c) + d2))
        };
        let (c, r2) = golden_min(worst, lo, hi, 64);
        AxialSphere {
            t: c,
            radius: r2.sqrt(),
        }
    }
}

/// Spheres for the slabs between consecutive `cuts` (first and last are the ends).
fn spheres_for_cuts(surface: &AxialSurface, cuts: &[f64]) -> Vec<AxialSphere> {
    cuts.windows(2)
        .map(|w| surface.slab_sphere(w[0], w[1]))
        .collect()
}

/// Weight of the root's volume in the objective: a tie-breaker. Small spheres
/// that poke out past the ends of the mesh add almost no union volume, but
/// they make the tree touch things early and inflate the root.
const ROOT_WEIGHT: f64 = 0.05;

/// What the cuts minimise: the union volume of `spheres` plus a little of the
/// root's, or infinity when they break the layout: the last sphere (the head,
/// at the high end of the axis) must be the largest.
fn layout_volume(spheres: &[AxialSphere]) -> f64 {
    let Some((head, rest)) = spheres.split_last() else {
        return 0.0;
    };
    if rest.iter().any(|s| s.radius > head.radius) {
        return f64::INFINITY;
    }
    let low = spheres
        .iter()
        .map(|s| s.t - s.radius)
        .fold(f64::INFINITY, f64::min);
    let high = spheres
        .iter()
        .map(|s| s.t + s.radius)
        .fold(f64::NEG_INFINITY, f64::max);
    let root_radius = 0.5 * (high - low);
    let root_volume = 4.0 / 3.0 * std::f64::consts::PI * root_radius.powi(3);
    union_volume_on_axis(spheres) + ROOT_WEIGHT * root_volume
}

/// Covers the surface with `count` spheres on the axis, minimising the union
/// volume, with the largest sphere (the head) at the high end of the axis.
pub fn fit_axial_spheres(surface: &AxialSurface, count: usize) -> Vec<AxialSphere> {
    let (t0, t1) = surface.t_range();
    let length = t1 - t0;
    if count <= 1 || length <= 0.0 {
        return vec![surface.slab_sphere(t0, t1.max(t0 + f64::EPSILON))];
    }
    // Starting cuts: a head slab of some share of the length at the high end,
    // the rest shared out evenly (fillers, then the neck at the low end).
    let mut best: Option<(f64, Vec<AxialSphere>)> = None;
    for head_share in [0.2, 0.275, 0.35, 0.425, 0.5, 0.575, 0.65] {
        let cuts: Vec<f64> = (0..=count)
            .map(|i| match i {
                i if i == count => t1,
                i => t0 + length * (1.0 - head_share) * i as f64 / (count - 1) as f64,
            })
            .collect();
        let spheres = descend(surface, cuts);
        let volume = layout_volume(&spheres);
        let better = match &best {
            None => true,
            Some((v, _)) => volume < *v,
        };
        if better {
            best = Some((volume, spheres));
        }
    }
    best.map(|(_, s)| s).unwrap_or_default()
}

/// Coordinate descent on the interior cuts.
fn descend(surface: &AxialSurface, mut cuts: Vec<f64>) -> Vec<AxialSphere> {
    let mut spheres = spheres_for_cuts(surface, &cuts);
    let mut volume = layout_volume(&spheres);
    let length = cuts[cuts.len() - 1] - cuts[0];
    for _sweep in 0..40 {
        let before = volume;
        for j in 1..cuts.len() - 1 {
            let (lo, hi) = (cuts[j - 1], cuts[j + 1]);
            let min_gap = length * 1e-4;
            if hi - lo <= 2.0 * min_gap {
                continue;
            }
            let (a, b) = (lo + min_gap, hi - min_gap);
            let mut trial = spheres.clone();
            let mut eval = |cut: f64| {
                trial[j - 1] = surface.slab_sphere(lo, cut);
                trial[j] = surface.slab_sphere(cut, hi);
                layout_volume(&trial)
            };
            // Coarse scan (the volume need not be unimodal in one cut), then refine.
            const SCAN: usize = 12;
            let step = (b - a) / SCAN as f64;
            let mut best_cut = cuts[j];
            let mut best_volume = volume;
            for k in 0..=SCAN {
                let cut = a + step * k as f64;
                let v = eval(cut);
                if v < best_volume {
                    best_volume = v;
                    best_cut = cut;
                }
            }
            let (ga, gb) = ((best_cut - step).max(a), (best_cut + step).min(b));
            let (refined, v) = golden_min(&mut eval, ga, gb, 32);
            if v < best_volume {
                best_volume = v;
                best_cut = refined;
            }
            if best_volume < volume {
                cuts[j] = best_cut;
                spheres[j - 1] = surface.slab_sphere(lo, best_cut);
                spheres[j] = surface.slab_sphere(best_cut, hi);
                volume = best_volume;
            }
        }
        if before.is_finite() && before - volume <= before * 1e-7 {
            break;
        }
    }
    spheres
}

/// Golden-section search for the minimum of `f` on `[a, b]`: returns the
/// best point it evaluated and its value.
fn golden_min(
    mut f: impl FnMut(f64) -> f64,
    mut a: f64,
    mut b: f64,
    iterations: usize,
) -> (f64, f64) {
    let mut x1 = b - GOLDEN * (b - a);
    let mut x2 = a + GOLDEN * (b - a);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..iterations {
        if f1 <= f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - GOLDEN * (b - a);
            f1 = f(x1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + GOLDEN * (b - a);
            f2 = f(x2);
        }
    }
    if f1 <= f2 {
        (x1, f1)
    } else {
        (x2, f2)
    }
}
