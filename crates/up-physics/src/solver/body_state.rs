//! The solver's view of a body during one step.

use glam::{Mat3, Quat, Vec3};
use up_geom::norm::Norm;

/// Hot per-body state for the substeps. 128 bytes: 108 used, aligned to a
/// cache line.
///
/// The layout is fixed (`repr(C)`) so that the wide solve reads a body's
/// velocities, masses and pose as blocks of four floats (`block`): what a
/// velocity pass needs is the first four blocks, what a position pass needs
/// block 1 (the inverse mass) and blocks 4 and 5. Aligned, the first four
/// blocks are one cache line and blocks 4 and 5 lie in the next (at 112
/// bytes a state three in four straddled two), and no line holds two
/// bodies' states: on several threads, two threads moving neighbouring
/// bodies (in the dense order, which is not the room's) never write the same line.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct BodyState {
    /// m/s, of the centre of mass.
    pub v: Vec3,
    /// rad/s, world frame.
    pub w: Vec3,
    /// 1 / (mass + added mass); 0 for static or sleeping bodies.
    pub inv_mass: f32,
    /// World-frame inverse inertia at the start of the step; 0 for static or sleeping.
    pub inv_inertia: Mat3,
    /// Displacement of the centre of mass since the step began, m.
    pub dp: Vec3,
    /// Rotation since the step began (world frame, pre-multiplied).
    pub dq: Quat,
    /// Current orientation.
    pub q: Quat,
    /// Set when its velocity ran away (`freeze_runaway`): the body sits out
    /// the rest of the step as static and is quarantined at its end.
    pub runaway: bool,
}

// Two cache lines: a field added past them would move block 5 off its line.
const _: () = assert!(std::mem::size_of::<BodyState>() == 128);

impl BodyState {
    /// The room, and sleeping bodies: immovable.
    pub const STATIC: BodyState = BodyState {
        v: Vec3::ZERO,
        w: Vec3::ZERO,
        dp: Vec3::ZERO,
        dq: Quat::IDENTITY,
        q: Quat::IDENTITY,
        inv_mass: 0.0,
        inv_inertia: Mat3::ZERO,
        runaway: false,
    };

    /// Takes no impulse and has not moved this step: what the passes read of
    /// it is `STATIC`'s, bit for bit (only `q` may differ), so they may use
    /// constants in its place (`coloring::Moving`).
    pub fn is_fixed(&self) -> bool {
        let bits = |v: &[f32]| v.iter().all(|x| x.to_bits() == 0);
        bits(&self.v.to_array())
            && bits(&self.w.to_array())
            && bits(&[self.inv_mass])
            && bits(&self.inv_inertia.to_cols_array())
            && bits(&self.dp.to_array())
            && self.dq.to_array().map(f32::to_bits) == Quat::IDENTITY.to_array().map(f32::to_bits)
    }

    /// Orientation when the step began: `q` with this step's rotation undone.
    pub fn start_rotation(&self) -> Quat {
        (self.dq.inverse() * self.q).unit()
    }

    /// Four consecutive floats of the state, `k` from 0 to 5 (see the layout).
    #[inline(always)]
    pub fn block(&self, k: usize) -> [f32; 4] {
        let (v, w, i, dp, dq) = (self.v, self.w, &self.inv_inertia, self.dp, self.dq);
        match k {
            0 => [v.x, v.y, v.z, w.x],
            1 => [w.y, w.z, self.inv_mass, i.x_axis.x],
            2 => [i.x_axis.y, i.x_axis.z, i.y_axis.x, i.y_axis.y],
            3 => [i.y_axis.z, i.z_axis.x, i.z_axis.y, i.z_axis.z],
            4 => [dp.x, dp.y, dp.z, dq.x],
            5 => [dq.y, dq.z, dq.w, self.q.x],
            _ => panic!("a BodyState has blocks 0 to 5, not {k}"),
        }
    }

