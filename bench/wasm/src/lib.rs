//! The viewer's workload, callable from JavaScript: a model (the built-in
//! teapot, or a mesh file's bytes), normalized and framed as the viewer
//! frames it, one point light, drawn by the tiled rasterizer into a reused
//! image with a chosen SIMD level, so that `run.js` can time the levels and
//! check that they give the same pixels.

use std::cell::RefCell;

use shadelab_core::{
    builtin_model, vertex_normals, Camera, Image, Light, LightKind, Material, Mesh,
    NormalWeighting, RenderOptions, Renderer, Rgb, Rgb8, Scene, Shading, SimdLevel, NO_ATTENUATION,
};

struct State {
    scene: Scene,
    renderers: [Renderer; 2],
    image: Image,
    width: u32,
    height: u32,
}

thread_local! {
    static STATE: RefCell<Option<State>> = const { RefCell::new(None) };
    static INPUT: RefCell<Vec<u8>> = const { RefCell::new(Vec::new()) };
}

/// A buffer of `len` bytes for `load`'s file; returns its address.
#[no_mangle]
pub extern "C" fn input(len: usize) -> *mut u8 {
    INPUT.with(|b| {
        let mut b = b.borrow_mut();
        b.clear();
        b.resize(len, 0);
        b.as_mut_ptr()
    })
}

/// Prepares the teapot at `detail` for `width` × `height` frames; 0 on success.
#[no_mangle]
pub extern "C" fn setup(detail: u32, width: u32, height: u32) -> u32 {
    match builtin_model("teapot", Some(detail)) {
        Ok(mesh) => keep(mesh, width, height),
        Err(_) => 1,
    }
}

/// Prepares the mesh file in the input buffer (an OBJ file) instead; 0 on success.
#[no_mangle]
pub extern "C" fn load(width: u32, height: u32) -> u32 {
    let mesh = INPUT.with(|b| shadelab_io::parse_mesh(&b.borrow(), "model.obj"));
    match mesh {
        Ok(mesh) => keep(mesh, width, height),
        Err(_) => 1,
    }
}

fn keep(mesh: Mesh, width: u32, height: u32) -> u32 {
    let mesh = mesh.normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let camera = Camera::framing_sphere(glam::Vec3::ZERO, 1.0, 45.0, width as f32 / height as f32);
    let scene = Scene {
        mesh,
        normals,
        camera,
        ambient: Rgb::new(0.2, 0.2, 0.2),
        lights: vec![Light {
            kind: LightKind::Point {
                position: glam::Vec3::new(2.0, 2.0, 3.0),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: NO_ATTENUATION,
        }],
        material: Material::default(),
    };
    STATE.with(|s| {
        *s.borrow_mut() = Some(State {
            scene,
            renderers: [
                Renderer::with_simd(SimdLevel::Portable),
                Renderer::with_simd(SimdLevel::detect()),
            ],
            image: Image::filled(width, height, Rgb8::new(0, 0, 0)),
            width,
            height,
        })
    });
    0
}

/// Renders one frame (shading 0 flat, 1 Gouraud, 2 Phong; level 0 the
/// portable lanes, 1 the best this module has), the camera turned by `yaw`
/// degrees; returns the covered pixels.
#[no_mangle]
pub extern "C" fn frame(shading: u32, level: u32, yaw: f32) -> u32 {
    STATE.with(|s| {
        let mut s = s.borrow_mut();
        let Some(state) = s.as_mut() else {
            return 0;
        };
        let options = RenderOptions {
            width: state.width,
            height: state.height,
            shading: match shading {
                0 => Shading::Flat,
                1 => Shading::Gouraud,
                _ => Shading::Phong,
            },
            ..RenderOptions::default()
        };
        state.scene.camera = Camera::framing_sphere(
            glam::Vec3::ZERO,
            1.0,
            45.0,
            state.width as f32 / state.height as f32,
        )
        .orbit(yaw, 0.0);
        let renderer = &mut state.renderers[level.min(1) as usize];
        renderer
            .render_into(&state.scene, &options, &mut state.image)
            .map_or(0, |stats| stats.covered_pixels as u32)
    })
}

/// The last frame's RGB pixels: their address (`pixels_len` bytes).
#[no_mangle]
pub extern "C" fn pixels() -> *const u8 {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or(std::ptr::null(), |s| s.image.pixels().as_ptr().cast())
    })
}

/// The length of `pixels` in bytes.
#[no_mangle]
pub extern "C" fn pixels_len() -> usize {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or(0, |s| s.image.pixels().len() * 3)
    })
}

/// The best SIMD level of this module: 0 portable, 1 avx2, 2 simd128, 3 avx512.
#[no_mangle]
pub extern "C" fn level() -> u32 {
    match SimdLevel::detect() {
        SimdLevel::Portable => 0,
        SimdLevel::Avx2 => 1,
        SimdLevel::Simd128 => 2,
        SimdLevel::Avx512 => 3,
    }
}
