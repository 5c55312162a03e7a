//! The linked set's solve proper (`HeldSolve::iterate`): each chain's
//! tridiagonal factored, the contacts' rows through their Schur complement,
//! the pushes that would pull and the grips beyond their cone left out
//! round by round, and the points moved by what the rows give.

use glam::Vec3;

use super::super::super::chain::{SLACK, TINY};
use super::super::super::solve::CHAIN_TOLERANCE;
use super::{HeldSolve, Side};

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

impl HeldSolve {
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
    pub(super) fn iterate(&mut self) -> bool {
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
