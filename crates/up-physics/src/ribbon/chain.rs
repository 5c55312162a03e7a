//! One direct solve of a chain's distance constraints (XPBD with zero
//! compliance, all constraints at once).
//!
//! Constraint j holds points j and j+1 at the segment length:
//! C_j = |x_{j+1} − x_j| − l (at the knot, only while taut: a ribbon pulls
//! its balloon and never pushes it). Linearised about the current points, the
//! multipliers that bring every C_j to zero together solve
//! (J·W·Jᵀ)·λ = −C, and for a chain that matrix is tridiagonal: row j has
//! w_j + w_{j+1} on the diagonal and −w_{j+1}·(n_j·n_{j+1}) beside it (w the
//! inverse masses, n_j the unit direction of segment j). The Thomas algorithm
//! solves it in one pass down and one up, so the knot feels the weight of the
//! whole chain in every substep whatever the mass ratios, where Gauss–Seidel
//! would move the pull one segment per sweep (the trap of light points on a
//! heavy body). The same idea for rods: Deul, Kugelstadt, Bender, "Direct
//! position-based solver for stiff rods" (2018).
//!
//! Point 0 may be the knot on a body: its inverse mass is the body's
//! effective one at the knot along the first segment, and its share of the
//! solve is handed back as a position impulse for the body.

use glam::Vec3;
use up_geom::norm::Norm;

use super::MAX_SEGMENTS;

/// A diagonal below this is a constraint between two immovable points: it is
/// left out (its multiplier 0).
const TINY: f32 = 1e-20;
/// The knot's segment shorter than its length by more than this fraction is
/// slack (a taut one is within float rounding of it).
const SLACK: f32 = 1e-3;

/// The knot's body, as the solve sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct KnotBody {
    /// 1 / (mass + added mass), kg⁻¹ (0: immovable).
    pub inv_mass: f32,
    /// World inverse inertia, kg⁻¹·m⁻².
    pub inv_inertia: glam::Mat3,
    /// The knot from the body's centre of mass, world frame, m.
    pub arm: Vec3,
}

impl KnotBody {
    /// How far a position impulse `p` at the knot moves it, m (linearised).
    pub fn point_motion(&self, p: Vec3) -> Vec3 {
        self.inv_mass * p + (self.inv_inertia * self.arm.cross(p)).cross(self.arm)
    }

    /// Effective inverse mass of the knot along unit `n`.
    fn inv_mass_along(&self, n: Vec3) -> f32 {
        let rn = self.arm.cross(n);
        self.inv_mass + rn.dot(self.inv_inertia * rn)
    }
}

