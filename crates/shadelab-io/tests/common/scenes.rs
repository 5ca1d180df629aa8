//! Scene files as the scene tests read them: parsed, resolved against the
//! current folder, and the shapes of what they load.

#![allow(dead_code)]

use std::path::Path;

use glam::Vec3;
use shadelab_core::{Mesh, RenderOptions, Scene};
use shadelab_io::{SceneError, SceneFile};

/// A small tetrahedron away from the origin, with no normals.
pub const TETRA_OBJ: &str = "\
v 10 0 0
v 12 0 0
v 10 2 0
v 10 0 2
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
";

pub fn parse(text: &str) -> SceneFile {
    SceneFile::parse(text, "test.toml").unwrap_or_else(|e| panic!("should parse: {e}"))
}

pub fn resolve(text: &str) -> Result<(Scene, RenderOptions), SceneError> {
    parse(text).resolve(Path::new("."))
}

pub fn resolved(text: &str) -> (Scene, RenderOptions) {
    resolve(text).unwrap_or_else(|e| panic!("should resolve: {e}"))
}

/// Centre of the bounding box and the distance of the farthest vertex from it.
pub fn centre_and_radius(mesh: &Mesh) -> (Vec3, f32) {
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    let radius = mesh
        .corners()
        .iter()
        .map(|&i| (mesh.positions()[i as usize] - centre).length())
        .fold(0.0f32, f32::max);
    (centre, radius)
}
