//! How wide an outline is where a point lies: the radius of the largest disc
//! inside the outline that holds the point (the "local thickness" of image
//! analysis). An inflated foil fills to about a tube that wide, so a star's
//! narrow arm stays thinner than its middle, though both lie the same
//! distance from the rim near the arm's root.
//!
//! Found on the outline's distance grid: every inside node's disc (its
//! distance to the rim) is stamped on the nodes it covers, each keeping the
//! largest; between nodes the field is read bilinearly.

use glam::Vec2;

/// The local width on a grid of nodes `spacing` apart, node (0, 0) at
/// `origin`, `columns` nodes to a row.
#[derive(Clone, Debug)]
pub(crate) struct LocalWidth {
    origin: Vec2,
    spacing: f32,
    columns: usize,
    rows: usize,
    radius: Vec<f32>,
}

impl LocalWidth {
    /// The field from the distances inside the outline at the grid's nodes
    /// (positive inside, row by row), never above `widest` (the largest
    /// distance inside, found finer than the grid).
    pub(crate) fn from_distances(
        distance: &[f32],
        columns: usize,
        origin: Vec2,
        spacing: f32,
        widest: f32,
    ) -> Self {
        let rows = distance.len() / columns;
        let mut radius: Vec<f32> = distance.iter().map(|&d| d.max(0.0)).collect();
        for (k, &d) in distance.iter().enumerate() {
            if d <= 0.0 {
                continue;
            }
            let (ci, cj) = ((k % columns) as i64, (k / columns) as i64);
            let cells = (d / spacing).floor() as i64;
            let reach2 = (d / spacing) * (d / spacing);
            for j in (cj - cells).max(0)..=(cj + cells).min(rows as i64 - 1) {
                for i in (ci - cells).max(0)..=(ci + cells).min(columns as i64 - 1) {
                    let (di, dj) = ((i - ci) as f32, (j - cj) as f32);
                    if di * di + dj * dj <= reach2 {
                        let r = &mut radius[j as usize * columns + i as usize];
                        *r = r.max(d);
                    }
                }
            }
        }
        for r in &mut radius {
            *r = r.min(widest);
        }
        Self {
            origin,
            spacing,
            columns,
            rows,
            radius,
        }
    }

    /// The width at node `k` of the grid.
    pub(crate) fn at_node(&self, k: usize) -> f32 {
        self.radius[k]
    }

    /// The width at `p`, bilinear between the four nodes round it (clamped
    /// to the grid's edge).
    pub(crate) fn at(&self, p: Vec2) -> f32 {
        let q = (p - self.origin) / self.spacing;
        let i = (q.x.floor() as i64).clamp(0, self.columns as i64 - 2) as usize;
        let j = (q.y.floor() as i64).clamp(0, self.rows as i64 - 2) as usize;
        let (fx, fy) = (
            (q.x - i as f32).clamp(0.0, 1.0),
            (q.y - j as f32).clamp(0.0, 1.0),
        );
        let node = |i: usize, j: usize| self.radius[j * self.columns + i];
        let below = node(i, j) + (node(i + 1, j) - node(i, j)) * fx;
        let above = node(i, j + 1) + (node(i + 1, j + 1) - node(i, j + 1)) * fx;
        below + (above - below) * fy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distances inside a rectangle `w` × `h` centred on the origin, on a
    /// grid of spacing `g`.
    fn rectangle(w: f32, h: f32, g: f32) -> (Vec<f32>, usize, Vec2) {
        let (nx, ny) = ((w / g).round() as usize + 3, (h / g).round() as usize + 3);
        let origin = Vec2::new(-0.5 * w - g, -0.5 * h - g);
        let mut d = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let p = origin + Vec2::new(i as f32, j as f32) * g;
                d.push((0.5 * w - p.x.abs()).min(0.5 * h - p.y.abs()));
            }
        }
        (d, nx, origin)
    }

    #[test]
    fn a_strip_is_half_its_width_wide_everywhere_inside() {
        // 1 m by 0.2 m: every inside point lies in a disc of radius 0.1.
        let g = 0.01;
        let (d, nx, origin) = rectangle(1.0, 0.2, g);
        let field = LocalWidth::from_distances(&d, nx, origin, g, 0.1);
        for p in [
            Vec2::new(0.0, 0.0),
            Vec2::new(0.3, 0.095),
            Vec2::new(-0.45, -0.05),
        ] {
            assert!((field.at(p) - 0.1).abs() < 1e-4, "{p}: {}", field.at(p));
        }
    }

    #[test]
    fn a_narrow_arm_is_narrower_than_the_body_it_leaves() {
        // An L: a 0.6 m square body with a 0.1 m wide arm along its bottom
        // (distances inside the union: the larger of the two).
        let g = 0.005;
        let (extent, nx, origin) = rectangle(1.4, 0.6, g);
        let d: Vec<f32> = (0..extent.len())
            .map(|k| {
                let p = origin + Vec2::new((k % nx) as f32, (k / nx) as f32) * g;
                // The arm: y in [-0.3, -0.2], x in [-0.7, 0.7].
                let arm = (p.y + 0.3).min(-0.2 - p.y).min(0.7 - p.x.abs());
                // The body: x in [-0.7, -0.1], y in [-0.3, 0.3].
                let square = (0.3 - (p.x + 0.4).abs()).min(0.3 - p.y.abs());
                arm.max(square)
            })
            .collect();
        let field = LocalWidth::from_distances(&d, nx, origin, g, 0.3);
        assert!((field.at(Vec2::new(-0.4, 0.0)) - 0.3).abs() < 1e-3);
        assert!((field.at(Vec2::new(0.4, -0.25)) - 0.05).abs() < 2e-3);
        // Never narrower than the point's own distance to the rim.
        for (k, &dk) in d.iter().enumerate() {
            assert!(field.at_node(k) >= dk.clamp(0.0, 0.3));
        }
    }
}
