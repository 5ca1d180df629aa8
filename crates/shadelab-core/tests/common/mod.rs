//! Helpers shared by shadelab-core's integration tests.
//!
//! Everything here is an independent re-derivation of the project's
//! conventions in `f64`: camera rays and projection computed from the camera
//! parameters (never from the renderer's matrices), the Phong reflection model
//! written from its formula, and a brute-force edge-function coverage test
//! with the top-left rule. Image comparisons write the actual and expected
//! images as PPM files into the temporary directory when they fail.
#![allow(dead_code)]

mod coverage;
mod floor;
mod images;

// Each test binary uses some of these.
#[allow(unused_imports)]
pub use coverage::*;
#[allow(unused_imports)]
pub use floor::*;
#[allow(unused_imports)]
pub use images::*;

use glam::{DVec3, Vec3};
use shadelab_core::{
    Camera, CornerNormals, Interpolation, Light, LightKind, Material, Mesh, Polygons, Rasterizer,
    RenderOptions, Rgb, Rgb8, Scene, Shading, Specular,
};

/// Snapped window units per pixel (1/256 pixel).
pub const SUB: i64 = 256;

// ---------------------------------------------------------------- conversions

pub fn d(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

pub fn f(v: DVec3) -> Vec3 {
    v.as_vec3()
}

pub fn rgb(c: Rgb) -> DVec3 {
    DVec3::new(c.r.into(), c.g.into(), c.b.into())
}

// ---------------------------------------------------------------- camera

/// The camera, re-derived from its parameters: an orthonormal basis, the
/// vertical half-angle and the image size. Rays and projections follow the
/// written conventions (OpenGL perspective, row 0 at the top, pixel centres
/// at half-integers).
#[derive(Debug, Clone, Copy)]
pub struct View {
    pub eye: DVec3,
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub tan_half_y: f64,
    pub aspect: f64,
    pub width: f64,
    pub height: f64,
    pub near: f64,
    pub far: f64,
}

impl View {
    pub fn new(camera: &Camera, width: u32, height: u32) -> View {
        let eye = d(camera.eye);
        let forward = (d(camera.target) - eye).normalize();
        let right = forward.cross(d(camera.up)).normalize();
        let up = right.cross(forward);
        View {
            eye,
            forward,
            right,
            up,
            tan_half_y: (f64::from(camera.fov_y_degrees).to_radians() * 0.5).tan(),
            aspect: f64::from(width) / f64::from(height),
            width: width.into(),
            height: height.into(),
            near: camera.near.into(),
            far: camera.far.into(),
        }
    }

    /// The direction through window point (`x`, `y`) (pixels), scaled so its
    /// component along the view direction is 1: `eye + t·dir` is at view depth `t`.
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        let ndc_x = 2.0 * x / self.width - 1.0;
        let ndc_y = 1.0 - 2.0 * y / self.height;
        self.forward
            + self.right * (ndc_x * self.tan_half_y * self.aspect)
            + self.up * (ndc_y * self.tan_half_y)
    }

    /// The ray through the centre of pixel (`i`, `j`).
    pub fn pixel_ray(&self, i: u32, j: u32) -> DVec3 {
        self.ray(f64::from(i) + 0.5, f64::from(j) + 0.5)
    }

    /// View depth (distance along the view direction) of a world point.
    pub fn depth(&self, p: DVec3) -> f64 {
        (p - self.eye).dot(self.forward)
    }

    /// Window position in pixels of a world point in front of the camera.
    pub fn project(&self, p: DVec3) -> (f64, f64) {
        let q = p - self.eye;
        let depth = q.dot(self.forward);
        let ndc_x = q.dot(self.right) / (depth * self.tan_half_y * self.aspect);
        let ndc_y = q.dot(self.up) / (depth * self.tan_half_y);
        (
            (ndc_x + 1.0) * 0.5 * self.width,
            (1.0 - ndc_y) * 0.5 * self.height,
        )
    }

    /// Window position snapped to 1/256 pixel.
    pub fn snapped(&self, p: DVec3) -> (i64, i64) {
        let (x, y) = self.project(p);
        (snap(x), snap(y))
    }

    /// Where the ray through window point (`x`, `y`) meets the plane through
    /// `point` with normal `normal`, as (view depth, world point).
    pub fn hit_plane(&self, x: f64, y: f64, point: DVec3, normal: DVec3) -> Option<(f64, DVec3)> {
        let dir = self.ray(x, y);
        let denom = normal.dot(dir);
        if denom.abs() < 1e-300 {
            return None;
        }
        let t = normal.dot(point - self.eye) / denom;
        Some((t, self.eye + dir * t))
    }

    /// Where the ray through window point (`x`, `y`) first meets a sphere, as
    /// (view depth, world point).
    pub fn hit_sphere(&self, x: f64, y: f64, centre: DVec3, radius: f64) -> Option<(f64, DVec3)> {
        let dir = self.ray(x, y);
        let oc = self.eye - centre;
        let a = dir.dot(dir);
        let b = oc.dot(dir);
        let c = oc.dot(oc) - radius * radius;
        let disc = b * b - a * c;
        if disc < 0.0 {
            return None;
        }
        let t = (-b - disc.sqrt()) / a;
        Some((t, self.eye + dir * t))
    }

    /// Angle between the ray through (`x`, `y`) and the direction to `centre`.
    pub fn angle_to(&self, x: f64, y: f64, centre: DVec3) -> f64 {
        let a = self.ray(x, y).normalize();
        let b = (centre - self.eye).normalize();
        a.dot(b).clamp(-1.0, 1.0).acos()
    }

    /// The angle one pixel subtends at the centre of the image (an upper
    /// bound elsewhere).
    pub fn pixel_angle(&self) -> f64 {
        2.0 * self.tan_half_y / self.height
    }
}

