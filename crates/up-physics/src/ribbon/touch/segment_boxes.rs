//! Every segment's box as its points now stand, kept for a pass of the
//! ribbons' contacts: most of a step's pairs, found for its whole sweep,
//! are apart at any one pass, and a pair's two boxes, read side by side,
//! tell so for a fraction of what reading its four points out of the lane
//! groups costs. Made at each pass's start (and at the step's end, for the
//! pairs left touching) and made again, for the three segments a push can
//! move, after each push, so a pair's gap is the one its points give at
//! that moment, bit for bit.

use glam::Vec3;

use super::super::lane_group::LaneGroup;
use super::super::RIBBON_RADIUS;
use super::{Segment, Touching};
use crate::solver::lanes::{F4, LANES};

/// A segment's box and the most its radius can be, m: half a cache line.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(32))]
struct SegmentBox {
    low: Vec3,
    radius: f32,
    high: Vec3,
}

/// The boxes of every lane group's segments, group after group, a
/// group's in segment order, each segment's four lanes side by side; and
/// where the step's pairs' two boxes are, read in the pairs' order.
#[derive(Clone, Debug, Default)]
pub(crate) struct SegmentBoxes {
    boxes: Vec<SegmentBox>,
    /// Per group: where its boxes start in `boxes`.
    offsets: Vec<u32>,
    /// Per pair: its two segments' boxes in `boxes`.
    pairs: Vec<[u32; 2]>,
    /// Per group: whether a pair has a segment of it (the others' boxes
    /// are not made).
    paired: Vec<bool>,
}

impl SegmentBox {
    fn new(p0: Vec3, p1: Vec3, radius: f32) -> SegmentBox {
        SegmentBox {
            low: p0.min(p1),
            radius,
            high: p0.max(p1),
        }
    }

    /// Whether the boxes, each grown by its radius and `within` more, do
    /// not meet: along some axis, what lies between them less the radii is
    /// more than `within` (the same test, bit for bit, as the largest of
    /// these being positive).
    #[inline(always)]
    fn apart(&self, other: &SegmentBox, within: f32) -> bool {
        let reach = Vec3::splat(self.radius + other.radius + within);
        let beyond = (self.low - other.high - reach).cmpgt(Vec3::ZERO);
        let below = (other.low - self.high - reach).cmpgt(Vec3::ZERO);
        (beyond | below).any()
    }
}

impl SegmentBoxes {
    /// Readies the step's passes over `pairs` of segments of `groups`,
    /// once the pairs are found.
    pub fn begin(&mut self, groups: &[LaneGroup], pairs: &[Touching]) {
        self.offsets.clear();
        let mut first = 0;
        for g in groups {
            self.offsets.push(first);
            first += (g.points.len().saturating_sub(1) * LANES) as u32;
        }
        self.boxes.resize(first as usize, SegmentBox::default());
        self.paired.clear();
        self.paired.resize(groups.len(), false);
        for p in pairs {
            self.paired[p.a.group as usize] = true;
            self.paired[p.b.group as usize] = true;
        }
        self.pairs.clear();
        let offsets = &self.offsets;
        let at = |s: Segment| index(offsets, s) as u32;
        self.pairs.extend(pairs.iter().map(|p| [at(p.a), at(p.b)]));
    }

    /// Per group: whether a pair has a segment of it.
    pub fn paired(&self) -> &[bool] {
        &self.paired
    }

    /// Makes the paired groups' segments' boxes from their points as they
    /// now are, for passes over the `pairs` pairs `begin` was given: a
    /// segment's four lanes at once.
    pub fn make(&mut self, groups: &[LaneGroup], pairs: usize) {
        assert_eq!(pairs, self.pairs.len(), "the pairs changed since `begin`");
        let paired = groups.iter().zip(&self.offsets).zip(&self.paired);
        for ((g, &first), _) in paired.filter(|(_, &p)| p) {
            let n = g.points.len().saturating_sub(1);
            let boxes = &mut self.boxes[first as usize..][..n * LANES];
            for (i, boxes) in boxes.chunks_exact_mut(LANES).enumerate() {
                let (p, q) = (&g.points[i], &g.points[i + 1]);
                let (low, high) = (
                    [least(p.x, q.x), least(p.y, q.y), least(p.z, q.z)],
                    [most(p.x, q.x), most(p.y, q.y), most(p.z, q.z)],
                );
                let lane = |v: &[F4; 3], l: usize| {
                    Vec3::new(v[0].as_array()[l], v[1].as_array()[l], v[2].as_array()[l])
                };
                for (l, b) in boxes.iter_mut().enumerate() {
                    *b = SegmentBox {
                        low: lane(&low, l),
                        radius: most_radius(g, l, i),
                        high: lane(&high, l),
                    };
                }
            }
        }
    }

    /// Makes again the boxes of the segments that share a point with
    /// segment `s`, whose two points a push has just moved.
    pub fn moved(&mut self, groups: &[LaneGroup], s: Segment) {
        let g = &groups[s.group as usize];
        let (l, i) = (s.lane as usize, s.index as usize);
        let segments = g.points.len() - 1;
        for k in i.saturating_sub(1)..(i + 2).min(segments) {
            let at = index(
                &self.offsets,
                Segment {
                    index: k as u32,
                    ..s
                },
            );
            self.boxes[at] = segment_box(g, l, k);
        }
    }

