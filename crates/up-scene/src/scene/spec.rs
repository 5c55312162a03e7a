//! The scene's structs, one per section of the file (docs/scene-format.md):
//! the room, the groups of balloons and their ribbons, the air, the
//! simulation settings; and what follows from them (a group's diameter and
//! masses, the air at the start). Their defaults are in `defaults`, their
//! ranges in `validate`.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use super::{
    AboutSpec, DraughtSpec, FurnitureSpec, JetSpec, KeyLines, DEFAULT_DIAMETER_M,
    DEFAULT_ENVELOPE_MASS_G_11IN, DEFAULT_FOIL_DIAMETER_M, DEFAULT_FOIL_ENVELOPE_MASS_G_18IN,
    DEFAULT_FOIL_VALVE_MASS_G, DEFAULT_KNOT_MASS_G, METRES_PER_INCH,
};
use crate::error::SceneError;

/// A whole scene. `Scene::default()` is the original.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scene {
    pub room: RoomSpec,
    /// Groups of identical balloons (colours cycle within a group); at most 64.
    pub balloons: Vec<BalloonGroup>,
    pub air: AirSpec,
    /// Fans blowing round jets (`air_sources`); at most 64.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub fans: Vec<JetSpec>,
    /// Ceiling or wall vents: jets with a vent's defaults; at most 64.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub vents: Vec<JetSpec>,
    /// Open doors and windows the air moves through; at most 64.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub draughts: Vec<DraughtSpec>,
    /// Tables, chairs and meshes standing in the room (`furniture`); at most 64.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub furniture: Vec<FurnitureSpec>,
    pub sim: SimSpec,
    /// A title and caption for a page (`about`); optional.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub about: Option<AboutSpec>,
    /// Where the scene came from: for messages and for paths relative to the file.
    #[serde(skip)]
    pub source: SceneSource,
}

/// Where a scene was read from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneSource {
    /// The file name as given, or `<default scene>`.
    pub name: String,
    /// Directory that relative paths in the scene (`room.mesh`) start from.
    pub dir: Option<PathBuf>,
    /// Lines of the keys in the file, to point messages at them.
    pub lines: KeyLines,
}

/// The room: a box with a pyramidal or flat ceiling, or any closed OBJ mesh.
/// Origin at the centre of the floor, Y up.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RoomSpec {
    /// m, along x; 6. Range [0.5, 1000].
    pub width: f32,
    /// m, along z; 6. Range [0.5, 1000].
    pub depth: f32,
    /// m, floor to the top of the walls; 3. Range [0.5, 1000].
    pub wall_height: f32,
    /// `"pyramid"` (the original) or `"flat"`.
    pub ceiling: CeilingKind,
    /// m above the walls to the pyramid's apex; 1.5. Range (0, 1000]; pyramid only.
    pub apex_height: f32,
    /// A closed OBJ mesh to use instead of the box, relative to the scene file.
    /// Normals may point either way; the floor should be at y = 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
}

impl RoomSpec {
    /// Highest point of a box room, m (the apex for a pyramid).
    pub fn top(&self) -> f32 {
        match self.ceiling {
            CeilingKind::Pyramid => self.wall_height + self.apex_height,
            CeilingKind::Flat => self.wall_height,
        }
    }
}

#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CeilingKind {
    Pyramid,
    Flat,
}

#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GasKind {
    Helium,
    Air,
}

/// What a balloon is made of.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BalloonKind {
    /// A latex balloon: stretches with its gas, which leaks through it in hours.
    #[default]
    Latex,
    /// A round foil (metallised nylon) balloon: a flat pillow standing on
    /// edge, nearly inextensible, holding its gas for weeks.
    Foil,
}

/// How a balloon's surface is drawn: looks only, the physics does not read it.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Finish {
    /// Glossy latex: clearcoat over a slightly translucent, velvety body.
    Latex,
    /// Pearl latex: the same with a mother-of-pearl shimmer (iridescence).
    Pearl,
    /// Metal: a foil balloon's film, or a chrome latex balloon.
    Foil,
}

