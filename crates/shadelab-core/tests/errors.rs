//! Invalid frames are errors from `render` and `coverage`, never panics (and
//! never a huge allocation before the check).

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, coverage, render, vertex_normals, Camera, CameraError, CornerNormals, Light,
    LightKind, NormalWeighting, RenderError, RenderOptions, Rgb, Scene, Shading, MAX_IMAGE_PIXELS,
    MAX_IMAGE_SIDE,
};

fn good_scene() -> Scene {
    let mesh = builtin_model("icosphere", Some(1)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 45.0, 0.5, 10.0),
    )
}

/// Both entry points give `expected`, for every shading method.
fn assert_error(scene: &Scene, options: &RenderOptions, expected: &RenderError) {
    for shading in Shading::ALL {
        let options = RenderOptions {
            shading,
            ..*options
        };
        assert_eq!(
            render(scene, &options).err().as_ref(),
            Some(expected),
            "render, {shading:?}"
        );
        assert_eq!(
            coverage(scene, &options).err().as_ref(),
            Some(expected),
            "coverage, {shading:?}"
        );
    }
}

#[test]
fn image_size_out_of_range() {
    let scene = good_scene();
    let side = MAX_IMAGE_SIDE;
    // Square images at the side limit exceed the pixel limit.
    assert!(u64::from(side) * u64::from(side) > MAX_IMAGE_PIXELS);
    let too_many = (MAX_IMAGE_PIXELS / u64::from(side) + 1) as u32;
    for (width, height) in [
        (0, 10),
        (10, 0),
        (0, 0),
        (side + 1, 1),
        (1, side + 1),
        (u32::MAX, 1),
        (1, u32::MAX),
        (u32::MAX, u32::MAX),
        (side, side),
        (side, too_many),
    ] {
        let options = options(width, height, Shading::Phong);
        assert_error(&scene, &options, &RenderError::ImageSize { width, height });
    }
    // The limits themselves are fine (a 1-pixel-high strip: cheap).
    for (width, height) in [(1, 1), (side, 1), (1, side)] {
        render(&scene, &options(width, height, Shading::Phong)).unwrap();
    }
}

#[test]
fn camera_out_of_range() {
    let good = good_scene();
    let cam = good.camera;
    let cases = [
        (
            Camera {
                target: cam.eye,
                ..cam
            },
            CameraError::EyeAtTarget,
        ),
        (
            Camera {
                eye: Vec3::splat(1.0),
                target: Vec3::splat(1.0),
                ..cam
            },
            CameraError::EyeAtTarget,
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
                fov_y_degrees: 180.0,
                ..cam
            },
            CameraError::FieldOfView(180.0),
        ),
        (
            Camera {
                fov_y_degrees: -30.0,
                ..cam
            },
            CameraError::FieldOfView(-30.0),
        ),
        (
            Camera {
                fov_y_degrees: 270.0,
                ..cam
            },
            CameraError::FieldOfView(270.0),
        ),
        (
            Camera {
                near: 10.0,
                far: 10.0,
                ..cam
            },
            CameraError::DepthRange {
                near: 10.0,
                far: 10.0,
            },
        ),
        (
            Camera {
                near: 11.0,
                far: 10.0,
                ..cam
            },
            CameraError::DepthRange {
                near: 11.0,
                far: 10.0,
            },
        ),
        (
            Camera { near: 0.0, ..cam },
            CameraError::DepthRange {
                near: 0.0,
                far: cam.far,
            },
        ),
        (
            Camera { near: -1.0, ..cam },
            CameraError::DepthRange {
                near: -1.0,
                far: cam.far,
            },
        ),
        (
            Camera {
                up: Vec3::ZERO,
                ..cam
            },
            CameraError::BadUp,
        ),
        // Up along the view direction (the eye is on +z, looking down −z).
        (Camera { up: Vec3::Z, ..cam }, CameraError::BadUp),
        (
            Camera {
                up: Vec3::NEG_Z * 3.0,
                ..cam
            },
            CameraError::BadUp,
        ),
        (
            Camera {
                eye: Vec3::new(0.0, f32::NAN, 4.0),
                ..cam
            },
            CameraError::NonFinite("eye"),
        ),
        (
            Camera {
                fov_y_degrees: f32::INFINITY,
                ..cam
            },
            CameraError::NonFinite("fov_y"),
        ),
    ];
    for (camera, error) in cases {
        let scene = Scene {
            camera,
            ..good.clone()
        };
        assert_error(
            &scene,
            &options(32, 24, Shading::Phong),
            &RenderError::Camera(error),
        );
    }
    // Near the limits it renders.
    for camera in [
        Camera {
            fov_y_degrees: 0.01,
            ..cam
        },
        Camera {
            fov_y_degrees: 179.9,
            ..cam
        },
        Camera {
            near: 1e-6,
            far: 1e6,
            ..cam
        },
    ] {
        render(
            &Scene {
                camera,
                ..good.clone()
            },
            &options(32, 24, Shading::Phong),
        )
        .unwrap();
    }
}

