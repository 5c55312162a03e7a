//! Covering a flat surface (a foil balloon, a cushion) with spheres centred
//! on its mid-surface, spread over the plane instead of strung along one axis.
//!
//! Design. The plane is the one through the surface centroid across the
//! direction of least spread (the smallest principal axis of the surface's
//! covariance). In that frame a point is `(x, y, z)`, `z` its height off the
//! plane; a sphere centred on the plane at `(cx, cy)` holds it when
//! `(x − cx)² + (y − cy)² + z² ≤ r²`. Each triangle goes to one sphere, which
//! holds its three corners and so, being convex, the whole triangle: the cover
//! is exact for every point of the surface, not only for samples.
//!
//! Where the spheres go: a weighted k-means of the triangles' centres in the
//! plane, the weight the triangle's area times its height squared, so the
//! thick middle gets more, smaller cells than the thin rim (a sphere must be at
//! least as large as the half-thickness where it sits; cells there must be
//! small to keep it near that). Two covers are made from there:
//!
//! - the even one: rounds of each triangle to the sphere that already holds
//!   it with the smallest radius (else the one it grows least), each centre
//!   moved to where its triangles need the least radius (a convex problem:
//!   subgradient steps towards the farthest corner); the spheres come out
//!   about as large as the largest, which `balance` then lowers;
//! - the tight one: rounds of each triangle to the sphere that holds it
//!   with the least radius, each centre moved likewise, the round with the
//!   smallest union kept; placed `PLACEMENTS` times in all, each time with
//!   each triangle's weight scaled by how far its sphere's part of the union
//!   stood outside the mesh (`planar_excess`), so thin parts (a star's
//!   arms) get the cells the broad middle can spare; `balance` last.
//!
//! The tight cover is kept unless its largest sphere stands higher than the
//! even one's (by more than `TOP_SLACK`): the largest spheres set how far two
//! flat shapes rest apart face to face. Where it stands higher (a pillow,
//! whose broad middle is nearly as high as its top), a capped cover is tried
//! and the lower of it and the even one kept. Its caps form a dome (`Dome`):
//! a little over the surface's highest point, dropping half as fast as the
//! surface does, so that the shape lying on a plane rests on the leaves
//! nearest its middle and a tip brings it back, as its curved face would (a
//! plateau of leaves all one height leaves it rocking from leaf to leaf).
//! Its cells are placed as densely as spheres under the caps need them
//! (where the surface stands `z` off the plane a sphere of radius `cap`
//! holds a patch `√(cap² − z²)` across: a few centimetres over a pillow's
//! middle), the triangles, split finer, go to the spheres that stand least
//! past their caps, and the spheres are then shrunk within the worst such
//! overshoot (`planar_capped`; the surface and its finer split are
//! `planar_surface`'s). Fixed starts and sweep orders: the same mesh and
//! count give the same spheres.
//!
//! The union's volume is exact per column across the plane: every centre lies
//! on it, so along a line through the plane the spheres' chords share their
//! middle and the union is the longest chord.

use glam::{DVec2, DVec3, Vec3};

use super::planar_capped::{capped_cover, Dome};
use super::planar_excess::excess_by_leaf;
use super::planar_surface::Surface;
use super::principal_axis::{covariance, symmetric_eigen};

/// Placements of the cells, each weighted by where the last one's union
/// stood out most.
const PLACEMENTS: usize = 4;
/// Rounds of giving triangles to spheres and moving the spheres, per placement.
const ENCLOSING_ROUNDS: usize = 8;
/// Squares across the plane the k-means gathers the triangles into.
const BINS: usize = 64;
/// Rounds of k-means from the farthest-point start.
pub(super) const K_MEANS_ITERATIONS: usize = 40;
/// Columns across the plane when a round's union is weighed (to keep the
/// best round: coarser than the placement's weighing, which steers cells).
const ROUND_COLUMNS: usize = 64;
/// Columns across the plane when a placement's union is weighed.
const EXCESS_COLUMNS: usize = 128;
/// Rounds of the even cover, and of the capped cover's share-out.
pub(super) const EVEN_ROUNDS: usize = 4;
/// How much higher (relatively) the tight cover's largest sphere may stand
/// than the even cover's.
const TOP_SLACK: f64 = 1e-4;
/// The mid-plane: a point on it and an orthonormal frame, `normal` across it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneFrame {
    pub origin: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    pub normal: Vec3,
}

