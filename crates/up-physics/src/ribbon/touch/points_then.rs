//! The lane groups' points as they stood at some moment (as the step began,
//! or as the current pass of the ribbons' contacts began), read back by
//! segment: only the groups a pair reads are taken, and only theirs may be
//! read back.

use glam::Vec3;

use super::super::lane_group::LaneGroup;
use super::Segment;
use crate::solver::lanes::V4;

/// The groups' points at a moment, group after group.
#[derive(Clone, Debug, Default)]
pub(crate) struct PointsThen {
    points: Vec<V4>,
    /// Per group: where its points start in `points`.
    offsets: Vec<u32>,
}

impl PointsThen {
    /// Takes the points of the groups marked in `read` as they now are
    /// (the others' are not read back).
    pub fn take(&mut self, groups: &[LaneGroup], read: &[bool]) {
        self.points.clear();
        self.offsets.clear();
        for (g, &read) in groups.iter().zip(read) {
            self.offsets.push(self.points.len() as u32);
            if read {
                self.points.extend_from_slice(&g.points);
            }
        }
    }

    /// Where segment `s`'s first point is, counted over the groups taken.
    fn index(&self, s: Segment) -> usize {
        self.offsets[s.group as usize] as usize + s.index as usize
    }

    /// Segment `s`'s two points as taken.
    pub fn segment(&self, s: Segment) -> [Vec3; 2] {
        let (i, l) = (self.index(s), s.lane as usize);
        [self.points[i].lane(l), self.points[i + 1].lane(l)]
    }
}
