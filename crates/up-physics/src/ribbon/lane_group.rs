//! The awake ribbons laid out for the substeps: grouped by segment count,
//! four to a group, a ribbon a lane (`solver::lanes`), in structure of
//! arrays (per point index, one `V4` of the four ribbons' points). The
//! substeps then run each group's steps on its four ribbons at once
//! (`lane_substep`), with no branch on a ribbon and no allocation once the
//! buffers have grown to the scene.
//!
//! Packed once a step, straight from the world's ribbons, once
//! `World::prepare_ribbons` has readied them (`RibbonLanes::assign`,
//! `pack`), and their
//! points handed back once a step in `World::finish_ribbons`
//! (`RibbonLanes::take_out`). A
//! group short of four ribbons fills its spare lanes with copies of its
//! first: they compute harmless numbers that nothing reads.
//!
//! A point lying still on the room rests for the step (`Rest`): held where
//! it lies, as an anchored end is, so no fall, push or friction is worked
//! out for it; and where every lane's points rest from some point to the
//! end, the substeps stop at the first of them (`active`), so a ribbon
//! lying on the floor costs what its moving part does. A point rests only
//! while it, the point before it and every point after it ended the last
//! step exactly still (friction held them: a ribbon dragged along the floor
//! slips somewhere along its lying part, and rests nowhere), lying on a room
//! triangle near it, apart from every body near the ribbon; a move ends the
//! rest of the point after it the next step, so a pull that starts reaches
//! along a lying ribbon a point a step.

use std::ops::Range;

use super::body_spheres::BodySpheres;
use super::chain::Knots;
use super::collide::{NearBalloon, NearTriangle};
use super::lane_pushes::NearSlot;
use super::lane_room::{RoomSlot, TriangleSlot};
use super::solve::ActiveRibbon;
use super::{Ribbon, Ribbons, MAX_SEGMENTS, RIBBON_RADIUS};
use crate::solver::lanes::{select, set, F4, LANES, M4, V4};
use crate::threading::tasks::for_each_run;
use glam::{Mat3, Vec3};

/// Lane groups one task packs (128 ribbons).
const PACK_CHUNK: usize = 32;

/// A ribbon's lane, what is not laid out across the lanes: its balloon, what
/// it may touch, and what it did to them this substep.
#[derive(Clone, Debug, Default)]
pub(crate) struct Lane {
    /// Its balloon's solver state (dense index) and `BodyDef::user_data`.
    pub state: u32,
    pub user_data: u32,
    /// The balloon's centre of mass at the step's start, and the knot from
    /// it, world frame at the step's start, m.
    pub origin: Vec3,
    pub arm0: Vec3,
    /// Room triangles and balloons near it this step, in the stage's lists.
    pub triangles: Range<u32>,
    pub bodies: Range<u32>,
    /// A grabbed point, where it is carried and how fast, m/s.
    pub grab: Option<(usize, Vec3)>,
    pub grab_speed: f32,
    /// This substep's pushes back on the balloons its points touched: the
    /// balloon's state, the position impulse (kg·m) and its arm (m).
    pub reactions: Vec<(u32, Vec3, Vec3)>,
    /// The balloons near it at this substep's poses.
    pub near: Vec<NearBalloon>,
}

