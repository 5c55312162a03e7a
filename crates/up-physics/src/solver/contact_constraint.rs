//! Contact constraints: prepare, warm start, solve (with and without bias),
//! restitution, position stabilisation, and storing impulses for the next step.
//!
//! Each contact point holds a non-penetration row along the normal and two
//! friction rows along tangents, clamped to the Coulomb disk μ·λn. Anchors
//! are fixed at the start of the step; the current separation is updated
//! from the bodies' motion since then (Box2D v3), so substeps never rerun
//! collision detection.
//!
//! Constraints are prepared one at a time (`prepare`) and solved four at a
//! time (`ContactGroup`, Box2D v3's wide solve): the four lanes of a group
//! never move the same body (`coloring`), so a group is solved as four
//! independent constraints with one stream of SIMD instructions.

use glam::Vec3;
use up_geom::norm::Norm;

use super::body_lanes::{Displacements, Poses, Velocities};
use super::lanes::{max, select, F4, LANES, V4};
use super::softness::Softness;
use crate::contact::{ContactFeature, ContactPoint, StoredImpulse};

/// One prepared contact, before it takes its lane in a group.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PreparedContact {
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
    /// Warm start: last step's impulses.
    pub normal_impulse: f32,
    pub tangent_impulse: [f32; 2],
    pub feature: ContactFeature,
}

/// Four contact constraints, field by field (structure of arrays): what the
/// velocity passes read, kept apart from the anchors (`GroupAnchors`) and
/// the step's records (`GroupRecords`) so that a pass streams no more memory
/// than it uses. A lane left empty has zero masses and the static room on both
/// sides: it takes and gives no impulse.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ContactGroup {
    pub a: [u32; LANES],
    pub b: [u32; LANES],
    normal: V4,
    /// The first tangent; the second is normal × tangent (`tangents`).
    tangent: V4,
    normal_mass: F4,
    tangent_mass: [F4; 2],
    normal_impulse: F4,
    tangent_impulse: [F4; 2],
    /// The largest single push this step (restitution only bounces contacts that pushed).
    max_normal_impulse: F4,
    /// Separation and lever arms at the bodies' current positions: positions
    /// only change between passes, so each is computed once per substep
    /// (`refresh`) and shared by the passes that follow.
    separation: F4,
    arm_a: V4,
    arm_b: V4,
    /// What the step gave, for reports (`ContactTotals`), never read by the
    /// solve: the normal impulses of its substeps summed, the largest of
    /// them, and the tangent impulses summed (first tangent, second).
    step_normal_impulse: F4,
    peak_normal_impulse: F4,
    step_tangent_impulse: [F4; 2],
}

/// Where the four contacts' spheres were at the step's start, to track the
/// separation as the bodies move (`refresh`, `stabilize`), and how fast they
/// approached then (`apply_restitution`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct GroupAnchors {
    /// Centres of the touching spheres from each body's centre of mass, world
    /// frame, at step start (for the room, B's is the point on the triangle).
    /// Tracking centres, not surface points, keeps the separation exact when a
    /// balloon spins: a point on a spinning sphere rolls away from the contact.
    r_a: V4,
    r_b: V4,
    /// From each sphere's centre to its surface along the normal, m.
    radius_a: F4,
    radius_b: F4,
    /// Centre of B minus centre of A at step start, m.
    center_offset: V4,
    /// Separation minus the surface points' offset along the normal (≈ 0), m.
    adjusted_separation: F4,
    /// Normal relative velocity before solving, m/s (for restitution).
    relative_velocity: F4,
}

/// Which features of the bodies the four contacts are between (for the next
/// step's warm start).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct GroupRecords {
    pub feature: [ContactFeature; LANES],
}

/// Fills lane `i` of a group's three parts with a prepared contact.
pub(crate) fn set_lane(
    (g, anchors, records): (&mut ContactGroup, &mut GroupAnchors, &mut GroupRecords),
    i: usize,
    c: &PreparedContact,
) {
    // SAFETY: pointers from exclusive references: valid, and no one else's.
    unsafe { set_lane_shared((g, anchors, records), i, c) }
}

