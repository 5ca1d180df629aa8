//! Progress of a run: a bar on a terminal, plain lines in a log.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use shadelab_core::escape_message;

/// Writes one line to standard error, its control characters escaped; a
/// closed or full standard error loses the line rather than panicking.
fn say(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{}", escape_message(line));
}

/// How a run shows its progress (on standard error).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Progress {
    /// A bar when standard error is a terminal, lines otherwise.
    #[default]
    Auto,
    /// An `indicatif` bar.
    Bar,
    /// A plain line at most every few seconds, and one per failed mesh.
    Lines,
    /// Nothing.
    Quiet,
}

/// Seconds between two plain progress lines.
const LINE_INTERVAL: Duration = Duration::from_secs(5);

/// The progress display of one run.
pub(crate) struct Reporter {
    bar: Option<ProgressBar>,
    lines: Option<Mutex<Lines>>,
    total: u64,
    start: Instant,
}

struct Lines {
    done: u64,
    images: u64,
    last: Instant,
}

impl Reporter {
    /// A display for `total` meshes.
    pub(crate) fn new(progress: Progress, total: u64) -> Reporter {
        let mode = match progress {
            Progress::Auto if std::io::stderr().is_terminal() => Progress::Bar,
            Progress::Auto => Progress::Lines,
            other => other,
        };
        let start = Instant::now();
        let bar = (mode == Progress::Bar).then(|| {
            let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template(
                    "{elapsed_precise} [{bar:40}] {pos}/{len} meshes  {msg}  eta {eta}",
                )
                .expect("a valid template")
                .progress_chars("=> "),
            );
            bar
        });
        let lines = (mode == Progress::Lines).then(|| {
            Mutex::new(Lines {
                done: 0,
                images: 0,
                last: start,
            })
        });
        Reporter {
            bar,
            lines,
            total,
            start,
        }
    }

    /// One mesh finished with `images` drawn; `failure` is its error, if any.
    pub(crate) fn mesh_done(&self, images: u64, total_images: u64, failure: Option<&str>) {
        let rate = total_images as f64 / self.start.elapsed().as_secs_f64().max(1e-9);
        if let Some(bar) = &self.bar {
            if let Some(f) = failure {
                bar.println(format!("error: {}", escape_message(f)));
            }
            bar.set_message(format!("{total_images} images, {rate:.1}/s"));
            bar.inc(1);
        }
        if let Some(lines) = &self.lines {
            let mut l = lines.lock().unwrap_or_else(|e| e.into_inner());
            l.done += 1;
            l.images += images;
            if let Some(f) = failure {
                say(&format!("error: {f}"));
            }
            if l.last.elapsed() >= LINE_INTERVAL || l.done == self.total {
                l.last = Instant::now();
                say(&format!(
                    "progress: {}/{} meshes, {total_images} images, {rate:.1} images/s, {:.0} s",
                    l.done,
                    self.total,
                    self.start.elapsed().as_secs_f64()
                ));
            }
        }
    }

    /// A manifest line could not be used.
    pub(crate) fn line_failed(&self, message: &str) {
        if let Some(bar) = &self.bar {
            bar.println(format!("error: {}", escape_message(message)));
        } else if self.lines.is_some() {
            say(&format!("error: {message}"));
        }
    }

    /// The run is over.
    pub(crate) fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
