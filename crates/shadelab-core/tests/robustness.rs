//! The rendering robustness list, through both rasterizers explicitly (the
//! other suites run one, chosen by `SHADELAB_TEST_RASTERIZER`): degenerate,
//! sliver, huge (1e30) and NaN triangles, the camera inside the mesh, the eye
//! on the target, fields of view of 0 and 180 degrees and next to them,
//! near ≥ far and extreme depth ranges. Each gives a clear error or a correct
//! image of the requested size, never a panic; and both rasterizers agree.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, coverage, render, Camera, CameraError, CornerNormals, Mesh, MeshError,
    Rasterizer, RenderError, RenderOptions, Scene, Shading,
};

fn with(rasterizer: Rasterizer, cull: bool, shading: Shading, w: u32, h: u32) -> RenderOptions {
    RenderOptions {
        rasterizer,
        cull_backfaces: cull,
        ..options(w, h, shading)
    }
}

/// Renders and counts coverage with both rasterizers, culling on and off,
/// in every method: the same outcome from both (an error, or coverage maps
/// that agree), images of the requested size, and background wherever
/// nothing covers a pixel. Returns the coverage maps (culling on, off).
fn outcome(name: &str, scene: &Scene, w: u32, h: u32) -> Result<[Vec<u32>; 2], RenderError> {
    let mut maps = Vec::new();
    for cull in [true, false] {
        let mut reference: Option<Result<Vec<u32>, RenderError>> = None;
        for rasterizer in Rasterizer::ALL {
            let counts = coverage(scene, &with(rasterizer, cull, Shading::Flat, w, h));
            match &reference {
                None => reference = Some(counts.clone()),
                Some(first) => assert_eq!(
                    &counts, first,
                    "{name}: scanline and tiled disagree (cull {cull})"
                ),
            }
            for shading in Shading::ALL {
                let options = with(rasterizer, cull, shading, w, h);
                match (render(scene, &options), &counts) {
                    (Ok((image, _)), Ok(counts)) => {
                        assert_eq!((image.width(), image.height()), (w, h), "{name}");
                        for (k, &c) in counts.iter().enumerate() {
                            if c == 0 {
                                let (x, y) = (k as u32 % w, k as u32 / w);
                                assert_eq!(
                                    image.pixel(x, y),
                                    BACKGROUND,
                                    "{name}: {rasterizer:?} {shading:?} drew ({x}, {y}), which nothing covers"
                                );
                            }
                        }
                    }
                    (Err(a), Err(b)) => assert_eq!(&a, b, "{name}"),
                    (a, b) => panic!(
                        "{name}: render and coverage disagree: {:?} vs {:?}",
                        a.map(|_| ()),
                        b.as_ref().map(|_| ())
                    ),
                }
            }
        }
        maps.push(reference.unwrap()?);
    }
    let [on, off]: [Vec<u32>; 2] = maps.try_into().unwrap();
    Ok([on, off])
}

fn triangle(corners: [Vec3; 3]) -> Mesh {
    Mesh::from_polygons(corners.to_vec(), [[0u32, 1, 2]]).unwrap()
}

fn front_camera() -> Camera {
    camera(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 50.0, 0.5, 20.0)
}

