//! `[[fans]]`, `[[vents]]` and `[[draughts]]`: the sources of the room's
//! moving air (`up_physics::air`, where the jet model and its limits are).
//!
//! A fan and a vent are the same round jet with different defaults: a fan
//! is a household fan blowing across the room, a vent a ceiling diffuser
//! blowing down. A draught is air moving through an open door or window.
//! Each may be switched on and off by `on` intervals. Their ranges are
//! checked here (`check`), with the file, line and key path of a bad value;
//! `build::air` turns them into the world's `AirFlow`.

use serde::{Deserialize, Serialize};

use super::validate::Checker;
use super::Scene;
use crate::error::SceneError;

/// Most fans, vents or draughts a scene may list, each: every source is
/// evaluated for every balloon and ribbon point in every substep, so the
/// cost grows with their number.
pub const MAX_AIR_SOURCES: usize = 64;
/// Most `on` intervals of one source (each is looked at for every drag).
pub const MAX_ON_INTERVALS: usize = 64;
/// Fastest outlet or draught speed, m/s (a strong storm through a window;
/// household fans blow 2–6 m/s).
pub const MAX_AIR_SPEED_M_S: f32 = 30.0;
/// Outlet diameter range, m: `(MIN, MAX]`.
pub const MIN_JET_DIAMETER_M: f32 = 0.05;
pub const MAX_JET_DIAMETER_M: f32 = 3.0;
/// Widest sweep, degrees (total, side to side).
pub const MAX_SWEEP_DEG: f32 = 180.0;
/// Longest sweep period, s.
pub const MAX_SWEEP_PERIOD_S: f32 = 600.0;

/// A fan's outlet: 0.4 m, a 16″ household fan (the common pedestal size).
pub const DEFAULT_FAN_DIAMETER_M: f32 = 0.4;
/// A fan's outlet speed: 3 m/s, an estimate for a household fan on a
/// middle setting (no measured figure; its blades' tip speed is several
/// times more).
pub const DEFAULT_FAN_SPEED_M_S: f32 = 3.0;
/// Where a fan blows by default: level, along +z.
pub const DEFAULT_FAN_DIRECTION: [f32; 3] = [0.0, 0.0, 1.0];
/// A vent's outlet: 0.25 m, a 10″ round ceiling diffuser neck, a common
/// catalogue size (an estimate of a typical room's, not a measurement).
pub const DEFAULT_VENT_DIAMETER_M: f32 = 0.25;
/// A vent's outlet speed: 2 m/s, at the quiet end of the 2–4 m/s neck
/// speeds diffusers are commonly sized for (an estimate).
pub const DEFAULT_VENT_SPEED_M_S: f32 = 2.0;
/// Where a vent blows by default: straight down, from the ceiling.
pub const DEFAULT_VENT_DIRECTION: [f32; 3] = [0.0, -1.0, 0.0];
/// One sweep there and back, s: oscillating household fans take 10–15 s.
pub const DEFAULT_SWEEP_PERIOD_S: f32 = 12.0;

/// A round outlet blowing a jet: a fan (`[[fans]]`) or a vent (`[[vents]]`).
/// The keys a file leaves out take the kind's defaults (`JetSpec::resolved`).
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JetSpec {
    /// m, world frame: the outlet's centre. Required; inside the room.
    #[serde(deserialize_with = "super::parse::xyz")]
    pub position: [f32; 3],
    /// Where it blows, any length but zero (normalised when built); a fan
    /// [0, 0, 1], a vent [0, −1, 0].
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "super::parse::point"
    )]
    pub direction: Option<[f32; 3]>,
    /// m; a fan 0.4, a vent 0.25. Range (0.05, 3].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter_m: Option<f32>,
    /// m/s at the outlet; a fan 3, a vent 2. Range [0, 30].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_m_s: Option<f32>,
    /// Degrees: the total angle it sweeps side to side about the vertical;
    /// 0 (it does not sweep). Range [0, 180].
    #[serde(default)]
    pub sweep_deg: f32,
    /// s: one sweep there and back; 12. Range (0, 600].
    #[serde(default = "default_sweep_period")]
    pub sweep_period_s: f32,
    /// `[start, end]` intervals of simulated time, s, when it blows (it
    /// spins up and down over `up_physics::air::SPIN_UP_S` at their ends).
    /// Left out or empty: always on.
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "super::parse::intervals"
    )]
    pub on: Vec<[f64; 2]>,
}

fn default_sweep_period() -> f32 {
    DEFAULT_SWEEP_PERIOD_S
}

