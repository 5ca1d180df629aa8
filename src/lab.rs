//! What the teaching subcommands share: a scene read and overridden as
//! `render` does, and the exact surface of its model when it has one.

use std::path::{Path, PathBuf};

use shadelab_core::{RenderOptions, Scene};
use shadelab_io::SceneFile;
use shadelab_lab::{Surface, EXACT_MODELS};

use crate::cli::SceneOverrides;
use crate::{input_error, read_scene, resolve, Failure};

/// A scene ready to draw.
pub struct Loaded {
    /// The file as overridden.
    pub file: SceneFile,
    /// What to draw.
    pub scene: Scene,
    /// How.
    pub options: RenderOptions,
    /// The files it was read from (never to be written over).
    pub inputs: Vec<PathBuf>,
}

/// Reads the scene (or the defaults), gives it `default_size` when neither
/// the file nor a flag sets one and `default_model` when none names a
/// model, applies the flags, and resolves it.
pub fn load(
    scene_path: Option<&Path>,
    overrides: &SceneOverrides,
    default_size: Option<(u32, u32)>,
    default_model: Option<&str>,
) -> Result<Loaded, Failure> {
    let mut file = read_scene(scene_path)?;
    if let Some((w, h)) = default_size {
        if file.render.width.is_none() && file.render.height.is_none() {
            file.render.width = Some(w);
            file.render.height = Some(h);
        }
    }
    if let Some(model) = default_model {
        if file.model.source.is_none() {
            file.model.source = Some(model.to_owned());
        }
    }
    overrides
        .apply(&mut file, scene_path.is_some())
        .map_err(input_error)?;
    let (scene, options, inputs) = resolve(&file, scene_path)?;
    Ok(Loaded {
        file,
        scene,
        options,
        inputs,
    })
}

impl Loaded {
    /// Fails when drawing this scene at `bytes_per_pixel` would need more
    /// memory than the limit ([`crate::memory::check`]).
    pub fn check_memory(&self, command: &str, bytes_per_pixel: u64) -> Result<(), Failure> {
        let pixels = u64::from(self.options.width) * u64::from(self.options.height);
        crate::memory::check(command, Some(&self.scene.mesh), pixels, bytes_per_pixel)
    }
}

/// The exact surface of the scene's model, placed as the mesh is.
pub fn exact_surface(file: &SceneFile) -> Option<Surface> {
    let source = file.model.source.as_deref().unwrap_or("teapot");
    Surface::for_builtin(source, file.model.detail, file.camera.is_none())
}

/// The exact surface, or an input error saying which models have one.
pub fn require_exact_surface(file: &SceneFile) -> Result<Surface, Failure> {
    exact_surface(file).ok_or_else(|| {
        input_error(anyhow::anyhow!(
            "model {:?} has no exact surface; the exact surface is known for the built-in {}",
            file.model.source.as_deref().unwrap_or("teapot"),
            EXACT_MODELS.join(", ")
        ))
    })
}

impl From<shadelab_core::RenderError> for Failure {
    fn from(e: shadelab_core::RenderError) -> Failure {
        input_error(e)
    }
}
