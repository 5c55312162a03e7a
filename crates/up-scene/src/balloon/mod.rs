//! The balloon model: the procedural mesh, its fitted sphere tree and its
//! mass properties, packed into the `BalloonShape` the physics world takes.
//!
//! Mass comes from the parts (see `mass`): the latex envelope over
//! the mesh's surface, thicker where it is stretched less, the knot as a small ball at the bottom of the
//! neck, and the gas filling the mesh's volume at the room's temperature and
//! pressure. Buoyancy acts at the centroid of the volume; the knot pulls the
//! centre of mass below it, so a balloon floats upright.
//!
//! The default 11″ balloon (28 cm across, 14.1 L): envelope 3 g + knot 0.5 g +
//! helium 2.3 g ≈ 5.9 g, displaced air ≈ 17 g, free lift ≈ 11.1 g, terminal
//! ascent ≈ 1.75 m/s with C_D = 0.95 (physics reference: 5.4 g without the
//! knot, 11.7 g free lift, ≈ 1.7 m/s).
//!
//! A foil balloon (`EnvelopeKind::Foil`, `foil_mesh`) is a flat pillow on
//! edge: its film (9 g at 18″) spread evenly over the surface, its 1 g valve
//! a small ball at the bottom of the rim. 18″ holds 14.1 L: with 2.3 g of
//! helium it weighs 12.3 g against 17 g of air, 4.7 g of free lift (physics
//! reference: ≈ 4 g); the valve puts the centre of mass 2 cm below the
//! centre of buoyancy, so it floats upright.

pub mod foil_mesh;
pub mod foil_shape;
pub mod gas_fill;
mod local_width;
pub mod mass;
pub mod mesh;
pub mod outline;
pub mod report;
pub mod surface;

use glam::Vec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;
use up_geom::fit::mesh_integrals::{shell_integrals, solid_integrals};
use up_geom::fit::{FitError, FitReport, LeafRole, MAX_LEAVES};
use up_physics::gas::EnvelopeKind;
use up_physics::{Atmosphere, BalloonShape};

use foil_mesh::{foil_frontal_area, foil_mesh};
use foil_shape::foil_shape_balanced;
use mass::Moments;
use mesh::{BalloonMesh, BalloonMeshError};
pub use report::{CollidersReport, NodeReport};
use surface::{custom_frontal_area, fit_balloon_tree, is_flat, BalloonSurface, CustomMeshError};

/// Radius of a deflated balloon's latex tube as a share of the inflated
/// diameter: ≈ 2.5 cm for an 11″ (28 cm) balloon, whose flat deflated body is
/// about 8 cm wide (an estimate). Sets how much thinner the stretched top is
/// than the neck; see `Moments::stretched_shell`.
pub const UNSTRETCHED_RADIUS_FRACTION: f32 = 0.09;

/// Density of natural rubber latex, kg/m³ (0.92–0.96 g/cm³): used only to
/// report the envelope thickness its mass implies.
pub const LATEX_DENSITY: f32 = 930.0;

/// What fills the balloon.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Gas {
    /// Lighter than air: the balloon rises.
    #[default]
    Helium,
    /// Blown up by mouth (ignoring the breath's CO₂ and moisture): it sinks.
    Air,
}

/// A kind of balloon.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BalloonSpec {
    /// Latex (the default) or foil: the shape and how its mass is spread.
    pub kind: EnvelopeKind,
    /// m: widest diameter; 0.28 for an 11″ latex balloon, 0.457 for an 18″ foil.
    pub diameter_m: f32,
    /// kg: the envelope; 0.003 for 11″ latex (retail charts: 2–3 g), 0.009 for 18″ foil.
    pub envelope_mass_kg: f32,
    /// kg: the tied knot and neck, 0.0005 (a guess: no measurement found); a
    /// foil's valve, 0.001 (an estimate).
    pub knot_mass_kg: f32,
    pub gas: Gas,
}

impl Default for BalloonSpec {
    fn default() -> Self {
        Self {
            kind: EnvelopeKind::Latex,
            diameter_m: 0.28,
            envelope_mass_kg: 0.003,
            knot_mass_kg: 0.0005,
            gas: Gas::Helium,
        }
    }
}

