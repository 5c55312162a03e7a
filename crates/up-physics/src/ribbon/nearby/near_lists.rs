//! Each ribbon's candidate balloons and room triangles, kept for several
//! steps.
//!
//! A step asks which bodies' widened spheres meet a ribbon's widened box
//! (the ribbon's step reach, `World::prepare_ribbons`). Hashing every body
//! each step for that is most of the cost, and little moves in a step, so:
//! every body is anchored in a sphere `MARGIN` wider than its sphere was
//! when anchored (`anchor`), and a ribbon's list holds the bodies whose
//! anchors meet its box widened by `MARGIN` (its `reach`). The test is
//! taken in a frame that moves with the crowd (`drift`, the bodies' median
//! move since they were anchored: any shift of everything at once keeps
//! which spheres meet which boxes), so a crowd rising together keeps its
//! lists. While a body's sphere, shifted back by the drift, stays within its
//! anchor, and a ribbon's box within its reach, any body that meets the box
//! is on the list: each step checks the first (one distance a body), and a
//! ribbon whose box left its reach finds its list again among the anchors.
//! Bodies out of their anchors (`loose`) are tested against every ribbon
//! directly (those in its span along x, found by bisection); once more than
//! a sixteenth of them are, every body is anchored afresh. A body whose
//! sphere is as it was at the last step (a sleeper) keeps its verdict while
//! the drift holds, and the drift is taken again only once at least half
//! of the bodies moved: so in a room where one balloon moves among
//! sleepers a step checks one distance, not every body's. The room does not
//! drift: a ribbon's triangles are those whose boxes meet its box widened by
//! `ROOM_MARGIN`, found again when the box leaves that.
//!
//! A list is a superset: each step keeps of it exactly the bodies whose
//! spheres meet the box, in body order, and exactly the triangles whose
//! boxes meet it, in the room's tree order (as its query gives them). So the
//! candidates are the same whatever steps ago the lists were found: the same
//! after a snapshot is restored (which starts without lists), on any number
//! of threads.

use glam::Vec3;
use up_geom::{Aabb, TriMesh};

use super::sphere_grid::{sphere_meets_box, SphereGrid};
use crate::ribbon::collide::NearTriangle;

/// How much wider than a body's sphere its anchor is, and a ribbon's reach
/// than its box, m: a balloon rising at 1 m/s leaves its anchor after about
/// six steps of 1/60 s. Wider keeps the lists longer but makes them longer.
pub(crate) const MARGIN: f32 = 0.1;
/// How much wider than a ribbon's box the box its room triangles were
/// found for is, m: the room's triangles are few and large, a longer list of
/// them costs little.
pub(crate) const ROOM_MARGIN: f32 = 0.25;
/// Bodies whose move the drift is the median of, at most.
const DRIFT_SAMPLES: usize = 1024;
/// Taken off the anchors and the reaches when checking that a sphere or a
/// box is within them, m: more than the rounding of the distances and
/// bounds involved in a room of a few hundred metres.
const SLACK: f32 = 1e-4;

/// Loose bodies tolerated before every body is anchored afresh: those in a
/// ribbon's span along x are tested against it, each step.
fn most_loose(bodies: usize) -> usize {
    8 + bodies / 16
}

/// Whether `inner` lies within `outer`, `SLACK` inside its faces.
fn within(inner: &Aabb, outer: &Aabb) -> bool {
    let outer = outer.expanded(-SLACK);
    outer.min.cmple(inner.min).all() && inner.max.cmple(outer.max).all()
}

/// The bodies' spheres this step, as the lists test them (dense order).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spheres<'a> {
    pub centers: &'a [Vec3],
    pub radii: &'a [f32],
}

/// One ribbon's candidates, found for `reach`.
#[derive(Clone, Debug)]
pub(crate) struct RibbonList {
    /// The anchoring the lists were found in (0: none yet).
    epoch: u32,
    /// In the anchors' frame (the drift taken off).
    reach: Aabb,
    /// Dense body indices, ascending.
    bodies: Vec<u32>,
    room_reach: Aabb,
    /// Room triangles in the order the room's tree gives them.
    triangles: Vec<u32>,
    /// Each of `triangles` as the pushes read it (its edge lines found once
    /// a list, not once a step: the room does not move).
    near: Vec<NearTriangle>,
}

impl Default for RibbonList {
    fn default() -> RibbonList {
        RibbonList {
            epoch: 0,
            reach: Aabb::EMPTY,
            bodies: Vec::new(),
            room_reach: Aabb::EMPTY,
            triangles: Vec::new(),
            near: Vec::new(),
        }
    }
}

