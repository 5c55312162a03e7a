//! Range checks on a parsed scene. The first problem found is returned, with
//! the key path and line of the offending value and the documented range.

use super::{
    parse_color, AirSpec, BalloonKind, CeilingKind, Finish, RibbonSpec, RoomSpec, Scene, Treatment,
    METRES_PER_INCH,
};
use crate::error::SceneError;
use up_physics::limits::{self, Limit};
use up_physics::ribbon::{MAX_SEGMENTS, MIN_SEGMENTS};

/// At most this many balloons over all groups: far below
/// `up_physics::MAX_BODIES` (4 000 000), and about 0.2 GB of world and
/// broadphase memory; a run of that many steps at several seconds each.
pub const MAX_TOTAL_BALLOONS: u64 = 200_000;
/// At most this many balloon groups. Every group fits its own sphere tree
/// when the world is built (0.1 s for 5 leaves, 5 s for 32), so the count of
/// groups bounds the time before the first step.
pub const MAX_BALLOON_GROUPS: usize = 64;
/// At most this many colours listed in one group.
pub const MAX_GROUP_COLORS: usize = 64;
/// Most leaf spheres a scene may ask of a group's fitted tree. Fitting time
/// grows steeply with the leaves (5 s for 32, 90 s for 64 on one core), so
/// scene files stop at 32; `up fit-spheres --leaves` goes up to 64 offline.
pub const MAX_SCENE_LEAVES: u32 = 32;
/// Room width, depth and wall height range, m.
pub const MIN_ROOM_SIZE_M: f32 = 0.5;
pub const MAX_ROOM_SIZE_M: f32 = 1000.0;
/// Balloon diameter range, m.
pub const MIN_BALLOON_DIAMETER_M: f32 = 0.05;
pub const MAX_BALLOON_DIAMETER_M: f32 = 5.0;
/// Largest seed: 2⁵³ − 1, exact as a JavaScript number.
pub const MAX_SEED: u64 = (1 << 53) - 1;
/// Fastest initial speed, m/s (the speed of sound).
const MAX_SPEED: f32 = 343.0;
/// Longest ribbon, m.
pub const MAX_RIBBON_LENGTH_M: f32 = 20.0;
/// Heaviest ribbon per metre, g/m (a string with beads; a weight is `weight_g`).
pub const MAX_RIBBON_MASS_PER_M_G: f32 = 1000.0;
/// Heaviest weight at a ribbon's end, g.
pub const MAX_RIBBON_WEIGHT_G: f32 = 1000.0;

/// Latest fill before the run, h (`filled_hours_before`): 12 weeks, past
/// any balloon's float time.
pub const MAX_FILLED_HOURS_BEFORE: f32 = 2000.0;
/// Most points of `air.temperature_schedule`.
pub const MAX_SCHEDULE_POINTS: usize = 1000;
/// Latest time of a `temperature_schedule` point, h (as `filled_hours_before`).
pub const MAX_SCHEDULE_HOURS: f32 = 2000.0;

impl Scene {
    /// Checks every value against its documented range.
    pub fn validate(&self) -> Result<(), SceneError> {
        validate(self)
    }
}

/// Turns a bad value into an error that names its key, line and range.
pub(super) struct Checker<'a> {
    pub(super) scene: &'a Scene,
}

impl Checker<'_> {
    pub(super) fn fail(
        &self,
        key: &str,
        expected: impl Into<String>,
        found: impl Into<String>,
    ) -> SceneError {
        SceneError::Invalid {
            at: self.scene.locate(key),
            expected: expected.into(),
            found: found.into(),
        }
    }

    /// `value` inside a world parameter's shared limit.
    pub(super) fn limit(&self, key: &str, value: f32, limit: &Limit) -> Result<(), SceneError> {
        if limit.contains(value) {
            return Ok(());
        }
        Err(self.fail(key, limit.describe(), value.to_string()))
    }

    /// `lo <= value <= hi` (or `lo < value` when `lo_open`), finite.
    pub(super) fn range(
        &self,
        key: &str,
        value: f32,
        lo: f32,
        hi: f32,
        lo_open: bool,
        unit: &'static str,
    ) -> Result<(), SceneError> {
        let limit = Limit {
            min: lo,
            max: hi,
            min_exclusive: lo_open,
            unit,
        };
        self.limit(key, value, &limit)
    }

    pub(super) fn vector(
        &self,
        key: &str,
        v: [f32; 3],
        max_len: f32,
        unit: &str,
    ) -> Result<(), SceneError> {
        let len = v.iter().map(|c| c * c).sum::<f32>().sqrt();
        if v.iter().all(|c| c.is_finite()) && len <= max_len {
            return Ok(());
        }
        Err(self.fail(
            key,
            format!("finite [x, y, z] no longer than {max_len} {unit}"),
            format!("{v:?}"),
        ))
    }
}

