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

#[derive(Clone, Debug, Default, Serialize, Deserialize)]
struct Slot {
    generation: u32,
    joint: Option<Joint>,
}

/// The world's joints: slots reused through a free list, handles with
/// generations (as bodies' are).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct Joints {
    slots: Vec<Slot>,
    free: Vec<u32>,
}

impl Joints {
    pub fn add(&mut self, joint: Joint) -> JointId {
        let index = match self.free.pop() {
            Some(index) => index,
            None => {
                self.slots.push(Slot::default());
                self.slots.len() as u32 - 1
            }
        };
        let slot = &mut self.slots[index as usize];
        slot.joint = Some(joint);
        JointId {
            index,
            generation: slot.generation,
        }
    }

    pub fn get(&self, id: JointId) -> Option<&Joint> {
        let slot = self.slots.get(id.index as usize)?;
        (slot.generation == id.generation)
            .then_some(slot.joint.as_ref())
            .flatten()
    }

    pub fn remove(&mut self, id: JointId) -> Option<Joint> {
        let slot = self.slots.get_mut(id.index as usize)?;
        if slot.generation != id.generation {
            return None;
        }
        let joint = slot.joint.take()?;
        slot.generation = slot.generation.wrapping_add(1);
        self.free.push(id.index);
        Some(joint)
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
        self.slots.iter().enumerate().filter_map(|(index, slot)| {
            slot.joint.as_ref().map(|joint| {
                let id = JointId {
                    index: index as u32,
                    generation: slot.generation,
                };
                (id, joint)
            })
        })
    }

    pub fn len(&self) -> usize {
        self.slots.len() - self.free.len()
    }

    /// Writes the tension of the joint in slot `index`.
    pub fn set_tension(&mut self, index: u32, tension: f32) {
        if let Some(joint) = self.slots[index as usize].joint.as_mut() {
            joint.tension = tension;
        }
    }
}
