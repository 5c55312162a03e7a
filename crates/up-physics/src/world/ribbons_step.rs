//! The ribbons' stages of the step (`crate::ribbon`): `wake_ribbons` before
//! the broadphase, `prepare_ribbons` before the substeps (which solve them,
//! `ribbon::solve`), `finish_ribbons` after the continuous sweep.

use glam::Vec3;
use up_geom::norm::Norm;
use up_geom::{Aabb, TriMesh};

use super::ribbons::RibbonGrab;
use super::World;
use crate::body::{Bodies, HandleMap};
use crate::ribbon::lane_group::{Rest, RibbonLanes};
use crate::ribbon::nearby::{
    sphere_meets_box, NearFinder, NearFound, NearbyBodies, RibbonList, Spheres,
};
use crate::ribbon::solve::ActiveRibbon;
use crate::ribbon::{Ribbon, Ribbons, GRAB_MAX_SPEED};
use crate::threading::tasks::{for_each_run, for_each_run_collect, Ragged, TaskList};

/// Restless bodies at most that the wake pass tests against every sleeping
/// ribbon without hashing them.
const FEW_RESTLESS: usize = 16;

/// Ribbon pairs this close at a step's end are listed as touching (for drawing), m.
const TOUCHING_WITHIN: f32 = 1e-3;

impl World {
    /// Wakes the balloons whose sleeping ribbons a moving balloon reaches
    /// (its bounding sphere, widened by its motion this step, meets a point),
    /// so that the ribbon is pushed aside instead of passed through. Before
    /// the broadphase, from where the last step left the bodies.
    pub(super) fn wake_touched_ribbons(&mut self) {
        let b = &self.bodies;
        let stage = &mut self.stages.ribbons;
        stage.bound_center.clear();
        stage.bound_radius.clear();
        stage.awake_bodies.clear();
        // Only a sleeping ribbon is woken: with none (a room without
        // ribbons, or every ribbon awake) the bodies are not even looked at.
        let asleep = |body| self.handles.dense(body).is_some_and(|i| !b.awake[i]);
        if !self.ribbons.iter().any(|(_, r)| asleep(r.body)) {
            return;
        }
        // A balloon slower than the sleep speed pushes no ribbon aside to
        // speak of: waking a ribbon for it would keep a pile awake for ever,
        // each group woken by its neighbours as it falls asleep.
        let (slow, turning) = (self.def.sleep_linear_speed, self.def.sleep_angular_speed);
        let restless = |i: usize| {
            b.awake[i]
                && (b.linear_velocity[i].norm() >= slow || b.angular_velocity[i].norm() >= turning)
        };
        for i in (0..b.len()).filter(|&i| restless(i)) {
            let shape = &self.shapes[b.shape[i] as usize];
            let reach = b.linear_velocity[i].norm() * self.def.dt + self.def.speculative_distance;
            stage.bound_center.push(b.center[i]);
            stage
                .bound_radius
                .push(shape.bound_radius * b.size[i].scale + reach);
            stage.awake_bodies.push(i as u32);
        }
        if stage.awake_bodies.is_empty() {
            return;
        }
        // A few restless bodies are tested against each ribbon directly:
        // a grid's cells would cost more to walk than they spare.
        let few = stage.awake_bodies.len() <= FEW_RESTLESS;
        if !few {
            let restless = &mut stage.nearby.restless;
            restless.build(&stage.bound_center, &stage.bound_radius);
        }
        // The box around every restless sphere: a ribbon apart from it is
        // reached by none (most sleeping ribbons, while few bodies move).
        let (centers, radii) = (&stage.bound_center, &stage.bound_radius);
        let spheres = centers.iter().zip(radii);
        let restless_box = spheres.fold(Aabb::EMPTY, |b, (&c, &r)| {
            b.union(Aabb::new(c - Vec3::splat(r), c + Vec3::splat(r)))
        });
        let mut touched = std::mem::take(&mut stage.touched);
        touched.clear();
        for (id, ribbon) in self.ribbons.iter() {
            let Some(i) = self.handles.dense(ribbon.body) else {
                continue;
            };
            if b.awake[i] {
                continue;
            }
            // A sleeper's ribbon has not moved since its box was kept.
            let aabb = stage
                .point_boxes
                .of(id.index, ribbon)
                .expanded(ribbon.radius(ribbon.segments()));
            if !aabb.overlaps(&restless_box) {
                continue;
            }
            let (restless, found) = (&mut stage.nearby.restless, &mut stage.found);
            found.clear();
            let (centers, radii) = (&stage.bound_center, &stage.bound_radius);
            if few {
                let meets =
                    |k: &u32| sphere_meets_box(centers[*k as usize], radii[*k as usize], &aabb);
                found.extend((0..centers.len() as u32).filter(meets));
            } else {
                restless.query(&aabb, centers, radii, found);
            }
            let reached = found.iter().any(|&k| {
                let (c, r) = (
                    stage.bound_center[k as usize],
                    stage.bound_radius[k as usize],
                );
                let other = stage.awake_bodies[k as usize] as usize;
                other != i
                    && ribbon.points.iter().enumerate().any(|(p, point)| {
                        point.distance_squared(c) < (r + ribbon.radius(p)).powi(2)
                    })
            });
            if reached {
                touched.push(ribbon.body);
            }
        }
        for &body in &touched {
            // A ribbon's body exists while the ribbon does.
            let _ = self.wake(body);
        }
        self.stages.ribbons.touched = touched;
    }

