//! Adding, removing, grabbing and reading ribbons (`crate::ribbon`); their
//! part of the step is `ribbons_step`.

use glam::Vec3;
use up_geom::norm::Norm;

use super::{PhysicsError, World};
use crate::body::BodyId;
use crate::ribbon::{
    hang_path, Ribbon, RibbonDef, RibbonId, MAX_SEGMENTS, MIN_SEGMENTS, RIBBON_RADIUS,
    WEIGHT_RADIUS,
};

/// A ribbon point held by the pointer.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct RibbonGrab {
    pub ribbon: RibbonId,
    pub point: u32,
    pub target: Vec3,
}

impl World {
    /// Ties a ribbon to a balloon's knot; wakes the balloon. The ribbon
    /// starts hanging straight down from the knot, along the floor where it
    /// reaches it; one with an anchor starts sagging from the knot to the
    /// anchor at its length. Refused, naming why: a body that does not exist
    /// or already has a ribbon, a length or mass per metre not finite and
    /// above 0, segments outside [2, 128], a weight not finite and ≥ 0, an
    /// anchor not finite or farther from the knot than the ribbon's length.
    pub fn add_ribbon(&mut self, def: &RibbonDef) -> Result<RibbonId, PhysicsError> {
        let bad = |why: String| Err(PhysicsError::BadRibbon(why));
        if !(def.length.is_finite() && def.length > 0.0) {
            return bad(format!("length {} m: expected finite and > 0", def.length));
        }
        if !(def.mass_per_length.is_finite() && def.mass_per_length > 0.0) {
            return bad(format!(
                "mass per metre {} kg/m: expected finite and > 0",
                def.mass_per_length
            ));
        }
        if !(MIN_SEGMENTS..=MAX_SEGMENTS).contains(&def.segments) {
            return bad(format!(
                "{} segments: expected {MIN_SEGMENTS} to {MAX_SEGMENTS}",
                def.segments
            ));
        }
        if !(def.end_mass.is_finite() && def.end_mass >= 0.0) {
            return bad(format!(
                "weight {} kg: expected finite and ≥ 0",
                def.end_mass
            ));
        }
        if !def.knot.is_finite() {
            return Err(PhysicsError::NonFinite { what: "knot" });
        }
        if def.anchor.is_some_and(|a| !a.is_finite()) {
            return Err(PhysicsError::NonFinite { what: "anchor" });
        }
        let i = self.dense(def.body)?;
        if self.ribbons.on(def.body).is_some() {
            return bad(format!("body {:?} already has a ribbon", def.body));
        }
        let center_of_mass = self.shapes[self.bodies.shape[i] as usize]
            .def
            .center_of_mass;
        // At the shape's size: the knot moves in as its balloon shrinks.
        let arm = def.knot - center_of_mass;
        let knot =
            self.bodies.center[i] + self.bodies.rotation[i] * (arm * self.bodies.size[i].scale);
        let segments = def.segments as usize;
        let segment_length = def.length / segments as f32;
        let point_mass = def.mass_per_length * segment_length;
        let mut ribbon = Ribbon {
            body: def.body,
            arm,
            segment_length,
            point_mass,
            end_mass: point_mass + def.end_mass,
            weight: def.end_mass,
            points: Vec::new(),
            velocities: vec![Vec3::ZERO; segments + 1],
            pull: Vec3::ZERO,
            anchor: def.anchor,
        };
        ribbon.points = match def.anchor {
            None => self.hang(knot, &ribbon, segments),
            Some(anchor) => {
                let reach = knot.distance(anchor);
                if reach > def.length * (1.0 + 1e-4) {
                    return bad(format!(
                        "anchor {reach} m from the knot, beyond the ribbon's {} m",
                        def.length
                    ));
                }
                let down = self.def.gravity.try_normalize().unwrap_or(Vec3::NEG_Y);
                sag(knot, anchor, segment_length, segments, down)
            }
        };
        self.wake(def.body)?;
        let id = self.ribbons.add(ribbon);
        self.stages.ribbons.point_boxes.forget(id.index);
        Ok(id)
    }

    /// Points straight down from `knot` (along gravity), turning along the
    /// floor toward the room's middle where they reach it, and round its
    /// walls: a ribbon laid out inside the room.
    fn hang(&self, knot: Vec3, ribbon: &Ribbon, n: usize) -> Vec<Vec3> {
        let down = self.def.gravity.try_normalize().unwrap_or(Vec3::NEG_Y);
        let bounds = self.def.room.as_ref().map(|room| {
            let end_radius = if ribbon.weight > 0.0 {
                WEIGHT_RADIUS
            } else {
                RIBBON_RADIUS
            };
            let margin = end_radius + 1e-3;
            let b = room.aabb();
            (b.min + margin, b.max - margin)
        });
        hang_path(knot, down, ribbon.segment_length, n, bounds)
    }