#[test]
fn normals_and_lighting_out_of_range() {
    let good = good_scene();
    let corners = good.mesh.corners().len();
    let (normals, mut corner) = good.normals.clone().into_parts();
    corner.pop();
    let short = CornerNormals::new(normals, corner);
    let out_of_range = CornerNormals::new(vec![Vec3::Z], vec![1; corners]);
    for normals in [short, out_of_range, CornerNormals::default()] {
        let expected = RenderError::NormalsMismatch {
            normals: normals.corner().len(),
            corners,
        };
        let scene = Scene {
            normals,
            ..good.clone()
        };
        assert_error(&scene, &options(16, 16, Shading::Gouraud), &expected);
    }

    let nan = f32::NAN;
    let mut scene = Scene {
        ambient: Rgb::new(0.1, nan, 0.1),
        ..good.clone()
    };
    assert_error(
        &scene,
        &options(16, 16, Shading::Phong),
        &RenderError::NonFinite("ambient"),
    );
    scene = good.clone();
    scene.material.shininess = f32::INFINITY;
    assert_error(
        &scene,
        &options(16, 16, Shading::Phong),
        &RenderError::NonFinite("material"),
    );
    scene = good.clone();
    scene.material.ks = Rgb::new(nan, 0.0, 0.0);
    assert_error(
        &scene,
        &options(16, 16, Shading::Phong),
        &RenderError::NonFinite("material"),
    );
    for light in [
        Light {
            kind: LightKind::Point {
                position: Vec3::new(nan, 0.0, 0.0),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        },
        Light {
            kind: LightKind::Directional {
                direction: Vec3::splat(f32::INFINITY),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        },
        Light {
            kind: LightKind::Point {
                position: Vec3::ONE,
            },
            color: Rgb::WHITE,
            intensity: nan,
            attenuation: shadelab_core::NO_ATTENUATION,
        },
        Light {
            kind: LightKind::Point {
                position: Vec3::ONE,
            },
            color: Rgb::new(0.0, nan, 0.0),
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        },
    ] {
        scene = good.clone();
        scene.lights.push(light);
        assert_error(
            &scene,
            &options(16, 16, Shading::Phong),
            &RenderError::NonFinite("light"),
        );
    }
}

/// Odd but valid input renders: no lights, a zero directional light, a
/// light at the surface, no faces visible, a mesh entirely behind the eye.
#[test]
fn odd_but_valid_scenes_render() {
    let good = good_scene();
    let mut scenes = vec![Scene {
        lights: Vec::new(),
        ..good.clone()
    }];
    let mut zero = good.clone();
    zero.lights = vec![Light {
        kind: LightKind::Directional {
            direction: Vec3::ZERO,
        },
        color: Rgb::WHITE,
        intensity: 1.0,
        attenuation: shadelab_core::NO_ATTENUATION,
    }];
    scenes.push(zero);
    let mut at_surface = good.clone();
    let on_mesh = at_surface.mesh.positions()[0];
    at_surface.lights = vec![Light {
        kind: LightKind::Point { position: on_mesh },
        color: Rgb::WHITE,
        intensity: 1.0,
        attenuation: shadelab_core::NO_ATTENUATION,
    }];
    scenes.push(at_surface);
    let mut behind = good.clone();
    behind.camera = Camera {
        target: Vec3::new(0.0, 0.0, 10.0),
        ..good.camera
    };
    scenes.push(behind);
    for scene in scenes {
        for shading in Shading::ALL {
            for cull in [true, false] {
                let options = RenderOptions {
                    cull_backfaces: cull,
                    ..options(32, 24, shading)
                };
                render(&scene, &options).unwrap();
                coverage(&scene, &options).unwrap();
            }
        }
    }
}

/// `RenderOptions::check` is the one check of the options: the scene file
/// shows its errors as `key: problem`, exactly as `Display` does.
#[test]
fn option_errors_name_the_scene_file_key() {
    use shadelab_core::{Palette, Polygons, Rasterizer};
    let base = RenderOptions {
        rasterizer: Rasterizer::Tiled,
        ..options(64, 48, Shading::Phong)
    };
    let scanline = RenderOptions {
        rasterizer: Rasterizer::Scanline,
        ..base
    };
    let cases = [
        (
            RenderOptions { width: 0, ..base },
            "render.width: must be 1..=16384, got 0",
        ),
        (
            RenderOptions {
                height: MAX_IMAGE_SIDE + 1,
                ..base
            },
            "render.height: must be 1..=16384, got 16385",
        ),
        (
            RenderOptions {
                width: MAX_IMAGE_SIDE,
                height: MAX_IMAGE_SIDE,
                ..base
            },
            "render: 16384x16384 exceeds 67108864 pixels",
        ),
        (
            RenderOptions {
                polygons: Polygons::Whole,
                ..base
            },
            "render.polygons: \"whole\" needs rasterizer = \"scanline\"; the tiled rasterizer draws fans",
        ),
        (
            RenderOptions {
                fixed_point_bits: Some(99),
                ..base
            },
            "render.fixed_point_bits: must be 1..=30, got 99",
        ),
        (
            RenderOptions {
                fixed_point_bits: Some(8),
                ..base
            },
            "render.fixed_point_bits: needs rasterizer = \"scanline\"; the tiled rasterizer does not draw it",
        ),
        (
            RenderOptions {
                palette: Some(Palette {
                    shades: 1,
                    offset: 0,
                }),
                ..scanline
            },
            "render.palette_shades: needs 2..=256 shades with palette_offset + palette_shades ≤ 256, got 1 at offset 0",
        ),
        (
            RenderOptions {
                palette: Some(Palette {
                    shades: 8,
                    offset: 0,
                }),
                ..base
            },
            "render.palette_shades: needs rasterizer = \"scanline\"; the tiled rasterizer does not draw it",
        ),
    ];
    for (options, expected) in cases {
        let e = options.check().unwrap_err();
        assert_eq!(e.to_string(), expected);
        assert_eq!(format!("{}: {}", e.key().unwrap(), e.problem()), expected);
        assert_eq!(
            render(&good_scene(), &options).unwrap_err(),
            e,
            "{expected}"
        );
    }
    base.check().unwrap();
    RenderOptions {
        fixed_point_bits: Some(8),
        polygons: Polygons::Whole,
        ..scanline
    }
    .check()
    .unwrap();
}
