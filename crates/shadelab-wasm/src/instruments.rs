//! The teaching instruments as requests to a panel's engine: each takes a
//! small JSON request and answers in JSON, with any pictures as RGBA images
//! beside the answer ([`Engine::images`]). The work is the `shadelab-lab`
//! crate's, the same functions `shadelab explain`, `profile`, `errors`,
//! `quad` and `--overlay` call, on the scene the engine keeps, so a panel's
//! instruments and the command line given the same scene file agree.
//!
//! Requests about "the frame" (overlays, error map, heat) act on the last
//! frame the engine rendered; the others name their scene, which the
//! engine reads with its model cache.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use shadelab_core::{Image, Rgb8, Shading};
use shadelab_lab::{
    draw_overlays, drawn_mask, exact_image, heat_bar, heat_scale, inspect, inspection_header,
    method_inspection_text, profile, quad_study, CurveKind, ErrorMap, ExactImage, Lang, Overlays,
    ProfileLine, Surface, Texts, EXACT_MODELS,
};

use crate::engine::{rgba_of, Engine, EngineError, Loaded};

/// Largest quad study image, pixels a side.
pub const MAX_QUAD_SIZE: u32 = 512;

fn bad(message: impl Into<String>) -> EngineError {
    EngineError(message.into())
}

fn lang_of(code: &str) -> Result<Lang, EngineError> {
    if code.is_empty() {
        return Ok(Lang::En);
    }
    Lang::from_tag(code).ok_or_else(|| {
        bad(format!(
            "unknown language {code:?} (expected one of en, ru, sk, cs)"
        ))
    })
}

fn overlays_of(list: &str) -> Result<Overlays, EngineError> {
    Overlays::parse(list).map_err(bad)
}

/// What an image beside an answer is.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImageInfo {
    /// What it shows.
    pub name: &'static str,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Engine {
    fn set_images(&mut self, images: &[(&'static str, &Image)]) -> Vec<ImageInfo> {
        self.images.resize_with(images.len(), Vec::new);
        images
            .iter()
            .zip(&mut self.images)
            .map(|((name, image), out)| {
                rgba_of(image, out);
                ImageInfo {
                    name,
                    width: image.width(),
                    height: image.height(),
                }
            })
            .collect()
    }

    /// The last frame's scene, read again if a request since named another.
    fn frame_scene(&mut self) -> Result<Loaded<'_>, EngineError> {
        if self.image.is_none() {
            return Err(bad("no frame has been rendered yet"));
        }
        let toml = std::mem::take(&mut self.frame_toml);
        let ok = self.load_scene(&toml).map(|_| ());
        self.frame_toml = toml;
        ok?;
        self.load_scene_kept()
    }
}

// ------------------------------------------------------------ overlays

/// A request to draw overlays on the last frame.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OverlaysRequest {
    /// Comma-separated: `wireframe`, `face-normals`, `vertex-normals`, `light` (or `all`).
    pub overlays: String,
}

impl Engine {
    /// Draws the overlays over the last frame, as `shadelab render --overlay` does;
    /// [`Engine::rgba`] then holds the result.
    ///
    /// # Errors
    /// An unknown overlay's name, or no frame yet.
    pub fn overlays(&mut self, request: &OverlaysRequest) -> Result<(), EngineError> {
        let overlays = overlays_of(&request.overlays)?;
        let Loaded { options, .. } = self.frame_scene()?;
        let scene = &self.prepared.as_ref().expect("frame_scene read it").scene;
        let image = self.image.as_mut().expect("frame_scene checked");
        draw_overlays(image, scene, &options, overlays).map_err(|e| bad(e.to_string()))?;
        rgba_of(image, &mut self.rgba);
        Ok(())
    }
}

// ------------------------------------------------------------ error map

/// The last error map, kept to colour it again on another scale.
#[derive(Debug)]
pub struct KeptErrors {
    map: ErrorMap,
    exact: ExactImage,
    background: Rgb8,
}

