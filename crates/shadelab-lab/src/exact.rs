//! Exact surfaces: what the tessellated parametric models approximate.
//!
//! For each pixel, the ray through its centre meets the analytic surface
//! (sphere, torus, capped cylinder, cone with its base) and the point is lit
//! by the very same reflection model ([`Lighting::eval`]) with the true
//! normal. That image is what flat, Gouraud and Phong shading all try to
//! draw; the difference is each method's error.
//!
//! Rays and intersections are computed in `f64` from the camera's parameters.
//! A surface lives in its model's own coordinates and is placed in the world
//! by the same similarity the scene applies to the mesh (see
//! [`Surface::for_builtin`]), so mesh and surface coincide at the vertices.

use glam::{DMat4, DVec2, DVec3, DVec4, Vec3};
use shadelab_core::{builtin_model, Camera, Lighting, Mesh, Rgb, Scene, Terms};

use crate::lighting_of;

/// An analytic shape in its model's coordinates (axis along y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// The unit sphere.
    Sphere,
    /// Ring radius `ring` in the xz plane, tube radius `tube`.
    Torus {
        /// Distance from the axis to the tube's centre.
        ring: f64,
        /// The tube's radius.
        tube: f64,
    },
    /// Radius 1, from y = −1 to y = 1, with both caps.
    Cylinder,
    /// Base of radius 1 at y = −1, apex at y = 1, with the base disc.
    Cone,
    /// The square |x|, |y| ≤ 1 in the plane z = 0, facing +z (seen from
    /// either side): a polygon that tessellation reproduces exactly.
    Square,
}

/// A shape placed in the world: `world = (model − centre) · scale`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// The shape.
    pub shape: Shape,
    /// The model point that lands on the world origin.
    pub centre: DVec3,
    /// Uniform scale from model to world.
    pub scale: f64,
}

/// Where a ray met the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit {
    /// World position.
    pub point: DVec3,
    /// The true unit normal there, facing outward.
    pub normal: DVec3,
}

/// The built-in models that have an exact surface.
pub const EXACT_MODELS: [&str; 4] = ["sphere", "torus", "cylinder", "cone"];

impl Surface {
    /// A shape drawn in model coordinates, untouched.
    pub fn new(shape: Shape) -> Surface {
        Surface {
            shape,
            centre: DVec3::ZERO,
            scale: 1.0,
        }
    }

    /// The exact surface of built-in model `name` at `detail`, placed as the
    /// scene places the mesh: `normalized` when the scene gives no camera
    /// (the mesh is then centred and scaled as [`Mesh::normalized`] does).
    /// `None` for models without one (cube, icosphere, teapot) or a bad detail.
    pub fn for_builtin(name: &str, detail: Option<u32>, normalized: bool) -> Option<Surface> {
        let shape = match name {
            "sphere" => Shape::Sphere,
            "torus" => Shape::Torus {
                ring: 1.0,
                tube: 0.4,
            },
            "cylinder" => Shape::Cylinder,
            "cone" => Shape::Cone,
            _ => return None,
        };
        let mesh = builtin_model(name, detail).ok()?;
        Some(if normalized {
            let (centre, scale) = normalization(&mesh);
            Surface {
                shape,
                centre: centre.as_dvec3(),
                scale: f64::from(scale),
            }
        } else {
            Surface::new(shape)
        })
    }

    /// Where the world-space ray `origin + t·dir` (t ≥ 0) first meets the surface.
    pub fn intersect(&self, origin: DVec3, dir: DVec3) -> Option<SurfaceHit> {
        let o = origin / self.scale + self.centre;
        let d = dir.normalize();
        let (t, normal) = match self.shape {
            Shape::Sphere => sphere(o, d)?,
            Shape::Torus { ring, tube } => torus(o, d, ring, tube)?,
            Shape::Cylinder => cylinder(o, d)?,
            Shape::Cone => cone(o, d)?,
            Shape::Square => square(o, d)?,
        };
        Some(SurfaceHit {
            point: (o + d * t - self.centre) * self.scale,
            normal,
        })
    }
}

