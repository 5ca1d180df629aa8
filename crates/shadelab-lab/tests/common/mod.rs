//! Scenes the instrument tests share.
#![allow(dead_code)]

use glam::Vec3;
use shadelab_core::{
    builtin_model, vertex_normals, Camera, Interpolation, Light, LightKind, Material, Mesh,
    NormalWeighting, Polygons, Rasterizer, RenderOptions, Rgb, Rgb8, Scene, Shading, Specular,
};

pub const BACKGROUND: Rgb8 = Rgb8::new(0, 255, 0);

pub fn camera(eye: Vec3) -> Camera {
    Camera {
        eye,
        target: Vec3::ZERO,
        up: Vec3::Y,
        fov_y_degrees: 40.0,
        near: 0.5,
        far: 20.0,
    }
}

/// A built-in model in its own coordinates, uniform normals, one white
/// point light up and to the right, a mid-grey material that never clamps
/// in the diffuse range.
pub fn scene(model: &str, detail: u32, eye: Vec3) -> Scene {
    let mesh = builtin_model(model, Some(detail)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    Scene {
        mesh,
        normals,
        camera: camera(eye),
        ambient: Rgb::splat(0.1),
        lights: vec![Light {
            kind: LightKind::Point {
                position: Vec3::new(2.0, 2.5, 4.0),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        }],
        material: Material {
            ka: Rgb::new(0.6, 0.6, 0.6),
            kd: Rgb::new(0.6, 0.6, 0.6),
            ks: Rgb::new(0.4, 0.4, 0.4),
            shininess: 20.0,
        },
    }
}

pub fn options(width: u32, height: u32, shading: Shading) -> RenderOptions {
    RenderOptions {
        width,
        height,
        shading,
        background: BACKGROUND,
        cull_backfaces: true,
        gouraud_specular: false,
        interpolation: Interpolation::Perspective,
        rasterizer: Rasterizer::Scanline,
        polygons: Polygons::Fans,
        specular: Specular::Phong,
        fixed_point_bits: None,
        palette: None,
    }
}

/// The square |x|, |y| ≤ 1 at z = 0 as one quad facing +z.
pub fn square_mesh() -> Mesh {
    Mesh::from_polygons(
        vec![
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ],
        [[0u32, 1, 2, 3]],
    )
    .unwrap()
}
