//! A round turbulent free jet: the air a fan or a vent blows.
//!
//! The model (Pope, *Turbulent Flows*, 2000, ch. 5; constants from Hussein,
//! Capp & George 1994, Pope's table 5.1):
//!
//! - a potential core that keeps the outlet speed U₀ on the axis out to
//!   x₀ + B·D (5.8 D: the literature's core is 4–6 D);
//! - past it, the self-similar jet: centreline speed U_c = U₀·B·D/(x − x₀),
//!   with B = 5.8 and the virtual origin x₀ taken at the outlet (published
//!   virtual origins run from about 0 to 4 D; x₀ = 0 makes the core and the
//!   far law meet without a jump);
//! - a Gaussian profile across, U = U_c·exp(−ln 2·(r/r½)²), whose half-width
//!   r½ = S·(x − x₀) with S = 0.094 in the far jet, and grows linearly from
//!   the outlet's radius D/2 to that value along the core;
//! - entrainment: the jet's volume flow grows as 0.32·x/D times the
//!   outlet's (Ricou & Spalding 1961), so air flows in toward the axis from
//!   the side at (dQ/dx)/(2π·r), faded out inside the jet, where the profile
//!   carries the flow. It is what draws a balloon toward a jet's axis here.
//!
//! A household fan (hub, swirl, blades) is only roughly a round jet; nothing
//! blows behind the outlet plane (its intake is not modelled).

use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};

use super::schedule::Schedule;

/// B in U_c = U₀·B·D/(x − x₀) (Hussein, Capp & George 1994: 5.8).
pub const JET_DECAY_B: f32 = 5.8;
/// S in r½ = S·(x − x₀) (Hussein, Capp & George 1994: 0.094).
pub const JET_SPREAD_S: f32 = 0.094;
/// x₀ / D, the virtual origin (at the outlet).
pub const JET_VIRTUAL_ORIGIN_D: f32 = 0.0;
/// The jet's volume flow grows as this × x/D times the outlet's (Ricou &
/// Spalding 1961).
const ENTRAINMENT: f32 = 0.32;

/// What drew the jet: the same air, drawn differently in the page.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum JetKind {
    Fan,
    Vent,
}

/// A fan that turns side to side about the vertical, as oscillating
/// household fans do: its aim swings by ±`angle_rad`/2, sinusoidally.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Sweep {
    /// Total swing, rad, [0, π].
    pub angle_rad: f32,
    /// One full swing there and back, s.
    pub period_s: f32,
}

/// One round outlet blowing a jet.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Jet {
    pub kind: JetKind,
    /// The outlet's centre, m.
    pub outlet: Vec3,
    /// Where it blows with no sweep, a unit vector.
    pub direction: Vec3,
    /// Outlet diameter, m.
    pub diameter: f32,
    /// Outlet speed at full power, m/s.
    pub speed: f32,
    pub sweep: Sweep,
    pub schedule: Schedule,
}

impl Jet {
    /// A steady jet that is always on and does not sweep.
    pub fn new(kind: JetKind, outlet: Vec3, direction: Vec3, diameter: f32, speed: f32) -> Jet {
        Jet {
            kind,
            outlet,
            direction: direction.normalize_or_zero(),
            diameter,
            speed,
            sweep: Sweep::default(),
            schedule: Schedule::always(),
        }
    }

    /// Where it blows at `t`: the direction turned about the vertical by the
    /// sweep's angle then.
    pub fn aim_at(&self, t: f64) -> Vec3 {
        if self.sweep.angle_rad == 0.0 || self.sweep.period_s <= 0.0 {
            return self.direction;
        }
        let phase = core::f64::consts::TAU * t / f64::from(self.sweep.period_s);
        let angle = 0.5 * self.sweep.angle_rad * libm::sin(phase) as f32;
        Quat::from_rotation_y(angle) * self.direction
    }

