//! Where each balloon is over a long run, counted per balloon group: at the
//! ceiling, hovering, or on the floor. `up forecast` reads it to say when a
//! group's balloons leave the ceiling and when they are down.
//!
//! The definition, for a body looked at by `FloatCensus::observe`:
//! - **on the floor** when its lowest point (the lowest of its leaf spheres,
//!   at the size its gas gives it now) is within `FLOOR_BAND` (3 cm) of the
//!   room's lowest point;
//! - **at the ceiling** when, not on the floor, its centre of mass is within
//!   `CEILING_BAND` (0.3 m) of the highest its centre has been, and it has
//!   risen at least `MIN_RISE` (0.5 m) above where the census first saw it;
//! - **hovering** otherwise (held up by its lift below the ceiling, on a
//!   ribbon, or on its way up or down).
//!
//! Measured from where each balloon has been, not from the room's ceiling,
//! so a pile under a pyramid roof or a balloon caught under a beam counts as
//! up; a balloon that starts near the ceiling never counts as at it (it has
//! not risen). Without a room nothing is on the floor.

use std::collections::HashMap;

use glam::Vec3;
use up_physics::{BodyId, World};

use crate::build::group_index;

/// m: a body's lowest point this close to the room's lowest counts as on the floor.
pub const FLOOR_BAND: f32 = 0.03;
/// m: a centre this close to the highest it has been counts as at the ceiling.
pub const CEILING_BAND: f32 = 0.3;
/// m: how far above its first seen centre a body must have risen to count as at the ceiling.
pub const MIN_RISE: f32 = 0.5;

/// Where one balloon is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FloatState {
    Ceiling,
    Hovering,
    Floor,
}

/// One group's counts at one look.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GroupCensus {
    pub ceiling: u32,
    pub hovering: u32,
    pub floor: u32,
    /// Mean over the group's balloons that carry gas of the gas's lift now
    /// over its lift at fill (`Gas::lift_fraction` in the room's air now);
    /// 1 for a group without gas (its balloons keep their lift for ever).
    pub mean_lift_fraction: f32,
}

impl GroupCensus {
    /// Balloons counted.
    pub fn count(&self) -> u32 {
        self.ceiling + self.hovering + self.floor
    }
}

/// What the census remembers of one body.
#[derive(Clone, Copy, Debug)]
struct Track {
    /// m: the centre's height when first seen.
    start_y: f32,
    /// m: the highest the centre has been.
    highest_y: f32,
    state: FloatState,
}

/// Per body handle: the highest its centre has been, and its state at the last look.
#[derive(Clone, Debug, Default)]
pub struct FloatCensus {
    tracks: HashMap<BodyId, Track>,
    /// m: the room's lowest point, found at the first look (the room is static).
    floor_y: Option<f32>,
}

impl FloatCensus {
    pub fn new() -> Self {
        Self::default()
    }

    /// Looks at every body now; returns the counts per balloon group
    /// (`group_index` of its `user_data`), indexed by group, up to the
    /// highest group seen (a group with no bodies counts zeros and a lift
    /// fraction of 1). Bodies removed since the last look are forgotten.
    pub fn observe(&mut self, world: &World) -> Vec<GroupCensus> {
        let floor_y = *self.floor_y.get_or_insert_with(|| room_floor_y(world));
        let air = world.air();
        // Per group: counts, and the sum and number of lift fractions.
        let mut groups: Vec<(GroupCensus, f64, u32)> = Vec::new();
        let mut seen = HashMap::with_capacity(world.body_count());
        for &id in world.body_ids() {
            let (Some(centre), Some(lowest)) = (world.center_of_mass(id), lowest_point(world, id))
            else {
                continue;
            };
            let track = self.tracks.get(&id).copied().unwrap_or(Track {
                start_y: centre.y,
                highest_y: centre.y,
                state: FloatState::Floor,
            });
            let highest_y = track.highest_y.max(centre.y);
            let state = if lowest - floor_y <= FLOOR_BAND {
                FloatState::Floor
            } else if highest_y - centre.y <= CEILING_BAND && highest_y - track.start_y >= MIN_RISE
            {
                FloatState::Ceiling
            } else {
                FloatState::Hovering
            };
            seen.insert(
                id,
                Track {
                    highest_y,
                    state,
                    ..track
                },
            );

            let group = group_index(world.user_data(id).unwrap_or(0));
            if groups.len() <= group {
                groups.resize(group + 1, (GroupCensus::default(), 0.0, 0));
            }
            let (census, lift_sum, lift_count) = &mut groups[group];
            match state {
                FloatState::Ceiling => census.ceiling += 1,
                FloatState::Hovering => census.hovering += 1,
                FloatState::Floor => census.floor += 1,
            }
            if let Some(gas) = world.gas(id) {
                *lift_sum += gas.lift_fraction(&air);
                *lift_count += 1;
            }
        }
        self.tracks = seen;
        groups
            .into_iter()
            .map(|(mut census, sum, n)| {
                census.mean_lift_fraction = if n == 0 {
                    1.0
                } else {
                    (sum / f64::from(n)) as f32
                };
                census
            })
            .collect()
    }

