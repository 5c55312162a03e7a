//! Graph colouring of the contact constraints (the idea of Box2D v3's
//! constraint graph): no two constraints of one colour move the same body, so
//! the constraints of a colour can be solved at once, in any order and on any
//! number of threads, with the same result. Colours are solved one after the
//! other, which keeps the Gauss-Seidel character of the solve.
//!
//! Static bodies (the room, sleeping balloons) never take an impulse, so they
//! do not count as shared. Constraints that find no free colour among the 64
//! go to a last, overflow group that is solved serially.
//!
//! Within a colour, the constraints against a fixed body (`Moving::A`: the
//! room or a sleeper on side B; `Moving::B`: on side A) get groups of their
//! own, after those between two moving bodies: the passes then leave the
//! fixed side's lanes alone instead of gathering and updating four bodies
//! that cannot move. A colour's constraints are independent, so where in the
//! colour each goes changes no result.

use super::body_state::BodyState;
use super::lanes::LANES;
use crate::spare::{release_spare, BUFFER_FLOOR};

/// Marks a slot that holds no constraint.
#[cfg(feature = "parallel")]
pub(crate) const EMPTY_LANE: u32 = u32::MAX;

/// Colours a body can carry (bits of a `u64`).
const COLORS: usize = 64;

/// Which sides of a group's constraints can move: every lane of a group alike.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Moving {
    Both,
    /// Side B is fixed (`BodyState::is_fixed`) in every lane.
    A,
    /// Side A is fixed in every lane.
    B,
}

impl Moving {
    const ALL: [Moving; 3] = [Moving::Both, Moving::A, Moving::B];

    /// Whether side `side` (0: A, 1: B) is fixed in every lane.
    #[inline]
    pub fn fixes(self, side: usize) -> bool {
        match self {
            Moving::Both => false,
            Moving::A => side == 1,
            Moving::B => side == 0,
        }
    }

    fn of(a: &BodyState, b: &BodyState) -> Moving {
        match (a.is_fixed(), b.is_fixed()) {
            (false, true) => Moving::A,
            (true, false) => Moving::B,
            _ => Moving::Both,
        }
    }
}

/// Groups `[start, end)` of one colour whose constraints all move `moving`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ColourRun {
    pub start: u32,
    pub end: u32,
    pub moving: Moving,
}

/// Where each constraint goes, reused from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Coloring {
    /// Colour of each constraint, in the narrowphase's order (`COLORS` =
    /// overflow), and the sides it moves.
    color: Vec<(u8, Moving)>,
    /// Colours already used by each body's constraints.
    used: Vec<u64>,
    /// The groups of `LANES` constraints, colour by colour, each colour in
    /// up to three runs (`Moving::ALL`'s order); the last run is the
    /// overflow, one constraint per group so that it runs serially, all as
    /// `Moving::Both`.
    pub ranges: Vec<ColourRun>,
    /// For each constraint in the narrowphase's order, its slot: group · `LANES` + lane.
    pub slot: Vec<u32>,
    /// For each slot, its constraint (`EMPTY_LANE` if none): `slot` inverted.
    #[cfg(feature = "parallel")]
    constraint_at: Vec<u32>,
    /// Groups in all.
    pub groups: usize,
}

