//! The chains of ribbons that touch solved together with their contacts as
//! rows of the same solve (`RibbonTouch::solve_held`): where the contacts'
//! passes alone take turns with each chain's solve, the solve pulls a
//! strand that a contact pushed back into the other (a push moves the
//! light points, the solve the balloon only by its share), and on a taut
//! tangle, or a segment dragged by a carried end, the passes do not
//! converge before the strands pass through.
//!
//! Each contact the last pass pushed apart is a row
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
//! With friction, each contact brings two more rows, its grips: along two
//! directions across its normal, `t·(p_b − p_a)` is held where it was when
//! the substep began (static friction, at position level as in Müller et
//! al. 2020), both left out where their λ together would exceed μ times
//! the push's (the contact slides; the passes' own friction then takes its
//! slide). In the solve the grips see the normal force the chains' tension
//! gives the contact, which a pass's grip, within μ times its own push,
//! does not: a ribbon draped over a taut one hangs only with them.

use glam::{Mat3, Vec3};

use super::super::chain::{Knots, SLACK, TINY};
use super::super::lane_group::LaneGroup;
use super::super::solve::{CHAIN_ITERATIONS, CHAIN_TOLERANCE};
use super::RibbonTouch;

/// The most contacts one linked set of ribbons takes (each a push row and,
/// with friction, two grips), the first pushed (the rest are left to the
/// passes): a caught segment has a few; in a pile of ribbons laid across
/// each other more held at once let more through (500 released together,
/// push rows only: 23 crossings with 4 a set, 28 with 16, 38 with 32), and
/// the dense solve grows as the cube of its rows.
const MOST_CONTACTS: usize = 4;

/// Rounds of leaving out the contacts that pull and the grips that slip,
/// each followed by a solve of the rows left.
const ROUNDS: usize = 3;

/// Added to a contact's own entry of the Schur complement, a fraction of
/// its own weight: two contacts on one segment with about one normal would
/// make it singular.
const REGULAR: f32 = 1e-2;