    /// Takes the awake ribbons' points for the solve, and finds the room's
    /// triangles and the balloons near each, ribbons side by side in tasks
    /// (`RibbonPrep`); then lays them out in lanes, in slot order. Ribbons of
    /// sleepers stay still (one that a moving balloon reached was woken
    /// before the broadphase).
    pub(super) fn prepare_ribbons(&mut self) {
        let stage = &mut self.stages.ribbons;
        stage.awake = 0;
        stage.lanes.begin();
        stage.near.reset();
        let b = &self.bodies;
        let awake = |body| self.handles.dense(body).is_some_and(|i| b.awake[i]);
        stage.awake_slots.clear();
        let slots = self.ribbons.iter().filter(|(_, r)| awake(r.body));
        stage.awake_slots.extend(slots.map(|(id, _)| id.index));
        if stage.awake_slots.is_empty() {
            stage.touch.pairs.clear();
            // An awake body may move and fall asleep elsewhere before the
            // spheres are next found: its kept one is no longer a sleeper's.
            let found_asleep = stage.nearby.asleep.iter_mut();
            found_asleep.zip(&b.awake).for_each(|(f, &a)| *f &= !a);
            return; // every ribbon sleeps, or there are none
        }
        let n = self.bodies.len();
        let dt = self.def.dt;
        let fall = 0.5 * self.def.gravity.norm() * dt * dt;
        let margin = self.def.speculative_distance + fall;
        let NearbyBodies {
            centers,
            radii,
            asleep: found_asleep,
            margin: found_margin,
            lists,
            ..
        } = &mut stage.nearby;
        // A sleeper's sphere stays as it was found (it neither moves nor
        // changes size while it sleeps); bodies coming or going (dense
        // indices shift) or another margin find every sphere again.
        if centers.len() != n || *found_margin != margin {
            found_asleep.clear();
            found_asleep.resize(n, false);
            centers.resize(n, Vec3::ZERO);
            radii.resize(n, 0.0);
            *found_margin = margin;
        }
        let shapes = &self.shapes;
        let parts = (&mut centers[..], &mut radii[..], &mut found_asleep[..]);
        for_each_run(n, BODY_CHUNK, parts, |first, (centers, radii, found)| {
            for (k, found_asleep) in found.iter_mut().enumerate() {
                let i = first + k;
                let asleep = !b.awake[i];
                if asleep && *found_asleep {
                    continue;
                }
                let shape = &shapes[b.shape[i] as usize];
                let reach = if asleep {
                    0.0
                } else {
                    b.linear_velocity[i].norm() * dt
                };
                centers[k] = b.center[i];
                radii[k] = shape.bound_radius * b.size[i].scale + reach + margin;
                *found_asleep = asleep;
            }
        });
        let room = self.def.room.as_ref();
        let spheres = Spheres { centers, radii };
        lists.begin_step(spheres, room);
        let count = stage.awake_slots.len();
        if stage.active.len() < count {
            stage.active.resize_with(count, ActiveRibbon::default);
        }
        let (finder, slot_lists) = lists.split(self.ribbons.slot_count());
        let prep = RibbonPrep {
            world: WorldView {
                bodies: &self.bodies,
                handles: &self.handles,
                ribbons: &self.ribbons,
            },
            finder,
            spheres,
            room,
            dt,
            margin,
            air_density: self.air.air_density(),
            grab: self.ribbon_grab,
            rests: !self.def.ribbon_contacts,
        };
        let awake_slots = &stage.awake_slots;
        let parts = (
            &mut stage.active[..count],
            Ragged::new(slot_lists, awake_slots),
        );
        let (tasks, near) = (&mut stage.near_tasks, &mut stage.near);
        for_each_run_collect(
            count,
            RIBBON_CHUNK,
            parts,
            tasks,
            near,
            |first, run, found| {
                let (active, mut lists) = run;
                for (k, r) in active.iter_mut().enumerate() {
                    let slot = awake_slots[first + k];
                    prep.take(slot, r, &mut lists.item(k)[0], found);
                }
            },
        );
        lists.found_count += stage.near.found;
        // Each ribbon's candidates were counted from its task's lists' start.
        let (mut first_body, mut first_triangle) = (0, 0);
        for r in &mut stage.active[..count] {
            let (bodies, triangles) = (r.bodies.len() as u32, r.triangles.len() as u32);
            r.bodies = first_body..first_body + bodies;
            r.triangles = first_triangle..first_triangle + triangles;
            (first_body, first_triangle) = (r.bodies.end, r.triangles.end);
        }
        for r in &stage.active[..count] {
            // Its slot holds it: it was found awake above.
            if let Some(ribbon) = self.ribbons.slot(r.slot) {
                stage.lanes.assign(ribbon.segments(), r.rest_tail as usize);
            }
        }
        stage.lanes.pack(&stage.active[..count], &self.ribbons);
        stage.awake = count;
        stage.touch.enabled = self.def.ribbon_contacts;
        stage.touch.friction = self.def.ribbon_friction;
        stage.touch.find_pairs(&stage.lanes, dt, margin);
    }

