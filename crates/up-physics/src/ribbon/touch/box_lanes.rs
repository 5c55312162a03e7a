//! Segment boxes four at a time, for the step's pairing (`broad`): one
//! four-lane test says which of four segments' boxes meet a box, where box
//! by box it took four. A lane meets exactly where `Aabb::overlaps` does
//! (the same comparisons; a NaN bound meets nothing), so the pairs found,
//! and their order, are those of the box-by-box test.

use up_geom::Aabb;

use crate::solver::lanes::{LANES, V4};

/// Up to `LANES` boxes; an unused lane holds zeros, and `used` leaves it out.
#[derive(Clone, Copy, Debug)]
pub(super) struct BoxLanes {
    min: V4,
    max: V4,
    /// Bit `l` for a box in lane `l`.
    used: u32,
}

impl BoxLanes {
    /// Appends `boxes` to `out`, `LANES` to a group.
    pub fn push_all(boxes: &[Aabb], out: &mut Vec<BoxLanes>) {
        for chunk in boxes.chunks(LANES) {
            let mut group = BoxLanes {
                min: V4::ZERO,
                max: V4::ZERO,
                used: 0,
            };
            for (l, b) in chunk.iter().enumerate() {
                group.min.set_lane(l, b.min);
                group.max.set_lane(l, b.max);
                group.used |= 1 << l;
            }
            out.push(group);
        }
    }

    /// Which lanes' boxes meet `b` (bit `l` for lane `l`).
    #[inline]
    pub fn meeting(&self, b: &Aabb) -> u32 {
        let (min, max) = (V4::splat(b.min), V4::splat(b.max));
        let below =
            self.min.x.simd_le(max.x) & self.min.y.simd_le(max.y) & self.min.z.simd_le(max.z);
        let above =
            min.x.simd_le(self.max.x) & min.y.simd_le(self.max.y) & min.z.simd_le(self.max.z);
        (below & above).to_bitmask() & self.used
    }
}

/// Groups of `LANES` that hold `boxes` boxes.
pub(super) fn groups_for(boxes: usize) -> usize {
    boxes.div_ceil(LANES)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Four lanes meet exactly the boxes `Aabb::overlaps` meets: random
    /// boxes, a NaN bound, and boxes that only touch, face on face along
    /// each axis from either side (each of the six comparisons at equality),
    /// over a count that leaves the last group part empty.
    #[test]
    fn four_lanes_meet_the_boxes_one_at_a_time_meets() {
        let mut next = crate::hash::uniform(3);
        let mut random = move || Vec3::new(next(), next(), next());
        let mut boxes: Vec<Aabb> = (0..11)
            .map(|_| {
                let (a, b) = (random(), random());
                Aabb::new(a.min(b), a.max(b))
            })
            .collect();
        boxes[4] = Aabb::new(Vec3::new(0.2, 0.3, f32::NAN), Vec3::splat(0.6));
        let mut lanes = Vec::new();
        BoxLanes::push_all(&boxes, &mut lanes);
        assert_eq!(lanes.len(), groups_for(boxes.len()));
        let mut probes: Vec<Aabb> = (0..500)
            .map(|_| {
                let (a, b) = (random(), random() * 0.3);
                Aabb::new(a, a + b)
            })
            .collect();
        // Face on face: each box's face along each axis, met from outside.
        for other in &boxes {
            for axis in 0..3 {
                let (mut above, mut below) = (*other, *other);
                above.min[axis] = other.max[axis];
                above.max[axis] = other.max[axis] + 0.1;
                below.max[axis] = other.min[axis];
                below.min[axis] = other.min[axis] - 0.1;
                probes.extend([above, below]);
            }
        }
        let (mut met, mut tests) = (0, 0);
        for (k, probe) in probes.iter().enumerate() {
            for (g, group) in lanes.iter().enumerate() {
                let want = (0..LANES)
                    .filter(|l| boxes.get(g * LANES + l).is_some_and(|b| b.overlaps(probe)))
                    .fold(0, |bits, l| bits | 1 << l);
                assert_eq!(group.meeting(probe), want, "probe {k}, group {g}");
                met += want.count_ones();
                tests += 1;
            }
        }
        assert!(
            met > tests / 8 && met < 3 * tests,
            "{met} met in {tests} tests"
        );
        let all = Aabb::new(Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY));
        assert_eq!(
            lanes[2].meeting(&all),
            0b111,
            "the unused lane meets nothing"
        );
    }
}
