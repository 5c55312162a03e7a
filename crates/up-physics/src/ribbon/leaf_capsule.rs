//! A balloon's leaves held in one capsule in the balloon's frame, and the
//! test of four ribbon points against four balloons' capsules at once: a
//! point within a balloon's bounding sphere but outside the capsule is
//! outside every leaf, so its exact push (`collide::push_out_of_balloon`,
//! a turn into the balloon's frame and a test per leaf) is not made. In the
//! 10,000-balloon crowd three in four points within a bound are outside
//! every leaf: the sphere round an elongated balloon holds much room the
//! balloon does not (docs/perf-log.md).
//!
//! The capsule holds each leaf widened by the frame test's slack and more
//! than the rounding between the two tests, so no point the exact test
//! would push is passed over, and the pushes are the same bit for bit.

use glam::{Quat, Vec3};
use up_geom::SphereTree;

use super::collide::FRAME_SLACK;
use crate::solver::lanes::{set, F4, V4};

/// How much wider the capsule test is than the leaves widened by
/// `FRAME_SLACK`, m, near the origin: more than the rounding of the
/// capsule's placing and of the exact test's turn into the balloon's frame,
/// a few ulps of a coordinate (~1e-6 m in a room of tens of metres); far
/// out, `ULPS_SLACK` ulps of the balloon's largest coordinate more.
const CAPSULE_SLACK: f32 = 1e-4;
const ULPS_SLACK: f32 = 8.0;

/// A turn whose quaternion's length squared is further than this from 1
/// (never, as the solver keeps them) is not trusted to place a capsule
/// the exact test agrees with: the capsule then holds everything.
const UNIT_TOLERANCE: f32 = 1e-4;

/// A segment on a line through the tree's origin (the balloon's centre of
/// mass), from `t0` to `t1` along the unit `axis`, and `radius` round it,
/// that holds every leaf of a tree, in the tree's frame at its own scale:
/// on a line through the origin, one turn places it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct LeafCapsule {
    pub axis: Vec3,
    pub t0: f32,
    pub t1: f32,
    pub radius: f32,
}

impl LeafCapsule {
    /// The capsule along the line between the first leaf's centre and the
    /// leaf centre farthest from it (a balloon's axis, for the axial
    /// covers), moved onto the parallel line through the origin, as wide as
    /// the leaf that reaches farthest from the moved segment.
    pub fn of(tree: &SphereTree) -> LeafCapsule {
        let leaves: Vec<_> = tree.leaf_spheres().collect();
        let first = leaves.first().map_or(tree.root().center, |s| s.center);
        let far = leaves.iter().map(|s| s.center).fold(first, |far, c| {
            if c.distance_squared(first) > far.distance_squared(first) {
                c
            } else {
                far
            }
        });
        let axis = (far - first).normalize_or(Vec3::Y);
        // The line through `first` and `far`, moved by `-across` onto the origin.
        let across = first - first.dot(axis) * axis;
        let (a, b) = (first - across, far - across);
        let (t0, t1) = (a.dot(axis), b.dot(axis));
        let holds = |s: up_geom::Sphere| distance_to_segment(s.center, a, b) + s.radius;
        let radius = if leaves.is_empty() {
            let root = tree.root();
            holds(up_geom::Sphere::new(root.center, root.radius))
        } else {
            leaves.iter().map(|&s| holds(s)).fold(0.0f32, f32::max)
        };
        LeafCapsule {
            axis,
            t0,
            t1,
            radius,
        }
    }

    /// The segment's ends in the tree's frame.
    #[cfg(test)]
    fn ends(&self) -> (Vec3, Vec3) {
        (self.t0 * self.axis, self.t1 * self.axis)
    }
}

/// Distance from `p` to the segment from `a` to `b`.
fn distance_to_segment(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let length_sq = ab.length_squared();
    let t = if length_sq > 0.0 {
        ((p - a).dot(ab) / length_sq).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + t * ab)
}

