//! shadelab's teaching instruments: the pictures and numbers that show
//! *why* flat, Gouraud and Phong shading differ. No I/O; the same functions
//! serve the command line and, through WebAssembly, the viewer.
//!
//! | instrument | module | entry point |
//! |---|---|---|
//! | pixel inspector | `inspect`, `inspect_text` | [`inspect()`], [`inspection_text`] ([`inspection_header`], [`method_inspection_text`]) |
//! | scanline profile (Mach bands) | `profile` | [`profile()`] |
//! | exact surfaces | `exact` | [`Surface`], [`ExactImage`] |
//! | error maps, accuracy | `errors` | [`error_maps`], [`heat_scale`], [`accuracy`] |
//! | overlays | `overlay` | [`draw_overlays`] |
//! | interpolation on polygons | `quad` | [`quad_study`] |
//! | cost | `cost` | [`measure_cost`] |
//! | texts in four languages | `texts` | [`Texts`], [`Lang`] |
//!
//! For a viewer: a click on pixel (x, y) of a panel is
//! [`inspect()`]`(scene, options, x, y, &[shading])`, shown with
//! [`inspection_text`] or from its fields; a chosen row is
//! [`profile()`]`(scene, options, ProfileLine::Row(y), surface)`, whose curves
//! are plotted as they are; [`error_maps`] gives each panel's
//! [`ErrorMap::heat_image`] with [`heat_bar`] as the scale; overlays are
//! [`draw_overlays`] on a rendered image; [`measure_cost`] takes the page's
//! clock; one panel's account of a pixel is [`method_inspection_text`] under
//! the shared [`inspection_header`]; the texts are [`Texts::new`]`(`[`Lang::negotiate`]`(navigator
//! languages))`. The exact surface of a built-in model is
//! [`Surface::for_builtin`].
//!
//! The inspector and the profiles read the renderer's own numbers through
//! [`shadelab_core::probe`]; the modes of old hardware they explain
//! (fixed-point stepping, the indexed palette) are render options of the
//! scanline rasterizer.
#![warn(missing_docs)]

mod cost;
mod errors;
mod exact;
mod inspect;
mod inspect_text;
mod overlay;
mod profile;
mod quad;
mod texts;

pub use cost::{measure_cost, Cost};
pub use errors::{
    accuracy, drawn_mask, error_maps, exact_image, heat_bar, heat_color, heat_scale, image_diff,
    AccuracyRow, ErrorMap, ImageDiff, MethodErrors, SILHOUETTE,
};
pub use exact::{
    exact_pixel, normalization, ExactImage, Rays, Shape, Surface, SurfaceHit, EXACT_MODELS,
};
pub use inspect::{
    inspect, lerp_attributes, CornerView, EdgeView, Inspection, MethodView, SpanView, WalkedVertex,
};
pub use inspect_text::{inspection_header, inspection_text, method_inspection_text};
pub use overlay::{
    draw_overlays, Canvas, Overlays, Projector, WindowPoint, FACE_NORMAL, LIGHT, NORMAL_LENGTH,
    VERTEX_NORMAL, WIREFRAME,
};
pub use profile::{intensity, profile, Curve, CurveKind, Profile, ProfileLine};
pub use quad::{quad_scene, quad_study, QuadSample};
pub use texts::{placeholders, Lang, Texts};

use shadelab_core::{Lighting, RenderOptions, Scene};

/// The reflection model of a frame, as the renderer sets it up.
pub fn lighting_of(scene: &Scene, options: &RenderOptions) -> Lighting {
    Lighting {
        ambient: scene.ambient,
        lights: scene.lights.clone(),
        material: scene.material,
        eye: scene.camera.eye,
        specular: options.specular,
    }
}
