//! Ribbons touching ribbons: each segment is a capsule of `RIBBON_RADIUS`
//! (a weighted end a sphere of its weight's radius), and segments of
//! different ribbons, and of one ribbon with itself two segments apart or
//! more, are kept from passing through each other (in a packed crowd some
//! still do: see docs/physics.md).
//!
//! Once a step, before the substeps, the segments that may touch are paired
//! (`broad`): each awake ribbon's box, widened by how far its points can
//! move in the step (their speed, gravity's fall and a margin), swept along
//! x for boxes that meet, then the two ribbons' segment boxes against each
//! other, each widened by how far its own points and their neighbours can
//! move; a ribbon against itself only where it is slack enough to fold back
//! on itself. The pairs are speculative, found before they touch, so that a
//! segment swept fast across another is caught in the substep it would
//! cross.
//!
//! In each substep the pairs are projected in their fixed order
//! (`contact`), taking turns with the chains' direct solve: between the
//! points' fall and pushes and the solve (`LaneGroup::substep_before_solve`,
//! `substep_solve`), so that the solve starts from ribbons apart; after it,
//! followed by a second solve of the groups a contact moved
//! (`substep_solve_again`, `SOLVES`); and once more before the velocities
//! (`substep_finish`), each pair by at most `LAST_PASS_MOST`, so that the
//! substep ends with a fold held (a solve that follows the last push pulls
//! a ribbon folded over another back into it substep after substep, until
//! the fold's point slips through). A projection pushes the closest points
//! of the two segments as they now are apart to the sum of their radii,
//! each segment's two points by their share and inverse mass (so each
//! ribbon pushes the other), with position-level Coulomb friction on what
//! the closest points slid past each other from the substep's start to the
//! pass's (the pass's own earlier pushes are no slide; Müller et al.,
//! "Detailed rigid body simulation with extended position based dynamics",
//! 2020). A pair keeps the side it was found on (`contact::side`): where
//! its closest points lie inside both segments and these cross at an
//! angle, along their common perpendicular, which turns only as the
//! segments turn, so that a segment swept through another shows as a
//! separation turned negative; elsewhere along the line between the closest
//! points, passed through where that turned more than a right angle. A pair
//! that passed through is pushed back to the side it came from. A pass
//! skips a pair whose segments' boxes, grown by their radii, do not meet
//! (most of the pairs, found for the step's whole sweep, at any one pass),
//! reading only the two boxes of a table it keeps as it pushes
//! (`segment_boxes`): the pair keeps the side it last had, and a pair's
//! side is first found, from where its segments began the step, when a
//! pass first comes to it with its boxes meeting. The lengths the last
//! push changed are the next substep's solve's to restore.
//!
//! The chains' solves that follow a pass see the contacts it pushed apart
//! that slide fast, that it pushed far or that touch a movable weight
//! (`HOLD_DEPTH`; `held`): the ribbons those link are solved together, the
//! contacts rows of the same solve that may push but not pull, so that a
//! segment caught on another, dragged by a carried end or a taut pull, is
//! not pulled back through it by a solve that does not see it; with
//! friction, each slow one with two rows that hold it from sliding within
//! the friction cone of the push the solve gives it. Contacts at rest are
//! left to the passes, whose friction follows each pass's push.
//!
//! The pass and the linked ribbons' solve run on one thread in a fixed
//! order, so the result is the same
//! on any number of threads; with no pair in a step the substeps run as
//! they would without it (one pass per group, bit for bit), so ribbons that
//! never touch, and sleeping ones, cost no more than the pairing.

mod box_lanes;
mod broad;
mod closest;
mod contact;
pub(crate) mod held;
mod points_then;
mod segment_boxes;
pub use contact::RibbonContact;

pub mod crossings;
pub mod linking;

use glam::Vec3;
use up_geom::Aabb;

/// Friction of a ribbon on a ribbon, polypropylene on polypropylene: a
/// guess (film on film is quoted at 0.3–0.5; curling ribbon, ribbed and
/// often crimped, grips at least as well).
pub const RIBBON_ON_RIBBON_FRICTION: f32 = 0.4;

/// Below this speed past each other over a substep, m/s, two ribbons'
/// touching points are gripped in the linked solve (`held`), within the
/// friction cone, if they are held there at all (`HOLD_DEPTH`); faster,
/// they slide and only the passes' friction acts. Gripping every contact
/// lets a ribbon swept across a taut one at 10 m/s through it.
pub const GRIP_SLIDE_SPEED: f32 = 0.25;

/// A contact that slides slower than `GRIP_SLIDE_SPEED` is held in the
/// linked solve (`held`) only where a pass pushed it apart by more than
/// this, m (a solve pulling a strand nearly a ribbon's radius into
/// another), or where it touches a weight free to move: a contact at rest
/// is left to the passes, whose friction follows each pass's push. Held, a
/// resting contact's push row takes the chains' tension off the passes'
/// pushes, and so off their friction: the drape over the tied weight held
/// 43–59 % under the capstan law with all held, 22–23 % with these left
/// out (docs/perf-log.md).
pub const HOLD_DEPTH: f32 = 2e-3;

/// Fastest two capsules that begin a step overlapping are pushed apart, m/s
/// (laid out on one spot, as a bouquet's weights are): at once, they would
/// fly apart; those that overlap only within the step (a crossing caught)
/// are pushed out whole.
pub const OVERLAP_PUSH_OUT_SPEED: f32 = 0.1;

/// The chains' solves a substep where ribbons touch, each after a
/// projection of the contacts (and one more projection after the last): a
/// ribbon pulled taut over another is pulled back into it by a solve that
/// does not see the contact, and one more turn halves the crossings of 500
/// ribbons released together; the second solve runs only for the groups
/// whose points a contact moved.
pub(crate) const SOLVES: usize = 2;

