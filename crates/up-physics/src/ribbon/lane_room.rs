//! A lane group's points pushed out of the room, four lanes at once.
//!
//! Which points may touch the room this substep: the planes of the room's
//! triangles near each ribbon (a plane once, however many triangles lie in
//! it), lined up across the lanes (the `k`th of each lane's), give each
//! point's height over each plane in one pass; a point clear of every plane
//! by more than its radius, with no friction held from an earlier push this
//! step, is one the push would leave as it is.
//!
//! The push itself (`collide::push_out_of_room`, its reference, one point
//! of one ribbon), for the lanes whose point may touch: the triangles lined
//! up across the lanes too, each tested against the point's lanes at once
//! (its edge lines decide, `TriangleReach`; only a point near an edge seeks
//! the closest point, lane by lane), then friction for all the lanes at
//! once. Every lane computes what the reference does, in its order, bit for
//! bit (a point lying on the floor holds friction every push: two square
//! roots and four divisions a lane, the largest part of the push).

use super::chain::{div, norm};
use super::collide::NearTriangle;
use super::lane_group::LaneGroup;
use super::ROOM_FRICTION;
use crate::solver::lanes::{set, F4, LANES, V4};

/// A point this much farther than its radius from a triangle's plane, by
/// the lined-up test, is farther than its radius by the push's own
/// arithmetic: the two differ by rounding only (a few ulps of a room's
/// coordinates, ~1e-5 m in a room of tens of metres), m.
const PLANE_SLACK: f32 = 1e-3;

/// The `k`th room plane near each lane (unit inward normal,
/// and the normal's dot product with a corner), and the lanes that have a
/// `k`th (bit `l` for lane `l`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RoomSlot {
    normal: V4,
    offset: F4,
    lanes: u32,
}

/// The `k`th room triangle near each lane: a corner, its unit inward
/// normal, its edge lines and their margin (`TriangleReach::lines`), and the
/// lanes that have a `k`th (bit `l` for lane `l`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TriangleSlot {
    corner: V4,
    normal: V4,
    inward: [V4; 3],
    offset: [F4; 3],
    margin: F4,
    lanes: u32,
}

impl TriangleSlot {
    /// Writes `t` into lane `l`.
    fn set_lane(&mut self, l: usize, t: &NearTriangle) {
        let (inward, offset, margin) = t.edges().lines();
        self.corner.set_lane(l, t.corners[0]);
        self.normal.set_lane(l, t.normal);
        for e in 0..3 {
            self.inward[e].set_lane(l, inward[e]);
            set(&mut self.offset[e], l, offset[e]);
        }
        set(&mut self.margin, l, margin);
        self.lanes |= 1 << l;
    }
}

impl LaneGroup {
    /// Lines up the lanes' room planes and triangles for the step (their
    /// lists are the step's); no point holds friction yet.
    pub(super) fn line_up_room(&mut self, triangles: &[NearTriangle]) {
        self.room_slots.clear();
        self.triangle_slots.clear();
        self.room_lanes = 0;
        self.gripped.clear();
        self.gripped.resize(self.points.len(), 0);
        for l in 0..self.live {
            let range = &self.lanes[l].triangles;
            let near = &triangles[range.start as usize..range.end as usize];
            if near.is_empty() {
                continue;
            }
            self.room_lanes |= 1 << l;
            for (k, t) in near.iter().enumerate() {
                if self.triangle_slots.len() == k {
                    self.triangle_slots.push(TriangleSlot::default());
                }
                self.triangle_slots[k].set_lane(l, t);
            }
            // A plane once: the triangles of a flat floor or wall share it,
            // and the same plane gives the same heights.
            let mut planes = 0;
            for (k, t) in near.iter().enumerate() {
                let offset = t.corners[0].dot(t.normal);
                let same = |u: &NearTriangle| {
                    u.normal.to_array().map(f32::to_bits) == t.normal.to_array().map(f32::to_bits)
                        && u.corners[0].dot(u.normal).to_bits() == offset.to_bits()
                };
                if near[..k].iter().any(same) {
                    continue;
                }
                if self.room_slots.len() == planes {
                    self.room_slots.push(RoomSlot::default());
                }
                let slot = &mut self.room_slots[planes];
                slot.normal.set_lane(l, t.normal);
                set(&mut slot.offset, l, offset);
                slot.lanes |= 1 << l;
                planes += 1;
            }
        }
    }

