//! `shadelab._shadelab`: the Python package's native half.
//!
//! The Python half (`python/shadelab/__init__.py`) turns keyword arguments
//! into scene-file keys and NumPy-like meshes into contiguous arrays; this
//! half builds the scene exactly as the `shadelab` command does (a
//! [`SceneFile`], the flags' keys merged over it), renders with the GIL
//! released, and hands the pixels to NumPy in one copy. Errors carry the
//! command's messages: `OSError` for files that cannot be read, `ValueError`
//! for everything the user can fix in the input.

use std::path::{Path, PathBuf};

use numpy::{PyArray1, PyArray3, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use shadelab_batch::{BatchConfig, PreparedMesh, Progress, View};
use shadelab_core::{coverage, render, Image, Mesh, RenderOptions, Renderer, Rgb8, Scene};
use shadelab_io::{LoadError, PngCompression, SceneError, SceneFile};

/// The exception for a scene or model error, as the command reports it.
fn scene_error(e: SceneError) -> PyErr {
    match &e {
        SceneError::Io { .. } | SceneError::Model(LoadError::Io { .. }) => {
            PyOSError::new_err(e.to_string())
        }
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// The shared settings: the scene file (if any) with `overrides` (a JSON
/// object of scene-file sections) merged over it key by key; `camera` and
/// `lights` are replaced whole. Also the folder relative paths start from.
fn settings(scene: Option<&Path>, overrides: &str) -> PyResult<(SceneFile, PathBuf)> {
    let base_dir = scene
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let file = match scene {
        Some(path) => SceneFile::load(path).map_err(scene_error)?,
        None => SceneFile::default(),
    };
    let overrides: serde_json::Map<String, serde_json::Value> = serde_json::from_str(overrides)
        .map_err(|e| PyValueError::new_err(format!("settings: {e}")))?;
    if overrides.is_empty() {
        return Ok((file, base_dir));
    }
    let mut table = match scene {
        Some(path) => SceneFile::read_text(path)
            .map_err(scene_error)?
            .parse::<toml::Table>()
            .map_err(|e| PyValueError::new_err(format!("{}: {e}", path.display())))?,
        None => toml::Table::new(),
    };
    for (section, value) in overrides {
        let value = toml::Value::try_from(value)
            .map_err(|e| PyValueError::new_err(format!("{section}: {e}")))?;
        match (table.get_mut(&section), value) {
            (Some(toml::Value::Table(old)), toml::Value::Table(new))
                if section != "camera" && section != "lights" =>
            {
                old.extend(new);
            }
            (_, value) => {
                table.insert(section, value);
            }
        }
    }
    let text = toml::to_string(&table).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let file = SceneFile::parse(&text, "settings").map_err(scene_error)?;
    Ok((file, base_dir))
}

/// Pixels for NumPy: RGB, or RGBA with alpha 255 where the model covers
/// the pixel. The one copy of the image.
fn pixels(image: &Image, cover: Option<&[u32]>) -> Vec<u8> {
    match cover {
        None => image.to_rgb_bytes(),
        Some(cover) => {
            let mut out = Vec::with_capacity(image.pixels().len() * 4);
            for (p, &c) in image.pixels().iter().zip(cover) {
                out.extend_from_slice(&p.0);
                out.push(if c > 0 { 255 } else { 0 });
            }
            out
        }
    }
}

/// An image as a NumPy array of shape (height, width, channels), taking
/// ownership of `bytes` (no copy).
fn to_numpy(
    py: Python<'_>,
    bytes: Vec<u8>,
    height: u32,
    width: u32,
    channels: usize,
) -> PyResult<Bound<'_, PyArray3<u8>>> {
    PyArray1::from_vec(py, bytes).reshape([height as usize, width as usize, channels])
}

type Frame = (Vec<u8>, u32, u32, usize);

/// A rendered image ready for [`to_numpy`]: RGB, or RGBA with the scene's
/// coverage as alpha.
fn frame(image: Image, scene: &Scene, options: &RenderOptions, alpha: bool) -> PyResult<Frame> {
    let cover = if alpha {
        Some(coverage(scene, options).map_err(|e| PyValueError::new_err(e.to_string()))?)
    } else {
        None
    };
    let channels = if alpha { 4 } else { 3 };
    Ok((
        pixels(&image, cover.as_deref()),
        image.height(),
        image.width(),
        channels,
    ))
}

/// Renders a model named as `shadelab render --model` names it (a built-in
/// model or a mesh file), or the scene file's own model when `source` is None.
#[pyfunction]
#[pyo3(signature = (scene=None, settings_json="{}", source=None, alpha=false))]
fn render_source<'py>(
    py: Python<'py>,
    scene: Option<PathBuf>,
    settings_json: &str,
    source: Option<String>,
    alpha: bool,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let (mut file, base_dir) = settings(scene.as_deref(), settings_json)?;
    if let Some(m) = source {
        // As the command line: a file named beside a scene file is relative
        // to the working directory, not to the scene file.
        let is_builtin = shadelab_core::builtin_model_info(&m).is_some();
        file.model.source = Some(match std::path::absolute(&m) {
            Ok(path) if !is_builtin && Path::new(&m).is_relative() && scene.is_some() => {
                path.to_string_lossy().into_owned()
            }
            _ => m,
        });
        file.model.detail = file.model.detail.filter(|_| is_builtin);
    }
    let result: PyResult<Frame> = py.detach(|| {
        let (scene, options) = file.resolve(&base_dir).map_err(scene_error)?;
        let (image, _) =
            render(&scene, &options).map_err(|e| PyValueError::new_err(e.to_string()))?;
        frame(image, &scene, &options, alpha)
    });
    let (bytes, h, w, c) = result?;
    to_numpy(py, bytes, h, w, c)
}

/// Renders a mesh given as arrays: `vertices` (N, 3) and `faces` (M, K)
/// of vertex indices, K ≥ 3 (polygons with K corners).
#[pyfunction]
#[pyo3(signature = (vertices, faces, scene=None, settings_json="{}", alpha=false))]
fn render_arrays<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f32>,
    faces: PyReadonlyArray2<'py, i64>,
    scene: Option<PathBuf>,
    settings_json: &str,
    alpha: bool,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let (file, _) = settings(scene.as_deref(), settings_json)?;
    let mesh = mesh_from_arrays(&vertices, &faces)?;
    let result: PyResult<Frame> = py.detach(|| {
        let mut prepared = PreparedMesh::from_mesh(&file, mesh).map_err(scene_error)?;
        let options = *prepared.options();
        let mut image = Image::filled(1, 1, Rgb8::default());
        let view = View {
            name: String::new(),
            yaw: 0.0,
            pitch: 0.0,
        };
        prepared
            .render(&mut Renderer::new(), &view, options.shading, &mut image)
            .map_err(PyValueError::new_err)?;
        frame(image, prepared.scene(), &options, alpha)
    });
    let (bytes, h, w, c) = result?;
    to_numpy(py, bytes, h, w, c)
}

