//! What the world's calls answer when they refuse.

use thiserror::Error;

use crate::body::BodyId;
use crate::joint::JointId;
use crate::ribbon::RibbonId;

#[derive(Debug, Error, PartialEq)]
pub enum PhysicsError {
    #[error("invalid world parameter `{key}` = {value}: expected {expected}")]
    BadParameter {
        key: &'static str,
        value: f32,
        expected: String,
    },
    #[error("invalid temperature_schedule: {0}")]
    BadSchedule(String),
    #[error("invalid balloon shape: {0}")]
    BadShape(String),
    #[error("unknown shape {0}")]
    UnknownShape(u32),
    #[error("body {0:?} does not exist (removed, or from another world)")]
    StaleBody(BodyId),
    #[error("non-finite {what}")]
    NonFinite { what: &'static str },
    #[error("the world is full: at most {0} bodies")]
    Full(usize),
    #[error("joint {0:?} does not exist (removed with a body, or from another world)")]
    StaleJoint(JointId),
    #[error("invalid joint: {0}")]
    BadJoint(String),
    #[error("ribbon {0:?} does not exist (removed with its balloon, or from another world)")]
    StaleRibbon(RibbonId),
    #[error("invalid ribbon: {0}")]
    BadRibbon(String),
}
