//! Contact constraints: prepare, warm start, solve (with and without bias),
//! restitution, and storing impulses for the next step.
//!
//! Each contact point holds a non-penetration row along the normal and two
//! friction rows along tangents, clamped to the Coulomb disk μ·λn. Anchors
//! are fixed at the start of the step; the current separation is updated
//! from the bodies' motion since then (Box2D v3), so substeps never rerun
//! collision detection.

use glam::Vec3;

use super::body_state::BodyState;
use super::softness::Softness;
use crate::contact::{ContactPoint, StoredImpulse};

/// 168 bytes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ContactConstraint {
    /// Solver state indices (the room is the last, static state).
    pub a: u32,
    pub b: u32,
    pub normal: Vec3,
    pub tangent: [Vec3; 2],
    /// Centres of the touching spheres from each body's centre of mass, world
    /// frame, at step start (for the room, B's is the point on the triangle).
    /// Tracking centres, not surface points, keeps the separation exact when a
    /// balloon spins: a point on a spinning sphere rolls away from the contact.
    pub r_a: Vec3,
    pub r_b: Vec3,
    /// From each sphere's centre to its surface along the normal, m.
    pub radius_a: f32,
    pub radius_b: f32,
    /// Centre of B minus centre of A at step start, m.
    pub center_offset: Vec3,
    /// Separation minus the surface points' offset along the normal (≈ 0), m.
    pub adjusted_separation: f32,
    pub normal_mass: f32,
    pub tangent_mass: [f32; 2],
    pub normal_impulse: f32,
    pub tangent_impulse: [f32; 2],
    pub max_normal_impulse: f32,
    /// Normal relative velocity before solving, m/s (for restitution).
    pub relative_velocity: f32,
    pub friction: f32,
    pub restitution: f32,
    pub feature: u64,
    /// Separation and lever arms at the bodies' current positions: positions
    /// only change between passes, so each is computed once per substep
    /// (`refresh`) and shared by the passes that follow.
    pub separation: f32,
    pub arm_a: Vec3,
    pub arm_b: Vec3,
}

/// A right-handed orthonormal basis around `n`, the same on every platform.
#[inline]
pub(crate) fn tangents(n: Vec3) -> [Vec3; 2] {
    // Pick the axis least aligned with n (Frisvad-style branch, no transcendental).
    let t1 = if n.x.abs() < 0.57735 {
        Vec3::new(0.0, n.z, -n.y)
    } else {
        Vec3::new(n.y, -n.x, 0.0)
    };
    let t1 = t1.normalize();
    [t1, n.cross(t1)]
}

#[inline]
fn effective_mass(a: &BodyState, b: &BodyState, r_a: Vec3, r_b: Vec3, axis: Vec3) -> f32 {
    let ra_x = r_a.cross(axis);
    let rb_x = r_b.cross(axis);
    let k =
        a.inv_mass + b.inv_mass + ra_x.dot(a.inv_inertia * ra_x) + rb_x.dot(b.inv_inertia * rb_x);
    if k > 0.0 {
        1.0 / k
    } else {
        0.0
    }
}

