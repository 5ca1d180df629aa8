//! The viewer's web server: the page's files, embedded in the binary at
//! build time (see `build.rs`), and nothing else.
//!
//! A request names a file of the site by its exact path; there is no file
//! system behind it, so a path with `..`, a backslash, a percent-escape or
//! anything not in the table is simply not found. Only `GET` and `HEAD` are
//! answered. Every response carries its content type (`application/wasm`
//! for the module, which browsers require to compile it while it streams
//! in), `nosniff`, and a content security policy that lets the page load
//! only the server's own files: no request leaves the machine.

use std::net::SocketAddr;
use std::sync::Arc;

mod site {
    include!(concat!(env!("OUT_DIR"), "/site.rs"));
}

/// The path the page asks for the WebAssembly module by.
pub const WASM_PATH: &str = "shadelab.wasm";

/// The content security policy of every response.
const CSP: &str = "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; \
    worker-src 'self'; img-src 'self' data: blob:; style-src 'self'; \
    connect-src 'self'; font-src 'self'; object-src 'none'; base-uri 'none'; \
    form-action 'none'; frame-ancestors 'none'";

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
        if site::WASM.is_empty() {
            let reason = if site::WASM_ERROR.is_empty() {
                "the module is empty"
            } else {
                site::WASM_ERROR
            };
            return Err(MissingWasm(reason));
        }
        let mut files = site::WEB_FILES.to_vec();
        files.push((WASM_PATH, site::WASM));
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

/// A running server.
pub struct Server {
    inner: Arc<tiny_http::Server>,
    addr: SocketAddr,
}

impl Server {
    /// Listens on `addr` (port 0: any free port).
    ///
    /// # Errors
    /// When the address cannot be bound (in use, not this machine's).
    pub fn bind(addr: SocketAddr) -> Result<Server, String> {
        let inner = tiny_http::Server::http(addr).map_err(|e| e.to_string())?;
        let addr = inner
            .server_addr()
            .to_ip()
            .ok_or_else(|| "the server has no IP address".to_string())?;
        Ok(Server {
            inner: Arc::new(inner),
            addr,
        })
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Answers requests with `site`'s files until the process ends, on a
    /// few threads so that one slow client does not hold up the others.
    pub fn run(self, site: Site) {
        let site = Arc::new(site);
        let workers: Vec<_> = (0..4)
            .map(|_| {
                let server = Arc::clone(&self.inner);
                let site = Arc::clone(&site);
                std::thread::spawn(move || {
                    for request in server.incoming_requests() {
                        respond(&site, request);
                    }
                })
            })
            .collect();
        for worker in workers {
            let _ = worker.join();
        }
    }
}

fn header(name: &str, value: &str) -> tiny_http::Header {
    tiny_http::Header::from_bytes(name.as_bytes(), value.as_bytes())
        .expect("header names and values here are ASCII")
}

fn respond(site: &Site, request: tiny_http::Request) {
    use tiny_http::{Method, Response, StatusCode};
    let common = [
        header("X-Content-Type-Options", "nosniff"),
        header("Content-Security-Policy", CSP),
        header("Cache-Control", "no-cache"),
        header("Referrer-Policy", "no-referrer"),
    ];
    let head = *request.method() == Method::Head;
    if !(head || *request.method() == Method::Get) {
        let mut response = Response::from_string("method not allowed\n")
            .with_status_code(StatusCode(405))
            .with_header(header("Allow", "GET, HEAD"))
            .with_header(header("Content-Type", "text/plain; charset=utf-8"));
        for h in common {
            response.add_header(h);
        }
        let _ = request.respond(response);
        return;
    }
    let (status, body, kind) = match site.lookup(request.url()) {
        Some((body, kind)) => (200, body, kind),
        None => (404, &b"not found\n"[..], "text/plain; charset=utf-8"),
    };
    let mut response = Response::from_data(if head { &[][..] } else { body })
        .with_status_code(StatusCode(status))
        .with_header(header("Content-Type", kind));
    if head {
        response = response.with_header(header("Content-Length", &body.len().to_string()));
    }
    for h in common {
        response.add_header(h);
    }
    let _ = request.respond(response);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn site() -> Site {
        Site {
            files: vec![
                ("index.html", b"<!doctype html>"),
                ("js/main.js", b"export {}"),
                (WASM_PATH, b"\0asm"),
            ],
        }
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
        assert_eq!(site().lookup("/js/main.js").unwrap().1, "text/javascript; charset=utf-8");
        assert_eq!(site().lookup("/shadelab.wasm").unwrap().1, "application/wasm");
        assert_eq!(content_type("a.css"), "text/css; charset=utf-8");
        assert_eq!(content_type("a.json"), "application/json");
        assert_eq!(content_type("noextension"), "application/octet-stream");
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
