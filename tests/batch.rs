//! `shadelab batch` end to end: the real binary in temporary directories,
//! killed mid-run, sharded, fed broken meshes, CSV and JSON Lines.

mod support;

use support::*;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A UV sphere as OBJ text: `slices` around, `slices / 2` stacks, triangles.
fn sphere_obj(slices: u32) -> String {
    let stacks = slices / 2;
    let mut text = String::new();
    for i in 0..=stacks {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let phi = std::f32::consts::TAU * j as f32 / slices as f32;
            text += &format!(
                "v {} {} {}\n",
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin()
            );
        }
    }
    let at = |i: u32, j: u32| i * slices + (j % slices) + 1;
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            text += &format!("f {a} {d} {c}\nf {a} {c} {b}\n");
        }
    }
    text
}

/// A unit cube as OBJ text (quads, counter-clockwise from outside).
const CUBE_OBJ: &str =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

/// The index's rows.
fn index(path: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{l:?}: {e}")))
        .collect()
}

fn rows_with<'a>(rows: &'a [serde_json::Value], status: &str) -> Vec<&'a serde_json::Value> {
    rows.iter().filter(|r| r["status"] == status).collect()
}

/// Decodes a PNG fully: (width, height, RGB bytes).
fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::fs::File::open(path).unwrap();
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader
        .next_frame(&mut buf)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Every file under `dir` whose name ends with `.png`, relative to `dir`.
fn pngs(dir: &Path) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let entry = entry.unwrap();
        let path = entry.path();
        if path.is_dir() {
            let sub = entry.file_name().to_string_lossy().into_owned();
            out.extend(pngs(&path).into_iter().map(|p| format!("{sub}/{p}")));
        } else if path.extension().is_some_and(|e| e == "png") {
            out.insert(entry.file_name().to_string_lossy().into_owned());
        }
    }
    out
}

#[test]
fn json_lines_and_csv_give_the_same_images_and_per_line_overrides_apply() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::create_dir(dir.join("meshes")).unwrap();
    std::fs::write(dir.join("meshes/ball.obj"), sphere_obj(16)).unwrap();
    std::fs::write(dir.join("meshes/box.obj"), CUBE_OBJ).unwrap();
    std::fs::write(
        dir.join("list.jsonl"),
        "{\"path\": \"meshes/ball.obj\"}\n\
         {\"path\": \"meshes/box.obj\", \"id\": \"box\", \"views\": 2, \"size\": \"40x30\", \"shading\": \"all\"}\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("list.csv"),
        "path,id,views,size,shading\nmeshes/ball.obj,,,,\nmeshes/box.obj,box,2,40x30,all\n",
    )
    .unwrap();
    let common = ["--views", "cube", "--size", "64x48", "--progress", "none"];
    for (manifest, out) in [("list.jsonl", "a"), ("list.csv", "b")] {
        let mut args = vec!["batch", manifest, "-o", out];
        args.extend(common);
        assert_ok(&run(dir, &args));
    }
    let want: BTreeSet<String> = ["front", "right", "back", "left", "top", "bottom"]
        .iter()
        .map(|v| format!("meshes_ball/{v}_phong.png"))
        .chain(
            ["v00", "v01"]
                .iter()
                .flat_map(|v| ["flat", "gouraud", "phong"].map(|m| format!("box/{v}_{m}.png"))),
        )
        .collect();
    assert_eq!(pngs(&dir.join("a")), want);
    assert_eq!(pngs(&dir.join("b")), want);
    for name in &want {
        let a = decode(&dir.join("a").join(name));
        assert_eq!(a, decode(&dir.join("b").join(name)), "{name}");
        let size = if name.starts_with("box") {
            (40, 30)
        } else {
            (64, 48)
        };
        assert_eq!((a.0, a.1), size, "{name}");
    }
    let rows = index(&dir.join("a/index.jsonl"));
    assert_eq!(rows.len(), want.len());
    assert_eq!(rows_with(&rows, "ok").len(), want.len());
    let row = rows
        .iter()
        .find(|r| r["file"] == "box/v01_gouraud.png")
        .unwrap();
    assert_eq!(
        (
            &row["id"],
            &row["view"],
            &row["mode"],
            &row["triangles"],
            &row["line"]
        ),
        (
            &serde_json::json!("box"),
            &serde_json::json!("v01"),
            &serde_json::json!("gouraud"),
            &serde_json::json!(12),
            &serde_json::json!(2)
        )
    );
    assert!(row["ms"].as_f64().unwrap() > 0.0 && row["error"].is_null());

    // A view is the render command's image with the view's yaw added.
    assert_ok(&run(
        dir,
        &[
            "render",
            "--model",
            "meshes/box.obj",
            "--size",
            "40x30",
            "--yaw",
            "180",
            "--shading",
            "gouraud",
            "-o",
            "single.png",
        ],
    ));
    assert_eq!(
        decode(&dir.join("single.png")).2,
        decode(&dir.join("a/box/v01_gouraud.png")).2
    );
}