/// `set_lane` through pointers to a group's three parts, for tasks that
/// fill other lanes of the same groups at the same time: it writes lane
/// `i`'s bytes and no others (a reference to the whole group would claim
/// them all). The one list of a lane's fields, for both.
///
/// # Safety
/// The pointers are valid for writes, and while this runs no other task
/// reads the parts or writes their lane `i`.
pub(crate) unsafe fn set_lane_shared(
    (g, anchors, records): (*mut ContactGroup, *mut GroupAnchors, *mut GroupRecords),
    i: usize,
    c: &PreparedContact,
) {
    use std::ptr::addr_of_mut;
    assert!(i < LANES);
    // SAFETY: every pointer below is to a field of a valid part (the
    // caller's contract), lane `i` within it (asserted), `F4` four `f32`s
    // in lane order.
    unsafe {
        let put = |x: *mut F4, v: f32| x.cast::<f32>().add(i).write(v);
        let put_v = |x: *mut V4, v: Vec3| {
            put(addr_of_mut!((*x).x), v.x);
            put(addr_of_mut!((*x).y), v.y);
            put(addr_of_mut!((*x).z), v.z);
        };
        addr_of_mut!((*g).a).cast::<u32>().add(i).write(c.a);
        addr_of_mut!((*g).b).cast::<u32>().add(i).write(c.b);
        put_v(addr_of_mut!((*g).normal), c.normal);
        put_v(addr_of_mut!((*g).tangent), c.tangent[0]);
        put(addr_of_mut!((*g).normal_impulse), c.normal_impulse);
        let tangent_impulse = addr_of_mut!((*g).tangent_impulse).cast::<F4>();
        put(tangent_impulse, c.tangent_impulse[0]);
        put(tangent_impulse.add(1), c.tangent_impulse[1]);
        put_v(addr_of_mut!((*anchors).r_a), c.r_a);
        put_v(addr_of_mut!((*anchors).r_b), c.r_b);
        put(addr_of_mut!((*anchors).radius_a), c.radius_a);
        put(addr_of_mut!((*anchors).radius_b), c.radius_b);
        put_v(addr_of_mut!((*anchors).center_offset), c.center_offset);
        put(
            addr_of_mut!((*anchors).adjusted_separation),
            c.adjusted_separation,
        );
        let feature = addr_of_mut!((*records).feature).cast::<ContactFeature>();
        feature.add(i).write(c.feature);
    }
}

impl ContactGroup {
    /// A group of empty lanes against `room` (the static state).
    pub fn empty(room: u32) -> ContactGroup {
        ContactGroup {
            a: [room; LANES],
            b: [room; LANES],
            ..ContactGroup::default()
        }
    }

    /// What lane `i` hands to the next step's warm start.
    pub fn stored(&self, records: &GroupRecords, i: usize) -> StoredImpulse {
        let ti = [
            self.tangent_impulse[0].as_array()[i],
            self.tangent_impulse[1].as_array()[i],
        ];
        let normal = self.normal.lane(i);
        let tangent = self.tangent.lane(i);
        StoredImpulse {
            feature: records.feature[i],
            normal: self.normal_impulse.as_array()[i],
            tangent: ti[0] * tangent + ti[1] * normal.cross(tangent),
        }
    }

    /// What lane `i` gave over the step (`ContactTotals`).
    pub fn totals(&self, i: usize) -> ContactTotals {
        let normal = self.normal.lane(i);
        let tangent = self.tangent.lane(i);
        let t = [
            self.step_tangent_impulse[0].as_array()[i],
            self.step_tangent_impulse[1].as_array()[i],
        ];
        ContactTotals {
            normal_impulse: self.step_normal_impulse.as_array()[i],
            max_normal_impulse: self.peak_normal_impulse.as_array()[i],
            // A takes −p for every impulse p that B takes (`solve`).
            tangent_impulse: -(t[0] * tangent + t[1] * normal.cross(tangent)),
        }
    }

    /// Adds the substep that just ended to the step's totals: each substep
    /// applies its accumulated impulse whole (warm start, then the solve's
    /// and the relax pass's changes to it).
    #[inline]
    pub fn add_substep(&mut self) {
        self.step_normal_impulse += self.normal_impulse;
        self.peak_normal_impulse = max(self.peak_normal_impulse, self.normal_impulse);
        self.step_tangent_impulse[0] += self.tangent_impulse[0];
        self.step_tangent_impulse[1] += self.tangent_impulse[1];
    }

