//! `[about]`: what a scene shows, for a page to caption it with (the
//! teaching scenes, `assets/scenes/learn-*.toml`). Optional; it changes
//! nothing in the world.

use serde::{Deserialize, Serialize};

use super::Scene;
use crate::error::SceneError;

/// Longest title, characters.
pub const MAX_TITLE_CHARS: usize = 80;
/// Longest caption, characters: a paragraph.
pub const MAX_CAPTION_CHARS: usize = 1200;

/// A scene's title and caption.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AboutSpec {
    /// One line.
    pub title: String,
    /// One paragraph: what to watch and why.
    pub caption: String,
}

/// A title of one line and a caption of one paragraph, neither empty nor too long.
pub(super) fn check(scene: &Scene) -> Result<(), SceneError> {
    let Some(about) = &scene.about else {
        return Ok(());
    };
    let fail = |key: &str, expected: String, found: &str| {
        let shown: String = found.chars().take(40).collect();
        Err(SceneError::Invalid {
            at: scene.locate(key),
            expected,
            found: format!(
                "{shown:?}{}",
                if shown.len() < found.len() { "…" } else { "" }
            ),
        })
    };
    let title = &about.title;
    if title.trim().is_empty() || title.contains('\n') || title.chars().count() > MAX_TITLE_CHARS {
        return fail(
            "about.title",
            format!("one line of 1 to {MAX_TITLE_CHARS} characters"),
            title,
        );
    }
    let caption = &about.caption;
    if caption.trim().is_empty()
        || caption.trim().contains("\n\n")
        || caption.chars().count() > MAX_CAPTION_CHARS
    {
        return fail(
            "about.caption",
            format!("one paragraph of 1 to {MAX_CAPTION_CHARS} characters (no blank line)"),
            caption,
        );
    }
    Ok(())
}