/// A request for the last frame's error against the exact surface.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErrorsRequest {
    /// The error shown brightest; none: a round number above the largest error.
    #[serde(default)]
    pub scale: Option<f32>,
    /// Also answer with the exact surface's image.
    #[serde(default)]
    pub exact: bool,
    /// Overlays to draw over the heat map (see [`OverlaysRequest`]).
    #[serde(default)]
    pub overlays: String,
    /// Also answer with the colour scale as a vertical bar `[width, height]`,
    /// its top the scale's brightest colour ([`heat_bar`]).
    #[serde(default)]
    pub bar: Option<[u32; 2]>,
}

/// The error map of one frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorsAnswer {
    /// Mean error over the pixels both the mesh and the surface cover, 0–255 units.
    pub mean: f64,
    /// The largest error.
    pub max: f32,
    /// Where it is.
    pub max_at: Option<[u32; 2]>,
    /// Pixels compared.
    pub compared: usize,
    /// Pixels only the mesh covers.
    pub mesh_only: usize,
    /// Pixels only the exact surface covers.
    pub surface_only: usize,
    /// The scale the heat image uses (its brightest colour), 0–255 units.
    pub scale: f32,
    /// The images: `heat`, then `exact` and `bar` when asked for.
    pub images: Vec<ImageInfo>,
}

/// A request to colour the last error map on another scale.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeatRequest {
    /// The error shown brightest, 0–255 units.
    pub scale: f32,
    /// Overlays to draw over it.
    #[serde(default)]
    pub overlays: String,
}

/// A heat image.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeatAnswer {
    /// The scale it uses.
    pub scale: f32,
    /// The image: `heat`.
    pub images: Vec<ImageInfo>,
}

fn check_scale(scale: f32) -> Result<f32, EngineError> {
    if scale.is_finite() && scale > 0.0 {
        Ok(scale)
    } else {
        Err(bad(format!(
            "the error scale must be a positive number, got {scale}"
        )))
    }
}

impl Engine {
    /// The exact surface of the last frame's model and each pixel's error
    /// against it, as `shadelab errors` computes them; the images are the
    /// heat map (and the exact surface when asked for).
    ///
    /// # Errors
    /// The model has no exact surface (only the built-in sphere, torus,
    /// cylinder and cone have one), a bad scale or overlay, or no frame yet.
    pub fn errors(&mut self, request: &ErrorsRequest) -> Result<ErrorsAnswer, EngineError> {
        if let Some(s) = request.scale {
            check_scale(s)?;
        }
        let overlays = overlays_of(&request.overlays)?;
        let Loaded { file, options, .. } = self.frame_scene()?;
        let source = file.model.source.as_deref().unwrap_or("teapot").to_owned();
        let surface = Surface::for_builtin(&source, file.model.detail, file.camera.is_none())
            .ok_or_else(|| {
                bad(format!(
                    "model {source:?} has no exact surface; the exact surface is known for the built-in {}",
                    EXACT_MODELS.join(", ")
                ))
            })?;
        let scene = self.prepared_scene();
        let exact = ExactImage::render(&surface, scene, &options);
        let drawn = drawn_mask(scene, &options).map_err(|e| bad(e.to_string()))?;
        let image = self.image.as_ref().expect("frame_scene checked");
        let map = ErrorMap::new(image, &exact, &drawn);
        let scale = request.scale.unwrap_or_else(|| heat_scale(map.max));
        self.errors = Some(KeptErrors {
            map,
            exact,
            background: options.background,
        });
        let heat = self.heat_image(scale, overlays)?;
        let kept = self.errors.as_ref().expect("just kept");
        let exact_pixels = request
            .exact
            .then(|| exact_image(&kept.exact, kept.background));
        let bar = match request.bar {
            Some([w, h]) if (1..=64).contains(&w) && (1..=1024).contains(&h) => {
                Some(heat_bar(w, h))
            }
            Some([w, h]) => {
                return Err(bad(format!("a colour bar of {w}x{h} pixels is not drawn")))
            }
            None => None,
        };
        let mut images = vec![("heat", &heat)];
        if let Some(e) = &exact_pixels {
            images.push(("exact", e));
        }
        if let Some(b) = &bar {
            images.push(("bar", b));
        }
        let map = &self.errors.as_ref().expect("just kept").map;
        let answer = ErrorsAnswer {
            mean: map.mean,
            max: map.max,
            max_at: map.max_at.map(|(x, y)| [x, y]),
            compared: map.compared,
            mesh_only: map.mesh_only,
            surface_only: map.surface_only,
            scale,
            images: Vec::new(),
        };
        Ok(ErrorsAnswer {
            images: self.set_images(&images),
            ..answer
        })
    }

