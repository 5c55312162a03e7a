//! Which of a lane group's points may touch the room this substep, four
//! lanes at once, so that the pushes out of the room (`collide`, point by
//! point) run only for them: the planes of the room's triangles near each
//! ribbon (a plane once, however many triangles lie in it), lined up across
//! the lanes (the `k`th of each lane's), give each point's height over each
//! plane in one pass; a point clear of every plane by more than
//! its radius, with no friction held from an earlier push this step, is
//! one the push would leave as it is.

use super::collide::NearTriangle;
use super::lane_group::LaneGroup;
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

impl LaneGroup {
    /// Lines up the lanes' room triangles for the step (their lists are the
    /// step's); no point holds friction yet.
    pub(super) fn line_up_room(&mut self, triangles: &[NearTriangle]) {
        self.room_slots.clear();
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

    /// Notes whether lane `l`'s point `i` holds friction against the room
    /// after a push (`grips`), which keeps it among the points pushed.
    pub(super) fn note_grip(&mut self, l: usize, i: usize) {
        let holds = self.grips[i * LANES + l].left != glam::Vec3::ZERO;
        let bit = 1u8 << l;
        if holds {
            self.gripped[i] |= bit;
        } else {
            self.gripped[i] &= !bit;
        }
    }
}
