//! Joint constraints, solved at position level once per substep (XPBD with
//! one iteration a substep, as in Macklin et al. 2019, "Small steps in
//! physics simulation"): after the substep has moved the bodies, each joint
//! moves its ends back to its length and hands the velocity that move implies
//! to the bodies. A position projection weighs each end by its inverse mass,
//! so a very light end and a heavy one meet at the length in one pass, where
//! a velocity solve would leave the light end stretched; the contacts' relax
//! pass then sees the corrected velocities in the same substep.
//!
//! Joints are coloured in a graph of their own (no two joints of a colour
//! move the same body), since they run in a pass of their own, and solved
//! colour after colour: the order, and so the result, does not depend on how
//! a colour's joints are shared out among threads.

use glam::Vec3;
use up_geom::norm::Norm;

use super::body_state::BodyState;
use crate::joint::DistanceLimit;

/// A distance joint ready for this step's substeps.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedJoint {
    /// The joint's slot, to hand its tension back.
    pub slot: u32,
    /// Solver states of the two ends (the room's state for a fixed end).
    pub states: [u32; 2],
    /// Where each end's body's centre of mass was at the step's start, or
    /// the fixed point, world frame, m.
    pub origin: [Vec3; 2],
    /// Each end's point from its centre of mass, world frame at the step's
    /// start (zero for a fixed end), m.
    pub arm: [Vec3; 2],
    pub length: f32,
    pub limit: DistanceLimit,
    /// m/N.
    pub compliance: f32,
    /// Tension at the end of the last substep, N.
    pub tension: f32,
}

impl PreparedJoint {
    /// Where end `k` is now, and its arm from its centre of mass.
    fn end(&self, k: usize, s: &BodyState) -> (Vec3, Vec3) {
        let r = s.dq * self.arm[k];
        (self.origin[k] + s.dp + r, r)
    }

    /// Moves both ends back to the joint's length in one projection over a
    /// substep of `h` s; keeps the tension it took.
    pub fn project(&mut self, states: &mut [BodyState], h: f32) {
        let (ia, ib) = (self.states[0] as usize, self.states[1] as usize);
        let (pa, ra) = self.end(0, &states[ia]);
        let (pb, rb) = self.end(1, &states[ib]);
        let d = pa - pb;
        let distance = d.norm();
        let stretch = distance - self.length;
        self.tension = 0.0;
        if distance <= f32::EPSILON || (self.limit == DistanceLimit::Rope && stretch <= 0.0) {
            return;
        }
        let n = d / distance;
        let weight = |s: &BodyState, r: Vec3| {
            let rn = r.cross(n);
            s.inv_mass + rn.dot(s.inv_inertia * rn)
        };
        let alpha = self.compliance / (h * h);
        let w = weight(&states[ia], ra) + weight(&states[ib], rb) + alpha;
        if w <= 0.0 {
            return;
        }
        // One XPBD iteration from λ = 0: Δλ = −C / (w_a + w_b + α/h²).
        let lambda = -stretch / w;
        let correction = lambda * n;
        let inv_h = 1.0 / h;
        states[ia].apply_position_correction(correction, ra, inv_h);
        states[ib].apply_position_correction(-correction, rb, inv_h);
        // λ is a position impulse over h²: the force, pulling the ends together.
        self.tension = -lambda * inv_h * inv_h;
    }
}

/// Colours available before the serial rest (bits of a `u64`).
const JOINT_COLORS: u32 = 64;

/// Greedy colouring of the joints by the moving bodies they touch; its
/// buffers are kept from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct JointColouring {
    /// Per state: the colours its joints took so far.
    used: Vec<u64>,
    /// Per joint, in the given order: its colour (64 colours; past them, one
    /// serial colour after the rest).
    colour: Vec<u32>,
    sorted: Vec<PreparedJoint>,
}

impl JointColouring {
    /// Colours `joints` and sorts them colour after colour, each colour in
    /// the given order.
    pub fn sort(&mut self, joints: &mut Vec<PreparedJoint>, states: &[BodyState]) {
        if joints.is_empty() {
            return;
        }
        self.colour(joints, states);
        // A counting sort: stable, so each colour keeps the given order.
        let mut next = [0usize; JOINT_COLORS as usize + 2];
        for &c in &self.colour {
            next[c as usize + 1] += 1;
        }
        for c in 1..next.len() {
            next[c] += next[c - 1];
        }
        self.sorted.clear();
        self.sorted.resize(joints.len(), joints[0]);
        for (joint, &c) in joints.iter().zip(&self.colour) {
            self.sorted[next[c as usize]] = *joint;
            next[c as usize] += 1;
        }
        std::mem::swap(joints, &mut self.sorted);
    }