    /// The last error map coloured on `scale`.
    ///
    /// # Errors
    /// No error map yet, a bad scale or overlay.
    pub fn heat(&mut self, request: &HeatRequest) -> Result<HeatAnswer, EngineError> {
        let scale = check_scale(request.scale)?;
        let overlays = overlays_of(&request.overlays)?;
        if self.errors.is_none() {
            return Err(bad("no error map has been computed for this frame"));
        }
        let heat = self.heat_image(scale, overlays)?;
        Ok(HeatAnswer {
            scale,
            images: self.set_images(&[("heat", &heat)]),
        })
    }

    fn heat_image(&mut self, scale: f32, overlays: Overlays) -> Result<Image, EngineError> {
        let kept = self.errors.as_ref().expect("callers check");
        let mut heat = kept.map.heat_image(scale, &kept.exact, kept.background);
        if overlays.any() {
            let Loaded { options, .. } = self.frame_scene()?;
            draw_overlays(&mut heat, self.prepared_scene(), &options, overlays)
                .map_err(|e| bad(e.to_string()))?;
        }
        Ok(heat)
    }
}

// ------------------------------------------------------------ inspector

/// A request to inspect one pixel.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InspectRequest {
    /// The scene, as for a frame.
    pub scene: String,
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// `en`, `ru`, `sk` or `cs` (default English).
    #[serde(default)]
    pub lang: String,
    /// The methods to inspect (`flat`, `gouraud`, `phong`); none: the scene's own.
    #[serde(default)]
    pub methods: Option<Vec<String>>,
}

/// The inspector's account of one pixel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InspectAnswer {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// The lines common to every method ([`inspection_header`]).
    pub header: String,
    /// Each method's account.
    pub methods: Vec<MethodAnswer>,
}

/// One method's account of the pixel: its text and where to mark it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodAnswer {
    /// `flat`, `gouraud` or `phong`.
    pub method: &'static str,
    /// The account as text ([`method_inspection_text`]).
    pub text: String,
    /// The colour written.
    pub color: [u8; 3],
    /// Whether a polygon covers the pixel.
    pub covered: bool,
    /// The mesh polygon.
    pub face: Option<usize>,
    /// The convex polygon the walk went round (the polygon or a triangle
    /// of its fan), window pixels.
    pub walked: Vec<[f64; 2]>,
    /// The scanline's row.
    pub row: Option<u32>,
    /// P, where the scanline enters the walked polygon.
    pub p: Option<[f64; 2]>,
    /// Q, where it leaves.
    pub q: Option<[f64; 2]>,
    /// u = |PO| / |PQ|.
    pub u: Option<f64>,
}

fn shading_of(name: &str) -> Result<Shading, EngineError> {
    name.parse()
        .map_err(|e: shadelab_core::UnknownChoice| bad(e.to_string()))
}

