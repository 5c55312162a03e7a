//! Friction as rows of the linked chains' solve (`held`): each contact's
//! slide over the substep held at zero along the directions across its
//! normal, the friction's λ kept within μ times the contact's push, the
//! passes' and the solve's summed over the substep (Coulomb's cone on the
//! accumulated totals, as an impulse solver bounds friction by the normal
//! impulse's running sum). Solved with the normal rows and the chains, so
//! that the chains' pull along a ribbon wrapped round another, which is a
//! slide, meets the grip in the same solve (a grip by the passes alone is
//! undone by the solve that follows them).

use super::super::Touching;
use super::{Held, HeldSolve, SetRow, ROUNDS};

impl HeldSolve {
    /// The set's rows from its contacts: each normal followed by its
    /// friction rows (none without friction), and their pairs' push and
    /// friction so far this substep.
    pub(super) fn gather_rows(&mut self, pairs: &[Touching]) {
        self.set.clear();
        self.before.clear();
        let grips = if self.friction > 0.0 { 2 } else { 0 };
        for k in 0..self.set_rows.len() {
            let r = self.set_rows[k] as usize;
            let row = self.rows[r];
            let chains = self.row_chains[r];
            let normal = self.set.len();
            let pair = &pairs[row.pair as usize];
            self.set.push(SetRow {
                a: row.a,
                b: row.b,
                dir: row.normal,
                floor: row.floor,
                chains,
                source: k as u32,
                friction: false,
            });
            self.before.push([
                pair.pushed,
                pair.gripped.dot(row.tangents[0]),
                pair.gripped.dot(row.tangents[1]),
            ]);
            for m in 0..grips {
                self.set.push(SetRow {
                    dir: row.tangents[m],
                    floor: row.goals[m],
                    friction: true,
                    ..self.set[normal]
                });
                self.before.push([0.0; 3]);
            }
        }
        self.total.clear();
        self.total.resize(self.set.len(), 0.0);
    }

    /// The friction rows after normal row `r`.
    fn grips(&self, r: usize) -> usize {
        let mut m = 0;
        while r + 1 + m < self.set.len() && self.set[r + 1 + m].friction {
            m += 1;
        }
        m
    }

    /// The set's λ: first without friction, which contacts push (those
    /// that would pull left out), then friction within its cone, the
    /// contacts that push kept (friction free from the start would let a
    /// contact's pull be taken for friction's and leave it out).
    pub(super) fn solve_rows(&mut self) {
        let k = self.set.len();
        self.state.clear();
        for r in 0..k {
            let held = if self.set[r].friction {
                Held::Fixed(0.0)
            } else {
                Held::Free
            };
            self.state.push(held);
        }
        for _ in 0..ROUNDS {
            self.schur_solve();
            let mut dropped = false;
            for r in 0..k {
                if !self.set[r].friction && self.state[r] == Held::Free && self.lambda[r] < 0.0 {
                    self.state[r] = Held::Fixed(0.0);
                    dropped = true;
                }
            }
            if !dropped {
                break;
            }
        }
        if !self.set.iter().any(|r| r.friction) {
            return;
        }
        for r in 0..k {
            if self.set[r].friction {
                self.state[r] = Held::Free;
            }
        }
        for _ in 0..ROUNDS {
            self.schur_solve();
            if !self.settle_rows() {
                break;
            }
        }
    }

    /// After a round's solve: normal rows that pull left out, friction
    /// outside its cone held on the cone's edge. True if a row changed.
    pub(super) fn settle_rows(&mut self) -> bool {
        let mut changed = false;
        let k = self.set.len();
        let mut r = 0;
        while r < k {
            if self.state[r] == Held::Free && self.lambda[r] < 0.0 {
                self.state[r] = Held::Fixed(0.0);
                self.lambda[r] = 0.0;
                changed = true;
            }
            let grips = self.grips(r);
            if grips > 0 {
                let before = self.before[r];
                let push = (before[0] + self.total[r] + self.lambda[r]).max(0.0);
                let limit = self.friction * push;
                let sum = |m: usize| before[1 + m] + self.total[r + 1 + m];
                let mut want = [0.0f32; 2];
                for m in 0..grips {
                    want[m] = sum(m) + self.lambda[r + 1 + m];
                }
                let size = (want[0] * want[0] + want[1] * want[1]).sqrt();
                let fixed = (0..grips).any(|m| self.state[r + 1 + m] != Held::Free);
                if size > limit * (1.0 + 1e-4) || fixed {
                    let scale = if size > 0.0 {
                        (limit / size).min(1.0)
                    } else {
                        0.0
                    };
                    for m in 0..grips {
                        let v = want[m] * scale - sum(m);
                        let moved = match self.state[r + 1 + m] {
                            Held::Fixed(u) => (u - v).abs(),
                            Held::Free => f32::MAX,
                        };
                        if moved > 1e-3 * limit.max(1e-12) {
                            changed = true;
                        }
                        self.state[r + 1 + m] = Held::Fixed(v);
                    }
                }
            }
            r += 1 + grips;
        }
        changed
    }

    /// The solve's pushes and friction added to their pairs' totals.
    pub(super) fn give_back(&mut self, pairs: &mut [Touching]) {
        for r in 0..self.set.len() {
            if self.set[r].friction {
                continue;
            }
            let row = self.rows[self.set_rows[self.set[r].source as usize] as usize];
            let pair = &mut pairs[row.pair as usize];
            pair.pushed += self.total[r];
            for m in 0..self.grips(r) {
                pair.gripped += row.tangents[m] * self.total[r + 1 + m];
            }
        }
    }
}
