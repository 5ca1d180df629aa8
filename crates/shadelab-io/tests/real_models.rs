//! The real meshes in `../shared/models/` (skipped, with a note, when absent),
//! converted here into every other format — STL binary (with a header
//! beginning `solid`) and ASCII, PLY ASCII and binary little and big endian,
//! glTF with an embedded and with an external buffer, GLB — loaded back,
//! rendered in all three methods, and compared with the OBJ render pixel for
//! pixel.
//!
//! A format can only be compared with an OBJ holding what the format holds:
//! STL keeps triangles and positions (no vertex identity: equal positions are
//! welded), glTF keeps triangles, PLY keeps polygons. Each format's render is
//! therefore compared with the render of its OBJ twin, written here from
//! exactly what the format keeps and loaded by the OBJ loader, and the test
//! asserts where that twin is the model itself: PLY always, glTF for the
//! all-triangle models, STL for the all-triangle models without coincident
//! vertices (all but the teapot, whose 403 coincident vertices STL cannot
//! keep apart; its flat shading, which does not depend on vertex identity,
//! is still compared with the model's). Where the model has normals
//! (Suzanne's `vn`), PLY and glTF carry them too, per vertex, and those
//! renders are compared with the model's own.

mod common;

use std::path::{Path, PathBuf};

use common::*;
use glam::Vec3;
use shadelab_core::{render, Image, Mesh, Shading};
use shadelab_io::{load_mesh, load_obj, SceneFile};

/// Every model of `../shared/models/`, one test each (they run in parallel).
const MODELS: [&str; 7] = [
    "armadillo.obj",
    "cow.obj",
    "dragon_100k.obj",
    "spot.obj",
    "stanford-bunny.obj",
    "suzanne.obj",
    "teapot.obj",
];

const SIZE: u32 = 120;

/// The three renders of a model file: flat, Gouraud, Phong, at a yaw and a
/// pitch so that no view is axis-aligned.
fn renders(path: &Path, normals: &str) -> [Image; 3] {
    let toml = format!(
        "[model]\nsource = {:?}\nnormals = \"{normals}\"\n\
         [render]\nwidth = {SIZE}\nheight = {SIZE}\nyaw = 25\npitch = 15\n",
        path.display().to_string()
    );
    let (scene, options) = SceneFile::parse(&toml, "test.toml")
        .unwrap()
        .resolve(Path::new("/"))
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    Shading::ALL.map(|shading| {
        render(&scene, &shadelab_core::RenderOptions { shading, ..options })
            .unwrap()
            .0
    })
}

#[track_caller]
fn assert_same(what: &str, actual: &[Image; 3], expected: &[Image; 3]) {
    for (k, shading) in Shading::ALL.into_iter().enumerate() {
        assert_same_image(&format!("{what}, {shading:?}"), &actual[k], &expected[k]);
    }
}

#[track_caller]
fn assert_same_image(what: &str, actual: &Image, expected: &Image) {
    assert_eq!(
        (actual.width(), actual.height()),
        (SIZE, SIZE),
        "{what}: image size"
    );
    let differ = actual
        .pixels()
        .iter()
        .zip(expected.pixels())
        .filter(|(a, e)| a != e)
        .count();
    assert!(differ == 0, "{what}: {differ} pixels differ");
}

/// Writes `text` as `name` in `dir`, returning its path.
fn put(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    write(dir, name, bytes)
}