    /// Hands the points back to the ribbons, each knot where its balloon
    /// ended the step, ribbons side by side in tasks (`finish_ribbon`);
    /// keeps the largest stretch; marks the balloons whose ribbons still
    /// move as a whole — those may not sleep yet — and those whose ribbons
    /// went non-finite (quarantined with them).
    pub(super) fn finish_ribbons(&mut self) {
        let stage = &mut self.stages.ribbons;
        let n = self.bodies.len();
        stage.moving.clear();
        stage.moving.resize(n, false);
        stage.touch.touching.clear();
        if self.ribbons.is_empty() {
            stage.lanes.clear();
            return;
        }
        if !stage.touch.is_empty() {
            stage
                .touch
                .keep_touching(&stage.lanes.groups, TOUCHING_WITHIN);
        }
        let count = stage.awake;
        let (lanes, b) = (&stage.lanes, &self.bodies);
        let slow = self.def.sleep_linear_speed;
        let parts = (
            &mut stage.active[..count],
            Ragged::new(self.ribbons.as_mut_slice(), &stage.awake_slots[..count]),
        );
        for_each_run(count, RIBBON_CHUNK, parts, |first, (active, mut slots)| {
            for (k, r) in active.iter_mut().enumerate() {
                if let Some(ribbon) = slots.item(k)[0].item_mut() {
                    finish_ribbon(first + k, r, ribbon, lanes, b, slow);
                }
            }
        });
        let mut max_stretch = self.ribbons.max_stretch;
        for r in &stage.active[..count] {
            stage.point_boxes.forget(r.slot);
            let i = r.state as usize;
            if !r.finite {
                self.stages.faults.non_finite.push(i);
                continue;
            }
            stage.moving[i] = r.moving;
            max_stretch = max_stretch.max(r.stretch);
        }
        stage.lanes.clear();
        self.ribbons.max_stretch = max_stretch;
    }
}

/// Awake ribbons at most one task takes ready or hands back.
const RIBBON_CHUNK: usize = 128;
/// Bodies whose spheres one task finds.
const BODY_CHUNK: usize = 2048;

/// What readying an awake ribbon for the step reads (`World::prepare_ribbons`).
struct RibbonPrep<'a> {
    world: WorldView<'a>,
    finder: NearFinder<'a>,
    spheres: Spheres<'a>,
    room: Option<&'a TriMesh>,
    dt: f32,
    margin: f32,
    air_density: f32,
    grab: Option<RibbonGrab>,
    /// Whether points lying still may rest (not where ribbons touch each
    /// other: their contacts move points the lanes hold).
    rests: bool,
}

/// The bodies and ribbons a task reads.
#[derive(Clone, Copy)]
struct WorldView<'a> {
    bodies: &'a Bodies,
    handles: &'a HandleMap,
    ribbons: &'a Ribbons,
}

