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
//!
//! It is a few dozen lines over `std::net`: one thread and one request per
//! connection (`Connection: close`), which is all a page of a dozen files
//! needs. (`tiny_http` 0.12, tried first, leaves a request unanswered when a
//! browser opens several connections at once: its task pool queues the work
//! behind threads that wait on idle keep-alive connections.)

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Duration;

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

/// Longest request head read (request line and headers), bytes.
const MAX_HEAD: usize = 8 * 1024;
/// Most connections served at once; more are refused with 503.
const MAX_CONNECTIONS: usize = 64;
/// How long a connection may take to send its request.
const READ_TIMEOUT: Duration = Duration::from_secs(10);

/// A running server.
pub struct Server {
    listener: TcpListener,
    addr: SocketAddr,
}

impl Server {
    /// Listens on `addr` (port 0: any free port).
    ///
    /// # Errors
    /// When the address cannot be bound (in use, not this machine's).
    pub fn bind(addr: SocketAddr) -> std::io::Result<Server> {
        let listener = TcpListener::bind(addr)?;
        let addr = listener.local_addr()?;
        Ok(Server { listener, addr })
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Answers requests with `site`'s files until the process ends: one
    /// thread per connection, one request per connection.
    pub fn run(self, site: Site) {
        let site = Arc::new(site);
        let active = Arc::new(AtomicUsize::new(0));
        for stream in self.listener.incoming() {
            let Ok(mut stream) = stream else { continue };
            if active.load(Ordering::Acquire) >= MAX_CONNECTIONS {
                let _ = write_response(&mut stream, &Response::status(503, "busy"), false);
                continue;
            }
            active.fetch_add(1, Ordering::AcqRel);
            let site = Arc::clone(&site);
            let active = Arc::clone(&active);
            std::thread::spawn(move || {
                serve_connection(&site, stream);
                active.fetch_sub(1, Ordering::AcqRel);
            });
        }
    }
}

/// What the server sends back.
#[derive(Debug, PartialEq)]
pub struct Response {
    /// HTTP status code.
    pub status: u16,
    /// Content type of the body.
    pub content_type: &'static str,
    /// The body.
    pub body: &'static [u8],
    /// Extra headers.
    pub headers: Vec<(&'static str, &'static str)>,
}

impl Response {
    fn status(status: u16, text: &'static str) -> Response {
        Response {
            status,
            content_type: "text/plain; charset=utf-8",
            body: text.as_bytes(),
            headers: Vec::new(),
        }
    }
}

fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        404 => "Not Found",
        405 => "Method Not Allowed",
        431 => "Request Header Fields Too Large",
        503 => "Service Unavailable",
        _ => "Error",
    }
}

/// The response to a request head (request line and headers), and whether
/// the body is to be left out (`HEAD`).
pub fn answer(site: &Site, head: &[u8]) -> (Response, bool) {
    let Some(line) = head.split(|&b| b == b'\n').next() else {
        return (Response::status(400, "bad request\n"), false);
    };
    let line = String::from_utf8_lossy(line);
    let mut parts = line.trim_end_matches('\r').split(' ');
    let (Some(method), Some(target), Some(version), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return (Response::status(400, "bad request\n"), false);
    };
    if !version.starts_with("HTTP/1.") {
        return (Response::status(400, "bad request\n"), false);
    }
    let head_only = method == "HEAD";
    if !(head_only || method == "GET") {
        let mut r = Response::status(405, "method not allowed\n");
        r.headers.push(("Allow", "GET, HEAD"));
        return (r, false);
    }
    let response = match site.lookup(target) {
        Some((body, content_type)) => Response {
            status: 200,
            content_type,
            body,
            headers: Vec::new(),
        },
        None => Response::status(404, "not found\n"),
    };
    (response, head_only)
}

fn serve_connection(site: &Site, mut stream: TcpStream) {
    let _ = stream.set_read_timeout(Some(READ_TIMEOUT));
    let _ = stream.set_write_timeout(Some(READ_TIMEOUT));
    let mut head = Vec::with_capacity(1024);
    let mut buf = [0u8; 1024];
    let complete = loop {
        if head.windows(4).any(|w| w == b"\r\n\r\n") || head.windows(2).any(|w| w == b"\n\n") {
            break true;
        }
        if head.len() > MAX_HEAD {
            break false;
        }
        match stream.read(&mut buf) {
            Ok(0) | Err(_) => return,
            Ok(n) => head.extend_from_slice(&buf[..n]),
        }
    };
    let (response, head_only) = if complete {
        answer(site, &head)
    } else {
        (Response::status(431, "request head too large\n"), false)
    };
    let _ = write_response(&mut stream, &response, head_only);
    let _ = stream.flush();
    let _ = stream.shutdown(std::net::Shutdown::Write);
}

fn write_response(stream: &mut TcpStream, r: &Response, head_only: bool) -> std::io::Result<()> {
    let mut head = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nConnection: close\r\n\
         X-Content-Type-Options: nosniff\r\nContent-Security-Policy: {CSP}\r\n\
         Cache-Control: no-cache\r\nReferrer-Policy: no-referrer\r\n",
        r.status,
        reason(r.status),
        r.content_type,
        r.body.len()
    );
    for (name, value) in &r.headers {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    head.push_str("\r\n");
    stream.write_all(head.as_bytes())?;
    if !head_only {
        stream.write_all(r.body)?;
    }
    Ok(())
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
    fn requests_are_answered_by_method() {
        let (r, head_only) = answer(&site(), b"GET /js/main.js HTTP/1.1\r\nHost: x\r\n\r\n");
        assert_eq!(
            (r.status, r.body, head_only),
            (200, &b"export {}"[..], false)
        );
        let (r, head_only) = answer(&site(), b"HEAD / HTTP/1.1\r\n\r\n");
        assert_eq!((r.status, head_only), (200, true));
        let (r, _) = answer(&site(), b"POST / HTTP/1.1\r\n\r\n");
        assert_eq!(r.status, 405);
        assert_eq!(r.headers, vec![("Allow", "GET, HEAD")]);
        for bad in [
            &b"GET /\r\n\r\n"[..],
            b"GET / HTTP/1.1 extra\r\n\r\n",
            b"GET / SPDY/3\r\n\r\n",
            b"\r\n\r\n",
        ] {
            assert_eq!(
                answer(&site(), bad).0.status,
                400,
                "{:?}",
                String::from_utf8_lossy(bad)
            );
        }
        assert_eq!(
            answer(&site(), b"GET /../etc/passwd HTTP/1.1\r\n\r\n")
                .0
                .status,
            404
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
