//! The lane groups' points as they stood at some moment of a substep (as
//! its first pass began, or as the current pass began), read back by
//! segment.

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
    /// Takes the groups' points as they now are.
    pub fn take(&mut self, groups: &[LaneGroup]) {
        self.points.clear();
        self.offsets.clear();
        for g in groups {
            self.offsets.push(self.points.len() as u32);
            self.points.extend_from_slice(&g.points);
        }
    }

    /// How many points (of four lanes) were taken.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Group `k`'s points as taken.
    pub fn of_group(&self, k: usize, count: usize) -> &[V4] {
        &self.points[self.offsets[k] as usize..][..count]
    }

    /// Where segment `s`'s first point is, counted over every group's.
    pub fn index(&self, s: Segment) -> usize {
        self.offsets[s.group as usize] as usize + s.index as usize
    }

    /// Segment `s`'s two points as taken.
    pub fn segment(&self, s: Segment) -> [Vec3; 2] {
        let (i, l) = (self.index(s), s.lane as usize);
        [self.points[i].lane(l), self.points[i + 1].lane(l)]
    }
}