fn validate(scene: &Scene) -> Result<(), SceneError> {
    super::about::check(scene)?;
    let c = Checker { scene };
    let room = &scene.room;
    let (lo, hi) = (MIN_ROOM_SIZE_M, MAX_ROOM_SIZE_M);
    if room.mesh.is_none() {
        c.range("room.width", room.width, lo, hi, false, "m")?;
        c.range("room.depth", room.depth, lo, hi, false, "m")?;
        c.range("room.wall_height", room.wall_height, lo, hi, false, "m")?;
        if room.ceiling == CeilingKind::Pyramid {
            c.range("room.apex_height", room.apex_height, 0.0, hi, true, "m")?;
        }
    } else if room.mesh.as_deref().is_some_and(|m| m.trim().is_empty()) {
        return Err(c.fail("room.mesh", "a path to an OBJ file", "an empty string"));
    }

    let air = &scene.air;
    c.range(
        "air.temperature_c",
        air.temperature_c,
        -60.0,
        60.0,
        false,
        "°C",
    )?;
    c.range(
        "air.pressure_kpa",
        air.pressure_kpa,
        50.0,
        150.0,
        false,
        "kPa",
    )?;
    check_schedule(&c, air)?;
    super::air_sources::check(&c)?;
    super::furniture::check(&c)?;

    let sim = &scene.sim;
    if sim.seed > MAX_SEED {
        return Err(c.fail(
            "sim.seed",
            format!("an integer in [0, {MAX_SEED}]"),
            sim.seed.to_string(),
        ));
    }
    c.limit("sim.dt", sim.dt, &limits::DT)?;
    let substeps = limits::SUBSTEPS;
    if !substeps.contains(sim.substeps as f32) {
        return Err(c.fail(
            "sim.substeps",
            format!("an integer in [{}, {}]", substeps.min, substeps.max),
            sim.substeps.to_string(),
        ));
    }
    c.range("sim.duration_s", sim.duration_s, 0.0, 86_400.0, true, "s")?;
    for (i, g) in sim.gravity.iter().enumerate() {
        c.range(
            &format!("sim.gravity[{i}]"),
            *g,
            -1000.0,
            1000.0,
            false,
            "m/s²",
        )?;
    }
    c.limit("sim.friction", sim.friction, &limits::FRICTION)?;
    c.limit(
        "sim.ribbon_friction",
        sim.ribbon_friction,
        &limits::FRICTION,
    )?;
    c.limit("sim.restitution", sim.restitution, &limits::RESTITUTION)?;
    let drag = sim.drag_coefficient;
    c.limit("sim.drag_coefficient", drag, &limits::DRAG_COEFFICIENT)?;
    let added = sim.added_mass_coefficient;
    c.limit(
        "sim.added_mass_coefficient",
        added,
        &limits::ADDED_MASS_COEFFICIENT,
    )?;
    let damping = sim.angular_damping;
    c.limit("sim.angular_damping", damping, &limits::ANGULAR_DAMPING)?;
    c.limit(
        "sim.contact_hertz",
        sim.contact_hertz,
        &limits::CONTACT_HERTZ,
    )?;
    let zeta = sim.contact_damping_ratio;
    c.limit(
        "sim.contact_damping_ratio",
        zeta,
        &limits::CONTACT_DAMPING_RATIO,
    )?;

    if scene.balloons.len() > MAX_BALLOON_GROUPS {
        return Err(c.fail(
            &format!("balloons[{MAX_BALLOON_GROUPS}]"),
            format!("at most {MAX_BALLOON_GROUPS} balloon groups"),
            format!("{} groups", scene.balloons.len()),
        ));
    }
    let mut total: u64 = 0;
    for (i, group) in scene.balloons.iter().enumerate() {
        let key = |k: &str| format!("balloons[{i}].{k}");
        total = total.saturating_add(group.count);
        if group.count > MAX_TOTAL_BALLOONS || total > MAX_TOTAL_BALLOONS {
            return Err(c.fail(
                &key("count"),
                format!("at most {MAX_TOTAL_BALLOONS} balloons over all groups"),
                format!("{} in this group, {total} so far", group.count),
            ));
        }
        if group.colors.is_empty() || group.colors.len() > MAX_GROUP_COLORS {
            return Err(c.fail(
                &key("colors"),
                format!("1 to {MAX_GROUP_COLORS} colours"),
                format!("{} colours", group.colors.len()),
            ));
        }
        for (j, color) in group.colors.iter().enumerate() {
            if parse_color(color).is_none() {
                let names: Vec<&str> = crate::palette::color_names().collect();
                return Err(c.fail(
                    &format!("balloons[{i}].colors[{j}]"),
                    format!("a colour name ({}) or \"#rrggbb\"", names.join(", ")),
                    format!("{color:?}"),
                ));
            }
        }
        if group.kind == BalloonKind::Foil && group.treatment == Treatment::HiFloat {
            return Err(c.fail(
                &key("treatment"),
                "\"none\" for a foil balloon (Hi-Float is a gel for latex)",
                "\"hi-float\"",
            ));
        }
        if group.kind == BalloonKind::Foil && group.finish() != Finish::Foil {
            return Err(c.fail(
                &key("finish"),
                "\"foil\" for a foil balloon (latex and pearl are latex finishes)",
                format!("\"{}\"", group.finish().name()),
            ));
        }
        c.range(
            &key("filled_hours_before"),
            group.filled_hours_before,
            0.0,
            MAX_FILLED_HOURS_BEFORE,
            false,
            "h",
        )?;
        if group.diameter_m.is_some() && group.size_in.is_some() {
            return Err(c.fail(
                &key("size_in"),
                "either diameter_m or size_in, not both",
                "both",
            ));
        }
        let (dmin, dmax) = (MIN_BALLOON_DIAMETER_M, MAX_BALLOON_DIAMETER_M);
        if let Some(d) = group.diameter_m {
            c.range(&key("diameter_m"), d, dmin, dmax, false, "m")?;
        }
        if let Some(inches) = group.size_in {
            let (lo, hi) = (dmin / METRES_PER_INCH, dmax / METRES_PER_INCH);
            c.range(&key("size_in"), inches, lo.ceil(), hi.floor(), false, "in")?;
        }
        if let Some(m) = group.envelope_mass_g {
            c.range(&key("envelope_mass_g"), m, 0.01, 10_000.0, false, "g")?;
        }
        if let Some(m) = group.knot_mass_g {
            c.range(&key("knot_mass_g"), m, 0.0, 1000.0, false, "g")?;
        }
        c.vector(&key("velocity"), group.velocity, MAX_SPEED, "m/s")?;
        c.vector(
            &key("angular_velocity"),
            group.angular_velocity,
            1000.0,
            "rad/s",
        )?;
        c.range(&key("tilt_deg"), group.tilt_deg, 0.0, 90.0, false, "°")?;
        c.range(&key("yaw_deg"), group.yaw_deg, 0.0, 180.0, false, "°")?;
        if !(1..=MAX_SCENE_LEAVES).contains(&group.leaves) {
            let expected = format!("an integer in [1, {MAX_SCENE_LEAVES}]");
            return Err(c.fail(&key("leaves"), expected, group.leaves.to_string()));
        }
        super::shapes::check_shape(&c, i, group)?;
        if let Some(ribbon) = &group.ribbon {
            check_ribbon(&c, &key("ribbon"), ribbon)?;
            check_anchor(&c, &key("ribbon"), ribbon, room)?;
        }

        // The balloon must fit in a box room (mesh rooms are checked when built).
        let d = group.diameter();
        let smallest_side = room.width.min(room.depth).min(room.wall_height);
        let diameter_key = if group.size_in.is_some() {
            key("size_in")
        } else {
            key("diameter_m")
        };
        if room.mesh.is_none() && d >= smallest_side {
            return Err(c.fail(
                &diameter_key,
                format!("a balloon smaller than the room's smallest side ({smallest_side} m)"),
                format!("{d} m"),
            ));
        }

        if let Some(spawn) = &group.spawn {
            for axis in 0..3 {
                let name = ["x", "y", "z"][axis];
                c.range(
                    &format!("{}.min[{axis}]", key("spawn")),
                    spawn.min[axis],
                    -hi,
                    hi,
                    false,
                    "m",
                )?;
                c.range(
                    &format!("{}.max[{axis}]", key("spawn")),
                    spawn.max[axis],
                    -hi,
                    hi,
                    false,
                    "m",
                )?;
                if spawn.max[axis] < spawn.min[axis] {
                    return Err(c.fail(
                        &key("spawn.max"),
                        format!("max.{name} ≥ min.{name} ({})", spawn.min[axis]),
                        spawn.max[axis].to_string(),
                    ));
                }
            }
            for axis in [0, 2] {
                let extent = spawn.max[axis] - spawn.min[axis];
                if extent < d {
                    let name = ["x", "y", "z"][axis];
                    return Err(c.fail(
                        &key("spawn"),
                        format!("a region at least one balloon ({d} m) wide along {name}"),
                        format!("{extent} m"),
                    ));
                }
            }
            if room.mesh.is_none() {
                let (hx, hz) = (room.width / 2.0, room.depth / 2.0);
                let lo = [-hx, 0.0, -hz];
                let hi = [hx, room.top(), hz];
                let inside = (0..3).all(|a| spawn.min[a] >= lo[a] && spawn.max[a] <= hi[a]);
                if !inside {
                    return Err(c.fail(
                        &key("spawn"),
                        format!("a region inside the room, from {lo:?} to {hi:?} m"),
                        format!("from {:?} to {:?}", spawn.min, spawn.max),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// `air.temperature_schedule`: hours increasing from ≥ 0, each °C in range,
/// and `air.temperature_c`, if the file gives it, the first point's.
fn check_schedule(c: &Checker, air: &AirSpec) -> Result<(), SceneError> {
    let schedule = &air.temperature_schedule;
    if schedule.len() > MAX_SCHEDULE_POINTS {
        return Err(c.fail(
            "air.temperature_schedule",
            format!("at most {MAX_SCHEDULE_POINTS} [hours, °C] points"),
            format!("{} points", schedule.len()),
        ));
    }
    for (i, &[hours, celsius]) in schedule.iter().enumerate() {
        let at = format!("air.temperature_schedule[{i}]");
        c.range(
            &format!("{at}[0]"),
            hours,
            0.0,
            MAX_SCHEDULE_HOURS,
            false,
            "h",
        )?;
        if let Some(&[previous, _]) = i.checked_sub(1).map(|j| &schedule[j]) {
            if hours <= previous {
                return Err(c.fail(
                    &format!("{at}[0]"),
                    format!(
                        "hours after the previous point's {previous} (points in increasing time)"
                    ),
                    hours.to_string(),
                ));
            }
        }
        c.range(&format!("{at}[1]"), celsius, -60.0, 60.0, false, "°C")?;
    }
    if let Some(&[_, first]) = schedule.first() {
        let given = c.scene.source.lines.contains("air.temperature_c");
        if given && air.temperature_c != first {
            return Err(c.fail(
                "air.temperature_c",
                format!(
                    "the schedule's first temperature ({first} °C), or no temperature_c: \
                     the schedule sets the air from its first point"
                ),
                air.temperature_c.to_string(),
            ));
        }
    }
    Ok(())
}

/// A group's `ribbon` table; `at` is its key path (`balloons[0].ribbon`).
fn check_ribbon(c: &Checker, at: &str, ribbon: &RibbonSpec) -> Result<(), SceneError> {
    let key = |k: &str| format!("{at}.{k}");
    let length = ribbon.length_m;
    if !(length.is_finite() && (0.0..=MAX_RIBBON_LENGTH_M).contains(&length)) {
        return Err(c.fail(
            &key("length_m"),
            format!("a length in (0, {MAX_RIBBON_LENGTH_M}] m, or 0 for no ribbon"),
            length.to_string(),
        ));
    }
    c.range(
        &key("mass_per_m_g"),
        ribbon.mass_per_m_g,
        0.0,
        MAX_RIBBON_MASS_PER_M_G,
        true,
        "g/m",
    )?;
    if !(MIN_SEGMENTS..=MAX_SEGMENTS).contains(&ribbon.segments) {
        return Err(c.fail(
            &key("segments"),
            format!("an integer in [{MIN_SEGMENTS}, {MAX_SEGMENTS}]"),
            ribbon.segments.to_string(),
        ));
    }
    if parse_color(&ribbon.color).is_none() {
        let names: Vec<&str> = crate::palette::color_names().collect();
        return Err(c.fail(
            &key("color"),
            format!("a colour name ({}) or \"#rrggbb\"", names.join(", ")),
            format!("{:?}", ribbon.color),
        ));
    }
    c.range(
        &key("weight_g"),
        ribbon.weight_g,
        0.0,
        MAX_RIBBON_WEIGHT_G,
        false,
        "g",
    )
}

/// A ribbon's `anchor`: a finite point inside the room's box (a mesh room's
/// bounds are checked when it is built), on a ribbon that exists.
fn check_anchor(
    c: &Checker,
    at: &str,
    ribbon: &RibbonSpec,
    room: &RoomSpec,
) -> Result<(), SceneError> {
    let Some(anchor) = ribbon.anchor else {
        return Ok(());
    };
    let key = format!("{at}.anchor");
    if ribbon.length_m == 0.0 {
        return Err(c.fail(
            &key,
            "no anchor on a group without a ribbon (length_m = 0)",
            format!("{anchor:?}"),
        ));
    }
    let (lo, hi) = if room.mesh.is_none() {
        let (hx, hz) = (room.width / 2.0, room.depth / 2.0);
        ([-hx, 0.0, -hz], [hx, room.top(), hz])
    } else {
        ([-MAX_ROOM_SIZE_M; 3], [MAX_ROOM_SIZE_M; 3])
    };
    let inside = (0..3).all(|a| anchor[a].is_finite() && lo[a] <= anchor[a] && anchor[a] <= hi[a]);
    if !inside {
        return Err(c.fail(
            &key,
            format!("a point [x, y, z] inside the room, from {lo:?} to {hi:?} m"),
            format!("{anchor:?}"),
        ));
    }
    Ok(())
}
