//! Counting ribbons passing through each other between two states of their
//! points (`crossings`): what the tests of ribbon contacts count, every
//! step.
//!
//! A crossing: two segments of different ribbons whose lines' signed
//! volume `((a1 − a0) × (b1 − b0))·(b0 − a0)` changes sign between the two
//! states and whose line between the lines' closest points turns over
//! (their centre lines passed through each other; two segments side by
//! side that turn through parallel flip the volume's sign but keep their
//! sides), while the closest points of the two lines lie inside both
//! segments, in both states, and were closer than `thickness` plus how far
//! those closest points moved against each other (so that a segment swept
//! past another within one step counts).

use glam::Vec3;

/// The closest points' parameters of two lines, `None` if parallel.
fn line_parameters(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> Option<(f32, f32)> {
    let (d1, d2, r) = (a1 - a0, b1 - b0, a0 - b0);
    let (a, b, c, e, f) = (d1.dot(d1), d1.dot(d2), d1.dot(r), d2.dot(d2), d2.dot(r));
    let denom = a * e - b * b;
    if denom <= 1e-9 * a * e {
        return None;
    }
    Some(((b * f - c * e) / denom, (a * f - b * c) / denom))
}

/// The line from segment `a`'s line's closest point to `b`'s, if both lie
/// inside the segments; and the signed volume.
fn closest_inside(a: [Vec3; 2], b: [Vec3; 2]) -> Option<(Vec3, f32)> {
    let (s, t) = line_parameters(a[0], a[1], b[0], b[1])?;
    if !((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t)) {
        return None;
    }
    let pa = a[0] + (a[1] - a[0]) * s;
    let pb = b[0] + (b[1] - b[0]) * t;
    let volume = (a[1] - a[0]).cross(b[1] - b[0]).dot(b[0] - a[0]);
    Some((pb - pa, volume))
}

/// Whether segment `a` passed through segment `b` between their states
/// `was` and `now`, by the rule above.
pub fn segments_crossed(
    was: ([Vec3; 2], [Vec3; 2]),
    now: ([Vec3; 2], [Vec3; 2]),
    thickness: f32,
) -> bool {
    let (Some((d0, v0)), Some((d1, v1))) =
        (closest_inside(was.0, was.1), closest_inside(now.0, now.1))
    else {
        return false;
    };
    if v0.signum() == v1.signum() || v0 == 0.0 || d0.dot(d1) >= 0.0 {
        return false;
    }
    let near = thickness + (d1 - d0).length();
    d0.length() < near && d1.length() < near
}

/// Whether segment `a` passed through segment `b` between their states
/// `was` and `now`, each point taken as moving in a straight line between
/// them, checked by the rule between `samples` evenly spaced states along
/// the way (so that a segment swept several of its lengths past another in
/// a step, turning as it goes, is seen where it crossed).
pub fn segments_crossed_along(
    was: ([Vec3; 2], [Vec3; 2]),
    now: ([Vec3; 2], [Vec3; 2]),
    thickness: f32,
    samples: u32,
) -> bool {
    let at = |k: u32| {
        let f = k as f32 / samples as f32;
        let lerp = |p: [Vec3; 2], q: [Vec3; 2]| [p[0].lerp(q[0], f), p[1].lerp(q[1], f)];
        (lerp(was.0, now.0), lerp(was.1, now.1))
    };
    (0..samples).any(|k| segments_crossed(at(k), at(k + 1), thickness))
}

/// The crossings between two states of the ribbons' points, `before` and
/// `after` (per ribbon, each ribbon's points in both), of ribbons
/// `thickness` m thick: every pair of segments of different ribbons whose
/// boxes over the two states come within 1 cm. The two states must hold
/// the same ribbons with the same points (it panics, saying which, if not).
pub fn crossings<P: AsRef<[Vec3]>>(before: &[P], after: &[P], thickness: f32) -> usize {
    assert_eq!(before.len(), after.len(), "ribbons before and after");
    for (k, (p, q)) in before.iter().zip(after).enumerate() {
        assert_eq!(p.as_ref().len(), q.as_ref().len(), "points of ribbon {k}");
    }
    let boxes: Vec<(Vec3, Vec3)> = after
        .iter()
        .zip(before)
        .map(|(p, q)| {
            let all = p.as_ref().iter().chain(q.as_ref());
            let lo = all.clone().fold(Vec3::splat(f32::MAX), |m, v| m.min(*v));
            let hi = all.fold(Vec3::splat(f32::MIN), |m, v| m.max(*v));
            (lo, hi)
        })
        .collect();
    let mut count = 0;
    for i in 0..after.len() {
        for j in i + 1..after.len() {
            let (lo, hi) = (boxes[i].0.max(boxes[j].0), boxes[i].1.min(boxes[j].1));
            if lo.cmpgt(hi + Vec3::splat(0.01)).any() {
                continue;
            }
            let (bi, bj) = (before[i].as_ref(), before[j].as_ref());
            let (ai, aj) = (after[i].as_ref(), after[j].as_ref());
            for si in 0..ai.len().saturating_sub(1) {
                for sj in 0..aj.len().saturating_sub(1) {
                    let was = ([bi[si], bi[si + 1]], [bj[sj], bj[sj + 1]]);
                    let now = ([ai[si], ai[si + 1]], [aj[sj], aj[sj + 1]]);
                    count += usize::from(segments_crossed(was, now, thickness));
                }
            }
        }
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_segment_swept_through_another_crosses_and_one_swept_past_does_not() {
        let b = [Vec3::new(0.0, 0.0, -0.1), Vec3::new(0.0, 0.0, 0.1)];
        let at = |y: f32| [Vec3::new(-0.1, y, 0.0), Vec3::new(0.1, y, 0.0)];
        // Through: from 1 cm above to 1 cm below in one step.
        assert!(segments_crossed((at(0.01), b), (at(-0.01), b), 0.005));
        // Back up to where it was, still above: no crossing.
        assert!(!segments_crossed((at(0.01), b), (at(0.02), b), 0.005));
        // Past its end: the lines' closest point lies outside `b`.
        let past = |y: f32| [Vec3::new(-0.1, y, 0.3), Vec3::new(0.1, y, 0.3)];
        assert!(!segments_crossed((past(0.01), b), (past(-0.01), b), 0.005));
        let ribbons = |y: f32| vec![vec![at(y)[0], at(y)[1]], vec![b[0], b[1]]];
        assert_eq!(crossings(&ribbons(0.01), &ribbons(-0.01), 0.005), 1);
        assert_eq!(crossings(&ribbons(0.01), &ribbons(0.004), 0.005), 0);
    }
}
