//! Adding, removing and reading joints (`crate::joint`).

use super::{PhysicsError, World};
use crate::body::BodyId;
use crate::joint::{DistanceJointDef, End, Joint, JointAnchor, JointId};

impl World {
    /// Adds a distance joint; wakes its bodies. Its ends are checked: a body
    /// that exists, finite points, a length > 0 m and a compliance ≥ 0 m/N.
    pub fn add_distance_joint(&mut self, def: &DistanceJointDef) -> Result<JointId, PhysicsError> {
        let bad = |why: &str| Err(PhysicsError::BadJoint(why.to_string()));
        if !(def.length.is_finite() && def.length > 0.0) {
            return bad("length must be finite and > 0 m");
        }
        if !(def.compliance.is_finite() && def.compliance >= 0.0) {
            return bad("compliance must be finite and ≥ 0 m/N");
        }
        let JointAnchor::Body { .. } = def.a else {
            return bad("end a must be on a body");
        };
        if def.a == def.b {
            return bad("the two ends are one point");
        }
        let ends = [self.end(&def.a)?, self.end(&def.b)?];
        for body in ends.iter().filter_map(End::body) {
            self.wake(body)?;
        }
        Ok(self.joints.add(Joint {
            ends,
            length: def.length,
            limit: def.limit,
            compliance: def.compliance,
            tension: 0.0,
        }))
    }

    /// An anchor as the solver holds it: a body's point about its centre of mass.
    fn end(&self, anchor: &JointAnchor) -> Result<End, PhysicsError> {
        match *anchor {
            JointAnchor::Fixed(point) if point.is_finite() => Ok(End::Fixed(point)),
            JointAnchor::Body { body, point } if point.is_finite() => {
                let i = self.dense(body)?;
                let center_of_mass = self.shapes[self.bodies.shape[i] as usize]
                    .def
                    .center_of_mass;
                Ok(End::Body {
                    body,
                    arm: point - center_of_mass,
                })
            }
            _ => Err(PhysicsError::NonFinite {
                what: "joint anchor",
            }),
        }
    }

    /// Removes a joint; wakes its bodies.
    pub fn remove_joint(&mut self, id: JointId) -> Result<(), PhysicsError> {
        let joint = self.joints.remove(id).ok_or(PhysicsError::StaleJoint(id))?;
        for body in joint.ends.iter().filter_map(End::body) {
            self.wake(body)?;
        }
        Ok(())
    }

    /// The tension a joint ended the last step with, N (0 when slack; < 0
    /// when a rod pushes).
    pub fn joint_tension(&self, id: JointId) -> Option<f32> {
        self.joints.get(id).map(|j| j.tension)
    }

    /// Where the two ends of a joint are now, world frame, m.
    pub fn joint_ends(&self, id: JointId) -> Option<[glam::Vec3; 2]> {
        let joint = self.joints.get(id)?;
        let at = |e: &End| match *e {
            End::Fixed(point) => Some(point),
            End::Body { body, arm } => {
                let i = self.handles.dense(body)?;
                Some(self.bodies.center[i] + self.bodies.rotation[i] * arm)
            }
        };
        Some([at(&joint.ends[0])?, at(&joint.ends[1])?])
    }

    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// The bodies joined to `body`.
    pub(super) fn joint_partners(&self, body: BodyId) -> Vec<BodyId> {
        let mut partners = Vec::new();
        for (_, joint) in self.joints.iter() {
            let [a, b] = joint.ends.map(|e| e.body());
            match (a, b) {
                (Some(a), Some(b)) if a == body && b != body => partners.push(b),
                (Some(a), Some(b)) if b == body && a != body => partners.push(a),
                _ => {}
            }
        }
        partners
    }

    /// This step's pairs of joined bodies, dense indices, for the sleep passes.
    pub(super) fn find_joined(&mut self) {
        let joined = &mut self.stages.joined;
        joined.clear();
        for (_, joint) in self.joints.iter() {
            let [a, b] = joint
                .ends
                .map(|e| e.body().and_then(|id| self.handles.dense(id)));
            if let (Some(a), Some(b)) = (a, b) {
                joined.push((a as u32, b as u32));
            }
        }
    }
}