/// Up to four ribbons of one segment count, a lane each.
#[derive(Clone, Debug, Default)]
pub(crate) struct LaneGroup {
    /// Ribbons in its lanes: lanes `live..` are spare.
    pub live: usize,
    /// All bits set in the ribbons' lanes.
    pub live_mask: F4,
    /// Per point (0 at the knot): position, velocity, where it began the
    /// substep, inverse mass (0: held; unused at the knot).
    pub points: Vec<V4>,
    pub velocities: Vec<V4>,
    pub start: Vec<V4>,
    pub inv_mass: Vec<F4>,
    /// Per point, once `touched`: the normal of the balloon that pushed it
    /// this substep (zero if none), and that balloon's velocity.
    pub touch_normal: Vec<V4>,
    pub touch_velocity: Vec<V4>,
    pub touched: bool,
    /// Per point, in lanes near the room: its friction against the room
    /// over the step's substeps (`collide::Grip`, the lanes' `left` and
    /// `anchor`).
    pub grip_left: Vec<V4>,
    pub grip_anchor: Vec<V4>,
    /// The room's planes and triangles near the lanes lined up across them,
    /// the lanes that have any (bit `l` for lane `l`), and per point the
    /// lanes whose grip holds friction (`lane_room`).
    pub room_slots: Vec<RoomSlot>,
    pub triangle_slots: Vec<TriangleSlot>,
    pub room_lanes: u32,
    pub gripped: Vec<u8>,
    /// Per point, once `windy`: the air's velocity there this step, sampled
    /// at the first substep (`lane_substep`); and per lane the fastest of it.
    pub air: Vec<V4>,
    pub windy: bool,
    pub air_speed: F4,
    pub segment_length: F4,
    /// Drag across, along and viscous (`ActiveRibbon::take`) of the points
    /// between the ends, and of the end.
    pub drag_mid: [F4; 3],
    pub drag_end: [F4; 3],
    /// The end's radius, m (the others': `RIBBON_RADIUS`).
    pub end_radius: F4,
    pub lanes: [Lane; LANES],
    /// This substep's position impulse on each balloon (kg·m) and the arm it
    /// acts at, world frame, m; the impulses summed over the step.
    pub impulse: V4,
    pub arm: V4,
    pub step_impulse: V4,
    /// The step's substeps so far and their length, s.
    pub substeps: u32,
    pub h: f32,
    /// The near balloons' bounds lined up across the lanes.
    pub near_slots: Vec<NearSlot>,
    /// The knots as this substep's chains' solve took them, for the solves
    /// that follow the ribbons' contacts (`touch`) within the substep.
    pub knots: Knots,
    /// A contact between ribbons moved one of its points since its chains
    /// were last solved.
    pub pushed: bool,
    /// Bit l: lane l's ribbon touches another as the last pass left them,
    /// and is solved with its contacts (`touch::held`), not in the lanes.
    pub held_lanes: u8,
    /// Per point, the lanes (bit `l` for lane `l`) where it rests this step,
    /// and its inverse mass were it not resting.
    pub rested: Vec<u8>,
    pub free_inv_mass: Vec<F4>,
    /// How far the room's friction holds a point against a pull over a
    /// substep, per kilogram of it: μ·g·h² (m·kg⁻¹·kg, so kg·m a kilogram).
    pub rest_hold: f32,
    /// Per lane, the first point of its resting tail (the point count if
    /// none rests).
    pub rest_from: [usize; LANES],
    /// The points the substeps move and solve: `active..` rest in every lane
    /// (all of them if none do); at least three.
    pub active: usize,
}

/// A point lying this close to its radius over a room triangle's plane
/// lies on it, m (a push leaves it at the radius, to rounding).
const LYING_WITHIN: f32 = 1e-5;

/// What tells which of a ribbon's points may rest this step: the room's
/// triangles and the bodies near it, and every body's sphere (widened by
/// its move this step and the margin, `NearbyBodies`).
#[derive(Clone, Copy)]
pub(crate) struct Rest<'a> {
    pub triangles: &'a [NearTriangle],
    pub bodies: &'a [u32],
    pub centers: &'a [Vec3],
    pub radii: &'a [f32],
}