    /// Sets the velocities from blocks 0 and 1 (the rest of block 1 is left as it is).
    #[inline(always)]
    pub fn set_velocity_blocks(&mut self, b0: [f32; 4], b1: [f32; 4]) {
        self.v = Vec3::new(b0[0], b0[1], b0[2]);
        self.w = Vec3::new(b0[3], b1[0], b1[1]);
    }

    /// Velocity of a point at `r` from the centre of mass.
    #[inline]
    pub fn point_velocity(&self, r: Vec3) -> Vec3 {
        self.v + self.w.cross(r)
    }

    #[inline]
    pub fn apply_impulse(&mut self, impulse: Vec3, r: Vec3) {
        self.v += self.inv_mass * impulse;
        self.w += self.inv_inertia * r.cross(impulse);
    }

    /// Takes a body whose velocity ran away out of the step: immovable from
    /// here on, so its impulses cannot spread to the bodies it touches.
    pub fn freeze_runaway(&mut self) {
        self.v = Vec3::ZERO;
        self.w = Vec3::ZERO;
        self.inv_mass = 0.0;
        self.inv_inertia = Mat3::ZERO;
        self.runaway = true;
    }

    /// Moves the body by a position impulse `p` (kg·m) at `r` from its centre
    /// of mass, and adds the velocity that move implies over a substep of
    /// `1 / inv_h` s (a joint's projection). An immovable body is left alone,
    /// bit for bit.
    #[inline]
    pub fn apply_position_correction(&mut self, p: Vec3, r: Vec3, inv_h: f32) {
        if self.inv_mass == 0.0 {
            return;
        }
        let dp = self.inv_mass * p;
        let turn = self.inv_inertia * r.cross(p);
        self.dp += dp;
        self.v += inv_h * dp;
        let spin = Quat::from_xyzw(turn.x, turn.y, turn.z, 0.0);
        self.q = add_scaled(self.q, spin * self.q, 0.5).unit();
        self.dq = add_scaled(self.dq, spin * self.dq, 0.5).unit();
        self.w += inv_h * turn;
    }

    /// A ribbon's pull, a position impulse `p` (kg·m) at `r`: moves the body
    /// as `apply_position_correction` does, but turns it only through its
    /// angular velocity, which the contacts' relax pass and friction see
    /// next. Turned directly, a balloon wedged in a pile would creep round
    /// under its ribbon's steady torque, no friction holding it.
    #[inline]
    pub fn apply_pull(&mut self, p: Vec3, r: Vec3, inv_h: f32) {
        if self.inv_mass == 0.0 {
            return;
        }
        let dp = self.inv_mass * p;
        self.dp += dp;
        self.v += inv_h * dp;
        self.w += inv_h * (self.inv_inertia * r.cross(p));
    }

    /// Advances position and orientation by substep `h` (the step's start pose stays put;
    /// `dp`/`dq` carry the motion).
    #[inline]
    pub fn integrate_position(&mut self, h: f32) {
        self.dp += h * self.v;
        let spin = Quat::from_xyzw(self.w.x, self.w.y, self.w.z, 0.0);
        self.q = add_scaled(self.q, spin * self.q, 0.5 * h).unit();
        self.dq = add_scaled(self.dq, spin * self.dq, 0.5 * h).unit();
    }
}

#[inline]
fn add_scaled(q: Quat, dq: Quat, s: f32) -> Quat {
    Quat::from_xyzw(
        q.x + s * dq.x,
        q.y + s * dq.y,
        q.z + s * dq.z,
        q.w + s * dq.w,
    )
}

/// World inverse inertia R·I⁻¹·Rᵀ.
#[inline]
pub(crate) fn world_inverse_inertia(rotation: Quat, inv_inertia_local: Mat3) -> Mat3 {
    let r = Mat3::from_quat(rotation);
    r * inv_inertia_local * r.transpose()
}
