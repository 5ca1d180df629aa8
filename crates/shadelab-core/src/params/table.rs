//! The declaration of every parameter and choice of a scene, section by
//! section, in the order the documentation lists them: the one place a
//! parameter's key, kind, range, default, unit, help, label and flag are
//! written. From it come the table ([`super::all`]), the schema's choices
//! and the scene file's sections ([`ModelSection`] … [`RenderSection`]).
//! The forms of a field are described in `declare.rs`.

use crate::color::Rgb8;
use crate::light::{LightKindName, Material, Specular, NO_ATTENUATION};
use crate::limits::{MAX_IMAGE_SIDE, MAX_SCENE_COORDINATE};
use crate::models::BUILTIN_MODELS;
use crate::normals::NormalsChoice;
use crate::palette::Palette;
use crate::scene::{Interpolation, Polygons, Rasterizer, RenderOptions, Shading};
use crate::scene::{MAX_FRACTION_BITS, MIN_FRACTION_BITS};

use super::declare::declare;
use super::{decimal, Open, Value, ATTENUATION_TERMS, MAX_ZOOM, MIN_ZOOM, RGB, XYZ};

/// A colour as a default.
fn rgb(c: Rgb8) -> Option<Value> {
    Some(Value::Three(c.0.map(f64::from)))
}

/// White, the lights' default colour.
const WHITE: Option<Value> = Some(Value::Three([255.0; 3]));

/// A number as a default.
fn number(v: f64) -> Option<Value> {
    Some(Value::Number(v))
}

/// Three numbers as a default.
fn three(v: [f64; 3]) -> Option<Value> {
    Some(Value::Three(v))
}

/// The largest detail of any built-in model.
fn max_detail() -> f64 {
    let max = BUILTIN_MODELS.iter().map(|m| m.detail_range.1).max();
    f64::from(max.unwrap_or(0))
}

/// The range of a scene's coordinates.
fn coordinate() -> f64 {
    decimal(MAX_SCENE_COORDINATE)
}