/// Builds a constraint, warm-started from `previous` when the same feature touched last step.
/// `centers` are the bodies' centres of mass, `spheres` the centres of the
/// touching spheres (for the room, the point on the triangle), world frame.
#[allow(clippy::too_many_arguments)]
pub(crate) fn prepare(
    c: &ContactPoint,
    a: u32,
    b: u32,
    states: &[BodyState],
    centers: (Vec3, Vec3),
    spheres: (Vec3, Vec3),
    material: (f32, f32),
    previous: &[StoredImpulse],
) -> ContactConstraint {
    let (sa, sb) = (&states[a as usize], &states[b as usize]);
    let n = c.normal;
    let tangent = tangents(n);
    // Impulses act at the surface points; effective masses use those arms.
    let arm_a = c.point_a - centers.0;
    let arm_b = c.point_b - centers.1;
    let radius_a = (c.point_a - spheres.0).dot(n);
    let radius_b = (spheres.1 - c.point_b).dot(n);
    let tracked = (spheres.1 - spheres.0).dot(n) - radius_a - radius_b;
    let mut normal_impulse = 0.0;
    let mut tangent_impulse = [0.0; 2];
    if let Some(p) = previous.iter().find(|p| p.feature == c.feature) {
        normal_impulse = p.normal;
        tangent_impulse = [p.tangent.dot(tangent[0]), p.tangent.dot(tangent[1])];
    }
    let dv = sb.point_velocity(arm_b) - sa.point_velocity(arm_a);
    let mut constraint = ContactConstraint {
        a,
        b,
        normal: n,
        tangent,
        r_a: spheres.0 - centers.0,
        r_b: spheres.1 - centers.1,
        radius_a,
        radius_b,
        center_offset: centers.1 - centers.0,
        adjusted_separation: c.separation - tracked,
        normal_mass: effective_mass(sa, sb, arm_a, arm_b, n),
        tangent_mass: [
            effective_mass(sa, sb, arm_a, arm_b, tangent[0]),
            effective_mass(sa, sb, arm_a, arm_b, tangent[1]),
        ],
        normal_impulse,
        tangent_impulse,
        max_normal_impulse: 0.0,
        relative_velocity: dv.dot(n),
        friction: material.0,
        restitution: material.1,
        feature: c.feature,
        separation: 0.0,
        arm_a: Vec3::ZERO,
        arm_b: Vec3::ZERO,
    };
    refresh(&mut constraint, sa, sb);
    constraint
}

/// Recomputes the separation and arms after the positions moved.
#[inline]
pub(crate) fn refresh(c: &mut ContactConstraint, sa: &BodyState, sb: &BodyState) {
    let (separation, arm_a, arm_b) = current_geometry(c, sa, sb);
    c.separation = separation;
    c.arm_a = arm_a;
    c.arm_b = arm_b;
}

/// Current separation, and the lever arms from each body's current centre to
/// the current midpoint of the two surface points. Both bodies take each
/// impulse at that one point, so the impulses cancel in the total angular
/// momentum as well as in the linear one.
#[inline]
fn current_geometry(c: &ContactConstraint, sa: &BodyState, sb: &BodyState) -> (f32, Vec3, Vec3) {
    let ra = sa.dq * c.r_a;
    let rb = sb.dq * c.r_b;
    let ab = c.center_offset + sb.dp - sa.dp;
    let separation = (ab + rb - ra).dot(c.normal) - c.radius_a - c.radius_b + c.adjusted_separation;
    // Surface points now, from A's centre: ra + radius_a·n and ab + rb − radius_b·n.
    let arm_a = 0.5 * (ra + ab + rb + (c.radius_a - c.radius_b) * c.normal);
    (separation, arm_a, arm_a - ab)
}

/// Applies last step's impulses again (warm start).
#[inline]
pub(crate) fn warm_start(c: &mut ContactConstraint, sa: &mut BodyState, sb: &mut BodyState) {
    let p = c.normal_impulse * c.normal
        + c.tangent_impulse[0] * c.tangent[0]
        + c.tangent_impulse[1] * c.tangent[1];
    sa.apply_impulse(-p, c.arm_a);
    sb.apply_impulse(p, c.arm_b);
}

/// How the solve pushes overlap out this substep.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bias {
    pub soft: Softness,
    pub inv_h: f32,
    /// m/s: the fastest push-out.
    pub max_push_out: f32,
    /// False for the relax pass: only the velocity constraint remains.
    pub use_bias: bool,
}

