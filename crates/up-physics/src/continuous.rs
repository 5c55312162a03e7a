//! Continuous collision against the room: a body that moved far in a step
//! has the core of each leaf swept along its path; on a hit it is moved back
//! to the time of impact and loses its velocity into the wall.

use glam::Vec3;
use up_geom::norm::Norm;
use up_geom::query::toi_sphere_trimesh::{sweep_may_hit, toi_sphere_trimesh_new_contact};
use up_geom::{Sphere, TriMesh};

use crate::body::{Bodies, ShapeData};
use crate::solver::Solver;
use crate::threading::tasks::collect_in_order;

/// A fast body's core, swept against the room: this share of each leaf's radius.
const CORE_FRACTION: f32 = 0.5;
/// Bodies that moved more than this share of their smallest leaf radius in a step are swept.
const FAST_FRACTION: f32 = 0.25;
/// Awake bodies one task sweeps.
const SWEEP_CHUNK: usize = 256;

/// What the sweep reads of the step.
pub(crate) struct SweepInput<'a> {
    pub room: &'a TriMesh,
    pub shapes: &'a [ShapeData],
    /// The step's solve: each awake body's motion (`dp`, `dq`).
    pub solver: &'a Solver,
    /// s.
    pub dt: f32,
    pub restitution: f32,
}

/// The sweep's buffers.
#[derive(Clone, Debug, Default)]
pub(crate) struct SweepBuffers {
    /// (body, time of impact, normal) of the bodies that hit the room.
    hits: Vec<(u32, f32, Vec3)>,
    /// Each task's hits.
    task_hits: Vec<Vec<(u32, f32, Vec3)>>,
}

/// Sweeps the fast bodies of this step against the room and moves those
/// that hit it back to their time of impact (`bodies` hold the step's end).
pub(crate) fn sweep_fast_bodies(
    input: &SweepInput,
    bodies: &mut Bodies,
    buffers: &mut SweepBuffers,
) {
    let (shapes, dt, solver) = (input.shapes, input.dt, input.solver);
    let (center, shape_of, size) = (&bodies.center, &bodies.shape, &bodies.size);
    // The sweeps (read-only, in tasks of awake bodies), then their hits.
    let mut hits = std::mem::take(&mut buffers.hits);
    hits.clear();
    collect_in_order(
        solver.awake.len(),
        SWEEP_CHUNK,
        &mut buffers.task_hits,
        &mut hits,
        |range, hits| {
            for &i in &solver.awake[range] {
                let i = i as usize;
                let s = &solver.states[i];
                let shape = &shapes[shape_of[i] as usize];
                let scale = size[i].scale;
                let moved = s.dp.norm() + s.w.norm() * (shape.bound_radius * scale) * dt;
                if moved <= FAST_FRACTION * (shape.min_leaf_radius * scale) {
                    continue;
                }
                let end = center[i];
                let begin = end - s.dp;
                // Most fast bodies rise through open air, or below a
                // ceiling they do not reach this step: one look for any
                // triangle that a sphere holding all their cores' paths
                // may hit spares a sweep of each core. A core stays
                // within its offset from the centre, whatever the turn,
                // and the centre within half its path from the middle.
                let core_reach = shape
                    .tree
                    .leaf_spheres()
                    .map(|leaf| scaled(leaf, scale))
                    .map(|leaf| leaf.center.norm() + leaf.radius * CORE_FRACTION)
                    .fold(0.0, f32::max);
                let bound = Sphere::new(begin + 0.5 * s.dp, 0.5 * s.dp.norm() + core_reach);
                if !sweep_may_hit(bound, input.room) {
                    continue;
                }
                let q0 = s.start_rotation();
                let mut earliest: Option<(f32, Vec3)> = None;
                for leaf in shape.tree.leaf_spheres().map(|leaf| scaled(leaf, scale)) {
                    let from = begin + q0 * leaf.center;
                    let to = end + s.q * leaf.center;
                    let core = Sphere::new(from, leaf.radius * CORE_FRACTION);
                    // Triangles the core is in already are the solver's to push
                    // out of: stopping at them would freeze the body in place,
                    // step after step.
                    if let Some((t, _, normal)) =
                        toi_sphere_trimesh_new_contact(core, to - from, input.room)
                    {
                        if earliest.is_none_or(|(te, _)| t < te) {
                            earliest = Some((t, normal));
                        }
                    }
                }
                if let Some((t, normal)) = earliest {
                    hits.push((i as u32, t, normal));
                }
            }
        },
    );
    for &(i, t, normal) in &hits {
        let (i, s) = (i as usize, &solver.states[i as usize]);
        let begin = bodies.center[i] - s.dp;
        let q0 = s.start_rotation();
        bodies.center[i] = begin + t * s.dp;
        bodies.rotation[i] = q0.lerp(s.q, t).unit();
        let v = bodies.linear_velocity[i];
        let into = v.dot(normal);
        if into > 0.0 {
            bodies.linear_velocity[i] = v - (1.0 + input.restitution) * into * normal;
        }
    }
    buffers.hits = hits;
}

/// A leaf sphere of a body grown by `scale`.
#[inline]
fn scaled(leaf: Sphere, scale: f32) -> Sphere {
    Sphere::new(leaf.center * scale, leaf.radius * scale)
}
