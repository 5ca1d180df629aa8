//! The engine behind one viewer panel: the user's file, the prepared model
//! kept from frame to frame, the renderer's buffers and the last frame.
//!
//! A frame is asked for with the whole scene as TOML text, every time. Only
//! the `[model]` section (with whether a `[camera]` is given, which decides
//! whether the mesh is normalised) determines the mesh and its normals, so
//! those are prepared again only when that part changes; the camera, lights,
//! material and options are read from the text through the same
//! [`SceneFile`] functions that `shadelab render` uses. A text that differs
//! from the last only in the camera's yaw, pitch and zoom (a drag, an arrow
//! key) is not read again as a whole: those values are set on the scene
//! file kept from it (`camera_patch`), so a turning frame reads no TOML,
//! builds no normals and allocates nothing.

use shadelab_core::{
    CornerNormals, Image, Mesh, RenderOptions, RenderStats, Renderer, Rgb8, Scene, Shading,
};
use shadelab_io::{parse_mesh, ModelSection, SceneError, SceneFile};

use crate::replies::{frame_info, EngineCounts, FileSummary, FrameInfo, ModelEntry};

/// Largest file the viewer reads, in bytes (128 MiB). The file is parsed
/// once, but each panel's worker keeps its own copy of the mesh in a 32-bit
/// address space; the command line reads files up to
/// [`shadelab_io::MAX_MESH_BYTES`].
pub const MAX_FILE_BYTES: usize = 128 << 20;

/// Why a request failed: the text shown to the user.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EngineError(pub String);

impl std::fmt::Display for EngineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for EngineError {}

impl From<SceneError> for EngineError {
    fn from(e: SceneError) -> EngineError {
        EngineError(e.to_string())
    }
}

/// What decides the prepared mesh and normals.
#[derive(Debug, Clone, PartialEq)]
struct ModelKey {
    model: ModelSection,
    has_camera: bool,
    file_generation: u64,
}

/// The user's file, parsed.
#[derive(Debug)]
struct UserFile {
    name: String,
    mesh: Mesh,
    /// The file's normals exactly as the parsing engine had them, when the
    /// mesh's differ by the rounding of normalising them again (an adopted
    /// mesh; see `shared_mesh`).
    exact_normals: Option<CornerNormals>,
}

/// Renders panels from scene text, keeping the prepared model between frames
/// while the scene's `[model]` section (and whether it gives a camera) stays the same.
#[derive(Debug, Default)]
pub struct Engine {
    pub(crate) renderer: Renderer,
    /// The user's file, and a count that changes with each file loaded.
    file: Option<UserFile>,
    file_generation: u64,
    /// The scene last asked for, with the key of its model and the text it
    /// was read from.
    pub(crate) prepared: Option<Prepared>,
    /// The last frame: the text it was drawn from, its options, its pixels
    /// (also as RGBA).
    pub(crate) frame_toml: String,
    pub(crate) image: Option<Image>,
    pub(crate) options: Option<RenderOptions>,
    pub(crate) rgba: Vec<u8>,
    /// The instruments' state: the last error map, and the images of the
    /// last instrument request.
    pub(crate) errors: Option<crate::instruments::KeptErrors>,
    pub(crate) images: Vec<Vec<u8>>,
    /// The three methods' frames of [`Engine::render_methods`], kept for
    /// their buffers.
    methods: Vec<Image>,
    counts: EngineCounts,
}

/// A scene ready to draw, and what it was made from.
#[derive(Debug)]
pub(crate) struct Prepared {
    key: ModelKey,
    toml: String,
    file: SceneFile,
    options: RenderOptions,
    pub(crate) scene: Scene,
}

/// A scene read from text, as [`Engine::load_scene`] leaves it.
pub(crate) struct Loaded<'a> {
    pub file: &'a SceneFile,
    pub options: RenderOptions,
}

impl Engine {
    /// A new engine with no file loaded.
    pub fn new() -> Engine {
        Engine::default()
    }

