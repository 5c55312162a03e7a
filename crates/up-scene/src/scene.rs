//! Scene files: the room, groups of balloons, the air and the simulation
//! settings, in TOML or JSON with one schema (docs/scene-format.md).
//!
//! Every section and every key may be left out and takes its default; the
//! defaults are the original project's scene: a 6 m × 6 m room with 3 m walls
//! and a pyramidal ceiling, 50 balloons in six colours released from the floor,
//! each on a 1.5 m ribbon.
//! Unknown keys are errors, and so is a file of nothing but whitespace (what a
//! failed write leaves). After parsing, `validate` checks every number is
//! finite and within its documented range; errors name the file, the key path
//! and the line. The key path of a parse error is serde's own
//! (`serde_path_to_error`), its line the parser's.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::{Location, SceneError};
use crate::palette::{color_rgb, DEFAULT_COLOR_COUNT, PALETTE};

#[path = "scene_about.rs"]
mod about;
#[path = "scene_lines.rs"]
mod lines;
#[path = "scene_validate.rs"]
mod validate;

pub use about::{AboutSpec, MAX_CAPTION_CHARS, MAX_TITLE_CHARS};
pub use lines::KeyLines;
pub use validate::{
    MAX_BALLOON_DIAMETER_M, MAX_BALLOON_GROUPS, MAX_GROUP_COLORS, MAX_RIBBON_LENGTH_M,
    MAX_RIBBON_MASS_PER_M_G, MAX_RIBBON_WEIGHT_G, MAX_ROOM_SIZE_M, MAX_SCENE_LEAVES, MAX_SEED,
    MAX_TOTAL_BALLOONS, MIN_BALLOON_DIAMETER_M, MIN_ROOM_SIZE_M,
};

/// Metres per inch: balloon sizes are sold in inches (11″ ≈ 0.28 m).
pub const METRES_PER_INCH: f32 = 0.0254;
/// Diameter of a latex group that gives neither `diameter_m` nor `size_in`, m (11″).
pub const DEFAULT_DIAMETER_M: f32 = 0.28;
/// Diameter of a foil group that gives neither, m: 18″, the common round foil balloon.
pub const DEFAULT_FOIL_DIAMETER_M: f32 = 18.0 * METRES_PER_INCH;
/// Latex envelope of an 11″ balloon, g; other sizes scale with the surface (d²).
pub const DEFAULT_ENVELOPE_MASS_G_11IN: f32 = 3.0;
/// Metallised nylon of an 18″ foil balloon, g; other sizes scale with the
/// surface. With its 1 g valve the balloon weighs the ≈ 10 g the physics
/// reference gives.
pub const DEFAULT_FOIL_ENVELOPE_MASS_G_18IN: f32 = 9.0;
/// Knot and neck latex, g.
pub const DEFAULT_KNOT_MASS_G: f32 = 0.5;
/// A foil balloon's valve strip and the seal round it, g (an estimate).
pub const DEFAULT_FOIL_VALVE_MASS_G: f32 = 1.0;
/// Latest fill before the run, h (`filled_hours_before`): 12 weeks, past
/// any balloon's float time.
pub const MAX_FILLED_HOURS_BEFORE: f32 = 2000.0;
/// The original's six colours: the palette's first six.
pub const DEFAULT_COLORS: [&str; DEFAULT_COLOR_COUNT] = {
    let mut names = [""; DEFAULT_COLOR_COUNT];
    let mut i = 0;
    while i < DEFAULT_COLOR_COUNT {
        names[i] = PALETTE[i].name;
        i += 1;
    }
    names
};
/// Largest scene file read, bytes (1 MiB: the full documented example is
/// about 2 KiB). A bigger file, or a device that never ends, is refused.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;
/// Name used in messages for a scene that did not come from a file.
pub const DEFAULT_SOURCE_NAME: &str = "<default scene>";

