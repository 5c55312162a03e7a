//! Building a scene into a `World`: the room, one balloon model per group,
//! and every balloon placed without overlap, deterministically from `sim.seed`,
//! filled with its gas (`gas_fill`: its group's envelope, its own leak
//! factor, filled `filled_hours_before` h before the run), and with its
//! group's ribbon tied at its knot (`ribbons::tie_ribbon`), its free end
//! tied down where the group gives an anchor (`anchor::tie_down`); the
//! room's moving air, its fans, vents and draughts (`air`); and the
//! furniture standing in it, collided with as the room is (`furniture`).
//!
//! Each body's `user_data` packs its group and colour:
//! `group << 16 | colour`, where `colour` indexes `BuiltScene::colors`
//! (see `user_data_for`, `color_index`, `group_index`).

use glam::{Quat, Vec3};
use up_geom::{Pose, SplitMix64};
use up_physics::gas::{EnvelopeDef, EnvelopeKind};
use up_physics::{BodyDef, BodyId, JointId, World, WorldDef};

use crate::balloon::gas_fill::{fill_balloon, group_envelope, PermeanceFactors};
use crate::balloon::{build_balloon_with, BalloonModel, BalloonSpec, Gas};
use crate::error::SceneError;
use crate::scene::{parse_color, BalloonGroup, BalloonKind, CeilingKind, GasKind, Scene};
use ribbons::{tie_ribbon, GroupRibbon};
use room::{box_room, room_from_obj, Ceiling, RoomMesh};

pub mod air;
pub mod anchor;
pub mod bench_scene;
pub mod furniture;
mod hang;
mod ribbon_path;
pub mod ribbons;
pub mod room;
pub mod spawn;

use anchor::{anchored_region, tie_down};
use hang::{lay_hanging, reserve_column, Hanging, HangingLayout};
use ribbon_path::WeightedRibbon;
use spawn::{place_spheres, place_spheres_clear_of_ribbons, Occupancy, SpawnRegion};

/// Most groups a scene may have (the group index lives in 16 bits of `user_data`).
pub const MAX_GROUPS: usize = 1 << 16;
/// Most distinct colours over a scene (the colour index lives in the low 16 bits).
pub const MAX_COLORS: usize = 1 << 16;
/// Spawn regions keep this far from the room's surfaces, m.
const ROOM_MARGIN: f32 = 0.01;

/// A scene built and ready to step.
pub struct BuiltScene {
    pub world: World,
    pub room: RoomMesh,
    /// The furniture, in the scene's order: its triangles are in the
    /// world's room mesh too (`furniture::room_with_furniture`).
    pub furniture: Vec<furniture::FurniturePiece>,
    /// One per balloon group, in the scene's order.
    pub balloon_models: Vec<BalloonModel>,
    /// RGB in 0–1, indexed by `color_index(user_data)`.
    pub colors: Vec<[f32; 3]>,
    /// The names the colours were given in the scene, parallel to `colors`.
    pub color_names: Vec<String>,
    /// The bodies of each group, in creation order.
    pub group_bodies: Vec<Vec<BodyId>>,
    /// Each group's ribbon (None: its balloons have none), in the scene's order.
    pub group_ribbons: Vec<Option<GroupRibbon>>,
    /// The ropes that tie each group's balloons to its ribbons' anchor
    /// (`anchor::tie_down`), in the order of `group_bodies`; empty for a
    /// group without an anchor.
    pub group_tethers: Vec<Vec<JointId>>,
    /// The envelope each group's balloons were filled with, before each
    /// balloon's own leak factor (`gas_fill`), in the scene's order. None: a
    /// group whose balloons carry no gas model (every group has one now).
    pub envelopes: Vec<Option<EnvelopeDef>>,
}

/// `user_data` of a body of `group` with palette colour `color`.
pub fn user_data_for(group: usize, color: usize) -> u32 {
    ((group as u32) << 16) | (color as u32 & 0xFFFF)
}

/// Palette index (into `BuiltScene::colors`) from a body's `user_data`.
pub fn color_index(user_data: u32) -> usize {
    (user_data & 0xFFFF) as usize
}

/// Balloon group index from a body's `user_data`.
pub fn group_index(user_data: u32) -> usize {
    (user_data >> 16) as usize
}

