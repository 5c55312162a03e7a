//! A ribbon's points against the room and the balloons, at position level.
//!
//! The room: a point closer to a triangle's inner face than its radius, or
//! one that crossed the face this substep, goes back to the radius in front
//! of it along the face's normal (also within a radius past its border, so
//! the seams between the triangles of a flat floor are not edges), and friction takes back up to μ times that push from its slide
//! along the face (Coulomb at position level, as in Müller et al. 2020). So
//! a ribbon cannot tunnel out through a wall at any speed it reaches, and it
//! lies on the floor instead of sliding off it.
//!
//! A substep pushes a point out of the room twice, before and after its
//! chain is solved, and friction is held over the step's substeps (`Grip`):
//! it takes back the slide from where the point began the step, or last
//! slid to, up to μ times the step's pushes so far. A weight resting on the
//! floor is pushed out in the first push (it fell), while its ribbon's pull
//! moves it along the floor in the chain's solve between, often lifting it
//! clear by a hair, so that the second push, or the next substep's, has no
//! push of its own to take friction from; held over the step, it holds
//! below μ·N and slides at the kinetic rate above (`tests/ribbon_friction.rs`).
//!
//! Balloons: a point inside a balloon's leaf sphere goes out to its surface
//! along the line from the sphere's centre, with the same friction against
//! the balloon's move, so a ribbon draped over a balloon stays draped; the
//! balloon takes the opposite impulse (momentum is kept: a one-way push lets
//! balloons stir each other through their ribbons for ever). The leaves are
//! not placed in the room to be tested: the point is turned into the
//! balloon's frame once and tested there against its shape's tree (shared by
//! every balloon of the shape, so it stays in cache), a little wider than
//! the leaves (`FRAME_SLACK`); only a leaf that passes is placed and the
//! push decided as it would be against that leaf placed, so the result is
//! the same bit for bit as testing every placed leaf in order.

use glam::{Quat, Vec3};

use super::leaf_capsule::PlacedCapsule;
use up_geom::norm::Norm;
use up_geom::{closest_point_triangle, Sphere, SphereTree, TriangleReach};

/// How much wider than a leaf the test in the balloon's frame is, m: far
/// more than the rounding between a point turned into that frame and a leaf
/// placed in the room (a few ulps of a room coordinate, ~1e-6 m in a room of
/// tens of metres), so no leaf the placed test would push from is skipped.
pub(super) const FRAME_SLACK: f32 = 1e-4;

/// A room triangle near a ribbon this step, with its unit inward normal,
/// its box and its edge lines (what each push reads of it, found once).
#[derive(Clone, Copy, Debug)]
pub(crate) struct NearTriangle {
    pub corners: [Vec3; 3],
    pub normal: Vec3,
    lo: Vec3,
    hi: Vec3,
    edges: TriangleReach,
}

impl NearTriangle {
    pub fn new(corners: [Vec3; 3], normal: Vec3) -> NearTriangle {
        let [a, b, c] = corners;
        NearTriangle {
            corners,
            normal,
            lo: a.min(b).min(c),
            hi: a.max(b).max(c),
            edges: TriangleReach::new(corners, normal),
        }
    }

    /// Its edge lines (`TriangleReach`).
    pub fn edges(&self) -> &TriangleReach {
        &self.edges
    }

    /// Whether `on_plane`, a point in its plane that its edge lines leave
    /// unsure of (`TriangleReach::within` is None), is within `radius` of
    /// it: outside its box widened past the radius (and rounding) it is
    /// farther, which spares the closest point's cost. A NaN point is
    /// taken as within.
    pub fn within_near_edge(&self, on_plane: Vec3, radius: f32) -> bool {
        let reach = Vec3::splat(radius * 1.001 + 1e-6);
        if on_plane.cmplt(self.lo - reach).any() || on_plane.cmpgt(self.hi + reach).any() {
            return false;
        }
        let [a, b, c] = self.corners;
        let (closest, _) = closest_point_triangle(on_plane, a, b, c);
        if closest.distance_squared(on_plane) > radius * radius {
            return false;
        }
        true
    }
}

