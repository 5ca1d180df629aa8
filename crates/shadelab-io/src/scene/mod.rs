//! The TOML scene format: every parameter of a render in one file.
//!
//! [`SceneFile`] mirrors the file (every section and key optional, with the
//! documented defaults); command-line flags override its fields; then
//! [`SceneFile::resolve`] checks every value, loads the model and builds the
//! core's [`Scene`](shadelab_core::Scene) and
//! [`RenderOptions`](shadelab_core::RenderOptions). Errors name the key at
//! fault.
//!
//! A model file's material (an OBJ file's `.mtl` colours, see
//! [`crate::load_mesh_file`]) fills in what the scene leaves unset: `kd` takes
//! the material's `Kd`, and `ka` its `Ka`, or its `Kd` when it gives no `Ka`.
//! A value in the scene (or a flag) always wins.
//!
//! This file holds the format (the sections and their keys) and its
//! reading; `resolve.rs` checks the values and builds the scene. Each
//! key's default, range, unit and help are the core's table of parameters
//! ([`shadelab_core::params`]), which the command line and the page read too.

mod resolve;

pub use resolve::model_path;

use std::path::Path;

use serde::{Deserialize, Serialize};
use shadelab_core::limits::MAX_SCENE_BYTES;
use shadelab_core::params;
pub use shadelab_core::params::{
    AmbientSection, CameraSection, LightSection, MaterialSection, ModelSection, RenderSection,
};
pub use shadelab_core::{LightKindName, NormalsChoice};

use crate::input::{read_capped, unify_line_ends};
use crate::LoadError;

/// A scene file as written: every key optional.
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// `[model]`
    #[serde(default)]
    pub model: ModelSection,
    /// `[camera]`; absent: the camera frames the model's bounding sphere.
    pub camera: Option<CameraSection>,
    /// `[ambient]`
    #[serde(default)]
    pub ambient: AmbientSection,
    /// `[[lights]]`; absent: one white point light at (2, 2, 3).
    pub lights: Option<Vec<LightSection>>,
    /// `[material]`
    #[serde(default)]
    pub material: MaterialSection,
    /// `[render]`
    #[serde(default)]
    pub render: RenderSection,
}

/// The range of `render.zoom` (declared with the other parameters in core).
pub use shadelab_core::params::{MAX_ZOOM, MIN_ZOOM};

/// The light of a scene that gives none: a white point light at the
/// table's default position (`lights.position`).
pub(crate) fn default_light() -> LightSection {
    let [x, y, z] = params::get("lights.position").default_three();
    LightSection {
        kind: LightKindName::Point,
        position: Some([x as f32, y as f32, z as f32]),
        ..LightSection::default()
    }
}

/// Why a scene could not be read or used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
    /// The TOML is malformed, a key is unknown or a value has the wrong type.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: String,
        /// The parser's message, with line and column.
        message: String,
    },
    /// A value is out of range.
    #[error("{key}: {message}")]
    Value {
        /// The key at fault, e.g. `material.shininess`.
        key: String,
        /// What is wrong with it.
        message: String,
    },
    /// The model could not be loaded.
    #[error(transparent)]
    Model(#[from] LoadError),
}

pub(crate) fn value_error(key: impl Into<String>, message: impl Into<String>) -> SceneError {
    SceneError::Value {
        key: key.into(),
        message: message.into(),
    }
}

impl SceneFile {
    /// Reads a scene file.
    ///
    /// # Errors
    /// [`SceneError::Io`] or [`SceneError::Parse`] (with line and column).
    /// Reads a scene file: a regular file of at most [`MAX_SCENE_BYTES`] of
    /// UTF-8 (a FIFO, a device or a directory is refused without waiting on
    /// it), parsed as [`SceneFile::parse`] does.
    ///
    /// # Errors
    /// [`SceneError::Io`] when it cannot be read, is not a regular file or
    /// is too large, or [`SceneError::Parse`] (with line and column).
    pub fn load(path: &Path) -> Result<SceneFile, SceneError> {
        let text = SceneFile::read_text(path)?;
        SceneFile::parse(&text, &path.display().to_string())
    }

