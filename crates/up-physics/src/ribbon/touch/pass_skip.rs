//! Passing over, in a substep's later passes, the pairs that cannot touch,
//! without reading their segments: most of a step's pairs, found for its
//! whole sweep, are apart at any one pass, and reading two segments out of
//! the lane groups is most of what a pass costs for them.
//!
//! The substep's first pass notes how far apart each pair's segment boxes,
//! grown by the segments' radii, were when it came to the pair. A later
//! pass passes over a pair still further apart than the most its four
//! points can have moved since: how far each point now is from where it
//! was as the first pass began, plus every push of it by the passes since
//! (which bounds both how far it had moved when the first pass came to the
//! pair and how far this pass has moved it so far). A pair passed over is
//! one whose boxes would still not meet, which a pass leaves as it is: the
//! results are the same, bit for bit.

use glam::Vec3;

use super::super::lane_group::LaneGroup;
use super::points_then::PointsThen;
use super::Segment;
use crate::solver::lanes::LANES;

/// A bound a little over the sum of the moves, for the rounding of the
/// moves' lengths and of the gaps: relative, and absolute (m; a point near
/// 2 m is stored to 1.2e-7 m).
const SAFETY: f32 = 1.001;
const SAFETY_M: f32 = 1e-6;

/// What the substep's later passes read to pass over a pair.
#[derive(Clone, Debug, Default)]
pub(crate) struct PassSkip {
    /// Whether the substep's first pass is under way (or yet to come).
    first: bool,
    /// Per pair: how far apart its grown boxes were in the first pass, m
    /// (positive: apart; negative: they met; −∞ until measured).
    gap: Vec<f32>,
    /// The groups' points as the first pass began.
    began: PointsThen,
    /// Per point (as in `began`), per lane: its moves by the passes' pushes
    /// since the first pass began (as stored), their lengths summed, m.
    pushed: Vec<[f32; LANES]>,
    /// Per point, per lane: how far it has moved since the first pass
    /// began, as the current pass began, m.
    moved: Vec<[f32; LANES]>,
}

impl PassSkip {
    /// Readies the substep's first pass over `pairs` pairs of `groups`.
    pub fn begin_substep(&mut self, groups: &[LaneGroup], pairs: usize) {
        self.first = true;
        self.gap.clear();
        self.gap.resize(pairs, f32::NEG_INFINITY);
        self.began.take(groups);
        self.pushed.clear();
        self.pushed.resize(self.began.len(), [0.0; LANES]);
        self.moved.clear();
        self.moved.resize(self.began.len(), [0.0; LANES]);
    }

    /// At a pass's start: after the first, how far each point has moved
    /// since it began.
    pub fn begin_pass(&mut self, groups: &[LaneGroup]) {
        if self.first {
            return;
        }
        let mut first = 0;
        for (k, g) in groups.iter().enumerate() {
            let n = g.points.len();
            let began = self.began.of_group(k, n);
            let moved = &mut self.moved[first..][..n];
            first += n;
            for ((now, then), moved) in g.points.iter().zip(began).zip(moved) {
                let d = *now - *then;
                *moved = d.dot(d).to_array().map(f32::sqrt);
            }
        }
    }

    /// Whether the substep's first pass is the one under way.
    pub fn in_first_pass(&self) -> bool {
        self.first
    }

    /// The points as the substep's first pass began.
    pub fn began(&self) -> &PointsThen {
        &self.began
    }

    /// At a pass's end: the first is over.
    pub fn end_pass(&mut self) {
        self.first = false;
    }

    /// Whether the pass may pass over pair `k`, of segments `a` and `b`,
    /// unread: a later pass, and the pair further apart in the first pass
    /// than both its segments can have moved since.
    pub fn passes_over(&self, k: usize, a: Segment, b: Segment) -> bool {
        !self.first && self.gap[k] > SAFETY * (self.bound(a) + self.bound(b)) + SAFETY_M
    }

    /// The most segment `s`'s points can have moved since the first pass
    /// came to a pair of it.
    fn bound(&self, s: Segment) -> f32 {
        let (i, l) = (self.began.index(s), s.lane as usize);
        let most = |v: &[[f32; LANES]]| v[i][l].max(v[i + 1][l]);
        most(&self.moved) + most(&self.pushed)
    }

    /// In the first pass, how far apart pair `k`'s grown boxes are.
    pub fn note_gap(&mut self, k: usize, gap: f32) {
        if self.first {
            self.gap[k] = gap;
        }
    }

    /// A push of segment `s`'s points by `d0` and `d1`, as stored.
    pub fn note_push(&mut self, s: Segment, d0: Vec3, d1: Vec3) {
        let (i, l) = (self.began.index(s), s.lane as usize);
        self.pushed[i][l] += d0.length();
        self.pushed[i + 1][l] += d1.length();
    }
}