/// A whole scene. `Scene::default()` is the original.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scene {
    pub room: RoomSpec,
    /// Groups of identical balloons (colours cycle within a group); at most 64.
    pub balloons: Vec<BalloonGroup>,
    pub air: AirSpec,
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

impl Default for SceneSource {
    fn default() -> Self {
        Self {
            name: DEFAULT_SOURCE_NAME.to_string(),
            dir: None,
            lines: KeyLines::default(),
        }
    }
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

impl Default for RoomSpec {
    fn default() -> Self {
        Self {
            width: 6.0,
            depth: 6.0,
            wall_height: 3.0,
            ceiling: CeilingKind::Pyramid,
            apex_height: 1.5,
            mesh: None,
        }
    }
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
}

impl Default for BalloonGroup {
    fn default() -> Self {
        Self {
            count: 1,
            kind: BalloonKind::Latex,
            treatment: Treatment::Untreated,
            finish: None,
            filled_hours_before: 0.0,
            colors: DEFAULT_COLORS.iter().map(|c| c.to_string()).collect(),
            diameter_m: None,
            size_in: None,
            gas: GasKind::Helium,
            envelope_mass_g: None,
            knot_mass_g: None,
            spawn: None,
            velocity: [0.0; 3],
            angular_velocity: [0.0; 3],
            tilt_deg: 3.0,
            yaw_deg: 10.0,
            leaves: 5,
            ribbon: None,
        }
    }
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

/// Length of the original room's ribbons, m: it hangs well clear of the
/// floor from a pile under the 3 m ceiling (knots at about 2.6 m).
pub const DEFAULT_RIBBON_LENGTH_M: f32 = 1.5;
/// Mass per metre of curling ribbon, g/m: an estimate, no measured figure
/// (5 mm of BOPP film 20–60 µm thick gives 0.1–0.3 g/m).
pub const DEFAULT_RIBBON_MASS_PER_M_G: f32 = 0.25;
/// Segments of a ribbon: 16 of 9.4 cm for 1.5 m.
pub const DEFAULT_RIBBON_SEGMENTS: u32 = 16;
/// Colour of a ribbon that names none.
pub const DEFAULT_RIBBON_COLOR: &str = "white";

/// A ribbon tied to each balloon of a group, at its knot, hanging from it;
/// a weight at the free end if `weight_g > 0`.
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
}

impl Default for RibbonSpec {
    fn default() -> Self {
        Self {
            length_m: DEFAULT_RIBBON_LENGTH_M,
            mass_per_m_g: DEFAULT_RIBBON_MASS_PER_M_G,
            segments: DEFAULT_RIBBON_SEGMENTS,
            color: DEFAULT_RIBBON_COLOR.to_string(),
            weight_g: 0.0,
        }
    }
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

/// Most points of `air.temperature_schedule`.
pub const MAX_SCHEDULE_POINTS: usize = 1000;
/// Latest time of a `temperature_schedule` point, h (as `filled_hours_before`).
pub const MAX_SCHEDULE_HOURS: f32 = 2000.0;

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
    #[serde(skip_serializing_if = "Vec::is_empty", deserialize_with = "pairs")]
    pub temperature_schedule: Vec<[f32; 2]>,
}

/// `[[a, b], ...]` with exactly two numbers a point: TOML's reader would
/// drop a third number unseen if read straight into `[f32; 2]`.
fn pairs<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Vec<[f32; 2]>, D::Error> {
    let points = Vec::<Vec<f32>>::deserialize(deserializer)?;
    points
        .into_iter()
        .enumerate()
        .map(|(i, point)| {
            <[f32; 2]>::try_from(point.as_slice()).map_err(|_| {
                serde::de::Error::custom(format!(
                    "point {i}: expected [hours, °C], two numbers, found {}",
                    point.len()
                ))
            })
        })
        .collect()
}

impl Default for AirSpec {
    fn default() -> Self {
        Self {
            temperature_c: 20.0,
            pressure_kpa: 101.325,
            temperature_schedule: Vec::new(),
        }
    }
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
}

impl Default for SimSpec {
    fn default() -> Self {
        let def = up_physics::WorldDef::default();
        Self {
            seed: 1,
            dt: def.dt,
            substeps: def.substeps,
            duration_s: 10.0,
            gravity: def.gravity.to_array(),
            friction: def.friction,
            restitution: def.restitution,
            drag_coefficient: def.drag_coefficient,
            added_mass_coefficient: def.added_mass_coefficient,
            angular_damping: def.angular_damping,
            contact_hertz: def.contact_hertz,
            contact_damping_ratio: def.contact_damping_ratio,
            sleep: def.enable_sleep,
            continuous: def.enable_continuous,
        }
    }
}

impl Default for Scene {
    /// The original: 6 m × 6 m room, 3 m walls, pyramid apex 1.5 m above them,
    /// 50 balloons in six colours released from the floor, each on a 1.5 m
    /// white ribbon.
    fn default() -> Self {
        Self {
            room: RoomSpec::default(),
            balloons: vec![BalloonGroup {
                count: 50,
                ribbon: Some(RibbonSpec::default()),
                ..BalloonGroup::default()
            }],
            air: AirSpec::default(),
            sim: SimSpec::default(),
            about: None,
            source: SceneSource::default(),
        }
    }
}

impl PartialEq for Scene {
    /// Same content; where it was read from does not matter.
    fn eq(&self, other: &Self) -> bool {
        self.room == other.room
            && self.balloons == other.balloons
            && self.air == other.air
            && self.sim == other.sim
    }
}

impl Scene {
    /// Reads a `.toml` or `.json` scene file and validates it.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let is_toml = match ext.as_deref() {
            Some("toml") => true,
            Some("json") => false,
            _ => {
                return Err(SceneError::UnknownFormat {
                    path: path.to_path_buf(),
                })
            }
        };
        let text = read_scene_text(path)?;
        let name = path.display().to_string();
        let mut scene = if is_toml {
            Self::from_toml_str(&text, &name)
        } else {
            Self::from_json_str(&text, &name)
        }?;
        scene.source.dir = Some(match path.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir.to_path_buf(),
            _ => PathBuf::from("."),
        });
        Ok(scene)
    }

    /// Parses and validates TOML; `source` names it in messages (a file name).
    pub fn from_toml_str(text: &str, source: &str) -> Result<Scene, SceneError> {
        refuse_empty(text, source)?;
        let parsed = serde_path_to_error::deserialize(toml::Deserializer::new(text));
        let scene = parsed.map_err(|e| {
            let key = key_path(e.path());
            let e = e.into_inner();
            let line = e.span().map(|span| lines::line_of_offset(text, span.start));
            parse_error(source, key, line, e.message().trim().to_string())
        })?;
        Self::finish_parse(scene, source, KeyLines::from_toml(text))
    }

    /// Parses and validates JSON; `source` names it in messages (a file name).
    pub fn from_json_str(text: &str, source: &str) -> Result<Scene, SceneError> {
        refuse_empty(text, source)?;
        let mut deserializer = serde_json::Deserializer::from_str(text);
        // `end` refuses text after the scene, as `serde_json::from_str` does.
        let parsed = match serde_path_to_error::deserialize(&mut deserializer) {
            Ok(scene) => deserializer.end().map(|()| scene).map_err(|e| (None, e)),
            Err(e) => Err((key_path(e.path()), e.into_inner())),
        };
        let scene = parsed.map_err(|(key, e)| {
            let line = (e.line() > 0).then_some(e.line());
            // serde_json appends " at line L column C"; the location says it already.
            let full = e.to_string();
            let message = match full.rfind(" at line ") {
                Some(cut) => full[..cut].to_string(),
                None => full,
            };
            parse_error(source, key, line, message)
        })?;
        Self::finish_parse(scene, source, KeyLines::from_json(text))
    }

    /// A parsed scene with its source attached, validated.
    fn finish_parse(mut scene: Scene, source: &str, lines: KeyLines) -> Result<Scene, SceneError> {
        scene.source = SceneSource {
            name: source.to_string(),
            dir: None,
            lines,
        };
        scene.validate()?;
        scene.air.temperature_c = scene.air.start_temperature_c();
        Ok(scene)
    }

    /// The scene as written out: `temperature_c` is the schedule's first
    /// temperature when there is a schedule, so the text reads back.
    fn normalized(&self) -> std::borrow::Cow<'_, Scene> {
        let start = self.air.start_temperature_c();
        if start.to_bits() == self.air.temperature_c.to_bits() {
            return std::borrow::Cow::Borrowed(self);
        }
        let mut scene = self.clone();
        scene.air.temperature_c = start;
        std::borrow::Cow::Owned(scene)
    }

    pub fn to_toml_string(&self) -> Result<String, SceneError> {
        toml::to_string_pretty(self.normalized().as_ref()).map_err(|e| SceneError::Serialize {
            format: "TOML",
            message: e.to_string(),
        })
    }

    pub fn to_json_string(&self) -> Result<String, SceneError> {
        serde_json::to_string_pretty(self.normalized().as_ref()).map_err(|e| {
            SceneError::Serialize {
                format: "JSON",
                message: e.to_string(),
            }
        })
    }

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

    /// Checks every value against its documented range.
    pub fn validate(&self) -> Result<(), SceneError> {
        validate::validate(self)
    }

    /// Where a key lies, for messages: this scene's file and the key's line.
    pub fn locate(&self, key: &str) -> Location {
        Location {
            file: self.source.name.clone(),
            key: Some(key.to_string()),
            line: self.source.lines.line_of(key),
        }
    }

    /// The room mesh path resolved against the scene file's directory.
    pub fn room_mesh_path(&self) -> Option<PathBuf> {
        let mesh = Path::new(self.room.mesh.as_ref()?);
        Some(match &self.source.dir {
            Some(dir) if mesh.is_relative() => dir.join(mesh),
            _ => mesh.to_path_buf(),
        })
    }
}