/// Brings the chain `points` (point 0 at the knot) back to `segment_length`
/// between neighbours. `inv_mass[i]` is point i's inverse mass for i ≥ 1
/// (0: held); `inv_mass[0]` is unused. Moves points 1.. and returns the
/// position impulse (kg·m) to apply to the knot's body at its arm, and the
/// largest |C_j| it started from (m); the knot in `points[0]` is left where
/// it is (the body carries it).
pub(crate) fn solve_chain(
    points: &mut [Vec3],
    inv_mass: &[f32],
    segment_length: f32,
    knot: &KnotBody,
) -> (Vec3, f32) {
    let n = points.len() - 1;
    debug_assert!(n as u32 <= MAX_SEGMENTS && inv_mass.len() == points.len());
    const CAP: usize = MAX_SEGMENTS as usize;
    let mut dir = [Vec3::ZERO; CAP];
    let mut upper = [0.0f32; CAP];
    let mut rhs = [0.0f32; CAP];
    let mut taut = [false; CAP];
    let mut worst = 0.0f32;
    for j in 0..n {
        let d = points[j + 1] - points[j];
        let len = d.norm();
        // A segment of no length has no direction: it keeps its neighbour's.
        dir[j] = if len > 1e-9 {
            d / len
        } else if j > 0 {
            dir[j - 1]
        } else {
            Vec3::NEG_Y
        };
        // The ribbon keeps its length along itself, both ways (it bends at
        // its points); its segment at the knot pulls the balloon but never
        // pushes it: slack, its row is left out (λ_0 = 0).
        taut[j] = j > 0 || len > (1.0 - SLACK) * segment_length;
        rhs[j] = if taut[j] { segment_length - len } else { 0.0 };
        worst = worst.max(rhs[j].abs());
    }
    let w = |i: usize| {
        if i == 0 {
            knot.inv_mass_along(dir[0])
        } else {
            inv_mass[i]
        }
    };
    // Forward sweep: `upper` becomes c'_j and `rhs` d'_j.
    let mut previous_upper = 0.0;
    let mut previous_rhs = 0.0;
    for j in 0..n {
        let coupled = |a: usize, b: usize| taut[a] && taut[b];
        let lower = if j > 0 && coupled(j - 1, j) {
            -w(j) * dir[j - 1].dot(dir[j])
        } else {
            0.0
        };
        let c = if j + 1 < n && coupled(j, j + 1) {
            -w(j + 1) * dir[j].dot(dir[j + 1])
        } else {
            0.0
        };
        let pivot = w(j) + w(j + 1) - lower * previous_upper;
        if !taut[j] || pivot.abs() < TINY {
            upper[j] = 0.0;
            rhs[j] = 0.0;
        } else {
            upper[j] = c / pivot;
            rhs[j] = (rhs[j] - lower * previous_rhs) / pivot;
        }
        previous_upper = upper[j];
        previous_rhs = rhs[j];
    }
    // Back substitution: `rhs` becomes λ_j.
    for j in (0..n.saturating_sub(1)).rev() {
        rhs[j] -= upper[j] * rhs[j + 1];
    }
    // Δx_i = w_i·(λ_{i−1}·n_{i−1} − λ_i·n_i).
    for i in 1..=n {
        let pull_back = rhs[i - 1] * dir[i - 1];
        let pull_on = if i < n { rhs[i] * dir[i] } else { Vec3::ZERO };
        points[i] += inv_mass[i] * (pull_back - pull_on);
    }
    // The knot's share: Δx_0 = −w_0·λ_0·n_0, an impulse −λ_0·n_0.
    (-rhs[0] * dir[0], worst)
}

#[cfg(test)]
mod tests {
    use glam::Mat3;

    use super::*;

    fn fixed_knot() -> KnotBody {
        KnotBody {
            inv_mass: 0.0,
            inv_inertia: Mat3::ZERO,
            arm: Vec3::ZERO,
        }
    }

    fn lengths(points: &[Vec3]) -> Vec<f32> {
        points.windows(2).map(|p| p[0].distance(p[1])).collect()
    }

    #[test]
    fn a_stretched_chain_on_a_fixed_knot_comes_back_in_one_solve() {
        // Straight and 1 % too long: the linearisation is exact along a line.
        let mut points: Vec<Vec3> = (0..17)
            .map(|i| Vec3::new(0.0, -0.101 * i as f32, 0.0))
            .collect();
        let inv_mass = vec![1.0 / 25e-6; 17];
        let (impulse, _) = solve_chain(&mut points, &inv_mass, 0.1, &fixed_knot());
        for l in lengths(&points) {
            assert!((l - 0.1).abs() < 1e-6, "{l}");
        }
        assert_eq!(points[0], Vec3::ZERO);
        // The knot is pulled toward the chain.
        assert!(impulse.y < 0.0, "{impulse}");
    }

    #[test]
    fn a_bent_chain_converges_quadratically() {
        // Stretched and sheared into a curve: each solve squares the error.
        let mut points: Vec<Vec3> = (0..17)
            .map(|i| Vec3::new(0.001 * (i * i) as f32, -0.101 * i as f32, 0.0))
            .collect();
        let inv_mass = vec![1.0 / 25e-6; 17];
        let worst = |p: &[Vec3]| {
            lengths(p)
                .iter()
                .fold(0.0f32, |m, l| m.max((l - 0.1).abs()))
        };
        let before = worst(&points);
        solve_chain(&mut points, &inv_mass, 0.1, &fixed_knot());
        let once = worst(&points);
        solve_chain(&mut points, &inv_mass, 0.1, &fixed_knot());
        let twice = worst(&points);
        assert!(
            once < 0.2 * before && twice < 1e-5,
            "{before} → {once} → {twice}"
        );
    }

