//! The standard scenes: the models, framed by the standard camera and lit
//! by the standard light and material, the same for every renderer compared.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use glam::Vec3;
use shadelab_core::{
    builtin_model, vertex_normals, Camera, Light, LightKind, Material, Mesh, NormalWeighting, Rgb,
    Rgb8, Scene,
};

use super::{BenchArgs, BenchModel};

/// The standard material and lights, as 0–1 colours.
pub(super) const AMBIENT: [u8; 3] = [255, 255, 255];
pub(super) const AMBIENT_INTENSITY: f32 = 0.2;
pub(super) const KA: [u8; 3] = [77, 64, 51];
pub(super) const KD: [u8; 3] = [204, 153, 102];
pub(super) const KS: [u8; 3] = [128, 128, 128];
pub(super) const SHININESS: f32 = 32.0;
pub(super) const BACKGROUND: Rgb8 = Rgb8::new(26, 26, 31);
/// Half the vertical field of view, degrees.
pub(super) const HALF_FOV: f32 = 22.5;

pub(super) fn rgb(c: [u8; 3]) -> Rgb {
    Rgb8(c).to_rgb()
}

/// A loaded model of the standard set.
pub(super) struct Model {
    pub(super) kind: BenchModel,
    pub(super) mesh: Mesh,
    /// Where it came from, for the report.
    pub(super) source: String,
}

/// The standard scene of `mesh` for an image of `aspect` (width / height):
/// camera on +z of the bounding-box centre `c`, 45° vertical field of view,
/// distance `hz + 1.1·max(hy/tan 22.5°, hx/(tan 22.5°·aspect))` (`h` the half
/// extents), near `max(d − 2r, 0.01·d)`, far `d + 2r` (`r = |h|`); one white
/// point light at `c + d·(1, 1.5, 1.2)`; ambient white × 0.2; Ka (77, 64, 51),
/// Kd (204, 153, 102), Ks (128, 128, 128), shininess 32; uniform vertex
/// normals. The full-screen quad instead has its camera at distance 1.
pub fn standard_scene(mesh: Mesh, aspect: f32, full_screen: bool) -> Scene {
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    let half = (hi - lo) * 0.5;
    let radius = half.length();
    let t = HALF_FOV.to_radians().tan();
    let distance = if full_screen {
        1.0
    } else {
        half.z + 1.1 * (half.y / t).max(half.x / (t * aspect))
    };
    let camera = Camera {
        eye: centre + Vec3::Z * distance,
        target: centre,
        up: Vec3::Y,
        fov_y_degrees: 2.0 * HALF_FOV,
        near: (distance - 2.0 * radius).max(0.01 * distance),
        far: distance + 2.0 * radius,
    };
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    Scene {
        mesh,
        normals,
        camera,
        ambient: rgb(AMBIENT) * AMBIENT_INTENSITY,
        lights: vec![Light {
            kind: LightKind::Point {
                position: centre + distance * Vec3::new(1.0, 1.5, 1.2),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        }],
        material: Material {
            ka: rgb(KA),
            kd: rgb(KD),
            ks: rgb(KS),
            shininess: SHININESS,
        },
    }
}

/// Two triangles in the plane z = 0 reaching 2 % past every side of the
/// image seen from the full-screen quad's camera (distance 1, 45°).
pub(super) fn full_screen_quad(aspect: f32) -> Mesh {
    let hy = HALF_FOV.to_radians().tan() * 1.02;
    let hx = hy * aspect;
    let positions = vec![
        Vec3::new(-hx, -hy, 0.0),
        Vec3::new(hx, -hy, 0.0),
        Vec3::new(hx, hy, 0.0),
        Vec3::new(-hx, hy, 0.0),
    ];
    Mesh::from_polygons(positions, [[0u32, 1, 2], [0, 2, 3]]).expect("a valid quad")
}

/// The models folder: `--models-dir`, else `../shared/models` from the
/// working directory, else beside the source tree.
pub(super) fn models_dir(args: &BenchArgs) -> Option<PathBuf> {
    if let Some(dir) = &args.models_dir {
        return Some(dir.clone());
    }
    let candidates = [
        PathBuf::from("../shared/models"),
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models"),
    ];
    candidates.into_iter().find(|d| d.is_dir())
}

/// Loads the selected models, noting on stderr the ones that are missing
/// when none was asked for by name; a missing `--models-dir`, or a model
/// asked for by name whose file is missing, is an error.
pub(super) fn load_models(args: &BenchArgs, selected: &[BenchModel]) -> anyhow::Result<Vec<Model>> {
    if let Some(dir) = &args.models_dir {
        if !dir.is_dir() {
            bail!("--models-dir {}: no such directory", dir.display());
        }
    }
    let dir = models_dir(args);
    let mut models = Vec::new();
    for &kind in selected {
        let (mesh, source) = match (kind, kind.file()) {
            (BenchModel::Quad, _) => (full_screen_quad(1.0), "two triangles".to_string()),
            (_, None) => (
                builtin_model(kind.name(), None).context("built-in model")?,
                format!("built-in {}", kind.name()),
            ),
            (_, Some(file)) => {
                let Some(path) = dir.as_ref().map(|d| d.join(file)).filter(|p| p.is_file()) else {
                    let place = dir.as_ref().map_or_else(
                        || "../shared/models (not found)".to_string(),
                        |d| d.display().to_string(),
                    );
                    if !args.model.is_empty() {
                        bail!(
                            "{} was asked for, but there is no {file} in {place}",
                            kind.name()
                        );
                    }
                    crate::warn(&format!(
                        "note: {} skipped: no {file} in {place}\n",
                        kind.name()
                    ));
                    continue;
                };
                let mesh = shadelab_io::load_mesh(&path)
                    .with_context(|| format!("cannot load {}", path.display()))?;
                (mesh, path.display().to_string())
            }
        };
        models.push(Model { kind, mesh, source });
    }
    Ok(models)
}
