//! Drops the speculative contacts of a pair that a shallower contact of the
//! same pair shadows.
//!
//! Two sphere trees pressed together meet at several leaf pairs within the
//! margin, most of them gaps of millimetres to centimetres with nearly the
//! normal of the pair's touching contact: about four contacts a pair in a
//! settling pile, a fifth of them touching. A speculative contact j (gap
//! `s_j > 0`) matters only if the bodies can close it before the next query.
//! Normals point from A to B; let `u(x)` be B's displacement relative to A at
//! the point x, so that a gap at midpoint p with normal n becomes, to first
//! order, `s + u(p)·n`. If `|u| ≤ displacement` at every surface point and
//! the bodies turn relative to each other by at most `turn` radians, then
//! `u(p_j) = u(p_i) + θ × (p_j − p_i)` and
//!
//! `gap_j' ≥ gap_i' + (s_j − s_i) − displacement·|n_j − n_i| − turn·|p_j − p_i|`.
//!
//! When the last three terms add up to no less than zero, gap j ends no
//! smaller than gap i, which the solver holds, and j is dropped. Contacts
//! that touch are always kept (they carry load), and so is anything a fast or
//! spinning pair could close (its bounds are wide, the inequality fails). The
//! promise is as good as the bounds the caller gives.

use crate::norm::{distance, Norm};
use crate::{Contact, Vec3};

/// The most two shapes can move relative to each other before their contacts
/// are found again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelativeMotion {
    /// Relative displacement of any pair of surface points, m.
    pub displacement: f32,
    /// Relative rotation, rad.
    pub turn: f32,
}

/// Removes the contacts of one pair that a kept, shallower contact shadows
/// (see the module's doc); the rest come out shallowest first (ties by
/// feature, so the order does not depend on the input's). Shadowing is
/// transitive (the triangle inequality, on normals and on points), so what a
/// dropped contact shadows, the contact that dropped it shadows too: testing
/// against the kept ones alone is enough.
pub fn prune_shadowed(contacts: &mut Vec<Contact>, motion: RelativeMotion) {
    if contacts.len() < 2 {
        return;
    }
    contacts.sort_unstable_by(|a, b| {
        a.separation
            .total_cmp(&b.separation)
            .then(a.feature_a.cmp(&b.feature_a))
            .then(a.feature_b.cmp(&b.feature_b))
    });
    let mut kept = 0;
    for j in 0..contacts.len() {
        let c = contacts[j];
        let shadowed =
            c.separation > 0.0 && contacts[..kept].iter().any(|i| shadows(i, &c, motion));
        if !shadowed {
            contacts[kept] = c;
            kept += 1;
        }
    }
    contacts.truncate(kept);
}

/// Whether `j` cannot close before the shallower `i` has (the inequality above).
#[inline]
fn shadows(i: &Contact, j: &Contact, motion: RelativeMotion) -> bool {
    let lead = j.separation - i.separation;
    let turn_room = motion.turn * distance(midpoint(j), midpoint(i));
    lead >= motion.displacement * (j.normal - i.normal).norm() + turn_room
}

