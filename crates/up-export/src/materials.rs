//! The PBR materials of an export, with the numbers the page draws with
//! (web/src/render/finishes.ts and room.ts): latex is a glossy clearcoat over
//! a slightly translucent body (`KHR_materials_clearcoat`,
//! `KHR_materials_transmission` through ≈ 1 cm, `KHR_materials_volume`,
//! `KHR_materials_ior`) with a velvet sheen that grows as the balloons age
//! (`KHR_materials_sheen`); pearl is that latex with a thin-film shimmer
//! (`KHR_materials_iridescence`); foil is metal. Extensions gltf-json has no
//! struct for are written through its `others` map, by name.

use gltf_json as json;
use json::extensions::material as ext;
use json::material::{PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use json::validation::Checked;
use json::Material;
use serde_json::{json as value, Map, Value};
use up_scene::scene::Finish;

/// Sheen of fresh and of fully aged latex (finishes.ts).
const SHEEN_FRESH: f32 = 0.08;
const SHEEN_AGED: f32 = 0.7;

/// A plain material: linear `rgb`, `roughness`, `metallic`.
pub fn plain(name: String, rgb: [f32; 3], roughness: f32, metallic: f32) -> Material {
    Material {
        name: Some(name),
        pbr_metallic_roughness: PbrMetallicRoughness {
            base_color_factor: PbrBaseColorFactor([rgb[0], rgb[1], rgb[2], 1.0]),
            metallic_factor: StrengthFactor(metallic),
            roughness_factor: StrengthFactor(roughness),
            ..Default::default()
        },
        alpha_mode: Checked::Valid(json::material::AlphaMode::Opaque),
        ..Default::default()
    }
}

/// A balloon's material: `finish` in linear `rgb`; `age` from 0 (fresh) to
/// 1 (its float spent) dulls latex and grows its sheen, as the page does.
pub fn balloon(name: String, finish: Finish, rgb: [f32; 3], age: f32) -> Material {
    let age = age.clamp(0.0, 1.0);
    if finish == Finish::Foil {
        return plain(name, rgb, 0.12, 1.0);
    }
    let pearl = finish == Finish::Pearl;
    let roughness = if pearl { 0.35 } else { 0.35 + 0.15 * age };
    let mut material = plain(name, rgb, roughness, 0.0);
    let mut others = Map::new();
    let clearcoat = if pearl { 1.0 } else { 1.0 - 0.5 * age };
    others.insert(
        "KHR_materials_clearcoat".into(),
        value!({ "clearcoatFactor": clearcoat, "clearcoatRoughnessFactor": 0.1 }),
    );
    // By name: gltf-json's struct would write an infinite attenuation distance as null.
    others.insert(
        "KHR_materials_volume".into(),
        value!({ "thicknessFactor": 0.01 }),
    );
    if pearl {
        others.insert(
            "KHR_materials_iridescence".into(),
            value!({
                "iridescenceFactor": 1.0,
                "iridescenceIor": 1.3,
                "iridescenceThicknessMinimum": 250.0,
                "iridescenceThicknessMaximum": 380.0,
            }),
        );
    } else {
        let sheen = SHEEN_FRESH + (SHEEN_AGED - SHEEN_FRESH) * age;
        others.insert(
            "KHR_materials_sheen".into(),
            value!({ "sheenColorFactor": [sheen, sheen, sheen], "sheenRoughnessFactor": 0.6 }),
        );
    }
    material.extensions = Some(ext::Material {
        transmission: Some(ext::Transmission {
            transmission_factor: ext::TransmissionFactor(if pearl { 0.15 } else { 0.25 }),
            ..Default::default()
        }),
        ior: Some(ext::Ior {
            ior: ext::IndexOfRefraction(1.52),
            extras: Default::default(),
        }),
        others,
    });
    material
}

/// The names of the extensions `material` uses.
pub fn extensions_of(material: &Material) -> Vec<String> {
    let Some(e) = &material.extensions else {
        return Vec::new();
    };
    let text = serde_json::to_value(e).unwrap_or(Value::Null);
    text.as_object()
        .map(|o| o.keys().cloned().collect())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The extensions the materials may use, for `extensionsUsed`.
    const MATERIAL_EXTENSIONS: [&str; 6] = [
        "KHR_materials_clearcoat",
        "KHR_materials_transmission",
        "KHR_materials_volume",
        "KHR_materials_ior",
        "KHR_materials_sheen",
        "KHR_materials_iridescence",
    ];

    #[test]
    fn each_finish_carries_its_extensions() {
        let latex = balloon("l".into(), Finish::Latex, [1.0, 0.0, 0.0], 0.0);
        let pearl = balloon("p".into(), Finish::Pearl, [1.0, 0.0, 0.0], 0.0);
        let foil = balloon("f".into(), Finish::Foil, [1.0, 0.0, 0.0], 0.0);
        let mut names = extensions_of(&latex);
        names.sort();
        assert_eq!(
            names,
            [
                "KHR_materials_clearcoat",
                "KHR_materials_ior",
                "KHR_materials_sheen",
                "KHR_materials_transmission",
                "KHR_materials_volume"
            ]
        );
        assert!(extensions_of(&pearl).contains(&"KHR_materials_iridescence".to_string()));
        assert!(!extensions_of(&pearl).contains(&"KHR_materials_sheen".to_string()));
        assert!(extensions_of(&foil).is_empty());
        assert_eq!(foil.pbr_metallic_roughness.metallic_factor.0, 1.0);
        for name in names {
            assert!(MATERIAL_EXTENSIONS.contains(&name.as_str()));
        }
    }

    #[test]
    fn aged_latex_is_duller_and_more_velvet() {
        let sheen = |m: &Material| {
            let e = serde_json::to_value(m.extensions.as_ref().unwrap()).unwrap();
            e["KHR_materials_sheen"]["sheenColorFactor"][0]
                .as_f64()
                .unwrap()
        };
        let fresh = balloon("a".into(), Finish::Latex, [1.0; 3], 0.0);
        let aged = balloon("b".into(), Finish::Latex, [1.0; 3], 1.0);
        assert!(sheen(&aged) > sheen(&fresh));
        assert!(
            aged.pbr_metallic_roughness.roughness_factor.0
                > fresh.pbr_metallic_roughness.roughness_factor.0
        );
    }
}