    /// The state of body `id` at the last look; None if it was not seen.
    pub fn state(&self, id: BodyId) -> Option<FloatState> {
        self.tracks.get(&id).map(|t| t.state)
    }
}

/// m: the lowest point of the room's mesh; −∞ without a room (nothing is on its floor).
fn room_floor_y(world: &World) -> f32 {
    world
        .room()
        .map(|room| {
            room.vertices()
                .iter()
                .map(|v| v.y)
                .fold(f32::INFINITY, f32::min)
        })
        .filter(|y| y.is_finite())
        .unwrap_or(f32::NEG_INFINITY)
}

/// m: the height of body `id`'s lowest point: the lowest of its leaf spheres
/// at its pose, scaled by `World::body_scale` about the mesh frame's origin
/// (as the renderer draws it).
fn lowest_point(world: &World, id: BodyId) -> Option<f32> {
    let pose = world.pose(id)?;
    let shape = world.shape(world.shape_of(id)?)?;
    let scale = world.body_scale(id).unwrap_or(1.0);
    shape
        .tree
        .leaf_spheres()
        .map(|s| {
            let centre: Vec3 = pose.position + pose.rotation * (s.center * scale);
            centre.y - s.radius * scale
        })
        .reduce(f32::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::build_world;
    use crate::scene::Scene;

    /// A 2 m × 2 m room, 2.5 m high with a flat ceiling; `balloons` is the
    /// `[[balloons]]` tables.
    fn small_room(balloons: &str) -> World {
        let text = format!(
            "[room]\nwidth = 2.0\ndepth = 2.0\nwall_height = 2.5\nceiling = \"flat\"\n\
             {balloons}\n[sim]\nseed = 3\n"
        );
        let scene = Scene::from_toml_str(&text, "census.toml").unwrap();
        build_world(&scene).unwrap().world
    }

    fn run(world: &mut World, seconds: f32) {
        let steps = (seconds / world.def().dt).round() as u32;
        for _ in 0..steps {
            world.step();
        }
    }

    #[test]
    fn a_helium_balloon_is_on_the_floor_at_release_then_at_the_ceiling() {
        let mut world = small_room("[[balloons]]\ncount = 1\ngas = \"helium\"\n");
        let mut census = FloatCensus::new();
        let id = world.body_ids()[0];
        let first = census.observe(&world);
        assert_eq!(first.len(), 1);
        assert_eq!(
            census.state(id),
            Some(FloatState::Floor),
            "released from the floor"
        );
        assert_eq!((first[0].floor, first[0].count()), (1, 1));

        run(&mut world, 6.0);
        let up = census.observe(&world);
        assert_eq!(census.state(id), Some(FloatState::Ceiling));
        assert_eq!((up[0].ceiling, up[0].hovering, up[0].floor), (1, 0, 0));
        let top = world.center_of_mass(id).unwrap().y;
        assert!(top > 2.0, "centre {top} m: not under the 2.5 m ceiling");
        assert!(up[0].mean_lift_fraction > 0.0 && up[0].mean_lift_fraction <= 1.0 + 1e-6);
    }

    #[test]
    fn an_air_balloon_stays_on_the_floor() {
        let mut world = small_room("[[balloons]]\ncount = 2\ngas = \"air\"\n");
        let mut census = FloatCensus::new();
        census.observe(&world);
        run(&mut world, 4.0);
        let now = census.observe(&world);
        assert_eq!((now[0].floor, now[0].ceiling, now[0].hovering), (2, 0, 0));
        for &id in world.body_ids() {
            assert_eq!(census.state(id), Some(FloatState::Floor));
        }
    }

    #[test]
    fn groups_are_counted_apart_and_a_rise_short_of_half_a_metre_is_hovering() {
        let mut world = small_room(
            "[[balloons]]\ncount = 1\ngas = \"air\"\n\
             [[balloons]]\ncount = 2\ngas = \"helium\"\n",
        );
        let mut census = FloatCensus::new();
        census.observe(&world);
        run(&mut world, 0.25);
        // A quarter of a second after release the helium balloons are off
        // the floor but have not risen half a metre.
        let early = census.observe(&world);
        assert_eq!(early.len(), 2);
        assert_eq!((early[0].floor, early[0].count()), (1, 1));
        assert_eq!((early[1].hovering, early[1].count()), (2, 2), "{early:?}");
        run(&mut world, 6.0);
        let late = census.observe(&world);
        assert_eq!((late[0].floor, late[1].ceiling), (1, 2), "{late:?}");
    }

    #[test]
    fn a_balloon_losing_its_helium_leaves_the_ceiling_and_lands() {
        let mut world = small_room("[[balloons]]\ncount = 1\ngas = \"helium\"\n");
        let id = world.body_ids()[0];
        // An untreated 11″ latex balloon filled 12 h before: about 2 h of
        // float left (the envelope as up_physics' own gas tests size it).
        let envelope = up_physics::EnvelopeDef::latex(0.0035, 0.003, 0.289, 1.0, 1.0);
        world.fill(id, &envelope, 12.0 * 3600.0).unwrap();
        let mut census = FloatCensus::new();
        census.observe(&world);
        run(&mut world, 6.0);
        let up = census.observe(&world);
        assert_eq!(census.state(id), Some(FloatState::Ceiling));
        let mut states = vec![FloatState::Ceiling];
        let mut lift = up[0].mean_lift_fraction;
        assert!(lift > 0.0 && lift < 1.0, "aged 12 h: {lift}");
        for _ in 0..6 * 60 {
            world.advance(60.0, u64::MAX);
            let now = census.observe(&world);
            assert!(now[0].mean_lift_fraction < lift, "the lift only falls");
            lift = now[0].mean_lift_fraction;
            let state = census.state(id).unwrap();
            if states.last() != Some(&state) {
                states.push(state);
            }
        }
        assert_eq!(states.first(), Some(&FloatState::Ceiling));
        assert_eq!(states.last(), Some(&FloatState::Floor), "{states:?}");
        assert!(world.body_scale(id).unwrap() < 1.0, "it shrank");
    }

    #[test]
    fn a_balloon_pulled_down_from_the_ceiling_hovers_then_lands() {
        let mut world = small_room("[[balloons]]\ncount = 1\ngas = \"helium\"\n");
        let mut census = FloatCensus::new();
        census.observe(&world);
        run(&mut world, 6.0);
        census.observe(&world);
        let id = world.body_ids()[0];
        assert_eq!(census.state(id), Some(FloatState::Ceiling));
        // Held a metre down: below the band of the highest it has been.
        let com = world.center_of_mass(id).unwrap();
        world.grab(id, com).unwrap();
        world.set_grab_target(com - Vec3::Y).unwrap();
        run(&mut world, 2.0);
        let held = world.center_of_mass(id).unwrap().y;
        assert!((held - (com.y - 1.0)).abs() < 0.1, "held at {held} m");
        census.observe(&world);
        assert_eq!(census.state(id), Some(FloatState::Hovering));
        // Pressed onto the floor.
        world
            .set_grab_target(Vec3::new(com.x, -0.5, com.z))
            .unwrap();
        run(&mut world, 2.0);
        let lowest = lowest_point(&world, id).unwrap();
        assert!(lowest.abs() < FLOOR_BAND, "lowest point {lowest} m");
        census.observe(&world);
        assert_eq!(census.state(id), Some(FloatState::Floor));
        // Let go, it rises again: at the ceiling once more (it has risen
        // from where it was first seen).
        world.release_grab();
        run(&mut world, 6.0);
        census.observe(&world);
        assert_eq!(census.state(id), Some(FloatState::Ceiling));
    }
}
