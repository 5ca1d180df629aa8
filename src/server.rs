//! The viewer's web server: it answers each request with a file of the
//! site ([`crate::site`]: the page, the WebAssembly module and the
//! parameters' schema), and nothing else. Only `GET` and `HEAD` are
//! answered. Every response carries its content type (`application/wasm`
//! for the module, which browsers require to compile it while it streams
//! in), `nosniff`, and a content security policy that lets the page load
//! only the server's own files: no request leaves the machine.
//!
//! It is a small server over `std::net`: one request per connection
//! (`Connection: close`), which is all a page of a dozen files needs, with
//! the limits of `shadelab_core::limits` so that no client can lock it:
//!
//! - a request head must arrive whole within [`REQUEST_HEAD_TIMEOUT`] and
//!   within [`MAX_REQUEST_HEAD_BYTES`]; a response must be taken within
//!   [`RESPONSE_TIMEOUT`]; bodies are never read;
//! - at most [`MAX_CONNECTIONS`] connections are held, each by one thread.
//!   A connection over the limit makes room by closing the one that has
//!   waited longest for its request head (an idle or slow client), or,
//!   when every one is being answered, is answered 503 at once. So 200 idle
//!   sockets cannot keep the page from a browser, and the server never runs
//!   out of threads;
//! - the `Host` header must name this server as the browser reached it:
//!   `localhost`, `127.0.0.1` or `[::1]`, or the address given with
//!   `--host` (any IP address when that is `0.0.0.0` or `::`), with the
//!   port listened on. Any other name is answered 403, so a page elsewhere
//!   cannot reach the viewer through DNS rebinding (its requests carry its
//!   own domain name).
//!
//! (`tiny_http` 0.12, tried first, leaves a request unanswered when a
//! browser opens several connections at once: its task pool queues the work
//! behind threads that wait on idle keep-alive connections.)

use std::collections::HashMap;
use std::io::{Read, Write};
use std::net::{IpAddr, SocketAddr, TcpListener, TcpStream};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::site::Site;
use shadelab_core::limits::{
    MAX_CONNECTIONS, MAX_REQUEST_HEAD_BYTES, REQUEST_HEAD_TIMEOUT, RESPONSE_TIMEOUT,
};

/// The content security policy of every response.
const CSP: &str = "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; \
    worker-src 'self'; img-src 'self' data: blob:; style-src 'self'; \
    connect-src 'self'; font-src 'self'; object-src 'none'; base-uri 'none'; \
    form-action 'none'; frame-ancestors 'none'";

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
    /// thread per connection, at most [`MAX_CONNECTIONS`] of them.
    pub fn run(self, site: Site) {
        let shared = Arc::new(Shared {
            site,
            hosts: AllowedHosts::for_address(self.addr),
            connections: Mutex::new(Connections::default()),
        });
        for stream in self.listener.incoming() {
            let Ok(mut stream) = stream else { continue };
            let Some(id) = shared.admit(&stream) else {
                let _ = stream.set_write_timeout(Some(Duration::from_secs(1)));
                let _ = write_response(&mut stream, &Response::status(503, "busy\n"), false);
                continue;
            };
            let worker = Arc::clone(&shared);
            let spawned = std::thread::Builder::new()
                .name("viewer connection".into())
                .stack_size(256 * 1024)
                .spawn(move || {
                    serve_connection(&worker, stream, id);
                    worker.leave(id);
                });
            if spawned.is_err() {
                shared.leave(id);
            }
        }
    }
}

/// What every connection's thread shares.
struct Shared {
    site: Site,
    hosts: AllowedHosts,
    connections: Mutex<Connections>,
}

/// The connections held, by number.
#[derive(Default)]
struct Connections {
    next: u64,
    open: HashMap<u64, Held>,
}

/// A connection held by a thread.
struct Held {
    /// Another handle to the socket, to close it from outside.
    stream: TcpStream,
    accepted: Instant,
    /// Still waiting for its request head (not yet being answered).
    reading: bool,
}

impl Shared {
    /// Takes `stream` in, closing the connection that has waited longest
    /// for its request head when the limit is reached; `None` when every
    /// held connection is being answered.
    fn admit(&self, stream: &TcpStream) -> Option<u64> {
        let handle = stream.try_clone().ok()?;
        let mut c = self.connections.lock().unwrap_or_else(|e| e.into_inner());
        if c.open.len() >= MAX_CONNECTIONS {
            let oldest = c
                .open
                .iter()
                .filter(|(_, h)| h.reading)
                .min_by_key(|(_, h)| h.accepted)
                .map(|(&id, _)| id)?;
            if let Some(evicted) = c.open.remove(&oldest) {
                let _ = evicted.stream.shutdown(std::net::Shutdown::Both);
            }
        }
        let id = c.next;
        c.next += 1;
        c.open.insert(
            id,
            Held {
                stream: handle,
                accepted: Instant::now(),
                reading: true,
            },
        );
        Some(id)
    }