impl PlaneFrame {
    fn local(&self, p: Vec3) -> DVec3 {
        let r = (p - self.origin).as_dvec3();
        DVec3::new(
            r.dot(self.u.as_dvec3()),
            r.dot(self.v.as_dvec3()),
            r.dot(self.normal.as_dvec3()),
        )
    }

    /// World point of plane coordinates `(x, y)`.
    pub fn point(&self, c: DVec2) -> Vec3 {
        self.origin + self.u * c.x as f32 + self.v * c.y as f32
    }
}

/// A sphere centred on the plane: its plane coordinates and radius, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarSphere {
    pub center: DVec2,
    pub radius: f64,
}

/// Snaps round-off (≈ 1e-9 on a mesh built along the coordinate axes) to zero.
fn snapped(a: Vec3) -> Vec3 {
    Vec3::select(a.abs().cmplt(Vec3::splat(1e-6)), Vec3::ZERO, a).normalize()
}

/// The plane of least spread of a surface with `area`, `centroid` and
/// `second_moment` (`mesh_integrals::shell_integrals`), and how flat the
/// surface is across it: its extent along the normal over its largest extent
/// in the plane (0 for a flat sheet, about 1 for a ball).
pub fn plane_of(
    vertices: &[Vec3],
    area: f32,
    centroid: Vec3,
    second_moment: glam::Mat3,
) -> (PlaneFrame, f32) {
    let (_, vectors) = symmetric_eigen(covariance(second_moment, area, centroid));
    let normal = snapped(vectors[2]);
    // Sign rule: the largest component positive, as `principal_axis`.
    let sign = |a: Vec3| {
        let m = a.abs().max_element();
        if a.x == m || a.y == m || a.z == m {
            a
        } else {
            -a
        }
    };
    let normal = sign(normal);
    let u = sign(snapped(vectors[0] - normal * vectors[0].dot(normal)));
    let v = normal.cross(u);
    let frame = PlaneFrame {
        origin: centroid,
        u,
        v,
        normal,
    };
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &p in vertices {
        let q = frame.local(p);
        lo = lo.min(q);
        hi = hi.max(q);
    }
    let e = hi - lo;
    let flatness = if e.x.max(e.y) > 0.0 {
        (e.z / e.x.max(e.y)) as f32
    } else {
        1.0
    };
    (frame, flatness)
}

/// Squared radius a sphere on the plane at `c` needs to hold `corners`.
pub(super) fn need(c: DVec2, corners: &[DVec3; 3]) -> f64 {
    corners.iter().fold(0.0f64, |m, p| {
        m.max((p.x - c.x).powi(2) + (p.y - c.y).powi(2) + p.z * p.z)
    })
}

/// The plane point that holds `corners` with the least radius, from `start`.
pub(super) fn least_radius_centre(start: DVec2, corners: &[DVec3]) -> DVec2 {
    let farthest = |c: DVec2| {
        let mut far = (0.0f64, c);
        for p in corners {
            let d = (p.x - c.x).powi(2) + (p.y - c.y).powi(2) + p.z * p.z;
            if d > far.0 {
                far = (d, DVec2::new(p.x, p.y));
            }
        }
        far
    };
    let mut c = start;
    let mut best = (farthest(c).0, c);
    for k in 0..96 {
        // The farthest corner: a subgradient of the radius points at it.
        let far = farthest(c);
        if far.0 < best.0 {
            best = (far.0, c);
        }
        c += (far.1 - c) / (k as f64 + 2.0);
    }
    if farthest(c).0 < best.0 {
        c
    } else {
        best.1
    }
}