/// The most a pair is pushed in a substep's last pass, after the last
/// solve, m: a fold that the solve pulls on by a fraction of a millimetre
/// a substep is held, while a larger correction (a pair caught passing
/// through, a tangle pulled taut), which would leave the ribbons stretched
/// at the step's end by as much, waits for the next substep's first pass,
/// the pair keeping its side (the bouquet's ribbons, pulled up through each
/// other's weights, ended steps stretched 2.4 % with the whole correction).
pub(crate) const LAST_PASS_MOST: f32 = 1e-3;

/// A segment: points `index` and `index + 1` of the ribbon in lane `lane`
/// of lane group `group`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Segment {
    pub group: u32,
    pub lane: u32,
    pub index: u32,
}

/// Two segments that may touch this step.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Touching {
    pub a: Segment,
    pub b: Segment,
    /// The contact is `a`'s (or `b`'s) weighted end, a sphere, against the
    /// other segment.
    pub end_a: bool,
    pub end_b: bool,
    /// Whether `normal` and `allowed` are set: when a pass first comes to
    /// the pair with its boxes meeting (most pairs never), from where the
    /// segments began the step (`contact::begin`).
    pub begun: bool,
    /// From `a` toward `b` as they last stood (at the step's start, or last
    /// projected): the side `b` keeps.
    pub normal: Vec3,
    /// How far they may still overlap this step, m: what they began the
    /// step overlapping less `OVERLAP_PUSH_OUT_SPEED` times the step.
    pub allowed: f32,
}

/// An awake ribbon's box for the step, and what says whether it can touch
/// itself.
#[derive(Clone, Copy, Debug)]
struct RibbonBox {
    aabb: Aabb,
    group: u32,
    lane: u32,
    segments: u32,
    /// How far any of its points may move this step (its fastest point's
    /// speed times the step, and the margin; a segment's box is grown by its
    /// own share, `broad::RibbonTouch::boxes_of`), and its points' largest
    /// radius, m.
    reach: f32,
    radius: f32,
    /// Its length along its points less the distance between its ends, and
    /// its shortest segment, m.
    slack: f32,
    shortest: f32,
    /// Its points' speeds start here in `RibbonTouch::speeds`.
    first_speed: u32,
    /// Its segments' boxes start here in `RibbonTouch::swept_boxes`
    /// (`u32::MAX`: not made this step).
    first_box: u32,
    /// The same boxes, four to a group, start here in
    /// `RibbonTouch::swept_lanes` (`u32::MAX`: not made this step).
    first_lanes: u32,
}

/// The ribbons' contacts with each other, kept between steps for their
/// buffers (no allocation a step once grown).
#[derive(Clone, Debug)]
pub(crate) struct RibbonTouch {
    /// Whether ribbons touch at all (`WorldDef::ribbon_contacts`).
    pub enabled: bool,
    /// Friction of a ribbon on a ribbon (`WorldDef::ribbon_friction`).
    pub friction: f32,
    /// How much of a pair's overlap at the step's start is taken out in the
    /// step, m.
    pub push_out: f32,
    /// Below this slide over the substep a contact is gripped (its speed
    /// `GRIP_SLIDE_SPEED` times the substep), m.
    grip_slide: f32,
    /// The step's pairs, in the order they are projected.
    pub pairs: Vec<Touching>,
    /// The pairs touching at the step's end (`keep_touching`), for drawing.
    pub touching: Vec<RibbonContact>,
    ribbons: Vec<RibbonBox>,
    /// The awake ribbons by their boxes' least x (ties by index).
    sorted: Vec<u32>,
    /// Their boxes in that order, for the sweep to read side by side.
    sorted_boxes: Vec<Aabb>,
    swept_boxes: Vec<Aabb>,
    swept_lanes: Vec<box_lanes::BoxLanes>,
    /// The step's length, s, and the margin a point may move beyond its
    /// speed times it, m (gravity's fall and the speculative distance).
    dt: f32,
    margin: f32,
    /// The awake ribbons' points' speeds, m/s, ribbon after ribbon.
    speeds: Vec<f32>,
    /// The last pass's contacts as rows of the chains' solve that follows.
    held: held::HeldSolve,
    /// The paired segments' boxes as the current pass has left them (or
    /// as the step ends, for `keep_touching`).
    boxes: segment_boxes::SegmentBoxes,
    /// The points as the current pass began: where its pairs' slides are
    /// measured to.
    pass_began: points_then::PointsThen,
    /// The points as the step began: where a pair's side is first found.
    step_began: points_then::PointsThen,
}

impl Default for RibbonTouch {
    fn default() -> Self {
        RibbonTouch {
            enabled: false,
            friction: RIBBON_ON_RIBBON_FRICTION,
            push_out: 0.0,
            grip_slide: 0.0,
            pairs: Vec::new(),
            touching: Vec::new(),
            ribbons: Vec::new(),
            sorted: Vec::new(),
            sorted_boxes: Vec::new(),
            swept_boxes: Vec::new(),
            swept_lanes: Vec::new(),
            dt: 0.0,
            margin: 0.0,
            speeds: Vec::new(),
            held: held::HeldSolve::default(),
            boxes: segment_boxes::SegmentBoxes::default(),
            pass_began: points_then::PointsThen::default(),
            step_began: points_then::PointsThen::default(),
        }
    }
}

impl RibbonTouch {
    /// No pair this step: the substeps run without the pass.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Readies a substep of `h` s, before its first pass.
    pub(crate) fn begin_substep(&mut self, h: f32) {
        self.grip_slide = GRIP_SLIDE_SPEED * h;
    }
}
