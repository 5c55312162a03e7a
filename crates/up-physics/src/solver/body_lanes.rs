//! A group's four bodies on one side, gathered into SIMD lanes and
//! scattered back: what the velocity passes (`Velocities`), the refresh
//! (`Poses`) and the position passes (`Displacements`) read of them.

use super::body_state::BodyState;
use super::lanes::{F4, LANES, M4, Q4, V4};

/// Block `k` of four states, transposed: one lane per state (`BodyState::block`).
/// Written out lane by lane, not with `array::map`, whose closure the
/// compiler left out of line: `k` then stayed a variable and each block went
/// through the stack as four scalar stores read back as one vector.
#[inline(always)]
fn gather_block(s: &[&BodyState; LANES], k: usize) -> [F4; 4] {
    let [s0, s1, s2, s3] = s;
    F4::transpose([
        F4::new(s0.block(k)),
        F4::new(s1.block(k)),
        F4::new(s2.block(k)),
        F4::new(s3.block(k)),
    ])
}

/// The four bodies on one side of a group, as the velocity passes need them.
pub(crate) struct Velocities {
    pub(super) v: V4,
    pub(super) w: V4,
    pub(super) inv_mass: F4,
    pub(super) inv_inertia: M4,
    /// The rest of block 1, written back as it was read.
    pub(super) inertia_xx: F4,
}

impl Velocities {
    /// Four fixed bodies (`BodyState::is_fixed`), as `gather` reads them.
    pub const FIXED: Velocities = Velocities {
        v: V4::ZERO,
        w: V4::ZERO,
        inv_mass: F4::ZERO,
        inv_inertia: M4::ZERO,
        inertia_xx: F4::ZERO,
    };

    #[inline]
    pub fn gather(s: [&BodyState; LANES]) -> Velocities {
        let [vx, vy, vz, wx] = gather_block(&s, 0);
        let [wy, wz, inv_mass, ixx] = gather_block(&s, 1);
        let [ixy, ixz, iyx, iyy] = gather_block(&s, 2);
        let [iyz, izx, izy, izz] = gather_block(&s, 3);
        Velocities {
            v: V4::new(vx, vy, vz),
            w: V4::new(wx, wy, wz),
            inv_mass,
            inv_inertia: M4 {
                x_axis: V4::new(ixx, ixy, ixz),
                y_axis: V4::new(iyx, iyy, iyz),
                z_axis: V4::new(izx, izy, izz),
            },
            inertia_xx: ixx,
        }
    }

    /// What writes a lane's velocities back to its body.
    #[inline]
    pub fn scatter(&self) -> impl Fn(usize, &mut BodyState) {
        let b0 = F4::transpose([self.v.x, self.v.y, self.v.z, self.w.x]);
        let b1 = F4::transpose([self.w.y, self.w.z, self.inv_mass, self.inertia_xx]);
        move |lane, s| s.set_velocity_blocks(b0[lane].to_array(), b1[lane].to_array())
    }

    /// Velocity of a point at `r` from the centre of mass.
    #[inline]
    pub(super) fn point_velocity(&self, r: V4) -> V4 {
        self.v + self.w.cross(r)
    }

    #[inline]
    pub(super) fn apply_impulse(&mut self, impulse: V4, r: V4) {
        self.v = self.v + self.inv_mass * impulse;
        self.w = self.w + self.inv_inertia.mul(r.cross(impulse));
    }
}

/// The four bodies on one side of a group, where they are now.
pub(crate) struct Poses {
    pub(super) dp: V4,
    pub(super) dq: Q4,
}

impl Poses {
    /// Four fixed bodies, as `gather` reads them.
    pub const FIXED: Poses = Poses {
        dp: V4::ZERO,
        dq: Q4::IDENTITY,
    };

    #[inline]
    pub fn gather(s: [&BodyState; LANES]) -> Poses {
        let [dpx, dpy, dpz, qx] = gather_block(&s, 4);
        let [qy, qz, qw, _] = gather_block(&s, 5);
        Poses {
            dp: V4::new(dpx, dpy, dpz),
            dq: Q4 {
                xyz: V4::new(qx, qy, qz),
                w: qw,
            },
        }
    }
}

/// The four bodies on one side of a group, as the position passes (which
/// only move them) need them.
pub(crate) struct Displacements {
    pub(super) dp: V4,
    pub(super) inv_mass: F4,
}

impl Displacements {
    /// Four fixed bodies, as `gather` reads them.
    pub const FIXED: Displacements = Displacements {
        dp: V4::ZERO,
        inv_mass: F4::ZERO,
    };

    #[inline]
    pub fn gather(s: [&BodyState; LANES]) -> Displacements {
        let [_, _, inv_mass, _] = gather_block(&s, 1);
        let [x, y, z, _] = gather_block(&s, 4);
        Displacements {
            dp: V4::new(x, y, z),
            inv_mass,
        }
    }

    /// What writes a lane's displacement back to its body.
    #[inline]
    pub fn scatter(&self) -> impl Fn(usize, &mut BodyState) + '_ {
        |lane, s| s.dp = self.dp.lane(lane)
    }
}