#[derive(Debug, Error, PartialEq)]
pub enum BalloonError {
    #[error("balloon {key}: expected {expected}, got {value}")]
    BadSpec {
        key: &'static str,
        value: f32,
        expected: &'static str,
    },
    #[error("balloon leaves: expected 1 to {MAX_LEAVES}, got {0}")]
    BadLeaves(usize),
    #[error("balloon air: {0}")]
    BadAtmosphere(String),
    #[error(transparent)]
    Mesh(#[from] BalloonMeshError),
    #[error("balloon sphere tree: {0}")]
    Fit(#[from] FitError),
    #[error("balloon mesh {0}")]
    Custom(#[from] CustomMeshError),
}

/// Masses of the parts, kg.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MassBreakdown {
    pub envelope_kg: f32,
    pub knot_kg: f32,
    pub gas_kg: f32,
}

/// Everything known about one kind of balloon.
#[derive(Clone, Debug)]
pub struct BalloonModel {
    pub spec: BalloonSpec,
    /// Body frame: see `balloon_mesh`.
    pub mesh: BalloonMesh,
    /// What the physics world takes.
    pub shape: BalloonShape,
    /// The fitted tree (also in `shape.tree`) and its quality.
    pub fit: FitReport,
    /// m²: the envelope's surface area; ≈ 0.289 for 11″.
    pub envelope_area_m2: f32,
    /// m, body frame: the centroid of the envelope's surface.
    pub envelope_centroid: Vec3,
    pub parts: MassBreakdown,
    /// kg/m³ of the room's air when the model was built; 1.204 at 20 °C.
    pub air_density: f32,
    /// Whether the surface is drawn from `mesh` (foil balloons and meshes of
    /// one's own) rather than the page's latex model.
    pub drawn_from_mesh: bool,
}

impl BalloonModel {
    /// kg of air the balloon displaces; ≈ 0.017 for 11″.
    pub fn displaced_air_kg(&self) -> f32 {
        self.air_density * self.shape.volume
    }

    /// kg: displaced air minus the whole balloon (negative when it sinks).
    pub fn free_lift_kg(&self) -> f32 {
        self.displaced_air_kg() - self.shape.mass
    }

    /// m: the envelope's mean thickness if it were latex of `LATEX_DENSITY`.
    pub fn envelope_thickness_m(&self) -> f32 {
        self.parts.envelope_kg / (LATEX_DENSITY * self.envelope_area_m2)
    }

    /// m/s: steady vertical speed in still air, `sqrt(2 g |ρV − m| / (ρ C_D A))`,
    /// positive rising, negative sinking. `gravity` in m/s² (9.81),
    /// `drag_coefficient` dimensionless (0.95 for a rising balloon).
    pub fn terminal_velocity(&self, gravity: f32, drag_coefficient: f32) -> f32 {
        let lift = self.free_lift_kg();
        let denominator = self.air_density * drag_coefficient * self.shape.reference_area;
        if denominator <= 0.0 {
            return 0.0;
        }
        (2.0 * gravity * lift.abs() / denominator).sqrt() * lift.signum()
    }

    /// m, body frame: where the net lift acts — buoyancy `ρ_air·V` at the
    /// centre of buoyancy and the weight `m` at the centre of mass, combined
    /// into one upward force. None when the balloon does not rise.
    pub fn lift_centre(&self) -> Option<Vec3> {
        let buoyancy = self.displaced_air_kg();
        let lift = self.free_lift_kg();
        (lift > 0.0).then(|| {
            (self.shape.center_of_buoyancy * buoyancy - self.shape.center_of_mass * self.shape.mass)
                / lift
        })
    }

    /// m: how far the lift centre lies above the centre of the head sphere
    /// (−0.008 for the default 11″ balloon). Pressed against a flat ceiling,
    /// a balloon rocks on its head sphere like a weeble turned over: the
    /// contact force acts through the sphere's centre and the lift through the
    /// lift centre, so upright is stable only when this margin is positive.
    /// Free in the air the balloon always rights itself; this is the much
    /// weaker preference left once the ceiling carries the lift.
    pub fn ceiling_upright_margin_m(&self) -> Option<f32> {
        let head = self.fit.roles.iter().position(|&r| r == LeafRole::Head)?;
        let leaf = self.shape.tree.leaves()[head] as usize;
        let head_centre = self.shape.tree.nodes()[leaf].center;
        Some(self.lift_centre()?.y - head_centre.y)
    }

    /// The sphere tree and mass properties, for `up colliders`.
    pub fn colliders_report(&self) -> CollidersReport {
        CollidersReport::new(self)
    }
}

fn check(
    key: &'static str,
    value: f32,
    ok: bool,
    expected: &'static str,
) -> Result<(), BalloonError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(BalloonError::BadSpec {
            key,
            value,
            expected,
        })
    }
}

/// Builds the mesh, fits `leaves` collision spheres (5: the report's head,
/// neck and three fillers) and computes the mass properties, with gas
/// densities from `atmosphere`.
pub fn build_balloon(
    spec: &BalloonSpec,
    atmosphere: &Atmosphere,
    leaves: usize,
) -> Result<BalloonModel, BalloonError> {
    build_balloon_with(spec, &BalloonSurface::Standard, atmosphere, leaves)
}