impl Coloring {
    /// Gives back the capacity this step's constraints left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.color, BUFFER_FLOOR);
        release_spare(&mut self.slot, BUFFER_FLOOR);
        #[cfg(feature = "parallel")]
        release_spare(&mut self.constraint_at, BUFFER_FLOOR);
    }

    /// Colours the constraints between the body pairs `pairs` greedily
    /// (lowest free colour, in the given order, so room contacts, which come
    /// first, are solved first) and gives each a slot: colour by colour,
    /// the sides it moves within a colour, `LANES` to a group, in the given
    /// order within those.
    pub fn assign(&mut self, pairs: impl Iterator<Item = (u32, u32)>, states: &[BodyState]) {
        self.used.clear();
        self.used.resize(states.len(), 0);
        self.color.clear();
        // Filled only when the groups are assembled in tasks; empty otherwise,
        // so that its length is this step's use (`spare`).
        #[cfg(feature = "parallel")]
        self.constraint_at.clear();
        let mut counts = [[0u32; 3]; COLORS + 1];
        let moving = |i: u32| states[i as usize].inv_mass > 0.0;
        for (a, b) in pairs {
            let taken = if moving(a) { self.used[a as usize] } else { 0 }
                | if moving(b) { self.used[b as usize] } else { 0 };
            let color = (!taken).trailing_zeros() as usize; // 64 when all are taken
            if color < COLORS {
                let bit = 1u64 << color;
                if moving(a) {
                    self.used[a as usize] |= bit;
                }
                if moving(b) {
                    self.used[b as usize] |= bit;
                }
            }
            let sides = if color < COLORS {
                Moving::of(&states[a as usize], &states[b as usize])
            } else {
                Moving::Both
            };
            self.color.push((color as u8, sides));
            counts[color][sides as usize] += 1;
        }

        // Each run's first group; the overflow takes a group per constraint.
        self.ranges.clear();
        let mut first_group = [[0u32; 3]; COLORS + 1];
        let mut start = 0u32;
        for (color, counts) in counts.iter().enumerate() {
            for moving in Moving::ALL {
                let count = counts[moving as usize];
                let groups = if color == COLORS {
                    count
                } else {
                    count.div_ceil(LANES as u32)
                };
                first_group[color][moving as usize] = start;
                if count > 0 || (color == COLORS && moving == Moving::Both) {
                    self.ranges.push(ColourRun {
                        start,
                        end: start + groups,
                        moving,
                    });
                }
                start += groups;
            }
        }
        self.groups = start as usize;

        self.slot.clear();
        let mut seen = [[0u32; 3]; COLORS + 1];
        for &(color, moving) in &self.color {
            let (color, moving) = (color as usize, moving as usize);
            let k = seen[color][moving];
            seen[color][moving] += 1;
            let first = first_group[color][moving];
            let slot = if color == COLORS {
                (first + k) * LANES as u32
            } else {
                first * LANES as u32 + k
            };
            self.slot.push(slot);
        }
    }

    /// For each slot, its constraint (`EMPTY_LANE` if none): `slot` inverted.
    #[cfg(feature = "parallel")]
    pub fn constraint_at(&mut self) -> &[u32] {
        self.constraint_at.clear();
        self.constraint_at.resize(self.groups * LANES, EMPTY_LANE);
        for (i, &slot) in self.slot.iter().enumerate() {
            self.constraint_at[slot as usize] = i as u32;
        }
        &self.constraint_at
    }
}

#[cfg(test)]
mod tests {
    use glam::Mat3;

    use super::*;

    fn moving() -> BodyState {
        BodyState {
            inv_mass: 1.0,
            inv_inertia: Mat3::IDENTITY,
            ..BodyState::STATIC
        }
    }

    /// The constraints of each colour (the overflow last), as (a, b) pairs.
    fn colours(coloring: &Coloring, pairs: &[(u32, u32)]) -> Vec<Vec<(u32, u32)>> {
        let mut by_colour = vec![Vec::new(); COLORS + 1];
        for (&pair, &(colour, _)) in pairs.iter().zip(&coloring.color) {
            by_colour[colour as usize].push(pair);
        }
        by_colour
    }

    /// The run holding each constraint's group.
    fn runs(coloring: &Coloring) -> Vec<ColourRun> {
        let run_of = |slot: u32| {
            let group = slot / LANES as u32;
            *coloring
                .ranges
                .iter()
                .find(|r| (r.start..r.end).contains(&group))
                .unwrap()
        };
        coloring.slot.iter().map(|&slot| run_of(slot)).collect()
    }