impl Rest<'_> {
    /// How many of `ribbon`'s last points rest, together (`find`): the
    /// tail held still in its lane.
    pub fn tail(&self, ribbon: &Ribbon) -> usize {
        let mut rests = [false; MAX_SEGMENTS as usize + 1];
        self.find(ribbon, &mut rests);
        rests[..ribbon.points.len()]
            .iter()
            .rev()
            .take_while(|&&r| r)
            .count()
    }

    /// Which of `ribbon`'s points (not its knot) rest, into `rests`: those
    /// that, with the point before them and every point after, ended the
    /// last step exactly still, lie on a near triangle, and no near body's
    /// sphere reaches.
    fn find(&self, ribbon: &Ribbon, rests: &mut [bool]) {
        let (v, points) = (&ribbon.velocities, &ribbon.points);
        let n = v.len() - 1;
        // The still tail: from `still_from` to the end, every point ended the
        // last step exactly still.
        let still_tail = v.iter().rev().take_while(|v| **v == Vec3::ZERO).count();
        let still_from = v.len() - still_tail;
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for i in 1..=n {
            let (p, radius) = (points[i], ribbon.radius(i));
            rests[i] = i > still_from
                && self.triangles.iter().any(|t| {
                    let height = (p - t.corners[0]).dot(t.normal);
                    (height - radius).abs() <= LYING_WITHIN
                        && t.edges().within(p - height * t.normal, radius) == Some(true)
                });
            if rests[i] {
                (lo, hi) = (lo.min(p), hi.max(p));
            }
        }
        if lo.x > hi.x {
            return;
        }
        // The bodies whose spheres meet the resting points' box (grown by
        // the largest radius), each against those points.
        let reach = Vec3::splat(ribbon.radius(n).max(RIBBON_RADIUS));
        let (lo, hi) = (lo - reach, hi + reach);
        for &b in self.bodies {
            let (c, r) = (self.centers[b as usize], self.radii[b as usize]);
            if c.clamp(lo, hi).distance_squared(c) > r * r {
                continue;
            }
            for i in 1..=n {
                let reach = r + ribbon.radius(i);
                if rests[i] && points[i].distance_squared(c) < reach * reach {
                    rests[i] = false;
                }
            }
        }
    }
}

impl LaneGroup {
    /// Empties the group for ribbons of `segments` segments.
    fn begin(&mut self, segments: usize) {
        self.live = 0;
        let points = segments + 1;
        for v in [&mut self.points, &mut self.velocities, &mut self.start] {
            v.resize(points, V4::ZERO);
        }
        for v in [
            &mut self.touch_normal,
            &mut self.touch_velocity,
            &mut self.air,
        ] {
            v.resize(points, V4::ZERO);
        }
        self.windy = false;
        self.held_lanes = 0;
        self.air_speed = F4::ZERO;
        self.inv_mass.resize(points, F4::ZERO);
        self.rested.clear();
        self.rested.resize(points, 0);
        self.free_inv_mass.resize(points, F4::ZERO);
        self.rest_from = [points; LANES];
        self.grip_left.resize(points, V4::ZERO);
        self.grip_anchor.resize(points, V4::ZERO);
        self.room_lanes = 0;
        self.step_impulse = V4::ZERO;
        self.substeps = 0;
        self.h = 0.0;
    }

    /// Puts `r`, whose points are `ribbon`'s, in lane `l` (one of the first
    /// `live`): an anchored end where it is tied, still; a held point of no
    /// inverse mass; a point of its resting tail, from point `from` (the
    /// point count if none rests), held too.
    fn add(&mut self, l: usize, r: &ActiveRibbon, ribbon: &Ribbon, from: usize) {
        let n = ribbon.points.len() - 1;
        self.rest_from[l] = from;
        for (i, (p, v)) in ribbon.points.iter().zip(&ribbon.velocities).enumerate() {
            self.points[i].set_lane(l, *p);
            self.velocities[i].set_lane(l, *v);
            let free = r.inv_mass(i, n);
            set(&mut self.free_inv_mass[i], l, free);
            let rests = i >= from && free > 0.0;
            if rests {
                self.rested[i] |= 1 << l;
            }
            set(&mut self.inv_mass[i], l, if rests { 0.0 } else { free });
        }
        if let Some(anchor) = r.anchor {
            self.points[n].set_lane(l, anchor);
            self.velocities[n].set_lane(l, Vec3::ZERO);
        }
        set(&mut self.segment_length, l, r.segment_length);
        for k in 0..3 {
            set(&mut self.drag_mid[k], l, r.drag_mid[k]);
            set(&mut self.drag_end[k], l, r.drag_end[k]);
        }
        set(&mut self.end_radius, l, r.end_radius);
        let lane = &mut self.lanes[l];
        lane.state = r.state;
        lane.user_data = r.user_data;
        lane.origin = r.origin;
        lane.arm0 = r.arm0;
        lane.triangles = r.triangles.clone();
        lane.bodies = r.bodies.clone();
        lane.grab = r.grab;
        lane.grab_speed = r.grab_speed;
    }

