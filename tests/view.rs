//! `shadelab view`: the real binary serving its embedded viewer on loopback,
//! with the right content types and nothing but its own files, and
//! `--export` writing the same files.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_shadelab");

/// A running `shadelab view`, stopped when dropped.
struct Viewer {
    child: Child,
    _stdout: BufReader<std::process::ChildStdout>,
    addr: String,
    url: String,
}

impl Viewer {
    fn start(args: &[&str]) -> Viewer {
        let mut child = Command::new(BIN)
            .args(["view", "--port", "0", "--no-open"])
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut line = String::new();
        let mut stdout = BufReader::new(child.stdout.take().unwrap());
        stdout.read_line(&mut line).unwrap();
        let url = line
            .trim()
            .strip_prefix("shadelab viewer: ")
            .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
            .to_string();
        let addr = url
            .trim_start_matches("http://")
            .trim_end_matches('/')
            .to_string();
        Viewer {
            child,
            _stdout: stdout,
            addr,
            url,
        }
    }

    /// Sends `request` as is; returns the status, the headers (lower-case names) and the body.
    fn raw(&self, request: &str) -> (u16, Vec<(String, String)>, Vec<u8>) {
        let mut stream = TcpStream::connect(&self.addr).unwrap();
        stream.write_all(request.as_bytes()).unwrap();
        let mut response = Vec::new();
        stream
            .read_to_end(&mut response)
            .unwrap_or_else(|e| panic!("{request:?}: {e}"));
        let split = response
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .expect("a response head");
        let head = String::from_utf8(response[..split].to_vec()).unwrap();
        let body = response[split + 4..].to_vec();
        let mut lines = head.lines();
        let status = lines
            .next()
            .unwrap()
            .split(' ')
            .nth(1)
            .unwrap()
            .parse()
            .unwrap();
        let headers = lines
            .map(|l| {
                let (k, v) = l.split_once(':').unwrap();
                (k.trim().to_ascii_lowercase(), v.trim().to_string())
            })
            .collect();
        (status, headers, body)
    }

    fn get(&self, target: &str) -> (u16, Vec<(String, String)>, Vec<u8>) {
        self.raw(&format!(
            "GET {target} HTTP/1.1\r\nHost: {}\r\n\r\n",
            self.addr
        ))
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn header<'a>(headers: &'a [(String, String)], name: &str) -> &'a str {
    headers
        .iter()
        .find(|(k, _)| k == name)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("no {name} header in {headers:?}"))
}

#[test]
fn serves_on_loopback_by_default_with_the_right_content_types() {
    let viewer = Viewer::start(&[]);
    assert!(
        viewer.url.starts_with("http://127.0.0.1:"),
        "{}",
        viewer.url
    );
    for (target, kind, starts) in [
        ("/", "text/html; charset=utf-8", &b"<!doctype html>"[..]),
        (
            "/index.html",
            "text/html; charset=utf-8",
            b"<!doctype html>",
        ),
        ("/style.css", "text/css; charset=utf-8", b"/*"),
        ("/js/main.js", "text/javascript; charset=utf-8", b"//"),
        ("/js/worker.js", "text/javascript; charset=utf-8", b"//"),
        ("/i18n/en.js", "text/javascript; charset=utf-8", b"//"),
        ("/favicon.svg", "image/svg+xml", b"<svg"),
        ("/shadelab.wasm", "application/wasm", b"\0asm"),
        (
            "/?model=cube",
            "text/html; charset=utf-8",
            b"<!doctype html>",
        ),
    ] {
        let (status, headers, body) = viewer.get(target);
        assert_eq!(status, 200, "{target}");
        assert_eq!(header(&headers, "content-type"), kind, "{target}");
        assert_eq!(header(&headers, "content-length"), body.len().to_string());
        assert_eq!(header(&headers, "x-content-type-options"), "nosniff");
        assert!(header(&headers, "content-security-policy").starts_with("default-src 'self'"));
        assert!(body.starts_with(starts), "{target}");
    }
    let (status, headers, body) = viewer.raw(&format!(
        "HEAD /shadelab.wasm HTTP/1.1\r\nHost: {}\r\n\r\n",
        viewer.addr
    ));
    assert_eq!(status, 200);
    assert!(body.is_empty());
    assert!(header(&headers, "content-length").parse::<usize>().unwrap() > 100_000);
}

#[test]
fn serves_nothing_but_its_own_files() {
    let viewer = Viewer::start(&[]);
    for target in [
        "/../Cargo.toml",
        "/../../../../../../etc/passwd",
        "/js/../../Cargo.toml",
        "/%2e%2e/Cargo.toml",
        "/%2e%2e%2fCargo.toml",
        "/..%5cCargo.toml",
        "//etc/passwd",
        "/Cargo.toml",
        "/src/main.rs",
        "/web/index.html",
        "/js",
        "/js/",
        "http://example.com/",
        "*",
    ] {
        let (status, _, body) = viewer.get(target);
        assert_eq!(
            status,
            404,
            "{target} was served: {}",
            String::from_utf8_lossy(&body)
        );
    }
    let (status, headers, _) = viewer.raw(&format!(
        "POST / HTTP/1.1\r\nHost: {}\r\nContent-Length: 0\r\n\r\n",
        viewer.addr
    ));
    assert_eq!(status, 405);
    assert_eq!(header(&headers, "allow"), "GET, HEAD");
    assert_eq!(viewer.raw("GET / FTP/1.0\r\n\r\n").0, 400);
    assert_eq!(viewer.raw("nonsense\r\n\r\n").0, 400);
    let huge = format!("GET / HTTP/1.1\r\nX: {}\r\n\r\n", "a".repeat(20_000));
    assert_eq!(viewer.raw(&huge).0, 431);
    // Still serving after all that.
    assert_eq!(viewer.get("/").0, 200);
}

#[test]
fn host_chooses_the_address() {
    let viewer = Viewer::start(&["--host", "::1"]);
    assert!(viewer.url.starts_with("http://[::1]:"), "{}", viewer.url);
    assert_eq!(viewer.get("/").0, 200);
}

#[test]
fn bad_arguments_and_a_busy_port_are_clear_errors() {
    let out = Command::new(BIN)
        .args(["view", "--host", "localhost:80", "--no-open"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--host"));

    let viewer = Viewer::start(&[]);
    let port = viewer.addr.rsplit(':').next().unwrap();
    let out = Command::new(BIN)
        .args(["view", "--port", port, "--no-open"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!("cannot listen on 127.0.0.1:{port}")),
        "{stderr}"
    );
    assert!(stderr.contains("--port"), "{stderr}");
}

#[test]
fn export_writes_the_served_files_and_overwrites_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let site = dir.path().join("site");
    let out = Command::new(BIN)
        .args(["view", "--export"])
        .arg(&site)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let viewer = Viewer::start(&[]);
    for name in [
        "index.html",
        "style.css",
        "js/main.js",
        "js/worker.js",
        "js/shadelab.js",
        "i18n/en.js",
        "shadelab.wasm",
    ] {
        let written = std::fs::read(site.join(name)).unwrap();
        let (status, _, served) = viewer.get(&format!("/{name}"));
        assert_eq!(status, 200);
        assert_eq!(written, served, "{name}");
    }
    // A second export into the same (now full) directory is refused.
    let out = Command::new(BIN)
        .args(["view", "--export"])
        .arg(&site)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("is not empty"));
}