/// The same for a contact that shares a point with another of its set (a
/// ribbon's point pinched between two segments of the other, or one
/// contact seen from both segments either side of a point): their rows
/// are nearly dependent there, and held as stiffly as the rest they trade
/// large opposite pushes that keep both ribbons trembling (at 1 %, a taut
/// ribbon under a draped one keeps its points at 2 cm/s; from 5 % both
/// rest).
const SHARED_REGULAR: f32 = 0.1;

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
    /// Per chain: its set (union–find), and the chain of each (group,
    /// lane) in this solve.
    parent: Vec<u32>,
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
        let at = |g: &[LaneGroup], s: Side| {
            let g = &g[s.group as usize];
            let (l, i) = (s.lane as usize, s.segment as usize);
            g.points[i].lane(l) * (1.0 - s.at) + g.points[i + 1].lane(l) * s.at
        };
        let started = |g: &[LaneGroup], s: Side| {
            let g = &g[s.group as usize];
            let (l, i) = (s.lane as usize, s.segment as usize);
            g.start[i].lane(l) * (1.0 - s.at) + g.start[i + 1].lane(l) * s.at
        };
        let floor = normal.dot(at(groups, b) - at(groups, a));
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
            let began = started(groups, b) - started(groups, a);
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
        if let Some(c) = self
            .chains
            .iter()
            .position(|c| c.group == s.group && c.lane == s.lane)
        {
            return c as u32;
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
        (self.chains.len() - 1) as u32
    }

    fn solve(&mut self, groups: &mut [LaneGroup], friction: f32) {
        self.friction = friction;
        self.chains.clear();
        self.parent.clear();
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
        // Each linked set in the order of its first chain.
        for c in 0..self.chains.len() as u32 {
            if self.find(c) != c {
                continue;
            }
            self.set_chains.clear();
            for d in 0..self.chains.len() as u32 {
                if self.find(d) == c {
                    self.set_chains.push(d);
                }
            }
            self.set_rows.clear();
            self.push_at.clear();
            self.taken.clear();
            self.taken.resize(self.rows.len(), u32::MAX);
            let mut pushes = 0;
            for r in 0..self.rows.len() {
                if self.find(self.row_chains[r].0) != c {
                    continue;
                }
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

    /// Where chain `c`'s point `i` is in `x`.
    fn point(&self, c: u32, i: usize) -> usize {
        let k = self.set_chains.iter().position(|&d| d == c).unwrap_or(0);
        self.chains[c as usize].first + k + i
    }

    /// A side's two points in `x` and their weights.
    fn side_points(&self, c: u32, s: &Side) -> ([usize; 2], [f32; 2]) {
        let q = s.segment as usize;
        ([self.point(c, q), self.point(c, q + 1)], [1.0 - s.at, s.at])
    }

    /// One linearised solve of the set; true once its lengths hold.
    fn iterate(&mut self) -> bool {
        let mut converged = true;
        for k in 0..self.set_chains.len() {
            let c = self.set_chains[k] as usize;
            let (first, n, length) = {
                let ch = &self.chains[c];
                (ch.first, ch.segments, ch.length)
            };
            let base = first + k;
            let mut before = Vec3::NEG_Y;
            for j in 0..n {
                let d = self.x[base + j + 1] - self.x[base + j];
                let len = d.length();
                let dir = if len > 1e-9 { d / len } else { before };
                before = dir;
                self.dir[first + j] = dir;
                self.rhs[first + j] = length - len;
            }
            let taut = -self.rhs[first] > -SLACK * length;
            self.chains[c].taut = taut;
            if !taut {
                self.rhs[first] = 0.0;
            }
            let mut worst = 0.0f32;
            for j in 0..n {
                worst = worst.max(self.rhs[first + j].abs());
                let own = if j == 0 {
                    self.chains[c].knot.inv_mass_along(self.dir[first])
                } else {
                    self.w[base + j]
                };
                self.diag[first + j] = own + self.w[base + j + 1];
                self.off[first + j] = if j + 1 < n {
                    -self.w[base + j + 1] * self.dir[first + j].dot(self.dir[first + j + 1])
                } else {
                    0.0
                };
            }
            if !taut {
                self.diag[first] = 1.0;
                self.off[first] = 0.0;
            }
            for j in 0..n {
                if self.diag[first + j] < TINY {
                    self.diag[first + j] = 1.0;
                    self.rhs[first + j] = 0.0;
                }
            }
            converged &= worst < CHAIN_TOLERANCE * length;
            // Factor A = L·D·Lᵀ over the chain's rows.
            self.pivot[first] = self.diag[first];
            for j in 1..n {
                let f = first + j;
                self.lower[f] = self.off[f - 1] / self.pivot[f - 1];
                self.pivot[f] = self.diag[f] - self.lower[f] * self.off[f - 1];
                if self.pivot[f].abs() < TINY {
                    // Dependent on the rows before (points in a line off a
                    // fixed knot): left out, as the chain's own solve does.
                    self.pivot[f] = 1.0;
                    self.rhs[f] = 0.0;
                }
            }
            for j in 0..n {
                self.z[first + j] = self.rhs[first + j];
            }
            back(&self.pivot, &self.lower, &mut self.z, first, n);
        }
        if converged {
            return true;
        }
        let k = self.set_rows.len();
        for r in 0..k {
            self.coupling(r);
            // Y_r = A⁻¹·B_r over the chains the row touches.
            let (ca, cb) = self.row_chains[self.set_rows[r] as usize];
            let total = self.column.len();
            let y = &mut self.y[r * total..(r + 1) * total];
            y.copy_from_slice(&self.column);
            for c in [ca, cb] {
                let ch = &self.chains[c as usize];
                back(&self.pivot, &self.lower, y, ch.first, ch.segments);
                if ca == cb {
                    break;
                }
            }
        }
        self.active.clear();
        self.active.resize(k, true);
        // After the last round's solve, what it would still leave out is
        // only zeroed (below), as a pull or a slip is not applied.
        for round in 0..=ROUNDS {
            self.schur_solve();
            if !self.leave_out() || round == ROUNDS {
                break;
            }
        }
        for r in 0..k {
            if !self.active[r] {
                self.lambda[r] = 0.0;
            }
        }
        // λ_d = z − Y·λ_c, then each point moved by its rows.
        let total = self.z.len();
        for j in 0..total {
            let mut l = self.z[j];
            for r in 0..k {
                l -= self.y[r * total + j] * self.lambda[r];
            }
            self.rhs[j] = l;
        }
        for k_ in 0..self.set_chains.len() {
            let c = self.set_chains[k_] as usize;
            let (first, n) = (self.chains[c].first, self.chains[c].segments);
            let base = first + k_;
            for i in 1..=n {
                let mut pull = self.rhs[first + i - 1] * self.dir[first + i - 1];
                if i < n {
                    pull -= self.rhs[first + i] * self.dir[first + i];
                }
                self.x[base + i] += self.w[base + i] * pull;
            }
            let impulse = -self.rhs[first] * self.dir[first];
            let knot = self.chains[c].knot;
            self.x[base] += knot.point_motion(impulse);
            self.chains[c].impulse += impulse;
        }
        for r in 0..k {
            let row = self.rows[self.set_rows[r] as usize];
            let (ca, cb) = self.row_chains[self.set_rows[r] as usize];
            for (c, side, sign) in [(ca, row.a, -1.0f32), (cb, row.b, 1.0)] {
                let (p, c_) = self.side_points(c, &side);
                for m in 0..2 {
                    let push = sign * c_[m] * self.lambda[r] * row.normal;
                    self.x[p[m]] += self.w[p[m]] * push;
                }
            }
        }
        false
    }

    /// Leaves out the pushes that would pull (and their grips) and the
    /// grips beyond their push's friction cone; true if any.
    fn leave_out(&mut self) -> bool {
        let k = self.set_rows.len();
        let mut dropped = false;
        for r in 0..k {
            let push = self.push_at[r] as usize;
            if push == r && self.active[r] && self.lambda[r] < 0.0 {
                self.active[r] = false;
                dropped = true;
            }
        }
        for r in 0..k {
            let push = self.push_at[r] as usize;
            if push == r || !self.active[r] {
                continue;
            }
            // Both grips of the push: their λ summed in quadrature.
            let grip: f32 = (0..k)
                .filter(|&c| c != push && self.push_at[c] as usize == push)
                .map(|c| self.lambda[c] * self.lambda[c])
                .sum::<f32>()
                .sqrt();
            if !self.active[push] || grip > self.friction * self.lambda[push] {
                for c in 0..k {
                    if c != push && self.push_at[c] as usize == push {
                        self.active[c] = false;
                    }
                }
                dropped = true;
            }
        }
        dropped
    }

    /// Row `r`'s column of `B` into `column`: distance row j of a chain
    /// pulls point j along −n_j and j + 1 along n_j; side a of the row
    /// pushes along −normal, side b along normal.
    fn coupling(&mut self, r: usize) {
        self.column.iter_mut().for_each(|c| *c = 0.0);
        let row = self.rows[self.set_rows[r] as usize];
        let (ca, cb) = self.row_chains[self.set_rows[r] as usize];
        for (c, side, sign) in [(ca, row.a, -1.0f32), (cb, row.b, 1.0)] {
            let ch = &self.chains[c as usize];
            let (first, n, taut) = (ch.first, ch.segments, ch.taut);
            let q = side.segment as usize;
            let (p, weights) = self.side_points(c, &side);
            for (m, point) in [q, q + 1].into_iter().enumerate() {
                let g = self.w[p[m]] * weights[m] * sign;
                if point >= 1 {
                    self.column[first + point - 1] +=
                        g * self.dir[first + point - 1].dot(row.normal);
                }
                if point < n {
                    self.column[first + point] -= g * self.dir[first + point].dot(row.normal);
                }
            }
            if !taut {
                self.column[first] = 0.0;
            }
        }
    }

    /// The active contacts' λ from their Schur complement.
    fn schur_solve(&mut self) {
        let k = self.set_rows.len();
        let total = self.z.len();
        for r in 0..k {
            let row = self.rows[self.set_rows[r] as usize];
            let (ca, cb) = self.row_chains[self.set_rows[r] as usize];
            let (pa, wa) = self.side_points(ca, &row.a);
            let (pb, wb) = self.side_points(cb, &row.b);
            let at = |x: &[Vec3], p: [usize; 2], w: [f32; 2]| x[p[0]] * w[0] + x[p[1]] * w[1];
            let now = row.normal.dot(at(&self.x, pb, wb) - at(&self.x, pa, wa));
            self.coupling(r);
            let bz: f32 = (0..total).map(|j| self.column[j] * self.z[j]).sum();
            self.right[r] = row.floor - now - bz;
            let (mut own, mut shares) = (0.0, false);
            for c in 0..k {
                let other = self.rows[self.set_rows[c] as usize];
                let (oa, ob) = self.row_chains[self.set_rows[c] as usize];
                let mut cc = 0.0;
                for (pc, side, sign) in [(ca, row.a, -1.0f32), (cb, row.b, 1.0)] {
                    let (p, w) = self.side_points(pc, &side);
                    for (po, oside, osign) in [(oa, other.a, -1.0f32), (ob, other.b, 1.0)] {
                        let (q, v) = self.side_points(po, &oside);
                        for m in 0..2 {
                            for o in 0..2 {
                                if p[m] == q[o] {
                                    shares |= self.push_at[c] != self.push_at[r];
                                    cc += self.w[p[m]]
                                        * sign
                                        * w[m]
                                        * osign
                                        * v[o]
                                        * row.normal.dot(other.normal);
                                }
                            }
                        }
                    }
                }
                let by: f32 = (0..total)
                    .map(|j| self.column[j] * self.y[c * total + j])
                    .sum();
                self.schur[r * k + c] = cc - by;
                if c == r {
                    own = cc;
                }
            }
            let regular = if shares { SHARED_REGULAR } else { REGULAR };
            self.schur[r * k + r] += regular * own;
        }
        for r in 0..k {
            if !self.active[r] {
                for c in 0..k {
                    let one = if c == r { 1.0 } else { 0.0 };
                    self.schur[r * k + c] = one;
                    self.schur[c * k + r] = one;
                }
                self.right[r] = 0.0;
            }
        }
        self.lambda[..k].copy_from_slice(&self.right[..k]);
        for col in 0..k {
            let pivot = self.schur[col * k + col];
            if pivot.abs() < TINY {
                continue;
            }
            for r in col + 1..k {
                let f = self.schur[r * k + col] / pivot;
                if f != 0.0 {
                    for c in col..k {
                        self.schur[r * k + c] -= f * self.schur[col * k + c];
                    }
                    self.lambda[r] -= f * self.lambda[col];
                }
            }
        }
        for r in (0..k).rev() {
            let pivot = self.schur[r * k + r];
            let mut v = self.lambda[r];
            for c in r + 1..k {
                v -= self.schur[r * k + c] * self.lambda[c];
            }
            self.lambda[r] = if pivot.abs() < TINY { 0.0 } else { v / pivot };
        }
    }
}

/// `v[first..first + n] ← A⁻¹·v` with the chain's factors.
fn back(pivot: &[f32], lower: &[f32], v: &mut [f32], first: usize, n: usize) {
    for j in 1..n {
        v[first + j] -= lower[first + j] * v[first + j - 1];
    }
    for j in 0..n {
        v[first + j] /= pivot[first + j];
    }
    for j in (0..n.saturating_sub(1)).rev() {
        v[first + j] -= lower[first + j + 1] * v[first + j + 1];
    }
}