/// One Gauss-Seidel update of one contact. With `use_bias` overlap is pushed
/// out softly; without it (the relax pass) only the velocity constraint remains.
#[inline]
pub(crate) fn solve(
    c: &mut ContactConstraint,
    sa: &mut BodyState,
    sb: &mut BodyState,
    bias: &Bias,
) {
    let Bias {
        soft,
        inv_h,
        max_push_out,
        use_bias,
    } = *bias;
    // Separation and arms as the last `refresh` left them.
    let (s, arm_a, arm_b) = (c.separation, c.arm_a, c.arm_b);

    let (bias, mass_scale, impulse_scale) = if s > 0.0 {
        (s * inv_h, 1.0, 0.0) // speculative: close the gap, no more
    } else if use_bias {
        (
            (soft.bias_rate * s).max(-max_push_out),
            soft.mass_scale,
            soft.impulse_scale,
        )
    } else {
        (0.0, 1.0, 0.0)
    };

    let vn = (sb.point_velocity(arm_b) - sa.point_velocity(arm_a)).dot(c.normal);
    let impulse = -c.normal_mass * mass_scale * (vn + bias) - impulse_scale * c.normal_impulse;
    let total = (c.normal_impulse + impulse).max(0.0);
    let applied = total - c.normal_impulse;
    c.normal_impulse = total;
    c.max_normal_impulse = c.max_normal_impulse.max(applied);
    let p = applied * c.normal;
    sa.apply_impulse(-p, arm_a);
    sb.apply_impulse(p, arm_b);

    // Friction: both tangent rows, then clamp the pair to the Coulomb disk.
    let dv = sb.point_velocity(arm_b) - sa.point_velocity(arm_a);
    let old = c.tangent_impulse;
    let mut new = [
        old[0] - c.tangent_mass[0] * dv.dot(c.tangent[0]),
        old[1] - c.tangent_mass[1] * dv.dot(c.tangent[1]),
    ];
    let limit = c.friction * c.normal_impulse;
    let len_sq = new[0] * new[0] + new[1] * new[1];
    if len_sq > limit * limit {
        let scale = limit / len_sq.sqrt();
        new = [new[0] * scale, new[1] * scale];
    }
    c.tangent_impulse = new;
    let p = (new[0] - old[0]) * c.tangent[0] + (new[1] - old[1]) * c.tangent[1];
    sa.apply_impulse(-p, arm_a);
    sb.apply_impulse(p, arm_b);
}

/// Bounces: contacts that approached faster than `threshold` and pushed this
/// step leave at `restitution` times their approach speed.
pub(crate) fn apply_restitution(
    c: &mut ContactConstraint,
    sa: &mut BodyState,
    sb: &mut BodyState,
    threshold: f32,
) {
    if c.restitution == 0.0 || c.relative_velocity > -threshold || c.max_normal_impulse == 0.0 {
        return;
    }
    let (arm_a, arm_b) = (c.arm_a, c.arm_b);
    let vn = (sb.point_velocity(arm_b) - sa.point_velocity(arm_a)).dot(c.normal);
    let impulse = -c.normal_mass * (vn + c.restitution * c.relative_velocity);
    let total = (c.normal_impulse + impulse).max(0.0);
    let applied = total - c.normal_impulse;
    c.normal_impulse = total;
    let p = applied * c.normal;
    sa.apply_impulse(-p, arm_a);
    sb.apply_impulse(p, arm_b);
}

/// What a constraint hands to the next step's warm start.
#[inline]
pub(crate) fn stored(c: &ContactConstraint) -> StoredImpulse {
    StoredImpulse {
        feature: c.feature,
        normal: c.normal_impulse,
        tangent: c.tangent_impulse[0] * c.tangent[0] + c.tangent_impulse[1] * c.tangent[1],
    }
}

/// Post-stabilisation (Box2D v2's position pass, translation only): overlap
/// deeper than `slop` is removed directly from the positions, split between
/// the two bodies by inverse mass. Velocities are untouched, so no energy or
/// momentum is added and the centre of mass stays put; the soft solve stays
/// in charge of the dynamics, this pass only bounds how deep a crowd pressing
/// on a pile can push balloons into each other.
pub(crate) fn stabilize(c: &ContactConstraint, sa: &mut BodyState, sb: &mut BodyState, slop: f32) {
    let inv_mass = sa.inv_mass + sb.inv_mass;
    if inv_mass == 0.0 {
        return;
    }
    let (s, _, _) = current_geometry(c, sa, sb);
    if s >= -slop {
        return;
    }
    let push = (-slop - s) / inv_mass * c.normal;
    sa.dp -= sa.inv_mass * push;
    sb.dp += sb.inv_mass * push;
}
