//! The chains of ribbons that touch solved together with their contacts as
//! rows of the same solve (`RibbonTouch::solve_held`): where the contacts'
//! passes alone take turns with each chain's solve, the solve pulls a
//! strand that a contact pushed back into the other (a push moves the
//! light points, the solve the balloon only by its share), and on a taut
//! tangle, or a segment dragged by a carried end, the passes do not
//! converge before the strands pass through.
//!
//! Each contact the last pass pushed apart, of those that slide fast, that
//! it pushed far or that touch a weight (`touch::HOLD_DEPTH`), is a row
//! `n·(p_b − p_a) ≥ floor` (as the push left them) between the closest points
//! `p = (1 − s)·x_q + s·x_{q+1}` of its two segments. The ribbons linked by
//! such rows are solved as one system, `[A B; Bᵀ C]·[λ_d; λ_c] = [r_d; r_c]`,
//! `A` block diagonal of each chain's tridiagonal (`chain`), through the
//! contacts' Schur complement `(C − Bᵀ·A⁻¹·B)·λ_c = r_c − Bᵀ·A⁻¹·r_d` (two
//! tridiagonal solves a row and a small dense one), a contact that
//! would pull (λ_c < 0) left out and the rest solved again; linearised
//! about the points and repeated until the lengths hold, as the chain's
//! own solve is. On one thread in the rows' order; the other lanes run the
//! four-lane solve as before.
//!
//! With friction, each slow contact held brings two more rows, its grips: along two
//! directions across its normal, `t·(p_b − p_a)` is held where it was when
//! the substep began (static friction, at position level as in Müller et
//! al. 2020), both left out where their λ together would exceed μ times
//! the push's (the contact slides; the passes' own friction then takes its
//! slide). They stand in for the passes' friction on the contacts held:
//! there the solve, not the next pass, takes the push the chains' tension
//! asks, and a pass's friction is within μ times its own push.
//!
//! Here the rows, the linked sets and the chains gathered and put back;
//! the solve of a set's system in `schur`.

use glam::{Mat3, Vec3};

use super::super::chain::Knots;
use super::super::lane_group::LaneGroup;
use super::super::solve::CHAIN_ITERATIONS;
use super::RibbonTouch;
use crate::solver::lanes::{LANES, V4};

mod schur;

/// The most contacts one linked set of ribbons takes (each a push row and,
/// with friction, two grips), the first pushed (the rest are left to the
/// passes): a caught segment has a few; in a pile of ribbons laid across
/// each other more held at once let more through (500 released together,
/// push rows only: 23 crossings with 4 a set, 28 with 16, 38 with 32), and
/// the dense solve grows as the cube of its rows.
const MOST_CONTACTS: usize = 4;

/// One side of a contact row: a point along a segment of a ribbon.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Side {
    pub group: u32,
    pub lane: u32,
    /// The segment (≥ 1: the knot's segment is its balloon's) and where
    /// along it, 0 to 1.
    pub segment: u32,
    pub at: f32,
}

/// A contact between two segments for the solve.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct HeldRow {
    pub a: Side,
    pub b: Side,
    /// Unit, from `a` toward `b`.
    pub normal: Vec3,
    /// The least `normal·(p_b − p_a)` may be, m (a grip: what it must be).
    pub floor: f32,
    /// A contact's push, or one of its two friction rows.
    pub kind: RowKind,
}

/// What a row holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum RowKind {
    /// The contact's push: may push, not pull.
    #[default]
    Push,
    /// No slide along `normal` since the substep began, within the friction
    /// cone of the push row at this index in `rows`.
    Grip(u32),
}

/// A ribbon in the solve: its lane, where its points and distance rows
/// start in the solve's arrays, and its knot.
#[derive(Clone, Debug)]
struct Chain {
    group: u32,
    lane: u32,
    first: usize,
    segments: usize,
    length: f32,
    knot: Knot,
    taut: bool,
    impulse: Vec3,
}

