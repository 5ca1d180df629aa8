//! Helpers shared by shadelab-core's integration tests.
//!
//! Everything here is an independent re-derivation of the project's
//! conventions in `f64`: camera rays and projection computed from the camera
//! parameters (never from the renderer's matrices), the Phong reflection model
//! written from its formula, and a brute-force edge-function coverage test
//! with the top-left rule. Image comparisons write the actual and expected
//! images as PPM files into the temporary directory when they fail.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::PathBuf;

use glam::{DVec3, Vec3};
use shadelab_core::{
    Camera, CornerNormals, Image, Interpolation, Light, LightKind, Material, Mesh, Polygons,
    Rasterizer, RenderOptions, Rgb, Rgb8, Scene, Shading, Specular,
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
    let up = CornerNormals {
        normals: vec![Vec3::Y],
        corner: vec![0; 4],
    };
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
    CornerNormals {
        normals: normals.to_vec(),
        corner: (0..normals.len() as u32).collect(),
    }
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

// ---------------------------------------------------------------- coverage

/// Twice the signed area of a window polygon (snapped units), positive when
/// the viewer sees it counter-clockwise (window y points down).
pub fn area2_ccw(poly: &[(i64, i64)]) -> i128 {
    let n = poly.len();
    let mut sum = 0i128;
    for i in 0..n {
        let (ax, ay) = poly[i];
        let (bx, by) = poly[(i + 1) % n];
        sum += ax as i128 * by as i128 - bx as i128 * ay as i128;
    }
    -sum
}

/// The edge function of `a → b` at `p`: positive on the inside of a polygon
/// wound counter-clockwise as seen (window y down), zero on the edge's line.
pub fn edge_function(a: (i64, i64), b: (i64, i64), p: (i64, i64)) -> i128 {
    (b.1 - a.1) as i128 * (p.0 - a.0) as i128 - (b.0 - a.0) as i128 * (p.1 - a.1) as i128
}

/// An edge whose points belong to the polygon under the top-left rule: a left
/// edge (it runs down the screen) or a top edge (horizontal, running left).
pub fn is_top_left(a: (i64, i64), b: (i64, i64)) -> bool {
    b.1 > a.1 || (b.1 == a.1 && b.0 < a.0)
}

/// Brute-force coverage of a convex polygon wound counter-clockwise as seen:
/// is the point `p` (snapped units) inside, with the top-left rule on ties?
pub fn covers(poly: &[(i64, i64)], p: (i64, i64)) -> bool {
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if a == b {
            continue;
        }
        let e = edge_function(a, b, p);
        if e < 0 || (e == 0 && !is_top_left(a, b)) {
            return false;
        }
    }
    true
}

/// The centre of pixel (`i`, `j`) in snapped units.
pub fn centre(i: i64, j: i64) -> (i64, i64) {
    (i * SUB + SUB / 2, j * SUB + SUB / 2)
}

/// The pixels of a `width` × `height` image a convex CCW polygon covers, by brute force.
pub fn brute_force_coverage(poly: &[(i64, i64)], width: u32, height: u32) -> Vec<u32> {
    let mut out = vec![0; (width * height) as usize];
    if poly.len() < 3 || area2_ccw(poly) <= 0 {
        return out;
    }
    for j in 0..height {
        for i in 0..width {
            if covers(poly, centre(i.into(), j.into())) {
                out[(j * width + i) as usize] = 1;
            }
        }
    }
    out
}

/// The smallest signed distance, in pixels, from a window point to the edges'
/// lines of a convex CCW polygon given in snapped units: positive inside.
pub fn inside_distance(poly: &[(i64, i64)], x: f64, y: f64) -> f64 {
    let n = poly.len();
    let (x, y) = (x * SUB as f64, y * SUB as f64);
    let mut min = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if a == b {
            continue;
        }
        let (ax, ay, bx, by) = (a.0 as f64, a.1 as f64, b.0 as f64, b.1 as f64);
        let len = (bx - ax).hypot(by - ay);
        let e = ((by - ay) * (x - ax) - (bx - ax) * (y - ay)) / len;
        min = min.min(e / SUB as f64);
    }
    min
}

/// The convex hull of points (monotone chain), counter-clockwise as seen in
/// window coordinates (y down), without collinear points.
pub fn convex_hull(points: &[(i64, i64)]) -> Vec<(i64, i64)> {
    let mut pts = points.to_vec();
    pts.sort_unstable();
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    // z of (a − o) × (b − o) in y-down coordinates; > 0 is a clockwise turn as seen.
    let cross = |o: (i64, i64), a: (i64, i64), b: (i64, i64)| {
        (a.0 - o.0) as i128 * (b.1 - o.1) as i128 - (a.1 - o.1) as i128 * (b.0 - o.0) as i128
    };
    let mut hull: Vec<(i64, i64)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(i64, i64)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) >= 0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if area2_ccw(&hull) < 0 {
        hull.reverse();
    }
    hull
}

// ---------------------------------------------------------------- images