/// The `WorldDef` a scene asks for, without the room.
pub fn world_def(scene: &Scene) -> WorldDef {
    let sim = &scene.sim;
    WorldDef {
        gravity: Vec3::from_array(sim.gravity),
        atmosphere: scene.air.atmosphere(),
        dt: sim.dt,
        substeps: sim.substeps,
        contact_hertz: sim.contact_hertz,
        contact_damping_ratio: sim.contact_damping_ratio,
        friction: sim.friction,
        restitution: sim.restitution,
        drag_coefficient: sim.drag_coefficient,
        added_mass_coefficient: sim.added_mass_coefficient,
        angular_damping: sim.angular_damping,
        enable_sleep: sim.sleep,
        enable_continuous: sim.continuous,
        ribbon_contacts: sim.ribbon_contacts,
        ribbon_friction: sim.ribbon_friction,
        temperature_schedule: scene.air.temperature_schedule(),
        ..WorldDef::default()
    }
}

/// The room a scene describes: its OBJ mesh, or the box.
pub fn build_room(scene: &Scene) -> Result<RoomMesh, SceneError> {
    match scene.room_mesh_path() {
        Some(path) => room_from_obj(&path).map_err(|e| SceneError::Room {
            at: scene.locate("room.mesh"),
            message: format!("{}: {e}", path.display()),
        }),
        None => {
            let room = &scene.room;
            let ceiling = match room.ceiling {
                CeilingKind::Pyramid => Ceiling::Pyramid {
                    apex_height: room.apex_height,
                },
                CeilingKind::Flat => Ceiling::Flat,
            };
            box_room(room.width, room.depth, room.wall_height, ceiling).map_err(|e| {
                SceneError::Room {
                    at: scene.locate("room"),
                    message: e.to_string(),
                }
            })
        }
    }
}

/// The balloon model of group `i`.
pub fn build_group_model(scene: &Scene, i: usize) -> Result<BalloonModel, SceneError> {
    let group = &scene.balloons[i];
    let spec = BalloonSpec {
        kind: match group.kind {
            BalloonKind::Latex => EnvelopeKind::Latex,
            BalloonKind::Foil => EnvelopeKind::Foil,
        },
        diameter_m: group.diameter(),
        envelope_mass_kg: group.shaped_envelope_mass_kg(),
        knot_mass_kg: group.knot_mass_kg(),
        gas: match group.gas {
            GasKind::Helium => Gas::Helium,
            GasKind::Air => Gas::Air,
        },
    };
    let surface = crate::scene::group_surface(scene, i)?;
    let leaves = group.leaves as usize;
    build_balloon_with(&spec, &surface, &scene.air.atmosphere(), leaves).map_err(|e| {
        SceneError::Balloon {
            at: scene.locate(&format!("balloons[{i}]")),
            message: e.to_string(),
        }
    })
}