impl Engine {
    /// What each method did at pixel (x, y), as `shadelab explain` tells it.
    ///
    /// # Errors
    /// The scene's error, a pixel outside the image, an unknown method or language.
    pub fn inspect(&mut self, request: &InspectRequest) -> Result<InspectAnswer, EngineError> {
        let texts = Texts::new(lang_of(&request.lang)?);
        let Loaded { options, .. } = self.load_scene(&request.scene)?;
        let (x, y) = (request.x, request.y);
        if x >= options.width || y >= options.height {
            return Err(bad(format!(
                "pixel ({x}, {y}) is outside the {}x{} image",
                options.width, options.height
            )));
        }
        let methods = match &request.methods {
            Some(names) => names
                .iter()
                .map(|n| shading_of(n))
                .collect::<Result<Vec<_>, _>>()?,
            None => vec![options.shading],
        };
        let inspection = inspect(self.prepared_scene(), &options, x, y, &methods)
            .map_err(|e| bad(e.to_string()))?;
        let methods = inspection
            .methods
            .iter()
            .map(|m| {
                let span = m.span.as_ref();
                let yc = span.map(|s| f64::from(s.row) + 0.5);
                MethodAnswer {
                    method: m.shading.name(),
                    text: method_inspection_text(m, &inspection, &texts),
                    color: m.color.0,
                    covered: m.fragment.is_some(),
                    face: m.fragment.as_ref().map(|f| f.face),
                    walked: m.walked.iter().map(|v| [v.window.0, v.window.1]).collect(),
                    row: span.map(|s| s.row),
                    p: span.zip(yc).map(|(s, yc)| [s.p.x, yc]),
                    q: span.zip(yc).map(|(s, yc)| [s.q.x, yc]),
                    u: span.map(|s| s.u),
                }
            })
            .collect();
        Ok(InspectAnswer {
            x,
            y,
            header: inspection_header(&inspection, &texts),
            methods,
        })
    }
}

// ------------------------------------------------------------ profile

/// A request for a scanline profile: a row, or a line between two points.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileRequest {
    /// The scene, as for a frame (its method does not matter).
    pub scene: String,
    /// A whole row.
    #[serde(default)]
    pub row: Option<u32>,
    /// Or a segment `[x0, y0, x1, y1]`, window pixels.
    #[serde(default)]
    pub line: Option<[f64; 4]>,
}

/// One curve of a profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CurveAnswer {
    /// `flat`, `gouraud`, `phong` or `exact`.
    pub kind: &'static str,
    /// Intensity (0–255, unrounded) per sample, `null` where nothing is drawn.
    pub values: Vec<Option<f64>>,
    /// Its change between samples k and k + 1.
    pub derivative: Vec<Option<f64>>,
    /// Gaps k where the line crosses an edge of the piece walked (polygon or fan triangle).
    pub edges: Vec<usize>,
    /// Gaps k where the mesh polygon changes.
    pub polygon_edges: Vec<usize>,
}

/// A profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProfileAnswer {
    /// The pixels sampled, in order.
    pub pixels: Vec<[u32; 2]>,
    /// Flat, Gouraud, Phong, then the exact surface when the model has one.
    pub curves: Vec<CurveAnswer>,
}

impl Engine {
    /// The intensity along a row or line for each method and the exact
    /// surface, as `shadelab profile` computes it.
    ///
    /// # Errors
    /// The scene's error, a row outside the image, a line that is not
    /// finite, or neither or both of row and line.
    pub fn profile(&mut self, request: &ProfileRequest) -> Result<ProfileAnswer, EngineError> {
        let Loaded { file, options, .. } = self.load_scene(&request.scene)?;
        let line = match (request.row, request.line) {
            (Some(row), None) if row < options.height => ProfileLine::Row(row),
            (Some(row), None) => {
                return Err(bad(format!(
                    "row {row} is outside the {}x{} image",
                    options.width, options.height
                )))
            }
            (None, Some([x0, y0, x1, y1])) => {
                if ![x0, y0, x1, y1]
                    .iter()
                    .all(|v| v.is_finite() && v.abs() <= 1e5)
                {
                    return Err(bad(format!(
                        "the line ({x0}, {y0})–({x1}, {y1}) is not a line in the image"
                    )));
                }
                ProfileLine::Segment {
                    from: (x0, y0),
                    to: (x1, y1),
                }
            }
            _ => return Err(bad("a profile takes either a row or a line")),
        };
        let source = file.model.source.as_deref().unwrap_or("teapot").to_owned();
        let surface = Surface::for_builtin(&source, file.model.detail, file.camera.is_none());
        let p = profile(self.prepared_scene(), &options, line, surface.as_ref())
            .map_err(|e| bad(e.to_string()))?;
        Ok(ProfileAnswer {
            pixels: p.pixels.iter().map(|&(x, y)| [x, y]).collect(),
            curves: p
                .curves
                .iter()
                .map(|c| CurveAnswer {
                    kind: match c.kind {
                        CurveKind::Method(s) => s.name(),
                        CurveKind::Exact => "exact",
                    },
                    values: c.values.clone(),
                    derivative: c.derivative.clone(),
                    edges: c.edges(),
                    polygon_edges: c.polygon_edges(),
                })
                .collect(),
        })
    }
}