    /// Fills the spare lanes with copies of the first, and sets `live_mask`
    /// and `active`.
    fn pad(&mut self) {
        let all = F4::splat(f32::from_bits(!0));
        let live = self.live;
        // The spare lanes rest where the first does.
        let every = (1u8 << LANES) - 1;
        let spare = every & !((1u8 << live) - 1);
        for r in &mut self.rested {
            if *r & 1 != 0 {
                *r |= spare;
            }
        }
        for l in live..LANES {
            self.rest_from[l] = self.rest_from[0];
        }
        // Lanes kept, each a lane of all bits set; the others take the first's.
        let mut kept = [0.0f32; LANES];
        kept[..live].fill(f32::from_bits(!0));
        let kept = F4::new(kept);
        let fill = |x: &mut F4| *x = select(kept, *x, F4::splat(x.as_array()[0]));
        self.free_inv_mass.iter_mut().for_each(fill);
        self.set_active();
        if live == LANES {
            self.live_mask = all;
            return;
        }
        let fill_v = |v: &mut V4| *v = V4::select(kept, *v, V4::splat(v.lane(0)));
        for v in self.points.iter_mut().chain(&mut self.velocities) {
            fill_v(v);
        }
        self.inv_mass.iter_mut().for_each(fill);
        fill(&mut self.segment_length);
        self.drag_mid
            .iter_mut()
            .chain(&mut self.drag_end)
            .for_each(fill);
        fill(&mut self.end_radius);
        self.live_mask = kept;
        for lane in &mut self.lanes[self.live..] {
            lane.grab = None;
            lane.reactions.clear();
            lane.near.clear();
        }
    }

    /// `active`: the chains end at the first point from which every lane
    /// rests (it held), at the third point at the earliest.
    fn set_active(&mut self) {
        let every = (1u8 << LANES) - 1;
        let resting = self.rested.iter().rev().take_while(|&&r| r == every);
        self.active = (self.points.len() - resting.count() + 1).clamp(3, self.points.len());
    }

    /// Ends the rest of the lanes in `lanes` (bit `l` for lane `l`) from
    /// here on: their resting points free again, still where they lie, with
    /// nothing held against the room yet this step.
    pub(super) fn end_rest(&mut self, lanes: u32) {
        let before = self.active;
        for l in (0..LANES).filter(|l| lanes & (1 << l) != 0) {
            let from = std::mem::replace(&mut self.rest_from[l], self.points.len());
            for i in from..self.points.len() {
                if self.rested[i] & (1 << l) == 0 {
                    continue;
                }
                self.rested[i] &= !(1 << l);
                set(
                    &mut self.inv_mass[i],
                    l,
                    self.free_inv_mass[i].as_array()[l],
                );
                let p: Vec3 = self.points[i].lane(l);
                self.start[i].set_lane(l, p);
                self.grip_anchor[i].set_lane(l, p);
                self.grip_left[i].set_lane(l, Vec3::ZERO);
            }
        }
        self.set_active();
        // The points the substeps now reach, resting in the other lanes or
        // not, start the rest of the substep where they lie (past `active`
        // nothing kept their start).
        for i in before..self.active {
            self.start[i] = self.points[i];
            self.grip_anchor[i] = self.points[i];
            self.grip_left[i] = V4::ZERO;
        }
    }

    /// Lane `l`'s points and velocities back into `ribbon`, its step's
    /// impulses into `r`.
    fn take_out(&self, l: usize, r: &mut ActiveRibbon, ribbon: &mut Ribbon) {
        for (i, (p, v)) in ribbon
            .points
            .iter_mut()
            .zip(&mut ribbon.velocities)
            .enumerate()
        {
            *p = self.points[i].lane(l);
            *v = self.velocities[i].lane(l);
        }
        r.step_impulse = self.step_impulse.lane(l);
        r.air_speed = self.air_speed.as_array()[l];
        r.substeps = self.substeps;
        r.h = self.h;
    }
}

