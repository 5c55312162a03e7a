//! The planar fitter's capped cover (`planar_cover`'s notes): tried where
//! the tight cover stands higher than the even one (a pillow, whose broad
//! middle is nearly as high as its top), its leaves' tops kept under a dome.

use glam::{DVec2, DVec3};

use super::planar_cover::{
    binned, farthest_point_start, k_means, move_to_least_radius, need, radii_of, spheres_of,
    PlanarSphere, EVEN_ROUNDS, K_MEANS_ITERATIONS,
};
use super::planar_surface::Surface;

/// The capped cover's cap over the surface's highest point, as a share of
/// the way from that point to the even cover's largest sphere (the caps
/// decide where the cells go and how the triangles are shared out; the
/// cover that comes of it is weighed by its own largest sphere).
const CAP_SHARE: f64 = 0.5;
/// Times the triangles are split in four for the capped cover: a sphere
/// must hold whole triangles, and a coarse mesh's (a pillow's are 2.7 cm
/// long across its middle) keep the cells there from being small.
const CAPPED_SPLITS: usize = 2;
/// No split that would pass this many triangles (the pillow's 2,400 split
/// twice come to 38,400): a fine mesh needs none, and its pieces' cost
/// grows as their count.
const CAPPED_TRIANGLES: usize = 40_000;
/// Rounds of shrinking a capped cover within its worst overshoot.
const TIGHTEN_ROUNDS: usize = 6;
/// How fast the capped cover's caps drop where the surface does, as a
/// share of its drop: the tops form a dome, so that a flat shape lying on a
/// plane rests on the leaves nearest the middle and tips back when tipped.
const DOME_FOLLOW: f64 = 0.5;

/// The tops a capped cover keeps under: `top` over the surface's highest
/// point, and lower where the surface is, dropping `DOME_FOLLOW` as fast.
#[derive(Clone, Copy, Debug)]
pub(super) struct Dome {
    top: f64,
    z_max: f64,
}

impl Dome {
    /// The dome `CAP_SHARE` of the way from the surface's highest point,
    /// `z_max`, to the even cover's largest sphere, `even_top`.
    pub(super) fn between(z_max: f64, even_top: f64) -> Self {
        Dome {
            top: z_max + CAP_SHARE * (even_top - z_max),
            z_max,
        }
    }

    /// The cap where the surface stands `z` off the plane.
    fn cap(&self, z: f64) -> f64 {
        self.top - DOME_FOLLOW * (self.z_max - z)
    }
}

/// How far the surface stands off the plane over plane point `c` (its
/// highest triangle there), 0 off the outline.
fn height_over(tris: &[[DVec3; 3]], c: DVec2) -> f64 {
    let mut height = 0.0f64;
    for t in tris {
        let (a, b, d) = (t[0].truncate(), t[1].truncate(), t[2].truncate());
        let area = (b - a).perp_dot(d - a);
        if area.abs() <= f64::MIN_POSITIVE {
            continue;
        }
        let (u, v) = (
            (b - c).perp_dot(d - c) / area,
            (d - c).perp_dot(a - c) / area,
        );
        if u >= 0.0 && v >= 0.0 && u + v <= 1.0 {
            height = height.max((u * t[0].z + v * t[1].z + (1.0 - u - v) * t[2].z).abs());
        }
    }
    height
}