// ------------------------------------------------------------ quad study

/// A request for the quad study.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuadRequest {
    /// The turn to draw, degrees.
    pub angle: f32,
    /// Image size, pixels a side (odd puts a pixel centre on the quad's centre).
    pub size: u32,
    /// Turns at which to report the centre's value.
    #[serde(default)]
    pub curve: Vec<f32>,
}

/// The quad at one turn, whole and as triangles, and the centre's value at others.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct QuadAnswer {
    /// The turn drawn.
    pub angle: f32,
    /// Intensity (0–1) at the centre, walked whole.
    pub whole_centre: f32,
    /// As two triangles.
    pub fans_centre: f32,
    /// `[angle, whole, fans]` at each turn asked for.
    pub curve: Vec<[f32; 3]>,
    /// The images: `whole`, `fans`.
    pub images: Vec<ImageInfo>,
}

impl Engine {
    /// A square with one bright vertex turned by `angle`, walked whole and
    /// as two triangles, as `shadelab quad` draws it.
    ///
    /// # Errors
    /// A size outside 3..=[`MAX_QUAD_SIZE`], a turn that is not finite.
    pub fn quad(&mut self, request: &QuadRequest) -> Result<QuadAnswer, EngineError> {
        if !(3..=MAX_QUAD_SIZE).contains(&request.size) {
            return Err(bad(format!(
                "the quad study is drawn 3 to {MAX_QUAD_SIZE} pixels a side, not {}",
                request.size
            )));
        }
        if !request.angle.is_finite() || request.curve.iter().any(|a| !a.is_finite()) {
            return Err(bad("the quad's turn must be a finite number of degrees"));
        }
        if request.curve.len() > 361 {
            return Err(bad("at most 361 turns in the quad's curve"));
        }
        let sample = quad_study(&[request.angle], request.size)
            .map_err(|e| bad(e.to_string()))?
            .remove(0);
        // The centre's value does not depend on the size: a small image will do.
        let curve = quad_study(&request.curve, 33)
            .map_err(|e| bad(e.to_string()))?
            .iter()
            .map(|s| [s.angle_degrees, s.whole_centre, s.fans_centre])
            .collect();
        let images = self.set_images(&[("whole", &sample.whole), ("fans", &sample.fans)]);
        Ok(QuadAnswer {
            angle: request.angle,
            whole_centre: sample.whole_centre,
            fans_centre: sample.fans_centre,
            curve,
            images,
        })
    }
}

// ------------------------------------------------------------ texts

/// A request for the instruments' texts in one language.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextsRequest {
    /// `en`, `ru`, `sk` or `cs`.
    pub lang: String,
}

impl Engine {
    /// Every text of the instruments in one language, by id
    /// (`about.gouraud`, `method.phong`, …), from `shadelab-lab`'s files.
    ///
    /// # Errors
    /// An unknown language.
    pub fn texts(request: &TextsRequest) -> Result<BTreeMap<String, String>, EngineError> {
        let texts = Texts::new(lang_of(&request.lang)?);
        Ok(texts
            .entries()
            .map(|(k, v)| (k.to_owned(), v.to_owned()))
            .collect())
    }
}
