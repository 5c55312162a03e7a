//! One substep of a lane group (`lane_group`): the steps that `solve` lists,
//! on four ribbons at once. Where one ribbon alone would branch (a held
//! point, a converged chain) each lane selects, so every lane computes bit
//! for bit what its ribbon would alone; the balloons' states, the force
//! fields, a grab and the pushes are read and made lane by lane.

use std::cell::RefCell;

use glam::Vec3;

use super::chain::{div, norm, solve_chains, ChainRows, Knots};
use super::lane_group::{set_matrix, LaneGroup};
use super::lane_pushes::NearInput;
use super::solve::{SubstepInput, CHAIN_ITERATIONS, CHAIN_TOLERANCE};
use super::ROOM_FRICTION;
use crate::forces::field::PointSample;
use crate::solver::body_state::BodyState;
use crate::solver::lanes::{prefetch, set, F4, LANES, V4};

/// A segment shorter than this gives the ribbon no direction at a point, m.
const NO_DIRECTION: f32 = 1e-9;
/// The air is sampled at every this many points of a ribbon (and its end),
/// linear between (`sample_air`).
const AIR_SAMPLE_EVERY: usize = 4;

thread_local! {
    /// The chains' solve's working rows, one set a thread: written and read
    /// within one group's solve, they stay in the cache from group to group
    /// (a set a group would add a third to what a substep walks through).
    static ROWS: RefCell<ChainRows> = RefCell::new(ChainRows::default());
}

impl LaneGroup {
    /// One substep of the group's ribbons, reading the balloons' `states`.
    pub(crate) fn substep(&mut self, near: &NearInput) {
        let knots = self.substep_before_solve(near);
        self.solve_and_finish(near, &knots);
    }

    /// The substep up to the chains' solve: the knots placed, the points'
    /// fall and the pushes out of balloons and room (the ribbons' contacts
    /// with each other, `touch`, come between this and `substep_solve`).
    pub(crate) fn substep_before_solve(&mut self, near: &NearInput) -> Knots {
        let (input, states) = (near.input, near.states);
        let h = input.h;
        // Fetched while the knots' balloons are read (a substep walks
        // through every group, more than the cache holds).
        prefetch(&self.velocities);
        prefetch(&self.inv_mass);
        prefetch(&self.start);
        let knots = self.place_knots(states);
        self.fall(input, h);
        self.carry_grabbed(h);
        self.push_out_of_balloons(near);
        self.push_out_of_room(input.triangles, self.substeps == 0);
        knots
    }

    /// The chains' solve, after the ribbons' contacts (`touch`) took their
    /// first turn; `substep_finish` follows their last.
    pub(crate) fn substep_solve(&mut self, near: &NearInput) {
        // The same knots as before the solve's part (the bodies have not
        // moved, and a knot is held: no contact moves it), placed again
        // rather than kept across the ribbons' contacts.
        let knots = self.place_knots(near.states);
        self.impulse = V4::ZERO;
        self.solve_lengths(&knots);
        self.knots = knots;
        self.pushed = false;
    }

    /// The chains solved again, if a contact moved the group's points since
    /// the last solve: from where that solve left them, knots included, its
    /// impulses on the balloons added to the substep's.
    pub(crate) fn substep_solve_again(&mut self) {
        if self.pushed {
            let knots = self.knots;
            self.solve_lengths(&knots);
            self.pushed = false;
        }
    }

    /// The rest of the substep, after the contacts' second turn: the room's
    /// push again and the velocities.
    pub(crate) fn substep_finish(&mut self, near: &NearInput) {
        self.finish(near);
    }

    /// `substep_solve` and `substep_finish` with the knots as
    /// `substep_before_solve` placed them.
    fn solve_and_finish(&mut self, near: &NearInput, knots: &Knots) {
        self.impulse = V4::ZERO;
        self.solve_lengths(knots);
        self.finish(near);
    }

