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
//!
//! Four chains of the same segment count are solved at once, one a lane
//! (`solver::lanes`): the Thomas algorithm has the same steps for every
//! chain, and where the scalar solve would branch (a slack knot, a pivot of
//! nothing) each lane selects, so a lane computes bit for bit what one chain
//! alone would.

use super::MAX_SEGMENTS;
use crate::solver::lanes::{select, F4, M4, V4};

/// A diagonal below this is a constraint between two immovable points: it is
/// left out (its multiplier 0).
pub(super) const TINY: f32 = 1e-20;
/// The knot's segment shorter than its length by more than this fraction is
/// slack (a taut one is within float rounding of it).
pub(super) const SLACK: f32 = 1e-3;
/// A segment shorter than this has no direction of its own, m.
const NO_LENGTH: f32 = 1e-9;

/// The knots' bodies, a lane each, as the solve sees them.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Knots {
    /// 1 / (mass + added mass), kg⁻¹ (0: immovable).
    pub inv_mass: F4,
    /// World inverse inertia, kg⁻¹·m⁻².
    pub inv_inertia: M4,
    /// The knot from the body's centre of mass, world frame, m.
    pub arm: V4,
}

impl Knots {
    /// How far a position impulse `p` at the knot moves it, m (linearised).
    #[inline]
    pub fn point_motion(&self, p: V4) -> V4 {
        self.inv_mass * p + self.inv_inertia.mul(self.arm.cross(p)).cross(self.arm)
    }

    /// Effective inverse mass of the knot along unit `n`.
    #[inline]
    fn inv_mass_along(&self, n: V4) -> F4 {
        let rn = self.arm.cross(n);
        self.inv_mass + rn.dot(self.inv_inertia.mul(rn))
    }
}

/// The solve's working rows, kept with the chains so that a solve allocates
/// nothing.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChainRows {
    dir: Vec<V4>,
    upper: Vec<F4>,
    rhs: Vec<F4>,
}

impl ChainRows {
    /// Segment `j`'s multiplier λ_j in each lane as the last solve found it
    /// (kg·m; negative where the segment pulls its points together).
    pub fn lambda(&self, j: usize) -> F4 {
        self.rhs[j]
    }

    /// Rows for chains of `segments` segments.
    pub fn resize(&mut self, segments: usize) {
        self.dir.resize(segments, V4::ZERO);
        self.upper.resize(segments, F4::ZERO);
        self.rhs.resize(segments, F4::ZERO);
    }
}

/// `v / s`, component by component, as glam divides a vector by a number.
#[inline]
pub(crate) fn div(v: V4, s: F4) -> V4 {
    V4::new(v.x / s, v.y / s, v.z / s)
}

/// Lane-wise `|v|`, as `Norm::norm`.
#[inline]
pub(crate) fn norm(v: V4) -> F4 {
    v.dot(v).sqrt()
}

/// `a.max(b)` as `f32::max` takes it when `b` may be NaN and `a` is not: `a`.
#[inline]
fn max_of_number(a: F4, b: F4) -> F4 {
    select(b.simd_gt(a), b, a)
}

