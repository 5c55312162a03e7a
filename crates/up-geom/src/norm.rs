//! Lengths and unit vectors on the square-root instruction, everywhere.
//!
//! glam's `libm` feature keeps its transcendental functions the same on
//! every platform, but also sends `sqrt` through libm, and in WebAssembly
//! libm's `sqrtf` is a software loop (its instruction path needs a nightly
//! compiler): 6.6 % of a 10,000-balloon step in Node. IEEE 754 rounds a
//! square root correctly, in hardware and in libm alike, so `f32::sqrt` (one
//! `sqrtss` natively, one `f32.sqrt` in WebAssembly) gives the same bits.
//! These are glam's `length`, `normalize`, `normalize_or_zero`,
//! `try_normalize`, `distance` and `Quat::normalize`, with its operations in
//! its order: the results, and so the simulation's state, are unchanged.
//! The step's hot paths use them; glam's own stay fine elsewhere.

use glam::{Quat, Vec3, Vec4};

/// glam's lengths with the square root as an instruction (see the module).
pub trait Norm: Sized {
    /// `length`.
    fn norm(self) -> f32;
    /// `normalize`.
    fn unit(self) -> Self;
}

impl Norm for Vec3 {
    #[inline]
    fn norm(self) -> f32 {
        self.dot(self).sqrt()
    }

    #[inline]
    fn unit(self) -> Vec3 {
        self * self.norm().recip()
    }
}

impl Norm for Vec4 {
    #[inline]
    fn norm(self) -> f32 {
        self.dot(self).sqrt()
    }

    #[inline]
    fn unit(self) -> Vec4 {
        self * self.norm().recip()
    }
}

impl Norm for Quat {
    #[inline]
    fn norm(self) -> f32 {
        Vec4::from(self).norm()
    }

    #[inline]
    fn unit(self) -> Quat {
        Quat::from_vec4(Vec4::from(self).unit())
    }
}

/// `Vec3::normalize_or_zero`.
#[inline]
pub fn unit_or_zero(v: Vec3) -> Vec3 {
    let rcp = v.norm().recip();
    if rcp.is_finite() && rcp > 0.0 {
        v * rcp
    } else {
        Vec3::ZERO
    }
}

/// `Vec3::try_normalize`.
#[inline]
pub fn try_unit(v: Vec3) -> Option<Vec3> {
    let rcp = v.norm().recip();
    (rcp.is_finite() && rcp > 0.0).then(|| v * rcp)
}

/// `Vec3::distance`.
#[inline]
pub fn distance(a: Vec3, b: Vec3) -> f32 {
    (a - b).norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn bits(v: &[f32]) -> Vec<u32> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    proptest! {
        /// Bit for bit what glam (through libm) gives, over magnitudes from
        /// 1e-20 to 1e20 and the zero vector.
        #[test]
        fn the_same_bits_as_glam(
            x in -1.0f32..1.0, y in -1.0f32..1.0, z in -1.0f32..1.0, w in -1.0f32..1.0,
            exponent in -20i32..20, zero in proptest::bool::weighted(0.05),
        ) {
            let scale = if zero { 0.0 } else { 10f32.powi(exponent) };
            let v = Vec3::new(x, y, z) * scale;
            prop_assert_eq!(v.norm().to_bits(), v.length().to_bits());
            prop_assert_eq!(bits(&v.unit().to_array()), bits(&v.normalize().to_array()));
            prop_assert_eq!(bits(&unit_or_zero(v).to_array()), bits(&v.normalize_or_zero().to_array()));
            prop_assert_eq!(try_unit(v).map(|u| bits(&u.to_array())), v.try_normalize().map(|u| bits(&u.to_array())));
            let u = Vec3::new(z, x, y);
            prop_assert_eq!(distance(v, u).to_bits(), v.distance(u).to_bits());
            let q = Quat::from_xyzw(x, y, z, w);
            prop_assert_eq!(q.norm().to_bits(), q.length().to_bits());
            prop_assert_eq!(bits(&q.unit().to_array()), bits(&q.normalize().to_array()));
        }
    }
}
