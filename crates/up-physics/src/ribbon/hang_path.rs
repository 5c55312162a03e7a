//! Where a new ribbon's points start: hung from its knot, laid inside the
//! room. The scene builder predicts the same path to keep balloons clear of
//! it, so both read this one function.

use glam::Vec3;

/// `segments` points after `knot`, `segment_length` apart, straight `down`;
/// where the next point would leave the box `bounds` (`(lo, hi)`, already
/// less the end's radius), along the floor toward the box's middle, and
/// round a wall where it meets one.
pub fn hang_path(
    knot: Vec3,
    down: Vec3,
    segment_length: f32,
    segments: usize,
    bounds: Option<(Vec3, Vec3)>,
) -> Vec<Vec3> {
    let mut points = vec![knot];
    let mut direction = down;
    for _ in 0..segments {
        let last = *points.last().unwrap_or(&knot);
        let mut next = last + direction * segment_length;
        if let Some((lo, hi)) = bounds {
            if next.clamp(lo, hi) != next {
                // Along the floor toward the room's middle, or round a wall.
                let middle = 0.5 * (lo + hi);
                let toward = (middle - last) - (middle - last).dot(down) * down;
                direction = if direction == down {
                    toward.try_normalize().unwrap_or(Vec3::X)
                } else {
                    down.cross(direction)
                };
                next = (last + direction * segment_length).clamp(lo, hi);
            }
        }
        points.push(next);
    }
    points
}
