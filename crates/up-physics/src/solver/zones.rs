//! Zones: the room cut into slabs across its longer horizontal axis, one
//! number a body, that order the constraints within their colours
//! (`coloring`) so that a thread keeps moving the same bodies.

use glam::Vec3;

use super::coloring::ZONES;

/// Each body's zone from its centre: `ZONES` equal slabs over the centres'
/// extent along x or z, whichever is longer.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))] // one thread: no zones
pub(crate) fn zone_bodies(centers: &[Vec3], zones: &mut Vec<u8>) {
    zones.clear();
    let Some(&first) = centers.first() else {
        return;
    };
    let (min, max) = centers
        .iter()
        .fold((first, first), |(lo, hi), &c| (lo.min(c), hi.max(c)));
    let extent = max - min;
    let (axis, length) = if extent.x >= extent.z {
        (0, extent.x)
    } else {
        (2, extent.z)
    };
    // Non-finite centres (a body about to be quarantined) land in zone 0.
    let per_metre = if length > 0.0 && length.is_finite() {
        ZONES as f32 / length
    } else {
        0.0
    };
    let last = (ZONES - 1) as f32;
    zones.extend(centers.iter().map(|c| {
        let zone = (c[axis] - min[axis]) * per_metre;
        // `as` takes NaN to 0.
        zone.clamp(0.0, last) as u8
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slabs_cut_the_longer_axis_evenly() {
        // 4 m along z, 1 m along x: the zones follow z.
        let centers: Vec<Vec3> = (0..=8)
            .map(|k| Vec3::new(0.1 * (k % 2) as f32, 3.0, 0.5 * k as f32))
            .collect();
        let mut zones = Vec::new();
        zone_bodies(&centers, &mut zones);
        let expected: Vec<u8> = (0..=8)
            .map(|k| (k * ZONES / 8).min(ZONES - 1) as u8)
            .collect();
        assert_eq!(zones, expected);
    }

    #[test]
    fn one_body_or_a_non_finite_centre_takes_zone_0() {
        let mut zones = vec![7];
        zone_bodies(&[Vec3::ONE], &mut zones);
        assert_eq!(zones, vec![0]);
        zone_bodies(
            &[Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X],
            &mut zones,
        );
        assert_eq!(zones[1], 0);
        assert_eq!(zones[2] as usize, ZONES - 1);
        zone_bodies(&[], &mut zones);
        assert!(zones.is_empty());
    }
}