impl Finish {
    /// Every finish, in the order the page lists them.
    pub const ALL: [Finish; 3] = [Finish::Latex, Finish::Pearl, Finish::Foil];

    /// The name scene files use.
    pub fn name(self) -> &'static str {
        match self {
            Finish::Latex => "latex",
            Finish::Pearl => "pearl",
            Finish::Foil => "foil",
        }
    }
}

/// A sealant gel inside a latex balloon that slows its leak.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Treatment {
    /// `"none"`: bare latex.
    #[default]
    #[serde(rename = "none")]
    Untreated,
    /// `"hi-float"`: treated; helium leaks `up_physics::gas::envelope::HI_FLOAT_FACTOR` as fast.
    #[serde(rename = "hi-float")]
    HiFloat,
}

/// A group of identical balloons.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BalloonGroup {
    /// How many; 1. At most 200 000 over all groups.
    pub count: u64,
    /// `"latex"` or `"foil"`; latex.
    pub kind: BalloonKind,
    /// `"none"` or `"hi-float"` (latex only); none.
    pub treatment: Treatment,
    /// `"latex"`, `"pearl"` or `"foil"`: how the surface is drawn; the kind's
    /// own (`finish()`) when left out. A foil balloon is always `"foil"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finish: Option<Finish>,
    /// h: the balloons were filled this long before the run starts (their gas
    /// has been leaking since); 0. Range [0, 2000].
    pub filled_hours_before: f32,
    /// Colour names (`"red"`, ...) or `"#rrggbb"`, cycled over the group; the six
    /// originals. 1 to 64 of them.
    pub colors: Vec<String>,
    /// m, widest diameter of the inflated balloon; 0.28 (11″) for latex, 0.457
    /// (18″) for foil. Range [0.05, 5].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diameter_m: Option<f32>,
    /// The same in inches, as balloons are sold (11 → 0.2794 m); give one of the two.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size_in: Option<f32>,
    /// `"helium"` (rises) or `"air"` (falls slowly).
    pub gas: GasKind,
    /// g of envelope: latex, 3 for 11″; foil, 9 for 18″; scaled with the
    /// surface for other sizes. Range [0.01, 10000].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub envelope_mass_g: Option<f32>,
    /// g of knot and neck (latex; 0.5) or of valve (foil; 1). Range [0, 1000].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub knot_mass_g: Option<f32>,
    /// Where the balloons start. Left out: spread over the floor.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spawn: Option<SpawnBox>,
    /// m/s, initial velocity of every balloon of the group; 0. Speed at most 343 (sound).
    pub velocity: [f32; 3],
    /// rad/s, initial angular velocity (world frame); 0. At most 1000.
    pub angular_velocity: [f32; 3],
    /// Degrees: each balloon starts tilted from upright by a random angle up to this; 3.
    /// Range [0, 90].
    pub tilt_deg: f32,
    /// Degrees: and turned about the vertical by a random angle within ± this; 10.
    /// Range [0, 180].
    pub yaw_deg: f32,
    /// Leaf spheres of the fitted collision tree; 5 (the original's layout). Range 1..=32.
    pub leaves: u32,
    /// A ribbon tied to every balloon of the group. Left out, or `length_m = 0`: none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ribbon: Option<RibbonSpec>,
    /// `"round"`, `"pillow"`, `"heart"`, `"star"` or `"digit"` (`shapes`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shape: Option<super::shapes::BalloonShape>,
    /// `shape = "digit"`: the digit, `"0"` to `"9"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub text: Option<String>,
    /// A closed OBJ mesh (m, +Y up) instead of `shape`, beside the scene file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    /// m, the mesh's frame: where its ribbon ties; its lowest point if left out.
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "super::parse::point"
    )]
    pub knot: Option<[f32; 3]>,
}