    #[test]
    fn the_knot_feels_the_whole_chain_at_once() {
        // Every point of a hanging chain fell by the same δ in a substep: only
        // the first segment is stretched, yet the multipliers carry the weight
        // of all the points below it (Gauss–Seidel would pull on one).
        let (points_n, m, delta) = (16usize, 25e-6f32, 1e-4f32);
        let mut points: Vec<Vec3> = (0..=points_n)
            .map(|i| Vec3::new(0.0, -0.1 * i as f32 - if i > 0 { delta } else { 0.0 }, 0.0))
            .collect();
        let inv_mass = vec![1.0 / m; points_n + 1];
        let (impulse, _) = solve_chain(&mut points, &inv_mass, 0.1, &fixed_knot());
        // Each point moves back up δ; the knot's impulse is the chain's momentum change.
        let expected = points_n as f32 * m * delta;
        assert!(
            (impulse.y + expected).abs() < 1e-3 * expected,
            "{} against {}",
            impulse.y,
            -expected
        );
        for p in &points[1..] {
            assert!((p.y - (p.y / 0.1).round() * 0.1).abs() < 1e-6, "{p}");
        }
    }

    #[test]
    fn a_light_chain_and_a_heavy_knot_share_the_correction_by_mass() {
        // One segment: a 25 mg point 1 % too far from a 14 g body's knot.
        let knot = KnotBody {
            inv_mass: 1.0 / 0.014,
            inv_inertia: Mat3::ZERO,
            arm: Vec3::ZERO,
        };
        let mut points = vec![Vec3::ZERO, Vec3::new(0.0, -0.101, 0.0)];
        let inv_mass = vec![0.0, 1.0 / 25e-6];
        let (impulse, _) = solve_chain(&mut points, &inv_mass, 0.1, &knot);
        let knot_moves = impulse * knot.inv_mass;
        let gap = (points[1] - knot_moves).length();
        assert!((gap - 0.1).abs() < 1e-6, "{gap}");
        // Momentum: what the point gained the knot's body lost.
        let point_moves = points[1].y + 0.101;
        assert!((point_moves * 25e-6 + impulse.y).abs() < 1e-12);
    }

    #[test]
    fn a_slack_ribbon_pushes_nothing() {
        // The knot's body moved 3 cm toward the ribbon: nothing pushes it back.
        let knot = KnotBody {
            inv_mass: 1.0 / 0.014,
            inv_inertia: Mat3::ZERO,
            arm: Vec3::ZERO,
        };
        let mut points: Vec<Vec3> = (0..5)
            .map(|i| Vec3::new(0.0, -0.1 * i as f32, 0.0))
            .collect();
        points[0].y -= 0.03;
        let before = points.clone();
        let (impulse, _) = solve_chain(&mut points, &[0.0, 4e4, 4e4, 4e4, 4e4], 0.1, &knot);
        assert_eq!(impulse, Vec3::ZERO);
        assert_eq!(
            points, before,
            "the ribbon's own segments were at their length"
        );
    }

    #[test]
    fn a_held_point_and_a_fixed_knot_leave_their_segment_alone() {
        let mut points = vec![
            Vec3::ZERO,
            Vec3::new(0.0, -0.2, 0.0),
            Vec3::new(0.0, -0.3, 0.0),
        ];
        let inv_mass = vec![0.0, 0.0, 1.0 / 25e-6];
        solve_chain(&mut points, &inv_mass, 0.1, &fixed_knot());
        assert_eq!(points[1], Vec3::new(0.0, -0.2, 0.0));
        assert!((points[2].y + 0.3).abs() < 1e-6);
    }
}
