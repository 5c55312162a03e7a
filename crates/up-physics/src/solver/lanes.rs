//! Four-lane vectors for the wide contact solve: SSE2 natively, simd128 in
//! WebAssembly when built with it, plain arrays otherwise (`wide`).
//!
//! Every operation here is the same IEEE operation, in the same order, as
//! glam's scalar code for one lane (no fused multiply-add, no reassociation),
//! so a lane computes bit for bit what the scalar solve did, on every
//! platform: the determinism across native and WebAssembly holds.

use std::ops::{Add, Mul, Neg, Sub};

use glam::Vec3;
pub(crate) use wide::f32x4 as F4;

/// Constraints solved at once.
pub(crate) const LANES: usize = 4;

/// Lane-wise `if mask { a } else { b }` for a mask from a comparison.
#[inline]
pub(crate) fn select(mask: F4, a: F4, b: F4) -> F4 {
    mask.select(a, b)
}

/// `a.max(b)` for numbers (not NaN), with the same result in every lane on
/// every platform (the platforms' own max instructions disagree on ±0).
#[inline]
pub(crate) fn max(a: F4, b: F4) -> F4 {
    select(a.simd_gt(b), a, b)
}

/// Three lanes of vectors, one per axis.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct V4 {
    pub x: F4,
    pub y: F4,
    pub z: F4,
}

impl V4 {
    pub const ZERO: V4 = V4::new(F4::ZERO, F4::ZERO, F4::ZERO);

    #[inline]
    pub const fn new(x: F4, y: F4, z: F4) -> V4 {
        V4 { x, y, z }
    }

    #[cfg(test)]
    #[inline]
    pub fn from_lanes(v: [Vec3; LANES]) -> V4 {
        V4 {
            x: F4::new([v[0].x, v[1].x, v[2].x, v[3].x]),
            y: F4::new([v[0].y, v[1].y, v[2].y, v[3].y]),
            z: F4::new([v[0].z, v[1].z, v[2].z, v[3].z]),
        }
    }

    /// `v` in every lane.
    #[inline]
    pub fn splat(v: Vec3) -> V4 {
        V4::new(F4::splat(v.x), F4::splat(v.y), F4::splat(v.z))
    }

    #[inline]
    pub fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(
            self.x.as_array()[i],
            self.y.as_array()[i],
            self.z.as_array()[i],
        )
    }

    #[inline]
    pub fn set_lane(&mut self, i: usize, v: Vec3) {
        set(&mut self.x, i, v.x);
        set(&mut self.y, i, v.y);
        set(&mut self.z, i, v.z);
    }

    #[inline]
    pub fn dot(self, o: V4) -> F4 {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }

    #[inline]
    pub fn cross(self, o: V4) -> V4 {
        V4 {
            x: self.y * o.z - o.y * self.z,
            y: self.z * o.x - o.z * self.x,
            z: self.x * o.y - o.x * self.y,
        }
    }

    /// `self` where `mask` is set, `other` elsewhere.
    #[inline]
    pub fn select(mask: F4, a: V4, b: V4) -> V4 {
        V4 {
            x: select(mask, a.x, b.x),
            y: select(mask, a.y, b.y),
            z: select(mask, a.z, b.z),
        }
    }
}

