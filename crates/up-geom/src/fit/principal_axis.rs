//! The principal axis of a surface: the direction of largest spread of its
//! area (principal component analysis of the area-weighted covariance), found
//! with cyclic Jacobi rotations on the symmetric 3×3 matrix. Deterministic: a
//! fixed sweep order, and the sign chosen so the largest component is positive.

use glam::{DMat3, DVec3, Mat3, Vec3};

/// Eigenvalues and unit eigenvectors (columns) of a symmetric matrix, sorted
/// by decreasing eigenvalue.
pub fn symmetric_eigen(m: Mat3) -> ([f32; 3], [Vec3; 3]) {
    let mut a = [[0.0f64; 3]; 3];
    for (c, col) in [m.x_axis, m.y_axis, m.z_axis].iter().enumerate() {
        for (r, value) in col.to_array().iter().enumerate() {
            a[r][c] = f64::from(*value);
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0f64]];
    for _sweep in 0..32 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        let scale = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if off <= 1e-30 * scale.max(1e-300) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            // Rotation that zeroes a[p][q] (Golub & Van Loan, symmetric Schur).
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J: columns p and q, then rows p and q; V ← V J.
            for row in a.iter_mut().chain(v.iter_mut()) {
                let (xp, xq) = (row[p], row[q]);
                row[p] = c * xp - s * xq;
                row[q] = s * xp + c * xq;
            }
            let (rp, rq) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| c * rp[k] - s * rq[k]);
            a[q] = std::array::from_fn(|k| s * rp[k] + c * rq[k]);
        }
    }
    let mut order = [0usize, 1, 2];
    // Stable sort on the values: equal eigenvalues keep the x, y, z order.
    order.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]));
    let values = order.map(|i| a[i][i] as f32);
    let vectors = order.map(|i| DVec3::new(v[0][i], v[1][i], v[2][i]).normalize().as_vec3());
    (values, vectors)
}

/// The unit axis of largest spread of a covariance matrix, signed so that its
/// largest component is positive.
pub fn principal_axis(covariance: Mat3) -> Vec3 {
    let (_, vectors) = symmetric_eigen(covariance);
    // Round-off leaves components of ~1e-9 on a mesh built along a
    // coordinate axis: snap them to zero so fitted centres sit exactly on it.
    let axis = vectors[0];
    let axis = Vec3::select(axis.abs().cmplt(Vec3::splat(1e-6)), Vec3::ZERO, axis).normalize();
    let a = axis.abs();
    let largest = if a.x >= a.y && a.x >= a.z {
        axis.x
    } else if a.y >= a.z {
        axis.y
    } else {
        axis.z
    };
    if largest < 0.0 {
        -axis
    } else {
        axis
    }
}

/// Covariance `S/m − c cᵀ` from a second moment `S`, mass `m` and centroid `c`.
pub fn covariance(second_moment: Mat3, mass: f32, centroid: Vec3) -> Mat3 {
    let s = second_moment.as_dmat3() / f64::from(mass.max(f32::MIN_POSITIVE));
    let c = centroid.as_dvec3();
    (s - DMat3::from_cols(c * c.x, c * c.y, c * c.z)).as_mat3()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn eigen_of_a_rotated_diagonal_matrix() {
        let r = Mat3::from_quat(Quat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1));
        let d = Mat3::from_diagonal(Vec3::new(1.0, 5.0, 2.0));
        let m = r * d * r.transpose();
        let (values, vectors) = symmetric_eigen(m);
        assert!((values[0] - 5.0).abs() < 1e-4 && (values[1] - 2.0).abs() < 1e-4);
        assert!((values[2] - 1.0).abs() < 1e-4);
        assert!(vectors[0].dot(r.y_axis).abs() > 0.9999);
        assert!(vectors[2].dot(r.x_axis).abs() > 0.9999);
    }

    #[test]
    fn principal_axis_points_along_the_long_direction() {
        let m = Mat3::from_diagonal(Vec3::new(0.1, 0.2, 3.0));
        assert_eq!(principal_axis(m), Vec3::Z);
        let flipped = principal_axis(Mat3::from_diagonal(Vec3::new(0.1, 4.0, 0.2)));
        assert_eq!(flipped, Vec3::Y);
    }
}
