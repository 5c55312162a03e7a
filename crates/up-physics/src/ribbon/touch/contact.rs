//! A projection of the ribbons' contacts, three times a substep
//! (`RibbonTouch::project`): each pair's closest points pushed apart to the
//! sum of their radii, on the side the pair keeps, with Coulomb friction on
//! their slide over the substep, in the pairs' order.

use glam::Vec3;

use super::super::lane_group::LaneGroup;
use super::super::RIBBON_RADIUS;
use super::points_then::PointsThen;
use super::{closest, RibbonTouch, Segment, Touching};

/// Closer than this, the closest points give no direction, m.
const NO_DIRECTION: f32 = 1e-7;

/// A segment as it stands: its two points and the radius at its end point.
struct Ends {
    p: [Vec3; 2],
    end_radius: f32,
    last: bool,
}

fn ends(groups: &[LaneGroup], s: Segment) -> Ends {
    let g = &groups[s.group as usize];
    let (l, i) = (s.lane as usize, s.index as usize);
    Ends {
        p: [g.points[i].lane(l), g.points[i + 1].lane(l)],
        end_radius: g.end_radius.as_array()[l],
        last: i + 2 == g.points.len(),
    }
}

/// Where segment `s`'s points began the substep and their inverse masses:
/// read only for a pair that touches (most pairs, found before they touch,
/// do not).
fn starts(groups: &[LaneGroup], s: Segment) -> ([Vec3; 2], [f32; 2]) {
    let g = &groups[s.group as usize];
    let (l, i) = (s.lane as usize, s.index as usize);
    (
        [g.start[i].lane(l), g.start[i + 1].lane(l)],
        [g.inv_mass[i].as_array()[l], g.inv_mass[i + 1].as_array()[l]],
    )
}

/// Moves segment `s`'s points by `d0` and `d1`.
fn shift(groups: &mut [LaneGroup], s: Segment, d0: Vec3, d1: Vec3) {
    let g = &mut groups[s.group as usize];
    g.pushed = true;
    let (l, i) = (s.lane as usize, s.index as usize);
    let (q0, q1) = (g.points[i].lane(l) + d0, g.points[i + 1].lane(l) + d1);
    g.points[i].set_lane(l, q0);
    g.points[i + 1].set_lane(l, q1);
}

/// The closest points' parameters on `a` and `b` for `pair`.
fn parameters(pair: &Touching, a: &Ends, b: &Ends) -> (f32, f32) {
    if pair.end_a {
        (1.0, closest::point_segment(a.p[1], b.p[0], b.p[1]))
    } else if pair.end_b {
        (closest::point_segment(b.p[1], a.p[0], a.p[1]), 1.0)
    } else {
        closest::segments(a.p[0], a.p[1], b.p[0], b.p[1])
    }
}

fn at(p: [Vec3; 2], s: f32) -> Vec3 {
    p[0] + (p[1] - p[0]) * s
}

/// Radius of `e` at parameter `s` in a contact that is (`end`) or is not its
/// weighted end's: the weight's only at the end itself.
fn radius(e: &Ends, s: f32, end: bool) -> f32 {
    if end || (e.last && s >= 1.0) {
        e.end_radius.max(RIBBON_RADIUS)
    } else {
        RIBBON_RADIUS
    }
}

/// Readies `pair` as its segments began the step (`then`, of `groups`):
/// its side (the unit line from its closest point on `a` to that on `b`;
/// any unit vector if they meet) and the overlap it may keep this step, of
/// the `push_out` m taken out of what it began with.
fn begin(pair: &mut Touching, groups: &[LaneGroup], then: &PointsThen, push_out: f32) {
    let ends_then = |s: Segment| Ends {
        p: then.segment(s),
        ..ends(groups, s)
    };
    let (a, b) = (ends_then(pair.a), ends_then(pair.b));
    let (s, t) = parameters(pair, &a, &b);
    let d = at(b.p, t) - at(a.p, s);
    let distance = d.length();
    pair.normal = if distance > NO_DIRECTION {
        d / distance
    } else {
        let across = (a.p[1] - a.p[0]).cross(b.p[1] - b.p[0]);
        across.try_normalize().unwrap_or(Vec3::Y)
    };
    let overlap = radius(&a, s, pair.end_a) + radius(&b, t, pair.end_b) - distance;
    pair.allowed = (overlap - push_out).max(0.0);
    pair.begun = true;
}