fn round_trip(file: &str) {
    let Some(models) = shared_models() else {
        return;
    };
    let model_path = models.join(file);
    let model = load_obj(&model_path).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let positions = model.positions();
    let polys = polygons(&model);
    let triangles = fan_indices(&polys);
    let tri_polys: Vec<Vec<u32>> = triangles.iter().map(|t| t.to_vec()).collect();
    let all_triangles = polys.iter().all(|p| p.len() == 3);
    let (welded, welded_polys) = weld(positions, &tri_polys);

    // The model's renders, with computed normals (and its own, if it has any).
    let computed = renders(&model_path, "uniform");
    assert!(
        computed[2]
            .pixels()
            .iter()
            .any(|&c| c != computed[2].pixel(0, 0)),
        "{file}: the render shows something"
    );

    // The twins: OBJ files holding what each format keeps.
    let twin_triangles = put(
        dir,
        "twin-triangles.obj",
        obj_text(positions, &tri_polys, None),
    );
    let twin_welded = put(
        dir,
        "twin-welded.obj",
        obj_text(&welded, &welded_polys, None),
    );
    let twin_triangles_mesh = load_obj(&twin_triangles).unwrap();
    let stl_is_the_model = all_triangles && {
        // Welding only drops coincident and unused vertices; the model's
        // used vertices are all distinct when the welded triangles refer
        // to as many vertices as the model's do.
        let used = |polys: &[Vec<u32>]| {
            let mut v: Vec<u32> = polys.iter().flatten().copied().collect();
            v.sort_unstable();
            v.dedup();
            v.len()
        };
        used(&welded_polys) == used(&polys)
    };
    eprintln!(
        "{file}: {} polygons, {}; STL twin {}; {}",
        polys.len(),
        if all_triangles {
            "all triangles"
        } else {
            "not all triangles"
        },
        if stl_is_the_model {
            "is the model"
        } else {
            "welded"
        },
        if model.file_normals().is_some() {
            "with normals"
        } else {
            "no normals"
        }
    );
    if all_triangles {
        assert_eq!(
            twin_triangles_mesh, model,
            "{file}: the triangle twin is the model"
        );
    }
    let expect_triangles = if all_triangles {
        computed.clone()
    } else {
        renders(&twin_triangles, "uniform")
    };
    let expect_welded = if stl_is_the_model {
        computed.clone()
    } else {
        renders(&twin_welded, "uniform")
    };

    // STL, binary (header beginning with "solid") and ASCII.
    let soup: Vec<[Vec3; 3]> = triangles
        .iter()
        .map(|t| t.map(|i| positions[i as usize]))
        .collect();
    let stl_files = [
        put(dir, "model-binary.stl", binary_stl(b"solid model", &soup)),
        put(dir, "model-ascii.stl", ascii_stl("solid model", &soup)),
    ];
    for path in &stl_files {
        let mesh = load_mesh(path).unwrap();
        assert_eq!(
            triangle_set(&mesh),
            triangle_set(&model),
            "{file}: {path:?}"
        );
        let got = renders(path, "uniform");
        assert_same(&format!("{file} as {path:?}"), &got, &expect_welded);
        if all_triangles {
            // Flat shading does not depend on vertex identity.
            assert_same_image(
                &format!("{file} as {path:?}, flat, against the model"),
                &got[0],
                &computed[0],
            );
        }
    }

    // PLY: ASCII, binary little and big endian; polygons and vertices kept.
    let ply_files = [
        put(dir, "model-ascii.ply", ascii_ply(positions, &polys, None)),
        put(
            dir,
            "model-le.ply",
            binary_ply(positions, &polys, None, false),
        ),
        put(
            dir,
            "model-be.ply",
            binary_ply(positions, &polys, None, true),
        ),
    ];
    for path in &ply_files {
        let mesh = load_mesh(path).unwrap();
        assert_eq!(mesh.positions(), positions, "{file}: {path:?}");
        assert_eq!(mesh.corners(), model.corners(), "{file}: {path:?}");
        assert_same(
            &format!("{file} as {path:?}"),
            &renders(path, "uniform"),
            &computed,
        );
    }

    // glTF: embedded buffer, external buffer, GLB; triangles.
    let gltf_files = gltf_variants(dir, "model", positions, &triangles, None);
    for path in &gltf_files {
        let mesh = load_mesh(path).unwrap();
        assert_eq!(
            triangle_set(&mesh),
            triangle_set(&model),
            "{file}: {path:?}"
        );
        assert_same(
            &format!("{file} as {path:?}"),
            &renders(path, "uniform"),
            &expect_triangles,
        );
    }

    // The model's own normals, carried per vertex by PLY and glTF.
    let Some(file_normals) = model.file_normals() else {
        return;
    };
    let own = renders(&model_path, "file");
    let (split_p, split_n, split_polys) = split_by_normal(
        positions,
        &polys,
        &file_normals.normals,
        file_normals.corner(),
    );
    let ply_files = [
        put(
            dir,
            "normals-ascii.ply",
            ascii_ply(&split_p, &split_polys, Some(&split_n)),
        ),
        put(
            dir,
            "normals-le.ply",
            binary_ply(&split_p, &split_polys, Some(&split_n), false),
        ),
        put(
            dir,
            "normals-be.ply",
            binary_ply(&split_p, &split_polys, Some(&split_n), true),
        ),
    ];
    for path in &ply_files {
        assert!(load_mesh(path).unwrap().file_normals().is_some());
        assert_same(
            &format!("{file} with its normals as {path:?}"),
            &renders(path, "file"),
            &own,
        );
    }
    // glTF's twin: the model's triangles, each corner with its own normal.
    let mut corner_of = Vec::new();
    for f in 0..model.polygon_count() {
        let r = model.corner_range(f);
        for k in 1..r.len() - 1 {
            corner_of.extend([r.start, r.start + k, r.start + k + 1]);
        }
    }
    let fan_normals: Vec<u32> = corner_of
        .iter()
        .map(|&c| file_normals.corner()[c])
        .collect();
    let twin = put(
        dir,
        "twin-normals.obj",
        obj_text(
            positions,
            &tri_polys,
            Some((&file_normals.normals, &fan_normals)),
        ),
    );
    let expect = if all_triangles {
        own.clone()
    } else {
        renders(&twin, "file")
    };
    let split_triangles = fan_indices(&split_polys);
    for path in gltf_variants(dir, "normals", &split_p, &split_triangles, Some(&split_n)) {
        assert!(load_mesh(&path).unwrap().file_normals().is_some());
        assert_same(
            &format!("{file} with its normals as {path:?}"),
            &renders(&path, "file"),
            &expect,
        );
    }
}