/// Asks for `data` to be brought into the cache ahead of its use, a line
/// at a time (x86-64; a hint that changes no result, left out elsewhere).
#[inline]
pub(crate) fn prefetch<T>(data: &[T]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let base = data.as_ptr().cast::<i8>();
        for offset in (0..std::mem::size_of_val(data)).step_by(64) {
            // SAFETY: a prefetch is a hint: it reads nothing into the
            // program and faults on no address; SSE is part of x86-64.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(base.wrapping_add(offset)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = data;
}

/// Writes one lane of `x`.
#[inline]
pub(crate) fn set(x: &mut F4, i: usize, value: f32) {
    x.as_mut_array()[i] = value;
}

impl Add for V4 {
    type Output = V4;
    #[inline]
    fn add(self, o: V4) -> V4 {
        V4 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl Sub for V4 {
    type Output = V4;
    #[inline]
    fn sub(self, o: V4) -> V4 {
        V4 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

impl Neg for V4 {
    type Output = V4;
    #[inline]
    fn neg(self) -> V4 {
        V4 {
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }
}

/// Scalar lanes times vector lanes.
impl Mul<V4> for F4 {
    type Output = V4;
    #[inline]
    fn mul(self, v: V4) -> V4 {
        V4 {
            x: self * v.x,
            y: self * v.y,
            z: self * v.z,
        }
    }
}

/// Four 3×3 matrices, column by column (glam's `Mat3` layout).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct M4 {
    pub x_axis: V4,
    pub y_axis: V4,
    pub z_axis: V4,
}

impl M4 {
    pub const ZERO: M4 = M4 {
        x_axis: V4::ZERO,
        y_axis: V4::ZERO,
        z_axis: V4::ZERO,
    };

    #[cfg(test)]
    pub fn from_lanes(m: [&glam::Mat3; LANES]) -> M4 {
        M4 {
            x_axis: V4::from_lanes(m.map(|m| m.x_axis)),
            y_axis: V4::from_lanes(m.map(|m| m.y_axis)),
            z_axis: V4::from_lanes(m.map(|m| m.z_axis)),
        }
    }

    /// `Mat3 * Vec3` as glam computes it.
    #[inline]
    pub fn mul(&self, v: V4) -> V4 {
        let res = v.x * self.x_axis;
        let res = res + v.y * self.y_axis;
        res + v.z * self.z_axis
    }
}

/// Four rotations.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Q4 {
    pub xyz: V4,
    pub w: F4,
}

impl Q4 {
    pub const IDENTITY: Q4 = Q4 {
        xyz: V4::ZERO,
        w: F4::ONE,
    };

    #[cfg(test)]
    pub fn from_lanes(q: [glam::Quat; LANES]) -> Q4 {
        Q4 {
            xyz: V4::from_lanes(q.map(|q| Vec3::new(q.x, q.y, q.z))),
            w: F4::new(q.map(|q| q.w)),
        }
    }

    /// `Quat * Vec3` as glam computes it.
    #[inline]
    pub fn rotate(&self, v: V4) -> V4 {
        let (b, w) = (self.xyz, self.w);
        let b2 = b.dot(b);
        let two = F4::splat(2.0);
        ((w * w - b2) * v + (v.dot(b) * two) * b) + (w * two) * b.cross(v)
    }
}

#[cfg(test)]
mod tests {
    use glam::{Mat3, Quat};

    use super::*;

    fn lanes_of(f: impl Fn(usize) -> Vec3) -> [Vec3; LANES] {
        std::array::from_fn(f)
    }

    fn sample(i: usize) -> Vec3 {
        Vec3::new(
            0.3 + i as f32,
            -1.7 * i as f32 + 0.11,
            2.9 / (i as f32 + 1.3),
        )
    }

    #[test]
    fn every_lane_is_bit_identical_to_glam() {
        let a = lanes_of(sample);
        let b = lanes_of(|i| sample(i + 7) * 0.37);
        let m = Mat3::from_cols(sample(1), sample(2), sample(3)) * 0.01;
        let q = lanes_of(sample).map(|v| Quat::from_scaled_axis(v * 0.2));
        let (va, vb) = (V4::from_lanes(a), V4::from_lanes(b));
        let m4 = M4::from_lanes([&m; LANES]);
        let q4 = Q4::from_lanes(q);
        for i in 0..LANES {
            assert_eq!(va.dot(vb).to_array()[i].to_bits(), a[i].dot(b[i]).to_bits());
            assert_eq!(va.cross(vb).lane(i), a[i].cross(b[i]));
            assert_eq!(m4.mul(va).lane(i), m * a[i]);
            assert_eq!(q4.rotate(vb).lane(i), q[i] * b[i]);
            let m = max(va.x, vb.x).to_array()[i];
            assert_eq!(m, a[i].x.max(b[i].x));
        }
    }
}
