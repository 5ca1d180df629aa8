//! From a [`SceneFile`] to the core's [`Scene`] and [`RenderOptions`]:
//! every value checked (errors name the key), the model loaded, the lights
//! and the material resolved.
//!
//! Defaults, ranges and the wording of range errors come from the core's
//! table of parameters ([`shadelab_core::params`]); the render options'
//! own check ([`RenderOptions::check`]) covers the image size, the
//! fixed-point bits and the palette.

use std::path::{Path, PathBuf};

use glam::Vec3;
use shadelab_core::limits::MAX_MODEL_COORDINATE_WITH_CAMERA;
use shadelab_core::params;
use shadelab_core::{
    builtin_model, builtin_model_info, vertex_normals, Camera, CornerNormals, Light, LightKind,
    Material, Mesh, NormalWeighting, Palette, Rasterizer, RenderOptions, Rgb, Rgb8, Scene,
};
use shadelab_core::{escape_token, format_number};

use super::{
    default_light, value_error, LightKindName, LightSection, NormalsChoice, SceneError, SceneFile,
};
use crate::{load_mesh_file, FileMaterial};

impl SceneFile {
    /// Checks every value, loads the model (a relative path is taken from
    /// `base_dir`) and builds what the renderer needs.
    ///
    /// The same as [`SceneFile::render_options`], [`SceneFile::model_mesh`]
    /// reading mesh files from disk, [`SceneFile::prepare_model`] and
    /// [`SceneFile::build_scene`] in turn; a caller that keeps the model
    /// between frames (the viewer) calls those itself.
    ///
    /// # Errors
    /// [`SceneError::Value`] naming the key, or [`SceneError::Model`].
    pub fn resolve(&self, base_dir: &Path) -> Result<(Scene, RenderOptions), SceneError> {
        self.resolve_reporting(base_dir, &mut Vec::new())
    }

    /// [`SceneFile::resolve`], adding to `warnings` what was passed over
    /// while loading the model ([`crate::MeshFile::warnings`]: a material
    /// library that is missing, outside the model's folder or not a regular
    /// file), for the caller to show.
    ///
    /// # Errors
    /// As [`SceneFile::resolve`].
    pub fn resolve_reporting(
        &self,
        base_dir: &Path,
        warnings: &mut Vec<String>,
    ) -> Result<(Scene, RenderOptions), SceneError> {
        let options = self.render_options()?;
        let mut file_material = None;
        let (mesh, default_crease) = self.model_mesh(|source| {
            let path = model_path(source, base_dir);
            if !path.exists() && !source.contains('.') && !source.contains('/') {
                return Err(value_error(
                    "model.source",
                    format!(
                        "`{}` is neither a built-in model ({}) nor an existing file",
                        escape_token(source),
                        builtin_names()
                    ),
                ));
            }
            let file = load_mesh_file(&path)?;
            warnings.extend(file.warnings);
            file_material = file.material;
            Ok(file.mesh)
        })?;
        let (mesh, normals) = self.prepare_model(mesh, default_crease)?;
        let mut scene = self.build_scene(mesh, normals, &options)?;
        if file_material.is_some() {
            self.update_scene_with_file_material(&mut scene, &options, file_material.as_ref())?;
        }
        Ok((scene, options))
    }

    /// The scene: `mesh` and `normals` as [`SceneFile::prepare_model`] made
    /// them, with the camera, lights and material of this file
    /// ([`SceneFile::update_scene`]).
    ///
    /// # Errors
    /// As [`SceneFile::update_scene`].
    pub fn build_scene(
        &self,
        mesh: Mesh,
        normals: CornerNormals,
        options: &RenderOptions,
    ) -> Result<Scene, SceneError> {
        let mut scene = Scene {
            mesh,
            normals,
            camera: Camera::framing_sphere(Vec3::ZERO, 1.0, 45.0, 1.0),
            ambient: Rgb::default(),
            lights: Vec::new(),
            material: Material::default(),
        };
        self.update_scene(&mut scene, options)?;
        Ok(scene)
    }

