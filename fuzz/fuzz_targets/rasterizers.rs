#![no_main]
//! Arbitrary triangles (tiny, huge, degenerate, crossing the near plane,
//! behind the eye) seen by an arbitrary camera through the whole renderer
//! with both rasterizers: no panic; the same coverage from both, or the same
//! error; images of the requested size, with the background wherever
//! nothing covers a pixel.
use libfuzzer_sys::{arbitrary::Arbitrary, fuzz_target};
use shadelab_core::{
    coverage, render, vertex_normals, Camera, Interpolation, Light, LightKind, Material, Mesh,
    NormalWeighting, Polygons, Rasterizer, RenderOptions, Rgb, Rgb8, Scene, Shading, Specular,
};

/// A coordinate: mostly small steps of 1/64 near the origin, sometimes any float.
#[derive(Debug, Arbitrary)]
enum Coord {
    Small(i16),
    Any(f32),
}

impl Coord {
    fn value(&self) -> f32 {
        match *self {
            Coord::Small(v) => f32::from(v) / 64.0,
            Coord::Any(v) => v,
        }
    }
}

#[derive(Debug, Arbitrary)]
struct Input {
    vertices: Vec<[Coord; 3]>,
    faces: Vec<[u8; 3]>,
    eye: [Coord; 3],
    target: [i8; 3],
    fov: u8,
    near: u8,
    far: u16,
    width: u8,
    height: u8,
    shading: u8,
    cull: bool,
    screen: bool,
}

const BACKGROUND: Rgb8 = Rgb8::new(1, 2, 3);

fuzz_target!(|input: Input| {
    if input.vertices.is_empty() || input.faces.is_empty() || input.faces.len() > 64 {
        return;
    }
    let n = input.vertices.len();
    let positions = input
        .vertices
        .iter()
        .map(|v| glam::Vec3::new(v[0].value(), v[1].value(), v[2].value()))
        .collect();
    let faces = input
        .faces
        .iter()
        .map(|f| f.map(|i| u32::from(i) % n as u32));
    let Ok(mesh) = Mesh::from_polygons(positions, faces) else {
        return;
    };
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let near = f32::from(input.near) / 16.0;
    let scene = Scene {
        mesh,
        normals,
        camera: Camera {
            eye: glam::Vec3::new(input.eye[0].value(), input.eye[1].value(), input.eye[2].value()),
            target: glam::Vec3::from_array(input.target.map(|t| f32::from(t) / 16.0)),
            up: glam::Vec3::Y,
            fov_y_degrees: f32::from(input.fov) * 0.75,
            near,
            far: near + f32::from(input.far) / 8.0,
        },
        ambient: Rgb::splat(0.2),
        lights: vec![Light {
            kind: LightKind::Point {
                position: glam::Vec3::new(2.0, 2.0, 3.0),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        }],
        material: Material {
            ka: Rgb::new(1.0, 0.25, 0.25),
            kd: Rgb::new(1.0, 0.25, 0.25),
            ks: Rgb::WHITE,
            shininess: 32.0,
        },
    };
    let (width, height) = (u32::from(input.width % 48) + 1, u32::from(input.height % 48) + 1);
    let options = |rasterizer| RenderOptions {
        width,
        height,
        shading: Shading::ALL[usize::from(input.shading % 3)],
        background: BACKGROUND,
        cull_backfaces: input.cull,
        gouraud_specular: input.shading & 4 != 0,
        interpolation: if input.screen {
            Interpolation::Screen
        } else {
            Interpolation::Perspective
        },
        rasterizer,
        polygons: Polygons::Fans,
        specular: if input.shading & 8 != 0 {
            Specular::BlinnPhong
        } else {
            Specular::Phong
        },
        ..RenderOptions::default()
    };
    let scanline = coverage(&scene, &options(Rasterizer::Scanline));
    let tiled = coverage(&scene, &options(Rasterizer::Tiled));
    assert_eq!(scanline, tiled, "the rasterizers cover different pixels");
    for rasterizer in Rasterizer::ALL {
        let image = render(&scene, &options(rasterizer));
        match (&image, &scanline) {
            (Ok((image, _)), Ok(counts)) => {
                assert_eq!((image.width(), image.height()), (width, height));
                for (k, &c) in counts.iter().enumerate() {
                    let (x, y) = (k as u32 % width, k as u32 / width);
                    if c == 0 {
                        assert_eq!(image.pixel(x, y), BACKGROUND, "drawn where nothing covers");
                    }
                }
            }
            (Err(a), Err(b)) => assert_eq!(a, b),
            _ => panic!("render and coverage disagree on whether the scene is valid"),
        }
    }
});