    /// The text of a scene file, read as [`SceneFile::load`] reads it (a
    /// regular file, at most [`MAX_SCENE_BYTES`], UTF-8), not yet parsed:
    /// for callers that merge other settings into the TOML first.
    ///
    /// # Errors
    /// As [`SceneFile::load`].
    pub fn read_text(path: &Path) -> Result<String, SceneError> {
        let name = path.display().to_string();
        let io = |source| SceneError::Io {
            path: name.clone(),
            source,
        };
        let bytes = read_capped(path, MAX_SCENE_BYTES).map_err(|e| match e {
            LoadError::Io { source, .. } => io(source),
            LoadError::Invalid { message, .. } => io(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                message,
            )),
            other => io(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                match other {
                    LoadError::TooLarge { bytes, limit, .. } => format!(
                        "{bytes} bytes is more than the limit of {limit} bytes for a scene file"
                    ),
                    other => other.to_string(),
                },
            )),
        })?;
        let text = String::from_utf8(bytes).map_err(|e| SceneError::Parse {
            path: name.clone(),
            message: format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        })?;
        Ok(text)
    }

    /// Sets each scene-file key of `edits` (`material.ks`; a light's, as
    /// `lights.position`, is the first light's, made when there is none) to
    /// its value, or removes it (`None`), in order, as if the file had said
    /// so. The command line's flags write themselves here, by the key the
    /// table of parameters gives them ([`shadelab_core::params`]): the
    /// scene goes to TOML and back once for all of them.
    ///
    /// # Errors
    /// [`SceneError::Value`] naming the key when it is not `section.key` of
    /// the format, or the keys when a value is not of its key's type.
    pub fn edit(&mut self, edits: &[(&str, Option<toml::Value>)]) -> Result<(), SceneError> {
        let keys = || edits.iter().map(|(k, _)| *k).collect::<Vec<_>>().join(", ");
        let mut document =
            toml::Table::try_from(&*self).map_err(|e| value_error(keys(), e.to_string()))?;
        for (key, value) in edits {
            let bad = |message: String| value_error(*key, message);
            let (section, field) = key
                .split_once('.')
                .ok_or_else(|| bad("not a key of the form section.key".to_owned()))?;
            let slot = document.entry(section).or_insert_with(|| match section {
                "lights" => toml::Value::Array(Vec::new()),
                _ => toml::Value::Table(toml::Table::new()),
            });
            let table = match slot {
                toml::Value::Array(lights) => {
                    if lights.is_empty() {
                        let light = toml::Value::try_from(default_light())
                            .map_err(|e| bad(e.to_string()))?;
                        lights.push(light);
                    }
                    lights[0].as_table_mut()
                }
                other => other.as_table_mut(),
            }
            .ok_or_else(|| bad(format!("[{section}] is not a section")))?;
            match value {
                Some(v) => table.insert(field.to_owned(), v.clone()),
                None => table.remove(field),
            };
        }
        *self = SceneFile::deserialize(toml::Value::Table(document))
            .map_err(|e| value_error(keys(), e.message().to_owned()))?;
        Ok(())
    }

    /// Parses scene TOML; `name` is used in error messages. Lines may end
    /// with LF, CR LF or a lone CR. A value of the wrong type or length is
    /// reported with its key (`lights[0].position`), line and column.
    ///
    /// # Errors
    /// [`SceneError::Parse`].
    pub fn parse(text: &str, name: &str) -> Result<SceneFile, SceneError> {
        let text = unify_line_ends(text);
        let parse_error = |mut e: toml::de::Error, key: Option<String>| {
            e.set_input(Some(&text));
            let message = e.to_string();
            SceneError::Parse {
                path: name.to_owned(),
                message: match key {
                    Some(key) => format!("{key}: {message}"),
                    None => message,
                },
            }
        };
        let document = toml::Deserializer::parse(&text).map_err(|e| parse_error(e, None))?;
        serde_path_to_error::deserialize(document).map_err(|e| {
            let key = e.path().to_string();
            let key = (key != ".").then_some(key);
            parse_error(e.into_inner(), key)
        })
    }
}
