//! Mass properties of a balloon from its parts: a thin latex shell spread
//! evenly over the mesh's surface, a knot (a small solid ball), and the gas
//! filling the enclosed volume. Each part contributes its mass, first moment
//! and second moment `∫ x xᵀ dm` about the mesh origin; the sums give the
//! centre of mass and, by the parallel axis theorem, the inertia tensor about
//! it (full 3×3). Sums run in f64.

use glam::{DMat3, DVec3, Mat3, Vec3};
use up_geom::fit::mesh_integrals::{ShellIntegrals, SolidIntegrals};

/// Mass, centre of mass and inertia of a rigid body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    /// kg.
    pub mass: f32,
    /// m, body frame.
    pub center_of_mass: Vec3,
    /// kg·m², about the centre of mass, body axes.
    pub inertia: Mat3,
}

/// Zeroth, first and second moments of a mass distribution about the origin.
#[derive(Clone, Copy, Debug, Default)]
pub struct Moments {
    mass: f64,
    first: DVec3,
    second: DMat3,
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

impl Moments {
    /// A thin shell of total `mass` (kg) spread evenly over a surface.
    pub fn shell(surface: &ShellIntegrals, mass: f32) -> Self {
        let sigma = f64::from(mass) / f64::from(surface.area).max(f64::MIN_POSITIVE);
        Self {
            mass: f64::from(mass),
            first: surface.centroid.as_dvec3() * f64::from(mass),
            second: surface.second_moment.as_dmat3() * sigma,
        }
    }

    /// A latex envelope of total `mass` (kg) over a surface of revolution about
    /// +Y, thinner where it is stretched more. Rubber keeps its volume as it
    /// stretches, so its mass per area falls as 1/(area stretch). Stretch is
    /// taken as circumferential, r / r₀ in both directions, where `r` is the
    /// distance from the axis and `r₀` (m) the radius of the deflated
    /// balloon's tube (no stretch where r ≤ r₀: the neck). The neck and the
    /// lower body so hold far more latex per area than the thin top, which
    /// puts the centre of mass well below the centre of buoyancy: what keeps a
    /// real balloon knot-down, even when pressed against a ceiling.
    pub fn stretched_shell(
        vertices: &[Vec3],
        triangles: &[[u32; 3]],
        mass: f32,
        unstretched_radius: f32,
    ) -> Self {
        let r0 = f64::from(unstretched_radius).max(1e-6);
        let mut weight = 0.0f64;
        let mut first = DVec3::ZERO;
        let mut second = DMat3::ZERO;
        for t in triangles {
            let [a, b, c] = t.map(|i| vertices[i as usize].as_dvec3());
            let area = 0.5 * (b - a).cross(c - a).length();
            let s = a + b + c;
            let centroid = s / 3.0;
            let r = (centroid.x * centroid.x + centroid.z * centroid.z).sqrt();
            let stretch = (r / r0).max(1.0);
            let w = area / (stretch * stretch);
            weight += w;
            first += centroid * w;
            // ∫ x xᵀ dA over a triangle = A/12 · (Σ vᵢ vᵢᵀ + s sᵀ).
            let m = outer(a, a) + outer(b, b) + outer(c, c) + outer(s, s);
            second += m * (w / 12.0);
        }
        let scale = f64::from(mass) / weight.max(f64::MIN_POSITIVE);
        Self {
            mass: f64::from(mass),
            first: first * scale,
            second: second * scale,
        }
    }

    /// A uniform solid of `density` (kg/m³) filling a closed volume.
    pub fn solid(solid: &SolidIntegrals, density: f32) -> Self {
        let mass = f64::from(solid.volume) * f64::from(density);
        Self {
            mass,
            first: solid.centroid.as_dvec3() * mass,
            second: solid.second_moment.as_dmat3() * f64::from(density),
        }
    }

    /// A solid ball of `mass` (kg) and `radius` (m) centred at `center`.
    pub fn ball(center: Vec3, radius: f32, mass: f32) -> Self {
        let (m, c, r) = (f64::from(mass), center.as_dvec3(), f64::from(radius));
        // About its own centre ∫ x xᵀ dm = m r²/5 · I (inertia 2/5 m r²).
        Self {
            mass: m,
            first: c * m,
            second: outer(c, c) * m + DMat3::IDENTITY * (m * r * r / 5.0),
        }
    }

    /// kg.
    pub fn mass(&self) -> f32 {
        self.mass as f32
    }

