//! A draught through an open door or window: air crossing the opening at a
//! set velocity, which carries on into the room as a jet from an outlet of
//! the opening's area (a round jet of the same area: a door's slab of air is
//! only roughly round, and spreads as one here).

use glam::Vec3;
use serde::{Deserialize, Serialize};
use up_geom::norm::Norm;

use super::jet::{Jet, JetKind, JetNow};
use super::schedule::Schedule;

/// An opening the air moves through.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Draught {
    /// The opening's box, m (thin along the velocity).
    pub min: Vec3,
    pub max: Vec3,
    /// The air's velocity through the opening, m/s.
    pub velocity: Vec3,
    pub schedule: Schedule,
}

impl Draught {
    /// The jet the opening blows into the room: from the box's downstream
    /// face, of the box's area seen along the velocity, always on (the
    /// draught's own schedule scales it).
    pub fn jet(&self) -> Jet {
        let speed = self.velocity.norm();
        let aim = self.velocity / speed.max(1e-12);
        let size = self.max - self.min;
        let area = aim.x.abs() * size.y * size.z
            + aim.y.abs() * size.x * size.z
            + aim.z.abs() * size.x * size.y;
        let diameter = (4.0 * area / core::f32::consts::PI).sqrt();
        let centre = 0.5 * (self.min + self.max);
        let half_depth = 0.5 * (aim.abs().dot(size));
        Jet::new(
            JetKind::Vent,
            centre + half_depth * aim,
            aim,
            diameter,
            speed,
        )
    }

    /// The air's velocity at `p` at `t`, m/s: the set velocity inside the
    /// opening, the jet's beyond it.
    pub fn velocity_at(&self, p: Vec3, t: f64) -> Vec3 {
        self.now(t).velocity_at(p)
    }

    /// The draught as it blows at `t`.
    pub(crate) fn now(&self, t: f64) -> DraughtNow {
        let level = if self.velocity == Vec3::ZERO {
            0.0
        } else {
            self.schedule.level_at(t)
        };
        let jet = if level == 0.0 {
            None
        } else {
            let jet = self.jet();
            Some(JetNow::new(
                jet.outlet,
                jet.direction,
                jet.diameter,
                jet.speed * level,
            ))
        };
        DraughtNow {
            min: self.min,
            max: self.max,
            through: self.velocity * level,
            jet,
        }
    }

    pub fn validate(&self) -> Result<(), String> {
        if !(self.min.is_finite() && self.max.is_finite() && self.velocity.is_finite()) {
            return Err("min/max/velocity_m_s: expected finite numbers".into());
        }
        if !self.min.cmplt(self.max).all() {
            return Err(format!(
                "max: expected above min on every axis, got min {} max {}",
                self.min, self.max
            ));
        }
        if self.velocity.norm() > 30.0 {
            return Err(format!(
                "velocity_m_s: expected at most 30 m/s, got {}",
                self.velocity.norm()
            ));
        }
        self.schedule.validate()
    }
}

/// A draught at one instant (`Draught::now`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DraughtNow {
    min: Vec3,
    max: Vec3,
    /// The velocity inside the opening now, m/s.
    through: Vec3,
    /// The jet beyond it; None while the draught is off.
    jet: Option<JetNow>,
}

impl DraughtNow {
    /// The air's velocity at `p`, m/s.
    #[inline]
    pub fn velocity_at(&self, p: Vec3) -> Vec3 {
        let Some(jet) = &self.jet else {
            return Vec3::ZERO;
        };
        let inside = p.cmpge(self.min).all() && p.cmple(self.max).all();
        if inside {
            self.through
        } else {
            jet.flow_at(p)
        }
    }
}