/// Builds the world: validates, makes the room and the balloon models, and
/// places every balloon.
pub fn build_world(scene: &Scene) -> Result<BuiltScene, SceneError> {
    scene.validate()?;
    if scene.balloons.len() > MAX_GROUPS {
        return Err(SceneError::Invalid {
            at: scene.locate("balloons"),
            expected: format!("at most {MAX_GROUPS} balloon groups"),
            found: scene.balloons.len().to_string(),
        });
    }
    let room = build_room(scene)?;
    let physics = |source| SceneError::Physics {
        file: scene.source.name.clone(),
        source,
    };
    let furniture = furniture::build_furniture(scene, &room)?;
    let mut def = world_def(scene);
    def.room = Some(furniture::room_with_furniture(scene, &room, &furniture)?);
    let mut world = World::new(def).map_err(physics)?;
    air::check_air_in(scene, &room)?;
    if scene.has_moving_air() {
        // Before any body: still scenes build exactly as they did.
        world.set_air_flow(air::air_flow(scene));
    }

    let (colors, color_names, group_palette) = palette(scene)?;
    let bounds = room.bounds();
    let inside = |p: Vec3| room.contains_point(p);
    let mut occupied = Occupancy::default();
    furniture::reserve(&furniture, &mut occupied);
    let mut rng = SplitMix64::new(scene.sim.seed);
    let mut balloon_models = Vec::with_capacity(scene.balloons.len());
    let mut group_bodies = Vec::with_capacity(scene.balloons.len());
    let mut group_ribbons = Vec::with_capacity(scene.balloons.len());
    let mut group_tethers = Vec::with_capacity(scene.balloons.len());
    let mut envelopes = Vec::with_capacity(scene.balloons.len());
    let mut factors = PermeanceFactors::new(scene.sim.seed);

    let mut shape_ids = Vec::with_capacity(scene.balloons.len());
    for i in 0..scene.balloons.len() {
        let model = build_group_model(scene, i)?;
        shape_ids.push(world.add_shape(model.shape.clone()).map_err(physics)?);
        check_anchor_in(scene, i, &bounds)?;
        balloon_models.push(model);
    }
    // Where each group's balloons go and how they lean, laid in
    // `placement_order`; the bodies are then added in the scene's order.
    let mut layouts: Vec<Vec<(Vec3, Quat)>> = vec![Vec::new(); scene.balloons.len()];
    for i in placement_order(scene) {
        let group = &scene.balloons[i];
        let model = &balloon_models[i];
        let root = model.shape.tree.root().sphere();
        let region = spawn_region(scene, i, model, &bounds.min, &bounds.max)?;
        let hung = group.tied_ribbon().filter(|_| hangs_weights(group));
        let knot = ribbons::knot_point(model);
        let count = group.count as usize;
        let centres = if let Some(ribbon) = hung {
            let hanging = Hanging {
                radius: root.radius,
                knot: knot - root.center,
                ribbon_length: ribbon.length_m,
                tilt_deg: group.tilt_deg,
            };
            let floor = bounds.min.y;
            let layout = lay_hanging(
                count,
                &hanging,
                &region,
                floor,
                &inside,
                &mut occupied,
                &mut rng,
            );
            if layout.centres.len() < count {
                return Err(too_many_to_hang(scene, i, &layout, &bounds));
            }
            layout.centres
        } else {
            let weighted = weighted_ribbon(scene, i, knot - root.center, &bounds);
            let before = occupied.clone();
            let mut centres = match &weighted {
                Some(ribbon) => place_spheres_clear_of_ribbons(
                    count,
                    root.radius,
                    &region,
                    &inside,
                    &mut occupied,
                    &mut rng,
                    ribbon,
                ),
                None => place_spheres(
                    count,
                    root.radius,
                    &region,
                    &inside,
                    &mut occupied,
                    &mut rng,
                ),
            };
            if centres.len() < count {
                // The layers are full: the gaps between them, more densely.
                centres.extend(spawn::fill_gaps(
                    count - centres.len(),
                    root.radius,
                    &region,
                    &inside,
                    &mut occupied,
                    weighted.as_ref(),
                ));
            }
            if centres.len() < count {
                // Still short: the whole group in the gaps, packed as densely
                // as they go (the next level in the hollows of the one below).
                let mut packed = before;
                let dense = spawn::fill_gaps(
                    count,
                    root.radius,
                    &region,
                    &inside,
                    &mut packed,
                    weighted.as_ref(),
                );
                if dense.len() > centres.len() {
                    (centres, occupied) = (dense, packed);
                }
            }
            if centres.len() < count {
                return Err(SceneError::DoesNotFit {
                    at: scene.locate(&format!("balloons[{i}].count")),
                    requested: group.count,
                    placed: centres.len() as u64,
                });
            }
            centres
        };
        layouts[i] = centres
            .into_iter()
            .map(|centre| {
                let rotation = random_upright(&mut rng, group.tilt_deg, group.yaw_deg);
                // The bounding sphere's centre goes where the layout put it.
                (centre - rotation * root.center, rotation)
            })
            .collect();
        if hung.is_some() {
            // The ribbons and weights hang straight down from the knots:
            // balloons laid later keep out of them.
            for &(position, rotation) in &layouts[i] {
                reserve_column(&mut occupied, position + rotation * knot, bounds.min.y);
            }
        }
    }

    for (i, group) in scene.balloons.iter().enumerate() {
        let model = &balloon_models[i];
        let envelope = group_envelope(group, model);
        let ribbon = group.tied_ribbon().and_then(GroupRibbon::new);
        let mut bodies = Vec::with_capacity(layouts[i].len());
        let mut tethers = Vec::new();
        for (k, &(position, rotation)) in layouts[i].iter().enumerate() {
            let mut body = BodyDef::new(shape_ids[i], Pose::new(position, rotation));
            body.linear_velocity = Vec3::from_array(group.velocity);
            body.angular_velocity = Vec3::from_array(group.angular_velocity);
            let palette = &group_palette[i];
            body.user_data = user_data_for(i, palette[k % palette.len()]);
            let id = world.add_body(&body).map_err(physics)?;
            let factor = factors.next_factor();
            fill_balloon(&mut world, id, &envelope, factor, group.filled_hours_before)
                .map_err(physics)?;
            if let Some(ribbon) = &ribbon {
                tie_ribbon(&mut world, id, model, &ribbon.spec).map_err(physics)?;
                if let Some(tether) =
                    tie_down(&mut world, id, model, &ribbon.spec).map_err(physics)?
                {
                    tethers.push(tether);
                }
            }
            bodies.push(id);
        }
        group_bodies.push(bodies);
        group_ribbons.push(ribbon);
        group_tethers.push(tethers);
        envelopes.push(Some(envelope));
    }
    Ok(BuiltScene {
        world,
        room,
        furniture,
        balloon_models,
        colors,
        color_names,
        group_bodies,
        group_ribbons,
        group_tethers,
        envelopes,
    })
}