    /// Both tangents (the second as `tangents` makes it, bit for bit).
    #[inline]
    fn tangents(&self) -> [V4; 2] {
        [self.tangent, self.normal.cross(self.tangent)]
    }
}

/// What one contact gave over a step, N·s (`ContactInfo` carries it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ContactTotals {
    /// Along the normal, summed over the substeps and the bounce; ≥ 0.
    pub normal_impulse: f32,
    /// The largest a single substep applied (the bounce counted in the last).
    pub max_normal_impulse: f32,
    /// Friction on body A, world frame, summed.
    pub tangent_impulse: Vec3,
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
    let t1 = t1.unit();
    [t1, n.cross(t1)]
}

/// Builds a constraint, warm-started from `previous` when the same feature touched last step.
/// `centers` are the bodies' centres of mass, `spheres` the centres of the
/// touching spheres (for the room, the point on the triangle), world frame.
pub(crate) fn prepare(
    c: &ContactPoint,
    (a, b): (u32, u32),
    centers: (Vec3, Vec3),
    spheres: (Vec3, Vec3),
    previous: &[StoredImpulse],
) -> PreparedContact {
    let n = c.normal;
    let tangent = tangents(n);
    let radius_a = (c.point_a - spheres.0).dot(n);
    let radius_b = (spheres.1 - c.point_b).dot(n);
    let tracked = (spheres.1 - spheres.0).dot(n) - radius_a - radius_b;
    let mut normal_impulse = 0.0;
    let mut tangent_impulse = [0.0; 2];
    if let Some(p) = previous.iter().find(|p| p.feature == c.feature) {
        normal_impulse = p.normal;
        tangent_impulse = [p.tangent.dot(tangent[0]), p.tangent.dot(tangent[1])];
    }
    PreparedContact {
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
        normal_impulse,
        tangent_impulse,
        feature: c.feature,
    }
}

/// Effective masses along the normal and the tangents, and the approach
/// speed, at the start of the step (after its first `refresh`): impulses act
/// at the arms `refresh` gives, so the masses use those arms too.
#[inline]
pub(crate) fn prepare_masses(
    c: &mut ContactGroup,
    anchors: &mut GroupAnchors,
    a: &Velocities,
    b: &Velocities,
) {
    let (arm_a, arm_b) = (c.arm_a, c.arm_b);
    let effective_mass = |axis: V4| {
        let ra_x = arm_a.cross(axis);
        let rb_x = arm_b.cross(axis);
        let k = a.inv_mass
            + b.inv_mass
            + ra_x.dot(a.inv_inertia.mul(ra_x))
            + rb_x.dot(b.inv_inertia.mul(rb_x));
        select(k.simd_gt(F4::ZERO), F4::ONE / k, F4::ZERO)
    };
    let tangent = c.tangents();
    c.normal_mass = effective_mass(c.normal);
    c.tangent_mass = [effective_mass(tangent[0]), effective_mass(tangent[1])];
    let dv = b.point_velocity(arm_b) - a.point_velocity(arm_a);
    anchors.relative_velocity = dv.dot(c.normal);
}

/// Recomputes the separation and arms after the positions moved.
#[inline]
pub(crate) fn refresh(c: &mut ContactGroup, anchors: &GroupAnchors, a: &Poses, b: &Poses) {
    let (separation, arm_a, arm_b) = current_geometry(c.normal, anchors, a, b);
    c.separation = separation;
    c.arm_a = arm_a;
    c.arm_b = arm_b;
}

/// Current separation, and the lever arms from each body's current centre to
/// the current midpoint of the two surface points. Both bodies take each
/// impulse at that one point, so the impulses cancel in the total angular
/// momentum as well as in the linear one.
#[inline]
fn current_geometry(normal: V4, c: &GroupAnchors, a: &Poses, b: &Poses) -> (F4, V4, V4) {
    let ra = a.dq.rotate(c.r_a);
    let rb = b.dq.rotate(c.r_b);
    let (separation, ab) = separation(normal, c, (ra, rb), (a.dp, b.dp));
    // Surface points now, from A's centre: ra + radius_a·n and ab + rb − radius_b·n.
    let arm_a = F4::splat(0.5) * (((ra + ab) + rb) + (c.radius_a - c.radius_b) * normal);
    (separation, arm_a, arm_a - ab)
}

