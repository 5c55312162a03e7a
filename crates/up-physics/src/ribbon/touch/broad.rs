//! The step's pairs of segments that may touch (`RibbonTouch::find_pairs`):
//! the awake ribbons' boxes swept along x, then, for two ribbons whose boxes
//! meet, the first one's segments that meet the second's box tested against
//! all of the second's segments, four boxes at a time (`box_lanes`).
//! Every order is fixed (the ribbons' solver order, ties broken by it), so
//! the pairs come out the same on any number of threads.

use glam::Vec3;
use up_geom::Aabb;

use super::super::lane_group::RibbonLanes;
use super::super::RIBBON_RADIUS;
use super::box_lanes::{groups_for, BoxLanes};
use super::{RibbonBox, RibbonTouch, Segment, Touching};
use crate::solver::lanes::LANES;

/// The first segments' separation that two segments of one ribbon must
/// have to be paired: neighbours share a point and bend about it.
const SELF_GAP: u32 = 2;

impl RibbonTouch {
    /// Pairs the segments of the awake ribbons in `lanes` that may touch
    /// within a step of `dt` s: each point may move its speed times `dt`
    /// plus `margin` m (gravity's fall and the speculative distance).
    pub(crate) fn find_pairs(&mut self, lanes: &RibbonLanes, dt: f32, margin: f32) {
        self.pairs.clear();
        self.push_out = super::OVERLAP_PUSH_OUT_SPEED * dt;
        self.ribbons.clear();
        self.swept_boxes.clear();
        self.swept_lanes.clear();
        self.speeds.clear();
        (self.dt, self.margin) = (dt, margin);
        if !self.enabled || lanes.order.is_empty() {
            return;
        }
        for &(g, l) in &lanes.order {
            let group = &lanes.groups[g as usize];
            let l_ = l as usize;
            let n = group.points.len() - 1;
            let mut aabb = Aabb::EMPTY;
            let (mut speed, mut along, mut shortest) = (0.0f32, 0.0f32, f32::MAX);
            let mut before: Vec3 = group.points[0].lane(l_);
            let first_speed = self.speeds.len() as u32;
            for i in 0..=n {
                let p: Vec3 = group.points[i].lane(l_);
                aabb = aabb.including(p);
                let v = group.velocities[i].lane(l_).length();
                self.speeds.push(v);
                speed = speed.max(v);
                if i > 0 {
                    let length = p.distance(before);
                    along += length;
                    shortest = shortest.min(length);
                }
                before = p;
            }
            let ends = group.points[0].lane(l_).distance(group.points[n].lane(l_));
            let reach = speed * dt + margin;
            let radius = RIBBON_RADIUS.max(group.end_radius.as_array()[l_]);
            self.ribbons.push(RibbonBox {
                aabb: aabb.expanded(reach + radius),
                group: g,
                lane: l,
                segments: n as u32,
                reach,
                radius,
                slack: (along - ends).max(0.0),
                shortest,
                first_speed,
                first_box: u32::MAX,
                first_lanes: u32::MAX,
            });
        }
        self.sorted.clear();
        self.sorted.extend(0..self.ribbons.len() as u32);
        let ribbons = &self.ribbons;
        self.sorted.sort_unstable_by(|&i, &j| {
            let (a, b) = (
                ribbons[i as usize].aabb.min.x,
                ribbons[j as usize].aabb.min.x,
            );
            a.total_cmp(&b).then(i.cmp(&j))
        });
        // The boxes in that order, for the sweep to read side by side: read
        // through `sorted`, most would miss the cache in a crowd.
        self.sorted_boxes.clear();
        let ribbons = &self.ribbons;
        let in_order = self.sorted.iter().map(|&i| ribbons[i as usize].aabb);
        self.sorted_boxes.extend(in_order);
        for s in 0..self.sorted.len() {
            let i = self.sorted[s] as usize;
            self.pair_with_itself(lanes, i);
            let box_i = self.sorted_boxes[s];
            for t in s + 1..self.sorted.len() {
                let box_j = &self.sorted_boxes[t];
                if box_j.min.x > box_i.max.x {
                    break;
                }
                if box_i.overlaps(box_j) {
                    let j = self.sorted[t] as usize;
                    self.pair_ribbons(lanes, i.min(j), i.max(j));
                }
            }
        }
        // The paired ribbons as they begin the step, where a pair's side is
        // found when a pass first needs it (`contact::begin`).
        self.boxes.begin(&lanes.groups, &self.pairs);
        self.step_began.take(&lanes.groups, self.boxes.paired());
    }

    /// Ribbon `k`'s segments' boxes, made once a step when first needed,
    /// each grown by how far its points may move: their speeds' and their
    /// neighbours' (which pull on them through the segments either side),
    /// the fastest times the step, and the margin. Grown by the ribbon's
    /// fastest point instead, a ribbon whipped at one end paired every
    /// segment it has: a third more pairs in a crowd's release, none of
    /// which came within touching there.
    fn boxes_of(&mut self, lanes: &RibbonLanes, k: usize) -> u32 {
        let r = self.ribbons[k];
        if r.first_box != u32::MAX {
            return r.first_box;
        }
        let first = self.swept_boxes.len() as u32;
        let group = &lanes.groups[r.group as usize];
        let l = r.lane as usize;
        let n = r.segments as usize;
        let end_radius = group.end_radius.as_array()[l];
        let speeds = &self.speeds[r.first_speed as usize..][..=n];
        for i in 0..n {
            let near = &speeds[i.saturating_sub(1)..(i + 3).min(n + 1)];
            let fastest = near.iter().fold(0.0f32, |most, &v| most.max(v));
            let reach = fastest * self.dt + self.margin;
            let radius = if i + 1 == n {
                end_radius.max(RIBBON_RADIUS)
            } else {
                RIBBON_RADIUS
            };
            let (p, q) = (group.points[i].lane(l), group.points[i + 1].lane(l));
            let aabb = Aabb::new(p.min(q), p.max(q)).expanded(reach + radius);
            self.swept_boxes.push(aabb);
        }
        self.ribbons[k].first_lanes = self.swept_lanes.len() as u32;
        BoxLanes::push_all(&self.swept_boxes[first as usize..], &mut self.swept_lanes);
        self.ribbons[k].first_box = first;
        first
    }