impl RibbonTouch {
    /// Projects every pair once, in order, on the groups' points as the
    /// substep's fall and pushes left them, each by at most `most` m. A
    /// pair whose segments' boxes, grown by the most their radii can be, do
    /// not meet cannot touch and is passed over on the boxes alone
    /// (`segment_boxes`; most of a step's pairs, found for its whole sweep,
    /// are apart at any one pass): it keeps the side it last had, which is
    /// how a pair found apart keeps the side it was found on.
    pub(crate) fn project(&mut self, groups: &mut [LaneGroup], most: f32) {
        for g in groups.iter_mut() {
            g.held_lanes = 0;
        }
        self.held.rows.clear();
        self.boxes.make(groups, self.pairs.len());
        self.pass_began.take(groups, self.boxes.paired());
        for k in 0..self.pairs.len() {
            if self.boxes.apart(k) {
                continue;
            }
            let mut pair = self.pairs[k];
            if !pair.begun {
                begin(&mut pair, groups, &self.step_began, self.push_out);
            }
            let (a, b) = (ends(groups, pair.a), ends(groups, pair.b));
            let began = [
                self.pass_began.segment(pair.a),
                self.pass_began.segment(pair.b),
            ];
            let friction = self.friction;
            if let Some(pushed) = project_pair(&mut pair, groups, &a, &b, began, friction, most) {
                let side = |seg: Segment, at: f32| super::held::Side {
                    group: seg.group,
                    lane: seg.lane,
                    segment: seg.index,
                    at,
                };
                self.boxes.moved(groups, pair.a);
                self.boxes.moved(groups, pair.b);
                let grip = pushed.slide < self.grip_slide;
                // A contact at rest is left to the passes (`HOLD_DEPTH`).
                if !grip
                    || pushed.depth > super::HOLD_DEPTH
                    || moves_a_weight(groups, pair.a)
                    || moves_a_weight(groups, pair.b)
                {
                    let (a, b) = (side(pair.a, pushed.s), side(pair.b, pushed.t));
                    self.hold(groups, a, b, pushed.normal, grip);
                }
            }
            self.pairs[k] = pair;
        }
    }
}

/// Below this sine of the angle between two segments they are taken as
/// parallel: their common perpendicular gives no side.
const PARALLEL_SINE: f32 = 0.25;

/// The side `b` is on from `a` (a unit vector) and how far along it their
/// closest points `s`, `t` lie, m, negative where they have passed through
/// each other since `pair.normal` was last set. Where the closest points
/// lie inside both segments (and these cross at an angle) the side is their
/// common perpendicular `(a1 − a0) × (b1 − b0)`, turned toward the kept
/// side: it turns only as the segments turn, not as they move, so a segment
/// swept through another shows as a distance turned negative whatever its
/// speed. Elsewhere (a segment's end nearest the other, or the two side by
/// side) the line between the closest points, which turns about an end as a
/// segment slides round it: passed through where it turned more than a
/// right angle.
fn side(pair: &Touching, a: &Ends, b: &Ends, s: f32, t: f32) -> (Vec3, f32) {
    let d = at(b.p, t) - at(a.p, s);
    let inside = |x: f32| x > 0.0 && x < 1.0;
    if !pair.end_a && !pair.end_b && inside(s) && inside(t) {
        let (da, db) = (a.p[1] - a.p[0], b.p[1] - b.p[0]);
        let across = da.cross(db);
        let sine2 = PARALLEL_SINE * PARALLEL_SINE;
        if across.length_squared() > sine2 * da.length_squared() * db.length_squared() {
            let n = across.normalize();
            let n = if n.dot(pair.normal) < 0.0 { -n } else { n };
            return (n, d.dot(n));
        }
    }
    let distance = d.length();
    if distance > NO_DIRECTION {
        let n = d / distance;
        if n.dot(pair.normal) < 0.0 {
            (-n, -distance)
        } else {
            (n, distance)
        }
    } else {
        (pair.normal, 0.0)
    }
}

/// A pair's projection: how far it was pushed apart, m, its normal, its
/// closest points' parameters (a row of the solve that follows, `held`),
/// and how far they slid past each other this substep, m.
struct Pushed {
    depth: f32,
    normal: Vec3,
    s: f32,
    t: f32,
    slide: f32,
}

