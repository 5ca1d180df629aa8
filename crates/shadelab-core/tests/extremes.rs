//! Coordinates far beyond the screen and values that are not numbers: a
//! wall and a floor at 1e30, cuts with both ends far away, random triangles
//! from 1e-3 to 1e35 seen by random cameras, and NaN anywhere in a scene.
//! (Clipping at the near and far planes: `clipping.rs`.)

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, coverage, render, Camera, CameraError, CornerNormals, Mesh, MeshError,
    RenderError, RenderOptions, Shading,
};

/// Vertices at 1e30: a wall in front of the camera much larger than the
/// screen covers every pixel once; a floor to the horizon covers exactly
/// the rows its rays meet between the near and far planes.
#[test]
fn huge_coordinates() {
    let (w, h) = (64u32, 48u32);
    let big = 1e30f32;
    // A wall at z = −5 (a triangle and a quad), and the same tilted.
    let walls = [
        Mesh::from_polygons(
            vec![
                Vec3::new(-big, -big, -5.0),
                Vec3::new(big, -big, -5.0),
                Vec3::new(0.0, big, -5.0),
            ],
            [[0u32, 1, 2]],
        )
        .unwrap(),
        Mesh::from_polygons(
            vec![
                Vec3::new(-big, -big, -5.0),
                Vec3::new(big, -big, -5.0),
                Vec3::new(big, big, -5.0),
                Vec3::new(-big, big, -5.0),
            ],
            [[0u32, 1, 2, 3]],
        )
        .unwrap(),
        Mesh::from_polygons(
            vec![
                Vec3::new(-big, -big, -big),
                Vec3::new(big, -big, -5.0),
                Vec3::new(0.0, big, -5.0),
            ],
            [[0u32, 1, 2]],
        )
        .unwrap(),
    ];
    let cam = camera(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), 60.0, 0.1, 100.0);
    let view = View::new(&cam, w, h);
    for (k, mesh) in walls.into_iter().enumerate() {
        let corners: Vec<DVec3> = mesh.positions().iter().map(|&p| d(p)).collect();
        let scene = smooth(mesh, cam);
        let name = format!("huge-wall{k}");
        let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
        let n = ok(compare_counts(
            &name,
            &counts,
            w,
            h,
            polygon_expectation(&view, corners, 0.05),
        ));
        assert!(
            n > (w * h) as usize * 9 / 10,
            "{name}: only {n} pixels checked"
        );
        let covered = counts.iter().filter(|&&c| c > 0).count();
        if k < 2 {
            assert_eq!(
                covered,
                (w * h) as usize,
                "{name}: the wall fills the screen"
            );
        }
        for shading in Shading::ALL {
            let (image, _) = render(&scene, &options(w, h, shading)).unwrap();
            let drawn = image.pixels().iter().filter(|&&p| p != BACKGROUND).count();
            assert_eq!(drawn, covered, "{name} {shading:?}");
        }
    }

    // A floor with corners at ±1e6, cut by the near and far planes, exactly.
    for (m, mesh) in floor(1e6, 1e6).into_iter().enumerate() {
        let scene = smooth(mesh, cam);
        let name = format!("big-floor-mesh{m}");
        let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
        ok(compare_counts(
            &name,
            &counts,
            w,
            h,
            polygon_expectation(&view, floor_corners(1e6, 1e6), 0.05),
        ));
        assert_eq!(
            counts.iter().filter(|&&c| c == 1).count(),
            (w * h / 2) as usize,
            "{name}: below the horizon"
        );
    }

    // Known limitation: with corners at ±1e8 and beyond, the f32 clip-space
    // z of a vertex (error ≈ 1e-7·|z|) no longer resolves the near plane
    // (z = −w at w = near), so the cut through the near plane cannot be placed
    // and the floor goes missing. It must still not panic nor overlap itself.
    for (m, mesh) in floor(big, big).into_iter().enumerate() {
        let scene = smooth(mesh, cam);
        for shading in Shading::ALL {
            render(&scene, &options(w, h, shading)).unwrap();
        }
        let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
        assert!(counts.iter().all(|&c| c <= 1), "huge-floor-mesh{m}");
    }
}

/// The case `extremes::never_panics` found: a y-plane cut between two ends
/// near 1e34 came out with w = 0 and x = −4e23, outside the guard band, and
/// the window coordinate overflowed the rasterizer's edge arithmetic.
#[test]
fn cut_with_both_ends_far_away_does_not_overflow() {
    let mesh = Mesh::from_polygons(
        vec![
            Vec3::new(1.0, 2.011_606_8e34, 1.0),
            Vec3::new(1.0, -5.191_603_6e33, 1.0),
            Vec3::new(1.0, 1.0, -4.608_372e24),
        ],
        [[0u32, 1, 2]],
    )
    .unwrap();
    let cam = Camera {
        eye: Vec3::new(-1.522_326_2, -0.622_656_1, 2.808_611_4),
        target: Vec3::new(-1.288_057_1, 1.367_201_7, -0.045_316_96),
        up: Vec3::Y,
        fov_y_degrees: 70.0,
        near: 1.0,
        far: 258.517,
    };
    let scene = smooth(mesh, cam);
    for shading in Shading::ALL {
        let options = RenderOptions {
            cull_backfaces: false,
            ..options(40, 30, shading)
        };
        render(&scene, &options).unwrap();
        coverage(&scene, &options).unwrap();
    }
}

/// Random triangles with coordinates from 1e-3 to 1e35 in magnitude, seen by
/// random cameras: rendering never panics, and one triangle never covers a
/// pixel twice.
mod extremes {
    use super::*;
    use proptest::prelude::*;