/// The knot of a lane as one ribbon's solve sees it.
#[derive(Clone, Copy, Debug)]
struct Knot {
    inv_mass: f32,
    inv_inertia: Mat3,
    arm: Vec3,
}

impl Knot {
    fn of(knots: &Knots, l: usize) -> Knot {
        let m = &knots.inv_inertia;
        Knot {
            inv_mass: knots.inv_mass.as_array()[l],
            inv_inertia: Mat3::from_cols(m.x_axis.lane(l), m.y_axis.lane(l), m.z_axis.lane(l)),
            arm: knots.arm.lane(l),
        }
    }

    fn inv_mass_along(&self, n: Vec3) -> f32 {
        let rn = self.arm.cross(n);
        self.inv_mass + rn.dot(self.inv_inertia * rn)
    }

    fn point_motion(&self, p: Vec3) -> Vec3 {
        self.inv_mass * p + (self.inv_inertia * self.arm.cross(p)).cross(self.arm)
    }
}

/// The solve's buffers, kept with the contacts (no allocation once grown).
/// Points and distance rows of the linked chains back to back: chain c's
/// points `first + c..` (one more than rows), rows `first..`.
#[derive(Clone, Debug, Default)]
pub(crate) struct HeldSolve {
    chains: Vec<Chain>,
    /// Per chain: its set (union–find).
    parent: Vec<u32>,
    /// Per chain: its set's root; per row: its set's.
    set_of: Vec<u32>,
    row_set: Vec<u32>,
    /// The chains, and the rows, set by set in the sets' order, each
    /// set's in their own order; and a count per set for the sorting.
    chains_by_set: Vec<u32>,
    rows_by_set: Vec<u32>,
    counts: Vec<u32>,
    /// Per (group, lane), four lanes a group: its chain in this solve
    /// (`u32::MAX`: none).
    chain_at: Vec<u32>,
    pub(super) rows: Vec<HeldRow>,
    /// Per row: its two sides' chains.
    row_chains: Vec<(u32, u32)>,
    set_rows: Vec<u32>,
    set_chains: Vec<u32>,
    x: Vec<Vec3>,
    w: Vec<f32>,
    dir: Vec<Vec3>,
    rhs: Vec<f32>,
    diag: Vec<f32>,
    off: Vec<f32>,
    pivot: Vec<f32>,
    lower: Vec<f32>,
    z: Vec<f32>,
    y: Vec<f32>,
    column: Vec<f32>,
    schur: Vec<f32>,
    right: Vec<f32>,
    lambda: Vec<f32>,
    active: Vec<bool>,
    /// Per row of the set: the set position of its contact's push row.
    push_at: Vec<u32>,
    /// Per row: where a push taken into its set stands there (`u32::MAX`:
    /// not taken).
    taken: Vec<u32>,
    friction: f32,
}

/// Side `s`'s point along its segment, of a group's `points` (or `start`).
fn on(points: &[V4], s: Side) -> Vec3 {
    let (l, i) = (s.lane as usize, s.segment as usize);
    points[i].lane(l) * (1.0 - s.at) + points[i + 1].lane(l) * s.at
}

impl RibbonTouch {
    /// Adds a row: the closest points `a` and `b` of a pair just pushed
    /// apart may not come closer along `normal` than they now are; and,
    /// with friction, its two grips if `grip` (not sliding).
    pub(super) fn hold(
        &mut self,
        groups: &mut [LaneGroup],
        a: Side,
        b: Side,
        normal: Vec3,
        grip: bool,
    ) {
        if a.segment == 0 || b.segment == 0 {
            return; // a knot's segment: the balloon holds it
        }
        let now = |s: Side| on(&groups[s.group as usize].points, s);
        let floor = normal.dot(now(b) - now(a));
        for s in [a, b] {
            groups[s.group as usize].held_lanes |= 1 << s.lane;
        }
        let push = self.held.rows.len() as u32;
        self.held.rows.push(HeldRow {
            a,
            b,
            normal,
            floor,
            kind: RowKind::Push,
        });
        if grip && self.friction > 0.0 {
            let started = |s: Side| on(&groups[s.group as usize].start, s);
            let began = started(b) - started(a);
            let t1 = normal.any_orthonormal_vector();
            for t in [t1, normal.cross(t1)] {
                self.held.rows.push(HeldRow {
                    a,
                    b,
                    normal: t,
                    floor: t.dot(began),
                    kind: RowKind::Grip(push),
                });
            }
        }
    }