    /// The chains brought back to their lengths.
    fn solve_lengths(&mut self, knots: &Knots) {
        let unconverged = self.solve_chains(knots);
        if unconverged.any() {
            self.follow_the_leader(unconverged);
        }
    }

    /// The room's push after the solve, the step's impulse and the
    /// velocities.
    fn finish(&mut self, near: &NearInput) {
        let (input, states) = (near.input, near.states);
        let h = input.h;
        self.push_out_of_room(input.triangles, false);
        self.held_lanes = 0;
        self.step_impulse = self.step_impulse + self.impulse;
        self.substeps += 1;
        self.h = h;
        self.update_velocities(h, states);
    }

    /// Each knot where its balloon is now; the balloons as the chains' solve
    /// sees them.
    fn place_knots(&mut self, states: &[BodyState]) -> Knots {
        let mut knots = Knots::default();
        for (l, lane) in self.lanes[..self.live].iter().enumerate() {
            let s = &states[lane.state as usize];
            let arm = s.dq * lane.arm0;
            self.points[0].set_lane(l, lane.origin + s.dp + arm);
            knots.arm.set_lane(l, arm);
            set(&mut knots.inv_mass, l, s.inv_mass);
            set_matrix(&mut knots.inv_inertia, l, &s.inv_inertia);
        }
        self.arm = knots.arm;
        knots
    }

    /// Gravity, the fields' forces and drag on each point (drag implicit,
    /// across and along the ribbon apart, on the velocity relative to the
    /// air), then its move over the substep; `start` keeps where each point
    /// began it (in the same pass). In still air, or where no lane's point
    /// feels any, the still-air arithmetic runs unchanged.
    fn fall(&mut self, input: &SubstepInput, h: f32) {
        let n = self.points.len() - 1;
        self.start[0] = self.points[0];
        // Points past `active` rest where they lie, still.
        let last = self.active - 1;
        if self.substeps == 0 {
            if let Some(air) = input.air {
                self.sample_air(air);
            }
        }
        self.rest_hold = ROOM_FRICTION * up_geom::norm::Norm::norm(input.gravity) * h * h;
        let fields = (!input.fields.is_empty()).then_some(input.fields);
        let (h4, one) = (F4::splat(h), F4::ONE);
        let hg = h * input.gravity;
        let hg = V4::new(F4::splat(hg.x), F4::splat(hg.y), F4::splat(hg.z));
        for i in 1..=last {
            self.start[i] = self.points[i];
            let inv_mass = self.inv_mass[i];
            let movable = inv_mass.simd_ne(F4::ZERO);
            let mut v = self.velocities[i] + hg;
            if let Some(fields) = fields {
                let force = self.field_forces(fields, i, input.time);
                v = v + (h4 * inv_mass) * force;
            }
            // Relative to the air, moved with it again after the drag.
            let air = if self.windy { self.air[i] } else { V4::ZERO };
            if self.windy {
                v = v - air;
            }
            // Along the ribbon: from the point before to the one after.
            let along = self.points[(i + 1).min(n)] - self.points[i - 1];
            let len = norm(along);
            let t = V4::select(
                len.simd_gt(F4::splat(NO_DIRECTION)),
                div(along, len),
                V4::ZERO,
            );
            let v_along = v.dot(t) * t;
            let v_across = v - v_along;
            let [k_across, k_along, viscous] = if i == n { self.drag_end } else { self.drag_mid };
            let w = h4 * inv_mass;
            let v_along = div(v_along, one + w * k_along * norm(v_along));
            let across = k_across * norm(v_across) + viscous;
            let v_across = div(v_across, one + w * across);
            let mut v = v_along + v_across;
            if self.windy {
                v = v + air;
            }
            let moved = self.points[i] + h4 * v;
            self.velocities[i] = V4::select(movable, v, self.velocities[i]);
            self.points[i] = V4::select(movable, moved, self.points[i]);
        }
    }

