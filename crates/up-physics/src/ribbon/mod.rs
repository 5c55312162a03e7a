//! Ribbons: light strings tied to a balloon's knot, with a weight at the free
//! end if wanted. A ribbon is a chain of point masses (its segments' masses
//! lumped at their ends) held at fixed distances: inextensible, free to bend.
//!
//! It is solved with the balloons, in the same substeps (`solve`): after the
//! substep has moved the bodies, each awake ribbon's points move under gravity
//! and air drag, are pushed out of the room and the balloons near them
//! (`collide`), and the whole chain, knot included, is brought back to its
//! segments' lengths by one direct solve (`chain`): the Lagrange multipliers
//! of all its distance constraints at once, from a tridiagonal system, where
//! Gauss–Seidel would need as many sweeps as the chain has points for the
//! knot to feel the whole ribbon's weight. The knot's share of that solve is
//! an impulse on the balloon (two-way), so the balloon carries exactly the
//! ribbon it lifts. The awake ribbons are solved four at a time, a ribbon a
//! SIMD lane, in groups of one segment count (`lane_group`), each lane bit
//! for bit what its ribbon gives alone.
//!
//! A ribbon's free end may be tied to a fixed point (`RibbonDef::anchor`):
//! the solve holds it there as a point of infinite mass, which the direct
//! solve takes as it takes a held point, so the ribbon holds its balloon
//! within its length of the point.
//!
//! Balloons push ribbons aside and take the opposite impulse (a few
//! milligrams' worth); where the world asks for it
//! (`WorldDef::ribbon_contacts`), ribbons touch each other, and themselves,
//! as capsules with friction (`touch`); otherwise they pass through each
//! other. A ribbon
//! sleeps and wakes with its balloon, and keeps its balloon awake while it
//! still moves.

mod body_spheres;
pub(crate) mod chain;
pub(crate) mod collide;
mod hang_path;
pub(crate) mod lane_group;
mod lane_pushes;
mod lane_room;
mod lane_substep;
mod leaf_capsule;
pub(crate) mod nearby;
pub(crate) mod solve;
pub(crate) mod touch;

pub use hang_path::hang_path;
pub use touch::{
    crossings, linking, RibbonContact, OVERLAP_PUSH_OUT_SPEED, RIBBON_ON_RIBBON_FRICTION,
};

use std::collections::BTreeMap;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::body::BodyId;
use crate::slots::Slots;

/// Mass per metre of 5 mm polypropylene curling ribbon, kg/m. No measured
/// figure was found: BOPP film of 20–60 µm gives 0.1–0.3 g/m; an estimate.
pub const DEFAULT_MASS_PER_LENGTH: f32 = 0.25e-3;
/// Collision radius of a ribbon's points: half its 5 mm width, m.
pub const RIBBON_RADIUS: f32 = 0.0025;
/// Width of the ribbon the air sees, m.
pub const RIBBON_WIDTH: f32 = 0.005;
/// Collision radius of a balloon weight at the free end, m (a small foil weight).
pub const WEIGHT_RADIUS: f32 = 0.025;
/// Drag coefficient of the ribbon moving across its length at high Reynolds
/// numbers (a flat strip broadside, ≈ 1.2; a guess for a strip that twists).
/// Slow, the air is viscous: the coefficient grows as C = C∞ + 10/Re (Re on
/// the width; the order of Lamb's drag on a cylinder at Re ≈ 1, a viscous
/// force linear in the speed), which is what stills a ribbon's last swing
/// (quadratic drag alone would take minutes to damp a 1 cm/s sway).
pub const NORMAL_DRAG_COEFFICIENT: f32 = 1.2;
/// Viscosity of air at 20 °C, Pa·s.
pub const AIR_VISCOSITY: f32 = 1.81e-5;
/// Drag coefficient along its length, on its width (skin friction; a guess).
pub const TANGENT_DRAG_COEFFICIENT: f32 = 0.02;
/// Drag coefficient of the weight at high Reynolds numbers, on its
/// cross-section (a sphere, ≈ 0.5); slow, Stokes's 24/Re is added.
pub const WEIGHT_DRAG_COEFFICIENT: f32 = 0.5;
/// Friction of a ribbon point on the room's surfaces (a guess).
pub const ROOM_FRICTION: f32 = 0.5;
/// Friction of a ribbon point on latex (a guess).
pub const BALLOON_FRICTION: f32 = 0.5;
/// Fastest a grabbed point is carried toward its target, m/s.
pub const GRAB_MAX_SPEED: f32 = 10.0;
/// Segments of a ribbon, at least and at most.
pub const MIN_SEGMENTS: u32 = 2;
pub const MAX_SEGMENTS: u32 = 128;

/// A ribbon to tie to a balloon.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RibbonDef {
    /// The balloon; it holds at most one ribbon.
    pub body: BodyId,
    /// Where the ribbon is tied, in the body's mesh frame (the frame of
    /// `BodyDef::pose`): the bottom of the balloon's neck, m.
    pub knot: Vec3,
    /// m, > 0.
    pub length: f32,
    /// kg/m, > 0.
    pub mass_per_length: f32,
    /// Points after the knot; [`MIN_SEGMENTS`, `MAX_SEGMENTS`].
    pub segments: u32,
    /// A weight tied to the free end, kg (0: none).
    pub end_mass: f32,
    /// Where the free end is tied, world frame, m (None: it hangs free): the
    /// end is held there, as a point of infinite mass in the chain's solve,
    /// so the ribbon holds its balloon within its length of the point.
    #[serde(default)]
    pub anchor: Option<Vec3>,
}

