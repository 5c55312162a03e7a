//! Errors from reading, checking and building scenes.
//!
//! Every message names the scene (its file, or `<default scene>`), the key path
//! in it (`balloons[0].count`) and the line where it is known, then says what
//! was expected: `party.toml:7: balloons[0].count: expected at most 200000 ...`.

use std::fmt;
use std::path::PathBuf;

use thiserror::Error;
use up_physics::PhysicsError;

/// Where in a scene a problem lies: the file, the key path, the line (1-based).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The scene's file name as given, or `<default scene>`.
    pub file: String,
    /// Key path such as `room.width` or `balloons[2].spawn.min`, when known.
    pub key: Option<String>,
    /// 1-based line in the file, when the parser or the key index knows it.
    pub line: Option<usize>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if let Some(key) = &self.key {
            write!(f, ": {key}")?;
        }
        Ok(())
    }
}

#[derive(Debug, Error)]
pub enum SceneError {
    /// The file could not be read (it does not exist, is a directory, ...).
    #[error("{}: cannot read the scene file: {source}", path.display())]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// The file is larger than a scene can be (`scene::MAX_SCENE_BYTES`).
    #[error("{}: too large: expected a scene file of at most {max} bytes", path.display())]
    TooLarge { path: PathBuf, max: u64 },
    /// The scene is empty or only whitespace (a failed write leaves such a file).
    #[error("{file}: the scene is empty: expected TOML or JSON text (`{{}}` in JSON, or a comment in TOML, for the default scene)")]
    Empty { file: String },
    /// The extension is neither `.toml` nor `.json`.
    #[error("{}: unknown scene file type: expected a `.toml` or `.json` extension", path.display())]
    UnknownFormat { path: PathBuf },
    /// The text is not valid TOML/JSON, or does not match the schema
    /// (unknown key, wrong type).
    #[error("{at}: {message}")]
    Parse { at: Location, message: String },
    /// A value is out of its documented range or not finite.
    #[error("{at}: expected {expected}, found {found}")]
    Invalid {
        at: Location,
        expected: String,
        found: String,
    },
    /// The balloons of a group cannot be placed without overlapping each other or the room.
    #[error(
        "{at}: {requested} balloons do not fit: only {placed} could be placed without \
         overlap (expected fewer balloons, smaller balloons, or a larger spawn region or room)"
    )]
    DoesNotFit {
        at: Location,
        requested: u64,
        placed: u64,
    },
    /// The balloon model could not be built from the group's parameters.
    #[error("{at}: cannot build the balloon: {message}")]
    Balloon { at: Location, message: String },
    /// The room could not be built (bad OBJ mesh, degenerate box).
    #[error("{at}: cannot build the room: {message}")]
    Room { at: Location, message: String },
    /// The physics world rejected a parameter or body.
    #[error("{file}: cannot create the world: {source}")]
    Physics {
        file: String,
        #[source]
        source: PhysicsError,
    },
    /// The scene could not be written as TOML or JSON.
    #[error("cannot write the scene as {format}: {message}")]
    Serialize {
        format: &'static str,
        message: String,
    },
}

impl SceneError {
    /// Where the problem lies, for the errors that point into a scene.
    pub fn location(&self) -> Option<&Location> {
        match self {
            SceneError::Parse { at, .. }
            | SceneError::Invalid { at, .. }
            | SceneError::DoesNotFit { at, .. }
            | SceneError::Balloon { at, .. }
            | SceneError::Room { at, .. } => Some(at),
            _ => None,
        }
    }

    /// The key path of the offending value, when known (`balloons[0].count`).
    pub fn key(&self) -> Option<&str> {
        self.location().and_then(|at| at.key.as_deref())
    }

    /// The 1-based line of the offending value, when known.
    pub fn line(&self) -> Option<usize> {
        self.location().and_then(|at| at.line)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn location_prints_file_line_and_key() {
        let at = Location {
            file: "a.toml".into(),
            key: Some("room.width".into()),
            line: Some(3),
        };
        assert_eq!(at.to_string(), "a.toml:3: room.width");
        let at = Location {
            file: "a.toml".into(),
            key: None,
            line: None,
        };
        assert_eq!(at.to_string(), "a.toml");
    }

    #[test]
    fn invalid_message_says_what_was_expected() {
        let e = SceneError::Invalid {
            at: Location {
                file: "s.json".into(),
                key: Some("sim.dt".into()),
                line: Some(9),
            },
            expected: "a step in (0, 0.1] s".into(),
            found: "0.5".into(),
        };
        assert_eq!(
            e.to_string(),
            "s.json:9: sim.dt: expected a step in (0, 0.1] s, found 0.5"
        );
        assert_eq!(e.key(), Some("sim.dt"));
        assert_eq!(e.line(), Some(9));
    }
}