/// A balloon's capsule placed at its pose: what the lanes' test reads.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct PlacedCapsule {
    /// The segment's start and its run to the end, in the room, m.
    pub a: Vec3,
    pub ab: Vec3,
    /// 1 / |ab|² (0 for a segment of no length).
    pub inv_length_sq: f32,
    /// The capsule's radius at the balloon's scale, and the slacks, m.
    pub reach: f32,
}

impl PlacedCapsule {
    /// A capsule that holds everything: every point goes on to the exact test.
    pub const ANYWHERE: PlacedCapsule = PlacedCapsule {
        a: Vec3::ZERO,
        ab: Vec3::ZERO,
        inv_length_sq: 0.0,
        reach: f32::INFINITY,
    };
}

impl LeafCapsule {
    /// This capsule scaled by `scale` on a balloon centred at `center`
    /// turned by `rotation` (the frame the leaves are tested in).
    pub fn placed(&self, center: Vec3, rotation: Quat, scale: f32) -> PlacedCapsule {
        if (rotation.length_squared() - 1.0).abs() > UNIT_TOLERANCE {
            return PlacedCapsule::ANYWHERE;
        }
        let axis = rotation * self.axis;
        let far_out = ULPS_SLACK * f32::EPSILON * center.abs().max_element();
        let length = (self.t1 - self.t0) * scale;
        let length_sq = length * length;
        PlacedCapsule {
            a: center + (self.t0 * scale) * axis,
            ab: length * axis,
            inv_length_sq: if length_sq > 0.0 {
                1.0 / length_sq
            } else {
                0.0
            },
            reach: self.radius * scale + FRAME_SLACK + CAPSULE_SLACK + far_out,
        }
    }
}

/// Four balloons' placed capsules, for testing a point of each of four
/// ribbons.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CapsuleLanes {
    a: V4,
    ab: V4,
    inv_length_sq: F4,
    reach: F4,
}

impl CapsuleLanes {
    /// Sets lane `l` to `capsule`.
    pub fn set_lane(&mut self, l: usize, capsule: &PlacedCapsule) {
        self.a.set_lane(l, capsule.a);
        self.ab.set_lane(l, capsule.ab);
        set(&mut self.inv_length_sq, l, capsule.inv_length_sq);
        set(&mut self.reach, l, capsule.reach);
    }

