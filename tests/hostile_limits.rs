//! Inputs that would hang, blow up memory or panic (issue items 6–10, 12,
//! 16 and 17): each ends quickly in a clear error within bounded memory, or
//! is simply read, as CR-only line ends now are.

mod support;

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use support::*;

const SOON: Duration = Duration::from_secs(30);

/// `args` run under a cap on address space of `mebibytes`, so that a
/// command that allocated what it should not fails instead of exhausting
/// the machine.
fn run_capped(dir: &Path, mebibytes: u64, args: &[&str]) -> std::process::Output {
    let mut c = Command::new("sh");
    c.arg("-c")
        .arg(format!(
            "ulimit -v {}; exec \"$0\" \"$@\"",
            mebibytes * 1024
        ))
        .arg(bin())
        .args(args)
        .current_dir(dir);
    run_within(c, SOON)
}

#[test]
fn a_ply_element_without_properties_ends_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let mut ply = b"ply\nformat binary_little_endian 1.0\nelement junk 18446744073709551615\n\
element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        .to_vec();
    ply.extend(f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]));
    ply.push(3);
    for i in 0i32..3 {
        ply.extend(i.to_le_bytes());
    }
    write(dir.path(), "junk.ply", &ply);
    let out = run_within(
        command(
            dir.path(),
            &["render", "--model", "junk.ply", "-o", "o.png"],
        ),
        SOON,
    );
    assert_input_error(&out, &["junk.ply", "`junk`", "no properties"]);
}

#[test]
fn three_hundred_thousand_materials_take_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let mut mtl = String::new();
    for k in 0..300_000 {
        mtl.push_str(&format!("newmtl m{k}\nKd 1 0 0\n"));
    }
    mtl.push_str("newmtl last\nKd 0 1 0\n");
    write(dir.path(), "many.mtl", mtl);
    write(
        dir.path(),
        "many.obj",
        format!("mtllib many.mtl\nusemtl last\n{TETRA}"),
    );
    let start = Instant::now();
    let out = run_within(
        command(
            dir.path(),
            &[
                "render", "--model", "many.obj", "--size", "16x16", "-o", "o.png",
            ],
        ),
        Duration::from_secs(120),
    );
    let took = start.elapsed();
    assert_ok(&out);
    // Linear parsing takes a fraction of a second; quadratic took over 30 s.
    assert!(took < Duration::from_secs(10), "{took:?}");
    let image = std::fs::read(dir.path().join("o.png")).unwrap();
    let mut reader = png::Decoder::new(std::io::Cursor::new(image))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    reader.next_frame(&mut buf).unwrap();
    assert!(
        buf.chunks(3).any(|p| p[1] > p[0] && p[1] > p[2]),
        "the last material's green Kd was not used"
    );
}

#[test]
fn gltf_instancing_is_budgeted_before_anything_is_allocated() {
    let dir = tempfile::tempdir().unwrap();
    // 64 triangles, drawn by 100 primitives of one mesh, drawn by 2700
    // nodes: 17,280,000 triangles after instancing, from a small file.
    let buffer: Vec<u8> = triangle_buffer().repeat(64);
    let doc = gltf_doc(&data_uri(&buffer), buffer.len(), 192, 100, 2700, "");
    assert!(doc.len() < 64 * 1024, "{} bytes", doc.len());
    write(dir.path(), "instanced.gltf", doc);
    let out = run_capped(
        dir.path(),
        1024,
        &[
            "render",
            "--model",
            "instanced.gltf",
            "--size",
            "16x16",
            "-o",
            "o.png",
        ],
    );
    assert_input_error(
        &out,
        &[
            "instanced.gltf",
            "17280000 triangles after instancing",
            "16777216",
        ],
    );
    // Within the limits, instancing draws every instance.
    let doc = gltf_doc(&data_uri(&buffer), buffer.len(), 192, 2, 3, "");
    write(dir.path(), "three.gltf", doc);
    assert_ok(&run(
        dir.path(),
        &[
            "render",
            "--model",
            "three.gltf",
            "--size",
            "16x16",
            "-o",
            "o.png",
        ],
    ));
}