    fn colour(&mut self, joints: &[PreparedJoint], states: &[BodyState]) {
        self.used.clear();
        self.used.resize(states.len(), 0);
        self.colour.clear();
        for j in joints {
            let moving = |k: usize| {
                let i = j.states[k] as usize;
                (!states[i].is_fixed()).then_some(i)
            };
            let (a, b) = (moving(0), moving(1));
            let taken = a.map_or(0, |i| self.used[i]) | b.map_or(0, |i| self.used[i]);
            let colour = (!taken).trailing_zeros().min(JOINT_COLORS);
            if colour < JOINT_COLORS {
                for i in [a, b].into_iter().flatten() {
                    self.used[i] |= 1 << colour;
                }
            }
            self.colour.push(colour);
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::{Mat3, Quat};

    use super::*;

    fn body(inv_mass: f32) -> BodyState {
        BodyState {
            inv_mass,
            inv_inertia: Mat3::from_diagonal(Vec3::splat(inv_mass * 10.0)),
            ..BodyState::STATIC
        }
    }

    fn joint(limit: DistanceLimit, states: [u32; 2], origin: [Vec3; 2]) -> PreparedJoint {
        PreparedJoint {
            slot: 0,
            states,
            origin,
            arm: [Vec3::ZERO; 2],
            length: 1.0,
            limit,
            compliance: 0.0,
            tension: 0.0,
        }
    }

    #[test]
    fn a_light_end_and_a_heavy_one_meet_at_the_length_in_one_projection() {
        // 25 mg against 14 g: the mass ratio of a ribbon's particle and a balloon.
        let mut states = vec![body(1.0 / 0.014), body(1.0 / 25e-6)];
        let mut j = joint(
            DistanceLimit::Rod,
            [0, 1],
            [Vec3::ZERO, Vec3::new(0.0, -1.2, 0.0)],
        );
        j.project(&mut states, 1.0 / 240.0);
        let a = j.origin[0] + states[0].dp;
        let b = j.origin[1] + states[1].dp;
        assert!(
            ((a - b).length() - 1.0).abs() < 1e-5,
            "{}",
            (a - b).length()
        );
        // The light end did nearly all the moving, momentum is conserved.
        let momentum = states[0].v / states[0].inv_mass + states[1].v / states[1].inv_mass;
        assert!(momentum.length() < 1e-6, "{momentum}");
        assert!(states[1].dp.length() > 500.0 * states[0].dp.length());
    }

    #[test]
    fn a_slack_rope_pulls_nothing_and_a_rod_pushes() {
        let origin = [Vec3::ZERO, Vec3::new(0.0, -0.5, 0.0)];
        let mut states = vec![body(1.0), BodyState::STATIC];
        let mut rope = joint(DistanceLimit::Rope, [0, 1], origin);
        rope.project(&mut states, 0.01);
        assert_eq!(states[0].dp, Vec3::ZERO);
        assert_eq!(rope.tension, 0.0);
        let mut rod = joint(DistanceLimit::Rod, [0, 1], origin);
        rod.project(&mut states, 0.01);
        assert!((states[0].dp.y - 0.5).abs() < 1e-6, "{}", states[0].dp);
        assert!(rod.tension < 0.0, "a pushing rod is in compression");
        // The fixed end did not move, nor turn.
        assert_eq!(states[1].dp, Vec3::ZERO);
        assert_eq!(states[1].dq, Quat::IDENTITY);
    }

    #[test]
    fn joints_of_one_colour_share_no_moving_body() {
        // A chain 0-1-2-3 tied to the room (state 4) at both ends.
        let mut states = vec![body(1.0); 4];
        states.push(BodyState::STATIC);
        let pairs = [[4, 0], [0, 1], [1, 2], [2, 3], [3, 4]];
        let joints: Vec<_> = pairs
            .iter()
            .map(|&s| joint(DistanceLimit::Rod, s, [Vec3::ZERO; 2]))
            .collect();
        let mut colouring = JointColouring::default();
        colouring.colour(&joints, &states);
        assert_eq!(colouring.colour, vec![0, 1, 0, 1, 0]);
        let mut sorted = joints.clone();
        colouring.sort(&mut sorted, &states);
        let order: Vec<[u32; 2]> = sorted.iter().map(|j| j.states).collect();
        assert_eq!(order, vec![[4, 0], [1, 2], [3, 4], [0, 1], [2, 3]]);
    }
}