/// The separation when the sphere centres are `offsets` from their bodies'
/// centres, which moved by `dp`; and the centre of B from the centre of A.
#[inline]
fn separation(normal: V4, c: &GroupAnchors, offsets: (V4, V4), dp: (V4, V4)) -> (F4, V4) {
    let (ra, rb) = offsets;
    let ab = (c.center_offset + dp.1) - dp.0;
    let separation =
        (((ab + rb) - ra).dot(normal) - c.radius_a) - c.radius_b + c.adjusted_separation;
    (separation, ab)
}

/// Turns the anchors' sphere offsets into those at the bodies' current
/// orientations, which the position passes (`stabilize`) leave as they are:
/// the rotations are then done once, not once per pass.
#[inline]
pub(crate) fn rotate_to_end(c: &mut GroupAnchors, a: &Poses, b: &Poses) {
    c.r_a = a.dq.rotate(c.r_a);
    c.r_b = b.dq.rotate(c.r_b);
}

/// Applies last step's impulses again (warm start).
#[inline]
pub(crate) fn warm_start(c: &mut ContactGroup, a: &mut Velocities, b: &mut Velocities) {
    let tangent = c.tangents();
    let p = (c.normal_impulse * c.normal + c.tangent_impulse[0] * tangent[0])
        + c.tangent_impulse[1] * tangent[1];
    a.apply_impulse(-p, c.arm_a);
    b.apply_impulse(p, c.arm_b);
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
    /// Coulomb friction coefficient.
    pub friction: f32,
}

/// One Gauss-Seidel update of four contacts. With `use_bias` overlap is pushed
/// out softly; without it (the relax pass) only the velocity constraint remains.
#[inline]
pub(crate) fn solve(c: &mut ContactGroup, a: &mut Velocities, b: &mut Velocities, bias: &Bias) {
    let splat = F4::splat;
    // Separation and arms as the last `refresh` left them.
    let (s, arm_a, arm_b) = (c.separation, c.arm_a, c.arm_b);

    // Speculative (s > 0): close the gap, no more. Overlapping: the soft push-out,
    // or nothing but the velocity constraint in the relax pass.
    let speculative = s.simd_gt(F4::ZERO);
    let (push, mass_scale, impulse_scale) = if bias.use_bias {
        let soft = bias.soft;
        (
            max(splat(soft.bias_rate) * s, splat(-bias.max_push_out)),
            splat(soft.mass_scale),
            splat(soft.impulse_scale),
        )
    } else {
        (F4::ZERO, F4::ONE, F4::ZERO)
    };
    let bias_velocity = select(speculative, s * splat(bias.inv_h), push);
    let mass_scale = select(speculative, F4::ONE, mass_scale);
    let impulse_scale = select(speculative, F4::ZERO, impulse_scale);

    let vn = (b.point_velocity(arm_b) - a.point_velocity(arm_a)).dot(c.normal);
    let impulse =
        -c.normal_mass * mass_scale * (vn + bias_velocity) - impulse_scale * c.normal_impulse;
    let total = max(c.normal_impulse + impulse, F4::ZERO);
    let applied = total - c.normal_impulse;
    c.normal_impulse = total;
    c.max_normal_impulse = max(c.max_normal_impulse, applied);
    let p = applied * c.normal;
    a.apply_impulse(-p, arm_a);
    b.apply_impulse(p, arm_b);

    // Friction: both tangent rows, then clamp the pair to the Coulomb disk.
    let dv = b.point_velocity(arm_b) - a.point_velocity(arm_a);
    let tangent = c.tangents();
    let old = c.tangent_impulse;
    let mut new = [
        old[0] - c.tangent_mass[0] * dv.dot(tangent[0]),
        old[1] - c.tangent_mass[1] * dv.dot(tangent[1]),
    ];
    let limit = splat(bias.friction) * c.normal_impulse;
    let len_sq = new[0] * new[0] + new[1] * new[1];
    let clamp = len_sq.simd_gt(limit * limit);
    let scale = limit / len_sq.sqrt();
    new = [
        select(clamp, new[0] * scale, new[0]),
        select(clamp, new[1] * scale, new[1]),
    ];
    c.tangent_impulse = new;
    let p = (new[0] - old[0]) * tangent[0] + (new[1] - old[1]) * tangent[1];
    a.apply_impulse(-p, arm_a);
    b.apply_impulse(p, arm_b);
}

