//! The contact rows' Schur complement in the linked chains' solve
//! (`held`): `C − Bᵀ·A⁻¹·B` and its right side built once an iteration,
//! then solved in rounds, rows held at a value (a contact left out, friction
//! on its cone's edge) moved to the right side.

use super::super::super::chain::TINY;
use super::{Held, HeldSolve, REGULAR};
use glam::Vec3;

impl HeldSolve {
    /// The rows' Schur complement and right side for the iterate's rounds.
    pub(super) fn build_schur(&mut self) {
        let k = self.set.len();
        let total = self.z.len();
        for r in 0..k {
            let row = self.set[r];
            let (ca, cb) = row.chains;
            let (pa, wa) = self.side_points(ca, &row.a);
            let (pb, wb) = self.side_points(cb, &row.b);
            let at = |x: &[Vec3], p: [usize; 2], w: [f32; 2]| x[p[0]] * w[0] + x[p[1]] * w[1];
            let now = row.dir.dot(at(&self.x, pb, wb) - at(&self.x, pa, wa));
            self.coupling(r);
            let bz: f32 = (0..total).map(|j| self.column[j] * self.z[j]).sum();
            self.right[r] = row.floor - now - bz;
            for c in 0..k {
                let other = self.set[c];
                let (oa, ob) = other.chains;
                let mut cc = 0.0;
                for (pc, side, sign) in [(ca, row.a, -1.0f32), (cb, row.b, 1.0)] {
                    let (p, w) = self.side_points(pc, &side);
                    for (po, oside, osign) in [(oa, other.a, -1.0f32), (ob, other.b, 1.0)] {
                        let (q, v) = self.side_points(po, &oside);
                        for m in 0..2 {
                            for o in 0..2 {
                                if p[m] == q[o] {
                                    cc += self.w[p[m]]
                                        * sign
                                        * w[m]
                                        * osign
                                        * v[o]
                                        * row.dir.dot(other.dir);
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
                    self.schur[r * k + c] += REGULAR * cc;
                }
            }
        }
        self.schur_built.clear();
        self.schur_built.extend_from_slice(&self.schur);
        self.right_built.clear();
        self.right_built.extend_from_slice(&self.right);
    }

    /// The rows' λ from their Schur complement (`build_schur`), those
    /// held at a value (`state`) kept there.
    pub(super) fn schur_solve(&mut self) {
        let k = self.set.len();
        self.schur.copy_from_slice(&self.schur_built);
        self.right.copy_from_slice(&self.right_built);
        // A row held at a value moves its column to the right side.
        for r in 0..k {
            if let Held::Fixed(v) = self.state[r] {
                for c in 0..k {
                    if c != r {
                        self.right[c] -= self.schur[c * k + r] * v;
                    }
                }
            }
        }
        for r in 0..k {
            if let Held::Fixed(v) = self.state[r] {
                for c in 0..k {
                    let one = if c == r { 1.0 } else { 0.0 };
                    self.schur[r * k + c] = one;
                    self.schur[c * k + r] = one;
                }
                self.right[r] = v;
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