/// A point's friction against the room over one step's substeps: μ times
/// the room's pushes on it so far, less the slide friction took back, along
/// their normal (m), and where it holds the point: where it was when the
/// step began, or where it last slid to. The lanes keep it as two vectors
/// a point (`LaneGroup::grip_left`, `grip_anchor`).
#[cfg(test)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Grip {
    pub left: Vec3,
    pub anchor: Vec3,
}

#[cfg(test)]
impl Grip {
    /// At the step's start, the point at `start`: nothing held yet.
    pub fn new(start: Vec3) -> Grip {
        Grip {
            left: Vec3::ZERO,
            anchor: start,
        }
    }
}

/// `point` (which was at `start` when the substep began) pushed out of the
/// triangles `near`, with friction `mu`: its slide from `grip`'s anchor is
/// taken back up to what `grip` has left with this call's pushes added; a
/// point that slides further than that keeps sliding from where it is.
/// One point of one ribbon: the lanes push four ribbons' points at once
/// (`LaneGroup::push_point_out_of_room`), each as this does, bit for bit,
/// which this is kept to test.
#[cfg(test)]
pub(crate) fn push_out_of_room(
    mut point: Vec3,
    start: Vec3,
    radius: f32,
    mu: f32,
    near: &[NearTriangle],
    grip: &mut Grip,
) -> Vec3 {
    for t in near {
        let a = t.corners[0];
        let height = (point - a).dot(t.normal);
        if height >= radius {
            continue;
        }
        // Over the face, or over its border by less than the radius: a room
        // is flat across the seams of its triangles (an edge pushes along the
        // face normal, never sideways, as a ribbon lying over a seam needs).
        let on_plane = point - height * t.normal;
        // Well inside or outside the edge lines the answer is sure (what the
        // closest point would say); near an edge the closest point decides.
        match t.edges.within(on_plane, radius) {
            Some(true) => {}
            Some(false) => continue,
            None if t.within_near_edge(on_plane, radius) => {}
            None => continue,
        }
        // In front of the face at the substep's start: it may not cross.
        if (start - a).dot(t.normal) <= -radius {
            continue;
        }
        let push = (radius - height) * t.normal;
        point += push;
        grip.left += mu * push;
    }
    let held = grip.left.norm();
    if held <= 0.0 {
        return point;
    }
    // Along the pushes' normal, what the point slid across it.
    let normal = grip.left / held;
    let moved = point - grip.anchor;
    let slide = moved - moved.dot(normal) * normal;
    let slide_len = slide.norm();
    if slide_len <= held {
        point -= slide;
        grip.left = normal * (held - slide_len);
    } else {
        point -= slide * (held / slide_len);
        *grip = Grip::new(point);
    }
    point
}

/// Coulomb friction at position level: of `moved`, the point's move over the
/// substep relative to the surface, friction takes back the slide along the
/// surface, up to `mu` times the surface's `push`.
fn take_back_slide(point: &mut Vec3, moved: Vec3, push: Vec3, mu: f32) {
    let depth = push.norm();
    if depth <= 0.0 {
        return;
    }
    let normal = push / depth;
    let slide = moved - moved.dot(normal) * normal;
    let slide_len = slide.norm();
    if slide_len > 0.0 {
        *point -= slide * (mu * depth / slide_len).min(1.0);
    }
}

/// A balloon near a ribbon at this substep's pose: its bounding sphere, and
/// where its shape's tree is.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NearBalloon {
    /// Its solver state.
    pub state: u32,
    pub bound: Sphere,
    /// Its move over this substep, m (its centre's; its spin is left out).
    pub moved: Vec3,
    pub center: Vec3,
    pub rotation: Quat,
    pub tree: u32,
    /// Its tree's scale (`BodySize::scale`).
    pub scale: f32,
    /// The capsule that holds its leaves, placed.
    pub capsule: PlacedCapsule,
}

/// Pushes `point` (which was at `start` when the substep began), found
/// within `b`'s bounding sphere, out of the leaves of `tree` (`b`'s shape's)
/// placed at `b`'s pose, with friction `mu` against the balloon's move.
/// Returns the point's move, if it moved (the balloon takes the push back).
pub(crate) fn push_out_of_balloon(
    point: &mut Vec3,
    start: Vec3,
    radius: f32,
    mu: f32,
    b: &NearBalloon,
    tree: &SphereTree,
) -> Option<Vec3> {
    let before = *point;
    push_out_of_leaves(point, radius, tree, b);
    take_back_slide(point, *point - start - b.moved, *point - before, mu);
    (*point != before).then_some(*point - before)
}