/// Brings four chains `points` (per point index, a lane a chain; point 0 at
/// the knot) back to `segment_length` between neighbours, in the lanes of
/// `moving` (the others are left as they are). `inv_mass[i]` is point i's
/// inverse mass for i ≥ 1 (0: held); `inv_mass[0]` is unused. Moves points
/// 1.. and returns the position impulse (kg·m) to apply to each knot's body
/// at its arm, and the largest |C_j| each started from (m); the knots in
/// `points[0]` are left where they are (the bodies carry them).
pub(crate) fn solve_chains(
    points: &mut [V4],
    inv_mass: &[F4],
    segment_length: F4,
    knot: &Knots,
    moving: F4,
    rows: &mut ChainRows,
) -> (V4, F4) {
    let n = points.len() - 1;
    debug_assert!(n as u32 <= MAX_SEGMENTS && inv_mass.len() == points.len());
    let (dir, upper, rhs) = (&mut rows.dir[..n], &mut rows.upper[..n], &mut rows.rhs[..n]);
    let zero = F4::ZERO;
    let mut worst = zero;
    // Row 0: the knot's segment, coupled to row 1 only while taut.
    let len = segment(points, 0, V4::new(zero, F4::splat(-1.0), zero), dir);
    let taut_knot = len.simd_gt(F4::splat(1.0 - SLACK) * segment_length);
    rhs[0] = select(taut_knot, segment_length - len, zero);
    worst = max_of_number(worst, rhs[0].abs());
    let knot_w = knot.inv_mass_along(dir[0]);
    // One pass down: each row's segment found (its direction, how far it is
    // from its length), then the row before it eliminated (the Thomas
    // algorithm's forward sweep: `upper` becomes c'_j and `rhs` d'_j), so
    // the sweep's chain of divisions overlaps the next segment's norm.
    let mut w_j = knot_w;
    let mut previous_upper = zero;
    let mut previous_rhs = zero;
    for j in 0..n {
        let w_next = inv_mass[j + 1];
        let c = if j + 1 < n {
            let len = segment(points, j + 1, dir[j], dir);
            rhs[j + 1] = segment_length - len;
            // A segment held at both ends (resting points, `lane_group`)
            // is none of the solve's to bring back: it does not count.
            let free = (w_next + inv_mass[j + 2]).simd_gt(zero);
            worst = max_of_number(worst, select(free, rhs[j + 1].abs(), zero));
            let c = -w_next * dir[j].dot(dir[j + 1]);
            if j == 0 {
                select(taut_knot, c, zero)
            } else {
                c
            }
        } else {
            zero
        };
        let lower = if j > 0 {
            let lower = -w_j * dir[j - 1].dot(dir[j]);
            if j == 1 {
                select(taut_knot, lower, zero)
            } else {
                lower
            }
        } else {
            zero
        };
        let pivot = w_j + w_next - lower * previous_upper;
        let mut solved = !pivot.abs().simd_lt(F4::splat(TINY));
        if j == 0 {
            solved &= taut_knot;
        }
        previous_upper = select(solved, c / pivot, zero);
        previous_rhs = select(solved, (rhs[j] - lower * previous_rhs) / pivot, zero);
        upper[j] = previous_upper;
        rhs[j] = previous_rhs;
        w_j = w_next;
    }
    // One pass up: back substitution (`rhs` becomes λ_j, kept for
    // `ChainRows::lambda`), and each point
    // moved as soon as both its segments' λ are known:
    // Δx_i = w_i·(λ_{i−1}·n_{i−1} − λ_i·n_i).
    let mut lambda_after = rhs[n - 1];
    let moved = points[n] + inv_mass[n] * (lambda_after * dir[n - 1] - V4::ZERO);
    points[n] = V4::select(moving, moved, points[n]);
    for j in (0..n - 1).rev() {
        let lambda = rhs[j] - upper[j] * lambda_after;
        rhs[j] = lambda;
        let i = j + 1;
        let moved = points[i] + inv_mass[i] * (lambda * dir[j] - lambda_after * dir[i]);
        points[i] = V4::select(moving, moved, points[i]);
        lambda_after = lambda;
    }
    // The knot's share: Δx_0 = −w_0·λ_0·n_0, an impulse −λ_0·n_0.
    (-lambda_after * dir[0], worst)
}

/// Segment `j` of the chains (from point `j` to `j + 1`): its unit direction
/// into `dir[j]` (`before`'s where it has no length: it keeps its
/// neighbour's), and its length.
#[inline(always)]
fn segment(points: &[V4], j: usize, before: V4, dir: &mut [V4]) -> F4 {
    let d = points[j + 1] - points[j];
    let len = norm(d);
    dir[j] = V4::select(len.simd_gt(F4::splat(NO_LENGTH)), div(d, len), before);
    len
}

#[cfg(test)]
mod tests {
    use glam::{Mat3, Vec3};

    use super::*;
    use crate::solver::lanes::{set, LANES};

    /// A knot's body for one lane: inverse mass, inverse inertia, arm.
    type Knot = (f32, Mat3, Vec3);

    const FIXED: Knot = (0.0, Mat3::ZERO, Vec3::ZERO);

    /// A chain to share the lanes with: bent, stretched, of other masses.
    fn filler(lane: usize, points: usize) -> (Vec<Vec3>, Vec<f32>) {
        let l = lane as f32;
        let p = (0..points)
            .map(|i| {
                let i = i as f32;
                Vec3::new(0.02 * (i * (1.0 + l)).sin(), -0.103 * i, 0.01 * l * i)
            })
            .collect();
        (p, vec![1.0 / (20e-6 + 5e-6 * l); points])
    }

    fn set_knot(knots: &mut Knots, lane: usize, (inv_mass, inv_inertia, arm): Knot) {
        set(&mut knots.inv_mass, lane, inv_mass);
        knots.arm.set_lane(lane, arm);
        let m = &mut knots.inv_inertia;
        for (axis, column) in [
            (&mut m.x_axis, inv_inertia.x_axis),
            (&mut m.y_axis, inv_inertia.y_axis),
            (&mut m.z_axis, inv_inertia.z_axis),
        ] {
            axis.set_lane(lane, column);
        }
    }

    /// Solves `chains` (one a lane, all of one length) in the lanes of
    /// `moving`; returns each lane's points, impulse and worst |C|.
    fn solve_lanes(
        chains: [(&[Vec3], &[f32], Knot); LANES],
        segment_length: f32,
        moving: [bool; LANES],
    ) -> [(Vec<Vec3>, Vec3, f32); LANES] {
        let n = chains[0].0.len();
        let mut points = vec![V4::ZERO; n];
        let mut inv_mass = vec![F4::ZERO; n];
        let mut knots = Knots::default();
        for (lane, (p, w, knot)) in chains.iter().enumerate() {
            for i in 0..n {
                points[i].set_lane(lane, p[i]);
                set(&mut inv_mass[i], lane, w[i]);
            }
            set_knot(&mut knots, lane, *knot);
        }
        let mask = F4::new(moving.map(|m| if m { f32::from_bits(!0) } else { 0.0 }));
        let mut rows = ChainRows::default();
        rows.resize(n - 1);
        let length = F4::splat(segment_length);
        let (impulse, worst) =
            solve_chains(&mut points, &inv_mass, length, &knots, mask, &mut rows);
        std::array::from_fn(|lane| {
            let p = points.iter().map(|v| v.lane(lane)).collect();
            (p, impulse.lane(lane), worst.to_array()[lane])
        })
    }

