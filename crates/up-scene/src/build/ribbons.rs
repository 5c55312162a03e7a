//! Ribbons on balloons: where the balloon model's knot is, and the engine's
//! `RibbonDef` that a scene's `[balloons.ribbon]` table makes. `build_world`
//! ties the scene's ribbons with `tie_ribbon`; the web engine calls it for
//! balloons added while the world runs.

use glam::Vec3;
use up_physics::{BodyId, PhysicsError, RibbonDef, RibbonId, World};

use crate::balloon::BalloonModel;
use crate::scene::{parse_color, RibbonSpec, DEFAULT_RIBBON_COLOR};

/// A group's ribbon: the scene's table and its colour.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupRibbon {
    pub spec: RibbonSpec,
    /// sRGB in 0–1.
    pub rgb: [f32; 3],
}

impl GroupRibbon {
    /// The ribbon `spec` describes, or None when it has none (`length_m = 0`).
    pub fn new(spec: &RibbonSpec) -> Option<GroupRibbon> {
        (spec.length_m > 0.0).then(|| GroupRibbon {
            spec: spec.clone(),
            rgb: ribbon_rgb(spec),
        })
    }
}

/// The ribbon's colour; white where the name is not one (a scene's names are
/// checked before it is built).
pub fn ribbon_rgb(spec: &RibbonSpec) -> [f32; 3] {
    parse_color(&spec.color)
        .or_else(|| parse_color(DEFAULT_RIBBON_COLOR))
        .unwrap_or([1.0; 3])
}

/// Where a ribbon is tied, in the balloon's mesh frame (the frame of
/// `BodyDef::pose`), m: the bottom of the knot ball under the neck, the
/// lowest point of the drawn balloon.
pub fn knot_point(model: &BalloonModel) -> Vec3 {
    let d = &model.mesh.dimensions;
    d.knot_center - Vec3::Y * d.knot_radius
}

/// The engine's ribbon for `spec` on `body`, a balloon of `model`.
pub fn ribbon_def(body: BodyId, model: &BalloonModel, spec: &RibbonSpec) -> RibbonDef {
    RibbonDef {
        body,
        knot: knot_point(model),
        length: spec.length_m,
        mass_per_length: spec.mass_per_m_g * 1e-3,
        segments: spec.segments,
        end_mass: spec.weight_g * 1e-3,
        anchor: spec.anchor.map(Vec3::from_array),
    }
}

/// Ties `spec`'s ribbon to `body` (added with `model`'s shape) at its knot,
/// hanging straight down from it, or sagging to its anchor where the group
/// ties its ribbons down; None when `spec` has no ribbon (`length_m = 0`).
/// A balloon whose knot is beyond its ribbon's reach of the anchor (one the
/// page adds elsewhere in the room) gets a free ribbon: it was never tied
/// there. The engine refuses, saying why, a body that does not exist or has
/// a ribbon already, and values out of its ranges.
pub fn tie_ribbon(
    world: &mut World,
    body: BodyId,
    model: &BalloonModel,
    spec: &RibbonSpec,
) -> Result<Option<RibbonId>, PhysicsError> {
    if spec.length_m == 0.0 {
        return Ok(None);
    }
    let mut def = ribbon_def(body, model, spec);
    if let (Some(anchor), Some(pose)) = (def.anchor, world.pose(body)) {
        if pose.transform_point(def.knot).distance(anchor) > def.length {
            def.anchor = None;
        }
    }
    world.add_ribbon(&def).map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::build_world;
    use crate::scene::Scene;

    fn built(text: &str) -> crate::build::BuiltScene {
        let scene = Scene::from_toml_str(text, "ribbons.rs").unwrap();
        build_world(&scene).unwrap()
    }

    #[test]
    fn the_knot_is_the_lowest_point_of_the_balloon_mesh() {
        let built = built("[[balloons]]\ncount = 1\n");
        let model = &built.balloon_models[0];
        let knot = knot_point(model);
        let lowest = model
            .mesh
            .positions
            .iter()
            .min_by(|a, b| a.y.total_cmp(&b.y))
            .unwrap();
        assert!(knot.distance(*lowest) < 1e-6, "{knot} vs {lowest}");
        assert!((knot.y - model.mesh.dimensions.bottom_y).abs() < 1e-6);
    }

    #[test]
    fn each_balloon_of_a_group_with_a_ribbon_gets_one_at_its_knot() {
        let text = "[room]\nceiling = \"flat\"\n[[balloons]]\ncount = 3\n\
                    [balloons.ribbon]\nlength_m = 1.2\nsegments = 8\ncolor = \"red\"\nweight_g = 4\n\
                    [[balloons]]\ncount = 2\n";
        let built = built(text);
        let world = &built.world;
        assert_eq!(world.ribbon_count(), 3);
        let ribbon = built.group_ribbons[0].as_ref().unwrap();
        assert_eq!(ribbon.rgb, parse_color("red").unwrap());
        assert!(built.group_ribbons[1].is_none());
        let knot = knot_point(&built.balloon_models[0]);
        for &body in &built.group_bodies[0] {
            let id = world.ribbon_of(body).expect("a ribbon");
            let points = world.ribbon_points(id).unwrap();
            assert_eq!(points.len(), 9);
            // Point 0 is the knot, where the body's pose puts the mesh's knot.
            let pose = world.pose(body).unwrap();
            let at = pose.position + pose.rotation * knot;
            assert!(points[0].distance(at) < 1e-5, "{} vs {at}", points[0]);
            let (length, mass) = world.ribbon_length_and_mass(id).unwrap();
            assert!((length - 1.2).abs() < 1e-5);
            let expected = 1.2 * 0.25e-3 + 4e-3;
            assert!((mass - expected).abs() < 1e-7, "{mass} kg");
        }
        for &body in &built.group_bodies[1] {
            assert!(world.ribbon_of(body).is_none());
        }
    }

    #[test]
    fn length_zero_ties_nothing_and_a_second_ribbon_is_refused() {
        let built = built("[[balloons]]\ncount = 1\n[balloons.ribbon]\nlength_m = 0\n");
        assert!(built.group_ribbons[0].is_none());
        let mut world = built.world;
        assert_eq!(world.ribbon_count(), 0);
        let body = built.group_bodies[0][0];
        let model = &built.balloon_models[0];
        let none = RibbonSpec {
            length_m: 0.0,
            ..RibbonSpec::default()
        };
        assert_eq!(tie_ribbon(&mut world, body, model, &none).unwrap(), None);
        let spec = RibbonSpec::default();
        let id = tie_ribbon(&mut world, body, model, &spec).unwrap().unwrap();
        assert_eq!(world.ribbon_body(id), Some(body));
        assert!(tie_ribbon(&mut world, body, model, &spec).is_err());
    }
}