    /// Whether pair `k`'s segments' boxes, grown by the most their radii
    /// can be, do not meet, so that their capsules cannot touch.
    #[inline]
    pub fn apart(&self, k: usize) -> bool {
        self.apart_by(k, 0.0)
    }

    /// Whether pair `k`'s capsules are more than `within` m apart by their
    /// boxes.
    #[inline(always)]
    pub fn apart_by(&self, k: usize, within: f32) -> bool {
        let [a, b] = self.pairs[k];
        self.boxes[a as usize].apart(&self.boxes[b as usize], within)
    }
}

/// Lane by lane the lesser of `a` and `b`, the number where one is not a
/// number, as `f32::min` (which of ±0 aside: no box test tells them
/// apart, the radii being positive).
fn least(a: F4, b: F4) -> F4 {
    (a.simd_lt(b) | b.is_nan()).select(a, b)
}

/// Lane by lane the greater, as `f32::max`.
fn most(a: F4, b: F4) -> F4 {
    (a.simd_gt(b) | b.is_nan()).select(a, b)
}

/// Where segment `s`'s box is, the groups' boxes starting at `offsets`.
fn index(offsets: &[u32], s: Segment) -> usize {
    offsets[s.group as usize] as usize + s.index as usize * LANES + s.lane as usize
}

/// Segment `i` of lane `l` of `g`: its points' box and the most its radius
/// can be (a weighted end's, on a ribbon's last segment).
fn segment_box(g: &LaneGroup, l: usize, i: usize) -> SegmentBox {
    let (p0, p1) = (g.points[i].lane(l), g.points[i + 1].lane(l));
    SegmentBox::new(p0, p1, most_radius(g, l, i))
}

/// The most segment `i` of lane `l` of `g` can be wide, m: a weighted
/// end's radius on the ribbon's last segment.
fn most_radius(g: &LaneGroup, l: usize, i: usize) -> f32 {
    if i + 2 == g.points.len() {
        g.end_radius.as_array()[l].max(RIBBON_RADIUS)
    } else {
        RIBBON_RADIUS
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ribbon::touch::closest;
    use proptest::prelude::*;

    /// A coordinate, now and then exactly ±0 or not a number.
    fn coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![
            8 => -1.0f32..1.0,
            1 => Just(0.0f32),
            1 => Just(-0.0f32),
            1 => Just(f32::NAN),
        ]
    }

    fn point() -> impl Strategy<Value = Vec3> {
        (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        /// The comparisons decide as the largest gap did, not a number included.
        #[test]
        fn apart_is_the_largest_gap_positive(
            a in (point(), point(), 0.0f32..0.05),
            b in (point(), point(), 0.0f32..0.05),
            within in prop_oneof![Just(0.0f32), 0.0f32..0.01],
        ) {
            let (a, b) = (SegmentBox::new(a.0, a.1, a.2), SegmentBox::new(b.0, b.1, b.2));
            let reach = Vec3::splat(a.radius + b.radius + within);
            let gap = ((a.low - b.high).max(b.low - a.high) - reach).max_element();
            prop_assert_eq!(a.apart(&b, within), gap > 0.0);
        }

        /// The four-lane least and most are `f32::min` and `max`, lane by
        /// lane, not a number included (±0 either way).
        #[test]
        fn least_and_most_are_min_and_max(
            a in prop::array::uniform4(coordinate()),
            b in prop::array::uniform4(coordinate()),
        ) {
            let same = |x: f32, y: f32| x == y || (x.is_nan() && y.is_nan());
            let (lo, hi) = (least(F4::new(a), F4::new(b)), most(F4::new(a), F4::new(b)));
            for l in 0..LANES {
                prop_assert!(same(lo.as_array()[l], a[l].min(b[l])), "{a:?} {b:?}");
                prop_assert!(same(hi.as_array()[l], a[l].max(b[l])), "{a:?} {b:?}");
            }
        }

        /// Capsules whose boxes are apart are further apart than their radii.
        #[test]
        fn apart_capsules_do_not_touch(
            a in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
            da in (-0.1f32..0.1, -0.1f32..0.1, -0.1f32..0.1),
            b in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
            db in (-0.1f32..0.1, -0.1f32..0.1, -0.1f32..0.1),
            radii in (0.0f32..0.05, 0.0f32..0.05),
        ) {
            let (a0, b0) = (Vec3::new(a.0, a.1, a.2), Vec3::new(b.0, b.1, b.2));
            let (a1, b1) = (a0 + Vec3::new(da.0, da.1, da.2), b0 + Vec3::new(db.0, db.1, db.2));
            let boxes = (SegmentBox::new(a0, a1, radii.0), SegmentBox::new(b0, b1, radii.1));
            if boxes.0.apart(&boxes.1, 0.0) {
                let (s, t) = closest::segments(a0, a1, b0, b1);
                let distance = (b0 + (b1 - b0) * t).distance(a0 + (a1 - a0) * s);
                prop_assert!(distance > radii.0 + radii.1, "{distance}");
            }
        }
    }
}