/// A [`Mesh`] from NumPy arrays, its size checked against the mesh limits
/// before anything is allocated.
fn mesh_from_arrays(
    vertices: &PyReadonlyArray2<'_, f32>,
    faces: &PyReadonlyArray2<'_, i64>,
) -> PyResult<Mesh> {
    let vshape = vertices.shape();
    if vshape[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "vertices must have shape (N, 3), got ({}, {})",
            vshape[0], vshape[1]
        )));
    }
    let fshape = faces.shape();
    if fshape[1] < 3 {
        return Err(PyValueError::new_err(format!(
            "faces must have shape (M, K) with K >= 3 corners, got ({}, {})",
            fshape[0], fshape[1]
        )));
    }
    if vshape[0] > Mesh::MAX_VERTICES {
        return Err(PyValueError::new_err(format!(
            "{} vertices; at most {} are supported",
            vshape[0],
            Mesh::MAX_VERTICES
        )));
    }
    if fshape[0].saturating_mul(fshape[1]) > Mesh::MAX_CORNERS {
        return Err(PyValueError::new_err(format!(
            "{} face corners; at most {} are supported",
            fshape[0].saturating_mul(fshape[1]),
            Mesh::MAX_CORNERS
        )));
    }
    let v = vertices.as_array();
    let positions: Vec<glam::Vec3> = v
        .rows()
        .into_iter()
        .map(|r| glam::Vec3::new(r[0], r[1], r[2]))
        .collect();
    let f = faces.as_array();
    let mut corners = Vec::with_capacity(fshape[0] * fshape[1]);
    for (i, row) in f.rows().into_iter().enumerate() {
        for (j, &k) in row.iter().enumerate() {
            let k = u32::try_from(k).map_err(|_| {
                PyValueError::new_err(format!(
                    "faces[{i}][{j}] = {k} is not a vertex index (0..{})",
                    positions.len()
                ))
            })?;
            corners.push(k);
        }
    }
    Mesh::from_polygons(positions, corners.chunks(fshape[1]))
        .map_err(|e| PyValueError::new_err(format!("mesh: {e}")))
}