    /// Centre of mass, and inertia about it (parallel axis theorem).
    pub fn properties(&self) -> MassProperties {
        if self.mass <= 0.0 {
            return MassProperties {
                mass: 0.0,
                center_of_mass: Vec3::ZERO,
                inertia: Mat3::ZERO,
            };
        }
        let c = self.first / self.mass;
        let s = self.second - outer(c, c) * self.mass;
        let trace = s.x_axis.x + s.y_axis.y + s.z_axis.z;
        let inertia = DMat3::IDENTITY * trace - s;
        MassProperties {
            mass: self.mass as f32,
            center_of_mass: c.as_vec3(),
            inertia: inertia.as_mat3(),
        }
    }
}

impl std::ops::Add for Moments {
    type Output = Moments;

    fn add(self, other: Moments) -> Moments {
        Moments {
            mass: self.mass + other.mass,
            first: self.first + other.first,
            second: self.second + other.second,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::balloon::mesh::BalloonMesh;
    use up_geom::fit::mesh_integrals::{shell_integrals, solid_integrals};

    /// A fine UV sphere, wound outward.
    fn sphere(radius: f32, center: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let (rings, segments) = (64u32, 96u32);
        let mut v = vec![center + Vec3::Y * radius];
        for i in 1..rings {
            let polar = std::f32::consts::PI * i as f32 / rings as f32;
            for j in 0..segments {
                let a = std::f32::consts::TAU * j as f32 / segments as f32;
                let dir = Vec3::new(polar.sin() * a.cos(), polar.cos(), -polar.sin() * a.sin());
                v.push(center + dir * radius);
            }
        }
        let bottom = v.len() as u32;
        v.push(center - Vec3::Y * radius);
        let ring = |i: u32, j: u32| 1 + i * segments + j % segments;
        let mut t = Vec::new();
        for j in 0..segments {
            t.push([0, ring(0, j), ring(0, j + 1)]);
            t.push([bottom, ring(rings - 2, j + 1), ring(rings - 2, j)]);
        }
        for i in 0..rings - 2 {
            for j in 0..segments {
                t.push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
                t.push([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
            }
        }
        (v, t)
    }

    #[test]
    fn shell_and_solid_spheres_match_textbook_inertia() {
        let (r, c) = (0.5, Vec3::new(1.0, 2.0, -1.0));
        let (v, t) = sphere(r, c);
        let shell = Moments::shell(&shell_integrals(&v, &t), 2.0).properties();
        // Thin spherical shell: 2/3 m r².
        let expected = 2.0 / 3.0 * 2.0 * r * r;
        assert!(shell.center_of_mass.distance(c) < 1e-4);
        assert!(
            (shell.inertia.x_axis.x / expected - 1.0).abs() < 2e-3,
            "{}",
            shell.inertia
        );
        assert!(shell.inertia.x_axis.y.abs() < 1e-4 * expected);
        // Solid ball of density 3: 2/5 m r² with m = ρ V.
        let solid = Moments::solid(&solid_integrals(&v, &t), 3.0).properties();
        let m = 3.0 * 4.0 / 3.0 * std::f32::consts::PI * r * r * r;
        assert!((solid.mass / m - 1.0).abs() < 3e-3);
        let expected = 0.4 * solid.mass * r * r;
        assert!(
            (solid.inertia.y_axis.y / expected - 1.0).abs() < 3e-3,
            "{}",
            solid.inertia
        );
    }

    #[test]
    fn parallel_axis_theorem_for_two_balls() {
        let a = Moments::ball(Vec3::new(-1.0, 0.0, 0.0), 0.1, 1.0);
        let b = Moments::ball(Vec3::new(1.0, 0.0, 0.0), 0.1, 1.0);
        let p = (a + b).properties();
        assert_eq!(p.center_of_mass, Vec3::ZERO);
        let own = 0.4 * 0.01;
        assert!((p.inertia.x_axis.x - 2.0 * own).abs() < 1e-6);
        assert!((p.inertia.y_axis.y - (2.0 * own + 2.0)).abs() < 1e-6);
        assert!((p.inertia.z_axis.z - (2.0 * own + 2.0)).abs() < 1e-6);
    }

    #[test]
    fn balloon_inertia_is_symmetric_about_its_axis() {
        let mesh = BalloonMesh::new(0.28).unwrap();
        let shell = shell_integrals(&mesh.positions, &mesh.indices);
        let p = Moments::shell(&shell, 0.003).properties();
        let i = p.inertia;
        assert!((i.x_axis.x - i.z_axis.z).abs() < 1e-3 * i.x_axis.x, "{i}");
        assert!(i.x_axis.y.abs() < 1e-4 * i.x_axis.x && i.y_axis.z.abs() < 1e-4 * i.x_axis.x);
        assert!(p.center_of_mass.x.abs() < 1e-5 && p.center_of_mass.z.abs() < 1e-5);
    }
}
