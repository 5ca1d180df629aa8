//! Builds the viewer's WebAssembly and embeds it, with the page's files
//! under `web/`, into the `shadelab` binary, so that `shadelab view` serves
//! only its own files and works offline.
//!
//! The WebAssembly is `crates/shadelab-wasm` built for
//! `wasm32-unknown-unknown` with the `wasm` profile, by a second cargo in
//! its own target directory (`target/viewer-wasm`, so it never waits for
//! the lock of the build that runs this script). The target is added with
//! rustup when it is missing. `SHADELAB_WASM=path/to/file.wasm` embeds a
//! ready-made module instead. When the module cannot be built, the rest of
//! shadelab still builds: the reason is printed as a warning now, and
//! `shadelab view` repeats it.

use std::path::{Path, PathBuf};
use std::process::Command;

const TARGET: &str = "wasm32-unknown-unknown";

fn main() {
    let root = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets it"));
    for watched in [
        "web",
        "crates/shadelab-wasm",
        "crates/shadelab-core/src",
        "crates/shadelab-core/Cargo.toml",
        "crates/shadelab-io/src",
        "crates/shadelab-io/Cargo.toml",
        "crates/shadelab-lab/src",
        "crates/shadelab-lab/texts",
        "crates/shadelab-lab/Cargo.toml",
        "Cargo.lock",
    ] {
        println!("cargo:rerun-if-changed={watched}");
    }
    println!("cargo:rerun-if-env-changed=SHADELAB_WASM");

    let wasm_out = out.join("shadelab.wasm");
    let error = match wasm_module(&root) {
        Ok(module) => match std::fs::copy(&module, &wasm_out) {
            Ok(_) => String::new(),
            Err(e) => format!("cannot copy {}: {e}", module.display()),
        },
        Err(e) => e,
    };
    if !error.is_empty() {
        for line in error.lines() {
            println!("cargo:warning=viewer: {line}");
        }
        println!("cargo:warning=viewer: shadelab builds without it; `shadelab view` will explain");
        std::fs::write(&wasm_out, b"").expect("OUT_DIR is writable");
    }

    let mut files = Vec::new();
    collect(&root.join("web"), &root.join("web"), &mut files);
    files.sort();
    let mut code = String::from(
        "/// The page's files, by path relative to the site's root.\n\
         pub static WEB_FILES: &[(&str, &[u8])] = &[\n",
    );
    for (name, path) in &files {
        code.push_str(&format!("    ({name:?}, include_bytes!({path:?})),\n"));
    }
    code.push_str("];\n");
    code.push_str(&format!(
        "/// The WebAssembly module (empty when it could not be built).\n\
         pub static WASM: &[u8] = include_bytes!({:?});\n\
         /// Why the WebAssembly module could not be built (empty when it was).\n\
         pub static WASM_ERROR: &str = {error:?};\n",
        wasm_out.display().to_string()
    ));
    std::fs::write(out.join("site.rs"), code).expect("OUT_DIR is writable");
}

/// Every file under `dir`, as (path relative to `base` with `/`, absolute path).
fn collect(base: &Path, dir: &Path, files: &mut Vec<(String, String)>) {
    let entries = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot read the viewer's files in {}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("a readable directory entry").path();
        if path.is_dir() {
            collect(base, &path, files);
        } else {
            let relative = path.strip_prefix(base).expect("under base");
            let name = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            files.push((name, path.display().to_string()));
        }
    }
}

/// The path of the built (or given) module, or why there is none.
fn wasm_module(root: &Path) -> Result<PathBuf, String> {
    if let Some(given) = std::env::var_os("SHADELAB_WASM") {
        let given = PathBuf::from(given);
        return if given.is_file() {
            Ok(given)
        } else {
            Err(format!("SHADELAB_WASM={} is not a file", given.display()))
        };
    }
    ensure_target()?;
    let target_dir = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"))
        .join("viewer-wasm");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = Command::new(cargo);
    command
        .current_dir(root)
        .args([
            "build",
            "--locked",
            "-p",
            "shadelab-wasm",
            "--profile",
            "wasm",
        ])
        .args(["--target", TARGET])
        .arg("--target-dir")
        .arg(&target_dir);
    // This script runs inside another cargo: do not let its settings (a
    // wrapper such as clippy's, flags for the host, the package being built)
    // leak into the nested build; keep the toolchain and the jobserver.
    for (key, _) in std::env::vars_os() {
        let key = key.to_string_lossy();
        let keep = key == "CARGO_HOME" || key == "CARGO_MAKEFLAGS" || key == "CARGO_NET_OFFLINE";
        if (key.starts_with("CARGO_") && !keep)
            || matches!(
                &*key,
                "RUSTFLAGS"
                    | "RUSTDOCFLAGS"
                    | "RUSTC"
                    | "RUSTC_WRAPPER"
                    | "RUSTC_WORKSPACE_WRAPPER"
            )
        {
            command.env_remove(&*key);
        }
    }
    // 128-bit SIMD: every browser of the last years runs it.
    command.env("CARGO_ENCODED_RUSTFLAGS", "-Ctarget-feature=+simd128");
    let output = command
        .output()
        .map_err(|e| format!("cannot run cargo to build the WebAssembly: {e}"))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let tail: Vec<&str> = stderr.lines().rev().take(20).collect();
        return Err(format!(
            "building crates/shadelab-wasm for {TARGET} failed:\n{}",
            tail.into_iter().rev().collect::<Vec<_>>().join("\n")
        ));
    }
    Ok(target_dir
        .join(TARGET)
        .join("wasm")
        .join("shadelab_wasm.wasm"))
}

/// Adds the WebAssembly target with rustup when the toolchain lacks it.
fn ensure_target() -> Result<(), String> {
    let rustc = std::env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    let sysroot = Command::new(&rustc)
        .args(["--print", "sysroot"])
        .output()
        .map_err(|e| format!("cannot run rustc: {e}"))?;
    let sysroot = PathBuf::from(String::from_utf8_lossy(&sysroot.stdout).trim());
    if sysroot.join("lib/rustlib").join(TARGET).is_dir() {
        return Ok(());
    }
    let status = Command::new("rustup")
        .args(["target", "add", TARGET])
        .status()
        .map_err(|e| {
            format!(
                "the Rust toolchain lacks the {TARGET} target and rustup could not be run ({e}); \
                 install the target and build again"
            )
        })?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "`rustup target add {TARGET}` failed; run it yourself and build again"
        ))
    }
}