    /// The `[render]` section, checked: size, method and options.
    ///
    /// # Errors
    /// [`SceneError::Value`] naming the key.
    pub fn render_options(&self) -> Result<RenderOptions, SceneError> {
        let r = &self.render;
        let defaults = RenderOptions::default();
        if let Some(offset) = r.palette_offset {
            whole("render.palette_offset", offset)?;
        }
        let mut options = RenderOptions {
            width: r.width.unwrap_or(defaults.width),
            height: r.height.unwrap_or(defaults.height),
            shading: r.shading.unwrap_or_default(),
            background: rgb8("render.background", r.background)?,
            cull_backfaces: r.cull_backfaces.unwrap_or(defaults.cull_backfaces),
            gouraud_specular: r.gouraud_specular.unwrap_or(defaults.gouraud_specular),
            interpolation: r.interpolation.unwrap_or_default(),
            polygons: r.polygons.unwrap_or_default(),
            rasterizer: r.rasterizer.unwrap_or_default(),
            specular: r.specular.unwrap_or_default(),
            fixed_point_bits: r.fixed_point_bits,
            palette: match (r.palette_shades, r.palette_offset) {
                (None, Some(_)) => {
                    return Err(value_error(
                        "render.palette_offset",
                        "needs render.palette_shades",
                    ));
                }
                (None, None) => None,
                (Some(shades), offset) => Some(Palette {
                    shades,
                    offset: offset.unwrap_or(0),
                }),
            },
        };
        // Modes only the scanline rasterizer draws choose it unless the file
        // insists on the tiled one (which the check then refuses).
        if options.needs_scanline() && r.rasterizer.is_none() {
            options.rasterizer = Rasterizer::Scanline;
        }
        // The one check of the options, shared with every other caller.
        options
            .check()
            .map_err(|e| value_error(e.key().unwrap_or("render"), e.problem()))?;
        Ok(options)
    }

    /// The model's mesh as given (not yet normalised) and its default crease
    /// angle: a built-in model with its detail, or `file(source)` for any
    /// other source (the command line reads the file from disk; the viewer
    /// looks up a file the user gave it).
    ///
    /// # Errors
    /// [`SceneError::Value`] for a bad detail, or what `file` returns.
    pub fn model_mesh(
        &self,
        file: impl FnOnce(&str) -> Result<Mesh, SceneError>,
    ) -> Result<(Mesh, Option<f32>), SceneError> {
        let default_source = match params::get("model.source").default {
            Some(params::Value::Text(name)) => name,
            _ => unreachable!("model.source has a default name"),
        };
        let source = self.model.source.as_deref().unwrap_or(default_source);
        if source.trim().is_empty() {
            return Err(value_error(
                "model.source",
                format!(
                    "is empty: name a built-in model ({}) or a mesh file",
                    builtin_names()
                ),
            ));
        }
        if let Some(info) = builtin_model_info(source) {
            let mesh = builtin_model(source, self.model.detail)
                .map_err(|e| value_error("model.detail", e.to_string()))?;
            return Ok((mesh, info.default_crease_degrees));
        }
        if self.model.detail.is_some() {
            return Err(value_error(
                "model.detail",
                format!(
                    "only built-in models have a detail; `{}` is a file",
                    escape_token(source)
                ),
            ));
        }
        Ok((file(source)?, None))
    }

    /// The mesh ready to draw and its corner normals, from the `[model]`
    /// section (normals, crease angle): the mesh is normalised (centred, unit
    /// bounding sphere) when the scene gives no camera.
    ///
    /// # Errors
    /// [`SceneError::Value`] naming `model.crease_angle` or `model.normals`.
    pub fn prepare_model(
        &self,
        mesh: Mesh,
        default_crease: Option<f32>,
    ) -> Result<(Mesh, CornerNormals), SceneError> {
        let crease = match self.model.crease_angle {
            Some(a) => Some(number("model.crease_angle", Some(a))?),
            None => default_crease,
        };
        // A model drawn in its own coordinates must keep its products
        // (face normals) within f32; one framed by the default camera is
        // first scaled by an exact power of two, which changes no normal and
        // no normalized position, so that any finite coordinates are framed.
        let (lo, hi) = mesh.bounds();
        let extent = lo.abs().max(hi.abs()).max_element();
        let mesh = if self.camera.is_some() {
            if extent > MAX_MODEL_COORDINATE_WITH_CAMERA {
                return Err(value_error(
                    "model.source",
                    format!(
                        "the model's coordinates reach {}; drawn with a [camera] in its own \
                         coordinates a model may reach ±{} (its face normals would overflow); \
                         without [camera] it is framed whatever its size",
                        format_number(extent),
                        format_number(MAX_MODEL_COORDINATE_WITH_CAMERA)
                    ),
                ));
            }
            mesh
        } else {
            match mesh.extreme_scale_exponent() {
                Some(exponent) => mesh.scaled_by_power_of_two(exponent),
                None => mesh,
            }
        };
        let choice = self.model.normals.unwrap_or_default();
        let normals = match (choice, mesh.file_normals()) {
            (NormalsChoice::File, None) => {
                return Err(value_error(
                    "model.normals",
                    "\"file\" was asked for, but the model has no normals on every face",
                ));
            }
            (NormalsChoice::File | NormalsChoice::Auto, Some(n)) => n.clone(),
            (NormalsChoice::Auto | NormalsChoice::Uniform, _) => {
                vertex_normals(&mesh, NormalWeighting::Uniform, crease)
            }
            (NormalsChoice::Area, _) => vertex_normals(&mesh, NormalWeighting::Area, crease),
            (NormalsChoice::Angle, _) => vertex_normals(&mesh, NormalWeighting::Angle, crease),
        };
        let mesh = if self.camera.is_some() {
            mesh
        } else {
            mesh.normalized()
        };
        Ok((mesh, normals))
    }

