//! Overlays drawn onto a rendered image: the wireframe of the polygons
//! facing the viewer, face normals from their centroids, vertex normals
//! from their corners (short segments, a fixed fraction of the model's
//! size), and each light: a point light as a sun at its projected position
//! (hollow when the model hides it, an arrow at the border when it is out
//! of view), a directional light as an arrow along its projected direction.
//!
//! Depth is respected: a segment's pixels are drawn where they are not
//! behind the frame's depth buffer (with a small tolerance, and the buffer's
//! largest depth over the 3×3 neighbourhood so silhouette edges survive).
//! Window depth is linear along a projected segment, so it is interpolated
//! linearly between the ends, as a rasterizer does.

use glam::{Mat4, Vec3, Vec4};
use shadelab_core::{
    depth_buffer, face_normals, Image, LightKind, RenderError, RenderOptions, Rgb8, Scene,
};

/// Which overlays to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Overlays {
    /// Edges of the polygons facing the viewer.
    pub wireframe: bool,
    /// A segment along each face normal, from the centroid.
    pub face_normals: bool,
    /// A segment along each corner's vertex normal.
    pub vertex_normals: bool,
    /// The lights.
    pub light: bool,
}

impl Overlays {
    /// The names accepted by [`Overlays::parse`].
    pub const NAMES: [&'static str; 4] = ["wireframe", "face-normals", "vertex-normals", "light"];

    /// Parses a comma-separated list of [`Overlays::NAMES`] (or `all`).
    ///
    /// # Errors
    /// The first unknown name.
    pub fn parse(list: &str) -> Result<Overlays, String> {
        let mut o = Overlays::default();
        for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            match name {
                "wireframe" => o.wireframe = true,
                "face-normals" => o.face_normals = true,
                "vertex-normals" => o.vertex_normals = true,
                "light" | "lights" => o.light = true,
                "all" => {
                    o = Overlays {
                        wireframe: true,
                        face_normals: true,
                        vertex_normals: true,
                        light: true,
                    }
                }
                other => {
                    return Err(format!(
                        "unknown overlay {other:?} (expected {} or all)",
                        Overlays::NAMES.join(", ")
                    ))
                }
            }
        }
        Ok(o)
    }

    /// Whether any overlay is on.
    pub fn any(&self) -> bool {
        self.wireframe || self.face_normals || self.vertex_normals || self.light
    }
}

/// Overlay colours.
pub const WIREFRAME: Rgb8 = Rgb8::new(255, 230, 90);
/// Face normals.
pub const FACE_NORMAL: Rgb8 = Rgb8::new(80, 220, 255);
/// Vertex normals.
pub const VERTEX_NORMAL: Rgb8 = Rgb8::new(120, 255, 120);
/// Lights.
pub const LIGHT: Rgb8 = Rgb8::new(255, 255, 255);

/// Normal segments are this fraction of the model's bounding-box diagonal.
pub const NORMAL_LENGTH: f32 = 0.06;

/// Window depth tolerance for overlay visibility.
const DEPTH_TOLERANCE: f32 = 2e-3;

/// Projects world points to the window of a frame.
#[derive(Debug, Clone, Copy)]
pub struct Projector {
    view_projection: Mat4,
    width: f32,
    height: f32,
}

/// A point in the window: pixels and window depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowPoint {
    /// x, pixels.
    pub x: f32,
    /// y, pixels, down.
    pub y: f32,
    /// Window depth, 0 at the near plane and 1 at the far one.
    pub depth: f32,
}

impl Projector {
    /// The projection of `scene`'s camera into a frame of `options`' size.
    pub fn new(scene: &Scene, options: &RenderOptions) -> Projector {
        let aspect = options.width as f32 / options.height as f32;
        Projector {
            view_projection: scene.camera.projection(aspect) * scene.camera.view(),
            width: options.width as f32,
            height: options.height as f32,
        }
    }

    fn clip(&self, p: Vec3) -> Vec4 {
        self.view_projection * p.extend(1.0)
    }

    fn window(&self, c: Vec4) -> WindowPoint {
        WindowPoint {
            x: (c.x / c.w + 1.0) * 0.5 * self.width,
            y: (1.0 - c.y / c.w) * 0.5 * self.height,
            depth: (c.z / c.w + 1.0) * 0.5,
        }
    }

    /// Where `p` lands, if it is in front of the near plane.
    pub fn project(&self, p: Vec3) -> Option<WindowPoint> {
        let c = self.clip(p);
        (c.z >= -c.w && c.w > 0.0).then(|| self.window(c))
    }

    /// The part of segment `a`–`b` in front of the near plane, projected.
    pub fn segment(&self, a: Vec3, b: Vec3) -> Option<(WindowPoint, WindowPoint)> {
        let (mut ca, mut cb) = (self.clip(a), self.clip(b));
        let (da, db) = (ca.z + ca.w, cb.z + cb.w);
        if da < 0.0 && db < 0.0 {
            return None;
        }
        if da < 0.0 {
            ca = ca + (cb - ca) * (da / (da - db));
        } else if db < 0.0 {
            cb = cb + (ca - cb) * (db / (db - da));
        }
        (ca.w > 0.0 && cb.w > 0.0).then(|| (self.window(ca), self.window(cb)))
    }
}