    /// The air's velocity at each point of each live lane (spare lanes'
    /// zero), and `windy` if any is not zero: sampled at the knot, every
    /// `AIR_SAMPLE_EVERY`th point and the end, linear between, since a
    /// jet's air changes over decimetres and a ribbon's points are a few
    /// centimetres apart; a uniform stream is the same at every point.
    fn sample_air(&mut self, air: &crate::air::AirNow) {
        let n = self.points.len() - 1;
        let mut fastest = [0.0f32; LANES];
        let mut windy = false;
        for (l, fastest) in fastest.iter_mut().enumerate() {
            if l >= self.live {
                self.air.iter_mut().for_each(|u| u.set_lane(l, Vec3::ZERO));
                continue;
            }
            let (mut before, mut u_before) = (0, air.velocity_at(self.points[0].lane(l)));
            self.air[0].set_lane(l, u_before);
            while before < n {
                let after = (before + AIR_SAMPLE_EVERY).min(n);
                let u_after = air.velocity_at(self.points[after].lane(l));
                for k in before + 1..after {
                    let t = (k - before) as f32 / (after - before) as f32;
                    self.air[k].set_lane(l, u_before + (u_after - u_before) * t);
                }
                self.air[after].set_lane(l, u_after);
                (before, u_before) = (after, u_after);
            }
            for u in &self.air {
                let here = u.lane(l);
                windy |= here != Vec3::ZERO;
                *fastest = fastest.max(up_geom::norm::Norm::norm(here));
            }
        }
        self.windy = windy;
        self.air_speed = F4::new(fastest);
    }

    /// The world's force fields on point `i` of each ribbon (none on a held
    /// point), N.
    fn field_forces(&self, fields: &crate::forces::field::ForceFields, i: usize, time: f64) -> V4 {
        let n = self.points.len() - 1;
        let drag = if i == n { self.drag_end } else { self.drag_mid };
        let mut force = V4::ZERO;
        for (l, lane) in self.lanes[..self.live].iter().enumerate() {
            let inv_mass = self.inv_mass[i].as_array()[l];
            if inv_mass == 0.0 {
                continue;
            }
            let f = fields.force_on_point(&PointSample {
                position: self.points[i].lane(l),
                velocity: self.velocities[i].lane(l),
                mass: 1.0 / inv_mass,
                end: i == n,
                drag_factor: drag[0].as_array()[l],
                user_data: lane.user_data,
                time,
            });
            force.set_lane(l, f);
        }
        force
    }

    /// A grabbed point carried at the speed that reaches its target by the
    /// step's end.
    fn carry_grabbed(&mut self, h: f32) {
        for (l, lane) in self.lanes[..self.live].iter().enumerate() {
            let Some((k, target)) = lane.grab else {
                continue;
            };
            let start = self.start[k].lane(l);
            let to = target - start;
            let len = up_geom::norm::Norm::norm(to);
            let reach = (lane.grab_speed * h).min(len);
            if len > 0.0 {
                self.points[k].set_lane(l, start + to * (reach / len));
            }
        }
    }