    /// Sets `scene`'s camera, ambient light, lights and material from this
    /// file, for an image of `options`' size; the mesh and normals are left
    /// alone. On error `scene` is unchanged.
    ///
    /// # Errors
    /// [`SceneError::Value`] naming the key.
    pub fn update_scene(
        &self,
        scene: &mut Scene,
        options: &RenderOptions,
    ) -> Result<(), SceneError> {
        self.update_scene_with_file_material(scene, options, None)
    }

    /// [`SceneFile::update_scene`], with the colours of the model file's
    /// material filling in the material keys this file leaves unset.
    ///
    /// # Errors
    /// As [`SceneFile::update_scene`].
    pub fn update_scene_with_file_material(
        &self,
        scene: &mut Scene,
        options: &RenderOptions,
        file_material: Option<&FileMaterial>,
    ) -> Result<(), SceneError> {
        let r = &self.render;
        let aspect = options.width as f32 / options.height as f32;
        let camera = match &self.camera {
            Some(c) => {
                let camera = Camera {
                    eye: vec3("camera.eye", Some(c.eye))?,
                    target: vec3("camera.target", c.target)?,
                    up: vec3("camera.up", c.up)?,
                    fov_y_degrees: number("camera.fov_y", c.fov_y)?,
                    near: number("camera.near", c.near)?,
                    far: number("camera.far", c.far)?,
                };
                camera
                    .validate()
                    .map_err(|e| value_error("camera", e.to_string()))?;
                camera
            }
            None => Camera::framing_sphere(Vec3::ZERO, 1.0, 45.0, aspect),
        };
        let yaw = number("render.yaw", r.yaw)?;
        let pitch = number("render.pitch", r.pitch)?;
        let mut camera = camera.orbit(yaw, pitch);
        if let Some(zoom) = r.zoom {
            let zoom = number("render.zoom", Some(zoom))?;
            let given = camera.fov_y_degrees;
            let half = (given.to_radians() * 0.5).tan() / zoom;
            camera.fov_y_degrees = (2.0 * half.atan()).to_degrees();
            if !(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0) {
                // Report what was given, not the field of view it became.
                let key = if self.camera.is_some() {
                    "camera.fov_y"
                } else {
                    "the default field of view"
                };
                return Err(value_error(
                    "render.zoom",
                    format!(
                        "a zoom of {} widens {key} = {} degrees to 180 degrees or more in \
                         single precision; use a larger zoom or a narrower field of view",
                        format_number(zoom),
                        format_number(given)
                    ),
                ));
            }
        }
        // Orbiting moves the eye: say what was given when the result fails.
        if let Err(e) = camera.validate() {
            return Err(value_error(
                "render.yaw",
                format!(
                    "yaw {} and pitch {} give a camera that cannot be used: {e}",
                    format_number(yaw),
                    format_number(pitch)
                ),
            ));
        }

        let a = &self.ambient;
        let ambient_intensity = number("ambient.intensity", a.intensity)?;
        let ambient = rgb("ambient.color", a.color)? * ambient_intensity;

        let default_lights = [default_light()];
        let light_sections = self.lights.as_deref().unwrap_or(&default_lights);
        let lights = light_sections
            .iter()
            .enumerate()
            .map(|(k, l)| resolve_light(k, l))
            .collect::<Result<Vec<_>, _>>()?;

        let m = &self.material;
        // The core's default material (one declaration: `Material::default`).
        let defaults = Material::default();
        let file_kd = file_material.and_then(|f| f.kd);
        let file_ka = file_material.and_then(|f| f.ka.or(f.kd));
        let material = Material {
            ka: match m.ka {
                Some(_) => rgb("material.ka", m.ka)?,
                None => file_ka.unwrap_or(defaults.ka),
            },
            kd: match m.kd {
                Some(_) => rgb("material.kd", m.kd)?,
                None => file_kd.unwrap_or(defaults.kd),
            },
            ks: rgb("material.ks", m.ks)?,
            shininess: number("material.shininess", m.shininess)?,
        };
        scene.camera = camera;
        scene.ambient = ambient;
        scene.lights = lights;
        scene.material = material;
        Ok(())
    }
}

