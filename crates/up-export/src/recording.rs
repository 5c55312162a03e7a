//! A run as frames: the scene's looks once (`SceneLooks`), then every
//! balloon's pose and size and every ribbon's points at each recorded
//! instant. `up export-gltf` records a frame per sample; the page's engine
//! records each frame it sends and keeps the last few seconds (`keep_s`),
//! so both write their `.glb` from the same data through the same code.

use std::collections::VecDeque;

use glam::{Quat, Vec3};
use up_physics::World;

use crate::looks::SceneLooks;

/// The world at one instant, in the order of the recording's looks.
#[derive(Clone, Debug, Default)]
pub struct Frame {
    /// Simulated seconds since the world was built.
    pub time: f64,
    /// Each balloon's mesh frame: position (m) and rotation.
    pub positions: Vec<Vec3>,
    pub rotations: Vec<Quat>,
    /// Each balloon's size over its model's (1 while its gas is as filled).
    pub scales: Vec<f32>,
    /// Every ribbon's points, ribbon after ribbon, the knot first, m.
    pub ribbon_points: Vec<Vec3>,
}

/// Frames of one world whose balloons and ribbons stay the same throughout.
#[derive(Clone, Debug)]
pub struct Recording {
    pub looks: SceneLooks,
    frames: VecDeque<Frame>,
    /// Keep only the frames of the last this many simulated seconds; None: all.
    keep_s: Option<f64>,
    /// Frames dropped from the front, reused so a warm ring allocates nothing.
    spare: Vec<Frame>,
    /// Simulated seconds per second of the animation (1: real time).
    pub time_scale: f64,
}

/// Why a world cannot be recorded into a recording.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mismatch {
    /// Balloons were added or removed, or ribbons tied or untied, since the
    /// recording began: start a new one.
    WorldChanged,
}

impl Recording {
    /// An empty recording of a world that looks like `looks`; `keep_s`
    /// bounds how much simulated time it holds (None: everything).
    pub fn new(looks: SceneLooks, keep_s: Option<f64>) -> Recording {
        Recording {
            looks,
            frames: VecDeque::new(),
            keep_s,
            spare: Vec::new(),
            time_scale: 1.0,
        }
    }

    /// The frames held, oldest first.
    pub fn frames(&self) -> impl ExactSizeIterator<Item = &Frame> {
        self.frames.iter()
    }

    pub fn frame_count(&self) -> usize {
        self.frames.len()
    }

    /// Forgets every frame (the looks stay).
    pub fn clear(&mut self) {
        self.spare.extend(self.frames.drain(..));
    }

    /// Whether `world` has the balloons and ribbons of the looks, in order.
    pub fn matches(&self, world: &World) -> bool {
        let looks = &self.looks;
        let ids = world.body_ids();
        if ids.len() != looks.balloons.len()
            || ids
                .iter()
                .zip(&looks.balloons)
                .any(|(id, b)| id.index != b.id)
        {
            return false;
        }
        let ribbons = world.ribbon_ids();
        ribbons.len() == looks.ribbons.len()
            && ribbons.iter().zip(&looks.ribbons).all(|(&r, look)| {
                world.ribbon_body(r).map(|b| b.index) == Some(look.balloon)
                    && world.ribbon_points(r).map(<[Vec3]>::len) == Some(look.points)
            })
    }

    /// Records the world as it is now. A frame at the time of the last one
    /// replaces it (a frame sent again without a step), so times increase.
    pub fn record(&mut self, world: &World) -> Result<(), Mismatch> {
        if !self.matches(world) {
            return Err(Mismatch::WorldChanged);
        }
        let time = world.time();
        if self.frames.back().is_some_and(|last| last.time >= time) {
            if let Some(replaced) = self.frames.pop_back() {
                self.spare.push(replaced);
            }
        }
        let mut frame = self.spare.pop().unwrap_or_default();
        frame.time = time;
        frame.positions.clear();
        frame.rotations.clear();
        frame.scales.clear();
        frame.ribbon_points.clear();
        for (id, pose) in world.poses() {
            frame.positions.push(pose.position);
            frame.rotations.push(pose.rotation);
            frame.scales.push(world.body_scale(id).unwrap_or(1.0));
        }
        for r in world.ribbon_ids() {
            if let Some(points) = world.ribbon_points(r) {
                frame.ribbon_points.extend_from_slice(points);
            }
        }
        self.frames.push_back(frame);
        if let Some(keep) = self.keep_s {
            while self
                .frames
                .front()
                .is_some_and(|first| time - first.time > keep)
            {
                if let Some(old) = self.frames.pop_front() {
                    self.spare.push(old);
                }
            }
        }
        Ok(())
    }

    /// The animation's time of a frame, s: from the first frame, at `time_scale`.
    pub fn animation_time(&self, frame: &Frame) -> f32 {
        let start = self.frames.front().map_or(0.0, |f| f.time);
        ((frame.time - start) / self.time_scale) as f32
    }
}