declare! {
    /// `[model]`
    [model] ModelSection {
        source: param(Text) "A built-in model's name or a mesh file (.obj, .stl, .ply, .gltf, .glb), relative to the scene file." {
            default: Some(Value::Text("teapot")),
            label: "Model",
        },
        normals: choice(NormalsChoice),
        detail: param(Integer) "Tessellation level of a built-in model, within that model's own range." {
            min: 0.0, max: max_detail(),
            absent: "the model's own",
            label: "Detail",
            flag: "detail",
        },
        crease_angle: param(Number) "No smoothing of vertex normals across edges sharper than this." {
            min: 0.0, max: 180.0, unit: "degrees",
            absent: "the model's own (none for a file)",
            label: "Crease angle",
            flag: "crease-angle",
        },
    }

    /// `[ambient]`
    [ambient] AmbientSection {
        color: param(Rgb) "Colour of the ambient light." {
            min: 0.0, max: 255.0,
            default: WHITE,
            label: "Ambient colour",
            parts: RGB,
            flag: "ambient",
        },
        intensity: param(Number) "Intensity multiplying the ambient light's colour." {
            min: 0.0, max: 100.0,
            default: number(0.2),
            label: "Ambient intensity",
            flag: "ambient-intensity",
        },
    }

    /// `[[lights]]`: one table per light.
    [lights] LightSection {
        kind: required_choice(LightKindName),
        position: param(Vec3) "Where a point light is, in world coordinates (the default light's position)." {
            min: -coordinate(), max: coordinate(),
            default: three([2.0, 2.0, 3.0]),
            label: "Position",
            parts: XYZ,
            flag: "light-pos",
        },
        direction: param(Vec3) "The direction a directional light's rays travel, not zero." {
            min: -coordinate(), max: coordinate(),
            absent: "required by a directional light",
            typical: three([-1.0, -1.0, -1.0]),
            label: "Direction",
            parts: XYZ,
        },
        color: param(Rgb) "Colour of a light." {
            min: 0.0, max: 255.0,
            default: WHITE,
            label: "Colour",
            parts: RGB,
            flag: "light-color",
        },
        intensity: param(Number) "Intensity multiplying a light's colour." {
            min: 0.0, max: 100.0,
            default: number(1.0),
            label: "Intensity",
            flag: "light-intensity",
        },
        attenuation: param(Vec3) "A point light's fall-off with distance d: its light is divided by \
                constant + linear·d + quadratic·d² (the three numbers, as OpenGL's); [1, 0, 0] is none." {
            min: 0.0, max: 1e6,
            default: three(NO_ATTENUATION.map(f64::from)),
            label: "Fall-off",
            parts: ATTENUATION_TERMS,
            flag: "light-attenuation",
        },
    }

    /// `[material]`
    [material] MaterialSection {
        ka: param(Rgb) "Ambient reflectance Ka." {
            min: 0.0, max: 255.0,
            default: rgb(Rgb8::from_rgb(Material::default().ka)),
            label: "Ka",
            parts: RGB,
            flag: "ka",
        },
        kd: param(Rgb) "Diffuse reflectance Kd." {
            min: 0.0, max: 255.0,
            default: rgb(Rgb8::from_rgb(Material::default().kd)),
            label: "Kd",
            parts: RGB,
            flag: "kd",
        },
        ks: param(Rgb) "Specular reflectance Ks." {
            min: 0.0, max: 255.0,
            default: rgb(Rgb8::from_rgb(Material::default().ks)),
            label: "Ks",
            parts: RGB,
            flag: "ks",
        },
        shininess: param(Number) "Specular exponent: the larger, the smaller and sharper the highlight." {
            min: 0.0, max: 10000.0,
            default: number(decimal(Material::default().shininess)),
            label: "Shininess",
            flag: "shininess",
        },
    }

    /// `[camera]`; a scene without it is framed by the default camera.
    [camera] CameraSection {
        eye: required(Vec3) "Where the camera is, in world coordinates." {
            min: -coordinate(), max: coordinate(),
            absent: "the camera frames the model's bounding sphere; required in [camera]",
            typical: three([0.0, 0.0, 3.0]),
            label: "Eye",
            parts: XYZ,
        },
        target: param(Vec3) "The point the camera looks at." {
            min: -coordinate(), max: coordinate(),
            default: three([0.0; 3]),
            label: "Target",
            parts: XYZ,
        },
        up: param(Vec3) "Up on the screen: any vector not along the line of sight." {
            min: -coordinate(), max: coordinate(),
            default: three([0.0, 1.0, 0.0]),
            label: "Up",
            parts: XYZ,
        },
        fov_y: param(Number) "The vertical field of view." {
            min: 0.0, max: 180.0, unit: "degrees",
            default: number(45.0),
            label: "Field of view",
            open: Open::Both,
        },
        near: param(Number) "Distance to the near clipping plane, less than far." {
            min: 0.0, max: coordinate(),
            default: number(0.1),
            label: "Near plane",
            open: Open::Min,
        },
        far: param(Number) "Distance to the far clipping plane, more than near." {
            min: 0.0, max: coordinate(),
            default: number(100.0),
            label: "Far plane",
            open: Open::Min,
        },
    }

    /// `[render]`
    [render] RenderSection {
        width: param(Integer) "Width of the image." {
            min: 1.0, max: f64::from(MAX_IMAGE_SIDE), unit: "pixels",
            default: number(f64::from(RenderOptions::default().width)),
            label: "Width",
        },
        height: param(Integer) "Height of the image." {
            min: 1.0, max: f64::from(MAX_IMAGE_SIDE), unit: "pixels",
            default: number(f64::from(RenderOptions::default().height)),
            label: "Height",
        },
        shading: choice(Shading),
        background: param(Rgb) "Colour where nothing is drawn." {
            min: 0.0, max: 255.0,
            default: rgb(RenderOptions::default().background),
            label: "Background",
            parts: RGB,
            flag: "background",
        },
        cull_backfaces: param(Bool) "Skip polygons facing away from the viewer (false: draw them lit from behind)." {
            default: Some(Value::Bool(RenderOptions::default().cull_backfaces)),
            label: "Cull back faces",
        },
        gouraud_specular: param(Bool) "Include the specular term in Gouraud shading's vertex lighting." {
            default: Some(Value::Bool(RenderOptions::default().gouraud_specular)),
            label: "Specular in Gouraud",
            flag: "gouraud-specular",
        },
        interpolation: choice(Interpolation),
        rasterizer: choice(Rasterizer),
        polygons: choice(Polygons),
        specular: choice(Specular),
        fixed_point_bits: param(Integer) "Step attributes in fixed point with this many fraction bits (scanline rasterizer)." {
            min: f64::from(MIN_FRACTION_BITS), max: f64::from(MAX_FRACTION_BITS), unit: "bits",
            absent: "floating point",
            typical: number(8.0),
            label: "Fixed-point bits",
            flag: "fixed-point",
        },
        palette_shades: param(Integer) "Draw with an indexed palette of this many shades of the material colour (scanline rasterizer)." {
            min: f64::from(Palette::MIN_SHADES), max: f64::from(Palette::ENTRIES), unit: "shades",
            absent: "true colour",
            typical: number(8.0),
            label: "Palette shades",
            flag: "palette",
        },
        palette_offset: param(Integer) "The palette entry of the darkest shade; offset + shades is at most 256." {
            min: 0.0, max: f64::from(Palette::ENTRIES - Palette::MIN_SHADES),
            default: number(0.0),
            needs: "render.palette_shades",
            label: "Palette offset",
            flag: "palette-offset",
        },
        yaw: param(Number) "Orbit the camera about its up axis." {
            min: -1e6, max: 1e6, unit: "degrees",
            default: number(0.0),
            label: "Yaw",
            flag: "yaw",
        },
        pitch: param(Number) "Orbit the camera towards its up axis; the elevation stops at ±89 degrees." {
            min: -180.0, max: 180.0, unit: "degrees",
            default: number(0.0),
            label: "Pitch",
            flag: "pitch",
        },
        zoom: param(Number) "Magnification: the field of view narrows to 2·atan(tan(fov_y/2)/zoom)." {
            min: decimal(MIN_ZOOM), max: decimal(MAX_ZOOM),
            default: number(1.0),
            label: "Zoom",
            flag: "zoom",
        },
    }
}