    /// Unties and removes a ribbon; wakes its balloon.
    pub fn remove_ribbon(&mut self, id: RibbonId) -> Result<(), PhysicsError> {
        let ribbon = self
            .ribbons
            .remove(id)
            .ok_or(PhysicsError::StaleRibbon(id))?;
        self.stages.ribbons.point_boxes.forget(id.index);
        if self.ribbon_grab.is_some_and(|g| g.ribbon == id) {
            self.ribbon_grab = None;
        }
        self.wake(ribbon.body)
    }

    /// Removes the ribbon of a body being removed.
    pub(super) fn remove_ribbon_on(&mut self, body: BodyId) {
        if let Some(id) = self.ribbons.on(body) {
            let _ = self.remove_ribbon(id);
        }
    }

    /// Turns the ribbons' contacts with each other on or off from the next
    /// step (`WorldDef::ribbon_contacts`).
    pub fn set_ribbon_contacts(&mut self, on: bool) {
        self.def.ribbon_contacts = on;
        if !on {
            self.stages.ribbons.touch.touching.clear();
        }
    }

    /// Sets the friction of a ribbon on a ribbon (`WorldDef::ribbon_friction`).
    pub fn set_ribbon_friction(&mut self, friction: f32) -> Result<(), PhysicsError> {
        super::def::within(&super::limits::FRICTION, "ribbon_friction", friction)?;
        self.def.ribbon_friction = friction;
        Ok(())
    }

    /// Pairs of ribbon segments that may touch this step (found before
    /// the substeps; 0 with contacts off or no ribbon awake).
    pub fn ribbon_contact_pairs(&self) -> usize {
        self.stages.ribbons.touch.pairs.len()
    }

    /// Where ribbons touched each other at the last step's end (pairs
    /// within a millimetre of touching): for drawing; empty once contacts
    /// are turned off.
    pub fn ribbon_contacts(&self) -> &[crate::ribbon::RibbonContact] {
        &self.stages.ribbons.touch.touching
    }

    pub fn ribbon_count(&self) -> usize {
        self.ribbons.len()
    }

    /// The ribbons, in a stable order (the solver's).
    pub fn ribbon_ids(&self) -> Vec<RibbonId> {
        self.ribbons.iter().map(|(id, _)| id).collect()
    }

    /// The ribbon tied to `body`.
    pub fn ribbon_of(&self, body: BodyId) -> Option<RibbonId> {
        self.ribbons.on(body)
    }

    /// The balloon a ribbon is tied to.
    pub fn ribbon_body(&self, id: RibbonId) -> Option<BodyId> {
        self.ribbons.get(id).map(|r| r.body)
    }

    /// A ribbon's points, world frame, m: the knot first, the free end last.
    pub fn ribbon_points(&self, id: RibbonId) -> Option<&[Vec3]> {
        self.ribbons.get(id).map(|r| &r.points[..])
    }

    /// Its points' velocities, m/s, in the same order.
    pub fn ribbon_velocities(&self, id: RibbonId) -> Option<&[Vec3]> {
        self.ribbons.get(id).map(|r| &r.velocities[..])
    }

    /// Points of all ribbons together (each ribbon has its segments + 1).
    pub fn ribbon_point_count(&self) -> usize {
        self.ribbons.iter().map(|(_, r)| r.points.len()).sum()
    }

    /// Writes every ribbon's points, ribbon after ribbon in `ribbon_ids`
    /// order, as x, y, z floats into `out` (3 × `ribbon_point_count`).
    pub fn write_ribbon_points(&self, out: &mut [f32]) {
        let points = self.ribbons.iter().flat_map(|(_, r)| r.points.iter());
        for (chunk, p) in out.chunks_exact_mut(3).zip(points) {
            chunk.copy_from_slice(&p.to_array());
        }
    }

    /// What the ribbon pulls its knot with, N, world frame: the mean over the
    /// last step its balloon was awake.
    pub fn ribbon_pull(&self, id: RibbonId) -> Option<Vec3> {
        self.ribbons.get(id).map(|r| r.pull)
    }

    /// Its length along its points over its length, less one: now.
    pub fn ribbon_stretch(&self, id: RibbonId) -> Option<f32> {
        self.ribbons.get(id).map(Ribbon::stretch)
    }

    /// The largest stretch any ribbon ended a step with since the world was made.
    pub fn ribbon_max_stretch(&self) -> f32 {
        self.ribbons.max_stretch
    }

    /// Its length, m, and mass with its weight, kg.
    pub fn ribbon_length_and_mass(&self, id: RibbonId) -> Option<(f32, f32)> {
        self.ribbons.get(id).map(|r| (r.length(), r.total_mass()))
    }