/// Draws on an image, testing depth against a frame's depth buffer.
pub struct Canvas<'a> {
    image: &'a mut Image,
    depth: Option<&'a [f32]>,
}

impl<'a> Canvas<'a> {
    /// A canvas over `image`; with `depth`, strokes are hidden behind it.
    pub fn new(image: &'a mut Image, depth: Option<&'a [f32]>) -> Canvas<'a> {
        Canvas { image, depth }
    }

    /// Whether window depth `z` at pixel (`x`, `y`) is in front of the frame.
    pub fn visible(&self, x: i64, y: i64, z: f32) -> bool {
        let Some(depth) = self.depth else {
            return true;
        };
        let (w, h) = (self.image.width() as i64, self.image.height() as i64);
        let mut farthest = f32::NEG_INFINITY;
        for dy in -1..=1 {
            for dx in -1..=1 {
                let (px, py) = (x + dx, y + dy);
                if px >= 0 && py >= 0 && px < w && py < h {
                    farthest = farthest.max(depth[(py * w + px) as usize]);
                }
            }
        }
        z <= farthest + DEPTH_TOLERANCE
    }

    fn plot(&mut self, x: i64, y: i64, color: Rgb8) {
        if x >= 0 && y >= 0 {
            self.image.set_pixel(x as u32, y as u32, color);
        }
    }

    /// A one-pixel segment between window points, each pixel depth-tested.
    pub fn line(&mut self, a: WindowPoint, b: WindowPoint, color: Rgb8) {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let steps = dx.abs().max(dy.abs()).ceil().clamp(1.0, 65536.0) as i64;
        let mut last = None;
        for k in 0..=steps {
            let f = k as f32 / steps as f32;
            let (x, y) = ((a.x + dx * f).floor() as i64, (a.y + dy * f).floor() as i64);
            if last == Some((x, y)) {
                continue;
            }
            last = Some((x, y));
            let z = a.depth + (b.depth - a.depth) * f;
            if self.visible(x, y, z) {
                self.plot(x, y, color);
            }
        }
    }

    /// A disc (filled) or ring of `radius` pixels at window point `c`, not depth-tested.
    pub fn disc(&mut self, c: WindowPoint, radius: f32, filled: bool, color: Rgb8) {
        let r = radius.ceil() as i64 + 1;
        let (cx, cy) = (c.x.floor() as i64, c.y.floor() as i64);
        for y in cy - r..=cy + r {
            for x in cx - r..=cx + r {
                let d = ((x as f32 + 0.5 - c.x).powi(2) + (y as f32 + 0.5 - c.y).powi(2)).sqrt();
                if d <= radius && (filled || d >= radius - 1.2) {
                    self.plot(x, y, color);
                }
            }
        }
    }

    /// A segment not depth-tested (markers).
    pub fn stroke(&mut self, a: (f32, f32), b: (f32, f32), color: Rgb8) {
        let wp = |p: (f32, f32)| WindowPoint {
            x: p.0,
            y: p.1,
            depth: 0.0,
        };
        let depth = self.depth.take();
        self.line(wp(a), wp(b), color);
        self.depth = depth;
    }
}

/// Draws `overlays` of `scene` onto `image`, a frame rendered with `options`.
///
/// # Errors
/// As [`shadelab_core::render`] (the depth buffer is rendered here).
pub fn draw_overlays(
    image: &mut Image,
    scene: &Scene,
    options: &RenderOptions,
    overlays: Overlays,
) -> Result<(), RenderError> {
    if !overlays.any() {
        return Ok(());
    }
    let depth = depth_buffer(scene, options)?;
    let projector = Projector::new(scene, options);
    let mut canvas = Canvas::new(image, Some(&depth));
    let mesh = &scene.mesh;
    let faces = face_normals(mesh);
    let (lo, hi) = mesh.bounds();
    let length = (hi - lo).length() * NORMAL_LENGTH;
    let eye = scene.camera.eye;
    let position = |c: usize| mesh.positions()[mesh.corners()[c] as usize];
    for (face, normal) in faces.iter().enumerate() {
        let Some(normal) = *normal else { continue };
        let range = mesh.corner_range(face);
        let centroid = range.clone().map(position).sum::<Vec3>() / range.len() as f32;
        let front = normal.dot(eye - centroid) > 0.0;
        if !front && options.cull_backfaces {
            continue;
        }
        let sign = if front { 1.0 } else { -1.0 };
        if overlays.wireframe {
            for c in range.clone() {
                let next = if c + 1 == range.end {
                    range.start
                } else {
                    c + 1
                };
                if let Some((a, b)) = projector.segment(position(c), position(next)) {
                    canvas.line(a, b, WIREFRAME);
                }
            }
        }
        if overlays.face_normals {
            normal_segment(
                &mut canvas,
                &projector,
                centroid,
                normal * sign,
                length,
                FACE_NORMAL,
            );
        }
        if overlays.vertex_normals {
            for c in range.clone() {
                let n = scene.normals.normals[scene.normals.corner()[c] as usize] * sign;
                normal_segment(
                    &mut canvas,
                    &projector,
                    position(c),
                    n,
                    length,
                    VERTEX_NORMAL,
                );
            }
        }
    }
    if overlays.light {
        let centre = (lo + hi) * 0.5;
        for light in &scene.lights {
            draw_light(&mut canvas, &projector, light.kind, centre, options);
        }
    }
    Ok(())
}