/// Degenerate triangles (a repeated corner, collinear corners, all three at
/// one point, at a huge coordinate) draw nothing, and next to a good
/// triangle change nothing.
#[test]
fn degenerate_triangles_draw_nothing() {
    let good = [
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let alone = triangle(good);
    let cam = front_camera();
    let [reference, _] = outcome("good", &smooth(alone, cam), 48, 40).unwrap();
    assert!(reference.iter().any(|&c| c > 0));
    for (k, bad) in [
        [Vec3::ZERO, Vec3::ZERO, Vec3::X],
        [Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
        [Vec3::ONE; 3],
        [
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ],
        [Vec3::splat(1e30), Vec3::splat(1e30), Vec3::splat(-1e30)],
    ]
    .into_iter()
    .enumerate()
    {
        let name = format!("degenerate{k}");
        let [on, off] = outcome(&name, &smooth(triangle(bad), cam), 48, 40).unwrap();
        assert!(
            on.iter().chain(&off).all(|&c| c == 0),
            "{name} covers something"
        );
        let both = Mesh::from_polygons(
            good.iter().chain(&bad).copied().collect(),
            [[0u32, 1, 2], [3, 4, 5]],
        )
        .unwrap();
        let [on, _] = outcome(&name, &smooth(both, cam), 48, 40).unwrap();
        assert_eq!(on, reference, "{name} changes the good triangle's pixels");
        let (_, stats) = render(
            &smooth(triangle(bad), cam),
            &with(Rasterizer::Tiled, true, Shading::Phong, 48, 40),
        )
        .unwrap();
        assert_eq!(stats.fragments_shaded, 0, "{name}");
    }
}

/// Slivers — long triangles narrower than a pixel, at every angle — cover
/// exactly the pixel centres inside them (top-left rule), each once.
#[test]
fn slivers_cover_exactly_their_pixel_centres() {
    let (w, h) = (64u32, 48u32);
    let cam = front_camera();
    let view = View::new(&cam, w, h);
    let mut checked = 0;
    for k in 0..48 {
        let angle = f64::from(k) * 0.131;
        let dir = DVec3::new(angle.cos(), angle.sin(), 0.0);
        let side = DVec3::new(-dir.y, dir.x, 0.0);
        for width in [1e-6, 1e-3, 0.01, 0.03] {
            let a = dir * -2.1 + side * (0.01 * f64::from(k % 5));
            let b = dir * 2.0;
            let c = b + side * width;
            let mesh = triangle([a, b, c].map(f));
            let scene = smooth(mesh, cam);
            let [on, off] = outcome(&format!("sliver{k}"), &scene, w, h).unwrap();
            let snapped: Vec<(i64, i64)> =
                [a, b, c].iter().map(|&p| view.snapped(d(f(p)))).collect();
            let mut ccw = snapped.clone();
            if area2_ccw(&ccw) < 0 {
                ccw.reverse();
            }
            let front = area2_ccw(&snapped) > 0;
            let expected = brute_force_coverage(&ccw, w, h);
            assert_eq!(off, expected, "sliver {k} width {width}");
            if front {
                assert_eq!(on, expected, "sliver {k} width {width}, culling on");
            } else {
                assert!(on.iter().all(|&c| c == 0));
            }
            checked += expected.iter().filter(|&&c| c > 0).count();
        }
    }
    assert!(checked > 100, "the slivers cover some pixels: {checked}");
}

/// Corners at ±1e30 (and one at f32::MAX): a wall filling the screen covers
/// every pixel once; nothing panics and the rasterizers agree.
#[test]
fn huge_triangles() {
    let (w, h) = (40u32, 30u32);
    let cam = camera(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), 60.0, 0.1, 100.0);
    let big = 1e30f32;
    let wall = triangle([
        Vec3::new(-big, -big, -5.0),
        Vec3::new(big, -big, -5.0),
        Vec3::new(0.0, big, -5.0),
    ]);
    let [on, off] = outcome("wall", &smooth(wall, cam), w, h).unwrap();
    assert!(on.iter().all(|&c| c == 1) && off.iter().all(|&c| c == 1));
    for (k, corners) in [
        [
            Vec3::new(-big, 0.0, -big),
            Vec3::new(big, 0.0, -big),
            Vec3::new(0.0, 0.0, big),
        ],
        [
            Vec3::new(-big, -1.0, 1.0),
            Vec3::new(big, -1.0, 1.0),
            Vec3::new(0.0, big, -big),
        ],
        [
            Vec3::new(-1.0, -1.0, -5.0),
            Vec3::new(1.0, -1.0, -5.0),
            Vec3::new(0.0, f32::MAX, -f32::MAX),
        ],
        [
            Vec3::splat(-f32::MAX),
            Vec3::new(f32::MAX, -f32::MAX, 0.0),
            Vec3::new(0.0, f32::MAX, f32::MAX),
        ],
    ]
    .into_iter()
    .enumerate()
    {
        let [on, off] =
            outcome(&format!("huge{k}"), &smooth(triangle(corners), cam), w, h).unwrap();
        assert!(
            on.iter().chain(&off).all(|&c| c <= 1),
            "huge{k}: a pixel covered twice"
        );
    }
}

/// NaN and infinite positions cannot make a mesh; NaN normals render.
#[test]
fn nan_triangles() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let corners = vec![Vec3::ZERO, Vec3::new(1.0, bad, 0.0), Vec3::Y];
        assert!(matches!(
            Mesh::from_polygons(corners, [[0u32, 1, 2]]),
            Err(MeshError::NonFinite { vertex: 1, .. })
        ));
    }
    let mesh = builtin_model("icosphere", Some(1)).unwrap();
    let normals = CornerNormals::new(
        vec![Vec3::splat(f32::NAN), Vec3::Z],
        (0..mesh.corners().len() as u32).map(|c| c % 2).collect(),
    );
    let scene = scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 45.0, 0.5, 10.0),
    );
    let [on, _] = outcome("nan-normals", &scene, 32, 32).unwrap();
    assert!(on.iter().any(|&c| c > 0));
}

/// Inside a closed convex mesh with culling off, every pixel is covered by
/// exactly one (back) face; with culling on, by none.
#[test]
fn camera_inside_the_mesh() {
    for (model, detail) in [("cube", 2), ("icosphere", 2), ("sphere", 16)] {
        let mesh = builtin_model(model, Some(detail)).unwrap().normalized();
        for (eye, target) in [
            (DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0)),
            (DVec3::new(0.2, -0.1, 0.3), DVec3::new(1.0, 0.5, -0.3)),
        ] {
            let cam = camera(eye, target, 100.0, 0.01, 10.0);
            let name = format!("inside-{model}");
            let [on, off] = outcome(&name, &smooth(mesh.clone(), cam), 40, 30).unwrap();
            assert!(on.iter().all(|&c| c == 0), "{name}: culling on");
            assert!(off.iter().all(|&c| c == 1), "{name}: culling off");
        }
    }
}