impl RibbonPrep<'_> {
    /// Readies the awake ribbon in `slot` as `r`: its figures, the balloons
    /// and triangles near it pushed into `found` (its ranges counted from
    /// the list's start), from its kept `list`, and its resting tail.
    fn take(&self, slot: u32, r: &mut ActiveRibbon, list: &mut RibbonList, found: &mut NearFound) {
        let WorldView {
            bodies: b,
            handles,
            ribbons,
        } = self.world;
        r.slot = slot;
        (r.bodies, r.triangles) = (0..0, 0..0);
        // Awake ribbons' slots hold ribbons of existing bodies.
        let Some(ribbon) = ribbons.slot(slot) else {
            return;
        };
        let Some(i) = handles.dense(ribbon.body) else {
            return;
        };
        let dt = self.dt;
        r.state = i as u32;
        r.user_data = b.user_data[i];
        r.origin = b.center[i];
        r.arm0 = b.rotation[i] * (ribbon.arm * b.size[i].scale);
        r.grab = self
            .grab
            .filter(|g| g.ribbon.index == slot)
            .map(|g| (g.point as usize, g.target));
        if let Some((k, target)) = r.grab {
            let distance = target.distance(ribbon.points[k]);
            r.grab_speed = (distance / dt).min(GRAB_MAX_SPEED);
        }
        // The root of the largest square: the largest root, one root taken.
        let speed = ribbon
            .velocities
            .iter()
            .fold(0.0f32, |m, v| m.max(v.length_squared()))
            .sqrt();
        let reach = speed * dt + self.margin + ribbon.radius(ribbon.segments());
        let aabb = Aabb::from_points(&ribbon.points).expanded(reach);
        // An anchored end is held where it is tied, a grabbed point
        // carried: no mass the chain's solve can move (`ActiveRibbon::inv_mass`).
        r.take(ribbon, self.air_density);
        let (first_body, first_triangle) = (found.bodies.len(), found.triangles.len());
        let (bodies, triangles) = (&mut found.bodies, &mut found.triangles);
        let spheres = self.spheres;
        if self
            .finder
            .near(list, &aabb, spheres, self.room, bodies, triangles)
        {
            found.found += 1;
        }
        r.bodies = first_body as u32..found.bodies.len() as u32;
        r.triangles = first_triangle as u32..found.triangles.len() as u32;
        // Points lying still rest, but not where a point is carried.
        let rest = (self.rests && r.grab.is_none()).then(|| Rest {
            triangles: &found.triangles[first_triangle..],
            bodies: &found.bodies[first_body..],
            centers: spheres.centers,
            radii: spheres.radii,
        });
        r.rest_tail = rest.map_or(0, |rest| rest.tail(ribbon)) as u32;
    }
}

/// Hands the `k`th awake ribbon's points back to `ribbon` from the lanes,
/// its knot where its balloon ended the step; notes in `r` whether it went
/// non-finite, its stretch, and whether it moves as a whole (its points'
/// root-mean-square speed, or that past the knot, beyond the knot's own: a
/// free end's millimetre sway alone keeps no pile awake).
fn finish_ribbon(
    k: usize,
    r: &mut ActiveRibbon,
    ribbon: &mut Ribbon,
    lanes: &RibbonLanes,
    b: &Bodies,
    slow: f32,
) {
    lanes.take_out(k, r, ribbon);
    r.give_back(ribbon);
    let i = r.state as usize;
    let arm = b.rotation[i] * (ribbon.arm * b.size[i].scale);
    ribbon.points[0] = b.center[i] + arm;
    ribbon.velocities[0] = b.linear_velocity[i] + b.angular_velocity[i].cross(arm);
    r.finite = ribbon.points.iter().all(|p| p.is_finite());
    if !r.finite {
        return;
    }
    // Beyond what its knot moves: a balloon slow enough to rest (under
    // the sleep speeds) may still turn its knot at a few mm/s, and the
    // ribbon it drags must not keep it awake for that alone; a ribbon
    // swinging against its knot moves past it by its own speed and more.
    let knot_speed = ribbon.velocities[0].length();
    let speed = ribbon.rms_speed().max(ribbon.rms_speed_past_knot());
    r.moving = speed >= slow + knot_speed || r.air_speed >= crate::air::RESTLESS_AIR_SPEED;
    r.stretch = ribbon.stretch();
}