/// Which list a jet is in: the kind picks its defaults.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JetSource {
    Fan,
    Vent,
}

impl JetSource {
    /// The scene key of the list: `fans` or `vents`.
    pub fn key(self) -> &'static str {
        match self {
            JetSource::Fan => "fans",
            JetSource::Vent => "vents",
        }
    }
}

/// A jet's keys with the kind's defaults filled in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResolvedJet {
    pub position: [f32; 3],
    pub direction: [f32; 3],
    pub diameter_m: f32,
    pub speed_m_s: f32,
}

impl JetSpec {
    /// A jet at `position` with every other key left out.
    pub fn at(position: [f32; 3]) -> JetSpec {
        JetSpec {
            position,
            direction: None,
            diameter_m: None,
            speed_m_s: None,
            sweep_deg: 0.0,
            sweep_period_s: DEFAULT_SWEEP_PERIOD_S,
            on: Vec::new(),
        }
    }

    /// The keys a fan or vent leaves out, filled in with its kind's defaults.
    pub fn resolved(&self, source: JetSource) -> ResolvedJet {
        let (direction, diameter, speed) = match source {
            JetSource::Fan => (
                DEFAULT_FAN_DIRECTION,
                DEFAULT_FAN_DIAMETER_M,
                DEFAULT_FAN_SPEED_M_S,
            ),
            JetSource::Vent => (
                DEFAULT_VENT_DIRECTION,
                DEFAULT_VENT_DIAMETER_M,
                DEFAULT_VENT_SPEED_M_S,
            ),
        };
        ResolvedJet {
            position: self.position,
            direction: self.direction.unwrap_or(direction),
            diameter_m: self.diameter_m.unwrap_or(diameter),
            speed_m_s: self.speed_m_s.unwrap_or(speed),
        }
    }
}

/// Air moving through an open door or window (`[[draughts]]`).
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DraughtSpec {
    /// m, world frame: the opening's box, thin along the velocity (a door
    /// 1 m wide and 2 m high in a wall: 0.1 m deep). Required; inside the
    /// room, `min` below `max` on every axis.
    #[serde(deserialize_with = "super::parse::xyz")]
    pub min: [f32; 3],
    #[serde(deserialize_with = "super::parse::xyz")]
    pub max: [f32; 3],
    /// m/s, world frame: the air's velocity through the opening. Required;
    /// at most 30 m/s.
    #[serde(deserialize_with = "super::parse::xyz")]
    pub velocity_m_s: [f32; 3],
    /// `[start, end]` intervals, s, when the opening is open (as a jet's
    /// `on`). Left out or empty: always.
    #[serde(
        default,
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "super::parse::intervals"
    )]
    pub on: Vec<[f64; 2]>,
}

impl Scene {
    /// Whether the scene has any source of moving air.
    pub fn has_moving_air(&self) -> bool {
        !(self.fans.is_empty() && self.vents.is_empty() && self.draughts.is_empty())
    }

    /// Every fan then every vent, with its key path (`fans[0]`) and kind.
    pub fn jets(&self) -> impl Iterator<Item = (String, JetSource, &JetSpec)> {
        listed(JetSource::Fan, &self.fans).chain(listed(JetSource::Vent, &self.vents))
    }
}

/// A list of jets with their key paths.
fn listed(
    source: JetSource,
    jets: &[JetSpec],
) -> impl Iterator<Item = (String, JetSource, &JetSpec)> {
    let at = move |(i, jet)| (format!("{}[{i}]", source.key()), source, jet);
    jets.iter().enumerate().map(at)
}

/// The room's box, m: a point outside it is outside the room. A mesh
/// room's bounds are known only when it is built (`build::air`).
fn room_box(scene: &Scene) -> Option<([f32; 3], [f32; 3])> {
    let room = &scene.room;
    if room.mesh.is_some() {
        return None;
    }
    let (hx, hz) = (room.width / 2.0, room.depth / 2.0);
    Some(([-hx, 0.0, -hz], [hx, room.top(), hz]))
}

/// Every fan, vent and draught within its ranges, inside the room.
pub(super) fn check(c: &Checker) -> Result<(), SceneError> {
    let scene = c.scene;
    for (key, list) in [
        ("fans", scene.fans.len()),
        ("vents", scene.vents.len()),
        ("draughts", scene.draughts.len()),
    ] {
        if list > MAX_AIR_SOURCES {
            return Err(c.fail(
                &format!("{key}[{MAX_AIR_SOURCES}]"),
                format!("at most {MAX_AIR_SOURCES} {key}"),
                format!("{list}"),
            ));
        }
    }
    let bounds = room_box(scene);
    for (at, _, jet) in scene.jets() {
        check_jet(c, &at, jet, bounds)?;
    }
    for (i, draught) in scene.draughts.iter().enumerate() {
        check_draught(c, &format!("draughts[{i}]"), draught, bounds)?;
    }
    Ok(())
}

