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

use glam::Vec3;
use up_geom::SphereTree;

use super::collide::FRAME_SLACK;
use crate::solver::lanes::{F4, Q4, V4};

/// How much wider the capsule test is than the leaves widened by
/// `FRAME_SLACK`, m: more than the rounding of a point turned into the
/// balloon's frame and of the capsule's own arithmetic in a room of tens
/// of metres (a few ulps of a coordinate, ~1e-6 m).
const CAPSULE_SLACK: f32 = 1e-4;

/// The segment from `a` to `b`, `radius` round it, that holds every leaf of
/// a tree, in the tree's frame at its own scale.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct LeafCapsule {
    pub a: Vec3,
    pub b: Vec3,
    pub radius: f32,
}

impl LeafCapsule {
    /// The capsule along the line between the two leaves' centres farthest
    /// apart from the first leaf (a balloon's axis, for the axial covers),
    /// as wide as the leaf that reaches farthest from that segment.
    pub fn of(tree: &SphereTree) -> LeafCapsule {
        let leaves: Vec<_> = tree.leaf_spheres().collect();
        let Some(first) = leaves.first() else {
            let root = tree.root();
            return LeafCapsule {
                a: root.center,
                b: root.center,
                radius: root.radius,
            };
        };
        let a = first.center;
        let b = leaves.iter().map(|s| s.center).fold(a, |far, c| {
            if c.distance_squared(a) > far.distance_squared(a) {
                c
            } else {
                far
            }
        });
        let radius = leaves
            .iter()
            .map(|s| distance_to_segment(s.center, a, b) + s.radius)
            .fold(0.0f32, f32::max);
        LeafCapsule { a, b, radius }
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

/// Four balloons' capsules, for testing a point of each of four ribbons.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CapsuleLanes {
    /// Into each balloon's frame (its turn's conjugate), from its centre.
    to_frame: Q4,
    center: V4,
    /// The segment's start and its run to the end, scaled, in the frame.
    a: V4,
    ab: V4,
    /// 1 / |ab|² (0 for a segment of no length).
    inv_length_sq: F4,
    /// The capsule's radius, scaled, and the slacks.
    reach: F4,
}

impl CapsuleLanes {
    /// Sets lane `l` to `capsule` scaled by `scale`, of a balloon centred at
    /// `center` turned by `rotation`.
    pub fn set_lane(
        &mut self,
        l: usize,
        capsule: &LeafCapsule,
        (center, rotation, scale): (Vec3, glam::Quat, f32),
    ) {
        let to_frame = rotation.conjugate();
        self.to_frame
            .xyz
            .set_lane(l, Vec3::new(to_frame.x, to_frame.y, to_frame.z));
        crate::solver::lanes::set(&mut self.to_frame.w, l, to_frame.w);
        self.center.set_lane(l, center);
        let (a, b) = (capsule.a * scale, capsule.b * scale);
        self.a.set_lane(l, a);
        self.ab.set_lane(l, b - a);
        let length_sq = (b - a).length_squared();
        let inv = if length_sq > 0.0 {
            1.0 / length_sq
        } else {
            0.0
        };
        crate::solver::lanes::set(&mut self.inv_length_sq, l, inv);
        let reach = capsule.radius * scale + FRAME_SLACK + CAPSULE_SLACK;
        crate::solver::lanes::set(&mut self.reach, l, reach);
    }

    /// The lanes (bit `l` for lane `l`) whose point, of radius `radius`,
    /// may touch its balloon's leaves: within the capsule's reach, or not a
    /// number (as the exact test takes a NaN point).
    #[inline]
    pub fn may_touch(&self, points: V4, radius: F4) -> u32 {
        let local = self.to_frame.rotate(points - self.center);
        let from_a = local - self.a;
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
    use glam::Quat;
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
        for s in tree.leaf_spheres() {
            assert!(distance_to_segment(s.center, c.a, c.b) + s.radius <= c.radius + 1e-6);
        }
        assert!((c.radius - 0.13).abs() < 1e-6, "{c:?}");
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
            let center = Vec3::new(next(), next(), next()) * 20.0 - 10.0;
            let scale = 0.9 + 0.2 * next();
            let mut lanes = CapsuleLanes::default();
            let mut points = V4::ZERO;
            let radius = 0.0025;
            for l in 0..4 {
                lanes.set_lane(l, &capsule, (center, rotation, scale));
                let offset = Vec3::new(next(), next(), next()) * 0.44 - 0.22;
                points.set_lane(l, center + offset * scale);
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
                } else if within_bound {
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
}