impl BalloonGroup {
    /// m: `diameter_m`, else `size_in` converted, else 11″ (latex) or 18″ (foil).
    pub fn diameter(&self) -> f32 {
        match (self.diameter_m, self.size_in) {
            (Some(d), _) => d,
            (None, Some(inches)) => inches * METRES_PER_INCH,
            (None, None) => match self.kind {
                BalloonKind::Latex => DEFAULT_DIAMETER_M,
                BalloonKind::Foil => DEFAULT_FOIL_DIAMETER_M,
            },
        }
    }

    /// How the group is drawn: `finish` as given, else latex for a latex
    /// balloon and foil for a foil one.
    pub fn finish(&self) -> Finish {
        self.finish.unwrap_or(match self.kind {
            BalloonKind::Latex => Finish::Latex,
            BalloonKind::Foil => Finish::Foil,
        })
    }

    /// kg of envelope: as given, or the kind's default (3 g at 11″ latex,
    /// 9 g at 18″ foil) scaled by the surface.
    pub fn envelope_mass_kg(&self) -> f32 {
        let (grams, diameter) = match self.kind {
            BalloonKind::Latex => (DEFAULT_ENVELOPE_MASS_G_11IN, DEFAULT_DIAMETER_M),
            BalloonKind::Foil => (DEFAULT_FOIL_ENVELOPE_MASS_G_18IN, DEFAULT_FOIL_DIAMETER_M),
        };
        let scale = self.diameter() / diameter;
        self.envelope_mass_g.unwrap_or(grams * scale * scale) * 1e-3
    }

    /// kg of knot (latex) or valve (foil).
    pub fn knot_mass_kg(&self) -> f32 {
        let grams = match self.kind {
            BalloonKind::Latex => DEFAULT_KNOT_MASS_G,
            BalloonKind::Foil => DEFAULT_FOIL_VALVE_MASS_G,
        };
        self.knot_mass_g.unwrap_or(grams) * 1e-3
    }

    /// The group's ribbon, if it has one (a table with `length_m > 0`).
    pub fn tied_ribbon(&self) -> Option<&RibbonSpec> {
        self.ribbon.as_ref().filter(|r| r.length_m > 0.0)
    }
}

/// A ribbon tied to each balloon of a group, at its knot, hanging from it;
/// a weight at the free end if `weight_g > 0`; its free end tied to a fixed
/// point if `anchor` is given.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RibbonSpec {
    /// m; 1.5. Range [0, 20]; 0: no ribbon.
    pub length_m: f32,
    /// g per metre; 0.25 (an estimate). Range (0, 1000].
    pub mass_per_m_g: f32,
    /// Straight segments the ribbon is simulated as; 16. Range [2, 128].
    pub segments: u32,
    /// A colour name (`"white"`, ...) or `"#rrggbb"`; white.
    pub color: String,
    /// g: a balloon weight tied to the free end; 0 (none). Range [0, 1000].
    pub weight_g: f32,
    /// m, world frame: the free end is tied to this fixed point (a chair's
    /// back, a table leg), so each balloon floats at most `length_m` from it.
    /// Left out: the end hangs free. Inside the room; needs `length_m > 0`.
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "super::parse::point"
    )]
    pub anchor: Option<[f32; 3]>,
}

/// A box the balloons of a group fill, m, world frame.
///
/// Balloons (their bounding spheres) are laid out inside it layer by layer
/// from `min.y` upward, spread out over its x–z extent; a group too large for
/// the box stacks further layers above `max.y`, up to the ceiling.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpawnBox {
    pub min: [f32; 3],
    pub max: [f32; 3],
}

/// The room's air: densities for buoyancy, drag and added mass follow (ideal gas).
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AirSpec {
    /// °C at the start (and throughout, without a schedule); 20. Range [−60, 60].
    /// With a schedule: its first point's temperature (left out, or the same).
    pub temperature_c: f32,
    /// kPa; 101.325 (sea level). Range [50, 150].
    pub pressure_kpa: f32,
    /// `[hours from the start, °C]` pairs, hours ≥ 0 and increasing, °C in
    /// [−60, 60]; linear between points, held before the first and after the
    /// last. Left out or empty: `temperature_c` throughout.
    #[serde(
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "super::parse::pairs"
    )]
    pub temperature_schedule: Vec<[f32; 2]>,
}

