//! `shadelab bench` end to end, on tiny configurations: the shape of its
//! table and JSON, the filters, the note for missing meshes and `--export`.
//! (Timings are not checked here: speed claims come from benchmark runs.)

use std::path::Path;
use std::process::{Command, Output};

fn shadelab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shadelab"))
        .args(args)
        .output()
        .expect("the shadelab binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

const TINY: [&str; 9] = [
    "bench",
    "--size",
    "40x30",
    "--frames",
    "2",
    "--warmup",
    "0",
    "--budget=0",
    "--warmup-time=0",
];

#[test]
fn json_has_one_row_per_combination() {
    let mut args = TINY.to_vec();
    args.extend([
        "--json",
        "--model",
        "sphere,quad",
        "--shading",
        "flat,phong",
        "--threads",
        "1,2",
        "--rasterizer",
        "tiled,scanline",
    ]);
    let out = shadelab(&args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert!(json["machine"]["cpu"].is_string());
    assert!(json["machine"]["cores"].as_u64().unwrap() >= 1);
    let simd = json["machine"]["simd"].as_str().unwrap();
    // The level this machine's renderer chose, by its name.
    let best = shadelab_core::SimdLevel::detect().name();
    assert_eq!(simd, best);
    // Measured: some hundreds of MHz at the very least, on anything that runs this.
    let clock = json["machine"]["clock_mhz"].as_f64().unwrap();
    assert!((100.0..20_000.0).contains(&clock), "{clock}");
    // A cache line's round trip between two threads: measured where there
    // are two cores (under 20 ms, a sample's limit), `null` with one.
    let cores = json["machine"]["cores"].as_u64().unwrap();
    match json["machine"]["round_trip_ns"].as_f64() {
        Some(ns) => assert!(
            cores >= 2 && ns > 0.0 && ns < 20e6,
            "{ns} ns, {cores} cores"
        ),
        None => assert!(cores < 2 && json["machine"]["round_trip_ns"].is_null()),
    }
    assert_eq!(json["warmup"].as_u64(), Some(0));
    assert_eq!(json["warmup_s"].as_f64(), Some(0.0));
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(
        rows.len(),
        2 * 2 * 2 * 2,
        "models × methods × threads × rasterizers"
    );
    for row in rows {
        for key in [
            "model",
            "triangles",
            "width",
            "height",
            "shading",
            "rasterizer",
            "threads",
            "frames",
            "median_ms",
            "min_ms",
            "covered_pixels",
            "mpixels_per_s",
            "mtriangles_per_s",
            "cycles_per_pixel",
        ] {
            assert!(!row[key].is_null(), "{key} missing in {row}");
        }
        assert_eq!(
            (row["width"].as_u64(), row["height"].as_u64()),
            (Some(40), Some(30))
        );
        assert!(row["frames"].as_u64().unwrap() >= 2);
        assert!(row["median_ms"].as_f64().unwrap() >= row["min_ms"].as_f64().unwrap());
        // Each timed frame, in the order they ran: as many as `frames`,
        // their least the row's minimum and their middle its median.
        let mut times: Vec<f64> = (row["frame_ms"].as_array().unwrap().iter())
            .map(|t| t.as_f64().unwrap())
            .collect();
        assert_eq!(times.len() as u64, row["frames"].as_u64().unwrap(), "{row}");
        times.sort_by(f64::total_cmp);
        let n = times.len();
        let middle = (times[(n - 1) / 2] + times[n / 2]) / 2.0;
        assert!(
            (times[0] - row["min_ms"].as_f64().unwrap()).abs() < 1e-3,
            "{row}"
        );
        assert!(
            (middle - row["median_ms"].as_f64().unwrap()).abs() < 1e-3,
            "{row}"
        );
        assert!(row["covered_pixels"].as_u64().unwrap() > 0, "{row}");
    }
    // The full-screen quad covers every pixel; both rasterizers agree on it.
    for row in rows.iter().filter(|r| r["model"] == "quad") {
        assert_eq!(row["covered_pixels"].as_u64(), Some(40 * 30), "{row}");
        assert_eq!(row["triangles"].as_u64(), Some(2));
    }
    let covered = |r: &str| {
        rows.iter()
            .filter(|row| row["model"] == "sphere" && row["rasterizer"] == r)
            .map(|row| row["covered_pixels"].as_u64().unwrap())
            .collect::<Vec<_>>()
    };
    assert_eq!(covered("tiled"), covered("scanline"));
}

#[test]
fn table_has_a_header_and_a_line_per_row() {
    let mut args = TINY.to_vec();
    args.extend([
        "--model",
        "teapot",
        "--shading",
        "gouraud",
        "--threads",
        "1",
    ]);
    let out = shadelab(&args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let header = stdout
        .lines()
        .find(|l| l.starts_with("model"))
        .expect("a header line");
    for column in ["ms/frame", "Mpix/s", "Mtri/s", "cyc/px", "raster", "thr"] {
        assert!(header.contains(column), "{header}");
    }
    let rows: Vec<&str> = stdout
        .lines()
        .filter(|l| l.starts_with("teapot "))
        .collect();
    assert_eq!(rows.len(), 2, "tiled and scanline:\n{stdout}");
    assert!(rows
        .iter()
        .all(|r| r.contains("40x30") && r.contains("gouraud")));
}

#[test]
fn missing_meshes_are_named_and_skipped() {
    // A folder that exists but holds none of the meshes (a missing folder is
    // an error: see tests/hostile_limits.rs).
    let empty = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("bench-no-models");
    std::fs::create_dir_all(&empty).unwrap();
    let empty = empty.to_str().unwrap().to_owned();
    let mut args = TINY.to_vec();
    args.extend([
        "--json",
        "--models-dir",
        &empty,
        "--shading",
        "flat",
        "--threads",
        "1",
        "--rasterizer",
        "tiled",
    ]);
    // The default set: the meshes that are missing are named and skipped,
    // the built-in models are measured.
    let out = shadelab(&args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stderr = text(&out.stderr);
    assert!(
        stderr.contains("bunny skipped") && stderr.contains("dragon skipped"),
        "{stderr}"
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert!(!rows.is_empty());
    assert!(rows
        .iter()
        .all(|r| r["model"] != "bunny" && r["model"] != "dragon"));
    // A mesh asked for by name and missing is an error that names it.
    args.extend(["--model", "bunny,sphere"]);
    let out = shadelab(&args);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("stanford-bunny.obj"));
}

#[test]
fn bad_filters_are_input_errors() {
    for bad in [
        ["--size", "0x10"],
        ["--model", "cow"],
        ["--threads", "0"],
        ["--shading", "toon"],
        ["--simd", "sse9"],
    ] {
        let mut args = TINY.to_vec();
        args.extend(bad);
        let out = shadelab(&args);
        assert_eq!(out.status.code(), Some(2), "{bad:?}: {}", text(&out.stderr));
    }
}

#[test]
fn simd_chooses_the_level_and_refuses_one_the_cpu_lacks() {
    use shadelab_core::SimdLevel;
    for level in SimdLevel::ALL {
        let mut args = TINY.to_vec();
        args.extend(["--json", "--model", "quad", "--simd", level.name()]);
        let out = shadelab(&args);
        if level.is_supported() {
            assert!(out.status.success(), "{level}: {}", text(&out.stderr));
            let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            assert_eq!(json["machine"]["simd"], level.name());
        } else {
            // simd128 outside WebAssembly, AVX-512 on most desktops.
            assert_eq!(out.status.code(), Some(2), "{level}");
            let err = text(&out.stderr);
            assert!(
                err.contains("cannot run") && err.contains("portable"),
                "{err}"
            );
        }
    }
}

#[test]
fn export_writes_consistent_geometry_and_images() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("scenes");
    let out = shadelab(&[
        "bench",
        "--export",
        target.to_str().unwrap(),
        "--model",
        "sphere",
        "--size",
        "40x30",
        "--shading",
        "phong",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let file = |name: &str| target.join(name);
    let info: serde_json::Value =
        serde_json::from_slice(&std::fs::read(file("sphere-40x30.json")).unwrap()).unwrap();
    let (vertices, triangles) = (
        info["vertices"].as_u64().unwrap(),
        info["triangles"].as_u64().unwrap(),
    );
    let len = |name: &str| std::fs::metadata(file(name)).unwrap().len();
    assert_eq!(len("sphere-40x30.vertices.f32"), vertices * 6 * 4);
    assert_eq!(len("sphere-40x30.indices.u32"), triangles * 3 * 4);
    assert_eq!(len("sphere-40x30.flat.f32"), triangles * 6 * 4);
    let indices = std::fs::read(file("sphere-40x30.indices.u32")).unwrap();
    assert!(indices
        .chunks_exact(4)
        .all(|i| u64::from(u32::from_le_bytes(i.try_into().unwrap())) < vertices));
    for key in [
        "eye",
        "target",
        "up",
        "light",
        "ka",
        "kd",
        "ks",
        "background",
    ] {
        assert_eq!(info[key].as_array().map(Vec::len), Some(3), "{key}");
    }
    assert_eq!(info["shininess"].as_f64(), Some(32.0));
    assert!(is_png(&file("sphere-40x30-phong.png")));
    assert!(
        !file("sphere-40x30-flat.png").exists(),
        "only the methods asked for"
    );
}

fn is_png(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|b| b.starts_with(b"\x89PNG"))
}