#[inline]
fn midpoint(c: &Contact) -> Vec3 {
    0.5 * (c.point_a + c.point_b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn contact(separation: f32, normal: Vec3, at: Vec3, feature: u32) -> Contact {
        let normal = normal.normalize();
        Contact {
            point_a: at - 0.5 * separation * normal,
            point_b: at + 0.5 * separation * normal,
            normal,
            separation,
            feature_a: feature,
            feature_b: feature,
        }
    }

    const STILL: RelativeMotion = RelativeMotion {
        displacement: 0.02,
        turn: 0.0,
    };

    #[test]
    fn a_parallel_deeper_gap_is_dropped_and_touching_contacts_stay() {
        let mut cs = vec![
            contact(0.004, Vec3::Y, Vec3::new(0.05, 0.0, 0.0), 1),
            contact(-0.001, Vec3::Y, Vec3::ZERO, 2),
            contact(-0.0005, Vec3::Y, Vec3::new(-0.05, 0.0, 0.0), 3),
        ];
        prune_shadowed(&mut cs, STILL);
        let features: Vec<u32> = cs.iter().map(|c| c.feature_a).collect();
        assert_eq!(features, vec![2, 3]);
    }

    #[test]
    fn a_gap_at_a_different_normal_stays_unless_it_leads_by_enough() {
        // 0.1 rad apart: |Δn| ≈ 0.1, so 2 mm of lead at a 2 cm displacement.
        let tilted = Vec3::new(0.1f32.sin(), 0.1f32.cos(), 0.0);
        let near = contact(0.0015, tilted, Vec3::X * 0.05, 1);
        let far = contact(0.0025, tilted, Vec3::X * 0.05, 1);
        for (c, dropped) in [(near, false), (far, true)] {
            let mut cs = vec![contact(0.0, Vec3::Y, Vec3::ZERO, 0), c];
            prune_shadowed(&mut cs, STILL);
            assert_eq!(cs.len(), if dropped { 1 } else { 2 }, "{c:?}");
        }
    }

    #[test]
    fn turning_keeps_distant_gaps() {
        let mut cs = vec![
            contact(0.0, Vec3::Y, Vec3::ZERO, 0),
            contact(0.003, Vec3::Y, Vec3::X * 0.1, 1),
        ];
        let turning = RelativeMotion {
            displacement: 0.02,
            turn: 0.05, // 5 mm of turn room at 0.1 m
        };
        prune_shadowed(&mut cs, turning);
        assert_eq!(cs.len(), 2);
        prune_shadowed(&mut cs, STILL);
        assert_eq!(cs.len(), 1);
    }

    #[test]
    fn the_result_does_not_depend_on_the_input_order() {
        let n = |angle: f32| Vec3::new(angle.sin(), angle.cos(), 0.0);
        let cs = vec![
            contact(0.0, n(0.0), Vec3::ZERO, 0),
            contact(0.003, n(0.1), Vec3::X * 0.02, 1),
            contact(0.003, n(-0.1), Vec3::X * -0.02, 2),
            contact(0.001, n(0.3), Vec3::Z * 0.05, 3),
            contact(-0.0002, n(0.05), Vec3::Z * -0.05, 4),
            // A tie that both stay: the order is the features'.
            contact(0.002, n(-0.8), Vec3::X * -0.08, 6),
            contact(0.002, n(0.8), Vec3::X * 0.08, 5),
        ];
        let mut forward = cs.clone();
        prune_shadowed(&mut forward, STILL);
        let mut backward: Vec<Contact> = cs.into_iter().rev().collect();
        prune_shadowed(&mut backward, STILL);
        assert_eq!(forward, backward);
        let features: Vec<u32> = forward.iter().map(|c| c.feature_a).collect();
        assert_eq!(features, vec![4, 0, 3, 5, 6]);
    }

    proptest! {
        /// The promise itself: for a relative motion within the bounds (a
        /// displacement of at most `displacement` at a kept contact i and a
        /// turn of at most `turn` about it, the bounds themselves included),
        /// no contact that i shadows ends with a smaller gap than i's, and
        /// every dropped contact has such an i.
        #[test]
        fn no_dropped_contact_closes_before_the_kept_ones(
            raw in prop::collection::vec(
                ((-0.002f32..0.02), (-0.4f32..0.4), (-0.4f32..0.4), (-0.1f32..0.1), (-0.1f32..0.1)),
                1..12,
            ),
            d in ((-1f32..1.0), (-1f32..1.0), (-1f32..1.0)),
            axis in ((-1f32..1.0), (-1f32..1.0), (-1f32..1.0)),
            (u_share, theta_share) in prop_oneof![Just((1.0f32, 1.0f32)), ((0f32..1.0), (0f32..1.0))],
            displacement in 0.0f32..0.03,
            turn in 0.0f32..0.1,
        ) {
            let all: Vec<Contact> = raw
                .iter()
                .enumerate()
                .map(|(k, &(s, nx, nz, px, pz))| {
                    contact(s, Vec3::new(nx, 1.0, nz), Vec3::new(px, 0.0, pz), k as u32)
                })
                .collect();
            let bounds = RelativeMotion { displacement, turn };
            let mut kept = all.clone();
            prune_shadowed(&mut kept, bounds);
            let unit = |v: (f32, f32, f32)| Vec3::new(v.0, v.1, v.2).normalize_or(Vec3::X);
            let u = unit(d) * displacement * u_share;
            let theta = unit(axis) * turn * theta_share;
            for j in all.iter().filter(|c| !kept.contains(c)) {
                prop_assert!(j.separation > 0.0);
                let shadowing: Vec<&Contact> =
                    kept.iter().filter(|i| shadows(i, j, bounds)).collect();
                prop_assert!(!shadowing.is_empty(), "{j:?} dropped, shadowed by nothing kept");
                for i in shadowing {
                    let offset = midpoint(j) - midpoint(i);
                    // The motion that closes j fastest against i, and a random one.
                    let worst_u = -(j.normal - i.normal).normalize_or_zero() * displacement;
                    let worst_theta = -offset.cross(j.normal).normalize_or_zero() * turn;
                    for (u, theta) in [(u, theta), (worst_u, worst_theta)] {
                        // B's displacement relative to A: u at i, turning about i.
                        let at = |c: &Contact| u + theta.cross(midpoint(c) - midpoint(i));
                        let gap = |c: &Contact| c.separation + at(c).dot(c.normal);
                        prop_assert!(gap(j) >= gap(i) - 1e-6,
                            "dropped {j:?} closes to {} before {i:?} (to {})", gap(j), gap(i));
                    }
                }
            }
        }
    }
}