#[test]
fn a_scene_file_gives_shared_settings_and_flags_override_it() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("box.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.join("m.jsonl"), "{\"path\": \"box.obj\"}\n").unwrap();
    std::fs::write(
        dir.join("s.toml"),
        "[render]\nwidth = 50\nheight = 40\nshading = \"flat\"\nbackground = [10, 20, 30]\npitch = 20\n",
    )
    .unwrap();
    let out = run(
        dir,
        &[
            "batch",
            "m.jsonl",
            "-o",
            "out",
            "--scene",
            "s.toml",
            "--kd",
            "0,200,0",
            "--progress",
            "none",
        ],
    );
    assert_ok(&out);
    assert_ok(&run(
        dir,
        &[
            "render", "s.toml", "--model", "box.obj", "--kd", "0,200,0", "-o", "r.png",
        ],
    ));
    let batch = decode(&dir.join("out/box/v00_flat.png"));
    assert_eq!((batch.0, batch.1), (50, 40));
    assert_eq!(batch, decode(&dir.join("r.png")));
    let err = run(dir, &["batch", "m.jsonl", "-o", "o2", "--model", "teapot"]);
    assert_eq!(err.status.code(), Some(2), "{}", stderr(&err));
    assert!(stderr(&err).contains("--model"));
}

#[test]
fn broken_meshes_become_error_rows_and_the_run_goes_on() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    let dir = root.join("set");
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("good.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.join("big.obj"), sphere_obj(64)).unwrap();
    std::fs::write(root.join("outside.obj"), CUBE_OBJ).unwrap();
    std::fs::write(
        dir.join("m.jsonl"),
        [
            r#"{"path": "good.obj"}"#,
            r#"{"path": "missing.obj"}"#,
            r#"{"path": "bad.obj"}"#,
            r#"this is not json"#,
            r#"{"path": "big.obj"}"#,
            r#"{"path": "../outside.obj"}"#,
            r#"{"path": "good.obj", "id": "good"}"#,
            r#"{"path": "good.obj", "id": "../escape"}"#,
            r#"{"path": "good.obj", "views": 0}"#,
            r#"{"path": "good.obj", "id": "second"}"#,
        ]
        .join("\n"),
    )
    .unwrap();
    let args = [
        "batch",
        "set/m.jsonl",
        "-o",
        "out",
        "--size",
        "32x32",
        "--max-mesh-bytes",
        "20000",
        "--progress",
        "lines",
    ];
    let out = run(root, &args);
    assert_ok(&out);
    let err = stderr(&out);
    assert!(
        err.contains("8 meshes: 2 images written, 0 already there, 6 failed (6 meshes), 2 bad manifest lines"),
        "{err}"
    );
    let rows = index(&root.join("out/index.jsonl"));
    let by_line: BTreeMap<u64, &serde_json::Value> = rows
        .iter()
        .map(|r| (r["line"].as_u64().unwrap(), r))
        .collect();
    assert_eq!(by_line.len(), 10, "one row per line: {rows:#?}");
    let error = |line: u64| -> String {
        let r = by_line[&line];
        assert_eq!(r["status"], "error", "line {line}: {r}");
        r["error"].as_str().unwrap().to_owned()
    };
    assert_eq!(by_line[&1]["status"], "ok");
    assert!(error(2).contains("missing.obj"), "{}", error(2));
    assert!(error(3).contains("bad.obj"), "{}", error(3));
    assert!(error(4).contains("m.jsonl:4"), "{}", error(4));
    assert!(
        error(5).contains("more than the limit of 20000 bytes"),
        "{}",
        error(5)
    );
    assert!(error(6).contains("outside"), "{}", error(6));
    assert!(error(7).contains("already used on line 1"), "{}", error(7));
    assert!(error(8).contains("not usable"), "{}", error(8));
    assert!(error(9).contains("views"), "{}", error(9));
    assert_eq!(by_line[&10]["status"], "ok");
    assert_eq!(
        pngs(&root.join("out")),
        BTreeSet::from([
            "good/v00_phong.png".to_owned(),
            "second/v00_phong.png".to_owned()
        ])
    );
    assert!(!root.join("escape").exists());
    for line in 2..=9 {
        assert!(
            err.contains(&format!("m.jsonl:{line}")),
            "line {line} not reported:\n{err}"
        );
    }

    let strict = run(root, &[&args[..], &["--strict"]].concat());
    assert_eq!(strict.status.code(), Some(3), "{}", stderr(&strict));
    assert!(stderr(&strict).contains("--strict"), "{}", stderr(&strict));
    // Nothing was drawn again: both good outputs were complete.
    let rows = index(&root.join("out/index.jsonl"));
    assert_eq!(rows_with(&rows, "skipped").len(), 2);
    assert_eq!(rows_with(&rows, "ok").len(), 0);
}