    /// The built-in models.
    pub fn models() -> Vec<ModelEntry> {
        shadelab_core::BUILTIN_MODELS
            .iter()
            .map(|m| ModelEntry {
                name: m.name,
                description: m.description,
                detail_meaning: m.detail_meaning,
                default_detail: m.default_detail,
                detail_min: m.detail_range.0,
                detail_max: m.detail_range.1,
                default_crease: m.default_crease_degrees,
            })
            .collect()
    }

    /// Parses the user's mesh file (the format chosen by `name`'s
    /// extension) and keeps it as the file scenes can name. On error the
    /// previous file stays.
    ///
    /// # Errors
    /// The loader's message (naming the file and the line or byte offset),
    /// or that the file is larger than [`MAX_FILE_BYTES`].
    pub fn load_file(&mut self, name: &str, bytes: &[u8]) -> Result<FileSummary, EngineError> {
        if bytes.len() > MAX_FILE_BYTES {
            return Err(EngineError(format!(
                "{name}: {} bytes is more than the viewer's limit of {} MiB",
                bytes.len(),
                MAX_FILE_BYTES >> 20
            )));
        }
        check_file_name(name)?;
        self.counts.files_parsed += 1;
        let mesh = parse_mesh(bytes, name).map_err(|e| EngineError(e.to_string()))?;
        Ok(self.keep_file(name, mesh, None))
    }

    /// Takes the mesh another engine parsed, as [`Engine::shared_file`] gave
    /// it, as the file scenes can name: the panels parse the user's file
    /// once. On error the previous file stays.
    ///
    /// # Errors
    /// When `name` is a built-in model's, or the bytes are not a mesh
    /// [`Engine::shared_file`] wrote.
    pub fn adopt_file(&mut self, name: &str, bytes: &[u8]) -> Result<FileSummary, EngineError> {
        check_file_name(name)?;
        let (mesh, exact_normals) = crate::shared_mesh::decode(bytes)?;
        self.counts.files_adopted += 1;
        Ok(self.keep_file(name, mesh, exact_normals))
    }

    /// The loaded file's mesh as bytes for [`Engine::adopt_file`] (None
    /// before a file is loaded).
    pub fn shared_file(&self) -> Option<Vec<u8>> {
        self.file
            .as_ref()
            .map(|f| crate::shared_mesh::encode(&f.mesh))
    }

    fn keep_file(
        &mut self,
        name: &str,
        mesh: Mesh,
        exact_normals: Option<CornerNormals>,
    ) -> FileSummary {
        let summary = FileSummary {
            name: name.to_owned(),
            vertices: mesh.positions().len(),
            polygons: mesh.polygon_count(),
            triangles: mesh.triangle_count(),
            has_normals: mesh.file_normals().is_some(),
        };
        self.file = Some(UserFile {
            name: name.to_owned(),
            mesh,
            exact_normals,
        });
        self.file_generation += 1;
        summary
    }

    /// How often the engine parsed, prepared and drew.
    pub fn counts(&self) -> EngineCounts {
        self.counts
    }

    /// Renders the scene `toml` (a scene file's text) into the engine's
    /// frame; [`Engine::rgba`] then holds its pixels.
    ///
    /// # Errors
    /// The scene's error naming the key (as `shadelab render` reports it),
    /// or that `model.source` names a file that has not been loaded.
    pub fn render(&mut self, toml: &str) -> Result<FrameInfo, EngineError> {
        let Loaded { options, .. } = self.load_scene(toml)?;
        let scene = &self.prepared.as_ref().expect("load_scene keeps it").scene;
        let image = self
            .image
            .get_or_insert_with(|| Image::filled(1, 1, Rgb8::default()));
        let stats = self
            .renderer
            .render_into(scene, &options, image)
            .map_err(|e| EngineError(e.to_string()))?;
        rgba_of(image, &mut self.rgba);
        let info = frame_info(scene, &options, stats);
        self.drawn(toml, options, 1);
        Ok(info)
    }