/// Covers the surface with at most `count` spheres centred on `frame`'s plane.
pub fn fit_planar_spheres(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    frame: &PlaneFrame,
    count: usize,
) -> Vec<PlanarSphere> {
    let ids: Vec<[u32; 3]> = triangles
        .iter()
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .copied()
        .collect();
    // Every vertex in the plane's frame; the triangles' corners from them.
    let surface = Surface::new(ids, vertices.iter().map(|&v| frame.local(v)).collect());
    let tris = &surface.tris;
    if tris.is_empty() {
        return Vec::new();
    }
    let z_max = tris
        .iter()
        .flat_map(|t| t.iter().map(|p| p.z.abs()))
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    // Weighted points: each triangle's centre in the plane.
    let mut points: Vec<(DVec2, f64)> = tris
        .iter()
        .map(|t| {
            let centre = (t[0] + t[1] + t[2]) / 3.0;
            let area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
            let h = centre.z.abs() / z_max;
            (DVec2::new(centre.x, centre.y), area * (0.05 + h * h))
        })
        .collect();
    let count = count.clamp(1, tris.len());
    let start = farthest_point_start(&points, count);
    // Even: the spheres share the triangles up to the largest's radius,
    // which is lowered as far as it goes.
    let mut even = start.clone();
    k_means(&points, &mut even, K_MEANS_ITERATIONS);
    let even_owner = enclose_evenly(&surface, &mut even);
    // Tight: the smallest union, placed again where it stands out most.
    let mut centres = start;
    let mut owner = Vec::new();
    for round in 0..PLACEMENTS {
        k_means(&binned(&points), &mut centres, K_MEANS_ITERATIONS);
        owner = enclose_tightly(&surface, &mut centres);
        if round + 1 == PLACEMENTS {
            break;
        }
        // Where the union stands out most, more (smaller) cells next time.
        let r2 = radii_of(tris, &owner, &centres);
        let excess = excess_by_leaf(tris, &centres, &r2, EXCESS_COLUMNS);
        let mean = excess.iter().sum::<f64>() / excess.len() as f64;
        if mean <= 0.0 {
            break;
        }
        for (p, &o) in points.iter_mut().zip(&owner) {
            p.1 *= (excess[o] / mean).sqrt().clamp(0.25, 4.0);
        }
    }
    // Two flat shapes face to face rest as far apart as their largest
    // spheres stand: the tight cover only where that costs (almost) nothing,
    // else the lower of the even and the capped cover.
    let largest = |tris: &[[DVec3; 3]], owner: &[usize], centres: &[DVec2]| {
        radii_of(tris, owner, centres)
            .into_iter()
            .fold(0.0f64, f64::max)
            .sqrt()
    };
    let (tight_top, even_top) = (
        largest(tris, &owner, &centres),
        largest(tris, &even_owner, &even),
    );
    if tight_top <= even_top * (1.0 + TOP_SLACK) {
        return spheres_of(tris, &owner, &centres);
    }
    let dome = Dome::between(z_max, even_top);
    let (capped_top, capped) = capped_cover(&surface, dome, count);
    if capped_top < even_top {
        capped
    } else {
        spheres_of(tris, &even_owner, &even)
    }
}

/// The spheres of a cover: each centre with the radius its triangles need
/// (centres given none left out).
pub(super) fn spheres_of(
    tris: &[[DVec3; 3]],
    owner: &[usize],
    centres: &[DVec2],
) -> Vec<PlanarSphere> {
    let radii = radii_of(tris, owner, centres);
    centres
        .iter()
        .zip(&radii)
        .filter(|(_, &r2)| r2 > 0.0)
        .map(|(&center, &r2)| PlanarSphere {
            center,
            radius: r2.sqrt(),
        })
        .collect()
}

/// The weighted points gathered into `BINS` × `BINS` squares over their
/// bounds, each square's weighted mean with its summed weight: k-means on
/// a fine mesh's tens of thousands of triangles places its cells as well
/// from a few thousand.
pub(super) fn binned(points: &[(DVec2, f64)]) -> Vec<(DVec2, f64)> {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for &(p, _) in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let size = (hi - lo).max_element() / BINS as f64;
    if size.is_nan() || size <= 0.0 {
        return points.to_vec();
    }
    let mut bins = vec![(DVec2::ZERO, 0.0f64); BINS * BINS];
    for &(p, w) in points {
        let cell = ((p - lo) / size).floor();
        let (i, j) = (
            (cell.x as usize).min(BINS - 1),
            (cell.y as usize).min(BINS - 1),
        );
        let b = &mut bins[j * BINS + i];
        b.0 += p * w;
        b.1 += w;
    }
    bins.into_iter()
        .filter(|b| b.1 > 0.0)
        .map(|(sum, w)| (sum / w, w))
        .collect()
}

/// Moves `centres` to the weighted means of the points nearest each.
pub(super) fn k_means(points: &[(DVec2, f64)], centres: &mut [DVec2], iterations: usize) {
    for _ in 0..iterations {
        let mut sums = vec![(DVec2::ZERO, 0.0f64); centres.len()];
        for &(p, w) in points {
            let k = nearest(centres, p);
            sums[k].0 += p * w;
            sums[k].1 += w;
        }
        for (c, (s, w)) in centres.iter_mut().zip(&sums) {
            if *w > 0.0 {
                *c = *s / *w;
            }
        }
    }
}

