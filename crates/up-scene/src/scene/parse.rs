//! Reading a scene from TOML or JSON text, and writing it back. Unknown keys
//! are errors, and so is a text of nothing but whitespace (what a failed
//! write leaves). The key path of a parse error is serde's own
//! (`serde_path_to_error`), its line the parser's; a parsed scene is then
//! validated (`validate`), its errors located by `lines`.

use serde::Deserialize;

use super::{lines, KeyLines, Scene, SceneSource};
use crate::error::{Location, SceneError};

impl Scene {
    /// Parses and validates TOML; `source` names it in messages (a file name).
    pub fn from_toml_str(text: &str, source: &str) -> Result<Scene, SceneError> {
        refuse_empty(text, source)?;
        let parsed = serde_path_to_error::deserialize(toml::Deserializer::new(text));
        let scene = parsed.map_err(|e| {
            let key = key_path(e.path());
            let e = e.into_inner();
            let line = e.span().map(|span| lines::line_of_offset(text, span.start));
            parse_error(source, key, line, e.message().trim().to_string())
        })?;
        Self::finish_parse(scene, source, KeyLines::from_toml(text))
    }

    /// Parses and validates JSON; `source` names it in messages (a file name).
    pub fn from_json_str(text: &str, source: &str) -> Result<Scene, SceneError> {
        refuse_empty(text, source)?;
        let mut deserializer = serde_json::Deserializer::from_str(text);
        // `end` refuses text after the scene, as `serde_json::from_str` does.
        let parsed = match serde_path_to_error::deserialize(&mut deserializer) {
            Ok(scene) => deserializer.end().map(|()| scene).map_err(|e| (None, e)),
            Err(e) => Err((key_path(e.path()), e.into_inner())),
        };
        let scene = parsed.map_err(|(key, e)| {
            let line = (e.line() > 0).then_some(e.line());
            // serde_json appends " at line L column C"; the location says it already.
            let full = e.to_string();
            let message = match full.rfind(" at line ") {
                Some(cut) => full[..cut].to_string(),
                None => full,
            };
            parse_error(source, key, line, message)
        })?;
        Self::finish_parse(scene, source, KeyLines::from_json(text))
    }

    /// A parsed scene with its source attached, validated.
    fn finish_parse(mut scene: Scene, source: &str, lines: KeyLines) -> Result<Scene, SceneError> {
        scene.source = SceneSource {
            name: source.to_string(),
            dir: None,
            lines,
        };
        scene.validate()?;
        scene.air.temperature_c = scene.air.start_temperature_c();
        Ok(scene)
    }

    /// The scene as written out: `temperature_c` is the schedule's first
    /// temperature when there is a schedule, so the text reads back.
    fn normalized(&self) -> std::borrow::Cow<'_, Scene> {
        let start = self.air.start_temperature_c();
        if start.to_bits() == self.air.temperature_c.to_bits() {
            return std::borrow::Cow::Borrowed(self);
        }
        let mut scene = self.clone();
        scene.air.temperature_c = start;
        std::borrow::Cow::Owned(scene)
    }

    pub fn to_toml_string(&self) -> Result<String, SceneError> {
        toml::to_string_pretty(self.normalized().as_ref()).map_err(|e| SceneError::Serialize {
            format: "TOML",
            message: e.to_string(),
        })
    }

    pub fn to_json_string(&self) -> Result<String, SceneError> {
        serde_json::to_string_pretty(self.normalized().as_ref()).map_err(|e| {
            SceneError::Serialize {
                format: "JSON",
                message: e.to_string(),
            }
        })
    }
}

/// A scene of nothing but whitespace is an error, not the default scene: it is
/// what an interrupted write or a truncated copy leaves.
fn refuse_empty(text: &str, source: &str) -> Result<(), SceneError> {
    if text.trim().is_empty() {
        return Err(SceneError::Empty {
            file: source.to_string(),
        });
    }
    Ok(())
}

/// The key path serde was in when it failed (`room.width`, `balloons[0].count`);
/// `None` at the top level.
fn key_path(path: &serde_path_to_error::Path) -> Option<String> {
    path.iter().next().is_some().then(|| path.to_string())
}

fn parse_error(
    source: &str,
    key: Option<String>,
    line: Option<usize>,
    message: String,
) -> SceneError {
    SceneError::Parse {
        at: Location {
            file: source.to_string(),
            key,
            line,
        },
        message,
    }
}

/// `[[a, b], ...]` with exactly two numbers a point: TOML's reader would
/// drop a third number unseen if read straight into `[f32; 2]`.
pub(super) fn pairs<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<Vec<[f32; 2]>, D::Error> {
    let points = Vec::<Vec<f32>>::deserialize(deserializer)?;
    points
        .into_iter()
        .enumerate()
        .map(|(i, point)| {
            <[f32; 2]>::try_from(point.as_slice()).map_err(|_| {
                serde::de::Error::custom(format!(
                    "point {i}: expected [hours, °C], two numbers, found {}",
                    point.len()
                ))
            })
        })
        .collect()
}

/// `[x, y, z]`, exactly three numbers (as `pairs`, TOML's reader would drop
/// a fourth unseen if read straight into `[f32; 3]`).
pub(super) fn point<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<Option<[f32; 3]>, D::Error> {
    let Some(point) = Option::<Vec<f32>>::deserialize(deserializer)? else {
        return Ok(None);
    };
    <[f32; 3]>::try_from(point.as_slice())
        .map(Some)
        .map_err(|_| {
            serde::de::Error::custom(format!(
                "expected [x, y, z], three numbers, found {}",
                point.len()
            ))
        })
}

/// `[x, y, z]` that must be given, exactly three numbers (as `point`).
pub(super) fn xyz<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<[f32; 3], D::Error> {
    let point = Vec::<f32>::deserialize(deserializer)?;
    <[f32; 3]>::try_from(point.as_slice()).map_err(|_| {
        serde::de::Error::custom(format!(
            "expected [x, y, z], three numbers, found {}",
            point.len()
        ))
    })
}

/// `[[start, end], ...]`, s, each exactly two numbers (as `pairs`).
pub(super) fn intervals<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<Vec<[f64; 2]>, D::Error> {
    let intervals = Vec::<Vec<f64>>::deserialize(deserializer)?;
    intervals
        .into_iter()
        .enumerate()
        .map(|(i, interval)| {
            <[f64; 2]>::try_from(interval.as_slice()).map_err(|_| {
                serde::de::Error::custom(format!(
                    "interval {i}: expected [start, end] in s, two numbers, found {}",
                    interval.len()
                ))
            })
        })
        .collect()
}