    #[test]
    fn no_colour_moves_a_body_twice_and_the_room_is_shared() {
        // A chain 0-1-2-3, a star around 4, and everything against the static room (5).
        let mut states = vec![moving(); 5];
        states.push(BodyState::STATIC);
        let mut pairs: Vec<(u32, u32)> = (0..5).map(|i| (i, 5)).collect();
        pairs.extend([(0, 1), (1, 2), (2, 3), (4, 0), (4, 1), (4, 2), (4, 3)]);

        let mut coloring = Coloring::default();
        coloring.assign(pairs.iter().copied(), &states);

        // Every constraint has its own slot, inside the groups.
        let mut slots = coloring.slot.clone();
        slots.sort_unstable();
        slots.dedup();
        assert_eq!(slots.len(), pairs.len());
        #[cfg(feature = "parallel")]
        {
            // ... and is found there.
            let slot = coloring.slot.clone();
            let constraint_at = coloring.constraint_at();
            for (i, &slot) in slot.iter().enumerate() {
                assert_eq!(constraint_at[slot as usize], i as u32);
            }
            let empty = constraint_at.iter().filter(|&&i| i == EMPTY_LANE);
            assert_eq!(empty.count(), coloring.groups * LANES - pairs.len());
        }
        assert!(slots
            .iter()
            .all(|&s| (s as usize) < coloring.groups * LANES));
        // The five room contacts share colour 0 (the room does not count):
        // two groups, the first full, in the given order.
        let room_run = ColourRun {
            start: 0,
            end: 2,
            moving: Moving::A,
        };
        assert_eq!(coloring.ranges[0], room_run);
        assert_eq!(&coloring.slot[..5], &[0, 1, 2, 3, 4]);
        let by_colour = colours(&coloring, &pairs);
        for colour in &by_colour[..by_colour.len() - 1] {
            let mut bodies: Vec<u32> = colour
                .iter()
                .flat_map(|&(a, b)| [a, b])
                .filter(|&i| i != 5)
                .collect();
            let n = bodies.len();
            bodies.sort_unstable();
            bodies.dedup();
            assert_eq!(bodies.len(), n, "a body moved twice in {colour:?}");
        }
        // Nothing overflowed.
        assert!(by_colour.last().unwrap().is_empty());
    }

    #[test]
    fn a_body_with_more_than_64_contacts_overflows_to_one_group_each() {
        let mut states = vec![moving(); 70];
        states.push(BodyState::STATIC);
        let pairs: Vec<(u32, u32)> = (1..70).map(|i| (0, i)).collect();
        let mut coloring = Coloring::default();
        coloring.assign(pairs.iter().copied(), &states);
        // 64 colours of one constraint (one group each), then 5 overflow groups.
        assert_eq!(coloring.ranges.len(), 65);
        let overflow = ColourRun {
            start: 64,
            end: 69,
            moving: Moving::Both,
        };
        assert_eq!(coloring.ranges[64], overflow);
        assert_eq!(coloring.groups, 69);
        // Each overflow constraint alone in lane 0 of its group.
        let lanes: Vec<u32> = coloring.slot[64..]
            .iter()
            .map(|s| s % LANES as u32)
            .collect();
        assert_eq!(lanes, vec![0; 5]);
    }

    /// Within a colour, the constraints against a fixed body (the room, a
    /// sleeper) take groups of their own, by the side that moves, in the
    /// given order within each; the runs say which side that is.
    #[test]
    fn constraints_against_fixed_bodies_get_groups_of_their_own() {
        // Bodies 0-3 move, 4 sleeps, 5 is the room.
        let mut states = vec![moving(); 4];
        let mut sleeper = BodyState::STATIC;
        sleeper.q = glam::Quat::from_rotation_z(0.3);
        states.extend([sleeper, BodyState::STATIC]);
        let pairs = [(0, 5), (4, 1), (2, 3), (1, 5), (3, 5), (4, 0)];
        let mut coloring = Coloring::default();
        coloring.assign(pairs.iter().copied(), &states);

        let run = |start, end, moving| ColourRun { start, end, moving };
        // Colour 0: (2, 3) between moving bodies, then (0, 5) against the
        // room, then (4, 1) against the sleeper; colour 1: (1, 5) and (3, 5)
        // in one group, then (4, 0); the overflow, empty.
        assert_eq!(
            coloring.ranges,
            vec![
                run(0, 1, Moving::Both),
                run(1, 2, Moving::A),
                run(2, 3, Moving::B),
                run(3, 4, Moving::A),
                run(4, 5, Moving::B),
                run(5, 5, Moving::Both),
            ]
        );
        assert_eq!(coloring.slot, vec![4, 8, 0, 12, 13, 16]);
        for ((a, b), run) in pairs.iter().zip(runs(&coloring)) {
            let (a, b) = (&states[*a as usize], &states[*b as usize]);
            assert_eq!(run.moving.fixes(0), a.is_fixed(), "{run:?}");
            assert_eq!(run.moving.fixes(1), b.is_fixed(), "{run:?}");
        }
    }
}