/// Gives each triangle to a sphere and moves each sphere to hold its own
/// with the least radius, then lowers the largest (`balance`); returns each
/// triangle's sphere.
fn enclose_tightly(surface: &Surface, centres: &mut [DVec2]) -> Vec<usize> {
    let tris = &surface.tris;
    // Rounds of: each triangle to the sphere that holds it with the least
    // radius, each sphere moved to hold its own with the least radius; the
    // round whose union is smallest is kept (the rounds drift towards the
    // highest point and need not improve).
    let mut owner = vec![0usize; tris.len()];
    let mut best = (f64::INFINITY, Vec::new(), Vec::new());
    for round in 0..ENCLOSING_ROUNDS {
        for (t, o) in tris.iter().zip(owner.iter_mut()) {
            let mut pick = (f64::INFINITY, 0usize);
            for (k, &c) in centres.iter().enumerate() {
                let n = need(c, t);
                if n < pick.0 {
                    pick = (n, k);
                }
            }
            *o = pick.1;
        }
        let spheres: Vec<PlanarSphere> = centres
            .iter()
            .zip(radii_of(tris, &owner, centres))
            .map(|(&center, r2)| PlanarSphere {
                center,
                radius: r2.sqrt(),
            })
            .collect();
        let volume = union_volume_on_plane(&spheres, ROUND_COLUMNS);
        // (A NaN volume keeps the first round rather than none.)
        if volume < best.0 || best.1.is_empty() {
            best = (volume, owner.clone(), centres.to_vec());
        }
        if round + 1 == ENCLOSING_ROUNDS {
            break;
        }
        move_to_least_radius(surface, &owner, centres);
    }
    let (_, mut owner, kept) = best;
    centres.copy_from_slice(&kept);
    balance(surface, &mut owner, centres);
    owner
}

/// As `enclose_tightly`, but after the first round each triangle goes to the
/// sphere that already holds it with the smallest radius (else the one it
/// grows least): the spheres come out about as large as the largest, which
/// `balance` then lowers.
fn enclose_evenly(surface: &Surface, centres: &mut [DVec2]) -> Vec<usize> {
    let tris = &surface.tris;
    let mut owner = vec![0usize; tris.len()];
    let mut radii = vec![f64::INFINITY; centres.len()];
    for round in 0..EVEN_ROUNDS {
        for (t, o) in tris.iter().zip(owner.iter_mut()) {
            let mut pick = ((f64::INFINITY, f64::INFINITY), 0usize);
            for (k, &c) in centres.iter().enumerate() {
                let n = need(c, t);
                let key = (n.max(radii[k]), n);
                if key < pick.0 {
                    pick = (key, k);
                }
            }
            *o = pick.1;
        }
        if round + 1 == EVEN_ROUNDS {
            break;
        }
        move_to_least_radius(surface, &owner, centres);
        radii = radii_of(tris, &owner, centres);
    }
    balance(surface, &mut owner, centres);
    owner
}

/// Moves each sphere to where it holds its own triangles with the least radius.
pub(super) fn move_to_least_radius(surface: &Surface, owner: &[usize], centres: &mut [DVec2]) {
    let mut seen = Vec::new();
    for (k, c) in centres.iter_mut().enumerate() {
        let mine = surface.corners_of(owner, k, &mut seen);
        if !mine.is_empty() {
            *c = least_radius_centre(*c, &mine);
        }
    }
}