    /// Marks connection `id` as being answered: it is no longer closed to
    /// make room.
    fn answering(&self, id: u64) {
        let mut c = self.connections.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(held) = c.open.get_mut(&id) {
            held.reading = false;
        }
    }

    /// Forgets connection `id`.
    fn leave(&self, id: u64) {
        let mut c = self.connections.lock().unwrap_or_else(|e| e.into_inner());
        c.open.remove(&id);
    }
}

/// The `Host` header values this server answers (see the module's
/// documentation).
#[derive(Debug, Clone)]
pub struct AllowedHosts {
    port: u16,
    /// The address listened on, when it is neither loopback nor unspecified.
    bound: Option<IpAddr>,
    /// Listening on every address: any IP address names this machine.
    any_address: bool,
}

impl AllowedHosts {
    /// The hosts a server listening on `addr` answers to.
    pub fn for_address(addr: SocketAddr) -> AllowedHosts {
        let ip = addr.ip();
        AllowedHosts {
            port: addr.port(),
            bound: (!ip.is_loopback() && !ip.is_unspecified()).then_some(ip),
            any_address: ip.is_unspecified(),
        }
    }

    /// Whether a request's `Host` value names this server.
    pub fn allows(&self, host: &str) -> bool {
        let host = host.trim();
        let (name, port) = if let Some(rest) = host.strip_prefix('[') {
            let Some((inside, after)) = rest.split_once(']') else {
                return false;
            };
            let port = match after {
                "" => None,
                p => match p.strip_prefix(':') {
                    Some(p) => Some(p),
                    None => return false,
                },
            };
            (inside, port)
        } else {
            match host.rsplit_once(':') {
                Some((name, port)) => (name, Some(port)),
                None => (host, None),
            }
        };
        let port_ok = match port {
            None => self.port == 80,
            Some(p) => p.parse::<u16>().is_ok_and(|p| p == self.port),
        };
        if !port_ok {
            return false;
        }
        if name.eq_ignore_ascii_case("localhost") {
            return true;
        }
        match name.parse::<IpAddr>() {
            Ok(ip) => ip.is_loopback() || self.any_address || Some(ip) == self.bound,
            Err(_) => false,
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
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        431 => "Request Header Fields Too Large",
        503 => "Service Unavailable",
        _ => "Error",
    }
}

/// The response to a request head (request line and headers) from a client
/// that reached the server by one of `hosts`, and whether the body is to be
/// left out (`HEAD`).
pub fn answer(site: &Site, hosts: &AllowedHosts, head: &[u8]) -> (Response, bool) {
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
    let mut host_values = head.split(|&b| b == b'\n').skip(1).filter_map(|line| {
        let line = String::from_utf8_lossy(line);
        let (name, value) = line.split_once(':')?;
        name.trim()
            .eq_ignore_ascii_case("host")
            .then(|| value.trim().to_owned())
    });
    match (host_values.next(), host_values.next()) {
        (Some(host), None) if hosts.allows(&host) => {}
        (Some(_), None) => {
            return (
                Response::status(403, "this server answers only to its own address\n"),
                false,
            );
        }
        _ => {
            return (
                Response::status(400, "bad request: one Host header\n"),
                false,
            )
        }
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

fn serve_connection(shared: &Shared, mut stream: TcpStream, id: u64) {
    let deadline = Instant::now() + REQUEST_HEAD_TIMEOUT;
    let mut head = Vec::with_capacity(1024);
    let mut buf = [0u8; 1024];
    let complete = loop {
        if head.windows(4).any(|w| w == b"\r\n\r\n") || head.windows(2).any(|w| w == b"\n\n") {
            break true;
        }
        if head.len() > MAX_REQUEST_HEAD_BYTES {
            break false;
        }
        // The whole head has one deadline, not each read: a client sending
        // a byte at a time is cut off as surely as a silent one.
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() || stream.set_read_timeout(Some(left)).is_err() {
            return;
        }
        match stream.read(&mut buf) {
            Ok(0) | Err(_) => return,
            Ok(n) => head.extend_from_slice(&buf[..n]),
        }
    };
    shared.answering(id);
    let (response, head_only) = if complete {
        answer(&shared.site, &shared.hosts, &head)
    } else {
        (Response::status(431, "request head too large\n"), false)
    };
    let _ = write_response(&mut stream, &response, head_only);
    let _ = stream.shutdown(std::net::Shutdown::Write);
}

/// Sends the response within [`RESPONSE_TIMEOUT`] in all, however slowly
/// the client reads.
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
    let body: &[u8] = if head_only { &[] } else { r.body };
    let deadline = Instant::now() + RESPONSE_TIMEOUT;
    for chunk in head
        .as_bytes()
        .chunks(64 * 1024)
        .chain(body.chunks(64 * 1024))
    {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(std::io::ErrorKind::TimedOut.into());
        }
        stream.set_write_timeout(Some(left))?;
        stream.write_all(chunk)?;
    }
    stream.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::site::tests::site;

    fn hosts() -> AllowedHosts {
        AllowedHosts::for_address("127.0.0.1:8080".parse().unwrap())
    }

    #[test]
    fn only_this_servers_own_names_are_answered() {
        let loopback = hosts();
        for good in [
            "localhost:8080",
            "LocalHost:8080",
            "127.0.0.1:8080",
            "[::1]:8080",
            " 127.0.0.1:8080 ",
        ] {
            assert!(loopback.allows(good), "{good}");
        }
        for bad in [
            "evil.example:8080",
            "localhost:8081",
            "localhost",
            "127.0.0.1",
            "localhost.:8080",
            "10.0.0.5:8080",
            "[::1]8080",
            "[::1",
            "",
            "localhost:8080:8080",
            "127.0.0.1.evil.example:8080",
        ] {
            assert!(!loopback.allows(bad), "{bad}");
        }
        // Bound to one address on purpose: that address too.
        let lan = AllowedHosts::for_address("192.168.1.20:9000".parse().unwrap());
        assert!(lan.allows("192.168.1.20:9000") && lan.allows("localhost:9000"));
        assert!(!lan.allows("192.168.1.21:9000") && !lan.allows("viewer.lan:9000"));
        // Bound to every address: any IP address, still no names.
        let any = AllowedHosts::for_address("[::]:80".parse().unwrap());
        assert!(any.allows("10.1.2.3") && any.allows("[fe80::1]:80"));
        assert!(!any.allows("rebound.example") && !any.allows("10.1.2.3:81"));
    }

    #[test]
    fn a_request_without_one_good_host_is_refused() {
        let (r, _) = answer(
            &site(),
            &hosts(),
            b"GET / HTTP/1.1\r\nHost: evil.example:8080\r\n\r\n",
        );
        assert_eq!(r.status, 403);
        let (r, _) = answer(&site(), &hosts(), b"GET / HTTP/1.1\r\n\r\n");
        assert_eq!(r.status, 400);
        let (r, _) = answer(
            &site(),
            &hosts(),
            b"GET / HTTP/1.1\r\nHost: localhost:8080\r\nhost: evil.example:8080\r\n\r\n",
        );
        assert_eq!(r.status, 400);
    }

    #[test]
    fn requests_are_answered_by_method() {
        let (r, head_only) = answer(
            &site(),
            &hosts(),
            b"GET /js/main.js HTTP/1.1\r\nHost: localhost:8080\r\n\r\n",
        );
        assert_eq!(
            (r.status, r.body, head_only),
            (200, &b"export {}"[..], false)
        );
        let (r, head_only) = answer(
            &site(),
            &hosts(),
            b"HEAD / HTTP/1.1\r\nHost: localhost:8080\r\n\r\n",
        );
        assert_eq!((r.status, head_only), (200, true));
        let (r, _) = answer(
            &site(),
            &hosts(),
            b"POST / HTTP/1.1\r\nHost: localhost:8080\r\n\r\n",
        );
        assert_eq!(r.status, 405);
        assert_eq!(r.headers, vec![("Allow", "GET, HEAD")]);
        for bad in [
            &b"GET /\r\n\r\n"[..],
            b"GET / HTTP/1.1 extra\r\n\r\n",
            b"GET / SPDY/3\r\n\r\n",
            b"\r\n\r\n",
        ] {
            assert_eq!(
                answer(&site(), &hosts(), bad).0.status,
                400,
                "{:?}",
                String::from_utf8_lossy(bad)
            );
        }
        assert_eq!(
            answer(
                &site(),
                &hosts(),
                b"GET /../etc/passwd HTTP/1.1\r\nHost: localhost:8080\r\n\r\n"
            )
            .0
            .status,
            404
        );
    }
}
