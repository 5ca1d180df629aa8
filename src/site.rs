//! The viewer's site: the page's files, embedded in the binary at build
//! time (see `build.rs`), the WebAssembly module, and the schema of the
//! scene's parameters the page builds its controls from ([`PARAMS_PATH`],
//! made from the core's table); and how a request's target names one of
//! them. The server ([`crate::server`]) answers with what this finds.
//!
//! A request names a file by its exact path; there is no file system
//! behind it, so a path with `..`, a backslash, a percent-escape or
//! anything not in the table is simply not found.

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/site.rs"));
}

/// The path the page asks for the WebAssembly module by.
pub const WASM_PATH: &str = "shadelab.wasm";

/// The path the page asks for the parameters' schema by
/// ([`shadelab_core::params::schema_json`]).
pub const PARAMS_PATH: &str = "params.json";

/// The parameters' schema, made once from the core's table.
fn params_json() -> &'static [u8] {
    static JSON: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    JSON.get_or_init(shadelab_core::params::schema_json)
        .as_bytes()
}

/// The viewer's files: the page and the WebAssembly module.
#[derive(Debug, Clone)]
pub struct Site {
    files: Vec<(&'static str, &'static [u8])>,
}

/// Why the site is not available: the WebAssembly module could not be
/// built with this binary, and why.
#[derive(Debug)]
pub struct MissingWasm(pub &'static str);

impl std::error::Error for MissingWasm {}

impl std::fmt::Display for MissingWasm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "this shadelab was built without the viewer's WebAssembly: {}\n\
             Fix the cause (often: `rustup target add wasm32-unknown-unknown`), then build again \
             (`cargo run --release -- view`)",
            self.0.trim()
        )
    }
}

impl Site {
    /// The site embedded in this binary.
    ///
    /// # Errors
    /// [`MissingWasm`] when the module could not be built with the binary.
    pub fn embedded() -> Result<Site, MissingWasm> {
        if embedded::WASM.is_empty() {
            let reason = if embedded::WASM_ERROR.is_empty() {
                "the module is empty"
            } else {
                embedded::WASM_ERROR
            };
            return Err(MissingWasm(reason));
        }
        let mut files = embedded::WEB_FILES.to_vec();
        files.push((WASM_PATH, embedded::WASM));
        files.push((PARAMS_PATH, params_json()));
        Ok(Site { files })
    }

    /// Every file, by its path relative to the site's root.
    pub fn files(&self) -> &[(&'static str, &'static [u8])] {
        &self.files
    }

    /// The file a request's target (path and query) names, with its content
    /// type; `/` is `index.html`.
    pub fn lookup(&self, target: &str) -> Option<(&'static [u8], &'static str)> {
        let path = target.split(['?', '#']).next().unwrap_or("");
        let path = path.strip_prefix('/')?;
        let path = if path.is_empty() { "index.html" } else { path };
        if path.contains("..") || path.contains(['\\', '%', '\0']) || path.starts_with('/') {
            return None;
        }
        self.files
            .iter()
            .find(|(name, _)| *name == path)
            .map(|(name, bytes)| (*bytes, content_type(name)))
    }
}

/// The content type for a file name, by its extension.
pub fn content_type(name: &str) -> &'static str {
    match name.rsplit_once('.').map(|(_, e)| e) {
        Some("html") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("json") => "application/json",
        Some("wasm") => "application/wasm",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("ico") => "image/x-icon",
        Some("txt" | "md") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A small site for the tests of the files and of the server.
    pub(crate) fn site() -> Site {
        Site {
            files: vec![
                ("index.html", b"<!doctype html>"),
                ("js/main.js", b"export {}"),
                (WASM_PATH, b"\0asm"),
            ],
        }
    }

    #[test]
    fn the_parameters_schema_is_served_with_the_files() {
        // A build without the WebAssembly has no site to look at.
        let Ok(site) = Site::embedded() else { return };
        let (body, kind) = site.lookup("/params.json").unwrap();
        assert_eq!(kind, "application/json");
        assert_eq!(body, shadelab_core::params::schema_json().as_bytes());
    }

    #[test]
    fn root_is_the_index() {
        let (body, kind) = site().lookup("/").unwrap();
        assert_eq!(body, b"<!doctype html>");
        assert_eq!(kind, "text/html; charset=utf-8");
        assert!(site().lookup("/?model=cube#x").is_some());
    }

    #[test]
    fn content_types_follow_the_extension() {
        assert_eq!(
            site().lookup("/js/main.js").unwrap().1,
            "text/javascript; charset=utf-8"
        );
        assert_eq!(
            site().lookup("/shadelab.wasm").unwrap().1,
            "application/wasm"
        );
        assert_eq!(content_type("a.css"), "text/css; charset=utf-8");
        assert_eq!(content_type("a.json"), "application/json");
        assert_eq!(content_type("noextension"), "application/octet-stream");
    }

    #[test]
    fn a_missing_module_is_explained() {
        let text = MissingWasm("`rustup target add wasm32-unknown-unknown` failed\n").to_string();
        assert!(
            text.starts_with("this shadelab was built without the viewer's WebAssembly: `rustup")
        );
        assert!(
            text.contains("then build again (`cargo run --release -- view`)"),
            "{text}"
        );
    }

    #[test]
    fn only_the_sites_own_files_are_found() {
        for target in [
            "/../Cargo.toml",
            "/js/../index.html",
            "/%2e%2e/Cargo.toml",
            "/js%2fmain.js",
            "//etc/passwd",
            "/..\\Cargo.toml",
            "/js/",
            "/JS/MAIN.JS",
            "/index.html/",
            "index.html",
            "",
            "/etc/passwd",
            "/js/main.js\0",
        ] {
            assert!(site().lookup(target).is_none(), "{target:?} was served");
        }
    }
}
