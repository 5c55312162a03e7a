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
use super::contact_constraint::ContactConstraint;

/// Colours a body can carry (bits of a `u64`).
const COLORS: usize = 64;

/// The constraints' order by colour, reused from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Coloring {
    /// Colour of each constraint, in the narrowphase's order (`COLORS` = overflow).
    color: Vec<u8>,
    /// Colours already used by each body's constraints.
    used: Vec<u64>,
    /// `[start, end)` of each colour in the sorted constraints; the last is the overflow.
    pub ranges: Vec<(u32, u32)>,
    /// For each constraint in the narrowphase's order, where it went.
    pub position: Vec<u32>,
    /// The inverse of `position`.
    order: Vec<u32>,
    sorted: Vec<ContactConstraint>,
}

impl Coloring {
    /// Colours `constraints` greedily (lowest free colour, in their given
    /// order, so room contacts, which come first, are solved first) and
    /// reorders them by colour, keeping the given order within a colour.
    pub fn sort(&mut self, constraints: &mut Vec<ContactConstraint>, states: &[BodyState]) {
        self.used.clear();
        self.used.resize(states.len(), 0);
        self.color.clear();
        let mut counts = [0u32; COLORS + 1];
        for c in constraints.iter() {
            let moving = |i: u32| states[i as usize].inv_mass > 0.0;
            let (a, b) = (c.a as usize, c.b as usize);
            let taken = if moving(c.a) { self.used[a] } else { 0 }
                | if moving(c.b) { self.used[b] } else { 0 };
            let color = (!taken).trailing_zeros() as usize; // 64 when all are taken
            if color < COLORS {
                let bit = 1u64 << color;
                if moving(c.a) {
                    self.used[a] |= bit;
                }
                if moving(c.b) {
                    self.used[b] |= bit;
                }
            }
            self.color.push(color as u8);
            counts[color] += 1;
        }

        self.ranges.clear();
        let mut next = [0u32; COLORS + 1];
        let mut start = 0u32;
        for (color, &count) in counts.iter().enumerate() {
            next[color] = start;
            if count > 0 || color == COLORS {
                self.ranges.push((start, start + count));
            }
            start += count;
        }
        // Counting sort: where each constraint goes, then one gathering copy.
        self.position.clear();
        self.order.clear();
        self.order.resize(constraints.len(), 0);
        for (i, &color) in self.color.iter().enumerate() {
            let slot = next[color as usize];
            next[color as usize] += 1;
            self.position.push(slot);
            self.order[slot as usize] = i as u32;
        }
        self.sorted.clear();
        self.sorted
            .extend(self.order.iter().map(|&i| constraints[i as usize]));
        std::mem::swap(constraints, &mut self.sorted);
    }
}

#[cfg(test)]
mod tests {
    use glam::{Mat3, Vec3};

    use super::*;
    use crate::contact::ContactPoint;
    use crate::solver::contact_constraint::prepare;

    fn moving() -> BodyState {
        BodyState {
            inv_mass: 1.0,
            inv_inertia: Mat3::IDENTITY,
            ..BodyState::STATIC
        }
    }

    fn constraint(a: u32, b: u32, states: &[BodyState]) -> ContactConstraint {
        let point = ContactPoint {
            body_a: a,
            body_b: b,
            normal: Vec3::Y,
            point_a: Vec3::ZERO,
            point_b: Vec3::ZERO,
            separation: 0.0,
            feature: (a as u64) << 32 | b as u64,
        };
        let zero = (Vec3::ZERO, Vec3::ZERO);
        prepare(&point, a, b, states, zero, zero, (0.5, 0.0), &[])
    }

    #[test]
    fn no_colour_moves_a_body_twice_and_the_room_is_shared() {
        // A chain 0-1-2-3, a star around 4, and everything against the static room (5).
        let mut states = vec![moving(); 5];
        states.push(BodyState::STATIC);
        let links = [(0, 1), (1, 2), (2, 3), (4, 0), (4, 1), (4, 2), (4, 3)];
        let mut constraints: Vec<_> = (0..5).map(|i| constraint(i, 5, &states)).collect();
        constraints.extend(links.iter().map(|&(a, b)| constraint(a, b, &states)));
        let original = constraints.clone();

        let mut coloring = Coloring::default();
        coloring.sort(&mut constraints, &states);

        // Every constraint kept, and `position` says where it went.
        for (i, c) in original.iter().enumerate() {
            assert_eq!(
                constraints[coloring.position[i] as usize].feature,
                c.feature
            );
        }
        // The five room contacts share colour 0: the room does not count.
        assert_eq!(coloring.ranges[0], (0, 5));
        for &(start, end) in &coloring.ranges[..coloring.ranges.len() - 1] {
            let mut bodies: Vec<u32> = constraints[start as usize..end as usize]
                .iter()
                .flat_map(|c| [c.a, c.b])
                .filter(|&i| i != 5)
                .collect();
            let n = bodies.len();
            bodies.sort_unstable();
            bodies.dedup();
            assert_eq!(
                bodies.len(),
                n,
                "a body moved twice in colour {start}..{end}"
            );
        }
        // Nothing overflowed.
        assert_eq!(coloring.ranges.last(), Some(&(12, 12)));
    }

    #[test]
    fn a_body_with_more_than_64_contacts_overflows_to_the_serial_group() {
        let mut states = vec![moving(); 70];
        states.push(BodyState::STATIC);
        let mut constraints: Vec<_> = (1..70).map(|i| constraint(0, i, &states)).collect();
        let mut coloring = Coloring::default();
        coloring.sort(&mut constraints, &states);
        assert_eq!(coloring.ranges.len(), 65);
        assert_eq!(coloring.ranges[64], (64, 69));
    }
}