/// The next float above a positive `x`.
fn next_up(x: f32) -> f32 {
    f32::from_bits(x.to_bits() + 1)
}

fn good_scene() -> Scene {
    let mesh = builtin_model("icosphere", Some(1)).unwrap();
    smooth(
        mesh,
        camera(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 45.0, 0.5, 10.0),
    )
}

/// Camera parameters that cannot make a view are errors from both
/// rasterizers, for render and coverage alike.
#[test]
fn impossible_cameras_are_errors() {
    let good = good_scene();
    let cam = good.camera;
    for (camera, error) in [
        (
            Camera {
                target: cam.eye,
                ..cam
            },
            CameraError::EyeAtTarget,
        ),
        (
            // Apart, but too little for a view direction in f32: the error
            // says by how much (1e-30 on two axes).
            Camera {
                target: cam.eye + Vec3::splat(1e-30),
                ..cam
            },
            CameraError::EyeTooClose {
                distance: 1e-30 * std::f32::consts::SQRT_2,
            },
        ),
        (
            Camera {
                fov_y_degrees: 0.0,
                ..cam
            },
            CameraError::FieldOfView(0.0),
        ),
        (
            Camera {
                fov_y_degrees: -0.0,
                ..cam
            },
            CameraError::FieldOfView(-0.0),
        ),
        (
            Camera {
                fov_y_degrees: 180.0,
                ..cam
            },
            CameraError::FieldOfView(180.0),
        ),
        (
            Camera {
                fov_y_degrees: 180.00002,
                ..cam
            },
            CameraError::FieldOfView(180.00002),
        ),
        (
            Camera {
                near: 5.0,
                far: 5.0,
                ..cam
            },
            CameraError::DepthRange {
                near: 5.0,
                far: 5.0,
            },
        ),
        (
            Camera {
                near: 6.0,
                far: 5.0,
                ..cam
            },
            CameraError::DepthRange {
                near: 6.0,
                far: 5.0,
            },
        ),
        (
            Camera { near: 0.0, ..cam },
            CameraError::DepthRange {
                near: 0.0,
                far: cam.far,
            },
        ),
    ] {
        let scene = Scene {
            camera,
            ..good.clone()
        };
        assert_eq!(
            outcome(&format!("{camera:?}"), &scene, 16, 12).unwrap_err(),
            RenderError::Camera(error),
            "{camera:?}"
        );
    }
}

/// Cameras at the edge of what is allowed render, at the requested size,
/// with both rasterizers agreeing: fields of view from the smallest positive
/// float to just below 180°, the eye a hair from the target, depth ranges
/// from 1e-30 to 1e30 and one float wide.
#[test]
fn extreme_but_valid_cameras_render() {
    let good = good_scene();
    let cam = good.camera;
    let next_below_180 = f32::from_bits(180f32.to_bits() - 1);
    let cameras = [
        Camera {
            fov_y_degrees: f32::from_bits(1),
            ..cam
        },
        Camera {
            fov_y_degrees: f32::MIN_POSITIVE,
            ..cam
        },
        Camera {
            fov_y_degrees: 1e-30,
            ..cam
        },
        Camera {
            fov_y_degrees: 1e-6,
            ..cam
        },
        Camera {
            fov_y_degrees: 179.99,
            ..cam
        },
        Camera {
            fov_y_degrees: next_below_180,
            ..cam
        },
        // The eye inside the sphere, 1e-18 from the target.
        Camera {
            eye: Vec3::new(0.0, 0.0, 2e-18),
            target: Vec3::new(0.0, 0.0, 1e-18),
            ..cam
        },
        Camera {
            near: 1e-30,
            far: 1e30,
            ..cam
        },
        Camera {
            near: f32::MIN_POSITIVE,
            far: f32::MAX,
            ..cam
        },
        Camera {
            near: f32::from_bits(1),
            far: 10.0,
            ..cam
        },
        Camera {
            near: 3.5,
            far: next_up(3.5),
            ..cam
        },
        Camera {
            near: 1e-6,
            far: next_up(1e-6),
            ..cam
        },
    ];
    for camera in cameras {
        assert!(camera.validate().is_ok(), "{camera:?}");
        let scene = Scene {
            camera,
            ..good.clone()
        };
        for (w, h) in [(1, 1), (17, 9), (3, 40)] {
            outcome(&format!("{camera:?} {w}x{h}"), &scene, w, h)
                .unwrap_or_else(|e| panic!("{camera:?}: {e}"));
        }
    }
    // A wide field of view still shows the model, centred.
    let scene = Scene {
        camera: Camera {
            fov_y_degrees: 179.0,
            ..cam
        },
        ..good.clone()
    };
    let [on, _] = outcome("wide", &scene, 41, 41).unwrap();
    assert_eq!(on[20 * 41 + 20], 1, "the centre pixel sees the sphere");
}