/// A scene of nothing but whitespace is an error, not the default scene: it is
/// what an interrupted write or a truncated copy leaves.
fn refuse_empty(text: &str, source: &str) -> Result<(), SceneError> {
    if text.trim().is_empty() {
        return Err(SceneError::Empty {
            file: source.to_string(),
        });
    }
    Ok(())
}

/// The key path serde was in when it failed (`room.width`, `balloons[0].count`);
/// `None` at the top level.
fn key_path(path: &serde_path_to_error::Path) -> Option<String> {
    path.iter().next().is_some().then(|| path.to_string())
}

fn parse_error(
    source: &str,
    key: Option<String>,
    line: Option<usize>,
    message: String,
) -> SceneError {
    SceneError::Parse {
        at: Location {
            file: source.to_string(),
            key,
            line,
        },
        message,
    }
}

/// The text of a scene file: at most `MAX_SCENE_BYTES`, UTF-8.
fn read_scene_text(path: &Path) -> Result<String, SceneError> {
    use std::io::Read as _;
    let read_error = |source| SceneError::Read {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(read_error)?;
    let mut bytes = Vec::new();
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(SceneError::TooLarge {
            path: path.to_path_buf(),
            max: MAX_SCENE_BYTES,
        });
    }
    String::from_utf8(bytes).map_err(|e| {
        read_error(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        ))
    })
}

/// `"#rrggbb"` → RGB in 0–1 (sRGB, as written); colour names are looked up in the `palette`.
pub fn parse_color(name: &str) -> Option<[f32; 3]> {
    if let Some(hex) = name.strip_prefix('#') {
        if hex.len() != 6 || !hex.is_ascii() {
            return None;
        }
        let channel = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        return Some([channel(0)?, channel(2)?, channel(4)?].map(|c| f32::from(c) / 255.0));
    }
    color_rgb(name)
}

#[cfg(test)]
#[path = "scene_tests.rs"]
mod tests;
