//! Ribbons tied down (`[balloons.ribbon] anchor`): each balloon of the group
//! holds a rope from its knot to the fixed point, as long as its ribbon
//! (`up_physics::DistanceLimit::Rope`, inextensible), so it floats at its
//! ribbon's length above the point; and where such a group starts.

use glam::Vec3;
use up_physics::{
    BodyId, DistanceJointDef, DistanceLimit, JointAnchor, JointId, PhysicsError, World,
};

use super::ribbons::knot_point;
use super::spawn::{cell_size, SpawnRegion};
use crate::balloon::BalloonModel;
use crate::scene::RibbonSpec;

/// Slack the ropes start with, m: a knot placed at exactly the ribbon's
/// length would start taut, and a random tilt could start it stretched.
const START_SLACK: f32 = 0.01;

/// Ties `body` (a balloon of `model`) to `spec`'s anchor by a rope from its
/// knot, `spec.length_m` long; None when `spec` has no anchor or no ribbon.
pub fn tie_down(
    world: &mut World,
    body: BodyId,
    model: &BalloonModel,
    spec: &RibbonSpec,
) -> Result<Option<JointId>, PhysicsError> {
    let Some(anchor) = spec.anchor.filter(|_| spec.length_m > 0.0) else {
        return Ok(None);
    };
    let def = DistanceJointDef {
        a: JointAnchor::Body {
            body,
            point: knot_point(model),
        },
        b: JointAnchor::Fixed(Vec3::from_array(anchor)),
        length: spec.length_m,
        limit: DistanceLimit::Rope,
        compliance: 0.0,
    };
    world.add_distance_joint(&def).map(Some)
}