#[test]
fn memory_is_estimated_before_it_is_allocated() {
    let dir = tempfile::tempdir().unwrap();
    for command in ["errors", "accuracy"] {
        let out = run_capped(
            dir.path(),
            2048,
            &[command, "--size", "16384x4096", "-o", "o.png"],
        );
        assert_input_error(
            &out,
            &[command, "of memory", "more than the limit of 8.0 GiB"],
        );
    }
    // The largest image renders within the estimate (not run here: it
    // takes a while), and a small one is well within it.
    assert_ok(&run(
        dir.path(),
        &["errors", "--size", "32x32", "-o", "o.png"],
    ));
}

#[test]
fn quad_angles_are_validated() {
    let dir = tempfile::tempdir().unwrap();
    let many = (0..1000)
        .map(|k| k.to_string())
        .collect::<Vec<_>>()
        .join(",");
    let out = run_capped(
        dir.path(),
        2048,
        &["quad", "--angles", &many, "-o", "o.png"],
    );
    assert_input_error(&out, &["--angles", "1..=36", "1000"]);
    for bad in ["1e30", "-400", "nan"] {
        let out = run(
            dir.path(),
            &["quad", "--angles", &format!("0,{bad}"), "-o", "o.png"],
        );
        assert_fails(&out, 2, &["--angles"]);
    }
    let out = run(dir.path(), &["quad", "--angles", "0,1e30", "-o", "o.png"]);
    assert_input_error(&out, &["-360..=360", "1e30"]);
    assert_ok(&run(
        dir.path(),
        &[
            "quad",
            "--size",
            "9",
            "--angles",
            "-360,0,360",
            "-o",
            "o.png",
        ],
    ));
}

/// `bench` flags for one quick row of 8×8 pixels.
const QUICK_BENCH: [&str; 13] = [
    "--size",
    "8x8",
    "--shading",
    "flat",
    "--threads",
    "1",
    "--rasterizer",
    "tiled",
    "--frames",
    "1",
    "--warmup",
    "0",
    "--warmup-time=0",
];

#[test]
fn nothing_panics_on_odd_environments_and_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let mut bench = vec!["bench", "--model", "quad"];
    bench.extend_from_slice(&QUICK_BENCH);
    for budget in ["inf", "nan", "1e300", "-0.5"] {
        let mut args = bench.clone();
        args.extend_from_slice(&["--budget", budget]);
        let out = run(dir.path(), &args);
        assert_input_error(&out, &["--budget", "0..=3600"]);
        // QUICK_BENCH without its own "--warmup-time=0".
        let mut args = bench[..bench.len() - 1].to_vec();
        args.extend_from_slice(&["--warmup-time", budget]);
        let out = run(dir.path(), &args);
        assert_input_error(&out, &["--warmup-time", "0..=3600"]);
    }
    for threads in ["5000", "many", "-1"] {
        let out = command(dir.path(), &["render", "--size", "16x16", "-o", "o.png"])
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert_input_error(&out, &["RAYON_NUM_THREADS", "0..=256"]);
    }
    let out = command(dir.path(), &["render", "--size", "16x16", "-o", "o.png"])
        .env("RAYON_NUM_THREADS", "3")
        .output()
        .unwrap();
    assert_ok(&out);
    let full = || std::fs::File::create("/dev/full").unwrap();
    // Text to a full standard output, from every command that prints.
    for args in [
        vec!["models"],
        vec!["--help"],
        vec![
            "explain", "--model", "cube", "--size", "16x16", "--pixel", "8,8",
        ],
        vec!["cost", "--model", "cube", "--size", "16x16", "--runs", "1"],
        vec!["quad", "--size", "9", "--angles", "0", "-o", "q.png"],
        [&bench[..], &["--budget", "0"]].concat(),
    ] {
        let out = command(dir.path(), &args).stdout(full()).output().unwrap();
        assert_fails(&out, 1, &["No space left on device"]);
    }
    // A full standard error loses the report, not the image, and never panics.
    let out = command(
        dir.path(),
        &["render", "--size", "16x16", "-o", "quiet.png"],
    )
    .stderr(full())
    .output()
    .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(is_png(
        &std::fs::read(dir.path().join("quiet.png")).unwrap()
    ));
    // A reader that goes away: quiet, as other tools are.
    let mut child = command(dir.path(), &["models"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stderr(&out).is_empty(), "{}", stderr(&out));
}