impl AirSpec {
    /// °C at the start: the schedule's first point, else `temperature_c`.
    pub fn start_temperature_c(&self) -> f32 {
        self.temperature_schedule
            .first()
            .map_or(self.temperature_c, |p| p[1])
    }

    /// The air at the start: the balloons are filled in it.
    pub fn atmosphere(&self) -> up_physics::Atmosphere {
        up_physics::Atmosphere {
            temperature_k: self.start_temperature_c() + 273.15,
            pressure_pa: self.pressure_kpa * 1000.0,
        }
    }

    /// The schedule as the engine takes it: (s, K) points; empty without one.
    pub fn temperature_schedule(&self) -> up_physics::gas::TemperatureSchedule {
        up_physics::gas::TemperatureSchedule {
            points: self
                .temperature_schedule
                .iter()
                .map(|&[hours, celsius]| (f64::from(hours) * 3600.0, celsius + 273.15))
                .collect(),
        }
    }
}

/// Simulation settings. Defaults match `up_physics::WorldDef::default()`.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SimSpec {
    /// Seed of the spawn layout (positions, tilts); 1. Range 0..=2⁵³−1 (exact in JavaScript).
    pub seed: u64,
    /// s per step; 1/60. Range (0, 0.1].
    pub dt: f32,
    /// Solver substeps per step; 4. Range 1..=64.
    pub substeps: u32,
    /// s simulated by `up run` when `--seconds` is not given; 10. Range (0, 86400].
    pub duration_s: f32,
    /// m/s²; [0, −9.81, 0]. Each component within ±1000.
    pub gravity: [f32; 3],
    /// Coulomb friction coefficient; 0.5. Range [0, 10].
    pub friction: f32,
    /// Coefficient of restitution; 0.4. Range [0, 1].
    pub restitution: f32,
    /// Drag coefficient C_D; 0.95. Range [0, 10].
    pub drag_coefficient: f32,
    /// Added-mass coefficient C_a; 0.5 (sphere). Range [0, 10].
    pub added_mass_coefficient: f32,
    /// Rotational air drag, 1/s; 2. Range [0, 1000].
    pub angular_damping: f32,
    /// Contact stiffness, Hz; 60. Range (0, 10000].
    pub contact_hertz: f32,
    /// Contact damping ratio; 10. Range [0, 1000].
    pub contact_damping_ratio: f32,
    /// Let settled balloons sleep; true.
    pub sleep: bool,
    /// Sweep fast balloons against the room (time of impact); true.
    pub continuous: bool,
    /// Ribbons touch each other (no ribbon passes through another); false.
    pub ribbon_contacts: bool,
    /// Friction of a ribbon on a ribbon; 0.4 (a guess). Range [0, 10].
    pub ribbon_friction: f32,
}

impl PartialEq for Scene {
    /// Same content; where it was read from does not matter.
    fn eq(&self, other: &Self) -> bool {
        self.room == other.room
            && self.balloons == other.balloons
            && self.air == other.air
            && self.fans == other.fans
            && self.vents == other.vents
            && self.draughts == other.draughts
            && self.furniture == other.furniture
            && self.sim == other.sim
    }
}

impl Scene {
    /// Balloons over all groups.
    pub fn total_balloons(&self) -> u64 {
        self.balloons.iter().map(|g| g.count).sum()
    }

    /// Sets the total number of balloons (the CLI's `--balloons N`), spread
    /// over the groups in order: each gets `N / groups`, the first ones one
    /// more until the remainder is used up. A scene with no group gets one
    /// default group. Validates the result.
    pub fn with_total_balloons(mut self, total: u64) -> Result<Scene, SceneError> {
        if self.balloons.is_empty() {
            self.balloons.push(BalloonGroup::default());
        }
        let groups = self.balloons.len() as u64;
        for (i, group) in self.balloons.iter_mut().enumerate() {
            group.count = total / groups + u64::from((i as u64) < total % groups);
        }
        self.validate()?;
        Ok(self)
    }
}
