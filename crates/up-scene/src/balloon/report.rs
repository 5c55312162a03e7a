//! A printable summary of a balloon model: its sphere tree (body frame) and
//! mass properties, what `up colliders` shows (as a table or JSON).

use std::fmt;

use serde::Serialize;
use up_geom::fit::LeafRole;

use super::BalloonModel;

/// One node of the sphere tree, body frame.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeReport {
    pub index: usize,
    /// m.
    pub center: [f32; 3],
    /// m.
    pub radius: f32,
    pub leaf: bool,
    /// Head, filler or neck for a leaf; none for the root.
    pub role: Option<LeafRole>,
    /// Indices of the children (empty for a leaf).
    pub children: Vec<usize>,
}

/// The sphere tree and mass properties of a balloon model; SI units, body frame.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CollidersReport {
    /// `"Latex"` or `"Foil"`.
    pub kind: up_physics::gas::EnvelopeKind,
    /// m.
    pub diameter_m: f32,
    /// m, top of the head to the tip of the knot.
    pub height_m: f32,
    pub nodes: Vec<NodeReport>,
    /// Share of surface sample points inside some leaf within 1 mm, 0–1.
    pub coverage: f32,
    /// m.
    pub max_uncovered_distance_m: f32,
    /// Union volume of the leaves ÷ mesh volume.
    pub tightness: f32,
    /// kg: envelope + knot + gas.
    pub mass_kg: f32,
    pub envelope_kg: f32,
    pub knot_kg: f32,
    pub gas_kg: f32,
    /// m.
    pub center_of_mass: [f32; 3],
    /// kg·m² about the centre of mass, row by row.
    pub inertia: [[f32; 3]; 3],
    /// m³.
    pub volume_m3: f32,
    /// m.
    pub center_of_buoyancy: [f32; 3],
    /// m², largest horizontal cross-section.
    pub reference_area_m2: f32,
    /// m².
    pub envelope_area_m2: f32,
    /// kg of displaced air.
    pub displaced_air_kg: f32,
    /// kg: displaced air − mass.
    pub free_lift_kg: f32,
    /// m: where the net lift acts (`BalloonModel::lift_centre`); none if it sinks.
    pub lift_centre: Option<[f32; 3]>,
    /// m: lift centre above the head sphere's centre; pressed against a flat
    /// ceiling the balloon stays upright only if positive
    /// (`BalloonModel::ceiling_upright_margin_m`).
    pub ceiling_upright_margin_m: Option<f32>,
}

impl CollidersReport {
    pub fn new(model: &BalloonModel) -> Self {
        let tree = &model.shape.tree;
        let mut roles = vec![None; tree.nodes().len()];
        for (&leaf, &role) in tree.leaves().iter().zip(&model.fit.roles) {
            roles[leaf as usize] = Some(role);
        }
        let nodes = tree
            .nodes()
            .iter()
            .enumerate()
            .map(|(index, n)| NodeReport {
                index,
                center: n.center.to_array(),
                radius: n.radius,
                leaf: n.is_leaf(),
                role: roles[index],
                children: n.children().collect(),
            })
            .collect();
        let s = &model.shape;
        Self {
            kind: model.spec.kind,
            diameter_m: model.spec.diameter_m,
            height_m: model.mesh.dimensions.height(),
            nodes,
            coverage: model.fit.coverage,
            max_uncovered_distance_m: model.fit.max_uncovered_distance_m,
            tightness: model.fit.tightness,
            mass_kg: s.mass,
            envelope_kg: model.parts.envelope_kg,
            knot_kg: model.parts.knot_kg,
            gas_kg: model.parts.gas_kg,
            center_of_mass: s.center_of_mass.to_array(),
            inertia: s.inertia.transpose().to_cols_array_2d(),
            volume_m3: s.volume,
            center_of_buoyancy: s.center_of_buoyancy.to_array(),
            reference_area_m2: s.reference_area,
            envelope_area_m2: model.envelope_area_m2,
            displaced_air_kg: model.displaced_air_kg(),
            free_lift_kg: model.free_lift_kg(),
            lift_centre: model.lift_centre().map(|c| c.to_array()),
            ceiling_upright_margin_m: model.ceiling_upright_margin_m(),
        }
    }
}