    /// Renders the scene `toml` with each method, flat, Gouraud and Phong,
    /// in one pass over the geometry ([`Renderer::render_methods`]): what
    /// three engines' [`Engine::render`] of the three panels' texts (which
    /// differ only in `render.shading`) would draw, for about the cost of
    /// one frame's geometry and three fills. [`Engine::images`] then holds
    /// the three frames' RGBA pixels, in that order; the frame of the
    /// text's own method becomes the engine's last frame, for the
    /// instruments, as if [`Engine::render`] had drawn it.
    ///
    /// # Errors
    /// As [`Engine::render`].
    pub fn render_methods(&mut self, toml: &str) -> Result<[FrameInfo; 3], EngineError> {
        let Loaded { options, .. } = self.load_scene(toml)?;
        let scene = &self.prepared.as_ref().expect("load_scene keeps it").scene;
        self.methods
            .resize_with(3, || Image::filled(1, 1, Rgb8::default()));
        let [a, b, c] = &mut self.methods[..] else {
            unreachable!("three images")
        };
        let stats = self
            .renderer
            .render_methods(scene, &options, [a, b, c])
            .map_err(|e| EngineError(e.to_string()))?;
        self.images.resize_with(3, Vec::new);
        self.images.truncate(3);
        for (image, out) in self.methods.iter().zip(&mut self.images) {
            rgba_of(image, out);
        }
        let own = Shading::ALL
            .iter()
            .position(|&s| s == options.shading)
            .expect("every method is in ALL");
        let last = self
            .image
            .get_or_insert_with(|| Image::filled(1, 1, Rgb8::default()));
        // Swapped, not copied: the next frame of this size reuses the buffer.
        std::mem::swap(last, &mut self.methods[own]);
        self.rgba.clear();
        self.rgba.extend_from_slice(&self.images[own]);
        let infos = std::array::from_fn(|k| {
            let options = RenderOptions {
                shading: Shading::ALL[k],
                ..options
            };
            frame_info(scene, &options, stats[k])
        });
        self.drawn(toml, options, 3);
        Ok(infos)
    }

    /// Part `part` of `parts` of [`Engine::render_methods`]: the three
    /// methods' frames of the scene `toml`, but only their rows `rows`
    /// ([`shadelab_core::part_rows`], returned), so that two engines (the
    /// page's two workers) draw one frame's three images together; the
    /// page puts the parts' rows one under the other. [`Engine::images`]
    /// then holds the three parts' RGBA pixels (`width × rows` each). A
    /// mode only the scanline rasterizer draws is drawn whole by part 0
    /// (rows `0..height`); the other parts then draw nothing (empty rows).
    ///
    /// Each frame's counts are the whole frame's, but for those of its rows'
    /// pixels (`stats.fragments_shaded`, `stats.covered_pixels` and
    /// `cost.per_pixel`) and flat's evaluations (`cost.per_polygon`: of the
    /// polygons whose top pixel row the part holds), both included in
    /// `stats.lighting_evaluations`, which the parts add up to. A part is
    /// not a frame the instruments can read: the engine keeps no last frame
    /// after it.
    ///
    /// # Errors
    /// As [`Engine::render`], and when `part` is not below `parts`.
    pub fn render_methods_part(
        &mut self,
        toml: &str,
        part: u32,
        parts: u32,
    ) -> Result<([FrameInfo; 3], [u32; 2]), EngineError> {
        if part >= parts {
            return Err(EngineError(format!(
                "part {part} of {parts}: parts are numbered from 0"
            )));
        }
        let Loaded { options, .. } = self.load_scene(toml)?;
        let scene = &self.prepared.as_ref().expect("load_scene keeps it").scene;
        let rows = match (shadelab_core::draws_in_parts(&options), part) {
            (true, _) => shadelab_core::part_rows(options.height, part, parts),
            // Drawn whole whatever the rows: by the first part alone.
            (false, 0) => 0..options.height,
            (false, _) => options.height..options.height,
        };
        self.images.resize_with(3, Vec::new);
        self.images.truncate(3);
        let each = |k: usize| RenderOptions {
            shading: Shading::ALL[k],
            ..options
        };
        if rows.is_empty() {
            // More parts than runs of rows, or a frame the first part draws
            // whole: nothing to draw, nothing to add.
            for image in &mut self.images {
                image.clear();
            }
            let infos =
                std::array::from_fn(|k| frame_info(scene, &each(k), RenderStats::default()));
            return Ok((infos, [rows.start, rows.end]));
        }
        self.methods
            .resize_with(3, || Image::filled(1, 1, Rgb8::default()));
        let [a, b, c] = &mut self.methods[..] else {
            unreachable!("three images")
        };
        let (stats, drawn) = self
            .renderer
            .render_methods_rows(scene, &options, rows, [a, b, c])
            .map_err(|e| EngineError(e.to_string()))?;
        for (image, out) in self.methods.iter().zip(&mut self.images) {
            rgba_of(image, out);
        }
        let infos = std::array::from_fn(|k| frame_info(scene, &each(k), stats[k]));
        self.counts.frames += 3;
        self.image = None;
        self.options = None;
        self.errors = None;
        Ok((infos, [drawn.start, drawn.end]))
    }