    /// The segments of ribbons `a` and `b` (`a < b`, in solver order) whose
    /// boxes meet: each of `a`'s that meets `b`'s box against all of `b`'s,
    /// four at a time (a box of `b`'s that meets one of `a`'s, which lies
    /// within `a`'s box, meets `a`'s box too).
    fn pair_ribbons(&mut self, lanes: &RibbonLanes, a: usize, b: usize) {
        if tied_together(lanes, &self.ribbons[a], &self.ribbons[b]) {
            return;
        }
        self.boxes_of(lanes, a);
        self.boxes_of(lanes, b);
        let (ra, rb) = (self.ribbons[a], self.ribbons[b]);
        let lanes_of = |r: &RibbonBox| {
            let first = r.first_lanes as usize;
            &self.swept_lanes[first..first + groups_for(r.segments as usize)]
        };
        let (lanes_a, lanes_b) = (lanes_of(&ra), lanes_of(&rb));
        let boxes_a = &self.swept_boxes[ra.first_box as usize..][..ra.segments as usize];
        for (ga, group_a) in lanes_a.iter().enumerate() {
            let mut near = group_a.meeting(&rb.aabb);
            while near != 0 {
                let i = ga * LANES + near.trailing_zeros() as usize;
                near &= near - 1;
                for (gb, group_b) in lanes_b.iter().enumerate() {
                    let mut meeting = group_b.meeting(&boxes_a[i]);
                    while meeting != 0 {
                        let j = gb * LANES + meeting.trailing_zeros() as usize;
                        meeting &= meeting - 1;
                        push_pairs(&mut self.pairs, lanes, (&ra, i as u32), (&rb, j as u32));
                    }
                }
            }
        }
    }

    /// Ribbon `k`'s segments `SELF_GAP` or more apart whose boxes meet, of
    /// those the ribbon's slack lets come near each other: two points `m`
    /// segments apart along a ribbon whose ends are its length less `slack`
    /// apart are at least `(m − 1)·shortest − slack` apart.
    fn pair_with_itself(&mut self, lanes: &RibbonLanes, k: usize) {
        let r = self.ribbons[k];
        let n = r.segments;
        let within = r.slack + 2.0 * (r.reach + r.radius);
        if n <= SELF_GAP || (SELF_GAP - 1) as f32 * r.shortest > within {
            return;
        }
        let widest = (within / r.shortest.max(1e-6)) as u32 + 1;
        let first = self.boxes_of(lanes, k) as usize;
        let boxes = &self.swept_boxes[first..][..n as usize];
        for i in 0..n {
            for j in i + SELF_GAP..n.min(i.saturating_add(widest).saturating_add(1)) {
                if boxes[i as usize].overlaps(&boxes[j as usize]) {
                    push_pairs(&mut self.pairs, lanes, (&r, i), (&r, j));
                }
            }
        }
    }
}

/// The contacts of segment `i` of ribbon `a` and segment `j` of ribbon `b`:
/// the two capsules, and each weighted end against the other segment.
fn push_pairs(
    pairs: &mut Vec<Touching>,
    lanes: &RibbonLanes,
    (a, i): (&RibbonBox, u32),
    (b, j): (&RibbonBox, u32),
) {
    let segment = |r: &RibbonBox, index: u32| Segment {
        group: r.group,
        lane: r.lane,
        index,
    };
    let weighted = |r: &RibbonBox, index: u32| {
        index + 1 == r.segments
            && lanes.groups[r.group as usize].end_radius.as_array()[r.lane as usize] > RIBBON_RADIUS
    };
    let pair = Touching {
        a: segment(a, i),
        b: segment(b, j),
        ..Touching::default()
    };
    pairs.push(pair);
    for (end_a, end_b) in [(weighted(a, i), false), (false, weighted(b, j))] {
        if end_a || end_b {
            pairs.push(Touching {
                end_a,
                end_b,
                ..pair
            });
        }
    }
}

/// Whether ribbons `a` and `b` are tied at one point (their held ends
/// within a ribbon's width): one knot holds them, and near it they have no
/// side of each other to keep; they are left to pass through each other.
fn tied_together(lanes: &RibbonLanes, a: &RibbonBox, b: &RibbonBox) -> bool {
    let held_end = |r: &RibbonBox| {
        let g = &lanes.groups[r.group as usize];
        let (l, n) = (r.lane as usize, r.segments as usize);
        (g.inv_mass[n].as_array()[l] == 0.0).then(|| g.points[n].lane(l))
    };
    match (held_end(a), held_end(b)) {
        (Some(p), Some(q)) => p.distance(q) < 2.0 * RIBBON_RADIUS,
        _ => false,
    }
}
