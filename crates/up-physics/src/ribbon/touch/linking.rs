//! The linking number of two closed polylines (`linking_number`), and how
//! to close two ribbons tied near one point into loops that have one
//! (`closed_pair`): what says how many times two ribbons are twisted round
//! each other, and stays the same while neither passes through the other.

use glam::Vec3;

/// How far the loops' closing points lie from the ribbons, m: far enough
/// that a loop's closing segments wind round the other loop by a
/// negligible solid angle.
const FAR: f32 = 1.0e3;

/// The Gauss linking integral of closed polylines `a` and `b` (each point
/// joined to the next and the last to the first): the sum over their pairs
/// of segments of the solid angle one segment sees the other sweep, over
/// 4π (Klenin and Langowski, "Computation of writhe in modeling of
/// supercoiled DNA", Biopolymers 54, 2000, the exact form for straight
/// segments). An integer, up to rounding, for loops that do not meet.
pub fn gauss_linking(a: &[Vec3], b: &[Vec3]) -> f64 {
    let mut sum = 0.0f64;
    for i in 0..a.len() {
        let (p1, p2) = (a[i], a[(i + 1) % a.len()]);
        for j in 0..b.len() {
            let (p3, p4) = (b[j], b[(j + 1) % b.len()]);
            sum += solid_angle(p1, p2, p3, p4);
        }
    }
    sum / (4.0 * std::f64::consts::PI)
}

/// The linking number of closed polylines `a` and `b`: the Gauss integral
/// rounded, and how far it was from the integer.
pub fn linking_number(a: &[Vec3], b: &[Vec3]) -> (i32, f64) {
    let lk = gauss_linking(a, b);
    let n = lk.round();
    (n as i32, (lk - n).abs())
}

/// The signed solid angle under which segment `p1p2` sees segment `p3p4`
/// sweep (in f64: the far closing segments see each other at tiny angles).
fn solid_angle(p1: Vec3, p2: Vec3, p3: Vec3, p4: Vec3) -> f64 {
    let v = |p: Vec3| [p.x as f64, p.y as f64, p.z as f64];
    let (p1, p2, p3, p4) = (v(p1), v(p2), v(p3), v(p4));
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let unit = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        (l > 0.0).then(|| [a[0] / l, a[1] / l, a[2] / l])
    };
    let (r13, r14, r23, r24) = (sub(p3, p1), sub(p4, p1), sub(p3, p2), sub(p4, p2));
    let normals = [
        unit(cross(r13, r14)),
        unit(cross(r14, r24)),
        unit(cross(r24, r23)),
        unit(cross(r23, r13)),
    ];
    let [Some(n1), Some(n2), Some(n3), Some(n4)] = normals else {
        return 0.0; // the segments are coplanar or meet: no solid angle
    };
    let asin = |x: f64| x.clamp(-1.0, 1.0).asin();
    let omega = asin(dot(n1, n2)) + asin(dot(n2, n3)) + asin(dot(n3, n4)) + asin(dot(n4, n1));
    let side = dot(cross(sub(p4, p3), sub(p2, p1)), r13);
    if side > 0.0 {
        omega
    } else if side < 0.0 {
        -omega
    } else {
        0.0
    }
}

/// Two ribbons' points, each from its tied end up to its balloon's knot
/// (`a[0]` and `b[0]` near each other, a few centimetres apart, not at
/// one point), closed into loops whose linking number counts the turns
/// they are twisted round each other: each goes on from its knot far
/// along `up` and out to its own side (`a` toward where its knot lies from
/// `b`'s, `b` away), down past its tied end and back to it from below on
/// that side. Untwisted ribbons, each on its own side all the way up, give
/// 0; each full turn of one round the other adds one, its sign the turn's
/// sense about `up`. Each ribbon needs a point at least (it panics if not).
pub fn closed_pair(a: &[Vec3], b: &[Vec3], up: Vec3) -> (Vec<Vec3>, Vec<Vec3>) {
    assert!(!a.is_empty() && !b.is_empty(), "a ribbon without points");
    let up = up.normalize();
    let (ka, kb) = (*a.last().unwrap(), *b.last().unwrap());
    let apart = (ka - kb) - (ka - kb).dot(up) * up;
    let side = apart
        .try_normalize()
        .unwrap_or_else(|| up.any_orthonormal_vector());
    let close = |points: &[Vec3], side: Vec3| {
        let (start, knot) = (points[0], *points.last().unwrap());
        let mut loop_ = points.to_vec();
        loop_.push(knot + FAR * up);
        loop_.push(knot + FAR * (up + side));
        loop_.push(start + FAR * (side - up));
        loop_.push(start - FAR * up);
        loop_
    };
    (close(a, side), close(b, -side))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A circle of `n` points of radius `r` about `centre` in the plane
    /// spanned by `u` and `v`.
    fn circle(centre: Vec3, u: Vec3, v: Vec3, r: f32, n: usize) -> Vec<Vec3> {
        (0..n)
            .map(|k| {
                let t = k as f32 / n as f32 * std::f32::consts::TAU;
                centre + r * (t.cos() * u + t.sin() * v)
            })
            .collect()
    }

    #[test]
    fn two_rings_through_each_other_link_once_and_apart_not_at_all() {
        let a = circle(Vec3::ZERO, Vec3::X, Vec3::Y, 1.0, 40);
        let b = circle(Vec3::X, Vec3::X, Vec3::Z, 1.0, 40);
        let (lk, off) = linking_number(&a, &b);
        assert_eq!(lk.abs(), 1, "Hopf link: {lk}");
        assert!(off < 1e-3, "{off}");
        let (lk_ba, _) = linking_number(&b, &a);
        assert_eq!(lk_ba, lk, "symmetric");
        let far = circle(Vec3::new(5.0, 0.0, 0.0), Vec3::X, Vec3::Z, 1.0, 40);
        let (lk, off) = linking_number(&a, &far);
        assert_eq!(lk, 0);
        assert!(off < 1e-3, "{off}");
    }

    /// Two strands from (±1 cm, 0, 0) up 1.5 m, wound `turns` times round
    /// each other (a double helix of radius 2 cm), in `n` points each.
    fn twisted(turns: f32, n: usize) -> (Vec<Vec3>, Vec<Vec3>) {
        let strand = |phase: f32| {
            (0..=n)
                .map(|k| {
                    let s = k as f32 / n as f32;
                    let t = phase + s * turns * std::f32::consts::TAU;
                    let r = 0.01 + 0.01 * (std::f32::consts::PI * s).sin();
                    Vec3::new(r * t.cos(), 1.5 * s, r * t.sin())
                })
                .collect::<Vec<_>>()
        };
        (strand(0.0), strand(std::f32::consts::PI))
    }

    #[test]
    fn strands_twisted_n_turns_link_n_times_with_the_turns_sense() {
        for turns in [0.0f32, 1.0, 3.0, -2.0] {
            let (a, b) = twisted(turns, 96);
            let (la, lb) = closed_pair(&a, &b, Vec3::Y);
            let (lk, off) = linking_number(&la, &lb);
            assert!(off < 0.01, "{turns} turns: {off} off an integer");
            assert_eq!(lk.abs(), turns.abs() as i32, "{turns} turns: {lk}");
        }
        let (a, b) = twisted(3.0, 96);
        let (c, d) = twisted(-3.0, 96);
        let (la, lb) = closed_pair(&a, &b, Vec3::Y);
        let (lc, ld) = closed_pair(&c, &d, Vec3::Y);
        assert_eq!(linking_number(&la, &lb).0, -linking_number(&lc, &ld).0);
    }
}