fn out_dir() -> PathBuf {
    let dir = std::env::temp_dir().join("shadelab-core-tests");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

/// Writes a binary PPM into the temporary directory and returns its path.
pub fn write_ppm(
    name: &str,
    width: u32,
    height: u32,
    pixel: impl Fn(u32, u32) -> [u8; 3],
) -> PathBuf {
    let path = out_dir().join(format!("{name}.ppm"));
    let mut bytes = format!("P6\n{width} {height}\n255\n").into_bytes();
    for y in 0..height {
        for x in 0..width {
            bytes.extend_from_slice(&pixel(x, y));
        }
    }
    if let Err(e) = std::fs::write(&path, bytes) {
        eprintln!("could not write {}: {e}", path.display());
    }
    path
}

/// An expected image: per pixel an unrounded 0–255 colour, or `None` where
/// the test does not care.
pub struct Expected {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Option<[f64; 3]>>,
}

impl Expected {
    pub fn new(width: u32, height: u32) -> Expected {
        Expected {
            width,
            height,
            pixels: vec![None; (width * height) as usize],
        }
    }

    pub fn set(&mut self, x: u32, y: u32, c: [f64; 3]) {
        self.pixels[(y * self.width + x) as usize] = Some(c);
    }

    pub fn set_rgb8(&mut self, x: u32, y: u32, c: Rgb8) {
        self.set(x, y, c.0.map(f64::from));
    }

    pub fn checked(&self) -> usize {
        self.pixels.iter().filter(|p| p.is_some()).count()
    }
}

/// Compares every pixel where `expected` has a value with `actual`, allowing
/// `tolerance` (0–255 units) per channel. On failure writes
/// `<name>-actual.ppm`, `<name>-expected.ppm` (don't-care pixels magenta) and
/// `<name>-diff.ppm`, and says where the first difference is.
pub fn compare_images(
    name: &str,
    actual: &Image,
    expected: &Expected,
    tolerance: f64,
) -> Result<usize, String> {
    assert_eq!(
        (actual.width(), actual.height()),
        (expected.width, expected.height),
        "{name}: image size"
    );
    let w = expected.width;
    let mut first = None;
    let mut bad = 0usize;
    let mut worst = 0f64;
    for y in 0..expected.height {
        for x in 0..w {
            let Some(e) = expected.pixels[(y * w + x) as usize] else {
                continue;
            };
            let a = actual.pixel(x, y).0;
            let diff = (0..3)
                .map(|k| (f64::from(a[k]) - e[k]).abs())
                .fold(0.0, f64::max);
            if diff > tolerance {
                bad += 1;
                worst = worst.max(diff);
                first.get_or_insert((x, y, a, e));
            }
        }
    }
    let Some((x, y, a, e)) = first else {
        return Ok(expected.checked());
    };
    let exp8 = |x: u32, y: u32| match expected.pixels[(y * w + x) as usize] {
        Some(c) => c.map(|v| v.round().clamp(0.0, 255.0) as u8),
        None => [255, 0, 255],
    };
    let pa = write_ppm(&format!("{name}-actual"), w, expected.height, |x, y| {
        actual.pixel(x, y).0
    });
    let pe = write_ppm(&format!("{name}-expected"), w, expected.height, exp8);
    let pd = write_ppm(
        &format!("{name}-diff"),
        w,
        expected.height,
        |x, y| match expected.pixels[(y * w + x) as usize] {
            None => [0, 0, 0],
            Some(e) => {
                let a = actual.pixel(x, y).0;
                let diff = (0..3)
                    .map(|k| (f64::from(a[k]) - e[k]).abs())
                    .fold(0.0, f64::max);
                if diff > tolerance {
                    [255, 0, 0]
                } else {
                    [(diff * 60.0).min(255.0) as u8; 3]
                }
            }
        },
    );
    let mut msg = String::new();
    let _ = write!(
        msg,
        "{name}: {bad} of {} checked pixels differ by more than {tolerance} (worst {worst:.2}); \
         first at ({x}, {y}): actual {a:?}, expected [{:.2}, {:.2}, {:.2}]\n  actual:   {}\n  expected: {}\n  diff:     {}",
        expected.checked(),
        e[0],
        e[1],
        e[2],
        pa.display(),
        pe.display(),
        pd.display()
    );
    Err(msg)
}

/// What a coverage count may be at one pixel.
pub type CountRange = std::ops::RangeInclusive<u32>;

/// Checks a coverage map against per-pixel expectations (`None`: any count).
/// On failure writes `<name>-counts.ppm` (black 0, grey 1, red more, blue
/// where the expectation fails) and reports the first failing pixel.
pub fn compare_counts(
    name: &str,
    counts: &[u32],
    width: u32,
    height: u32,
    expected: impl Fn(u32, u32) -> Option<CountRange>,
) -> Result<usize, String> {
    assert_eq!(counts.len(), (width * height) as usize, "{name}: map size");
    let mut first = None;
    let mut bad = 0usize;
    let mut checked = 0usize;
    for y in 0..height {
        for x in 0..width {
            let Some(range) = expected(x, y) else {
                continue;
            };
            checked += 1;
            let c = counts[(y * width + x) as usize];
            if !range.contains(&c) {
                bad += 1;
                first.get_or_insert((x, y, c, range));
            }
        }
    }
    let Some((x, y, c, range)) = first else {
        return Ok(checked);
    };
    let path = write_ppm(&format!("{name}-counts"), width, height, |x, y| {
        let c = counts[(y * width + x) as usize];
        if expected(x, y).is_some_and(|r| !r.contains(&c)) {
            [0, 0, 255]
        } else {
            match c {
                0 => [0, 0, 0],
                1 => [160, 160, 160],
                _ => [255, 0, 0],
            }
        }
    });
    Err(format!(
        "{name}: {bad} of {checked} checked pixels have a wrong coverage count; first at ({x}, {y}): \
         {c}, expected {range:?}\n  counts: {} (blue = wrong)",
        path.display()
    ))
}

/// Unwraps a comparison, panicking with its report.
pub fn ok(result: Result<usize, String>) -> usize {
    match result {
        Ok(n) => n,
        Err(msg) => panic!("{msg}"),
    }
}
