//! OBJ smoothing groups (`s`) and materials (`mtllib`, `usemtl`, `.mtl`):
//! groups reach the mesh and render as the mesh cut apart along them;
//! materials seed the scene's colours where it sets none, and never make
//! loading fail.

mod common;

use std::path::{Path, PathBuf};

use common::{polygons, write};
use glam::Vec3;
use shadelab_core::{
    builtin_model, render, Image, Mesh, Rasterizer, RenderOptions, Rgb, Rgb8, Shading,
};
use shadelab_io::{
    load_mesh, load_mesh_file, load_obj, load_obj_file, parse_obj, parse_obj_file, FileMaterial,
    LoadError, SceneFile,
};

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

fn groups_of(text: &str) -> Option<Vec<u32>> {
    parse_obj(text, "test.obj")
        .unwrap_or_else(|e| panic!("{e}"))
        .smoothing_groups()
        .map(<[u32]>::to_vec)
}

#[track_caller]
fn assert_syntax(text: &str, line: usize, needle: &str) {
    match parse_obj(text, "g.obj") {
        Err(LoadError::Syntax {
            line: l, message, ..
        }) => {
            assert_eq!(l, line, "{message}");
            assert!(message.contains(needle), "{message:?} lacks {needle:?}");
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

// ---------------------------------------------------------------- smoothing groups

#[test]
fn s_statements_become_smoothing_groups() {
    let faces = "f 1 2 3\n";
    // No `s` anywhere: no groups, every face may be smoothed.
    assert_eq!(groups_of(&format!("{TRIANGLE}{faces}{faces}")), None);
    // Faces before the first `s` are in none; `off` and 0 are none.
    let text = format!(
        "{TRIANGLE}{faces}s 1\n{faces}{faces}s off\n{faces}s 0\n{faces}s 2 # comment\n{faces}\
         s OFF\n{faces}s 4294967295\n{faces}s 1\n{faces}"
    );
    assert_eq!(
        groups_of(&text),
        Some(vec![0, 1, 1, 0, 0, 2, 0, u32::MAX, 1])
    );
    // A trailing `s` with no face after it still means the file has groups.
    assert_eq!(groups_of(&format!("{TRIANGLE}{faces}s 5\n")), Some(vec![0]));
    // Objects and groups do not reset the smoothing group.
    assert_eq!(
        groups_of(&format!("{TRIANGLE}s 3\n{faces}o b\ng c\n{faces}")),
        Some(vec![3, 3])
    );
}

#[test]
fn bad_smoothing_groups_are_syntax_errors() {
    assert_syntax(&format!("{TRIANGLE}s on\nf 1 2 3\n"), 4, "`s` takes");
    assert_syntax(&format!("{TRIANGLE}s\nf 1 2 3\n"), 4, "found ``");
    assert_syntax(&format!("{TRIANGLE}s -1\nf 1 2 3\n"), 4, "-1");
    assert_syntax(
        &format!("{TRIANGLE}s 4294967296\nf 1 2 3\n"),
        4,
        "4294967296",
    );
    assert_syntax(&format!("{TRIANGLE}s 1 2\nf 1 2 3\n"), 4, "`1 2`");
}

/// A unit UV sphere as OBJ text: `slices` × `stacks` quads (triangles at the
/// poles), one `s` statement before each face from `group(face centre)`.
fn sphere_obj(slices: u32, stacks: u32, group: impl Fn(Vec3) -> Option<u32>) -> String {
    let mesh = builtin_model("sphere", Some(slices)).unwrap();
    assert_eq!(mesh.polygon_count() as u32, slices * stacks);
    let mut text = String::new();
    for p in mesh.positions() {
        text += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for f in 0..mesh.polygon_count() {
        let poly = mesh.polygon(f);
        let centre = poly
            .iter()
            .map(|&i| mesh.positions()[i as usize])
            .sum::<Vec3>()
            / poly.len() as f32;
        match group(centre) {
            Some(g) => text += &format!("s {g}\n"),
            None => text += "s off\n",
        }
        text.push('f');
        for &i in poly {
            text += &format!(" {}", i + 1);
        }
        text.push('\n');
    }
    text
}

/// The same mesh with one vertex copy per (vertex, group), and per (vertex,
/// face) for faces in no group, as OBJ text with no `s` statement.
fn cut_apart(mesh: &Mesh) -> String {
    let groups = mesh.smoothing_groups().unwrap();
    let mut copies = std::collections::HashMap::new();
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for (f, poly) in polygons(mesh).into_iter().enumerate() {
        let key = if groups[f] == Mesh::NOT_SMOOTHED {
            u64::MAX - f as u64
        } else {
            u64::from(groups[f])
        };
        faces.push(
            poly.iter()
                .map(|&v| {
                    *copies.entry((v, key)).or_insert_with(|| {
                        positions.push(mesh.positions()[v as usize]);
                        positions.len() as u32 - 1
                    })
                })
                .collect::<Vec<u32>>(),
        );
    }
    common::obj_text(&positions, &faces, None)
}

fn render_file(path: &Path, rasterizer: Rasterizer, shading: Shading, size: u32) -> Image {
    let toml = format!(
        "[model]\nsource = {:?}\n[render]\nwidth = {size}\nheight = {size}\nyaw = 20\npitch = 25\n\
         rasterizer = \"{}\"\n",
        path.display().to_string(),
        rasterizer.name()
    );
    let (scene, options) = SceneFile::parse(&toml, "t.toml")
        .unwrap()
        .resolve(Path::new("/"))
        .unwrap();
    render(&scene, &RenderOptions { shading, ..options })
        .unwrap()
        .0
}

/// A sphere in three groups — left, right and a faceted cap — renders
/// exactly as the sphere cut apart along them, in every method and with
/// both rasterizers; and differently from the sphere without groups.
#[test]
fn groups_render_as_the_mesh_cut_apart() {
    let dir = tempfile::tempdir().unwrap();
    let text = sphere_obj(12, 6, |c| {
        if c.y > 0.6 {
            None
        } else if c.x > 0.0 {
            Some(1)
        } else {
            Some(2)
        }
    });
    let grouped = write(dir.path(), "grouped.obj", &text);
    let mesh = load_obj(&grouped).unwrap();
    let groups = mesh.smoothing_groups().unwrap();
    assert!(groups.contains(&0) && groups.contains(&1) && groups.contains(&2));
    let cut = write(dir.path(), "cut.obj", cut_apart(&mesh));
    let plain = write(
        dir.path(),
        "plain.obj",
        text.lines()
            .filter(|l| !l.starts_with('s'))
            .map(|l| format!("{l}\n"))
            .collect::<String>(),
    );
    for rasterizer in Rasterizer::ALL {
        for shading in Shading::ALL {
            let a = render_file(&grouped, rasterizer, shading, 96);
            let b = render_file(&cut, rasterizer, shading, 96);
            assert!(
                a == b,
                "{rasterizer:?} {shading:?}: groups differ from the cut"
            );
            let c = render_file(&plain, rasterizer, shading, 96);
            if shading != Shading::Flat {
                assert!(a != c, "{rasterizer:?} {shading:?}: groups change nothing");
            } else {
                assert!(a == c, "flat shading does not use vertex normals");
            }
        }
    }
}

// ---------------------------------------------------------------- materials

const MTL: &str = "\
# two materials
newmtl blue
Ka 0.2 0.2 0.6
Kd 0.2 0.6 1
newmtl grey
Kd 0.4
";

/// Writes `obj` (and `mtl` files given as (name, text)) into a new directory.
fn files(obj: &str, mtls: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in mtls {
        write(dir.path(), name, text);
    }
    let path = write(dir.path(), "model.obj", obj);
    (dir, path)
}

fn material_of(obj: &str, mtls: &[(&str, &str)]) -> Option<FileMaterial> {
    let (_dir, path) = files(obj, mtls);
    let file = load_obj_file(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(file.mesh, load_obj(&path).unwrap(), "same geometry");
    file.material
}

fn rgb(r: f32, g: f32, b: f32) -> Option<Rgb> {
    Some(Rgb::new(r, g, b))
}

#[test]
fn the_material_on_the_most_faces_gives_the_colours() {
    let obj = format!(
        "mtllib lib.mtl\n{TRIANGLE}usemtl grey\nf 1 2 3\nusemtl blue\nf 1 2 3\nf 1 2 3\n\
         usemtl grey\nf 1 2 3\nusemtl blue\nf 1 2 3\n"
    );
    assert_eq!(
        material_of(&obj, &[("lib.mtl", MTL)]),
        Some(FileMaterial {
            name: "blue".into(),
            library: "lib.mtl".into(),
            ka: rgb(0.2, 0.2, 0.6),
            kd: rgb(0.2, 0.6, 1.0),
        })
    );
    // A tie goes to the material used first; a one-value Kd is grey.
    let obj = format!(
        "mtllib lib.mtl\n{TRIANGLE}usemtl grey\nf 1 2 3\nusemtl blue\nf 1 2 3\nusemtl missing\n\
         f 1 2 3\nf 1 2 3\nf 1 2 3\nusemtl blue\n"
    );
    let m = material_of(&obj, &[("lib.mtl", MTL)]);
    // `missing` is on the most faces but no library defines it: no material.
    assert_eq!(m, None);
    let obj = format!("mtllib lib.mtl\n{TRIANGLE}usemtl grey\nf 1 2 3\nusemtl blue\nf 1 2 3\n");
    let m = material_of(&obj, &[("lib.mtl", MTL)]).unwrap();
    assert_eq!(
        (m.name.as_str(), m.ka, m.kd),
        ("grey", None, rgb(0.4, 0.4, 0.4))
    );
    // Faces without a material do not count; `usemtl` with no name ends one.
    let obj = format!(
        "mtllib lib.mtl\n{TRIANGLE}f 1 2 3\nf 1 2 3\nusemtl grey\nf 1 2 3\nusemtl\nf 1 2 3\n\
         f 1 2 3\nusemtl blue\n"
    );
    assert_eq!(material_of(&obj, &[("lib.mtl", MTL)]).unwrap().name, "grey");
}

#[test]
fn libraries_are_found_as_exporters_write_them() {
    let obj = |mtllib: &str| format!("{mtllib}\n{TRIANGLE}usemtl grey\nf 1 2 3\n");
    // Several libraries in one statement, the material in the second.
    let m = material_of(
        &obj("mtllib first.mtl second.mtl"),
        &[
            ("first.mtl", "newmtl other\nKd 1 0 0\n"),
            ("second.mtl", MTL),
        ],
    )
    .unwrap();
    assert_eq!(m.library, "second.mtl");
    // One name with a blank in it.
    let m = material_of(&obj("mtllib my lib.mtl"), &[("my lib.mtl", MTL)]).unwrap();
    assert_eq!(m.library, "my lib.mtl");
    // Two statements; the first library that defines the name wins.
    let m = material_of(
        &obj("mtllib a.mtl\nmtllib b.mtl"),
        &[("a.mtl", "newmtl grey\nKd 0 1 0\n"), ("b.mtl", MTL)],
    )
    .unwrap();
    assert_eq!((m.library.as_str(), m.kd), ("a.mtl", rgb(0.0, 1.0, 0.0)));
    // A library in a subdirectory, named relative to the OBJ file.
    let m = material_of(&obj("mtllib sub/lib.mtl"), &[("sub/lib.mtl", MTL)]);
    assert_eq!(m.unwrap().library, "sub/lib.mtl");
}

/// Nothing about materials makes loading fail, and nothing is reported:
/// the mesh loads and has no material.
#[test]
fn material_problems_are_silent_fallbacks() {
    let obj = |mtllib: &str| format!("{mtllib}\n{TRIANGLE}usemtl blue\nf 1 2 3\n");
    let no_material: &[(&str, &[(&str, &str)])] = &[
        ("mtllib absent.mtl", &[]),
        ("mtllib", &[]),
        ("", &[("lib.mtl", MTL)]),
        ("mtllib lib.mtl", &[("lib.mtl", "")]),
        (
            "mtllib lib.mtl",
            &[("lib.mtl", "newmtl blue\nKd one two three\nKa\n")],
        ),
        (
            "mtllib lib.mtl",
            &[("lib.mtl", "newmtl blue\nKs 1 1 1\nNs 20\nmap_Kd tex.png\n")],
        ),
        (
            "mtllib lib.mtl",
            &[("lib.mtl", "newmtl blue\nKd 1 0\nKd 0.5 0.5 0.5 0.5\n")],
        ),
        ("mtllib lib.mtl", &[("lib.mtl", "newmtl BLUE\nKd 1 0 0\n")]),
        ("mtllib .", &[]),
        ("mtllib /nonexistent/dir/lib.mtl", &[]),
    ];
    for (mtllib, mtls) in no_material {
        assert_eq!(material_of(&obj(mtllib), mtls), None, "{mtllib:?} {mtls:?}");
    }
    // Not UTF-8: read lossily; the material line itself is intact.
    let (_dir, path) = files(&obj("mtllib lib.mtl"), &[]);
    std::fs::write(
        path.with_file_name("lib.mtl"),
        b"\xff\xfe\x00junk\nnewmtl blue\nKd 0 0 1\n",
    )
    .unwrap();
    assert_eq!(
        load_obj_file(&path).unwrap().material.unwrap().kd,
        rgb(0.0, 0.0, 1.0)
    );
    // `usemtl` before any `mtllib`, or without faces, is fine too.
    assert!(parse_obj(&format!("usemtl x\n{TRIANGLE}f 1 2 3\nusemtl y\n"), "m.obj").is_ok());
}

#[test]
fn parse_obj_file_asks_for_each_library() {
    let mut asked = Vec::new();
    let file = parse_obj_file(
        &format!("mtllib a.mtl b.mtl\nmtllib c.mtl\n{TRIANGLE}usemtl blue\nf 1 2 3\n"),
        "m.obj",
        &mut |name| {
            asked.push(name.to_owned());
            (name == "c.mtl").then(|| MTL.to_owned())
        },
    )
    .unwrap();
    assert_eq!(asked, ["a.mtl b.mtl", "a.mtl", "b.mtl", "c.mtl"]);
    // A library named again is not read again.
    let mut asked = Vec::new();
    parse_obj_file(
        &format!(
            "mtllib a.mtl\nmtllib a.mtl a.mtl\nmtllib a.mtl\n{TRIANGLE}usemtl blue\nf 1 2 3\n"
        ),
        "m.obj",
        &mut |name| {
            asked.push(name.to_owned());
            None
        },
    )
    .unwrap();
    assert_eq!(asked, ["a.mtl", "a.mtl a.mtl"]);
    assert_eq!(file.material.unwrap().library, "c.mtl");
    // No material used: no library is read.
    let mut asked = 0;
    parse_obj_file(
        &format!("mtllib a.mtl\n{TRIANGLE}f 1 2 3\n"),
        "m.obj",
        &mut |_| {
            asked += 1;
            None
        },
    )
    .unwrap();
    assert_eq!(asked, 0);
}

#[test]
fn other_formats_have_no_material_and_load_mesh_agrees() {
    let (dir, path) = files(
        &format!("mtllib lib.mtl\n{TRIANGLE}usemtl blue\nf 1 2 3\n"),
        &[("lib.mtl", MTL)],
    );
    let file = load_mesh_file(&path).unwrap();
    assert_eq!(file.material.unwrap().name, "blue");
    assert_eq!(load_mesh(&path).unwrap(), file.mesh);
    let stl = write(
        dir.path(),
        "t.stl",
        common::ascii_stl("solid t", &[[Vec3::ZERO, Vec3::X, Vec3::Y]]),
    );
    assert_eq!(load_mesh_file(&stl).unwrap().material, None);
}

// ---------------------------------------------------------------- materials in scenes

fn scene_material(scene_toml: &str, dir: &Path) -> (Rgb, Rgb) {
    let (scene, _) = SceneFile::parse(scene_toml, "s.toml")
        .unwrap()
        .resolve(dir)
        .unwrap();
    (scene.material.ka, scene.material.kd)
}

#[test]
fn the_file_material_fills_in_what_the_scene_leaves_unset() {
    let blue_ka = Rgb::new(0.2, 0.2, 0.6);
    let blue_kd = Rgb::new(0.2, 0.6, 1.0);
    let default = Rgb8::new(200, 60, 60).to_rgb();
    let (dir, _) = files(
        &format!("mtllib lib.mtl\n{TRIANGLE}usemtl blue\nf 1 2 3\n"),
        &[("lib.mtl", MTL)],
    );
    let d = dir.path();
    write(
        d,
        "grey.obj",
        format!("mtllib lib.mtl\n{TRIANGLE}usemtl grey\nf 1 2 3\n"),
    );
    write(d, "plain.obj", format!("{TRIANGLE}f 1 2 3\n"));
    let model = "[model]\nsource = \"model.obj\"\n";
    assert_eq!(scene_material(model, d), (blue_ka, blue_kd));
    let kd = Rgb8::new(10, 20, 30).to_rgb();
    let ka = Rgb8::new(40, 50, 60).to_rgb();
    assert_eq!(
        scene_material(&format!("{model}[material]\nkd = [10, 20, 30]\n"), d),
        (blue_ka, kd),
        "the scene's kd wins, ka still from the file"
    );
    assert_eq!(
        scene_material(&format!("{model}[material]\nka = [40, 50, 60]\n"), d),
        (ka, blue_kd)
    );
    // No Ka in the material: ka takes its Kd.
    let grey = Rgb::splat(0.4);
    assert_eq!(
        scene_material("[model]\nsource = \"grey.obj\"\n", d),
        (grey, grey)
    );
    // No material: the defaults.
    assert_eq!(
        scene_material("[model]\nsource = \"plain.obj\"\n", d),
        (default, default)
    );
    assert_eq!(
        scene_material("[model]\nsource = \"cube\"\n", d),
        (default, default)
    );
}

/// The README's example, `docs/examples/groups.obj`: three smoothing groups
/// (two halves and a faceted cap) and a teal material from `groups.mtl`.
#[test]
fn the_documented_example() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/examples/groups.obj");
    let file = load_obj_file(&path).unwrap();
    let mut groups = file.mesh.smoothing_groups().unwrap().to_vec();
    assert_eq!(groups.len(), 16 * 8);
    groups.sort_unstable();
    groups.dedup();
    assert_eq!(groups, [0, 1, 2]);
    let material = file.material.unwrap();
    assert_eq!(
        (material.name.as_str(), material.library.as_str()),
        ("teal", "groups.mtl")
    );
    assert_eq!(material.ka, Some(Rgb::new(0.1, 0.5, 0.5)));
    assert_eq!(material.kd, Some(Rgb::new(0.2, 0.7, 0.7)));
}