/// The mesh as `.gltf` with an embedded buffer, `.gltf` with a `.bin` beside
/// it, and `.glb`.
fn gltf_variants(
    dir: &Path,
    stem: &str,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    normals: Option<&[Vec3]>,
) -> [PathBuf; 3] {
    let (json, _) = mesh_gltf(positions, triangles, normals, GltfBuffer::Embedded);
    let embedded = put(dir, &format!("{stem}-embedded.gltf"), json);
    let bin_name: &'static str = if stem == "model" {
        "model buffer.bin"
    } else {
        "normals buffer.bin"
    };
    let (json, bin) = mesh_gltf(
        positions,
        triangles,
        normals,
        GltfBuffer::External(if stem == "model" {
            "model%20buffer.bin"
        } else {
            "normals%20buffer.bin"
        }),
    );
    put(dir, bin_name, bin);
    let external = put(dir, &format!("{stem}-external.gltf"), json);
    let (json, bin) = mesh_gltf(positions, triangles, normals, GltfBuffer::Glb);
    let binary = put(dir, &format!("{stem}.glb"), glb(&json, &bin));
    [embedded, external, binary]
}

#[test]
fn every_shared_model_is_tested() {
    let Some(models) = shared_models() else {
        return;
    };
    let mut found: Vec<String> = std::fs::read_dir(models)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".obj"))
        .collect();
    found.sort();
    assert_eq!(found, MODELS, "add the new models to MODELS");
}

macro_rules! model_tests {
    ($($name:ident: $file:literal,)*) => {
        $(
            #[test]
            fn $name() {
                round_trip($file);
            }
        )*
    };
}

model_tests! {
    armadillo: "armadillo.obj",
    cow: "cow.obj",
    dragon_100k: "dragon_100k.obj",
    spot: "spot.obj",
    stanford_bunny: "stanford-bunny.obj",
    suzanne: "suzanne.obj",
    teapot: "teapot.obj",
}

#[test]
fn the_twins_are_what_the_formats_keep() {
    // On a small mesh with a quad and a coincident vertex: the triangle twin
    // splits the quad as the fans do, the welded twin merges the two
    // vertices at the same place.
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(-0.0, 1.0, 0.0),
        Vec3::new(-1.0, 0.5, 0.0),
    ];
    let polys = vec![vec![0, 1, 2, 3], vec![0, 4, 5]];
    let tri: Vec<Vec<u32>> = fan_indices(&polys).iter().map(|t| t.to_vec()).collect();
    assert_eq!(tri, vec![vec![0, 1, 2], vec![0, 2, 3], vec![0, 4, 5]]);
    let (welded, welded_polys) = weld(&positions, &tri);
    assert_eq!(welded.len(), 5);
    assert_eq!(welded_polys[2], vec![0, 3, 4]);
    let mesh = Mesh::from_polygons(welded, welded_polys).unwrap();
    assert_eq!(mesh.polygon_count(), 3);
}