/// Snaps a window coordinate to 1/256 pixel, rounding half away from zero.
pub fn snap(pixels: f64) -> i64 {
    (pixels * SUB as f64).round() as i64
}

// ---------------------------------------------------------------- lighting

#[derive(Debug, Clone, Copy)]
pub enum LightAt {
    Point(DVec3),
    /// The direction the light travels in.
    Directional(DVec3),
}

/// The Phong reflection model, written from its formula in `f64`.
#[derive(Debug, Clone)]
pub struct PhongModel {
    pub ambient: DVec3,
    /// Where, and colour times intensity.
    pub lights: Vec<(LightAt, DVec3)>,
    pub ka: DVec3,
    pub kd: DVec3,
    pub ks: DVec3,
    pub shininess: f64,
    pub eye: DVec3,
    /// Blinn's `n·h` in place of Phong's `r·v`.
    pub blinn: bool,
}

impl PhongModel {
    /// The model's parameters as the scene states them.
    pub fn of_scene(scene: &Scene) -> PhongModel {
        PhongModel {
            ambient: rgb(scene.ambient),
            lights: scene
                .lights
                .iter()
                .map(|l| {
                    let at = match l.kind {
                        LightKind::Point { position } => LightAt::Point(d(position)),
                        LightKind::Directional { direction } => LightAt::Directional(d(direction)),
                    };
                    (at, rgb(l.color) * f64::from(l.intensity))
                })
                .collect(),
            ka: rgb(scene.material.ka),
            kd: rgb(scene.material.kd),
            ks: rgb(scene.material.ks),
            shininess: scene.material.shininess.into(),
            eye: d(scene.camera.eye),
            blinn: false,
        }
    }

    /// `I = Ia·Ka + Σ [Id·Kd·max(0, n·l) + Is·Ks·max(0, r·v)^p]` (or Blinn's
    /// `n·h` with `h = normalize(l + v)` in place of `r·v`), unclamped,
    /// with the specular term only when `specular` and only where `n·l > 0`.
    /// `n` must be a unit vector.
    pub fn eval(&self, p: DVec3, n: DVec3, specular: bool) -> DVec3 {
        let mut out = self.ambient * self.ka;
        let v = (self.eye - p).normalize();
        for &(at, intensity) in &self.lights {
            let l = match at {
                LightAt::Point(q) => (q - p).normalize(),
                LightAt::Directional(dir) => -dir.normalize(),
            };
            let n_dot_l = n.dot(l);
            if n_dot_l <= 0.0 {
                continue;
            }
            out += intensity * self.kd * n_dot_l;
            if specular {
                let cosine = if self.blinn {
                    n.dot((l + v).normalize())
                } else {
                    (2.0 * n_dot_l * n - l).dot(v)
                };
                out += intensity * self.ks * cosine.max(0.0).powf(self.shininess);
            }
        }
        out
    }
}

/// Clamps a colour to 0–1 per channel.
pub fn clamp01(c: DVec3) -> DVec3 {
    c.clamp(DVec3::ZERO, DVec3::ONE)
}

/// A 0–1 colour as unrounded 0–255 values (clamped).
pub fn to_255(c: DVec3) -> [f64; 3] {
    (clamp01(c) * 255.0).to_array()
}

/// A 0–1 colour as the pixel the conventions prescribe: round(clamp(I)·255).
pub fn to_rgb8(c: DVec3) -> Rgb8 {
    let [r, g, b] = to_255(c).map(|v| v.round() as u8);
    Rgb8::new(r, g, b)
}

// ---------------------------------------------------------------- scenes

