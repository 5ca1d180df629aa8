//! `shadelab view`: serves the viewer on this machine, or writes it out as
//! a static site.

use std::io::Write;
use std::net::{IpAddr, SocketAddr};
use std::path::Path;

use anyhow::{bail, Context};

use crate::server::Server;
use crate::site::Site;

/// What `shadelab view` was asked to do.
pub struct ViewRequest<'a> {
    /// Address to listen on.
    pub host: IpAddr,
    /// Port (0: any free port).
    pub port: u16,
    /// Open the page in a browser.
    pub open: bool,
    /// Write the static site here instead of serving it.
    pub export: Option<&'a Path>,
    /// The language of the messages and of the page opened (None: the browser's).
    pub lang: Option<crate::cli::LangArg>,
}

/// Serves the viewer until the process is stopped, or exports it.
///
/// # Errors
/// When the binary has no WebAssembly, the address cannot be bound, or the
/// export directory is not new or empty or cannot be written.
pub fn view(request: &ViewRequest<'_>) -> anyhow::Result<()> {
    let site = Site::embedded()?;
    if let Some(dir) = request.export {
        return export(&site, dir);
    }
    let addr = SocketAddr::new(request.host, request.port);
    let server = Server::bind(addr).map_err(|e| {
        let hint = if request.port != 0 {
            " (another port: --port N, or --port 0 for any free one)".to_string()
        } else {
            String::new()
        };
        anyhow::anyhow!("cannot listen on {addr}: {e}{hint}")
    })?;
    let texts = shadelab_lab::Texts::new(request.lang.map_or(shadelab_lab::Lang::En, Into::into));
    // The page speaks the language asked for; the first line stays the same
    // in every language, for scripts that read the address from it.
    let url = match request.lang {
        Some(lang) => format!("{}#lang={}", page_url(server.addr()), lang.code()),
        None => page_url(server.addr()),
    };
    say(&format!("shadelab viewer: {url}"));
    if !request.host.is_loopback() {
        say(&texts.fill("cli.view_remote", &[("host", &request.host.to_string())]));
    }
    say(texts.get("cli.view_stop"));
    if request.open {
        open_browser(&url, &texts);
    }
    server.run(site);
    Ok(())
}

/// Prints a line; a server whose output has gone away (a closed pipe) keeps serving.
fn say(line: &str) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{line}").and_then(|()| out.flush());
}

/// The page's address; an unspecified host (0.0.0.0, ::) is shown as loopback.
fn page_url(addr: SocketAddr) -> String {
    let ip = match addr.ip() {
        IpAddr::V4(v4) if v4.is_unspecified() => IpAddr::V4(std::net::Ipv4Addr::LOCALHOST),
        IpAddr::V6(v6) if v6.is_unspecified() => IpAddr::V6(std::net::Ipv6Addr::LOCALHOST),
        ip => ip,
    };
    format!("http://{}/", SocketAddr::new(ip, addr.port()))
}

/// Opens `url` in the desktop's browser, when there is a desktop.
fn open_browser(url: &str, texts: &shadelab_lab::Texts) {
    // Without a display, opening would at best fail and at worst start a
    // text browser in this terminal.
    let has_display = !cfg!(all(unix, not(target_os = "macos")))
        || std::env::var_os("DISPLAY").is_some()
        || std::env::var_os("WAYLAND_DISPLAY").is_some();
    if !has_display || open::that_detached(url).is_err() {
        say(&texts.fill("cli.view_open", &[("url", url)]));
    }
}

/// Writes the site's files into `dir`, which must be new or empty.
fn export(site: &Site, dir: &Path) -> anyhow::Result<()> {
    if dir.exists() {
        let mut entries =
            std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))?;
        if entries.next().is_some() {
            bail!(
                "{} is not empty; export into a new or empty directory (nothing is overwritten)",
                dir.display()
            );
        }
    }
    for (name, bytes) in site.files() {
        let path = dir.join(name);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot create {}", parent.display()))?;
        }
        shadelab_io::write_atomic(&path, |out| out.write_all(bytes))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    writeln!(
        std::io::stdout().lock(),
        "wrote the viewer ({} files) to {}; serve that directory with any web server \
         (it must send .wasm files as application/wasm)",
        site.files().len(),
        dir.display()
    )
    .context("cannot write to standard output")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unspecified_hosts_are_shown_as_loopback() {
        let any: SocketAddr = "0.0.0.0:8080".parse().unwrap();
        assert_eq!(page_url(any), "http://127.0.0.1:8080/");
        let any6: SocketAddr = "[::]:9000".parse().unwrap();
        assert_eq!(page_url(any6), "http://[::1]:9000/");
        let lo: SocketAddr = "127.0.0.1:8080".parse().unwrap();
        assert_eq!(page_url(lo), "http://127.0.0.1:8080/");
    }
}
