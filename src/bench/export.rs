//! `--export DIR`: the standard scenes written for another renderer.

use std::path::Path;

use anyhow::{bail, Context};
use glam::Vec3;
use shadelab_core::{face_normal, Image, LightKind, Rasterizer, Renderer, Scene, Shading};

use super::report::quote;
use super::scene::{
    full_screen_quad, standard_scene, Model, AMBIENT, AMBIENT_INTENSITY, BACKGROUND, KA, KD, KS,
    SHININESS,
};
use super::{options, BenchModel};

/// Writes each model's standard scene for another renderer, per size:
///
/// * `MODEL-WxH.json`: camera, light, material, background, counts;
/// * `MODEL-WxH.vertices.f32`: distinct (position, normal) vertices, 6 floats each;
/// * `MODEL-WxH.indices.u32`: their triangles (polygons as fans from their
///   first corner, as both rasterizers draw them), counter-clockwise;
/// * `MODEL-WxH.flat.f32`: per triangle, its polygon's unit face normal and
///   centroid (6 floats), what flat shading lights;
/// * `MODEL-WxH-SHADING.png`: the tiled rasterizer's image.
///
/// All little-endian.
pub(super) fn export(
    dir: &Path,
    models: &[Model],
    sizes: &[(u32, u32)],
    shadings: &[Shading],
) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut renderer = Renderer::new();
    for model in models {
        for &(width, height) in sizes {
            let aspect = width as f32 / height as f32;
            let mesh = match model.kind {
                BenchModel::Quad => full_screen_quad(aspect),
                _ => model.mesh.clone(),
            };
            let scene = standard_scene(mesh, aspect, model.kind == BenchModel::Quad);
            let stem = format!("{}-{width}x{height}", model.kind.name());
            let counts = write_geometry(dir, &stem, &scene)?;
            let c = &scene.camera;
            let LightKind::Point { position: light } = scene.lights[0].kind else {
                bail!("the standard light is a point light");
            };
            let v = |v: Vec3| format!("[{},{},{}]", v.x, v.y, v.z);
            let c3 = |c: [u8; 3]| format!("[{},{},{}]", c[0], c[1], c[2]);
            let description = format!(
                "{{\"model\":{},\"width\":{width},\"height\":{height},\"vertices\":{},\"triangles\":{},\
                 \"eye\":{},\"target\":{},\"up\":{},\"fov_y\":{},\"near\":{},\"far\":{},\
                 \"light\":{},\"light_color\":[255,255,255],\"ambient\":{},\"ambient_intensity\":{},\
                 \"ka\":{},\"kd\":{},\"ks\":{},\"shininess\":{},\"background\":{}}}",
                quote(model.kind.name()),
                counts.0,
                counts.1,
                v(c.eye),
                v(c.target),
                v(c.up),
                c.fov_y_degrees,
                c.near,
                c.far,
                v(light),
                c3(AMBIENT),
                AMBIENT_INTENSITY,
                c3(KA),
                c3(KD),
                c3(KS),
                SHININESS,
                c3(BACKGROUND.0),
            );
            write_file(&dir.join(format!("{stem}.json")), description.as_bytes())?;
            for &shading in shadings {
                let options = options(width, height, shading, Rasterizer::Tiled);
                let mut image = Image::filled(width, height, BACKGROUND);
                renderer.render_into(&scene, &options, &mut image)?;
                let path = dir.join(format!("{stem}-{}.png", shading.name()));
                shadelab_io::write_png(&path, &image)
                    .with_context(|| format!("cannot write {}", path.display()))?;
            }
            crate::warn(&format!("exported {stem}\n"));
        }
    }
    Ok(())
}

pub(super) fn write_file(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    shadelab_io::write_atomic(path, |out| out.write_all(bytes))
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Writes the vertex, index and flat arrays; returns (vertices, triangles).
pub(super) fn write_geometry(
    dir: &Path,
    stem: &str,
    scene: &Scene,
) -> anyhow::Result<(usize, usize)> {
    let mesh = &scene.mesh;
    let normals = &scene.normals;
    let mut ids = std::collections::HashMap::new();
    let (mut vertices, mut indices, mut flat) = (Vec::<f32>::new(), Vec::<u32>::new(), Vec::new());
    let mut points = Vec::new();
    for face in 0..mesh.polygon_count() {
        let corners = mesh.corner_range(face);
        points.clear();
        points.extend(
            mesh.polygon(face)
                .iter()
                .map(|&p| mesh.positions()[p as usize]),
        );
        // Degenerate polygons are not drawn by either rasterizer.
        let Some(n) = face_normal(&points) else {
            continue;
        };
        let centroid = points.iter().sum::<Vec3>() / points.len() as f32;
        let polygon: Vec<u32> = corners
            .map(|c| {
                let key = (mesh.corners()[c], normals.corner()[c]);
                *ids.entry(key).or_insert_with(|| {
                    let p = mesh.positions()[key.0 as usize];
                    let n = normals.normals[key.1 as usize];
                    vertices.extend_from_slice(&[p.x, p.y, p.z, n.x, n.y, n.z]);
                    (vertices.len() / 6 - 1) as u32
                })
            })
            .collect();
        for k in 1..polygon.len() - 1 {
            indices.extend_from_slice(&[polygon[0], polygon[k], polygon[k + 1]]);
            flat.extend_from_slice(&[n.x, n.y, n.z, centroid.x, centroid.y, centroid.z]);
        }
    }
    let bytes = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    write_file(&dir.join(format!("{stem}.vertices.f32")), &bytes(&vertices))?;
    write_file(&dir.join(format!("{stem}.flat.f32")), &bytes(&flat))?;
    let index_bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
    write_file(&dir.join(format!("{stem}.indices.u32")), &index_bytes)?;
    Ok((vertices.len() / 6, indices.len() / 3))
}