    /// The lanes (bit `l` for lane `l`) whose point, of radius `radius`,
    /// may touch its balloon's leaves: within the capsule's reach, or not a
    /// number (as the exact test takes a NaN point).
    #[inline]
    pub fn may_touch(&self, points: V4, radius: F4) -> u32 {
        let from_a = points - self.a;
        let t = (from_a.dot(self.ab) * self.inv_length_sq)
            .max(F4::ZERO)
            .min(F4::ONE);
        let away = from_a - t * self.ab;
        let reach = self.reach + radius;
        let outside = away.dot(away).simd_ge(reach * reach).to_bitmask();
        !outside & 0b1111
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use up_geom::Sphere;

    /// An egg of five leaves along y, as the axial covers give a balloon.
    fn egg() -> SphereTree {
        let leaves: Vec<Sphere> = [
            (-0.1, 0.05),
            (-0.05, 0.11),
            (0.0, 0.13),
            (0.05, 0.12),
            (0.11, 0.07),
        ]
        .map(|(y, r)| Sphere::new(Vec3::new(0.0, y, 0.0), r))
        .to_vec();
        SphereTree::from_root_and_leaves(Sphere::new(Vec3::ZERO, 0.19), &leaves).unwrap()
    }

    /// Every leaf lies within the capsule.
    #[test]
    fn the_capsule_holds_every_leaf() {
        let tree = egg();
        let c = LeafCapsule::of(&tree);
        let (a, b) = c.ends();
        for s in tree.leaf_spheres() {
            assert!(distance_to_segment(s.center, a, b) + s.radius <= c.radius + 1e-6);
        }
        assert!((c.radius - 0.13).abs() < 1e-6, "{c:?}");
        // Off the origin and askew, it is moved onto the origin and widened.
        let leaves: Vec<Sphere> = [(0.0, 0.05), (0.1, 0.08), (0.2, 0.06)]
            .map(|(t, r)| Sphere::new(Vec3::new(0.03, 0.0, 0.01) + Vec3::new(t, t, 0.5 * t), r))
            .to_vec();
        let tree =
            SphereTree::from_root_and_leaves(Sphere::new(Vec3::splat(0.1), 0.4), &leaves).unwrap();
        let c = LeafCapsule::of(&tree);
        let (a, b) = c.ends();
        for s in tree.leaf_spheres() {
            assert!(distance_to_segment(s.center, a, b) + s.radius <= c.radius + 1e-6);
        }
    }

    /// Points all round a turned, scaled egg: each that is within a leaf
    /// widened by `FRAME_SLACK` (the exact test's reach) is said to touch,
    /// and most of those within the bounding sphere but outside every leaf
    /// are not; a NaN point is said to touch.
    #[test]
    fn no_point_within_a_leaf_is_passed_over() {
        let tree = egg();
        let capsule = LeafCapsule::of(&tree);
        let mut next = crate::hash::uniform(11);
        let (mut spared, mut in_bound_outside) = (0, 0);
        for round in 0..2000 {
            let rotation = Quat::from_scaled_axis(Vec3::new(next(), next(), next()) * 4.0 - 2.0);
            // A room of tens of metres, and now and then kilometres out.
            let far = if round % 5 == 0 { 300.0 } else { 1.0 };
            let center = (Vec3::new(next(), next(), next()) * 20.0 - 10.0) * far;
            let scale = 0.9 + 0.2 * next();
            let mut lanes = CapsuleLanes::default();
            let mut points = V4::ZERO;
            let radius = 0.0025;
            for l in 0..4 {
                lanes.set_lane(l, &capsule.placed(center, rotation, scale));
                let offset = Vec3::new(next(), next(), next()) * 0.44 - 0.22;
                let point = if l % 2 == 0 {
                    center + offset * scale
                } else {
                    // Just within the widest leaf's reach, across the
                    // axis: at the capsule's own edge.
                    let s = Sphere::new(Vec3::ZERO, 0.13);
                    let out = Vec3::new(offset.x, 0.0, offset.z).normalize_or(Vec3::X);
                    let reach = s.radius * scale + radius + FRAME_SLACK;
                    center + rotation * (s.center * scale + out * reach * (1.0 - 1e-6))
                };
                points.set_lane(l, point);
            }
            if round == 0 {
                points.set_lane(3, Vec3::NAN);
            }
            let touch = lanes.may_touch(points, F4::splat(radius));
            for l in 0..4 {
                let p = points.lane(l);
                let local = rotation.conjugate() * (p - center);
                let within_leaf = !tree.leaf_spheres().all(|s| {
                    (local - s.center * scale).length_squared()
                        >= (s.radius * scale + radius + FRAME_SLACK).powi(2)
                });
                let within_bound = local.length() < 0.19 * scale + radius;
                if within_leaf {
                    assert!(
                        touch & (1 << l) != 0,
                        "round {round} lane {l}: {p} passed over"
                    );
                } else if within_bound && l % 2 == 0 {
                    in_bound_outside += 1;
                    if touch & (1 << l) == 0 {
                        spared += 1;
                    }
                }
            }
        }
        assert!(
            spared * 2 > in_bound_outside,
            "{spared} of {in_bound_outside} spared"
        );
    }

    /// The capsule that is not placed holds every point.
    #[test]
    fn a_capsule_placed_anywhere_passes_every_point_on() {
        let mut lanes = CapsuleLanes::default();
        let mut points = V4::ZERO;
        let anywhere = [
            Vec3::ZERO,
            Vec3::splat(1e6),
            Vec3::new(-3.0, 40.0, 2.0),
            Vec3::NAN,
        ];
        for (l, p) in anywhere.into_iter().enumerate() {
            lanes.set_lane(l, &PlacedCapsule::ANYWHERE);
            points.set_lane(l, p);
        }
        assert_eq!(lanes.may_touch(points, F4::splat(0.0025)), 0b1111);
    }
}