/// Where `count` balloons of `model` tied to `anchor` by ribbons `length`
/// long start when their group gives no spawn box: one layer centred over
/// the anchor, as small as holds them, in the room's box `lo`..`hi`, their
/// knots as high as keeps every rope slack (at most `length` from the
/// anchor); a ribbon longer than its knot is high lies along the floor
/// (`World::add_ribbon`). A group too wide for its ribbons (many balloons
/// on a short ribbon) starts with its knots at the anchor's height and its
/// outer ropes pulled taut at once.
pub(super) fn anchored_region(
    anchor: Vec3,
    length: f32,
    count: usize,
    model: &BalloonModel,
    lo: Vec3,
    hi: Vec3,
) -> SpawnRegion {
    let root = model.shape.tree.root().sphere();
    let cell = cell_size(root.radius);
    // A square of cells holding the group; a little over, so that the
    // layout's floor(width / cell) does not lose a cell to rounding.
    let side = (count.max(1) as f32).sqrt().ceil() * cell * 1.001;
    let centre = |a: f32, lo: f32, hi: f32| {
        if hi - lo <= side {
            (lo + hi) * 0.5
        } else {
            a.clamp(lo + side * 0.5, hi - side * 0.5)
        }
    };
    let (cx, cz) = (centre(anchor.x, lo.x, hi.x), centre(anchor.z, lo.z, hi.z));
    let min = Vec3::new(
        (cx - side * 0.5).max(lo.x),
        0.0,
        (cz - side * 0.5).max(lo.z),
    );
    let max = Vec3::new(
        (cx + side * 0.5).min(hi.x),
        0.0,
        (cz + side * 0.5).min(hi.z),
    );
    // The farthest a knot may lie from the anchor across: a balloon's centre
    // stays a radius inside the footprint, and its knot lies under it.
    let inner = |lo: f32, hi: f32| [lo + root.radius, (hi - root.radius).max(lo + root.radius)];
    let reach = inner(min.x, max.x)
        .iter()
        .flat_map(|&x| inner(min.z, max.z).map(|z| (x - anchor.x).hypot(z - anchor.z)))
        .fold(0.0f32, f32::max);
    let knot_height = ((length * length - reach * reach).max(0.0).sqrt() - START_SLACK).max(0.0);
    // Upright, the knot lies this far below the centre of the bounding sphere.
    let knot_below_centre = root.center.y - knot_point(model).y;
    let bottom = anchor.y + knot_height + knot_below_centre - 0.5 * cell;
    let bottom = bottom.min(hi.y - cell).max(lo.y);
    SpawnRegion {
        min: Vec3::new(min.x, bottom, min.z),
        max: Vec3::new(max.x, bottom, max.z),
        top: hi.y,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{build_world, BuiltScene};
    use crate::error::SceneError;
    use crate::scene::Scene;

    fn build(text: &str) -> Result<BuiltScene, SceneError> {
        build_world(&Scene::from_toml_str(text, "anchor.rs").unwrap())
    }

    /// Each balloon's knot and its rope's fixed end, world frame.
    fn ropes(built: &BuiltScene, group: usize) -> Vec<(Vec3, Vec3)> {
        let world = &built.world;
        built.group_tethers[group]
            .iter()
            .map(|&rope| {
                let [knot, anchor] = world.joint_ends(rope).unwrap();
                (knot, anchor)
            })
            .collect()
    }

    #[test]
    fn anchored_balloons_start_over_their_anchor_apart_with_slack_ropes() {
        let text = "[[balloons]]\ncount = 4\n[balloons.ribbon]\nlength_m = 1.2\n\
                    anchor = [-1.5, 0.9, 1.0]\n\
                    [[balloons]]\ncount = 3\n[balloons.ribbon]\nlength_m = 1\n\
                    anchor = [2.9, 0.02, -2.9]\n\
                    [[balloons]]\ncount = 2\n[balloons.ribbon]\n";
        let mut built = build(text).unwrap();
        assert_eq!(built.world.joint_count(), 7);
        assert_eq!(built.world.max_penetration_now(), 0.0, "overlap at spawn");
        for (group, anchor, length) in [
            (0, Vec3::new(-1.5, 0.9, 1.0), 1.2),
            (1, Vec3::new(2.9, 0.02, -2.9), 1.0),
        ] {
            let ropes = ropes(&built, group);
            assert_eq!(ropes.len(), built.group_bodies[group].len());
            for (knot, fixed) in ropes {
                assert_eq!(fixed, anchor);
                let distance = knot.distance(anchor);
                // Slack, but not by much: the balloons rise a little and pull
                // (more in a corner, where the layer cannot centre on the anchor).
                assert!(distance <= length, "{distance} m on a {length} m rope");
                assert!(distance > 0.5 * length, "{distance} m on a {length} m rope");
                assert!(knot.y > anchor.y + 0.5 * length, "{knot} over {anchor}");
            }
        }
        // A group without an anchor is tied to nothing.
        assert!(built.group_tethers[2].is_empty());
        assert_eq!(built.world.ribbon_count(), 9);
    }

    #[test]
    fn a_spawn_box_wins_over_the_anchor_and_the_rope_still_ties() {
        let text =
            "[[balloons]]\ncount = 1\nspawn = { min = [1, 0.5, 1], max = [1.5, 0.5, 1.5] }\n\
                    [balloons.ribbon]\nlength_m = 2\nanchor = [-1, 0.1, -1]\n";
        let built = build(text).unwrap();
        let (knot, anchor) = ropes(&built, 0)[0];
        assert!(knot.x > 0.9 && knot.z > 0.9, "{knot}: in its spawn box");
        assert_eq!(anchor, Vec3::new(-1.0, 0.1, -1.0));
    }

    #[test]
    fn a_mesh_room_checks_its_anchor_against_its_bounds_when_built() {
        let dir = std::env::temp_dir().join(format!("up-scene-anchor-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let room =
            crate::build::room::box_room(4.0, 4.0, 2.5, crate::build::room::Ceiling::Flat).unwrap();
        crate::obj::export::export_room_obj(&dir, &room).unwrap();
        let mesh = dir.join("room.obj");
        let text = |anchor: &str| {
            format!(
                "[room]\nmesh = {:?}\n[[balloons]]\n[balloons.ribbon]\nanchor = {anchor}\n",
                mesh.display().to_string()
            )
        };
        assert_eq!(build(&text("[0, 0.5, 0]")).unwrap().world.joint_count(), 1);
        let e = build(&text("[0, 2.6, 0]")).err().unwrap();
        assert_eq!(e.key(), Some("balloons[0].ribbon.anchor"), "{e}");
        assert!(e.to_string().contains("inside the room's bounds"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