    /// Solves the chains the last pass's rows link, with those rows, and
    /// lets the rows go.
    pub(crate) fn solve_held(&mut self, groups: &mut [LaneGroup]) {
        if !self.held.rows.is_empty() {
            let friction = self.friction;
            self.held.solve(groups, friction);
        }
        self.held.rows.clear();
    }
}

impl HeldSolve {
    fn find(&mut self, c: u32) -> u32 {
        let mut c = c;
        while self.parent[c as usize] != c {
            let up = self.parent[self.parent[c as usize] as usize];
            self.parent[c as usize] = up;
            c = up;
        }
        c
    }

    /// The chain of (group, lane), added if new.
    fn chain_of(&mut self, groups: &[LaneGroup], s: Side) -> u32 {
        let at = s.group as usize * LANES + s.lane as usize;
        if self.chain_at.len() < groups.len() * LANES {
            self.chain_at.resize(groups.len() * LANES, u32::MAX);
        }
        if self.chain_at[at] != u32::MAX {
            return self.chain_at[at];
        }
        let g = &groups[s.group as usize];
        let l = s.lane as usize;
        self.chains.push(Chain {
            group: s.group,
            lane: s.lane,
            first: 0,
            segments: g.points.len() - 1,
            length: g.segment_length.as_array()[l],
            knot: Knot::of(&g.knots, l),
            taut: true,
            impulse: Vec3::ZERO,
        });
        self.parent.push(self.parent.len() as u32);
        self.set_of.push(0);
        let c = (self.chains.len() - 1) as u32;
        self.chain_at[at] = c;
        c
    }

    fn solve(&mut self, groups: &mut [LaneGroup], friction: f32) {
        self.friction = friction;
        self.chains.clear();
        self.parent.clear();
        self.set_of.clear();
        self.row_chains.clear();
        for r in 0..self.rows.len() {
            let row = self.rows[r];
            let (ca, cb) = (self.chain_of(groups, row.a), self.chain_of(groups, row.b));
            self.row_chains.push((ca, cb));
            let (ra, rb) = (self.find(ca), self.find(cb));
            if ra != rb {
                self.parent[ra.max(rb) as usize] = ra.min(rb);
            }
        }
        // Each linked set in the order of its first chain (its root), its
        // chains and rows each in their own order.
        let sets = self.chains.len();
        for c in 0..sets as u32 {
            let root = self.find(c);
            self.set_of[c as usize] = root;
        }
        let row_sets = self
            .row_chains
            .iter()
            .map(|&(a, _)| self.set_of[a as usize]);
        self.row_set.clear();
        self.row_set.extend(row_sets);
        by_set(
            &self.set_of[..sets],
            sets,
            &mut self.counts,
            &mut self.chains_by_set,
        );
        by_set(&self.row_set, sets, &mut self.counts, &mut self.rows_by_set);
        self.taken.clear();
        self.taken.resize(self.rows.len(), u32::MAX);
        let (mut next_chain, mut next_row) = (0, 0);
        while next_chain < sets {
            let set = self.set_of[self.chains_by_set[next_chain] as usize];
            let chains = self.chains_by_set[next_chain..]
                .iter()
                .take_while(|&&c| self.set_of[c as usize] == set)
                .count();
            self.set_chains.clear();
            self.set_chains
                .extend_from_slice(&self.chains_by_set[next_chain..][..chains]);
            next_chain += chains;
            let rows = self.rows_by_set[next_row..]
                .iter()
                .take_while(|&&r| self.row_set[r as usize] == set)
                .count();
            let (first_row, last_row) = (next_row, next_row + rows);
            next_row = last_row;
            self.set_rows.clear();
            self.push_at.clear();
            let mut pushes = 0;
            for k in first_row..last_row {
                let r = self.rows_by_set[k] as usize;
                let at = self.set_rows.len() as u32;
                match self.rows[r].kind {
                    RowKind::Push if pushes < MOST_CONTACTS => {
                        pushes += 1;
                        self.taken[r] = at;
                        self.set_rows.push(r as u32);
                        self.push_at.push(at);
                    }
                    RowKind::Grip(push) if self.taken[push as usize] != u32::MAX => {
                        self.set_rows.push(r as u32);
                        self.push_at.push(self.taken[push as usize]);
                    }
                    _ => {}
                }
            }
            self.solve_set(groups);
        }
        // The lanes go back to the four-lane solve.
        for chain in &self.chains {
            groups[chain.group as usize].held_lanes = 0;
            self.chain_at[chain.group as usize * LANES + chain.lane as usize] = u32::MAX;
        }
    }