/// The lighting most tests use: a warm point light up and to the right, a
/// bluish directional light from the front, a little ambient light.
pub fn standard_lighting() -> (Rgb, Vec<Light>, Material) {
    let ambient = Rgb::new(0.15, 0.12, 0.10);
    let lights = vec![
        Light {
            kind: LightKind::Point {
                position: Vec3::new(3.0, 4.0, 6.0),
            },
            color: Rgb::new(1.0, 0.95, 0.9),
            intensity: 0.9,
            attenuation: shadelab_core::NO_ATTENUATION,
        },
        Light {
            kind: LightKind::Directional {
                direction: Vec3::new(-0.3, -0.2, -1.0),
            },
            color: Rgb::new(0.4, 0.5, 1.0),
            intensity: 0.5,
            attenuation: shadelab_core::NO_ATTENUATION,
        },
    ];
    let material = Material {
        ka: Rgb::new(0.9, 0.4, 0.3),
        kd: Rgb::new(0.8, 0.45, 0.3),
        ks: Rgb::new(0.6, 0.6, 0.6),
        shininess: 12.0,
    };
    (ambient, lights, material)
}

/// A background colour the standard lighting never produces (its red
/// channel is at least 0.15·0.9·255 ≈ 34).
pub const BACKGROUND: Rgb8 = Rgb8::new(0, 255, 0);

/// A scene with the standard lighting.
pub fn scene(mesh: Mesh, normals: CornerNormals, camera: Camera) -> Scene {
    let (ambient, lights, material) = standard_lighting();
    Scene {
        mesh,
        normals,
        camera,
        ambient,
        lights,
        material,
    }
}

/// A scene with the standard lighting and the mesh's uniform vertex normals.
pub fn smooth(mesh: Mesh, camera: Camera) -> Scene {
    let normals =
        shadelab_core::vertex_normals(&mesh, shadelab_core::NormalWeighting::Uniform, None);
    scene(mesh, normals, camera)
}

/// Two scenes that need clipping: the camera inside a cube (near plane and
/// guard band) and a floor a million units wide seen from just above it.
pub fn clipped_scenes() -> [(&'static str, Scene); 2] {
    let cube = shadelab_core::builtin_model("cube", Some(4)).unwrap();
    let normals =
        shadelab_core::vertex_normals(&cube, shadelab_core::NormalWeighting::Uniform, Some(30.0));
    let inside = scene(
        cube,
        normals,
        camera(
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.0, 0.3, -0.4),
            70.0,
            0.05,
            10.0,
        ),
    );
    let floor = Mesh::from_polygons(
        vec![
            Vec3::new(-1e6, -1.0, -1e6),
            Vec3::new(-1e6, -1.0, 1e6),
            Vec3::new(1e6, -1.0, 1e6),
            Vec3::new(1e6, -1.0, -1e6),
        ],
        [[0u32, 1, 2, 3]],
    )
    .unwrap();
    let up = CornerNormals::new(vec![Vec3::Y], vec![0; 4]);
    let floor = scene(
        floor,
        up,
        camera(
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(0.0, 0.2, -3.0),
            60.0,
            0.1,
            1e7,
        ),
    );
    [("inside-cube", inside), ("floor", floor)]
}

/// Corner normals given explicitly, one per corner (no sharing).
pub fn explicit_normals(normals: &[Vec3]) -> CornerNormals {
    CornerNormals::new(normals.to_vec(), (0..normals.len() as u32).collect())
}

/// Each corner gets its face's normal (`+z` for a degenerate face).
pub fn face_corner_normals(mesh: &Mesh) -> CornerNormals {
    let faces = shadelab_core::face_normals(mesh);
    let mut normals = Vec::new();
    for (face, n) in faces.iter().enumerate() {
        for _ in mesh.corner_range(face) {
            normals.push(n.unwrap_or(Vec3::Z));
        }
    }
    explicit_normals(&normals)
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
        rasterizer: rasterizer_under_test(),
        polygons: Polygons::Fans,
        specular: Specular::Phong,
        fixed_point_bits: None,
        palette: None,
    }
}

/// The rasterizer these tests check: the default (tiled) one, or the one
/// named by `SHADELAB_TEST_RASTERIZER` (`scanline` or `tiled`), so that CI
/// runs the whole reference suite against both.
pub fn rasterizer_under_test() -> Rasterizer {
    match std::env::var("SHADELAB_TEST_RASTERIZER").as_deref() {
        Ok("scanline") => Rasterizer::Scanline,
        Ok("tiled") | Err(_) => Rasterizer::Tiled,
        Ok(other) => panic!("SHADELAB_TEST_RASTERIZER={other}: expected scanline or tiled"),
    }
}

pub fn camera(eye: DVec3, target: DVec3, fov_y_degrees: f32, near: f32, far: f32) -> Camera {
    Camera {
        eye: f(eye),
        target: f(target),
        up: Vec3::Y,
        fov_y_degrees,
        near,
        far,
    }
}