/// `pair`, of segments as `a` and `b` stand, pushed apart if its capsules
/// overlap or have passed through each other, with friction on the slide
/// from the substep's start to where the segments stood as the pass began
/// (`began`): the moves of this pass's earlier pairs are not slides of
/// this pair (taken for one, each push would drag the next pair's points
/// back along the ribbon, and the passes would walk a draped ribbon toward
/// one end).
fn project_pair(
    pair: &mut Touching,
    groups: &mut [LaneGroup],
    a: &Ends,
    b: &Ends,
    began: [[Vec3; 2]; 2],
    friction: f32,
    most: f32,
) -> Option<Pushed> {
    let (s, t) = parameters(pair, a, b);
    let reach = radius(a, s, pair.end_a) + radius(b, t, pair.end_b);
    let (normal, distance) = side(pair, a, b, s, t);
    pair.normal = normal;
    let depth = (reach - pair.allowed - distance).min(most);
    if depth <= 0.0 {
        return None;
    }
    let ((a_start, a_inv_mass), (b_start, b_inv_mass)) =
        (starts(groups, pair.a), starts(groups, pair.b));
    let wa = [(1.0 - s) * a_inv_mass[0], s * a_inv_mass[1]];
    let wb = [(1.0 - t) * b_inv_mass[0], t * b_inv_mass[1]];
    let w = (1.0 - s) * wa[0] + s * wa[1] + (1.0 - t) * wb[0] + t * wb[1];
    if w <= 0.0 {
        return None;
    }
    // The push: b along the normal, a against it, by inverse mass.
    let push = normal * (depth / w);
    // Friction on what the closest points slid past each other this
    // substep, taken out whole while the push could hold it, else by
    // the push times the coefficient.
    let [a_began, b_began] = began;
    let slid = (at(b_began, t) - at(b_start, t)) - (at(a_began, s) - at(a_start, s));
    let slid = slid - slid.dot(normal) * normal;
    let slide = slid.length();
    let limit = friction * depth;
    let held = if slide > limit && slide > 0.0 {
        limit / slide
    } else {
        1.0
    };
    let grip = -slid * (held / w);
    let impulse = push + grip;
    shift(groups, pair.a, -wa[0] * impulse, -wa[1] * impulse);
    shift(groups, pair.b, wb[0] * impulse, wb[1] * impulse);
    Some(Pushed {
        depth,
        normal,
        s,
        t,
        slide,
    })
}

/// Where two ribbons touch at a step's end, for drawing (`World::ribbon_contacts`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RibbonContact {
    /// Midway between the two segments' closest points, m.
    pub point: Vec3,
    /// Unit, from the first segment toward the second (the side it keeps).
    pub normal: Vec3,
    /// Between the two capsules' surfaces along `normal`, m: negative where
    /// they overlap (or have passed through each other).
    pub separation: f32,
}

impl RibbonTouch {
    /// Keeps the step's pairs within `within` m of touching as their
    /// segments end it in `groups` (read before the lanes are handed back).
    /// A pair whose boxes are further apart is not touching, whichever side
    /// it keeps: one that passed through another and drew away would
    /// otherwise be listed at a separation of minus the gap between them.
    pub(crate) fn keep_touching(&mut self, groups: &[LaneGroup], within: f32) {
        self.touching.clear();
        self.boxes.make(groups, self.pairs.len());
        for (k, pair) in self.pairs.iter().enumerate() {
            if self.boxes.apart_by(k, within) {
                continue;
            }
            let mut pair = *pair;
            if !pair.begun {
                begin(&mut pair, groups, &self.step_began, self.push_out);
            }
            let (a, b) = (ends(groups, pair.a), ends(groups, pair.b));
            let (s, t) = parameters(&pair, &a, &b);
            let reach = radius(&a, s, pair.end_a) + radius(&b, t, pair.end_b);
            let (normal, distance) = side(&pair, &a, &b, s, t);
            if distance - reach <= within {
                self.touching.push(RibbonContact {
                    point: 0.5 * (at(a.p, s) + at(b.p, t)),
                    normal,
                    separation: distance - reach,
                });
            }
        }
    }
}

/// Whether segment `s` ends at its ribbon's weight, free to move (not tied,
/// grabbed or resting): a pass's push moves the light ribbon against it
/// more than the weight, and the chain's tension pulls the ribbon back
/// through it in a solve that does not see the contact (a settled
/// bouquet's ribbons cross). A fixed weight's contacts at rest are the
/// passes' as any others (a drape over one holds by their friction).
fn moves_a_weight(groups: &[LaneGroup], s: Segment) -> bool {
    let g = &groups[s.group as usize];
    let (l, last) = (s.lane as usize, g.points.len() - 1);
    s.index as usize + 1 == last
        && g.end_radius.as_array()[l] > RIBBON_RADIUS
        && g.inv_mass[last].as_array()[l] > 0.0
}