    /// Records `frames` frames of the scene `toml` drawn (the last with
    /// `options`): the instruments that follow read this frame.
    fn drawn(&mut self, toml: &str, options: RenderOptions, frames: u64) {
        self.counts.frames += frames;
        self.options = Some(options);
        self.frame_toml.clear();
        self.frame_toml.push_str(toml);
        self.errors = None;
    }

    /// Reads the scene `toml`, preparing its model again only when its
    /// `[model]` section (or the file it names) changed since the last
    /// request, and keeps it for the requests that follow.
    ///
    /// # Errors
    /// As [`Engine::render`].
    pub(crate) fn load_scene(&mut self, toml: &str) -> Result<Loaded<'_>, EngineError> {
        if self
            .prepared
            .as_ref()
            .is_some_and(|p| p.toml == toml && p.key.file_generation == self.file_generation)
        {
            let p = self.prepared.as_ref().expect("just checked");
            return Ok(Loaded {
                file: &p.file,
                options: p.options,
            });
        }
        if self.turn_camera(toml) {
            let p = self.prepared.as_ref().expect("turn_camera keeps it");
            return Ok(Loaded {
                file: &p.file,
                options: p.options,
            });
        }
        self.counts.scenes_read += 1;
        let file = SceneFile::parse(toml, "scene")?;
        let options = file.render_options()?;
        let key = ModelKey {
            model: file.model.clone(),
            has_camera: file.camera.is_some(),
            file_generation: self.file_generation,
        };
        let mut scene = match self.prepared.take() {
            Some(p) if p.key == key => p.scene,
            _ => {
                self.counts.models_prepared += 1;
                self.prepare(&file, &options)?
            }
        };
        let result = file.update_scene(&mut scene, &options);
        // Keep the model even when the rest of the scene is invalid; such a
        // scene is never taken for a valid one (its text is not kept).
        let valid = result.is_ok();
        let p = self.prepared.insert(Prepared {
            key,
            toml: if valid {
                toml.to_owned()
            } else {
                String::new()
            },
            file,
            options,
            scene,
        });
        result?;
        Ok(Loaded {
            file: &p.file,
            options: p.options,
        })
    }

    /// Takes `toml` without reading it as a whole when it differs from the
    /// last scene only in the camera's `yaw`, `pitch` and `zoom`
    /// (`camera_patch`): sets those on the kept scene file and resolves the
    /// camera again. False, changing nothing, when the text is more than
    /// that or the values are refused (the whole reading then says why).
    fn turn_camera(&mut self, toml: &str) -> bool {
        let Some(p) = self.prepared.as_mut() else {
            return false;
        };
        if p.toml.is_empty() || p.key.file_generation != self.file_generation {
            return false;
        }
        let Some([yaw, pitch, zoom]) = crate::camera_patch::camera_change(&p.toml, toml) else {
            return false;
        };
        let mut file = p.file.clone();
        let render = &mut file.render;
        for (key, value) in [
            (&mut render.yaw, yaw),
            (&mut render.pitch, pitch),
            (&mut render.zoom, zoom),
        ] {
            if value.is_some() {
                *key = value;
            }
        }
        // On error the scene is left as it was.
        if file.update_scene(&mut p.scene, &p.options).is_err() {
            return false;
        }
        p.file = file;
        p.toml.clear();
        p.toml.push_str(toml);
        self.counts.camera_turns += 1;
        true
    }

    /// The scene [`Engine::load_scene`] last read.
    ///
    /// # Panics
    /// If none was read.
    pub(crate) fn prepared_scene(&self) -> &Scene {
        &self.prepared.as_ref().expect("a scene was loaded").scene
    }

    /// The scene [`Engine::load_scene`] last read, as it returned it.
    ///
    /// # Panics
    /// If none was read.
    pub(crate) fn load_scene_kept(&self) -> Result<Loaded<'_>, EngineError> {
        let p = self.prepared.as_ref().expect("a scene was loaded");
        Ok(Loaded {
            file: &p.file,
            options: p.options,
        })
    }

    /// The mesh and normals for `file`'s `[model]` section, in a scene whose
    /// camera, lights and material are still to be set.
    fn prepare(&self, file: &SceneFile, options: &RenderOptions) -> Result<Scene, EngineError> {
        let user_file = &self.file;
        let (mesh, default_crease) = file.model_mesh(|source| match user_file {
            Some(f) if f.name == source => Ok(f.mesh.clone()),
            _ => Err(SceneError::Value {
                key: "model.source".into(),
                message: format!(
                    "{source:?} is neither a built-in model nor the file loaded into the viewer"
                ),
            }),
        })?;
        let (mesh, mut normals) = file.prepare_model(mesh, default_crease)?;
        // The scene took the file's normals (they are its normals, index for
        // index): draw with them as the parsing engine had them.
        if let Some(exact) = user_file.as_ref().and_then(|f| f.exact_normals.as_ref()) {
            if mesh.file_normals() == Some(&normals) {
                normals = exact.clone();
            }
        }
        Ok(file.build_scene(mesh, normals, options)?)
    }

    /// The last frame's pixels, RGBA with alpha 255, row 0 at the top
    /// (empty before the first frame).
    pub fn rgba(&self) -> &[u8] {
        &self.rgba
    }

    /// The images the last instrument request made, each RGBA (its JSON
    /// answer says what each is and its size).
    pub fn images(&self) -> &[Vec<u8>] {
        &self.images
    }

    /// The last frame as an image, for tests.
    pub fn image(&self) -> Option<&Image> {
        self.image.as_ref()
    }
}

/// A user's file may not take a built-in model's name (a scene names either).
fn check_file_name(name: &str) -> Result<(), EngineError> {
    if shadelab_core::builtin_model_info(name).is_some() {
        return Err(EngineError(format!(
            "{name}: a file may not have the name of a built-in model"
        )));
    }
    Ok(())
}

/// Writes `image` as RGBA with alpha 255 into `out`, reusing its memory.
pub(crate) fn rgba_of(image: &Image, out: &mut Vec<u8>) {
    // Sized once, then written in place: a loop of fixed-size copies that the
    // compiler turns into shuffles (no length check per pixel).
    out.resize(image.pixels().len() * 4, 0);
    for (o, p) in out.chunks_exact_mut(4).zip(image.pixels()) {
        let [r, g, b] = p.0;
        o.copy_from_slice(&[r, g, b, 255]);
    }
}