#[test]
fn shards_cover_the_manifest_exactly_once() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("box.obj"), CUBE_OBJ).unwrap();
    let mut manifest: String = (0..30)
        .map(|k| format!("{{\"path\": \"box.obj\", \"id\": \"m{k:02}\"}}\n"))
        .collect();
    manifest += "not json\n{\"oops\": 1}\n";
    std::fs::write(dir.join("m.jsonl"), manifest).unwrap();
    let n = 4;
    let mut owners: BTreeMap<String, Vec<u32>> = BTreeMap::new();
    let mut bad_lines = Vec::new();
    for i in 0..n {
        let shard = format!("{i}/{n}");
        assert_ok(&run(
            dir,
            &[
                "batch",
                "m.jsonl",
                "-o",
                "out",
                "--size",
                "16x16",
                "--shard",
                &shard,
                "--progress",
                "none",
            ],
        ));
        for row in index(&dir.join(format!("out/index-{i}-of-{n}.jsonl"))) {
            match row["id"].as_str() {
                Some(id) => {
                    assert_eq!(row["status"], "ok", "{row}");
                    owners.entry(id.to_owned()).or_default().push(i);
                }
                None => bad_lines.push(row["line"].as_u64().unwrap()),
            }
        }
    }
    assert_eq!(owners.len(), 30);
    assert!(owners.values().all(|o| o.len() == 1), "{owners:?}");
    let used: BTreeSet<u32> = owners.values().map(|o| o[0]).collect();
    assert!(used.len() > 1, "every id in one shard: {owners:?}");
    bad_lines.sort();
    assert_eq!(bad_lines, [31, 32]);
    assert_eq!(pngs(&dir.join("out")).len(), 30);
    // The same share every time, whatever the order of the manifest.
    let reversed: String = std::fs::read_to_string(dir.join("m.jsonl"))
        .unwrap()
        .lines()
        .rev()
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.join("r.jsonl"), reversed).unwrap();
    assert_ok(&run(
        dir,
        &[
            "batch",
            "r.jsonl",
            "-o",
            "again",
            "--size",
            "16x16",
            "--shard",
            "1/4",
            "--progress",
            "none",
        ],
    ));
    let again: BTreeSet<String> = index(&dir.join("again/index-1-of-4.jsonl"))
        .iter()
        .filter_map(|r| r["id"].as_str().map(str::to_owned))
        .collect();
    let before: BTreeSet<String> = owners
        .iter()
        .filter(|(_, o)| o[0] == 1)
        .map(|(id, _)| id.clone())
        .collect();
    assert_eq!(again, before);
}

