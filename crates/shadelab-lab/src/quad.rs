//! Interpolation on polygons: Gouraud shading over a quad directly (along
//! edges and spans, as the textbook does) against over its two triangles.
//!
//! The study draws one square facing the camera, lit so that only its first
//! vertex is bright (intensity 1) and the other three dark (0), and turns
//! it in the image plane. Interpolated whole, the value at the centre
//! depends on the turn: 1/4 when the square is axis-aligned (the scanline
//! walk is then bilinear), 1/2 or 0 when it stands on a corner and the
//! centre's scanline runs from one side vertex to the other. Split into
//! triangles along the diagonal through the bright vertex, the centre lies
//! on that diagonal and is 1/2 at every turn, but which diagonal is split
//! decides the picture. Either way a quad's shading is not determined by
//! its vertices alone.

use glam::Vec3;
use shadelab_core::{
    probe, render, Camera, CornerNormals, Image, Interpolation, Light, LightKind, Material, Mesh,
    Polygons, ProbeRequest, Rasterizer, RenderError, RenderOptions, Rgb, Rgb8, Scene, Shading,
    Specular,
};

/// The quad study at one angle.
#[derive(Debug, Clone)]
pub struct QuadSample {
    /// Turn in the image plane, degrees counter-clockwise.
    pub angle_degrees: f32,
    /// Interpolated whole.
    pub whole: Image,
    /// Interpolated as a fan of two triangles.
    pub fans: Image,
    /// Intensity (0–1) at the centre pixel, whole.
    pub whole_centre: f32,
    /// Intensity (0–1) at the centre pixel, as triangles.
    pub fans_centre: f32,
}

/// The square turned by `angle_degrees`, its options for a `size` × `size`
/// image (odd sizes put a pixel centre on the square's centre).
pub fn quad_scene(angle_degrees: f32, size: u32) -> (Scene, RenderOptions) {
    let (s, c) = angle_degrees.to_radians().sin_cos();
    let corners = [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let positions = corners
        .iter()
        .map(|&(x, y)| Vec3::new(x * c - y * s, x * s + y * c, 0.0))
        .collect();
    let mesh = Mesh::from_polygons(positions, [[0u32, 1, 2, 3]]).expect("a square is a mesh");
    // Vertex 0 faces the light; the others face away and get no diffuse light.
    let normals = CornerNormals::new(vec![Vec3::Z, -Vec3::Z], vec![0, 1, 1, 1]);
    let scene = Scene {
        mesh,
        normals,
        camera: Camera {
            eye: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_degrees: 45.0,
            near: 1.0,
            far: 10.0,
        },
        ambient: Rgb::BLACK,
        lights: vec![Light {
            kind: LightKind::Directional {
                direction: -Vec3::Z,
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        }],
        material: Material {
            ka: Rgb::WHITE,
            kd: Rgb::WHITE,
            ks: Rgb::BLACK,
            shininess: 1.0,
        },
    };
    let options = RenderOptions {
        width: size,
        height: size,
        shading: Shading::Gouraud,
        background: Rgb8::new(30, 30, 40),
        cull_backfaces: true,
        gouraud_specular: false,
        interpolation: Interpolation::Screen,
        rasterizer: Rasterizer::Scanline,
        polygons: Polygons::Whole,
        specular: Specular::Phong,
        fixed_point_bits: None,
        palette: None,
    };
    (scene, options)
}

/// The quad drawn whole and as triangles at each angle.
///
/// # Errors
/// As [`shadelab_core::render`] (an absurd `size`).
pub fn quad_study(angles: &[f32], size: u32) -> Result<Vec<QuadSample>, RenderError> {
    angles
        .iter()
        .map(|&angle| {
            let (scene, options) = quad_scene(angle, size);
            let centre = [(size / 2, size / 2)];
            let draw = |polygons| -> Result<(Image, f32), RenderError> {
                let options = RenderOptions {
                    polygons,
                    ..options
                };
                let (image, _) = render(&scene, &options)?;
                let record = probe(
                    &scene,
                    &options,
                    ProbeRequest {
                        pixels: &centre,
                        trace: false,
                    },
                )?;
                let value = record[0].as_ref().map_or(f32::NAN, |r| r.lit.r);
                Ok((image, value))
            };
            let (whole, whole_centre) = draw(Polygons::Whole)?;
            let (fans, fans_centre) = draw(Polygons::Fans)?;
            Ok(QuadSample {
                angle_degrees: angle,
                whole,
                fans,
                whole_centre,
                fans_centre,
            })
        })
        .collect()
}