/// The capped cover (the module's notes): cells placed for spheres under
/// `dome` (`start_under`), the triangles (split finer) shared out so that
/// no sphere stands further past its cap than it must, then shrunk within
/// that; with the largest sphere's radius.
pub(super) fn capped_cover(
    surface: &Surface,
    dome: Dome,
    count: usize,
) -> (f64, Vec<PlanarSphere>) {
    let mut fine = None::<Surface>;
    for _ in 0..CAPPED_SPLITS {
        let last = fine.as_ref().unwrap_or(surface);
        if 4 * last.tris.len() > CAPPED_TRIANGLES {
            break;
        }
        fine = Some(last.split());
    }
    let fine = fine.as_ref().unwrap_or(surface);
    let mut centres = start_under(&fine.tris, dome, count);
    let caps = |centres: &[DVec2]| -> Vec<f64> {
        centres
            .iter()
            .map(|&c| dome.cap(height_over(&surface.tris, c)))
            .collect()
    };
    let past = |n: f64, cap: f64| n.sqrt() - cap;
    let tris = &fine.tris;
    let mut owner = vec![0usize; tris.len()];
    let mut worst_past = vec![f64::NEG_INFINITY; centres.len()];
    let mut cap = caps(&centres);
    for round in 0..EVEN_ROUNDS {
        for (t, o) in tris.iter().zip(owner.iter_mut()) {
            let mut pick = ((f64::INFINITY, f64::INFINITY), 0usize);
            for (k, &c) in centres.iter().enumerate() {
                let p = past(need(c, t), cap[k]);
                let key = (p.max(worst_past[k]), p);
                if key < pick.0 {
                    pick = (key, k);
                }
            }
            *o = pick.1;
        }
        if round + 1 == EVEN_ROUNDS {
            break;
        }
        move_to_least_radius(fine, &owner, &mut centres);
        cap = caps(&centres);
        worst_past = radii_of(tris, &owner, &centres)
            .iter()
            .zip(&cap)
            .map(|(&r2, &c)| past(r2, c))
            .collect();
    }
    // Shrunk: each triangle to the sphere that holds it with the least
    // radius among those it keeps within the worst overshoot.
    let worst = radii_of(tris, &owner, &centres)
        .iter()
        .zip(&cap)
        .fold(f64::NEG_INFINITY, |m, (&r2, &c)| m.max(past(r2, c)));
    for _ in 0..TIGHTEN_ROUNDS {
        for (t, o) in tris.iter().zip(owner.iter_mut()) {
            let mut pick = (need(centres[*o], t), *o);
            for (k, &c) in centres.iter().enumerate() {
                let n = need(c, t);
                if n < pick.0 && past(n, cap[k]) <= worst {
                    pick = (n, k);
                }
            }
            *o = pick.1;
        }
        move_to_least_radius(fine, &owner, &mut centres);
        cap = caps(&centres);
    }
    let spheres = spheres_of(tris, &owner, &centres);
    let top = spheres.iter().fold(0.0f64, |m, s| m.max(s.radius));
    (top, spheres)
}

/// Cells placed for a cover whose spheres stand under `dome`: a sphere on
/// the plane no larger than the cap holds a patch about `√(cap² − z²)`
/// across where the surface stands `z` off it, so the cells go
/// `1 / (cap² − z²)` to a unit of area (k-means places its cells as the
/// square root of its weights).
fn start_under(tris: &[[DVec3; 3]], dome: Dome, count: usize) -> Vec<DVec2> {
    let floor = 1e-3 * dome.top * dome.top;
    let points: Vec<(DVec2, f64)> = tris
        .iter()
        .map(|t| {
            let centre = (t[0] + t[1] + t[2]) / 3.0;
            let area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
            let z = t.iter().fold(0.0f64, |m, p| m.max(p.z.abs()));
            let cap = dome.cap(z);
            let patch = (cap * cap - z * z).max(floor);
            (DVec2::new(centre.x, centre.y), area / (patch * patch))
        })
        .collect();
    let points = binned(&points);
    let mut centres = farthest_point_start(&points, count);
    k_means(&points, &mut centres, K_MEANS_ITERATIONS);
    centres
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_height_over_a_point_is_the_triangles_whichever_way_they_wind() {
        let a = DVec3::new(0.0, 0.0, 0.1);
        let b = DVec3::new(1.0, 0.0, 0.3);
        let c = DVec3::new(0.0, 1.0, -0.1);
        let at = DVec2::new(0.25, 0.25);
        // z there: 0.5·0.1 + 0.25·0.3 + 0.25·(−0.1) = 0.1.
        let expected = 0.1;
        for t in [[a, b, c], [a, c, b]] {
            assert!((height_over(&[t], at) - expected).abs() < 1e-12);
            assert_eq!(height_over(&[t], DVec2::new(0.8, 0.8)), 0.0);
        }
        let high = [a + DVec3::Z, b + DVec3::Z, c + DVec3::Z];
        assert!((height_over(&[[a, b, c], high], at) - (1.0 + expected)).abs() < 1e-12);
    }
}