    fn magnitude() -> impl Strategy<Value = f32> {
        (any::<bool>(), -3.0f32..35.0).prop_map(|(negative, e)| {
            if negative {
                -(10f32.powf(e))
            } else {
                10f32.powf(e)
            }
        })
    }

    fn position() -> impl Strategy<Value = Vec3> {
        (magnitude(), magnitude(), magnitude()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(proptest::test_runner::Config { cases: 5000, failure_persistence: None, ..Default::default() })]

        #[test]
        fn never_panics(
            corners in prop::array::uniform3(position()),
            eye in prop::array::uniform3(-5.0f32..5.0),
            target in prop::array::uniform3(-5.0f32..5.0),
            near_far in (-3.0f32..1.0, 1.0f32..30.0),
            cull in any::<bool>(),
        ) {
            let cam = Camera {
                eye: Vec3::from_array(eye),
                target: Vec3::from_array(target),
                up: Vec3::Y,
                fov_y_degrees: 70.0,
                near: 10f32.powf(near_far.0),
                far: 10f32.powf(near_far.0) * near_far.1 * 10.0,
            };
            prop_assume!(cam.validate().is_ok());
            let mesh = Mesh::from_polygons(corners.to_vec(), [[0u32, 1, 2]]).unwrap();
            let scene = smooth(mesh, cam);
            for shading in Shading::ALL {
                let options = RenderOptions { cull_backfaces: cull, ..options(40, 30, shading) };
                render(&scene, &options).unwrap();
            }
            let counts = coverage(&scene, &RenderOptions { cull_backfaces: cull, ..options(40, 30, Shading::Flat) }).unwrap();
            prop_assert!(counts.iter().all(|&c| c <= 1));
        }
    }
}

/// Coordinates so large their transform overflows f32 must not panic.
#[test]
fn overflowing_coordinates_do_not_panic() {
    let (w, h) = (32u32, 24u32);
    let m = f32::MAX;
    let cam = camera(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), 60.0, 0.1, 100.0);
    let meshes = [
        vec![
            Vec3::new(-m, -m, -5.0),
            Vec3::new(m, -m, -5.0),
            Vec3::new(0.0, m, -5.0),
        ],
        vec![
            Vec3::new(-m, -1.0, m),
            Vec3::new(m, -1.0, m),
            Vec3::new(0.0, -1.0, -m),
        ],
        vec![
            Vec3::new(-1.0, -1.0, -5.0),
            Vec3::new(1.0, -1.0, -5.0),
            Vec3::new(0.0, m, -m),
        ],
    ];
    for positions in meshes {
        let mesh = Mesh::from_polygons(positions, [[0u32, 1, 2]]).unwrap();
        let scene = smooth(mesh, cam);
        for shading in Shading::ALL {
            for cull in [true, false] {
                let options = RenderOptions {
                    cull_backfaces: cull,
                    ..options(w, h, shading)
                };
                render(&scene, &options).unwrap();
                let counts = coverage(&scene, &options).unwrap();
                assert!(counts.iter().all(|&c| c <= 1));
            }
        }
    }
}

/// NaN anywhere in the camera or the positions is an error, not a panic;
/// NaN normals render (they are data, not geometry) without panicking.
#[test]
fn nan_is_an_error() {
    let mesh = builtin_model("icosphere", Some(1)).unwrap();
    let good = camera(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 45.0, 0.5, 10.0);
    let nan = f32::NAN;
    let nan3 = Vec3::new(nan, 0.0, 0.0);
    let bad_cameras = [
        (Camera { eye: nan3, ..good }, "eye"),
        (
            Camera {
                target: nan3,
                ..good
            },
            "target",
        ),
        (Camera { up: nan3, ..good }, "up"),
        (
            Camera {
                fov_y_degrees: nan,
                ..good
            },
            "fov_y",
        ),
        (Camera { near: nan, ..good }, "near"),
        (Camera { far: nan, ..good }, "far"),
        (
            Camera {
                eye: Vec3::new(f32::INFINITY, 0.0, 0.0),
                ..good
            },
            "eye",
        ),
        (
            Camera {
                far: f32::INFINITY,
                ..good
            },
            "far",
        ),
    ];
    for (cam, field) in bad_cameras {
        let scene = smooth(mesh.clone(), cam);
        let options = options(16, 16, Shading::Phong);
        let expected = RenderError::Camera(CameraError::NonFinite(field));
        assert_eq!(render(&scene, &options).unwrap_err(), expected);
        assert_eq!(coverage(&scene, &options).unwrap_err(), expected);
    }

    let mut positions = mesh.positions().to_vec();
    positions[3] = nan3;
    let polygons: Vec<Vec<u32>> = (0..mesh.polygon_count())
        .map(|f| mesh.polygon(f).to_vec())
        .collect();
    assert!(matches!(
        Mesh::from_polygons(positions.clone(), polygons.clone()),
        Err(MeshError::NonFinite { vertex: 3, .. })
    ));
    positions[3] = Vec3::new(0.0, f32::NEG_INFINITY, 0.0);
    assert!(matches!(
        Mesh::from_polygons(positions, polygons),
        Err(MeshError::NonFinite { vertex: 3, .. })
    ));

    // NaN normals: no panic, whatever colour comes out.
    let normals = CornerNormals::new(vec![Vec3::splat(nan)], vec![0; mesh.corners().len()]);
    let scene = scene(mesh, normals, good);
    for shading in Shading::ALL {
        let (_, stats) = render(&scene, &options(24, 24, shading)).unwrap();
        assert!(stats.fragments_shaded > 0);
    }
}