    /// The outlet speed at `t`, m/s: full speed times the schedule's level.
    pub fn speed_at(&self, t: f64) -> f32 {
        self.speed * self.schedule.level_at(t)
    }

    /// Where the potential core ends, m from the outlet.
    pub fn core_length(&self) -> f32 {
        core_length(self.diameter)
    }

    /// The axis speed `x` m downstream of the outlet, as a fraction of the
    /// outlet speed: 1 along the core, B·D/(x − x₀) past it, 0 behind.
    pub fn centreline_fraction(&self, x: f32) -> f32 {
        centreline_fraction(self.diameter, x)
    }

    /// Where the speed across the jet is half the centreline's, `x` m
    /// downstream, m.
    pub fn half_width(&self, x: f32) -> f32 {
        half_width(self.diameter, x)
    }

    /// The jet as it blows at `t`: aimed and at the speed of then.
    pub(crate) fn now(&self, t: f64) -> JetNow {
        JetNow::new(self.outlet, self.aim_at(t), self.diameter, self.speed_at(t))
    }

    /// The air's velocity at `p` at `t`, m/s.
    pub fn velocity_at(&self, p: Vec3, t: f64) -> Vec3 {
        self.now(t).velocity_at(p)
    }

    /// The jet's velocity at `p` when it blows along `aim` at outlet speed
    /// `speed`, m/s (the schedule and sweep already applied).
    pub fn flow_at(&self, p: Vec3, aim: Vec3, speed: f32) -> Vec3 {
        JetNow::new(self.outlet, aim, self.diameter, speed).flow_at(p)
    }

    pub fn validate(&self) -> Result<(), String> {
        let finite = self.outlet.is_finite() && self.direction.is_finite();
        if !finite {
            return Err("position: expected finite numbers".into());
        }
        if self.direction.length_squared() < 1e-12 {
            return Err("direction: expected a non-zero vector".into());
        }
        if !(self.diameter > 0.05 && self.diameter <= 3.0) {
            return Err(format!(
                "diameter_m: expected (0.05, 3], got {}",
                self.diameter
            ));
        }
        if !(0.0..=30.0).contains(&self.speed) {
            return Err(format!("speed_m_s: expected [0, 30], got {}", self.speed));
        }
        if !(0.0..=core::f32::consts::PI + 1e-6).contains(&self.sweep.angle_rad) {
            return Err(format!(
                "sweep_deg: expected [0, 180], got {}",
                self.sweep.angle_rad.to_degrees()
            ));
        }
        if self.sweep.angle_rad > 0.0
            && !(self.sweep.period_s > 0.0 && self.sweep.period_s <= 600.0)
        {
            return Err(format!(
                "sweep_period_s: expected (0, 600], got {}",
                self.sweep.period_s
            ));
        }
        self.schedule.validate()
    }
}

/// A jet at one instant: its aim and outlet speed fixed (the sweep and the
/// schedule applied) and what every point's evaluation shares worked out
/// once, so that many points are evaluated at one time without the sweep's
/// sine each.
///
/// A point's cost is bounded by where it lies: behind the outlet plane
/// nothing blows (no work past one dot product); beyond `BELL_REACH_SQ`
/// half-widths squared from the axis the bell's share is under f32's
/// rounding of one, so only the entrainment's inflow is left, a closed form
/// (a division, no exponential); inside, the whole profile. The inflow
/// falls only as 1/r (a 4 m/s, 0.4 m fan still draws 3 mm/s at 20 m), so no
/// distance cuts a jet off within a room. Distances are squared throughout:
/// across/r · 1/r is across/r², and (r/r½)² is r²/r½², with no square root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct JetNow {
    outlet: Vec3,
    /// A unit vector.
    aim: Vec3,
    /// Outlet speed, m/s.
    speed: f32,
    /// Where the potential core ends, m downstream.
    core: f32,
    /// The virtual origin, m downstream.
    origin: f32,
    /// U₀·B·D, m²/s: past the core the centreline speed is this / (x − x₀).
    decay: f32,
    /// The half-width at the outlet, m, and its growth per metre along the core.
    outlet_half_width: f32,
    core_spread: f32,
    /// (dQ/dx)/(2π) = 0.32·U₀·D/8, m²/s: the inflow's speed times r.
    entrainment: f32,
}