#[test]
fn a_run_killed_midway_resumes_without_partial_images_or_repeated_work() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("ball.obj"), sphere_obj(200)).unwrap();
    let meshes = 40;
    let manifest: String = (0..meshes)
        .map(|k| format!("{{\"path\": \"ball.obj\", \"id\": \"b{k:02}\"}}\n"))
        .collect();
    std::fs::write(dir.join("m.jsonl"), manifest).unwrap();
    let args = [
        "batch",
        "m.jsonl",
        "-o",
        "out",
        "--size",
        "320x320",
        "--views",
        "6",
        "--shading",
        "all",
        "--png",
        "small",
        "--progress",
        "none",
    ];
    let total = meshes * 18;

    let mut child = Command::new(bin())
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        let done = dir
            .join("out")
            .is_dir()
            .then(|| pngs(&dir.join("out")).len());
        if done.is_some_and(|d| d >= 20) {
            break;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before it could be killed"
        );
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "no output after 2 minutes"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();

    // Whatever is named .png is whole; record what was complete.
    let before = pngs(&dir.join("out"));
    assert!(
        before.len() < total,
        "the kill came too late to test anything"
    );
    let mut stamps = BTreeMap::new();
    for name in &before {
        let path = dir.join("out").join(name);
        decode(&path);
        let meta = std::fs::metadata(&path).unwrap();
        use std::os::unix::fs::MetadataExt;
        stamps.insert(name.clone(), (meta.ino(), meta.mtime_nsec(), meta.mtime()));
    }

    assert_ok(&run(dir, &args));
    let rows = index(&dir.join("out/index.jsonl"));
    assert_eq!(rows.len(), total);
    let skipped: BTreeSet<String> = rows_with(&rows, "skipped")
        .iter()
        .map(|r| r["file"].as_str().unwrap().to_owned())
        .collect();
    assert_eq!(skipped, before, "exactly the complete outputs are skipped");
    assert_eq!(rows_with(&rows, "ok").len(), total - before.len());
    for (name, stamp) in &stamps {
        let meta = std::fs::metadata(dir.join("out").join(name)).unwrap();
        use std::os::unix::fs::MetadataExt;
        assert_eq!(
            &(meta.ino(), meta.mtime_nsec(), meta.mtime()),
            stamp,
            "{name} was written again"
        );
    }
    let after = pngs(&dir.join("out"));
    assert_eq!(after.len(), total);
    for name in &after {
        decode(&dir.join("out").join(name));
    }

    // A third run has nothing to do; --force redoes everything.
    assert_ok(&run(dir, &args));
    assert_eq!(
        rows_with(&index(&dir.join("out/index.jsonl")), "skipped").len(),
        total
    );
    let forced = run(
        dir,
        &[
            "batch",
            "m.jsonl",
            "-o",
            "out",
            "--size",
            "320x320",
            "--shading",
            "all",
            "--force",
            "--progress",
            "none",
        ],
    );
    assert_ok(&forced);
    assert_eq!(
        rows_with(&index(&dir.join("out/index.jsonl")), "ok").len(),
        meshes * 3
    );
}

#[test]
fn a_truncated_output_is_not_taken_as_complete() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("box.obj"), CUBE_OBJ).unwrap();
    std::fs::write(dir.join("m.csv"), "path,id\nbox.obj,box\n").unwrap();
    let args = [
        "batch",
        "m.csv",
        "-o",
        "out",
        "--size",
        "24x24",
        "--progress",
        "none",
    ];
    assert_ok(&run(dir, &args));
    let out: PathBuf = dir.join("out/box/v00_phong.png");
    let whole = std::fs::read(&out).unwrap();
    std::fs::write(&out, &whole[..whole.len() / 2]).unwrap();
    assert_ok(&run(dir, &args));
    assert_eq!(std::fs::read(&out).unwrap(), whole);
    assert_eq!(
        rows_with(&index(&dir.join("out/index.jsonl")), "ok").len(),
        1
    );
}

#[test]
fn a_mesh_too_large_for_a_workers_share_of_memory_is_an_error_row() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    std::fs::write(root.join("cube.obj"), CUBE_OBJ).unwrap();
    // 16384×4096 pixels need about 1 GiB to draw; 16 workers share 8 GiB,
    // 512 MiB each: the large line is refused before a frame is allocated,
    // the small one is drawn.
    std::fs::write(
        root.join("m.jsonl"),
        "{\"path\": \"cube.obj\", \"id\": \"huge\", \"size\": \"16384x4096\"}\n{\"path\": \"cube.obj\", \"id\": \"small\"}\n",
    )
    .unwrap();
    let out = run(
        root,
        &[
            "batch",
            "m.jsonl",
            "-o",
            "out",
            "--size",
            "16x16",
            "--jobs",
            "16",
            "--progress",
            "none",
        ],
    );
    assert_ok(&out);
    let rows = index(&root.join("out/index.jsonl"));
    let huge = rows.iter().find(|r| r["id"] == "huge").unwrap();
    assert_eq!(huge["status"], "error", "{huge}");
    let message = huge["error"].as_str().unwrap();
    assert!(
        message.contains("memory") && message.contains("16 workers"),
        "{message}"
    );
    let small = rows.iter().find(|r| r["id"] == "small").unwrap();
    assert_eq!(small["status"], "ok", "{small}");
    assert_eq!(
        pngs(&root.join("out")),
        BTreeSet::from(["small/v00_phong.png".to_owned()])
    );
}