/// The centre and scale [`Mesh::normalized`] applies, computed the same way.
pub fn normalization(mesh: &Mesh) -> (Vec3, f32) {
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    let radius = mesh
        .corners()
        .iter()
        .map(|&i| (mesh.positions()[i as usize] - centre).length())
        .fold(0.0f32, f32::max);
    let scale = if radius > 0.0 && radius.is_finite() {
        1.0 / radius
    } else {
        1.0
    };
    (centre, scale)
}

/// The smaller non-negative root of `a·t² + 2b·t + c`.
fn nearest_root(a: f64, b: f64, c: f64) -> Option<f64> {
    let disc = b * b - a * c;
    if a == 0.0 || disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    // The numerically stable pair of roots.
    let q = -(b + s.copysign(b));
    let (r1, r2) = (q / a, c / q);
    let (lo, hi) = (r1.min(r2), r1.max(r2));
    if lo >= 0.0 {
        Some(lo)
    } else if hi >= 0.0 {
        Some(hi)
    } else {
        None
    }
}

fn square(o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
    if d.z == 0.0 {
        return None;
    }
    let t = -o.z / d.z;
    let p = o + d * t;
    (t >= 0.0 && p.x.abs() <= 1.0 && p.y.abs() <= 1.0).then(|| (t, DVec3::Z * -d.z.signum()))
}

fn sphere(o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
    let t = nearest_root(1.0, o.dot(d), o.length_squared() - 1.0)?;
    Some((t, (o + d * t).normalize()))
}