    /// The chains, knots included, brought back to their lengths: direct
    /// solves, each lane until its solve started within the tolerance, at
    /// most `CHAIN_ITERATIONS`, their impulses on the knots added to
    /// `impulse`. Returns the lanes that never did.
    fn solve_chains(&mut self, knots: &Knots) -> F4 {
        let tolerance = F4::splat(CHAIN_TOLERANCE) * self.segment_length;
        let mut moving = self.live_mask;
        if self.held_lanes != 0 {
            // Those lanes are solved with their contacts (`touch::held`).
            let held = self.held_lanes;
            let others = std::array::from_fn(|l| {
                if held & (1 << l) != 0 {
                    0.0
                } else {
                    f32::from_bits(!0)
                }
            });
            moving &= F4::new(others);
            if !moving.any() {
                return moving;
            }
        }
        // Lanes with a resting tail, and the pull their first resting point
        // takes from the segment before it over this solve, kg·m.
        let resting = (0..LANES).filter(|&l| self.rest_from[l] < self.points.len());
        let resting = resting.fold(0u32, |bits, l| bits | 1 << l);
        let mut pull = [0.0f32; LANES];
        ROWS.with_borrow_mut(|rows| {
            // The chains end at the first point resting in every lane (held).
            let active = self.active;
            rows.resize(active - 1);
            for _ in 0..CHAIN_ITERATIONS {
                let (impulse, worst) = solve_chains(
                    &mut self.points[..active],
                    &self.inv_mass[..active],
                    self.segment_length,
                    knots,
                    moving,
                    rows,
                );
                let solved = moving.to_bitmask();
                for (l, pull) in pull.iter_mut().enumerate() {
                    if resting & solved & (1 << l) != 0 {
                        let lambda = rows.lambda(self.rest_from[l] - 1).as_array()[l];
                        *pull += lambda.abs();
                    }
                }
                // The knot moves with its body's share before the next solve.
                let knot = self.points[0] + knots.point_motion(impulse);
                self.points[0] = V4::select(moving, knot, self.points[0]);
                self.impulse = V4::select(moving, self.impulse + impulse, self.impulse);
                moving &= !worst.simd_lt(tolerance);
                if !moving.any() {
                    break;
                }
            }
        });
        // A resting tail pulled (or pushed) harder than the room's friction
        // holds its first point moves again from here on: the points it held
        // back then follow in the next solve, with their friction.
        let pulled = (0..LANES).filter(|&l| {
            let first = self.rest_from[l];
            resting & (1 << l) != 0
                && pull[l] > self.rest_hold / self.free_inv_mass[first].as_array()[l]
        });
        let pulled = pulled.fold(0u32, |bits, l| bits | 1 << l);
        if pulled != 0 {
            self.end_rest(pulled);
        }
        moving
    }

    /// In the lanes of `lanes`, each point pulled after the one before it,
    /// from the knot out, to at most the segment length (Müller, Kim,
    /// Chentanez, "Fast simulation of inextensible hair and fur", 2012): for
    /// a ribbon jerked harder than the solves converge on in a substep (a
    /// balloon thrown at 25 m/s with a weight on its ribbon), which bounds
    /// its length at the price of the momentum the solves had not yet handed
    /// round. A held point stays.
    fn follow_the_leader(&mut self, lanes: F4) {
        let length = self.segment_length;
        for i in 1..self.active {
            let d = self.points[i] - self.points[i - 1];
            let len = norm(d);
            let pulled = self.points[i - 1] + (length / len) * d;
            let far = len.simd_gt(length) & self.inv_mass[i].simd_gt(F4::ZERO) & lanes;
            self.points[i] = V4::select(far, pulled, self.points[i]);
        }
    }

    /// Each point's velocity: what it moved over the substep, less what a
    /// balloon's push gave it toward the outside (no bounce: a ribbon against
    /// latex is inelastic); the knot's, its balloon's at the knot.
    fn update_velocities(&mut self, h: f32, states: &[BodyState]) {
        let inv_h = F4::splat(1.0 / h);
        // Those past `active` rest: still, as they were.
        for i in 1..self.active {
            let mut v = inv_h * (self.points[i] - self.start[i]);
            if self.touched {
                let normal = self.touch_normal[i];
                let off = (v - self.touch_velocity[i]).dot(normal);
                v = V4::select(off.simd_gt(F4::ZERO), v - off * normal, v);
            }
            self.velocities[i] = v;
        }
        for (l, lane) in self.lanes[..self.live].iter().enumerate() {
            let arm: Vec3 = self.arm.lane(l);
            let v = states[lane.state as usize].point_velocity(arm);
            self.velocities[0].set_lane(l, v);
        }
    }
}
