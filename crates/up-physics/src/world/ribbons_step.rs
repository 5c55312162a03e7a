//! The ribbons' stages of the step (`crate::ribbon`): `wake_ribbons` before
//! the broadphase, `prepare_ribbons` before the substeps (which solve them,
//! `ribbon::solve`), `finish_ribbons` after the continuous sweep.

use glam::Vec3;
use up_geom::norm::Norm;
use up_geom::Aabb;

use super::World;
use crate::ribbon::lane_group::Rest;
use crate::ribbon::nearby::{sphere_meets_box, NearbyBodies, Spheres};
use crate::ribbon::solve::ActiveRibbon;
use crate::ribbon::GRAB_MAX_SPEED;

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
    /// triangles and the balloons near each. Ribbons of sleepers stay still
    /// (one that a moving balloon reached was woken before the broadphase).
    pub(super) fn prepare_ribbons(&mut self) {
        let stage = &mut self.stages.ribbons;
        stage.awake = 0;
        stage.lanes.begin();
        stage.triangles.clear();
        stage.bodies.clear();
        let b = &self.bodies;
        let awake = |body| self.handles.dense(body).is_some_and(|i| b.awake[i]);
        if !self.ribbons.iter().any(|(_, r)| awake(r.body)) {
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
        for i in 0..n {
            let asleep = !b.awake[i];
            if asleep && found_asleep[i] {
                continue;
            }
            let shape = &self.shapes[b.shape[i] as usize];
            let reach = if asleep {
                0.0
            } else {
                b.linear_velocity[i].norm() * dt
            };
            centers[i] = b.center[i];
            radii[i] = shape.bound_radius * b.size[i].scale + reach + margin;
            found_asleep[i] = asleep;
        }
        let room = self.def.room.as_ref();
        let spheres = Spheres { centers, radii };
        lists.begin_step(spheres, room);
        let air_density = self.air.air_density();
        let grab = self.ribbon_grab;
        let mut count = 0;
        for (slot, ribbon) in self.ribbons.slots_mut().enumerate() {
            let Some(ribbon) = ribbon else { continue };
            let Some(i) = self.handles.dense(ribbon.body) else {
                continue;
            };
            // A sleeper's ribbon keeps its points and the (sleep-slow)
            // velocities it fell asleep with, as they are, until it wakes.
            if !b.awake[i] {
                continue;
            }
            if stage.active.len() == count {
                stage.active.push(ActiveRibbon::default());
            }
            let r = &mut stage.active[count];
            count += 1;
            r.slot = slot as u32;
            r.state = i as u32;
            r.user_data = b.user_data[i];
            r.origin = b.center[i];
            r.arm0 = b.rotation[i] * (ribbon.arm * b.size[i].scale);
            r.grab = grab
                .filter(|g| g.ribbon.index as usize == slot)
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
            let reach = speed * dt + margin + ribbon.radius(ribbon.segments());
            let aabb = Aabb::from_points(&ribbon.points).expanded(reach);
            // An anchored end is held where it is tied, a grabbed point
            // carried: no mass the chain's solve can move (`ActiveRibbon::inv_mass`).
            r.take(ribbon, air_density);
            let (first_body, first_triangle) = (stage.bodies.len(), stage.triangles.len());
            let (bodies, triangles) = (&mut stage.bodies, &mut stage.triangles);
            lists.near(slot, &aabb, spheres, room, bodies, triangles);
            r.bodies = first_body as u32..stage.bodies.len() as u32;
            r.triangles = first_triangle as u32..stage.triangles.len() as u32;
            // Points lying still rest, but not where ribbons touch each
            // other (their contacts move points the lanes hold) or a point
            // is carried.
            let rest = (!self.def.ribbon_contacts && r.grab.is_none()).then(|| Rest {
                triangles: &stage.triangles[first_triangle..],
                bodies: &stage.bodies[first_body..],
                centers: spheres.centers,
                radii: spheres.radii,
            });
            stage.lanes.add(r, ribbon, rest);
        }
        stage.awake = count;
        stage.lanes.finish_packing();
        stage.touch.enabled = self.def.ribbon_contacts;
        stage.touch.friction = self.def.ribbon_friction;
        stage.touch.find_pairs(&stage.lanes, dt, margin);
    }

    /// Hands the points back to the ribbons, each knot where its balloon
    /// ended the step; keeps the largest stretch; marks the balloons whose
    /// ribbons still move as a whole (their points' root-mean-square speed,
    /// or that past the knot, beyond the knot's own: a free end's millimetre
    /// sway alone keeps no pile awake) — those may not sleep yet — and those whose ribbons
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
        let slow = self.def.sleep_linear_speed;
        let mut max_stretch = self.ribbons.max_stretch;
        for (k, r) in stage.active[..stage.awake].iter_mut().enumerate() {
            let Some(ribbon) = self.ribbons.slot_mut(r.slot) else {
                continue;
            };
            stage.lanes.take_out(k, r, ribbon);
            r.give_back(ribbon);
            let i = r.state as usize;
            let arm = self.bodies.rotation[i] * (ribbon.arm * self.bodies.size[i].scale);
            ribbon.points[0] = self.bodies.center[i] + arm;
            ribbon.velocities[0] =
                self.bodies.linear_velocity[i] + self.bodies.angular_velocity[i].cross(arm);
            stage.point_boxes.forget(r.slot);
            if !ribbon.points.iter().all(|p| p.is_finite()) {
                self.stages.faults.non_finite.push(i);
                continue;
            }
            // Beyond what its knot moves: a balloon slow enough to rest (under
            // the sleep speeds) may still turn its knot at a few mm/s, and the
            // ribbon it drags must not keep it awake for that alone; a ribbon
            // swinging against its knot moves past it by its own speed and more.
            let knot_speed = ribbon.velocities[0].length();
            let speed = ribbon.rms_speed().max(ribbon.rms_speed_past_knot());
            stage.moving[i] =
                speed >= slow + knot_speed || r.air_speed >= crate::air::RESTLESS_AIR_SPEED;
            max_stretch = max_stretch.max(ribbon.stretch());
        }
        stage.lanes.clear();
        self.ribbons.max_stretch = max_stretch;
    }
}