    /// The set's chains gathered, solved and put back.
    fn solve_set(&mut self, groups: &mut [LaneGroup]) {
        self.x.clear();
        self.w.clear();
        let mut first = 0;
        for k in 0..self.set_chains.len() {
            let c = self.set_chains[k] as usize;
            let chain = &mut self.chains[c];
            let g = &groups[chain.group as usize];
            let l = chain.lane as usize;
            chain.first = first;
            chain.impulse = Vec3::ZERO;
            first += chain.segments;
            self.x.extend(g.points.iter().map(|p| p.lane(l)));
            self.w.extend(g.inv_mass.iter().map(|m| m.as_array()[l]));
        }
        let rows = first;
        for v in [
            &mut self.rhs,
            &mut self.diag,
            &mut self.off,
            &mut self.pivot,
            &mut self.lower,
            &mut self.z,
            &mut self.column,
        ] {
            v.clear();
            v.resize(rows, 0.0);
        }
        self.dir.clear();
        self.dir.resize(rows, Vec3::ZERO);
        let k = self.set_rows.len();
        self.y.clear();
        self.y.resize(k * rows, 0.0);
        self.schur.clear();
        self.schur.resize(k * k, 0.0);
        self.right.clear();
        self.right.resize(k, 0.0);
        self.lambda.clear();
        self.lambda.resize(k, 0.0);
        // Not followed by follow-the-leader where it does not converge, as
        // the four-lane solve is: that pull ignores the contacts and drags a
        // caught strand back through the one it caught on.
        for _ in 0..CHAIN_ITERATIONS {
            if self.iterate() {
                break;
            }
        }
        for k in 0..self.set_chains.len() {
            let chain = &self.chains[self.set_chains[k] as usize];
            let g = &mut groups[chain.group as usize];
            let l = chain.lane as usize;
            let base = chain.first + k;
            for (i, p) in g.points.iter_mut().enumerate() {
                p.set_lane(l, self.x[base + i]);
            }
            let total: Vec3 = g.impulse.lane(l);
            g.impulse.set_lane(l, total + chain.impulse);
        }
    }
}

/// The items `0..set_of.len()` listed set by set in `out`, the sets in
/// their order (`0..sets`), each set's items in theirs: a counting sort.
fn by_set(set_of: &[u32], sets: usize, counts: &mut Vec<u32>, out: &mut Vec<u32>) {
    counts.clear();
    counts.resize(sets + 1, 0);
    for &s in set_of {
        counts[s as usize + 1] += 1;
    }
    for k in 1..=sets {
        counts[k] += counts[k - 1];
    }
    out.clear();
    out.resize(set_of.len(), 0);
    for (item, &s) in set_of.iter().enumerate() {
        out[counts[s as usize] as usize] = item as u32;
        counts[s as usize] += 1;
    }
}
