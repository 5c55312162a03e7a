//! How much of a planar cover's union lies outside the mesh, leaf by leaf:
//! the plane is cut into columns, each column's stretch of union beyond the
//! mesh's own stretch (its thickness there; all of it off the outline) goes
//! to the leaf whose chord is the union's there (the longest: every centre
//! lies on the plane, so chords share their middle).

use glam::{DVec2, DVec3};

/// Excess volume, m³, of each leaf (`centres`, squared radii `r2`) over the
/// surface `tris` (plane coordinates, z across), on `cells` × `cells`
/// columns over the leaves' bounding square.
pub(crate) fn excess_by_leaf(
    tris: &[[DVec3; 3]],
    centres: &[DVec2],
    r2: &[f64],
    cells: usize,
) -> Vec<f64> {
    let mut excess = vec![0.0f64; centres.len()];
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for (c, &r2) in centres.iter().zip(r2) {
        let r = r2.max(0.0).sqrt();
        lo = lo.min(*c - DVec2::splat(r));
        hi = hi.max(*c + DVec2::splat(r));
    }
    if !(lo.x < hi.x && lo.y < hi.y) {
        return excess;
    }
    let step = (hi - lo) / cells as f64;
    // The mesh's stretch across each column: lowest and highest z met.
    let mut span = vec![(f64::INFINITY, f64::NEG_INFINITY); cells * cells];
    for t in tris {
        let (a, b, c) = (t[0], t[1], t[2]);
        let det = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
        if det.abs() < 1e-18 {
            continue;
        }
        let cell = |v: f64, l: f64, s: f64| ((v - l) / s - 0.5).max(0.0);
        let x0 = cell(a.x.min(b.x).min(c.x), lo.x, step.x).floor() as usize;
        let x1 = (cell(a.x.max(b.x).max(c.x), lo.x, step.x).ceil() as usize).min(cells - 1);
        let y0 = cell(a.y.min(b.y).min(c.y), lo.y, step.y).floor() as usize;
        let y1 = (cell(a.y.max(b.y).max(c.y), lo.y, step.y).ceil() as usize).min(cells - 1);
        for j in y0..=y1 {
            for i in x0..=x1 {
                let p = lo + step * DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
                let l1 = ((b.y - c.y) * (p.x - c.x) + (c.x - b.x) * (p.y - c.y)) / det;
                let l2 = ((c.y - a.y) * (p.x - c.x) + (a.x - c.x) * (p.y - c.y)) / det;
                let l3 = 1.0 - l1 - l2;
                if l1 < -1e-9 || l2 < -1e-9 || l3 < -1e-9 {
                    continue;
                }
                let z = l1 * a.z + l2 * b.z + l3 * c.z;
                let s = &mut span[j * cells + i];
                *s = (s.0.min(z), s.1.max(z));
            }
        }
    }
    let area = step.x * step.y;
    for j in 0..cells {
        for i in 0..cells {
            let p = lo + step * DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
            let mut best = (0.0f64, usize::MAX);
            for (k, (c, &r2)) in centres.iter().zip(r2).enumerate() {
                let h = r2 - c.distance_squared(p);
                if h > best.0 {
                    best = (h, k);
                }
            }
            if best.1 == usize::MAX {
                continue;
            }
            let (zl, zh) = span[j * cells + i];
            let thick = if zh > zl { zh - zl } else { 0.0 };
            excess[best.1] += (2.0 * best.0.sqrt() - thick).max(0.0) * area;
        }
    }
    excess
}