/// A hanging group's count more than the room holds: how many it holds,
/// in how many layers, and the room's size.
fn too_many_to_hang(
    scene: &Scene,
    i: usize,
    layout: &HangingLayout,
    bounds: &up_geom::Aabb,
) -> SceneError {
    let group = &scene.balloons[i];
    let size = bounds.max - bounds.min;
    let length = group.tied_ribbon().map_or(0.0, |r| r.length_m);
    SceneError::Invalid {
        at: scene.locate(&format!("balloons[{i}].count")),
        expected: format!(
            "at most {} balloons: a room {:.2} m × {:.2} m and {:.2} m high holds that many \
             of these hanging their weights on {length} m ribbons, in {} staggered layers",
            layout.centres.len(),
            size.x,
            size.z,
            size.y,
            layout.layers
        ),
        found: group.count.to_string(),
    }
}

/// The order groups are laid in: groups that hang weights over the floor
/// (`hangs_weights`) first, then the rest, each in the scene's order. A weight hangs at its
/// ribbon's length under its balloon's knot; laid above other balloons, it
/// would hang among them, and its pull (tens of grams, where a balloon
/// weighs a few) drives them into each other from the first step (101 mm of
/// overlap in a 10 m room of 1,500 free balloons laid first and 200 weighted
/// above them). Laid first (`hang::lay_hanging`), the weighted balloons
/// start at their ribbon's length above the floor, in one layer or in
/// staggered ones, each ribbon and weight hanging straight down in a column
/// every later balloon keeps out of. (Laid on the
/// floor instead, each ribbon runs along it and its weight ends under some
/// other balloon's neck, pressed between the two: 8 to 17 mm of overlap.)
fn placement_order(scene: &Scene) -> Vec<usize> {
    let all = 0..scene.balloons.len();
    let weighted_at = |i: &usize| hangs_weights(&scene.balloons[*i]);
    all.clone()
        .filter(weighted_at)
        .chain(all.filter(|i| !weighted_at(i)))
        .collect()
}

/// Whether the builder lays `group` as weights hanging over the floor: its
/// ribbons end in a weight and nothing else says where it starts (a spawn
/// box, an anchor). Other groups keep the scene's order, so their layouts
/// (and the state hashes pinned on them) are as they were.
fn hangs_weights(group: &BalloonGroup) -> bool {
    group.spawn.is_none()
        && group
            .tied_ribbon()
            .is_some_and(|r| r.weight_g > 0.0 && r.anchor.is_none())
}

/// Group `i`'s ribbon as its layout keeps clear (`ribbon_path`), its knot
/// `knot` from the bounding sphere's centre: where it ends in a weight that
/// hangs free, None where it has no weight or is tied to an anchor (a light
/// ribbon under a balloon is pushed aside; an anchor holds its own end).
fn weighted_ribbon(
    scene: &Scene,
    i: usize,
    knot: Vec3,
    bounds: &up_geom::Aabb,
) -> Option<WeightedRibbon> {
    let group = &scene.balloons[i];
    let ribbon = group
        .tied_ribbon()
        .filter(|r| r.weight_g > 0.0 && r.anchor.is_none())?;
    Some(WeightedRibbon {
        knot,
        length: ribbon.length_m,
        segments: ribbon.segments,
        down: Vec3::from_array(scene.sim.gravity)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Y),
        room_min: bounds.min,
        room_max: bounds.max,
        clearance: ribbon_path::clearance(knot, group.tilt_deg),
    })
}

/// Distinct colours over the scene, and each group's colours as palette indices.
type Palette = (Vec<[f32; 3]>, Vec<String>, Vec<Vec<usize>>);