/// Lowers the largest sphere while it can: its triangles that need its full
/// radius go to the neighbour that holds them with a smaller one, and it
/// moves to where its remaining triangles need the least. The largest sphere
/// sets how far two flat shapes stay apart face to face (the pair of
/// largest spheres meets first), so this is what keeps them near the drawn
/// thickness.
fn balance(surface: &Surface, owner: &mut [usize], centres: &mut [DVec2]) {
    let tris = &surface.tris;
    let mut seen = Vec::new();
    let mut radii = radii_of(tris, owner, centres);
    for _ in 0..20 * centres.len() {
        let (k, top) =
            radii.iter().enumerate().fold(
                (0, f64::NEG_INFINITY),
                |b, (k, &r)| if r > b.1 { (k, r) } else { b },
            );
        let mut moved = false;
        for (t, o) in tris.iter().zip(owner.iter_mut()) {
            if *o != k || need(centres[k], t) < top * (1.0 - 1e-9) {
                continue;
            }
            let mut best = (f64::INFINITY, k);
            for (j, &c) in centres.iter().enumerate() {
                if j != k {
                    let n = need(c, t).max(radii[j]);
                    if n < best.0 {
                        best = (n, j);
                    }
                }
            }
            if best.0 >= top * (1.0 - 1e-6) {
                return;
            }
            *o = best.1;
            radii[best.1] = best.0;
            moved = true;
        }
        if !moved {
            return;
        }
        let mine = surface.corners_of(owner, k, &mut seen);
        if !mine.is_empty() {
            centres[k] = least_radius_centre(centres[k], &mine);
        }
        let c = centres[k];
        radii[k] = mine.iter().fold(0.0f64, |m, p| {
            m.max((p.x - c.x).powi(2) + (p.y - c.y).powi(2) + p.z * p.z)
        });
    }
}

fn nearest(centres: &[DVec2], p: DVec2) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (k, c) in centres.iter().enumerate() {
        let d = c.distance_squared(p);
        if d < best.0 {
            best = (d, k);
        }
    }
    best.1
}

/// Starting centres: the weighted mean, then each time the point farthest
/// (weighted) from those chosen.
pub(super) fn farthest_point_start(points: &[(DVec2, f64)], count: usize) -> Vec<DVec2> {
    let total: f64 = points.iter().map(|p| p.1).sum();
    let mean = points.iter().fold(DVec2::ZERO, |s, &(p, w)| s + p * w) / total.max(1e-300);
    let mut centres = vec![mean];
    let mut gap: Vec<f64> = points
        .iter()
        .map(|&(p, _)| p.distance_squared(mean))
        .collect();
    while centres.len() < count {
        let mut best = (-1.0f64, 0);
        for (i, (&(_, w), &g)) in points.iter().zip(&gap).enumerate() {
            if g * w > best.0 {
                best = (g * w, i);
            }
        }
        let c = points[best.1].0;
        centres.push(c);
        for (g, &(p, _)) in gap.iter_mut().zip(points) {
            *g = g.min(p.distance_squared(c));
        }
    }
    centres
}

/// Squared radius each centre needs for the triangles it owns.
pub(super) fn radii_of(tris: &[[DVec3; 3]], owner: &[usize], centres: &[DVec2]) -> Vec<f64> {
    let mut r2 = vec![0.0f64; centres.len()];
    for (t, &o) in tris.iter().zip(owner) {
        r2[o] = r2[o].max(need(centres[o], t));
    }
    r2
}

/// m³: the volume of the union of spheres centred on one plane, by columns
/// across it (`cells` × `cells` over their bounding square, midpoint rule).
pub fn union_volume_on_plane(spheres: &[PlanarSphere], cells: usize) -> f64 {
    if spheres.is_empty() || cells == 0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for s in spheres {
        lo = lo.min(s.center - DVec2::splat(s.radius));
        hi = hi.max(s.center + DVec2::splat(s.radius));
    }
    let step = (hi - lo) / cells as f64;
    let mut volume = 0.0;
    for i in 0..cells {
        for j in 0..cells {
            let p = lo + step * DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
            let half = spheres.iter().fold(0.0f64, |m, s| {
                m.max(s.radius * s.radius - s.center.distance_squared(p))
            });
            volume += 2.0 * half.sqrt();
        }
    }
    volume * step.x * step.y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_sphere_union_is_the_ball() {
        let s = [PlanarSphere {
            center: DVec2::new(0.3, -0.1),
            radius: 0.5,
        }];
        let v = union_volume_on_plane(&s, 400);
        let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
        assert!((v / ball - 1.0).abs() < 1e-3, "{v} vs {ball}");
    }

    #[test]
    fn the_least_radius_centre_of_two_points_is_between_them() {
        let t1 = [DVec3::new(-1.0, 0.0, 0.0); 3];
        let t2 = [DVec3::new(1.0, 0.0, 0.0); 3];
        let c = least_radius_centre(DVec2::new(0.9, 0.0), &[t1[0], t2[0]]);
        assert!(c.length() < 0.02, "{c}");
    }
}