/// The lists of every ribbon (by slot), and the bodies' anchors.
#[derive(Clone, Debug, Default)]
pub(crate) struct NearLists {
    anchor_center: Vec<Vec3>,
    anchor_radius: Vec<f32>,
    /// The anchors hashed, for finding a list.
    grid: SphereGrid,
    /// The bodies' median move since they were anchored, this step.
    drift: Vec3,
    /// Each body's sphere at the last `begin_step`, and whether it was
    /// within its anchor then (for the same anchoring and drift).
    last_center: Vec<Vec3>,
    last_radius: Vec<f32>,
    last_anchored: Vec<bool>,
    /// The moves sampled for it, a buffer.
    moves: [Vec<f32>; 3],
    /// The anchoring; lists of an earlier one are found again.
    epoch: u32,
    /// The room's triangle count when anchored (its triangles are listed by index).
    room_triangles: usize,
    /// Bodies out of their anchors this step, by their centres' x (then
    /// body), and the largest of their radii.
    loose: Vec<(f32, u32)>,
    loose_radius: f32,
    lists: Vec<RibbonList>,
    /// Lists found (again) and anchorings, since the world was made: how
    /// often the lists are kept is what they save.
    pub found_count: u64,
    pub anchor_count: u64,
}

impl NearLists {
    /// Before the ribbons' lists are asked for this step: finds the bodies
    /// out of their anchors, and anchors every body afresh if too many are.
    pub fn begin_step(&mut self, spheres: Spheres, room: Option<&TriMesh>) {
        let n = spheres.centers.len();
        let room_triangles = room.map_or(0, TriMesh::triangle_count);
        self.loose.clear();
        if self.epoch == 0 || self.anchor_center.len() != n || self.room_triangles != room_triangles
        {
            self.anchor(spheres, room_triangles);
            return;
        }
        // Bodies whose spheres moved since the last step; the rest keep
        // their verdicts while the drift holds.
        // Equal as numbers: a NaN counts as moved (and is tested again),
        // and a zero that changed sign moved nothing.
        let same = |i: usize, last_center: &[Vec3], last_radius: &[f32]| {
            spheres.centers[i] == last_center[i] && spheres.radii[i] == last_radius[i]
        };
        let (last_center, last_radius) = (&self.last_center, &self.last_radius);
        let moved = (0..n)
            .filter(|&i| !same(i, last_center, last_radius))
            .count();
        // The median moves only once half of the bodies do.
        let drift_holds = 2 * moved < n;
        if !drift_holds {
            self.drift = self.median_move(spheres.centers);
        }
        let most = most_loose(n);
        self.loose_radius = 0.0;
        for i in 0..n {
            let (center, radius) = (spheres.centers[i], spheres.radii[i]);
            let anchored = if drift_holds && same(i, &self.last_center, &self.last_radius) {
                self.last_anchored[i]
            } else {
                let out = (center - self.drift).distance(self.anchor_center[i]) + radius;
                // False for a non-finite body: it counts as loose.
                out <= self.anchor_radius[i] - SLACK
            };
            self.last_center[i] = center;
            self.last_radius[i] = radius;
            self.last_anchored[i] = anchored;
            if !anchored {
                if !center.is_finite() || radius.is_nan() {
                    continue; // no box meets it
                }
                self.loose.push((center.x, i as u32));
                self.loose_radius = self.loose_radius.max(radius);
                if self.loose.len() > most {
                    self.anchor(spheres, room_triangles);
                    return;
                }
            }
        }
        self.loose
            .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }

    /// Per axis, the median of the moves since anchoring of evenly spaced
    /// bodies (zero where they are not finite).
    fn median_move(&mut self, centers: &[Vec3]) -> Vec3 {
        let every = centers.len().div_ceil(DRIFT_SAMPLES).max(1);
        let mut drift = [0.0f32; 3];
        for (axis, moves) in self.moves.iter_mut().enumerate() {
            moves.clear();
            let sampled = centers.iter().zip(&self.anchor_center).step_by(every);
            moves.extend(sampled.map(|(c, a)| c[axis] - a[axis]));
            if moves.is_empty() {
                continue;
            }
            let middle = moves.len() / 2;
            let (_, &mut m, _) = moves.select_nth_unstable_by(middle, f32::total_cmp);
            drift[axis] = if m.is_finite() { m } else { 0.0 };
        }
        Vec3::from(drift)
    }