fn palette(scene: &Scene) -> Result<Palette, SceneError> {
    let mut colors = Vec::new();
    let mut names: Vec<String> = Vec::new();
    let mut per_group = Vec::with_capacity(scene.balloons.len());
    for (i, group) in scene.balloons.iter().enumerate() {
        let mut indices = Vec::with_capacity(group.colors.len());
        for (j, name) in group.colors.iter().enumerate() {
            let index = match names.iter().position(|n| n == name) {
                Some(index) => index,
                None => {
                    let key = format!("balloons[{i}].colors[{j}]");
                    let rgb = parse_color(name).ok_or_else(|| SceneError::Invalid {
                        at: scene.locate(&key),
                        expected: "a colour name or \"#rrggbb\"".into(),
                        found: format!("{name:?}"),
                    })?;
                    if names.len() >= MAX_COLORS {
                        return Err(SceneError::Invalid {
                            at: scene.locate(&key),
                            expected: format!("at most {MAX_COLORS} distinct colours"),
                            found: "more".into(),
                        });
                    }
                    colors.push(rgb);
                    names.push(name.clone());
                    names.len() - 1
                }
            };
            indices.push(index);
        }
        per_group.push(indices);
    }
    Ok((colors, names, per_group))
}

/// The region group `i` (of `model`) fills: its spawn box, else over its
/// ribbons' anchor, else the whole floor.
fn spawn_region(
    scene: &Scene,
    i: usize,
    model: &BalloonModel,
    lo: &Vec3,
    hi: &Vec3,
) -> Result<SpawnRegion, SceneError> {
    let margin = Vec3::splat(ROOM_MARGIN);
    let (lo, hi) = (*lo + margin, *hi - margin);
    let group = &scene.balloons[i];
    let Some(spawn) = &group.spawn else {
        if let Some((ribbon, anchor)) = group
            .tied_ribbon()
            .and_then(|r| Some((r, Vec3::from_array(r.anchor?))))
        {
            let count = group.count as usize;
            return Ok(anchored_region(
                anchor,
                ribbon.length_m,
                count,
                model,
                lo,
                hi,
            ));
        }
        return Ok(SpawnRegion {
            min: lo,
            max: Vec3::new(hi.x, lo.y, hi.z),
            top: hi.y,
        });
    };
    let (min, max) = (Vec3::from_array(spawn.min), Vec3::from_array(spawn.max));
    // A box room is checked in validation; a mesh room only now that its bounds are known.
    if min.cmplt(lo - margin).any() || max.cmpgt(hi + margin).any() {
        return Err(SceneError::Invalid {
            at: scene.locate(&format!("balloons[{i}].spawn")),
            expected: format!("a region inside the room's bounds, from {lo} to {hi} m"),
            found: format!("from {min} to {max}"),
        });
    }
    Ok(SpawnRegion {
        min: min.max(lo),
        max: max.min(hi),
        top: hi.y,
    })
}

/// Group `i`'s ribbon anchor inside the room's `bounds`: a box room's was
/// checked in validation, a mesh room's only now that its bounds are known.
fn check_anchor_in(scene: &Scene, i: usize, bounds: &up_geom::Aabb) -> Result<(), SceneError> {
    let Some(anchor) = scene.balloons[i].ribbon.as_ref().and_then(|r| r.anchor) else {
        return Ok(());
    };
    let point = Vec3::from_array(anchor);
    if point.cmplt(bounds.min).any() || point.cmpgt(bounds.max).any() {
        return Err(SceneError::Invalid {
            at: scene.locate(&format!("balloons[{i}].ribbon.anchor")),
            expected: format!(
                "a point inside the room's bounds, from {} to {} m",
                bounds.min, bounds.max
            ),
            found: format!("{anchor:?}"),
        });
    }
    Ok(())
}

/// Upright, tilted by up to `tilt_deg` about a random horizontal axis, and
/// turned by up to ±`yaw_deg` about the vertical.
fn random_upright(rng: &mut SplitMix64, tilt_deg: f32, yaw_deg: f32) -> Quat {
    let yaw = rng.range(-yaw_deg, yaw_deg).to_radians();
    let tilt = rng.range(0.0, tilt_deg).to_radians();
    let heading = rng.range(0.0, std::f32::consts::TAU);
    // A horizontal axis at a random heading (glam's trig goes through libm).
    let axis = Quat::from_rotation_y(heading) * Vec3::X;
    (Quat::from_axis_angle(axis, tilt) * Quat::from_rotation_y(yaw)).normalize()
}

#[cfg(test)]
mod air_tests;
#[cfg(test)]
mod hang_tests;
#[cfg(test)]
mod room_tests;
#[cfg(test)]
mod tests;
