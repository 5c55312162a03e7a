//! Joints: constraints between bodies, or a body and the room, that are not
//! contacts. They live in the world's state (snapshots keep them) and are
//! solved in the same substeps as the contacts, at position level
//! (`solver::joint_constraint`): a distance held by moving positions, not by
//! pushing velocities, keeps its length whatever the masses at its ends, which
//! is what a light chain on a heavy balloon needs (Müller et al. 2020,
//! "Detailed rigid body simulation with extended position based dynamics").
//!
//! The one kind today is the distance joint: a rope (at most its length) or a
//! rod (exactly its length), rigid or with a compliance.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::body::BodyId;
use crate::slots::Slots;

/// Generational handle of a joint; stale once the joint is removed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct JointId {
    pub index: u32,
    pub generation: u32,
}

/// One end of a joint.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum JointAnchor {
    /// A point fixed to a body, in the body's mesh frame (the frame of
    /// `BodyDef::pose`), m.
    Body { body: BodyId, point: Vec3 },
    /// A point fixed in the room, world frame, m.
    Fixed(Vec3),
}

/// What a distance joint holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum DistanceLimit {
    /// At most `length`: slack (no force) when the ends are closer, like a
    /// ribbon or a tether.
    Rope,
    /// Exactly `length`: pushes as well as pulls.
    Rod,
}

/// A distance joint between two anchors.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DistanceJointDef {
    /// Must be on a body.
    pub a: JointAnchor,
    pub b: JointAnchor,
    /// m, > 0.
    pub length: f32,
    pub limit: DistanceLimit,
    /// Stretch per newton of tension, m/N; 0 is inextensible (XPBD's α).
    pub compliance: f32,
}

/// One end as the solver needs it: a body and its point about the centre of
/// mass (body frame), or a world point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) enum End {
    Body { body: BodyId, arm: Vec3 },
    Fixed(Vec3),
}

impl End {
    pub fn body(&self) -> Option<BodyId> {
        match *self {
            End::Body { body, .. } => Some(body),
            End::Fixed(_) => None,
        }
    }
}

/// A joint in the world.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Joint {
    pub ends: [End; 2],
    pub length: f32,
    pub limit: DistanceLimit,
    pub compliance: f32,
    /// The tension the last step ended with, N (0 when slack).
    pub tension: f32,
}

/// The world's joints, in generational slots (`crate::slots`).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct Joints(Slots<Joint>);

impl Joints {
    pub fn add(&mut self, joint: Joint) -> JointId {
        let (index, generation) = self.0.add(joint);
        JointId { index, generation }
    }

    pub fn get(&self, id: JointId) -> Option<&Joint> {
        self.0.get(id.index, id.generation)
    }

    pub fn remove(&mut self, id: JointId) -> Option<Joint> {
        self.0.remove(id.index, id.generation)
    }

    /// Removes every joint with an end on `body`.
    pub fn remove_on(&mut self, body: BodyId) {
        let doomed: Vec<JointId> = self
            .iter()
            .filter(|(_, j)| j.ends.iter().any(|e| e.body() == Some(body)))
            .map(|(id, _)| id)
            .collect();
        for id in doomed {
            self.remove(id);
        }
    }

    /// Live joints in slot order (the solver's order before colouring).
    pub fn iter(&self) -> impl Iterator<Item = (JointId, &Joint)> + '_ {
        self.0
            .iter()
            .map(|(index, generation, joint)| (JointId { index, generation }, joint))
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Writes the tension of the joint in slot `index`.
    pub fn set_tension(&mut self, index: u32, tension: f32) {
        if let Some(joint) = self.0.slot_mut(index) {
            joint.tension = tension;
        }
    }
}
