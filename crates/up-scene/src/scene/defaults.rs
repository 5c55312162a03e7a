//! The default of every scene key: the original project's scene (a 6 m ×
//! 6 m room with 3 m walls and a pyramidal ceiling, 50 balloons in six
//! colours released from the floor, each on a 1.5 m white ribbon), and the
//! sizes and masses a group gets for what it leaves out. Every section and
//! every key may be left out (`#[serde(default)]` on each struct).

use super::{
    AirSpec, BalloonGroup, BalloonKind, CeilingKind, GasKind, KeyLines, RibbonSpec, RoomSpec,
    Scene, SceneSource, SimSpec, Treatment,
};
use crate::palette::{DEFAULT_COLOR_COUNT, PALETTE};

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
/// Name used in messages for a scene that did not come from a file.
pub const DEFAULT_SOURCE_NAME: &str = "<default scene>";

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

impl Default for SceneSource {
    fn default() -> Self {
        Self {
            name: DEFAULT_SOURCE_NAME.to_string(),
            dir: None,
            lines: KeyLines::default(),
        }
    }
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
            shape: None,
            text: None,
            mesh: None,
            knot: None,
        }
    }
}

impl Default for RibbonSpec {
    fn default() -> Self {
        Self {
            length_m: DEFAULT_RIBBON_LENGTH_M,
            mass_per_m_g: DEFAULT_RIBBON_MASS_PER_M_G,
            segments: DEFAULT_RIBBON_SEGMENTS,
            color: DEFAULT_RIBBON_COLOR.to_string(),
            weight_g: 0.0,
            anchor: None,
        }
    }
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
            ribbon_contacts: def.ribbon_contacts,
            ribbon_friction: def.ribbon_friction,
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
            fans: Vec::new(),
            vents: Vec::new(),
            draughts: Vec::new(),
            furniture: Vec::new(),
            sim: SimSpec::default(),
            about: None,
            source: SceneSource::default(),
        }
    }
}
