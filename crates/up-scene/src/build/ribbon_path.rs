//! Where a weighted ribbon starts, so that a group given a spawn box lays its
//! balloons clear of each other's ribbons and weights, and later groups keep
//! out of them.
//!
//! `World::add_ribbon` lays a free ribbon straight down from its knot,
//! turned along the floor toward the room's middle where it reaches it, and
//! round a wall where it meets one (`start_path` follows it, point for
//! point; a test holds the two together). A weight laid among balloons, or
//! hanging on a ribbon laid through one, drags its tens of grams through
//! them from the first step (121 mm of overlap in a 10 m room where 200
//! weighted balloons started in a floor-level box among 1,500 free ones, its
//! weights run along the floor under them; 217 mm where the box was above
//! them, their ribbons hanging through them). So each such balloon goes only
//! where its whole path is clear, and the path is reserved as `hang`
//! reserves a hanging weight's column.

use glam::Vec3;
use up_physics::ribbon::{hang_path, WEIGHT_RADIUS};

use super::hang::COLUMN_RADIUS;
use super::spawn::Occupancy;

/// A weighted ribbon as the layout sees it.
#[derive(Clone, Copy, Debug)]
pub(super) struct WeightedRibbon {
    /// The knot, from the bounding sphere's centre, the balloon upright, m.
    pub knot: Vec3,
    pub length: f32,
    pub segments: u32,
    /// Gravity's direction.
    pub down: Vec3,
    /// The room's bounds, m.
    pub room_min: Vec3,
    pub room_max: Vec3,
    /// How far the path keeps from anything, m: a weight's width and a gap,
    /// and the knot's swing with the balloon's lean.
    pub clearance: f32,
}

impl WeightedRibbon {
    /// The ribbon's start points for a balloon whose bounding sphere is at
    /// `centre`, upright: the knot first, the weight last.
    pub fn path(&self, centre: Vec3) -> Vec<Vec3> {
        start_path(
            centre + self.knot,
            self.length,
            self.segments,
            self.down,
            self.room_min,
            self.room_max,
        )
    }

    /// Whether the path from `centre` is clear of every balloon placed
    /// (other ribbons' paths may cross it: by default ribbons pass through
    /// each other, and ribbons laid crossing that touch are eased apart).
    pub fn clear(&self, centre: Vec3, occupied: &Occupancy) -> bool {
        along(&self.path(centre), self.clearance)
            .all(|p| !occupied.overlaps_balloon(p, self.clearance))
    }

    /// Reserves the path from `centre`: later balloons keep out of it.
    pub fn reserve(&self, centre: Vec3, occupied: &mut Occupancy) {
        for p in along(&self.path(centre), self.clearance) {
            occupied.insert_path(p, self.clearance);
        }
    }
}

/// The clearance a weighted ribbon keeps, its knot `knot` from the balloon's
/// bounding sphere's centre, leaning up to `tilt_deg`.
pub(super) fn clearance(knot: Vec3, tilt_deg: f32) -> f32 {
    COLUMN_RADIUS + knot.length() * tilt_deg.to_radians().sin()
}

/// Points along `path`, no further apart than `radius`, so that spheres of
/// `radius` about them cover it.
fn along(path: &[Vec3], radius: f32) -> impl Iterator<Item = Vec3> + '_ {
    path.windows(2)
        .flat_map(move |pair| {
            let (a, b) = (pair[0], pair[1]);
            let pieces = ((a.distance(b) / radius).ceil() as usize).max(1);
            (0..pieces).map(move |k| a.lerp(b, k as f32 / pieces as f32))
        })
        .chain(path.last().copied())
}

