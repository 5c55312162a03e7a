//! Graph colouring of the contact constraints (the idea of Box2D v3's
//! constraint graph): no two constraints of one colour move the same body, so
//! the constraints of a colour can be solved at once, in any order and on any
//! number of threads, with the same result. Colours are solved one after the
//! other, which keeps the Gauss-Seidel character of the solve.
//!
//! Static bodies (the room, sleeping balloons) never take an impulse, so they
//! do not count as shared. Constraints that find no free colour among the 64
//! go to a last, overflow group that is solved serially.

use super::body_state::BodyState;
use super::lanes::LANES;
use crate::spare::{release_spare, BUFFER_FLOOR};

/// Marks a slot that holds no constraint.
#[cfg(feature = "parallel")]
pub(crate) const EMPTY_LANE: u32 = u32::MAX;

/// Colours a body can carry (bits of a `u64`).
const COLORS: usize = 64;

/// Where each constraint goes, reused from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Coloring {
    /// Colour of each constraint, in the narrowphase's order (`COLORS` = overflow).
    color: Vec<u8>,
    /// Colours already used by each body's constraints.
    used: Vec<u64>,
    /// `[start, end)` of each colour's groups of `LANES` constraints; the
    /// last is the overflow, one constraint per group so that it runs serially.
    pub ranges: Vec<(u32, u32)>,
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
    /// `LANES` to a group, in the given order within a colour.
    pub fn assign(&mut self, pairs: impl Iterator<Item = (u32, u32)>, states: &[BodyState]) {
        self.used.clear();
        self.used.resize(states.len(), 0);
        self.color.clear();
        // Filled only when the groups are assembled in tasks; empty otherwise,
        // so that its length is this step's use (`spare`).
        #[cfg(feature = "parallel")]
        self.constraint_at.clear();
        let mut counts = [0u32; COLORS + 1];
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
            self.color.push(color as u8);
            counts[color] += 1;
        }

        // Each colour's first group; the overflow takes a group per constraint.
        self.ranges.clear();
        let mut first_group = [0u32; COLORS + 1];
        let mut start = 0u32;
        for (color, &count) in counts.iter().enumerate() {
            let groups = if color == COLORS {
                count
            } else {
                count.div_ceil(LANES as u32)
            };
            first_group[color] = start;
            if count > 0 || color == COLORS {
                self.ranges.push((start, start + groups));
            }
            start += groups;
        }
        self.groups = start as usize;

        self.slot.clear();
        let mut seen = [0u32; COLORS + 1];
        for &color in &self.color {
            let color = color as usize;
            let k = seen[color];
            seen[color] += 1;
            let slot = if color == COLORS {
                (first_group[color] + k) * LANES as u32
            } else {
                first_group[color] * LANES as u32 + k
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

    /// The constraints of each group of each colour, as (a, b) pairs.
    fn colours(coloring: &Coloring, pairs: &[(u32, u32)]) -> Vec<Vec<(u32, u32)>> {
        coloring
            .ranges
            .iter()
            .map(|&(start, end)| {
                pairs
                    .iter()
                    .zip(&coloring.slot)
                    .filter(|(_, &slot)| (start..end).contains(&(slot / LANES as u32)))
                    .map(|(&pair, _)| pair)
                    .collect()
            })
            .collect()
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
        assert_eq!(coloring.ranges[0], (0, 2));
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
        assert_eq!(coloring.ranges[64], (64, 69));
        assert_eq!(coloring.groups, 69);
        // Each overflow constraint alone in lane 0 of its group.
        let lanes: Vec<u32> = coloring.slot[64..]
            .iter()
            .map(|s| s % LANES as u32)
            .collect();
        assert_eq!(lanes, vec![0; 5]);
    }
}