    /// Solves one chain in lane 0 beside fillers: its points, impulse, worst |C|.
    fn solve_chain(
        points: &mut Vec<Vec3>,
        inv_mass: &[f32],
        length: f32,
        knot: Knot,
    ) -> (Vec3, f32) {
        let fillers: [_; LANES] = std::array::from_fn(|l| filler(l, points.len()));
        let mut chains = fillers.each_ref().map(|(p, w)| (&p[..], &w[..], FIXED));
        chains[0] = (&points[..], inv_mass, knot);
        let [(solved, impulse, worst), ..] = solve_lanes(chains, length, [true; LANES]);
        *points = solved;
        (impulse, worst)
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
        let (impulse, _) = solve_chain(&mut points, &inv_mass, 0.1, FIXED);
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
        let (_, started) = solve_chain(&mut points, &inv_mass, 0.1, FIXED);
        assert!(
            (started - before).abs() < 1e-6,
            "{started} against {before}"
        );
        let once = worst(&points);
        solve_chain(&mut points, &inv_mass, 0.1, FIXED);
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
        let (impulse, _) = solve_chain(&mut points, &inv_mass, 0.1, FIXED);
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
        let knot = (1.0 / 0.014, Mat3::ZERO, Vec3::ZERO);
        let mut points = vec![Vec3::ZERO, Vec3::new(0.0, -0.101, 0.0)];
        let inv_mass = vec![0.0, 1.0 / 25e-6];
        let (impulse, _) = solve_chain(&mut points, &inv_mass, 0.1, knot);
        let knot_moves = impulse * knot.0;
        let gap = (points[1] - knot_moves).length();
        assert!((gap - 0.1).abs() < 1e-6, "{gap}");
        // Momentum: what the point gained the knot's body lost.
        let point_moves = points[1].y + 0.101;
        assert!((point_moves * 25e-6 + impulse.y).abs() < 1e-12);
    }

    #[test]
    fn a_slack_ribbon_pushes_nothing() {
        // The knot's body moved 3 cm toward the ribbon: nothing pushes it back.
        let knot = (1.0 / 0.014, Mat3::ZERO, Vec3::ZERO);
        let mut points: Vec<Vec3> = (0..5)
            .map(|i| Vec3::new(0.0, -0.1 * i as f32, 0.0))
            .collect();
        points[0].y -= 0.03;
        let before = points.clone();
        let (impulse, _) = solve_chain(&mut points, &[0.0, 4e4, 4e4, 4e4, 4e4], 0.1, knot);
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
        solve_chain(&mut points, &inv_mass, 0.1, FIXED);
        assert_eq!(points[1], Vec3::new(0.0, -0.2, 0.0));
        assert!((points[2].y + 0.3).abs() < 1e-6);
    }

    #[test]
    fn each_lane_solves_its_own_chain_and_a_lane_left_out_stays() {
        // Four different chains together give, bit for bit, what each gives
        // beside other chains; a lane outside `moving` does not move.
        let chains: [_; LANES] = std::array::from_fn(|l| filler(l + 1, 9));
        let knots: [Knot; LANES] = std::array::from_fn(|l| {
            let arm = Vec3::new(0.01 * l as f32, 0.02, -0.01);
            (
                1.0 / (0.01 + 0.002 * l as f32),
                Mat3::from_diagonal(Vec3::splat(50.0)),
                arm,
            )
        });
        let together = chains.each_ref().map(|(p, w)| (&p[..], &w[..], FIXED));
        let mut together = together;
        for (l, chain) in together.iter_mut().enumerate() {
            chain.2 = knots[l];
        }
        let all = solve_lanes(together, 0.1, [true, true, false, true]);
        for (l, (p, w)) in chains.iter().enumerate() {
            let mut alone = p.clone();
            let (impulse, worst) = solve_chain(&mut alone, w, 0.1, knots[l]);
            if l == 2 {
                assert_eq!(&all[l].0, p, "lane {l} was left out");
                continue;
            }
            for (a, b) in all[l].0.iter().zip(&alone) {
                assert_eq!(
                    a.to_array().map(f32::to_bits),
                    b.to_array().map(f32::to_bits)
                );
            }
            assert_eq!(
                all[l].1.to_array().map(f32::to_bits),
                impulse.to_array().map(f32::to_bits)
            );
            assert_eq!(all[l].2.to_bits(), worst.to_bits());
        }
    }
}
