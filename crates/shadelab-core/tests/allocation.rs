//! The tiled rasterizer allocates nothing per frame once warmed up: every
//! buffer lives in the `Renderer` and is cleared, not dropped. Counted with
//! dhat's heap profiler in testing mode, over frames of each method on a
//! one-thread and on a two-thread pool (the pools and the renderers are
//! made, their threads started, and warmed up, before counting).

use glam::Vec3;
use shadelab_core::{
    builtin_model, vertex_normals, Camera, Image, Light, LightKind, Material, NormalWeighting,
    RenderOptions, Renderer, Rgb, Rgb8, Scene, Shading,
};

#[global_allocator]
static ALLOCATOR: dhat::Alloc = dhat::Alloc;

#[test]
fn frames_after_the_first_allocate_nothing() {
    let _profiler = dhat::Profiler::builder().testing().build();
    let mesh = builtin_model("teapot", None).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let scene = Scene {
        mesh,
        normals,
        camera: Camera::framing_sphere(Vec3::ZERO, 1.0, 45.0, 4.0 / 3.0),
        ambient: Rgb::new(0.2, 0.2, 0.2),
        lights: vec![Light {
            kind: LightKind::Point {
                position: Vec3::new(2.0, 2.0, 3.0),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        }],
        material: Material::default(),
    };
    let mut counts = Vec::new();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        // The pool's threads start in the background and allocate as they
        // start (their queues, their epoch handles). Running something on
        // every thread waits until all of them have started, so that only
        // frames are counted.
        pool.broadcast(|_| ());
        let mut renderer = Renderer::new();
        let mut image = Image::filled(320, 240, Rgb8::new(0, 0, 0));
        counts.push(pool.install(|| {
            let mut frame = |shading: Shading| {
                let options = RenderOptions {
                    width: 320,
                    height: 240,
                    shading,
                    ..RenderOptions::default()
                };
                renderer.render_into(&scene, &options, &mut image).unwrap();
            };
            // Enough warm-up frames that each thread has drawn bands of
            // every method (which thread takes which band varies).
            for _ in 0..10 {
                Shading::ALL.into_iter().for_each(&mut frame);
            }
            let before = dhat::HeapStats::get();
            for _ in 0..5 {
                Shading::ALL.into_iter().for_each(&mut frame);
            }
            let after = dhat::HeapStats::get();
            (threads, after.total_blocks - before.total_blocks)
        }));
    }
    dhat::assert_eq!(
        counts,
        vec![(1, 0), (2, 0)],
        "allocations during 15 warmed-up frames (threads, blocks)"
    );
}