/// Writes `m` into lane `l` of `m4`.
pub(crate) fn set_matrix(m4: &mut M4, l: usize, m: &Mat3) {
    m4.x_axis.set_lane(l, m.x_axis);
    m4.y_axis.set_lane(l, m.y_axis);
    m4.z_axis.set_lane(l, m.z_axis);
}

/// A lane group as `RibbonLanes::assign` chose it: its ribbons' segment
/// count, and the awake ribbon (its place in `order`) in each of its first
/// `live` lanes.
#[derive(Clone, Copy, Debug, Default)]
struct Members {
    segments: usize,
    live: usize,
    ribbons: [u32; LANES],
}

/// The awake ribbons in lane groups, with the buffers kept between steps.
#[derive(Clone, Debug, Default)]
pub(crate) struct RibbonLanes {
    /// The groups in use are the first `used`.
    pub groups: Vec<LaneGroup>,
    pub used: usize,
    /// Per awake ribbon, in the solver's order: its group and lane (pulls
    /// are applied in this order, whatever the grouping).
    pub order: Vec<(u32, u32)>,
    /// Per group in use, what `assign` chose for it (`pack` lays it out).
    members: Vec<Members>,
    /// Per segment count, and whether more than half rests: the group being
    /// filled (`u32::MAX`: none).
    filling: Vec<u32>,
    /// The bodies' spheres at the substep's pose.
    pub bodies: BodySpheres,
}

impl RibbonLanes {
    /// No ribbon packed.
    pub fn is_empty(&self) -> bool {
        self.used == 0
    }

    /// Empties the groups for the step's ribbons.
    pub fn begin(&mut self) {
        self.used = 0;
        self.order.clear();
        self.filling.clear();
        self.filling
            .resize(2 * (MAX_SEGMENTS as usize + 1), u32::MAX);
    }

    /// Chooses the next awake ribbon's lane, one of `segments` segments
    /// whose last `tail` points rest: in the latest group of its segment
    /// count with a free lane (`pack` fills it).
    pub fn assign(&mut self, segments: usize, tail: usize) {
        // Ribbons resting over more than half their points share groups,
        // whose substeps then stop early, apart from the others.
        let key = segments * 2 + usize::from(2 * tail > segments);
        let mut g = self.filling[key];
        if g == u32::MAX || self.members[g as usize].live == LANES {
            g = self.used as u32;
            if self.groups.len() == self.used {
                self.groups.push(LaneGroup::default());
                self.members.push(Members::default());
            }
            self.used += 1;
            self.members[g as usize] = Members {
                segments,
                ..Members::default()
            };
            self.filling[key] = g;
        }
        let members = &mut self.members[g as usize];
        members.ribbons[members.live] = self.order.len() as u32;
        self.order.push((g, members.live as u32));
        members.live += 1;
    }

    /// Packs the awake ribbons (`active`, in the order assigned; their
    /// points those of the world's `ribbons`) into their lanes and pads
    /// the groups: groups side by side in tasks.
    pub fn pack(&mut self, active: &[ActiveRibbon], ribbons: &Ribbons) {
        let used = self.used;
        let parts = (&mut self.groups[..used], &mut self.members[..used]);
        for_each_run(used, PACK_CHUNK, parts, |_, (groups, members)| {
            for (group, members) in groups.iter_mut().zip(members.iter()) {
                group.begin(members.segments);
                group.live = members.live;
                for (l, &k) in members.ribbons[..members.live].iter().enumerate() {
                    let r = &active[k as usize];
                    // An awake ribbon's slot holds it.
                    if let Some(ribbon) = ribbons.slot(r.slot) {
                        let from = ribbon.points.len() - r.rest_tail as usize;
                        group.add(l, r, ribbon, from);
                    }
                }
                group.pad();
            }
        });
    }

    /// Hands the `k`th awake ribbon's points back to `ribbon` (as added),
    /// its step's impulses to `r`.
    pub fn take_out(&self, k: usize, r: &mut ActiveRibbon, ribbon: &mut Ribbon) {
        let (g, l) = self.order[k];
        self.groups[g as usize].take_out(l as usize, r, ribbon);
    }

    /// Empties the groups once their points are handed back.
    pub fn clear(&mut self) {
        self.used = 0;
        self.order.clear();
    }
}