/// The nearest of several candidate hits.
fn nearest(candidates: impl IntoIterator<Item = Option<(f64, DVec3)>>) -> Option<(f64, DVec3)> {
    candidates
        .into_iter()
        .flatten()
        .filter(|(t, _)| *t >= 0.0)
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// Hits of the ray with the horizontal disc of `radius` at height `y`.
fn disc(o: DVec3, d: DVec3, y: f64, radius: f64, normal: DVec3) -> Option<(f64, DVec3)> {
    if d.y == 0.0 {
        return None;
    }
    let t = (y - o.y) / d.y;
    let p = o + d * t;
    (t >= 0.0 && p.x * p.x + p.z * p.z <= radius * radius).then_some((t, normal))
}

/// Both roots of the side quadric `a·t² + 2b·t + c`, each kept when its
/// point passes `keep`.
fn side_hits(
    a: f64,
    b: f64,
    c: f64,
    o: DVec3,
    d: DVec3,
    keep: impl Fn(DVec3) -> Option<DVec3>,
) -> [Option<(f64, DVec3)>; 2] {
    let disc = b * b - a * c;
    if a == 0.0 || disc < 0.0 {
        return [None, None];
    }
    let s = disc.sqrt();
    [(-b - s) / a, (-b + s) / a].map(|t| {
        let p = o + d * t;
        keep(p).map(|n| (t, n))
    })
}

fn cylinder(o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
    let [s1, s2] = side_hits(
        d.x * d.x + d.z * d.z,
        o.x * d.x + o.z * d.z,
        o.x * o.x + o.z * o.z - 1.0,
        o,
        d,
        |p| (p.y.abs() <= 1.0).then(|| DVec3::new(p.x, 0.0, p.z).normalize()),
    );
    nearest([
        s1,
        s2,
        disc(o, d, 1.0, 1.0, DVec3::Y),
        disc(o, d, -1.0, 1.0, -DVec3::Y),
    ])
}

fn cone(o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
    // x² + z² = ((1 − y)/2)², for −1 ≤ y ≤ 1.
    let (ky, kd) = ((1.0 - o.y) / 2.0, -d.y / 2.0);
    let [s1, s2] = side_hits(
        d.x * d.x + d.z * d.z - kd * kd,
        o.x * d.x + o.z * d.z - ky * kd,
        o.x * o.x + o.z * o.z - ky * ky,
        o,
        d,
        |p| {
            let rho = (1.0 - p.y) / 2.0;
            // The gradient (2x, ρ, 2z), on the real nappe only.
            ((-1.0..1.0).contains(&p.y) && rho > 0.0)
                .then(|| DVec3::new(2.0 * p.x, rho, 2.0 * p.z).normalize())
        },
    );
    nearest([s1, s2, disc(o, d, -1.0, 1.0, -DVec3::Y)])
}

/// The torus by sphere tracing its exact distance function, then Newton.
fn torus(o: DVec3, d: DVec3, ring: f64, tube: f64) -> Option<(f64, DVec3)> {
    let sdf = |p: DVec3| DVec2::new(DVec2::new(p.x, p.z).length() - ring, p.y).length() - tube;
    // Start where the ray enters the bounding sphere.
    let bound = ring + tube;
    let b = o.dot(d);
    let c = o.length_squared() - bound * bound;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let (enter, exit) = (-b - s, -b + s);
    if exit < 0.0 {
        return None;
    }
    let mut t = enter.max(0.0);
    for _ in 0..2000 {
        let dist = sdf(o + d * t);
        if dist < 1e-10 {
            // Polish with a few secant-free Newton steps on the distance.
            for _ in 0..3 {
                let p = o + d * t;
                let n = torus_normal(p, ring);
                let slope = n.dot(d);
                if slope.abs() < 1e-6 {
                    break;
                }
                t -= sdf(p) / slope;
            }
            let p = o + d * t;
            return Some((t, torus_normal(p, ring)));
        }
        t += dist;
        if t > exit {
            return None;
        }
    }
    None
}

fn torus_normal(p: DVec3, ring: f64) -> DVec3 {
    let radial = DVec3::new(p.x, 0.0, p.z);
    let centre = if radial.length_squared() > 0.0 {
        radial.normalize() * ring
    } else {
        DVec3::ZERO
    };
    (p - centre).normalize()
}

/// Rays through pixel centres, from the camera's parameters in `f64`.
#[derive(Debug, Clone, Copy)]
pub struct Rays {
    inverse: DMat4,
    width: u32,
    height: u32,
}

impl Rays {
    /// The rays of a `width` × `height` image seen by `camera`.
    pub fn new(camera: &Camera, width: u32, height: u32) -> Rays {
        let aspect = f64::from(width) / f64::from(height);
        let view = DMat4::look_at_rh(
            camera.eye.as_dvec3(),
            camera.target.as_dvec3(),
            camera.up.as_dvec3(),
        );
        let projection = DMat4::perspective_rh_gl(
            f64::from(camera.fov_y_degrees).to_radians(),
            aspect,
            f64::from(camera.near),
            f64::from(camera.far),
        );
        Rays {
            inverse: (projection * view).inverse(),
            width,
            height,
        }
    }

    /// The ray through window point (`x`, `y`) in pixels: it starts on the
    /// near plane, so only what the camera can see is hit.
    pub fn through(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let ndc_x = 2.0 * x / f64::from(self.width) - 1.0;
        let ndc_y = 1.0 - 2.0 * y / f64::from(self.height);
        let unproject = |z: f64| {
            let p = self.inverse * DVec4::new(ndc_x, ndc_y, z, 1.0);
            p.truncate() / p.w
        };
        let near = unproject(-1.0);
        let far = unproject(1.0);
        (near, (far - near).normalize())
    }
}

/// The exact surface drawn per pixel: where it is hit and the light there.
#[derive(Debug, Clone, PartialEq)]
pub struct ExactImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per pixel, row by row: the hit and its light (unclamped), or `None`.
    pub pixels: Vec<Option<(SurfaceHit, Rgb)>>,
}

impl ExactImage {
    /// The surface seen through each pixel centre of a `options.width` ×
    /// `options.height` frame of `scene`, lit with the full model.
    pub fn render(
        surface: &Surface,
        scene: &Scene,
        options: &shadelab_core::RenderOptions,
    ) -> ExactImage {
        let (w, h) = (options.width, options.height);
        let rays = Rays::new(&scene.camera, w, h);
        let lighting = lighting_of(scene, options);
        let pixels = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| exact_pixel(surface, &rays, &lighting, i, j))
            .collect();
        ExactImage {
            width: w,
            height: h,
            pixels,
        }
    }

    /// The light at pixel (`x`, `y`), if the surface is seen there.
    pub fn lit(&self, x: u32, y: u32) -> Option<Rgb> {
        self.pixels[y as usize * self.width as usize + x as usize].map(|(_, lit)| lit)
    }
}