/// Renders a manifest as `shadelab batch` does; returns the summary.
#[pyfunction]
#[pyo3(signature = (
    manifest, output, scene=None, settings_json="{}", views="1", shading=None, shard=None,
    force=false, root=None, jobs=0, frame_threads=1, max_mesh_bytes=None, png="fast",
    progress=false
))]
#[allow(clippy::too_many_arguments)]
fn batch<'py>(
    py: Python<'py>,
    manifest: PathBuf,
    output: PathBuf,
    scene: Option<PathBuf>,
    settings_json: &str,
    views: &str,
    shading: Option<&str>,
    shard: Option<&str>,
    force: bool,
    root: Option<PathBuf>,
    jobs: usize,
    frame_threads: usize,
    max_mesh_bytes: Option<u64>,
    png: &str,
    progress: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let value = |what: &str, m: String| PyValueError::new_err(format!("{what}: {m}"));
    let (file, _) = settings(scene.as_deref(), settings_json)?;
    let config = BatchConfig {
        settings: file,
        views: views.parse().map_err(|m| value("views", m))?,
        modes: shading
            .map(shadelab_batch::parse_modes)
            .transpose()
            .map_err(|m| value("shading", m))?,
        shard: shard
            .map(str::parse)
            .transpose()
            .map_err(|m| value("shard", m))?
            .unwrap_or_default(),
        force,
        root,
        jobs,
        frame_threads,
        max_mesh_bytes: max_mesh_bytes.unwrap_or(shadelab_io::MAX_MESH_BYTES),
        compression: match png {
            "fast" => PngCompression::Fast,
            "small" => PngCompression::Default,
            other => {
                return Err(value(
                    "png",
                    format!("{other:?} is not \"fast\" or \"small\""),
                ))
            }
        },
        progress: if progress {
            Progress::Auto
        } else {
            Progress::Quiet
        },
        ..BatchConfig::new(manifest, output)
    };
    let summary = py
        .detach(|| shadelab_batch::run(&config))
        .map_err(|e| match e {
            shadelab_batch::BatchError::Output { .. } => PyOSError::new_err(e.to_string()),
            _ => PyValueError::new_err(e.to_string()),
        })?;
    let dict = PyDict::new(py);
    dict.set_item("meshes", summary.meshes)?;
    dict.set_item("meshes_failed", summary.meshes_failed)?;
    dict.set_item("written", summary.written)?;
    dict.set_item("skipped", summary.skipped)?;
    dict.set_item("failed", summary.failed)?;
    dict.set_item("bad_lines", summary.bad_lines)?;
    dict.set_item("seconds", summary.seconds)?;
    dict.set_item("text", summary.to_string())?;
    dict.set_item("index", summary.index)?;
    Ok(dict)
}

/// Reads an 8-bit RGB or RGBA PNG into an (H, W, 3) array (alpha dropped).
#[pyfunction]
fn read_png<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let image = py
        .detach(|| shadelab_io::read_png(&path))
        .map_err(|e| PyOSError::new_err(format!("{}: {e}", path.display())))?;
    to_numpy(py, image.to_rgb_bytes(), image.height(), image.width(), 3)
}

/// The native module.
#[pymodule]
fn _shadelab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(render_source, m)?)?;
    m.add_function(wrap_pyfunction!(render_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(batch, m)?)?;
    m.add_function(wrap_pyfunction!(read_png, m)?)?;
    m.add(
        "BUILTIN_MODELS",
        shadelab_core::BUILTIN_MODELS
            .iter()
            .map(|m| m.name)
            .collect::<Vec<_>>(),
    )?;
    Ok(())
}