    /// Every body anchored where its sphere is now; every list to be found again.
    fn anchor(&mut self, spheres: Spheres, room_triangles: usize) {
        self.anchor_center.clear();
        self.anchor_center.extend_from_slice(spheres.centers);
        self.anchor_radius.clear();
        self.anchor_radius
            .extend(spheres.radii.iter().map(|r| r + MARGIN));
        self.grid.build(&self.anchor_center, &self.anchor_radius);
        self.drift = Vec3::ZERO;
        // Every body within its anchor, where it is now.
        self.last_center.clone_from(&self.anchor_center);
        self.last_radius.clear();
        self.last_radius.extend_from_slice(spheres.radii);
        self.last_anchored.clear();
        self.last_anchored.resize(spheres.centers.len(), true);
        self.epoch = self.epoch.wrapping_add(1).max(1);
        self.room_triangles = room_triangles;
        self.loose.clear();
        self.anchor_count += 1;
    }

    /// What this step's lists are found from, and every slot's list (at
    /// least `slots` of them): a ribbon's list is its own, the rest is
    /// read alone, so ribbons may be listed side by side.
    /// After `begin_step`.
    pub fn split(&mut self, slots: usize) -> (NearFinder<'_>, &mut [RibbonList]) {
        if self.lists.len() < slots {
            self.lists.resize_with(slots, RibbonList::default);
        }
        let finder = NearFinder {
            anchor_center: &self.anchor_center,
            anchor_radius: &self.anchor_radius,
            grid: &self.grid,
            drift: self.drift,
            epoch: self.epoch,
            loose: &self.loose,
            loose_radius: self.loose_radius,
        };
        (finder, &mut self.lists)
    }
}

/// The anchors, the drift and the loose bodies of a step, which every
/// ribbon's list is kept or found again from (`NearLists::split`).
pub(crate) struct NearFinder<'a> {
    anchor_center: &'a [Vec3],
    anchor_radius: &'a [f32],
    grid: &'a SphereGrid,
    drift: Vec3,
    epoch: u32,
    loose: &'a [(f32, u32)],
    loose_radius: f32,
}