fn vec3(v: [f32; 3]) -> String {
    format!("({:+.4}, {:+.4}, {:+.4})", v[0], v[1], v[2])
}

impl fmt::Display for CollidersReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "sphere tree of a {:.3} m {} balloon, {:.3} m tall (body frame: origin at the {}, +Y up)",
            self.diameter_m,
            match self.kind {
                up_physics::gas::EnvelopeKind::Latex => "latex",
                up_physics::gas::EnvelopeKind::Foil => "foil",
            },
            self.height_m,
            match self.kind {
                up_physics::gas::EnvelopeKind::Latex => "widest circle",
                up_physics::gas::EnvelopeKind::Foil => "disc's centre",
            },
        )?;
        for n in &self.nodes {
            let kind = match (n.role, n.leaf) {
                (Some(LeafRole::Head), _) => "leaf, head".to_string(),
                (Some(LeafRole::Filler), _) => "leaf, filler".to_string(),
                (Some(LeafRole::Neck), _) => "leaf, neck".to_string(),
                (None, true) => "leaf".to_string(),
                (None, false) => format!("root, children {:?}", n.children),
            };
            writeln!(
                f,
                "  node {:>2}  centre {} m  radius {:.4} m  {kind}",
                n.index,
                vec3(n.center),
                n.radius
            )?;
        }
        writeln!(
            f,
            "  coverage {:.2} % (max {:.2} mm outside), tightness {:.3}",
            self.coverage * 100.0,
            self.max_uncovered_distance_m * 1000.0,
            self.tightness
        )?;
        writeln!(f, "mass properties")?;
        writeln!(
            f,
            "  mass {:.3} g (envelope {:.3} g, knot {:.3} g, gas {:.3} g)",
            self.mass_kg * 1e3,
            self.envelope_kg * 1e3,
            self.knot_kg * 1e3,
            self.gas_kg * 1e3
        )?;
        writeln!(f, "  centre of mass {} m", vec3(self.center_of_mass))?;
        for (i, row) in self.inertia.iter().enumerate() {
            let label = if i == 0 { "inertia (kg·m²)" } else { "" };
            writeln!(
                f,
                "  {label:<16}[{:+.3e} {:+.3e} {:+.3e}]",
                row[0], row[1], row[2]
            )?;
        }
        writeln!(
            f,
            "  volume {:.3} L, centre of buoyancy {} m",
            self.volume_m3 * 1e3,
            vec3(self.center_of_buoyancy)
        )?;
        writeln!(
            f,
            "  reference area {:.4} m², envelope area {:.4} m²",
            self.reference_area_m2, self.envelope_area_m2
        )?;
        write!(
            f,
            "  displaced air {:.3} g, free lift {:.3} g",
            self.displaced_air_kg * 1e3,
            self.free_lift_kg * 1e3
        )?;
        if let Some(centre) = self.lift_centre {
            write!(f, "\n  net lift acts at {} m", vec3(centre))?;
        }
        if let Some(margin) = self.ceiling_upright_margin_m {
            let verdict = if margin > 0.0 {
                "stays upright"
            } else {
                "tips over"
            };
            write!(
                f,
                "\n  against a flat ceiling: lift centre {:+.1} mm above the head sphere's centre \
                 ({verdict} when nudged; see docs/physics.md)",
                margin * 1e3
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::balloon::{build_balloon, BalloonSpec};
    use up_physics::Atmosphere;

    #[test]
    fn report_lists_every_node_with_roles_and_prints() {
        let model = build_balloon(&BalloonSpec::default(), &Atmosphere::default(), 5).unwrap();
        let report = model.colliders_report();
        assert_eq!(report.nodes.len(), 6);
        assert!(!report.nodes[0].leaf && report.nodes[0].role.is_none());
        assert_eq!(report.nodes[0].children, vec![1, 2, 3, 4, 5]);
        assert!(report.nodes[1..].iter().all(|n| n.leaf && n.role.is_some()));
        let text = report.to_string();
        assert!(
            text.contains("leaf, head") && text.contains("leaf, neck"),
            "{text}"
        );
        assert!(text.contains("free lift"), "{text}");
        let json = serde_json::to_value(&report).unwrap();
        assert_eq!(json["nodes"][1]["role"], "head");
        assert_eq!(json["nodes"][5]["role"], "neck");
    }
}