/// The built-in models' names, comma-separated.
fn builtin_names() -> String {
    shadelab_core::BUILTIN_MODELS
        .iter()
        .map(|m| m.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Where a model source that is not built in lives.
pub fn model_path(source: &str, base_dir: &Path) -> PathBuf {
    let p = Path::new(source);
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        base_dir.join(p)
    }
}

fn resolve_light(k: usize, l: &LightSection) -> Result<Light, SceneError> {
    let key = |field: &str| format!("lights[{k}].{field}");
    // The light's keys are checked against the table's `lights.*` entries.
    let checked = |field: &str, e: String| value_error(key(field), e);
    let vector = |field: &str, v: [f32; 3]| {
        params::get(&format!("lights.{field}"))
            .check_vec3(v)
            .map(Vec3::from_array)
            .map_err(|e| checked(field, e))
    };
    let kind = match (l.kind, l.position, l.direction) {
        (LightKindName::Point, Some(p), None) => LightKind::Point {
            position: vector("position", p)?,
        },
        (LightKindName::Directional, None, Some(d)) => {
            let direction = vector("direction", d)?;
            if direction == Vec3::ZERO {
                return Err(value_error(key("direction"), "must not be zero"));
            }
            LightKind::Directional { direction }
        }
        (LightKindName::Point, _, _) => {
            return Err(value_error(
                key("position"),
                "a point light needs `position` and no `direction`",
            ));
        }
        (LightKindName::Directional, _, _) => {
            return Err(value_error(
                key("direction"),
                "a directional light needs `direction` and no `position`",
            ));
        }
    };
    let color = params::get("lights.color");
    let color = color
        .check_rgb(l.color.unwrap_or_else(|| color.default_rgb()))
        .map_err(|e| checked("color", e))?;
    let intensity = params::get("lights.intensity");
    let intensity = intensity
        .check(l.intensity.unwrap_or_else(|| intensity.default_number()))
        .map_err(|e| checked("intensity", e))?;
    let attenuation = params::get("lights.attenuation");
    let attenuation = match (l.attenuation, kind) {
        (None, _) => attenuation.default_three().map(|k| k as f32),
        (Some(k), LightKind::Point { .. }) => vector("attenuation", k)?.to_array(),
        (Some(_), LightKind::Directional { .. }) => {
            return Err(value_error(
                key("attenuation"),
                "only a point light has attenuation (a directional light has no distance)",
            ));
        }
    };
    Ok(Light {
        kind,
        color: color.to_rgb(),
        intensity,
        attenuation,
    })
}

/// The colour at `key`, or its default, checked against the table's range.
fn rgb8(key: &str, c: Option<[i64; 3]>) -> Result<Rgb8, SceneError> {
    let p = params::get(key);
    p.check_rgb(c.unwrap_or_else(|| p.default_rgb()))
        .map_err(|e| value_error(key, e))
}

fn rgb(key: &str, c: Option<[i64; 3]>) -> Result<Rgb, SceneError> {
    Ok(rgb8(key, c)?.to_rgb())
}

/// The number at `key`, or its default, checked against the table's range.
fn number(key: &str, v: Option<f32>) -> Result<f32, SceneError> {
    let p = params::get(key);
    p.check(v.unwrap_or_else(|| p.default_number()))
        .map_err(|e| value_error(key, e))
}

/// A whole number at `key`, checked against the table's range.
fn whole(key: &str, v: u32) -> Result<u32, SceneError> {
    params::get(key)
        .check_whole(i64::from(v))
        .map_err(|e| value_error(key, e))?;
    Ok(v)
}

/// A camera vector, or its default, checked against the table's range.
fn vec3(key: &str, v: Option<[f32; 3]>) -> Result<Vec3, SceneError> {
    let p = params::get(key);
    p.check_vec3(v.unwrap_or_else(|| p.default_three().map(|c| c as f32)))
        .map(Vec3::from_array)
        .map_err(|e| value_error(key, e))
}
