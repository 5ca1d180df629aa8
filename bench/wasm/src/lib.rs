//! A frame of the viewer's workload, callable from JavaScript: the built-in
//! teapot, normalized and framed as the viewer frames it, one light, drawn
//! by the tiled rasterizer into a reused image.

use std::cell::RefCell;

use shadelab_core::{
    builtin_model, vertex_normals, Camera, Image, Light, LightKind, Material, NormalWeighting,
    RenderOptions, Renderer, Rgb, Rgb8, Scene, Shading,
};

struct State {
    scene: Scene,
    renderer: Renderer,
    image: Image,
    width: u32,
    height: u32,
}

thread_local! {
    static STATE: RefCell<Option<State>> = const { RefCell::new(None) };
}

/// Prepares the teapot at `detail` for `width` × `height` frames; 0 on success.
#[no_mangle]
pub extern "C" fn setup(detail: u32, width: u32, height: u32) -> u32 {
    let Ok(mesh) = builtin_model("teapot", Some(detail)) else {
        return 1;
    };
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
        }],
        material: Material::default(),
    };
    STATE.with(|s| {
        *s.borrow_mut() = Some(State {
            scene,
            renderer: Renderer::new(),
            image: Image::filled(width, height, Rgb8::new(0, 0, 0)),
            width,
            height,
        })
    });
    0
}

/// Renders one frame (0 flat, 1 Gouraud, 2 Phong); returns the covered pixels.
#[no_mangle]
pub extern "C" fn frame(shading: u32) -> u32 {
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
        state
            .renderer
            .render_into(&state.scene, &options, &mut state.image)
            .map_or(0, |stats| stats.covered_pixels as u32)
    })
}
