//! Criterion benchmarks of the rasterizers' hot paths, one frame each:
//!
//! * `frame/*`: a whole frame of the built-in teapot at 512×512, each
//!   method, tiled (best SIMD level and portable) and scanline;
//! * `small-triangles/*`: an icosphere subdivided 6 times (81,920 triangles, most
//!   of a few pixels): vertex work, setup, binning, small-triangle walks;
//! * `fill/*`: a full-screen quad at 1920×1080: per-pixel shading and the
//!   write-out, nothing else;
//! * `three-methods/*`: the viewer's frame, the three methods of one scene at
//!   480×480, as three frames and as one `Renderer::render_methods` call.
//!
//! Run with `cargo bench -p shadelab-core`. The CPU and the SIMD level are
//! printed first and are part of each benchmark's name; work runs on a
//! one-thread rayon pool so that numbers do not depend on the machine's load
//! from other cores (`shadelab bench` measures 1 and 2 threads).

use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3;
use shadelab_core::{
    builtin_model, vertex_normals, Camera, Image, Light, LightKind, Material, Mesh,
    NormalWeighting, Rasterizer, RenderOptions, Renderer, Rgb, Rgb8, Scene, Shading, SimdLevel,
};

fn scene(mesh: Mesh, camera: Camera) -> Scene {
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    Scene {
        mesh,
        normals,
        camera,
        ambient: Rgb::new(0.2, 0.2, 0.2),
        lights: vec![Light {
            kind: LightKind::Point {
                position: Vec3::new(2.0, 3.0, 2.5),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        }],
        material: Material {
            ka: Rgb8::new(77, 64, 51).to_rgb(),
            kd: Rgb8::new(204, 153, 102).to_rgb(),
            ks: Rgb8::new(128, 128, 128).to_rgb(),
            shininess: 32.0,
        },
    }
}

fn framed(name: &str, detail: u32, aspect: f32) -> Scene {
    let mesh = builtin_model(name, Some(detail)).unwrap().normalized();
    scene(mesh, Camera::framing_sphere(Vec3::ZERO, 1.0, 45.0, aspect))
}

fn quad(aspect: f32) -> Scene {
    let (hy, hx) = (0.42, 0.42 * aspect);
    let positions = vec![
        Vec3::new(-hx, -hy, 0.0),
        Vec3::new(hx, -hy, 0.0),
        Vec3::new(hx, hy, 0.0),
        Vec3::new(-hx, hy, 0.0),
    ];
    let mesh = Mesh::from_polygons(positions, [[0u32, 1, 2], [0, 2, 3]]).unwrap();
    let camera = Camera {
        eye: Vec3::Z,
        target: Vec3::ZERO,
        up: Vec3::Y,
        fov_y_degrees: 45.0,
        near: 0.5,
        far: 2.0,
    };
    scene(mesh, camera)
}

fn cpu() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, n)| n.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}

fn options(w: u32, h: u32, shading: Shading, rasterizer: Rasterizer) -> RenderOptions {
    RenderOptions {
        width: w,
        height: h,
        shading,
        rasterizer,
        ..RenderOptions::default()
    }
}

fn benches(c: &mut Criterion) {
    let best = SimdLevel::detect();
    eprintln!("CPU: {}; SIMD: {} (and portable)", cpu(), best.name());
    // One thread, and the timed iterations run on it (`pool.install` around
    // `b.iter`, not inside it): installing each frame from outside the pool
    // added the wake-up of the sleeping caller, 20–40 µs, to every frame
    // (BENCHMARKS.md, "Frames timed on a thread of the pool").
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut run = |group: &str, scene: &Scene, options: RenderOptions, simd: SimdLevel| {
        let mut renderer = Renderer::with_simd(simd);
        let mut image = Image::filled(options.width, options.height, Rgb8::new(0, 0, 0));
        let raster = match options.rasterizer {
            Rasterizer::Tiled => format!("tiled-{}", simd.name()),
            Rasterizer::Scanline => "scanline".to_string(),
        };
        let id = format!("{group}/{raster}/{}", options.shading.name());
        // The iterations run on the pool's thread (see `pool` above).
        c.bench_function(&id, |b| {
            pool.install(|| b.iter(|| renderer.render_into(scene, &options, &mut image).unwrap()))
        });
    };

    let teapot = framed("teapot", 8, 1.0);
    for shading in Shading::ALL {
        run(
            "frame/teapot-512",
            &teapot,
            options(512, 512, shading, Rasterizer::Tiled),
            best,
        );
        run(
            "frame/teapot-512",
            &teapot,
            options(512, 512, shading, Rasterizer::Tiled),
            SimdLevel::Portable,
        );
        run(
            "frame/teapot-512",
            &teapot,
            options(512, 512, shading, Rasterizer::Scanline),
            best,
        );
    }
    let sphere = framed("icosphere", 6, 1.0);
    for shading in Shading::ALL {
        run(
            "small-triangles/icosphere6-512",
            &sphere,
            options(512, 512, shading, Rasterizer::Tiled),
            best,
        );
    }
    let fill = quad(1920.0 / 1080.0);
    for shading in Shading::ALL {
        run(
            "fill/quad-1080p",
            &fill,
            options(1920, 1080, shading, Rasterizer::Tiled),
            best,
        );
    }

    // The viewer's frame: the three methods of one scene, as three frames
    // and as one `render_methods` call (geometry once).
    let panel = options(480, 480, Shading::Flat, Rasterizer::Tiled);
    for (name, scene) in [("teapot", &teapot), ("icosphere6", &sphere)] {
        let mut renderer = Renderer::with_simd(best);
        let mut images: [Image; 3] =
            std::array::from_fn(|_| Image::filled(480, 480, Rgb8::new(0, 0, 0)));
        let group = format!("three-methods/{name}-480/tiled-{}", best.name());
        c.bench_function(&format!("{group}/one-by-one"), |b| {
            pool.install(|| {
                b.iter(|| {
                    for (shading, image) in Shading::ALL.into_iter().zip(&mut images) {
                        let options = RenderOptions { shading, ..panel };
                        renderer.render_into(scene, &options, image).unwrap();
                    }
                })
            })
        });
        c.bench_function(&format!("{group}/at-once"), |b| {
            pool.install(|| {
                b.iter(|| {
                    let [x, y, z] = &mut images;
                    renderer.render_methods(scene, &panel, [x, y, z]).unwrap()
                })
            })
        });
    }
}

criterion_group! {
    name = raster;
    config = Criterion::default().sample_size(20).warm_up_time(std::time::Duration::from_millis(500)).measurement_time(std::time::Duration::from_secs(2));
    targets = benches
}
criterion_main!(raster);