/// Pushes `point` out of each leaf of `tree` placed at `b`'s pose, in the
/// tree's order: tested first in the balloon's frame, a leaf placed only if
/// the point may be within it (`FRAME_SLACK`).
fn push_out_of_leaves(point: &mut Vec3, radius: f32, tree: &SphereTree, b: &NearBalloon) {
    let nodes = tree.nodes();
    let to_balloon = b.rotation.conjugate();
    let mut local = to_balloon * (*point - b.center);
    for &leaf in tree.leaves() {
        let node = &nodes[leaf as usize];
        // Placed as a leaf always was: the centre plus the turned, scaled offset.
        let offset = node.center * b.scale;
        let leaf_radius = node.radius * b.scale;
        let near = leaf_radius + radius + FRAME_SLACK;
        let away = local - offset;
        // Not `<`: a NaN point goes on to the placed test, as it would alone.
        if away.length_squared() >= near * near {
            continue;
        }
        let placed = Sphere::new(b.center + b.rotation * offset, leaf_radius);
        if push_out_of_sphere(point, radius, &placed) {
            local = to_balloon * (*point - b.center);
        }
    }
}

/// Pushes `point` out of each of `spheres`.
#[cfg(test)]
fn push_out_of_spheres(point: &mut Vec3, radius: f32, spheres: &[Sphere]) {
    for s in spheres {
        push_out_of_sphere(point, radius, s);
    }
}