/// (r/r½)² beyond which the profile exp(−ln 2·(r/r½)²) = 2^−(r/r½)² is at
/// most 2⁻²⁵: 1 minus it rounds to 1 in f32, and the speed along it, at most
/// 30 m/s × 2⁻²⁵ < 1 µm/s, is below the rounding of the outlet speed. Past
/// it a point feels the inflow alone.
const BELL_REACH_SQ: f32 = 25.0;

impl JetNow {
    pub fn new(outlet: Vec3, aim: Vec3, diameter: f32, speed: f32) -> JetNow {
        let core = core_length(diameter);
        let outlet_half_width = 0.5 * diameter;
        JetNow {
            outlet,
            aim,
            speed,
            core,
            origin: JET_VIRTUAL_ORIGIN_D * diameter,
            decay: speed * JET_DECAY_B * diameter,
            outlet_half_width,
            core_spread: (half_width(diameter, core) - outlet_half_width) / core,
            entrainment: ENTRAINMENT * 0.125 * speed * diameter,
        }
    }

    /// The air's velocity at `p`, m/s: zero while the jet is off.
    #[inline]
    pub fn velocity_at(&self, p: Vec3) -> Vec3 {
        if self.speed == 0.0 {
            return Vec3::ZERO;
        }
        self.flow_at(p)
    }

    /// The jet's velocity at `p`, m/s: along the aim with the profile's
    /// speed, and the entrainment's inflow toward the axis,
    /// (dQ/dx)/(2π·r), faded inside the jet where the profile carries the flow.
    #[inline]
    pub fn flow_at(&self, p: Vec3) -> Vec3 {
        let offset = p - self.outlet;
        let x = offset.dot(self.aim);
        if x <= 0.0 {
            return Vec3::ZERO;
        }
        let across = offset - x * self.aim;
        let r_sq = across.length_squared();
        let r_half = if x >= self.core {
            JET_SPREAD_S * (x - self.origin)
        } else {
            self.outlet_half_width + self.core_spread * x
        };
        let r_half_sq = r_half * r_half;
        if r_sq >= BELL_REACH_SQ * r_half_sq {
            return -(self.entrainment / r_sq) * across;
        }
        let inside = libm::exp2f(-(r_sq / r_half_sq));
        let centreline = if x <= self.core {
            self.speed
        } else {
            self.decay / (x - self.origin)
        };
        let inflow = if r_sq > 1e-12 {
            self.entrainment * (1.0 - inside) / r_sq
        } else {
            0.0
        };
        (centreline * inside) * self.aim - inflow * across
    }
}

/// Where the potential core of a jet of `diameter` ends, m from the outlet.
fn core_length(diameter: f32) -> f32 {
    (JET_VIRTUAL_ORIGIN_D + JET_DECAY_B) * diameter
}

/// `Jet::centreline_fraction` of a jet of `diameter`.
fn centreline_fraction(diameter: f32, x: f32) -> f32 {
    if x < 0.0 {
        0.0
    } else if x <= core_length(diameter) {
        1.0
    } else {
        JET_DECAY_B * diameter / (x - JET_VIRTUAL_ORIGIN_D * diameter)
    }
}

/// `Jet::half_width` of a jet of `diameter`.
fn half_width(diameter: f32, x: f32) -> f32 {
    let core = core_length(diameter);
    let far = |x: f32| JET_SPREAD_S * (x - JET_VIRTUAL_ORIGIN_D * diameter);
    if x >= core {
        far(x)
    } else {
        let outlet = 0.5 * diameter;
        outlet + (far(core) - outlet) * (x.max(0.0) / core)
    }
}
