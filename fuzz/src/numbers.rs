//! Shared input decoding for the fuzz targets: a byte string read as a
//! stream of bounded, finite numbers (missing bytes read as zero).

use glam::{Quat, Vec3};

/// Reads numbers from the fuzzer's bytes, front to back.
pub struct Numbers<'a> {
    bytes: &'a [u8],
}

impl<'a> Numbers<'a> {
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    pub fn byte(&mut self) -> u8 {
        match self.bytes.split_first() {
            Some((&b, rest)) => {
                self.bytes = rest;
                b
            }
            None => 0,
        }
    }

    /// Any finite f32 (non-finite bit patterns read as 0), folded into
    /// (−limit, limit) with `%` so tiny and subnormal values survive.
    pub fn f32_within(&mut self, limit: f32) -> f32 {
        let bits = u32::from_le_bytes([self.byte(), self.byte(), self.byte(), self.byte()]);
        let x = f32::from_bits(bits);
        if x.is_finite() {
            x % limit
        } else {
            0.0
        }
    }

    /// A radius in [min, min + limit).
    pub fn radius(&mut self, min: f32, limit: f32) -> f32 {
        self.f32_within(limit).abs() + min
    }

    pub fn vec3(&mut self, limit: f32) -> Vec3 {
        Vec3::new(
            self.f32_within(limit),
            self.f32_within(limit),
            self.f32_within(limit),
        )
    }

    /// A unit quaternion (the identity when the four numbers are all zero).
    pub fn rotation(&mut self) -> Quat {
        let q = Quat::from_xyzw(
            self.f32_within(1.0),
            self.f32_within(1.0),
            self.f32_within(1.0),
            self.f32_within(1.0),
        );
        if q.length_squared() > 1e-6 {
            q.normalize()
        } else {
            Quat::IDENTITY
        }
    }
}

/// |normal| = 1 within 1e-3.
pub fn is_unit(v: Vec3) -> bool {
    (v.length() - 1.0).abs() <= 1e-3
}

/// A sliver: smallest angle below ~0.06° (twice the area under 1e-3 of the
/// longest side squared), or sizes past f32 (a NaN on the way counts as one).
pub fn is_sliver(tri: &[Vec3; 3]) -> bool {
    let longest = (tri[1] - tri[0])
        .length_squared()
        .max((tri[2] - tri[1]).length_squared())
        .max((tri[0] - tri[2]).length_squared());
    let twice_area = (tri[1] - tri[0]).cross(tri[2] - tri[0]).length();
    let well_shaped = twice_area >= 1e-3 * longest;
    !well_shaped
}

/// Distance between two points in f64 (the reference for f32 results).
pub fn distance64(a: Vec3, b: Vec3) -> f64 {
    let d = a.as_dvec3() - b.as_dvec3();
    d.length()
}

/// The triangle's unit normal as the queries define it: none when the cross
/// product's squared length is zero or subnormal.
pub fn face_normal(tri: &[Vec3; 3]) -> Option<Vec3> {
    let cross = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    (cross.length_squared() >= f32::MIN_POSITIVE).then(|| cross.normalize())
}