fn check_jet(
    c: &Checker,
    at: &str,
    jet: &JetSpec,
    bounds: Option<([f32; 3], [f32; 3])>,
) -> Result<(), SceneError> {
    let key = |k: &str| format!("{at}.{k}");
    check_inside(c, &key("position"), jet.position, bounds)?;
    if let Some(direction) = jet.direction {
        let length = direction.iter().map(|x| x * x).sum::<f32>().sqrt();
        if !(direction.iter().all(|x| x.is_finite()) && length > 1e-6) {
            return Err(c.fail(
                &key("direction"),
                "a finite, non-zero [x, y, z] (it is normalised)",
                format!("{direction:?}"),
            ));
        }
    }
    if let Some(d) = jet.diameter_m {
        let (lo, hi) = (MIN_JET_DIAMETER_M, MAX_JET_DIAMETER_M);
        c.range(&key("diameter_m"), d, lo, hi, true, "m")?;
    }
    if let Some(speed) = jet.speed_m_s {
        c.range(
            &key("speed_m_s"),
            speed,
            0.0,
            MAX_AIR_SPEED_M_S,
            false,
            "m/s",
        )?;
    }
    c.range(
        &key("sweep_deg"),
        jet.sweep_deg,
        0.0,
        MAX_SWEEP_DEG,
        false,
        "°",
    )?;
    let period = jet.sweep_period_s;
    c.range(
        &key("sweep_period_s"),
        period,
        0.0,
        MAX_SWEEP_PERIOD_S,
        true,
        "s",
    )?;
    check_on(c, &key("on"), &jet.on)
}

fn check_draught(
    c: &Checker,
    at: &str,
    draught: &DraughtSpec,
    bounds: Option<([f32; 3], [f32; 3])>,
) -> Result<(), SceneError> {
    let key = |k: &str| format!("{at}.{k}");
    check_inside(c, &key("min"), draught.min, bounds)?;
    check_inside(c, &key("max"), draught.max, bounds)?;
    if !(0..3).all(|a| draught.min[a] < draught.max[a]) {
        return Err(c.fail(
            &key("max"),
            format!(
                "a corner above min ({:?}) on every axis: the opening is a box",
                draught.min
            ),
            format!("{:?}", draught.max),
        ));
    }
    c.vector(
        &key("velocity_m_s"),
        draught.velocity_m_s,
        MAX_AIR_SPEED_M_S,
        "m/s",
    )?;
    check_on(c, &key("on"), &draught.on)
}

/// A finite point inside the room's box (any finite point in a mesh room,
/// whose bounds are checked when it is built).
fn check_inside(
    c: &Checker,
    key: &str,
    p: [f32; 3],
    bounds: Option<([f32; 3], [f32; 3])>,
) -> Result<(), SceneError> {
    let finite = p.iter().all(|x| x.is_finite());
    let inside = match bounds {
        Some((lo, hi)) => (0..3).all(|a| lo[a] <= p[a] && p[a] <= hi[a]),
        None => true,
    };
    if finite && inside {
        return Ok(());
    }
    let expected = match bounds {
        Some((lo, hi)) => format!("a point [x, y, z] inside the room, from {lo:?} to {hi:?} m"),
        None => "a finite point [x, y, z], m".to_string(),
    };
    Err(c.fail(key, expected, format!("{p:?}")))
}

/// On intervals: each `[start, end]` finite with start ≤ end; at most
/// `MAX_ON_INTERVALS`.
fn check_on(c: &Checker, key: &str, on: &[[f64; 2]]) -> Result<(), SceneError> {
    if on.len() > MAX_ON_INTERVALS {
        return Err(c.fail(
            key,
            format!("at most {MAX_ON_INTERVALS} [start, end] intervals"),
            format!("{} intervals", on.len()),
        ));
    }
    for (k, &[start, end]) in on.iter().enumerate() {
        if !(start.is_finite() && end.is_finite() && start <= end) {
            return Err(c.fail(
                &format!("{key}[{k}]"),
                "[start, end] in s, finite, with start ≤ end",
                format!("[{start}, {end}]"),
            ));
        }
    }
    Ok(())
}
