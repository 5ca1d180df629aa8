//! One mesh made ready to be drawn from several cameras in several modes.
//!
//! The scene is built exactly as `shadelab render` builds it
//! ([`SceneFile`]'s checks, normals, framing, the model file's material),
//! with the mesh loaded once; each frame then only moves the camera (the
//! view's yaw and pitch added to the scene's) and picks the method.

use std::path::Path;

use shadelab_core::{Image, Mesh, RenderOptions, RenderStats, Renderer, Scene, Shading};
use shadelab_io::{load_mesh_file, FileMaterial, SceneError, SceneFile};

use crate::plan::View;

/// A loaded mesh with its scene and options.
#[derive(Debug)]
pub struct PreparedMesh {
    file: SceneFile,
    scene: Scene,
    options: RenderOptions,
    material: Option<FileMaterial>,
}

impl PreparedMesh {
    /// Loads the mesh file `path` under the shared `settings`, at `size`
    /// when given (else the settings' size).
    ///
    /// # Errors
    /// The scene's or the mesh file's error, with the message `render` gives.
    pub fn load(
        settings: &SceneFile,
        path: &Path,
        size: Option<(u32, u32)>,
    ) -> Result<PreparedMesh, SceneError> {
        let mut file = settings.clone();
        file.model.source = Some(path.to_string_lossy().into_owned());
        if let Some((w, h)) = size {
            file.render.width = Some(w);
            file.render.height = Some(h);
        }
        let options = file.render_options()?;
        let mut material = None;
        let (mesh, crease) = file.model_mesh(|_| {
            let loaded = load_mesh_file(path)?;
            material = loaded.material;
            Ok(loaded.mesh)
        })?;
        PreparedMesh::build(file, options, mesh, crease, material)
    }

    /// `mesh` (already in memory) under `settings`.
    ///
    /// # Errors
    /// The scene's error.
    pub fn from_mesh(settings: &SceneFile, mesh: Mesh) -> Result<PreparedMesh, SceneError> {
        let mut file = settings.clone();
        // Not a built-in name, so the closure below supplies the mesh.
        file.model.source = Some("<mesh>".into());
        let options = file.render_options()?;
        let (mesh, crease) = file.model_mesh(|_| Ok(mesh))?;
        PreparedMesh::build(file, options, mesh, crease, None)
    }

    fn build(
        file: SceneFile,
        options: RenderOptions,
        mesh: Mesh,
        crease: Option<f32>,
        material: Option<FileMaterial>,
    ) -> Result<PreparedMesh, SceneError> {
        let (mesh, normals) = file.prepare_model(mesh, crease)?;
        let mut scene = file.build_scene(mesh, normals, &options)?;
        file.update_scene_with_file_material(&mut scene, &options, material.as_ref())?;
        Ok(PreparedMesh {
            file,
            scene,
            options,
            material,
        })
    }

    /// The mesh's triangles (a polygon of n corners counts n − 2).
    pub fn triangles(&self) -> usize {
        self.scene.mesh.triangle_count()
    }

    /// The memory drawing this mesh needs, estimated as `render` estimates
    /// it (`shadelab_core::limits::memory_estimate`): the mesh and one frame.
    pub fn memory_estimate(&self) -> u64 {
        shadelab_core::limits::memory_estimate(
            self.scene.mesh.positions().len(),
            self.scene.mesh.triangle_count(),
            u64::from(self.options.width) * u64::from(self.options.height),
            shadelab_core::limits::RENDER_BYTES_PER_PIXEL,
        )
    }

    /// The scene as the last frame drew it (or as loaded).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The options every frame shares (size, background, …).
    pub fn options(&self) -> &RenderOptions {
        &self.options
    }

    /// Draws the mesh from `view` with `mode` into `image`.
    ///
    /// # Errors
    /// The scene's error for this camera, or the renderer's.
    pub fn render(
        &mut self,
        renderer: &mut Renderer,
        view: &View,
        mode: Shading,
        image: &mut Image,
    ) -> Result<RenderStats, String> {
        let mut file = self.file.clone();
        file.render.yaw = Some(file.render.yaw.unwrap_or(0.0) + view.yaw);
        file.render.pitch = Some(file.render.pitch.unwrap_or(0.0) + view.pitch);
        file.update_scene_with_file_material(
            &mut self.scene,
            &self.options,
            self.material.as_ref(),
        )
        .map_err(|e| e.to_string())?;
        let options = RenderOptions {
            shading: mode,
            ..self.options
        };
        renderer
            .render_into(&self.scene, &options, image)
            .map_err(|e| e.to_string())
    }
}