/// `build_balloon` on `surface`. A flat surface (a foil pillow, heart, star
/// or digit, a flat mesh of one's own) is fitted over its mid-surface with
/// `FLAT_LEAVES` leaves; the rest along their axis with `leaves`.
pub fn build_balloon_with(
    spec: &BalloonSpec,
    surface: &BalloonSurface,
    atmosphere: &Atmosphere,
    leaves: usize,
) -> Result<BalloonModel, BalloonError> {
    let d = spec.diameter_m;
    check(
        "diameter_m",
        d,
        (0.02..=5.0).contains(&d),
        "metres in 0.02..=5",
    )?;
    let e = spec.envelope_mass_kg;
    check(
        "envelope_mass_kg",
        e,
        e > 0.0 && e <= 10.0,
        "kilograms in (0, 10]",
    )?;
    let k = spec.knot_mass_kg;
    check(
        "knot_mass_kg",
        k,
        (0.0..=10.0).contains(&k),
        "kilograms in 0..=10",
    )?;
    if !(1..=MAX_LEAVES).contains(&leaves) {
        return Err(BalloonError::BadLeaves(leaves));
    }
    let (air_density, helium_density) = (atmosphere.air_density(), atmosphere.helium_density());
    if !(air_density.is_finite() && air_density > 0.0 && helium_density.is_finite()) {
        return Err(BalloonError::BadAtmosphere(format!(
            "temperature {} K and pressure {} Pa give no usable air density",
            atmosphere.temperature_k, atmosphere.pressure_pa
        )));
    }
    let gas_density = match spec.gas {
        Gas::Helium => helium_density,
        Gas::Air => air_density,
    };

    let (mesh, outline_frontal) = match (surface, spec.kind) {
        (BalloonSurface::Standard, EnvelopeKind::Latex) => (BalloonMesh::new(d)?, None),
        (BalloonSurface::Standard, EnvelopeKind::Foil) => (foil_mesh(d)?, None),
        (BalloonSurface::FoilOutline(kind), _) => {
            // The valve where it hangs the film's weight below the centre
            // of buoyancy (a weightless valve can balance nothing).
            let film_per_valve = if k > 0.0 { e / k } else { 0.0 };
            let shape = foil_shape_balanced(*kind, d, film_per_valve)?;
            (shape.mesh, Some(shape.frontal_area_m2))
        }
        (BalloonSurface::Custom { mesh, .. }, _) => (mesh.clone(), None),
    };
    let custom = matches!(surface, BalloonSurface::Custom { .. });
    let flat = match surface {
        // The pillow is flat too (over its face: tightness 1.32, where
        // along its axis it is 3.85); the latex balloon is round.
        BalloonSurface::Standard => spec.kind == EnvelopeKind::Foil,
        BalloonSurface::FoilOutline(_) => true,
        BalloonSurface::Custom { .. } => is_flat(&mesh.positions, &mesh.indices),
    };
    let solid = solid_integrals(&mesh.positions, &mesh.indices);
    let shell = shell_integrals(&mesh.positions, &mesh.indices);
    let knot = mesh.dimensions.knot_center;
    let gas = Moments::solid(&solid, gas_density);
    let envelope = match spec.kind {
        EnvelopeKind::Latex if !custom => Moments::stretched_shell(
            &mesh.positions,
            &mesh.indices,
            e,
            UNSTRETCHED_RADIUS_FRACTION * d,
        ),
        // The film hardly stretches (and a mesh of one's own says nothing of
        // its stretch): the same mass on every square metre.
        _ => Moments::shell(&shell, e),
    };
    let moments = envelope + Moments::ball(knot, mesh.dimensions.knot_radius, k) + gas;
    let mass = moments.properties();
    let fit = fit_balloon_tree(&mesh.positions, &mesh.indices, flat, leaves)?;
    // Frontal area for drag: the largest horizontal cross-section, π r_max²
    // for latex (round about Y); the pillow's section through its centre.
    let reference_area = match (outline_frontal, spec.kind) {
        (Some(area), _) => area,
        _ if custom => custom_frontal_area(&mesh),
        (None, EnvelopeKind::Latex) => {
            let r_max = mesh
                .positions
                .iter()
                .map(|p| Vec3::new(p.x, 0.0, p.z).length())
                .fold(0.0, f32::max);
            std::f32::consts::PI * r_max * r_max
        }
        (None, EnvelopeKind::Foil) => foil_frontal_area(&mesh),
    };
    let shape = BalloonShape {
        tree: fit.tree.clone(),
        mass: mass.mass,
        center_of_mass: mass.center_of_mass,
        inertia: mass.inertia,
        volume: solid.volume,
        center_of_buoyancy: solid.centroid,
        reference_area,
    };
    Ok(BalloonModel {
        spec: *spec,
        mesh,
        shape,
        fit,
        envelope_area_m2: shell.area,
        envelope_centroid: shell.centroid,
        parts: MassBreakdown {
            envelope_kg: e,
            knot_kg: k,
            gas_kg: gas.mass(),
        },
        air_density,
        drawn_from_mesh: custom || spec.kind == EnvelopeKind::Foil,
    })
}

#[cfg(test)]
mod tests;