/// The lanes that approached faster than `threshold` and pushed this step
/// (those that bounce, for restitution's threshold).
#[inline]
pub(crate) fn bounces(c: &ContactGroup, anchors: &GroupAnchors, threshold: f32) -> F4 {
    !anchors.relative_velocity.simd_gt(F4::splat(-threshold))
        & !c.max_normal_impulse.simd_eq(F4::ZERO)
}

/// Bounces: the `bounces` lanes leave at `restitution` times their approach speed.
pub(crate) fn apply_restitution(
    c: &mut ContactGroup,
    anchors: &GroupAnchors,
    a: &mut Velocities,
    b: &mut Velocities,
    restitution: f32,
    bounces: F4,
) {
    let approach = anchors.relative_velocity;
    let (arm_a, arm_b) = (c.arm_a, c.arm_b);
    let vn = (b.point_velocity(arm_b) - a.point_velocity(arm_a)).dot(c.normal);
    let impulse = -c.normal_mass * (vn + F4::splat(restitution) * approach);
    let total = select(
        bounces,
        max(c.normal_impulse + impulse, F4::ZERO),
        c.normal_impulse,
    );
    let applied = total - c.normal_impulse;
    c.normal_impulse = total;
    // The bounce belongs to the last substep's impulse.
    c.step_normal_impulse += applied;
    c.peak_normal_impulse = max(c.peak_normal_impulse, total);
    let p = applied * c.normal;
    a.apply_impulse(-p, arm_a);
    b.apply_impulse(p, arm_b);
}

/// What a position pass did to a group (`stabilize`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PositionPush {
    /// Some contact was deeper than the slop: its bodies moved.
    pub moved: bool,
    /// Some contact was deeper than the target before its push.
    pub beyond_target: bool,
    /// How much the shallowest contact between movable bodies could close
    /// before it is deeper than the slop, m: ∞ if there is none, −∞ if the
    /// group moved (it has to run again).
    pub room_left: f32,
    /// How far each lane's bodies moved, side A and side B, m.
    pub distance: [F4; 2],
}

/// Post-stabilisation (Box2D v2's position pass, translation only): overlap
/// deeper than `slop` is removed directly from the positions, split between
/// the two bodies by inverse mass. Velocities are untouched, so no energy or
/// momentum is added and the centre of mass stays put; the soft solve stays
/// in charge of the dynamics, this pass only bounds how deep a crowd pressing
/// on a pile can push balloons into each other. A target no smaller than
/// the slop makes `beyond_target` imply `moved`.
pub(crate) fn stabilize(
    c: &ContactGroup,
    anchors: &GroupAnchors,
    a: &mut Displacements,
    b: &mut Displacements,
    slop: f32,
    target: f32,
) -> PositionPush {
    let inv_mass = a.inv_mass + b.inv_mass;
    let (s, _) = separation(c.normal, anchors, (anchors.r_a, anchors.r_b), (a.dp, b.dp));
    let movable = inv_mass.simd_gt(F4::ZERO);
    let beyond_target = (s.simd_lt(F4::splat(-target)) & movable).any();
    let slop = F4::splat(slop);
    let deep = s.simd_lt(-slop) & movable;
    if !deep.any() {
        // A comparison, not `f32::min`, which WebAssembly calls out of line
        // (`fminf`); a NaN lane never pushes, and is passed over either way.
        let room = select(movable, s + slop, F4::splat(f32::INFINITY));
        let shallowest = room
            .to_array()
            .into_iter()
            .fold(f32::INFINITY, |m, r| if r < m { r } else { m });
        return PositionPush {
            moved: false,
            beyond_target,
            room_left: shallowest,
            distance: [F4::ZERO; 2],
        };
    }
    let push = V4::select(deep, ((-slop - s) / inv_mass) * c.normal, V4::ZERO);
    a.dp = a.dp - a.inv_mass * push;
    b.dp = b.dp + b.inv_mass * push;
    let length = push.dot(push).sqrt();
    PositionPush {
        moved: true,
        beyond_target,
        room_left: f32::NEG_INFINITY,
        distance: [a.inv_mass * length, b.inv_mass * length],
    }
}