impl RibbonDef {
    /// A ribbon of `length` m in `segments` of the default ribbon, no weight.
    pub fn new(body: BodyId, knot: Vec3, length: f32, segments: u32) -> RibbonDef {
        RibbonDef {
            body,
            knot,
            length,
            mass_per_length: DEFAULT_MASS_PER_LENGTH,
            segments,
            end_mass: 0.0,
            anchor: None,
        }
    }
}

/// Generational handle of a ribbon; stale once the ribbon is removed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct RibbonId {
    pub index: u32,
    pub generation: u32,
}

/// A ribbon in the world: its points (0 at the knot) and their velocities.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Ribbon {
    pub body: BodyId,
    /// The knot from the body's centre of mass, body frame, m.
    pub arm: Vec3,
    pub segment_length: f32,
    /// Mass of each point after the knot but the last, kg: the segment above
    /// it, so the points weigh the whole ribbon and the knot none of it.
    pub point_mass: f32,
    /// Mass of the last point: its segment and the weight, kg.
    pub end_mass: f32,
    /// The weight tied at the end, kg (0: none); sets the end's radius and drag.
    pub weight: f32,
    pub points: Vec<Vec3>,
    pub velocities: Vec<Vec3>,
    /// The ribbon's mean pull on the knot over the last step it was awake, N.
    pub pull: Vec3,
    /// Where its free end is tied (`RibbonDef::anchor`).
    pub anchor: Option<Vec3>,
}

impl Ribbon {
    pub fn segments(&self) -> usize {
        self.points.len() - 1
    }

    pub fn length(&self) -> f32 {
        self.segment_length * self.segments() as f32
    }

    /// Collision radius of point `i`, m.
    pub fn radius(&self, i: usize) -> f32 {
        if i == self.segments() && self.weight > 0.0 {
            WEIGHT_RADIUS
        } else {
            RIBBON_RADIUS
        }
    }

    /// Length along the points divided by the ribbon's length, less one.
    pub fn stretch(&self) -> f32 {
        let along: f32 = self.points.windows(2).map(|p| p[0].distance(p[1])).sum();
        along / self.length() - 1.0
    }

    /// Root-mean-square speed of its points (the knot's left out), m/s.
    pub fn rms_speed(&self) -> f32 {
        let sum: f32 = self.velocities[1..]
            .iter()
            .map(|v| v.length_squared())
            .sum();
        (sum / self.segments() as f32).sqrt()
    }

    /// Root-mean-square speed of the points past the knot relative to the
    /// knot, m/s: 0 for a ribbon its balloon drags along rigidly.
    pub fn rms_speed_past_knot(&self) -> f32 {
        let knot = self.velocities[0];
        let sum: f32 = self.velocities[1..]
            .iter()
            .map(|v| (*v - knot).length_squared())
            .sum();
        (sum / self.segments() as f32).sqrt()
    }

    /// Total mass, weight included, kg.
    pub fn total_mass(&self) -> f32 {
        self.point_mass * (self.segments() - 1) as f32 + self.end_mass
    }
}

/// The world's ribbons, in generational slots (`crate::slots`).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct Ribbons {
    slots: Slots<Ribbon>,
    /// Each balloon's ribbon (a balloon holds at most one), ordered so that
    /// snapshots come out the same.
    by_body: BTreeMap<BodyId, RibbonId>,
    /// The largest stretch any ribbon ended a step with since the world was
    /// made (`World::ribbon_max_stretch`).
    pub max_stretch: f32,
}

impl Ribbons {
    pub fn add(&mut self, ribbon: Ribbon) -> RibbonId {
        let body = ribbon.body;
        let (index, generation) = self.slots.add(ribbon);
        let id = RibbonId { index, generation };
        self.by_body.insert(body, id);
        id
    }

    pub fn get(&self, id: RibbonId) -> Option<&Ribbon> {
        self.slots.get(id.index, id.generation)
    }

    pub fn remove(&mut self, id: RibbonId) -> Option<Ribbon> {
        let ribbon = self.slots.remove(id.index, id.generation)?;
        self.by_body.remove(&ribbon.body);
        Some(ribbon)
    }

    /// The ribbon tied to `body`.
    pub fn on(&self, body: BodyId) -> Option<RibbonId> {
        self.by_body.get(&body).copied()
    }

    /// Live ribbons in slot order (the solver's order).
    pub fn iter(&self) -> impl Iterator<Item = (RibbonId, &Ribbon)> + '_ {
        self.slots
            .iter()
            .map(|(index, generation, ribbon)| (RibbonId { index, generation }, ribbon))
    }

    /// The ribbon in slot `index`, whatever its generation.
    pub fn slot(&self, index: u32) -> Option<&Ribbon> {
        self.slots.slot(index)
    }

    /// Every slot, live or free, by index (`Slots::as_mut_slice`).
    pub fn as_mut_slice(&mut self) -> &mut [crate::slots::Slot<Ribbon>] {
        self.slots.as_mut_slice()
    }

    /// Slots live or free: one past the largest index.
    pub fn slot_count(&self) -> usize {
        self.slots.slot_count()
    }

    pub fn slot_mut(&mut self, index: u32) -> Option<&mut Ribbon> {
        self.slots.slot_mut(index)
    }

    pub fn len(&self) -> usize {
        self.slots.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