impl NearFinder<'_> {
    /// Appends to `bodies` every body whose sphere meets `aabb` (the box of
    /// the ribbon whose list is `list` this step), ascending, and to
    /// `triangles` every room triangle (but degenerate ones) whose box
    /// meets it, in the room's tree order; finds the list again first if
    /// `aabb` left its reach, and then says so.
    pub fn near(
        &self,
        list: &mut RibbonList,
        aabb: &Aabb,
        spheres: Spheres,
        room: Option<&TriMesh>,
        bodies: &mut Vec<u32>,
        triangles: &mut Vec<NearTriangle>,
    ) -> bool {
        let fresh = list.epoch != self.epoch;
        list.epoch = self.epoch;
        let shifted = Aabb::new(aabb.min - self.drift, aabb.max - self.drift);
        let found = fresh || !within(&shifted, &list.reach);
        if found {
            list.reach = shifted.expanded(MARGIN);
            list.bodies.clear();
            let (centers, radii) = (self.anchor_center, self.anchor_radius);
            self.grid
                .query(&list.reach, centers, radii, &mut list.bodies);
            list.bodies.sort_unstable();
        }
        if fresh || !within(aabb, &list.room_reach) {
            list.room_reach = aabb.expanded(ROOM_MARGIN);
            list.triangles.clear();
            list.near.clear();
            if let Some(room) = room {
                room.query_aabb(&list.room_reach, |t| list.triangles.push(t));
                let near = list.triangles.iter();
                let near = near.map(|&t| NearTriangle::new(room.triangle(t), room.normal(t)));
                list.near.extend(near);
            }
        }
        let first = bodies.len();
        let meets =
            |i: u32| sphere_meets_box(spheres.centers[i as usize], spheres.radii[i as usize], aabb);
        bodies.extend(list.bodies.iter().copied().filter(|&i| meets(i)));
        let listed = bodies.len();
        let from = aabb.min.x - self.loose_radius;
        let to = aabb.max.x + self.loose_radius;
        let start = self.loose.partition_point(|&(x, _)| x < from);
        for &(_, i) in self.loose[start..].iter().take_while(|&&(x, _)| x <= to) {
            if list.bodies.binary_search(&i).is_err() && meets(i) {
                bodies.push(i);
            }
        }
        if bodies.len() > listed {
            bodies[first..].sort_unstable();
        }
        if let Some(room) = room {
            for (&t, near) in list.triangles.iter().zip(&list.near) {
                if !room.is_degenerate(t) && room.triangle_aabb(t).overlaps(aabb) {
                    triangles.push(*near);
                }
            }
        }
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed box room of 10 × 4 × 10 m, each face in 2 × 2 quads.
    fn room() -> TriMesh {
        let mut vertices = Vec::new();
        let mut triangles = Vec::new();
        let (lo, hi) = (Vec3::new(-5.0, 0.0, -5.0), Vec3::new(5.0, 4.0, 5.0));
        for axis in 0..3 {
            for side in [0.0f32, 1.0] {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let first = vertices.len() as u32;
                for a in 0..3 {
                    for b in 0..3 {
                        let mut p = lo;
                        p[axis] = lo[axis] + side * (hi[axis] - lo[axis]);
                        p[u] = lo[u] + a as f32 * 0.5 * (hi[u] - lo[u]);
                        p[v] = lo[v] + b as f32 * 0.5 * (hi[v] - lo[v]);
                        vertices.push(p);
                    }
                }
                for a in 0..2 {
                    for b in 0..2 {
                        let k = first + 3 * a + b;
                        triangles.push([k, k + 3, k + 1]);
                        triangles.push([k + 1, k + 3, k + 4]);
                    }
                }
            }
        }
        TriMesh::new(vertices, triangles).expect("a valid room")
    }

    /// Over a crowd that drifts up together while some of it wanders, a few
    /// bodies jump far and some fall still, for many steps (so lists are kept,
    /// found again, and everything anchored afresh now and then): each
    /// ribbon's bodies are exactly those whose spheres meet its box, in body
    /// order, and its triangles exactly the room's query for the box.
    #[test]
    fn lists_give_what_testing_every_body_and_the_room_gives() {
        let mut next = crate::hash::uniform(11);
        let mut random = move |scale: f32| Vec3::new(next(), next(), next()) * scale;
        let room = room();
        let n = 600;
        let mut centers: Vec<Vec3> = (0..n)
            .map(|_| random(1.0) * Vec3::new(9.0, 3.0, 9.0) - Vec3::new(4.5, 0.0, 4.5))
            .collect();
        let mut radii: Vec<f32> = (0..n).map(|_| 0.1 + 0.15 * random(1.0).x).collect();
        // Ribbons hang from the first bodies: a box below each.
        let ribbons = 200;
        let mut sway: Vec<Vec3> = vec![Vec3::ZERO; ribbons];
        let mut lists = NearLists::default();
        let (mut kept, mut found) = (0u64, 0u64);
        for step in 0..240 {
            let rise = Vec3::Y * if step < 120 { 0.03 } else { 0.0 };
            for (i, c) in centers.iter_mut().enumerate() {
                // Late on, most of the crowd stands still (sleepers): the
                // drift holds and their verdicts are kept.
                if step >= 180 && i % 10 != 0 {
                    continue;
                }
                let wander = (random(2.0) - 1.0) * if i % 3 == 0 { 0.02 } else { 0.004 };
                *c += rise + wander;
                if i % 97 == step % 97 {
                    *c += (random(2.0) - 1.0) * 0.5; // a jump: loose
                }
            }
            for r in radii
                .iter_mut()
                .step_by(7)
                .take(if step >= 180 { 3 } else { n })
            {
                *r = (*r + 0.01 * (random(2.0).x - 1.0)).clamp(0.05, 0.3);
            }
            let spheres = Spheres {
                centers: &centers,
                radii: &radii,
            };
            lists.begin_step(spheres, Some(&room));
            let (mut bodies, mut triangles) = (Vec::new(), Vec::new());
            for (slot, s) in sway.iter_mut().enumerate() {
                *s = (*s + (random(2.0) - 1.0) * 0.01).clamp(Vec3::splat(-0.3), Vec3::splat(0.3));
                let knot = centers[slot] + *s;
                let aabb = Aabb::new(knot - Vec3::new(0.1, 1.5, 0.1), knot + Vec3::splat(0.1));
                let aabb = aabb.expanded(0.02 * random(1.0).x);
                bodies.clear();
                triangles.clear();
                let (finder, slots) = lists.split(ribbons);
                let list = &mut slots[slot];
                let near_room = Some(&room);
                if finder.near(list, &aabb, spheres, near_room, &mut bodies, &mut triangles) {
                    found += 1;
                } else {
                    kept += 1;
                }
                let want: Vec<u32> = (0..n as u32)
                    .filter(|&i| sphere_meets_box(centers[i as usize], radii[i as usize], &aabb))
                    .collect();
                assert_eq!(bodies, want, "step {step}, ribbon {slot}");
                let mut want = Vec::new();
                room.query_aabb(&aabb, |t| {
                    if !room.is_degenerate(t) {
                        want.push(room.triangle(t));
                    }
                });
                let got: Vec<[Vec3; 3]> = triangles.iter().map(|t| t.corners).collect();
                assert_eq!(got, want, "step {step}, ribbon {slot}");
            }
        }
        // The test means something only if lists were both kept and found again.
        assert!(lists.anchor_count > 1, "never anchored afresh");
        assert!(kept > 2 * found, "kept {kept}, found {found}");
    }
}
