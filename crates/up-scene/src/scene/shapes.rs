//! A balloon group's shape keys: `shape` (`"round"`, `"pillow"`, `"heart"`,
//! `"star"`, `"digit"` with `text = "0"`…`"9"`) or `mesh = "file.obj"` with
//! an optional `knot = [x, y, z]`: their checks, and the surface and film
//! mass they give the balloon model.
//!
//! Round is the latex balloon, the rest foil (a foil shape asks for
//! `kind = "foil"`, round for latex); a mesh of one's own takes either kind
//! (the kind says how its gas leaks and how it is drawn). `size_in` (or
//! `diameter_m`) is the size as sold: a round balloon's width, a foil
//! shape's flat height (an 18″ heart, a 34″ digit).

use std::path::PathBuf;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::spec::{BalloonGroup, BalloonKind, Scene};
use super::validate::Checker;
use super::DEFAULT_FOIL_ENVELOPE_MASS_G_18IN;
use crate::balloon::foil_shape::sheet_area_m2;
use crate::balloon::outline::OutlineKind;
use crate::balloon::surface::{custom_mesh, BalloonSurface};
use crate::error::SceneError;

/// The shape of a group's balloons.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BalloonShape {
    /// The latex balloon (latex's default).
    Round,
    /// The round foil pillow (foil's default).
    Pillow,
    Heart,
    Star,
    /// A number balloon: the digit in `text`.
    Digit,
}

impl BalloonShape {
    pub fn name(self) -> &'static str {
        match self {
            Self::Round => "round",
            Self::Pillow => "pillow",
            Self::Heart => "heart",
            Self::Star => "star",
            Self::Digit => "digit",
        }
    }
}

/// kg/m² of foil film: the 18″ pillow's 9 g over its two 45.7 cm discs
/// (27 g/m²), for shapes cut from the same film.
pub fn foil_film_kg_per_m2() -> f32 {
    let r = 0.5 * 18.0 * super::METRES_PER_INCH;
    DEFAULT_FOIL_ENVELOPE_MASS_G_18IN * 1e-3 / (2.0 * std::f32::consts::PI * r * r)
}

impl BalloonGroup {
    /// `shape` as given, else round for latex, pillow for foil.
    pub fn shape(&self) -> BalloonShape {
        self.shape.unwrap_or(match self.kind {
            BalloonKind::Latex => BalloonShape::Round,
            BalloonKind::Foil => BalloonShape::Pillow,
        })
    }

    /// The foil outline a heart, star or digit is cut in; None otherwise.
    pub fn outline(&self) -> Option<OutlineKind> {
        match (self.mesh.is_some(), self.shape()) {
            (false, BalloonShape::Heart) => Some(OutlineKind::Heart),
            (false, BalloonShape::Star) => Some(OutlineKind::Star),
            (false, BalloonShape::Digit) => {
                let d = self.text.as_deref().and_then(|t| t.parse::<u8>().ok());
                Some(OutlineKind::Digit(d.unwrap_or(0).min(9)))
            }
            _ => None,
        }
    }

    /// kg of envelope: as given; for a heart, star or digit the film of its
    /// two sheets (`foil_film_kg_per_m2`); else the kind's default.
    pub fn shaped_envelope_mass_kg(&self) -> f32 {
        match (self.envelope_mass_g, self.outline()) {
            (None, Some(outline)) => {
                2.0 * sheet_area_m2(outline, self.diameter()) * foil_film_kg_per_m2()
            }
            _ => self.envelope_mass_kg(),
        }
    }
}

impl Scene {
    /// Group `i`'s `mesh`, relative to the scene file's folder.
    pub fn balloon_mesh_path(&self, i: usize) -> Option<PathBuf> {
        let mesh = std::path::Path::new(self.balloons.get(i)?.mesh.as_ref()?);
        Some(match &self.source.dir {
            Some(dir) if mesh.is_relative() => dir.join(mesh),
            _ => mesh.to_path_buf(),
        })
    }
}

/// The surface group `i`'s balloons are made of; reads its mesh file.
pub fn group_surface(scene: &Scene, i: usize) -> Result<BalloonSurface, SceneError> {
    let group = &scene.balloons[i];
    if let Some(path) = scene.balloon_mesh_path(i) {
        let fail = |message: String| SceneError::Balloon {
            at: scene.locate(&format!("balloons[{i}].mesh")),
            message,
        };
        let obj = crate::obj::read_obj_mesh(&path).map_err(|e| fail(e.to_string()))?;
        let name = path.display().to_string();
        let (vertices, triangles) = obj.into_parts();
        let knot = group.knot.map(Vec3::from_array);
        let mesh =
            custom_mesh(&name, vertices, triangles, knot).map_err(|e| fail(e.to_string()))?;
        return Ok(BalloonSurface::Custom { name, mesh });
    }
    Ok(match group.outline() {
        Some(outline) => BalloonSurface::FoilOutline(outline),
        None => BalloonSurface::Standard,
    })
}

/// The shape keys of group `i`.
pub(super) fn check_shape(c: &Checker, i: usize, group: &BalloonGroup) -> Result<(), SceneError> {
    let key = |k: &str| format!("balloons[{i}].{k}");
    if let Some(mesh) = &group.mesh {
        if group.shape.is_some() {
            return Err(c.fail(&key("shape"), "either shape or mesh, not both", "both"));
        }
        if mesh.trim().is_empty() {
            return Err(c.fail(
                &key("mesh"),
                "the path of a closed OBJ mesh",
                "an empty string",
            ));
        }
    } else if group.knot.is_some() {
        return Err(c.fail(
            &key("knot"),
            "a knot only with mesh = \"file.obj\" (the shapes place their own)",
            "knot without mesh",
        ));
    }
    if let Some(knot) = group.knot {
        c.vector(&key("knot"), knot, 10.0, "m")?;
    }
    if let Some(shape) = group.shape {
        let foil = shape != BalloonShape::Round;
        let kind_ok = foil == (group.kind == BalloonKind::Foil);
        if !kind_ok {
            let expected = if foil {
                format!("kind = \"foil\" for a {} (a foil shape)", shape.name())
            } else {
                "kind = \"latex\" for a round balloon (foil's own is \"pillow\")".to_string()
            };
            return Err(c.fail(&key("shape"), expected, format!("\"{}\"", shape.name())));
        }
    }
    let digit = group.shape == Some(BalloonShape::Digit);
    match (&group.text, digit) {
        (Some(t), true) if t.len() == 1 && t.as_bytes()[0].is_ascii_digit() => Ok(()),
        (Some(t), true) => Err(c.fail(&key("text"), "one digit, \"0\" to \"9\"", format!("{t:?}"))),
        (None, true) => Err(c.fail(
            &key("text"),
            "the digit of a shape = \"digit\" balloon, \"0\" to \"9\"",
            "nothing",
        )),
        (Some(t), false) => Err(c.fail(
            &key("text"),
            "text only with shape = \"digit\"",
            format!("{t:?}"),
        )),
        (None, false) => Ok(()),
    }
}