#[test]
fn bench_with_a_missing_models_folder_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["bench", "--models-dir", "no/such/folder", "--model", "quad"];
    args.extend_from_slice(&QUICK_BENCH);
    args.extend_from_slice(&["--budget", "0"]);
    assert_input_error(&run(dir.path(), &args), &["--models-dir", "no/such/folder"]);
    std::fs::create_dir(dir.path().join("empty")).unwrap();
    let mut args = vec!["bench", "--models-dir", "empty", "--model", "bunny"];
    args.extend_from_slice(&QUICK_BENCH);
    args.extend_from_slice(&["--budget", "0"]);
    assert_input_error(&run(dir.path(), &args), &["bunny", "stanford-bunny.obj"]);
}

/// `text` with every line end replaced by `end`.
fn with_ends(text: &str, end: &str) -> String {
    text.replace("\r\n", "\n").replace('\n', end)
}

#[test]
fn cr_only_line_ends_read_as_lf_and_crlf_do() {
    let dir = tempfile::tempdir().unwrap();
    let obj = format!("mtllib tetra.mtl\nusemtl blue\n{TETRA}");
    let mtl = "newmtl blue\nKd 0 0 1\n";
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    let stl = "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\n\
vertex 1 0 0\nendloop\nendfacet\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
vertex 0 0 1\nendloop\nendfacet\nendsolid t\n";
    let scene = "[model]\nsource = \"tetra.obj\"\n[render]\nwidth = 48\nheight = 40\nyaw = 20\n";
    let mut binary_ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\n\
property float x\nproperty float y\nproperty float z\nelement face 4\n\
property list uchar int vertex_indices\nend_header\n"
        .to_vec();
    binary_ply.extend(f32_bytes(&[
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0,
    ]));
    for face in [[0i32, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
        binary_ply.push(3);
        for i in face {
            binary_ply.extend(i.to_le_bytes());
        }
    }
    let mut images = Vec::new();
    for end in ["\n", "\r\n", "\r"] {
        let sub = dir
            .path()
            .join(format!("ends{}", end.len() + end.matches('\r').count()));
        std::fs::create_dir(&sub).unwrap();
        write(&sub, "tetra.obj", with_ends(&obj, end));
        write(&sub, "tetra.mtl", with_ends(mtl, end));
        write(&sub, "tetra.ply", with_ends(ply, end));
        write(&sub, "tetra.stl", with_ends(stl, end));
        write(&sub, "scene.toml", with_ends(scene, end));
        // Only the header of a binary file is text.
        let header_end = binary_ply
            .windows(11)
            .position(|w| w == b"end_header\n")
            .unwrap()
            + 11;
        let mut bin =
            with_ends(std::str::from_utf8(&binary_ply[..header_end]).unwrap(), end).into_bytes();
        bin.extend_from_slice(&binary_ply[header_end..]);
        write(&sub, "binary.ply", bin);
        let mut set = Vec::new();
        for args in [
            vec!["render", "scene.toml", "-o", "scene.png"],
            vec![
                "render",
                "scene.toml",
                "--model",
                "tetra.ply",
                "-o",
                "ply.png",
            ],
            vec![
                "render",
                "scene.toml",
                "--model",
                "binary.ply",
                "-o",
                "binary.png",
            ],
            vec![
                "render",
                "scene.toml",
                "--model",
                "tetra.stl",
                "-o",
                "stl.png",
            ],
        ] {
            let out = run(&sub, &args);
            assert_ok(&out);
            set.push(std::fs::read(sub.join(args[args.len() - 1])).unwrap());
        }
        images.push(set);
    }
    assert_eq!(images[1], images[0], "CR LF differs from LF");
    assert_eq!(images[2], images[0], "CR differs from LF");
}