    /// The lanes (bit `l` for lane `l`) whose point `i` the push out of the
    /// room may move: within its radius (and the slack) of a near
    /// triangle's plane or behind it, or holding friction from an earlier
    /// push, and movable. A NaN point is taken as near, as the push takes it.
    pub(super) fn near_room(&self, i: usize) -> u32 {
        let movable = self.inv_mass[i].simd_ne(F4::ZERO).to_bitmask();
        let candidates = self.room_lanes & movable;
        if candidates == 0 {
            return 0;
        }
        let p = self.points[i];
        let clear = self.radius(i) + F4::splat(PLANE_SLACK);
        let mut near = u32::from(self.gripped[i]);
        for slot in &self.room_slots {
            let height = p.dot(slot.normal) - slot.offset;
            near |= !height.simd_ge(clear).to_bitmask() & slot.lanes;
        }
        near & candidates
    }

    /// Pushes point `i` out of the room in the lanes of `lanes` (bit `l`
    /// for lane `l`, those `near_room` gives), `near_of[l]` lane `l`'s
    /// triangles as lined up: `collide::push_out_of_room` in each lane, at
    /// once; notes which lanes hold friction after it.
    pub(super) fn push_point_out_of_room(
        &mut self,
        i: usize,
        lanes: u32,
        near_of: &[&[NearTriangle]; LANES],
    ) {
        let radius = self.radius(i);
        let (start, mut point) = (self.start[i], self.points[i]);
        let mut left = self.grip_left[i];
        let mu = F4::splat(ROOM_FRICTION);
        for (k, slot) in self.triangle_slots.iter().enumerate() {
            let tested = slot.lanes & lanes;
            if tested == 0 {
                continue;
            }
            let height = (point - slot.corner).dot(slot.normal);
            // Not `<`: a NaN height goes on, as in the reference.
            let low = !height.simd_ge(radius).to_bitmask() & tested;
            if low == 0 {
                continue;
            }
            let on_plane = point - height * slot.normal;
            let side = |e: usize| on_plane.dot(slot.inward[e]) - slot.offset[e];
            let (s0, s1, s2) = (side(0), side(1), side(2));
            let m = slot.margin;
            let inside = (s0.simd_ge(m) & s1.simd_ge(m) & s2.simd_ge(m)).to_bitmask();
            let out = -(radius + m);
            let outside = (s0.simd_lt(out) | s1.simd_lt(out) | s2.simd_lt(out)).to_bitmask();
            let mut within = low & inside;
            // Unsure (near an edge, or a NaN): the closest point, lane by lane.
            let mut unsure = low & !inside & !outside;
            while unsure != 0 {
                let l = unsure.trailing_zeros() as usize;
                unsure &= unsure - 1;
                let r = radius.as_array()[l];
                if near_of[l][k].within_near_edge(on_plane.lane(l), r) {
                    within |= 1 << l;
                }
            }
            // In front of the face at the substep's start: it may not cross.
            let crossed = (start - slot.corner).dot(slot.normal).simd_le(-radius);
            let pushed = within & !crossed.to_bitmask();
            if pushed == 0 {
                continue;
            }
            let mask = lane_mask(pushed);
            let push = (radius - height) * slot.normal;
            point = V4::select(mask, point + push, point);
            left = V4::select(mask, left + mu * push, left);
        }
        // Friction: the slide from the anchor across the pushes' normal taken
        // back up to what the step's pushes hold.
        let anchor = self.grip_anchor[i];
        let held = norm(left);
        let rubs = lanes & !held.simd_le(F4::ZERO).to_bitmask();
        if rubs != 0 {
            let normal = div(left, held);
            let moved = point - anchor;
            let slide = moved - moved.dot(normal) * normal;
            let slide_len = norm(slide);
            let holds = slide_len.simd_le(held);
            let kept = point - slide;
            let slid = point - (held / slide_len) * slide;
            let rubs = lane_mask(rubs);
            let slips = rubs & !holds;
            point = V4::select(rubs, V4::select(holds, kept, slid), point);
            let left_kept = (held - slide_len) * normal;
            left = V4::select(rubs, V4::select(holds, left_kept, V4::ZERO), left);
            self.grip_anchor[i] = V4::select(slips, slid, anchor);
        }
        let all = lane_mask(lanes);
        self.points[i] = V4::select(all, point, self.points[i]);
        self.grip_left[i] = left;
        // A grip holds friction where its `left` is not zero.
        let zero = F4::ZERO;
        let holds = !(left.x.simd_eq(zero) & left.y.simd_eq(zero) & left.z.simd_eq(zero));
        let holds = holds.to_bitmask() as u8;
        let lanes = lanes as u8;
        self.gripped[i] = (self.gripped[i] & !lanes) | (holds & lanes);
    }
}