/// The surface's light at one pixel.
pub fn exact_pixel(
    surface: &Surface,
    rays: &Rays,
    lighting: &Lighting,
    x: u32,
    y: u32,
) -> Option<(SurfaceHit, Rgb)> {
    let (origin, dir) = rays.through(f64::from(x) + 0.5, f64::from(y) + 0.5);
    let hit = surface.intersect(origin, dir)?;
    let lit = lighting.eval(
        hit.point.as_vec3(),
        hit.normal.as_vec3().normalize(),
        Terms::Full,
    );
    Some((hit, lit))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(surface: Surface, inside: impl Fn(DVec3) -> f64) {
        // Rays from outside towards random points near the origin.
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let mut hits = 0;
        for _ in 0..2000 {
            let origin = DVec3::new(next(), next(), next()).normalize() * 5.0;
            let aim = DVec3::new(next(), next(), next()) * 0.8;
            if let Some(hit) = surface.intersect(origin, aim - origin) {
                hits += 1;
                assert!(inside(hit.point).abs() < 1e-7, "{surface:?}: {hit:?}");
                assert!((hit.normal.length() - 1.0).abs() < 1e-9);
                // The normal faces the ray's origin side.
                assert!(hit.normal.dot(origin - hit.point) > -1e-9, "{hit:?}");
                // Nothing nearer: march the segment before the hit.
                let d = (aim - origin).normalize();
                let t_hit = (hit.point - origin).length();
                for k in 0..200 {
                    let p = origin + d * (t_hit * f64::from(k) / 200.0);
                    assert!(
                        inside(p) > -1e-9,
                        "{surface:?}: inside before the hit at {p}"
                    );
                }
            }
        }
        assert!(hits > 200, "{surface:?}: {hits} hits");
    }

    #[test]
    fn hits_lie_on_the_surfaces_with_outward_normals() {
        check(Surface::new(Shape::Sphere), |p| p.length() - 1.0);
        check(
            Surface::new(Shape::Torus {
                ring: 1.0,
                tube: 0.4,
            }),
            |p| DVec2::new(DVec2::new(p.x, p.z).length() - 1.0, p.y).length() - 0.4,
        );
        // Signed distance-like functions: negative inside, zero on the surface.
        check(Surface::new(Shape::Cylinder), |p| {
            (DVec2::new(p.x, p.z).length() - 1.0).max(p.y.abs() - 1.0)
        });
        check(Surface::new(Shape::Cone), |p| {
            let rho = DVec2::new(p.x, p.z).length();
            // The side's implicit function scaled to a distance, and the base.
            ((rho - (1.0 - p.y) / 2.0) * 2.0 / 5f64.sqrt()).max(-1.0 - p.y)
        });
    }

    /// On a fine mesh each face's normal is the exact normal near its centroid.
    #[test]
    fn exact_normals_match_fine_face_normals() {
        for (name, shape) in [
            ("sphere", Shape::Sphere),
            ("cylinder", Shape::Cylinder),
            ("cone", Shape::Cone),
            (
                "torus",
                Shape::Torus {
                    ring: 1.0,
                    tube: 0.4,
                },
            ),
        ] {
            let mesh = builtin_model(name, Some(128)).unwrap();
            let normals = shadelab_core::face_normals(&mesh);
            let surface = Surface::new(shape);
            for face in (0..mesh.polygon_count()).step_by(7) {
                let range = mesh.corner_range(face);
                let centroid = range
                    .clone()
                    .map(|c| mesh.positions()[mesh.corners()[c] as usize].as_dvec3())
                    .sum::<DVec3>()
                    / range.len() as f64;
                let n = normals[face].unwrap().as_dvec3();
                let hit = surface.intersect(centroid + n * 0.5, -n).unwrap();
                assert!(
                    hit.normal.dot(n) > 0.999,
                    "{name} face {face}: {} vs {n}",
                    hit.normal
                );
            }
        }
    }

    #[test]
    fn placement_matches_the_normalized_mesh() {
        for name in EXACT_MODELS {
            for detail in [5, 12] {
                let raw = builtin_model(name, Some(detail)).unwrap();
                let normalized = raw.clone().normalized();
                let s = Surface::for_builtin(name, Some(detail), true).unwrap();
                for (p, q) in raw.positions().iter().zip(normalized.positions()) {
                    let placed = (p.as_dvec3() - s.centre) * s.scale;
                    assert!((placed - q.as_dvec3()).length() < 1e-6, "{name} {detail}");
                }
            }
        }
        assert!(Surface::for_builtin("teapot", None, true).is_none());
    }
}