/// A free weighted ribbon's start points, as `World::add_ribbon` lays one
/// (`up_physics::ribbon::hang_path`): from `knot` straight `down` in segments
/// of `length / segments`; where the next point would leave the room's box
/// (`room_min`..`room_max`, less the weight's radius and a millimetre), along
/// the floor toward the box's middle, and round a wall where it meets one.
pub(super) fn start_path(
    knot: Vec3,
    length: f32,
    segments: u32,
    down: Vec3,
    room_min: Vec3,
    room_max: Vec3,
) -> Vec<Vec3> {
    let margin = WEIGHT_RADIUS + 1e-3;
    let bounds = (room_min + margin, room_max - margin);
    hang_path(
        knot,
        down,
        length / segments as f32,
        segments as usize,
        Some(bounds),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{build_world, BuiltScene};
    use crate::scene::Scene;
    use up_physics::BodyId;

    /// A 6 m room of every kind of balloon, the weighted ones given boxes to
    /// start in: one on the floor (their ribbons run along it toward the
    /// middle) and one above the free balloons (their ribbons hang down
    /// through them). Laid without their paths, 169 mm of overlap within six
    /// steps.
    const BOXED: &str = "[room]\nwidth = 6.0\ndepth = 6.0\nwall_height = 3.0\n\
        ceiling = \"pyramid\"\napex_height = 1.5\n\
        [[balloons]]\ncount = 750\n[balloons.ribbon]\nlength_m = 1.5\n\
        [[balloons]]\ncount = 40\n\
        spawn = { min = [-2.9, 0.01, -2.9], max = [2.9, 0.01, 2.9] }\n\
        [balloons.ribbon]\nlength_m = 1.2\nweight_g = 35.0\n\
        [[balloons]]\ncount = 30\n\
        spawn = { min = [-2.9, 1.3, -2.9], max = [2.9, 1.3, 2.9] }\n\
        [balloons.ribbon]\nlength_m = 1.0\nweight_g = 35.0\n\
        [[balloons]]\ncount = 40\nkind = \"foil\"\n\
        [sim]\nseed = 5\n";

    fn boxed() -> BuiltScene {
        build_world(&Scene::from_toml_str(BOXED, "ribbon_path.rs").unwrap()).unwrap()
    }

    #[test]
    fn the_path_laid_out_is_the_ribbon_the_world_ties() {
        // Upright, so the knot is where the layout saw it; the first group on
        // the floor (its ribbons run along it), the second over it.
        let text = "[room]\nwidth = 4.0\ndepth = 4.0\nwall_height = 3.0\n\
            [[balloons]]\ncount = 20\ntilt_deg = 0.0\n\
            spawn = { min = [-1.9, 0.01, -1.9], max = [1.9, 0.01, 1.9] }\n\
            [balloons.ribbon]\nlength_m = 1.2\nweight_g = 35.0\n\
            [[balloons]]\ncount = 10\ntilt_deg = 0.0\n\
            spawn = { min = [-1.9, 1.0, -1.9], max = [1.9, 1.0, 1.9] }\n\
            [balloons.ribbon]\nlength_m = 1.0\nweight_g = 35.0\nsegments = 12\n";
        let built = build_world(&Scene::from_toml_str(text, "ribbon_path.rs").unwrap()).unwrap();
        let bounds = built.room.bounds();
        let mut on_the_floor = 0;
        for group in [0, 1] {
            let model = &built.balloon_models[group];
            let root = model.shape.tree.root().sphere();
            let spec = built.group_ribbons[group].as_ref().unwrap().spec.clone();
            let ribbon = WeightedRibbon {
                knot: crate::build::ribbons::knot_point(model) - root.center,
                length: spec.length_m,
                segments: spec.segments,
                down: Vec3::NEG_Y,
                room_min: bounds.min,
                room_max: bounds.max,
                clearance: COLUMN_RADIUS,
            };
            for &body in &built.group_bodies[group] {
                let world = &built.world;
                let centre = world.pose(body).unwrap().transform_point(root.center);
                let laid = world.ribbon_points(world.ribbon_of(body).unwrap()).unwrap();
                let path = ribbon.path(centre);
                assert_eq!(laid.len(), path.len());
                for (a, b) in laid.iter().zip(&path) {
                    assert!(a.distance(*b) < 1e-4, "laid {a}, predicted {b}");
                }
                on_the_floor += usize::from(path[path.len() - 2].y == path[path.len() - 1].y);
            }
        }
        assert!(
            on_the_floor >= 20,
            "{on_the_floor} ribbons end along the floor"
        );
    }

    #[test]
    fn weighted_ribbons_in_spawn_boxes_start_clear_of_every_balloon_and_stay_clean() {
        let mut built = boxed();
        let world = &built.world;
        let spheres: Vec<(BodyId, Vec3, f32)> = (0..built.group_bodies.len())
            .flat_map(|group| {
                let root = built.balloon_models[group].shape.tree.root().sphere();
                built.group_bodies[group].iter().map(move |&b| {
                    let centre = world.pose(b).unwrap().transform_point(root.center);
                    (b, centre, root.radius)
                })
            })
            .collect();
        for group in [1, 2] {
            for &b in &built.group_bodies[group] {
                let points = world.ribbon_points(world.ribbon_of(b).unwrap()).unwrap();
                for p in points {
                    for &(other, centre, radius) in &spheres {
                        assert!(
                            other == b || p.distance(centre) > radius + WEIGHT_RADIUS,
                            "a weighted ribbon's point {p} in the balloon at {centre}"
                        );
                    }
                }
            }
        }
        assert_eq!(built.world.max_penetration_now(), 0.0, "overlap at spawn");
        let mut worst = 0.0f32;
        for _ in 0..60 {
            built.world.step();
            worst = worst.max(built.world.stats().max_penetration);
        }
        // `up soak`'s bound: 1 % of the 11-inch balloons' radius.
        assert!(worst < 1.4e-3, "worst overlap {} mm", worst * 1e3);
    }
}