/// All bits set in the lanes of `bits` (bit `l` for lane `l`), none in the
/// others: a mask for `select`.
fn lane_mask(bits: u32) -> F4 {
    let on = f32::from_bits(!0);
    F4::new(std::array::from_fn(|l| {
        if bits & (1 << l) != 0 {
            on
        } else {
            0.0
        }
    }))
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::ribbon::collide::{push_out_of_room, Grip};
    use crate::ribbon::WEIGHT_RADIUS;

    /// A floor of two triangles, a wall beside it, and a sloped triangle
    /// across a corner.
    fn room() -> Vec<NearTriangle> {
        let v = Vec3::new;
        let floor = [
            [v(-3.0, 0.0, -3.0), v(-3.0, 0.0, 3.0), v(3.0, 0.0, -3.0)],
            [v(3.0, 0.0, -3.0), v(-3.0, 0.0, 3.0), v(3.0, 0.0, 3.0)],
        ];
        let wall = [v(3.0, 0.0, -3.0), v(3.0, 0.0, 3.0), v(3.0, 3.0, -3.0)];
        let slope = [v(2.0, 0.0, 3.0), v(3.0, 0.0, 2.0), v(3.0, 1.0, 3.0)];
        let mut near: Vec<NearTriangle> = floor
            .iter()
            .map(|&c| NearTriangle::new(c, Vec3::Y))
            .collect();
        near.push(NearTriangle::new(wall, Vec3::NEG_X));
        let n = (slope[1] - slope[0]).cross(slope[2] - slope[0]).normalize();
        let inward = if n.dot(Vec3::new(-1.0, 1.0, -1.0)) > 0.0 {
            n
        } else {
            -n
        };
        near.push(NearTriangle::new(slope, inward));
        near
    }

    /// Four ribbons' points lying on, over, under and across the floor's
    /// seam and edges, pushed out of the room twice a substep for a step's
    /// substeps with friction held over them: each lane ends where the
    /// one-point push (`collide::push_out_of_room`) leaves it, bit for bit,
    /// its grip too.
    #[test]
    fn the_lanes_push_as_the_one_point_push_does() {
        let mut next = crate::hash::uniform(11);
        let mut random = move || Vec3::new(next(), next(), next()) * 2.0 - 1.0;
        let triangles = room();
        let points = 9;
        let (mut pushed, mut slid, mut total) = (0, 0, 0);
        for round in 0..300 {
            let mut group = LaneGroup {
                live: LANES,
                active: points,
                points: vec![V4::ZERO; points],
                start: vec![V4::ZERO; points],
                inv_mass: vec![F4::ONE; points],
                grip_left: vec![V4::ZERO; points],
                grip_anchor: vec![V4::ZERO; points],
                end_radius: F4::new([0.0025, WEIGHT_RADIUS, 0.0025, WEIGHT_RADIUS]),
                ..LaneGroup::default()
            };
            // Lanes near all four triangles, the floor's, the wall alone, none.
            let ranges = [0..4, 0..2, 2..3, 0..0];
            for l in 0..LANES {
                group.lanes[l].triangles = ranges[(l + round) % 4].clone();
            }
            // Where each lane's points are: around the seam, an edge, the
            // wall's foot, the slope, or over the middle.
            let spots = [
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(-2.999, 0.0, 1.0),
                Vec3::new(2.998, 0.0, 0.5),
                Vec3::new(2.7, 0.2, 2.7),
                Vec3::new(1.0, 0.0, -1.0),
            ];
            let mut want: Vec<Vec<(Vec3, Grip)>> = Vec::new();
            for l in 0..LANES {
                let spot = spots[(round + 3 * l) % spots.len()];
                for i in 0..points {
                    let p = spot + random() * Vec3::new(0.004, 0.006, 0.004);
                    group.points[i].set_lane(l, p);
                    if (round + i) % 97 == 5 && l == 1 {
                        group.points[i].set_lane(l, Vec3::NAN);
                    }
                }
                want.push(Vec::new());
            }
            let mut grips: Vec<Vec<Grip>> = vec![Vec::new(); LANES];
            for substep in 0..4 {
                for half in 0..2 {
                    let first = substep == 0 && half == 0;
                    for i in 0..points {
                        if half == 0 {
                            group.start[i] = group.points[i];
                        }
                        // The fall or the chain's pull in between.
                        let mut p = group.points[i];
                        for l in 0..LANES {
                            let step = random() * Vec3::new(0.002, 0.003, 0.002);
                            p.set_lane(l, p.lane(l) + step);
                        }
                        group.points[i] = p;
                    }
                    let before = group.points.clone();
                    for (l, grips) in grips.iter_mut().enumerate() {
                        let range = group.lanes[l].triangles.clone();
                        let near = &triangles[range.start as usize..range.end as usize];
                        if first {
                            *grips = (0..points)
                                .map(|i| Grip::new(group.start[i].lane(l)))
                                .collect();
                        }
                        want[l] = (0..points)
                            .map(|i| {
                                let radius = group.radius(i).as_array()[l];
                                let (start, point) = (group.start[i].lane(l), before[i].lane(l));
                                let grip = &mut grips[i];
                                if near.is_empty() || i == 0 {
                                    return (point, *grip);
                                }
                                let p = push_out_of_room(point, start, radius, 0.5, near, grip);
                                (p, *grip)
                            })
                            .collect();
                    }
                    group.push_out_of_room(&triangles, first);
                    for (l, want) in want.iter().enumerate() {
                        if group.lanes[l].triangles.is_empty() {
                            continue;
                        }
                        for (i, (p, grip)) in want.iter().enumerate().skip(1) {
                            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                            let got = group.points[i].lane(l);
                            let ctx = format!("round {round} substep {substep} lane {l} point {i}");
                            assert_eq!(bits(got), bits(*p), "{ctx}: {got} against {p}");
                            let left = group.grip_left[i].lane(l);
                            assert_eq!(bits(left), bits(grip.left), "{ctx}");
                            if grip.left != Vec3::ZERO || p.is_nan() {
                                let anchor = group.grip_anchor[i].lane(l);
                                assert_eq!(bits(anchor), bits(grip.anchor), "{ctx}");
                            }
                            pushed += usize::from(*p != before[i].lane(l));
                            slid += usize::from(grip.left == Vec3::ZERO && *p != before[i].lane(l));
                            total += 1;
                        }
                    }
                }
            }
        }
        assert!(
            pushed > total / 10 && slid > total / 50,
            "{pushed} pushed, {slid} slid of {total}"
        );
    }
}