/// Pushes `point` out of `s` if it is within; whether it was.
fn push_out_of_sphere(point: &mut Vec3, radius: f32, s: &Sphere) -> bool {
    let away = *point - s.center;
    let reach = s.radius + radius;
    let d2 = away.length_squared();
    if d2 >= reach * reach {
        return false;
    }
    let d = d2.sqrt();
    // At the very centre any way out will do: up, where ribbons hang from.
    let out = if d > 1e-9 { away / d } else { Vec3::NEG_Y };
    *point = s.center + reach * out;
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn floor() -> Vec<NearTriangle> {
        let corners = [
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, -1.0),
        ];
        vec![NearTriangle::new(corners, Vec3::Y)]
    }

    #[test]
    fn a_point_that_crossed_the_floor_comes_back_above_it() {
        // Fell 5 cm in one substep, from just above the floor to well below it.
        let start = Vec3::new(0.0, 0.01, -0.5);
        let mut p = Vec3::new(0.0, -0.04, -0.5);
        p = push_out_of_room(p, start, 0.0025, 0.5, &floor(), &mut Grip::new(start));
        assert!((p.y - 0.0025).abs() < 1e-6, "{p}");
    }

    #[test]
    fn friction_holds_a_slow_slide_and_slows_a_fast_one() {
        let start = Vec3::new(0.0, 0.0025, -0.5);
        let mut slow = start + Vec3::new(0.001, -0.004, 0.0);
        let mut grip = Grip::new(start);
        slow = push_out_of_room(slow, start, 0.0025, 0.5, &floor(), &mut grip);
        assert!((slow.x - start.x).abs() < 1e-7, "{slow}");
        // Of the 2 mm of friction the 4 mm push gave, 1 mm is left.
        assert!(
            (grip.left - Vec3::new(0.0, 0.001, 0.0)).length() < 1e-7,
            "{grip:?}"
        );
        let mut fast = start + Vec3::new(0.02, -0.004, 0.0);
        fast = push_out_of_room(fast, start, 0.0025, 0.5, &floor(), &mut Grip::new(start));
        assert!((fast.x - 0.018).abs() < 1e-6, "{fast}");
    }

    #[test]
    fn a_slide_after_the_push_is_held_by_the_steps_friction() {
        // Pushed out of the floor by 4 mm, then pulled 1.5 mm along it and
        // lifted clear by the chain's solve: the second push has no push of
        // its own, and takes the slide back with what the first left.
        let start = Vec3::new(0.0, 0.0025, -0.5);
        let mut p = start + Vec3::new(0.0, -0.004, 0.0);
        let mut grip = Grip::new(start);
        p = push_out_of_room(p, start, 0.0025, 0.5, &floor(), &mut grip);
        p += Vec3::new(0.0015, 0.0001, 0.0);
        p = push_out_of_room(p, start, 0.0025, 0.5, &floor(), &mut grip);
        assert!((p.x - start.x).abs() < 1e-7, "{p}");
        assert!((grip.left.y - 0.0005).abs() < 1e-7, "{grip:?}");
        // Pulled 3 mm instead, it slides by what is beyond the 2 mm.
        let mut p = start + Vec3::new(0.0, -0.004, 0.0);
        let mut grip = Grip::new(start);
        p = push_out_of_room(p, start, 0.0025, 0.5, &floor(), &mut grip);
        p += Vec3::new(0.003, 0.0001, 0.0);
        p = push_out_of_room(p, start, 0.0025, 0.5, &floor(), &mut grip);
        assert!((p.x - 0.001).abs() < 1e-6, "{p}");
        assert_eq!(grip, Grip::new(p), "slides on from where it is");
    }

    /// Points at and around the leaves' surfaces of balloons turned, scaled
    /// and far out in a room: pushed out tested in the balloon's frame, they
    /// end where testing every placed leaf in order leaves them, bit for bit.
    #[test]
    fn leaves_tested_in_the_balloons_frame_push_as_the_placed_leaves_do() {
        let mut next = crate::hash::uniform(5);
        let mut random = move || Vec3::new(next(), next(), next()) * 2.0 - 1.0;
        let leaves: Vec<Sphere> = (0..9)
            .map(|k| Sphere::new(random() * 0.12, 0.06 + 0.01 * k as f32))
            .collect();
        let tree = SphereTree::from_root_and_leaves(Sphere::new(Vec3::ZERO, 0.3), &leaves)
            .expect("a tree");
        let (mut pushed, mut trials) = (0, 0);
        for _ in 0..400 {
            let axis = random().normalize_or(Vec3::Y);
            let rotation = Quat::from_axis_angle(axis, 3.0 * random().x).normalize();
            let b = NearBalloon {
                state: 0,
                bound: Sphere::new(Vec3::ZERO, 0.0),
                moved: random() * 0.01,
                center: random() * 40.0,
                rotation,
                tree: 0,
                scale: 1.0 + 0.3 * random().x,
                capsule: PlacedCapsule::default(),
            };
            let placed: Vec<Sphere> = tree
                .leaves()
                .iter()
                .map(|&leaf| {
                    let node = &tree.nodes()[leaf as usize];
                    Sphere::new(
                        b.center + b.rotation * (node.center * b.scale),
                        node.radius * b.scale,
                    )
                })
                .collect();
            for s in &placed {
                for _ in 0..8 {
                    let radius = 0.0025;
                    let out = random().normalize_or(Vec3::X);
                    // Within, just outside and just inside a leaf's reach.
                    let off = [0.5, 1.0 - 1e-6, 1.0, 1.0 + 1e-6, 1.2][trials % 5];
                    let start = s.center + out * (s.radius + radius) * off;
                    let mut want = start;
                    push_out_of_spheres(&mut want, radius, &placed);
                    let (slid, push) = (want - start - b.moved, want - start);
                    take_back_slide(&mut want, slid, push, 0.5);
                    let mut got = start;
                    let moved = push_out_of_balloon(&mut got, start, radius, 0.5, &b, &tree);
                    assert_eq!(
                        got.to_array().map(f32::to_bits),
                        want.to_array().map(f32::to_bits)
                    );
                    assert_eq!(moved.is_some(), got != start);
                    pushed += usize::from(moved.is_some());
                    trials += 1;
                }
            }
        }
        assert!(
            pushed > trials / 4 && pushed < trials,
            "{pushed} of {trials}"
        );
    }

    #[test]
    fn a_point_inside_a_balloon_goes_to_its_surface() {
        let mut p = Vec3::new(0.05, 0.0, 0.0);
        push_out_of_spheres(&mut p, 0.0025, &[Sphere::new(Vec3::ZERO, 0.1)]);
        assert!((p - Vec3::new(0.1025, 0.0, 0.0)).length() < 1e-6, "{p}");
    }
}