    /// Starts carrying point `point` of a ribbon (the free end is its
    /// segment count) toward `set_grab_target`'s target, at up to
    /// `GRAB_MAX_SPEED`; its balloon follows on the ribbon. Replaces any grab.
    pub fn grab_ribbon(
        &mut self,
        id: RibbonId,
        point: usize,
        target: Vec3,
    ) -> Result<(), PhysicsError> {
        if !target.is_finite() {
            return Err(PhysicsError::NonFinite {
                what: "grab target",
            });
        }
        let ribbon = self.ribbons.get(id).ok_or(PhysicsError::StaleRibbon(id))?;
        if point == 0 || point > ribbon.segments() {
            return Err(PhysicsError::BadRibbon(format!(
                "point {point}: expected 1 to {} (0 is the knot)",
                ribbon.segments()
            )));
        }
        if ribbon.anchor.is_some() && point == ribbon.segments() {
            return Err(PhysicsError::BadRibbon(format!(
                "point {point}: the free end is tied to its anchor"
            )));
        }
        let body = ribbon.body;
        self.wake(body)?;
        self.grab = None;
        self.ribbon_grab = Some(RibbonGrab {
            ribbon: id,
            point: point as u32,
            target,
        });
        Ok(())
    }

    /// The ribbon and point held, if a ribbon is.
    pub fn grabbed_ribbon(&self) -> Option<(RibbonId, usize)> {
        self.ribbon_grab.map(|g| (g.ribbon, g.point as usize))
    }

    /// Lays a ribbon's points (the knot first) where given, at rest: a
    /// ribbon wound round another, or two twisted together, for a test or a
    /// tool. Refused, naming why: not one point a segment end, a point not
    /// finite, the first farther than 1 mm from the knot, a segment more
    /// than 1 % off the ribbon's segment length, an anchored end away from
    /// its anchor. Wakes its balloon.
    pub fn set_ribbon_points(&mut self, id: RibbonId, points: &[Vec3]) -> Result<(), PhysicsError> {
        let ribbon = self.ribbons.get(id).ok_or(PhysicsError::StaleRibbon(id))?;
        let bad = |why: String| Err(PhysicsError::BadRibbon(why));
        if points.len() != ribbon.points.len() {
            return bad(format!(
                "{} points: expected {}",
                points.len(),
                ribbon.points.len()
            ));
        }
        if !points.iter().all(|p| p.is_finite()) {
            return Err(PhysicsError::NonFinite {
                what: "ribbon point",
            });
        }
        if points[0].distance(ribbon.points[0]) > 1e-3 {
            return bad(format!(
                "first point {} m from the knot",
                points[0].distance(ribbon.points[0])
            ));
        }
        let length = ribbon.segment_length;
        if let Some(k) = (1..points.len())
            .find(|&k| (points[k].distance(points[k - 1]) - length).abs() > 0.01 * length)
        {
            return bad(format!(
                "segment {k} {} m long: expected {length} m",
                points[k].distance(points[k - 1])
            ));
        }
        if let Some(anchor) = ribbon.anchor {
            if points.last().unwrap().distance(anchor) > 1e-3 {
                return bad("the free end away from its anchor".to_string());
            }
        }
        let body = ribbon.body;
        let ribbon = self.ribbons.slot_mut(id.index).expect("a live ribbon");
        ribbon.points[1..].copy_from_slice(&points[1..]);
        ribbon.velocities.iter_mut().for_each(|v| *v = Vec3::ZERO);
        self.stages.ribbons.point_boxes.forget(id.index);
        self.wake(body)
    }
}

/// `n` points from `knot` to `anchor`, `segment` apart, sagging along
/// `down`: the corners of a regular polygon's arc whose chord joins them
/// (a ribbon tied at both ends, laid out at its length). The arc's step
/// angle φ solves d/s = sin(n·φ/2) / sin(φ/2), which falls from n to 0 as φ
/// goes from 0 to 2π/n; bisected, so the layout is the same everywhere.
fn sag(knot: Vec3, anchor: Vec3, segment: f32, n: usize, down: Vec3) -> Vec<Vec3> {
    let chord = anchor - knot;
    let d = chord.norm();
    let nf = n as f32;
    if d >= segment * nf * (1.0 - 1e-6) {
        // Taut: straight from the knot to the anchor.
        return (0..=n).map(|i| knot + chord * (i as f32 / nf)).collect();
    }
    let u = if d > 1e-9 {
        chord / d
    } else {
        down.any_orthonormal_vector()
    };
    let w = (down - down.dot(u) * u)
        .try_normalize()
        .unwrap_or_else(|| u.any_orthonormal_vector());
    let ratio = d / segment;
    let (mut lo, mut hi) = (0.0f32, 2.0 * std::f32::consts::PI / nf);
    for _ in 0..64 {
        let phi = 0.5 * (lo + hi);
        if libm::sinf(0.5 * nf * phi) / libm::sinf(0.5 * phi) > ratio {
            lo = phi;
        } else {
            hi = phi;
        }
    }
    let phi = 0.5 * (lo + hi);
    let radius = segment / (2.0 * libm::sinf(0.5 * phi));
    let center = knot + 0.5 * chord - w * (radius * libm::cosf(0.5 * nf * phi));
    let mut points: Vec<Vec3> = (0..=n)
        .map(|i| {
            let theta = (i as f32 - 0.5 * nf) * phi;
            center + radius * (libm::sinf(theta) * u + libm::cosf(theta) * w)
        })
        .collect();
    // Exactly at its ends, whatever the rounding.
    points[0] = knot;
    points[n] = anchor;
    points
}