/// A normal from `base`, drawn only when its base is visible.
fn normal_segment(
    canvas: &mut Canvas<'_>,
    projector: &Projector,
    base: Vec3,
    normal: Vec3,
    length: f32,
    color: Rgb8,
) {
    let Some((a, b)) = projector.segment(base, base + normal * length) else {
        return;
    };
    if canvas.visible(a.x.floor() as i64, a.y.floor() as i64, a.depth) {
        canvas.line(a, b, color);
    }
}

fn draw_light(
    canvas: &mut Canvas<'_>,
    projector: &Projector,
    kind: LightKind,
    centre: Vec3,
    options: &RenderOptions,
) {
    let (w, h) = (options.width as f32, options.height as f32);
    // Towards the light from the model's centre, a short step that stays
    // in front of the camera even when the light is behind it.
    let towards = match kind {
        LightKind::Point { position } => {
            if let Some(p) = projector.project(position) {
                if p.x >= 0.0 && p.y >= 0.0 && p.x < w && p.y < h {
                    let seen = canvas.visible(p.x.floor() as i64, p.y.floor() as i64, p.depth);
                    sun(canvas, (p.x, p.y), seen);
                    return;
                }
            }
            (position - centre).normalize_or_zero()
        }
        LightKind::Directional { direction } => -direction.normalize_or_zero(),
    };
    let (Some(c), Some(to)) = (
        projector.project(centre),
        projector.project(centre + towards * 0.05),
    ) else {
        return;
    };
    border_arrow(canvas, (c.x, c.y), (to.x - c.x, to.y - c.y), w, h);
}

/// A sun: a disc with eight rays; hollow when hidden.
fn sun(canvas: &mut Canvas<'_>, at: (f32, f32), seen: bool) {
    let c = WindowPoint {
        x: at.0,
        y: at.1,
        depth: 0.0,
    };
    canvas.disc(c, 5.0, seen, LIGHT);
    for k in 0..8 {
        let a = k as f32 * std::f32::consts::FRAC_PI_4;
        let (s, co) = a.sin_cos();
        canvas.stroke(
            (at.0 + 8.0 * co, at.1 + 8.0 * s),
            (at.0 + 12.0 * co, at.1 + 12.0 * s),
            LIGHT,
        );
    }
}

/// A sun near the image border in direction `dir` from `from`, with an
/// arrow from it pointing back, the way its light travels.
fn border_arrow(canvas: &mut Canvas<'_>, from: (f32, f32), dir: (f32, f32), w: f32, h: f32) {
    let len = (dir.0 * dir.0 + dir.1 * dir.1).sqrt();
    if len == 0.0 || !len.is_finite() {
        return;
    }
    let d = (dir.0 / len, dir.1 / len);
    // Walk from `from` to 14 px inside the border.
    let mut t = f32::INFINITY;
    for (p, v, lo, hi) in [(from.0, d.0, 14.0, w - 14.0), (from.1, d.1, 14.0, h - 14.0)] {
        if v > 0.0 {
            t = t.min((hi - p) / v);
        } else if v < 0.0 {
            t = t.min((lo - p) / v);
        }
    }
    if !t.is_finite() || t < 0.0 {
        return;
    }
    let at = (from.0 + d.0 * t, from.1 + d.1 * t);
    sun(canvas, at, true);
    let tail = (at.0 - d.0 * 16.0, at.1 - d.1 * 16.0);
    let tip = (at.0 - d.0 * 44.0, at.1 - d.1 * 44.0);
    canvas.stroke(tail, tip, LIGHT);
    let (nx, ny) = (-d.1, d.0);
    for side in [-1.0, 1.0] {
        let wing = (
            tip.0 + d.0 * 8.0 + nx * 5.0 * side,
            tip.1 + d.1 * 8.0 + ny * 5.0 * side,
        );
        canvas.stroke(tip, wing, LIGHT);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlay_names_parse() {
        let o = Overlays::parse("wireframe, light").unwrap();
        assert!(o.wireframe && o.light && !o.face_normals && !o.vertex_normals);
        assert!(Overlays::parse("all").unwrap().vertex_normals);
        assert!(Overlays::parse("wires").is_err());
        assert!(!Overlays::parse("").unwrap().any());
    }
}
