//! How far apart two threads' cores are: the time a value takes to go from
//! one thread to another and back through one cache line ([`PingLine`]).
//!
//! A frame on two threads hands data from core to core: setup's bins are
//! written on one thread and read by the bands on both. On a virtual
//! machine the host decides where the virtual cores run, and moves them:
//! on the Zen 5 EPYC of BENCHMARKS.md the round trip was 40–130 ns while
//! the two cores shared a last-level cache, 300–650 ns while they ran
//! apart, and microseconds while they took turns on one core. The tiled
//! rasterizer measures it to decide whether its bands hand back the bins
//! they read (`raster/tiled/placement.rs`); `shadelab bench` prints it
//! beside each run.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// One cache line through which one thread asks and another answers:
/// question `n` is the value `2n + 1`, its answer `2n + 2`.
#[derive(Debug, Default)]
#[repr(align(128))]
pub struct PingLine(AtomicU64);

/// The value that ends the answering thread's loop (odd, like a question,
/// so it is tested first).
const STOP: u64 = u64::MAX;

impl PingLine {
    /// A line with no question asked.
    pub fn new() -> PingLine {
        PingLine::default()
    }

    /// Asks question `n` (0, 1, 2, …, below `u64::MAX / 2`).
    pub fn ask(&self, n: u64) {
        self.0.store(2 * n + 1, Ordering::Release);
    }

    /// Whether question `n` has been answered.
    pub fn answered(&self, n: u64) -> bool {
        self.0.load(Ordering::Acquire) == 2 * n + 2
    }

    /// Ends the other thread's [`PingLine::answer`].
    pub fn stop(&self) {
        self.0.store(STOP, Ordering::Release);
    }

    /// The answering thread's side: answers each question as it comes,
    /// until [`PingLine::stop`], or until `limit` has passed (the asking
    /// thread gave up, or never came).
    pub fn answer(&self, limit: Duration) {
        let started = Instant::now();
        let mut spins = 0u32;
        loop {
            let value = self.0.load(Ordering::Acquire);
            if value == STOP {
                return;
            }
            if value % 2 == 1 {
                self.0.store(value + 1, Ordering::Release);
            }
            std::hint::spin_loop();
            spins = spins.wrapping_add(1);
            if spins.is_multiple_of(1024) && started.elapsed() > limit {
                return;
            }
        }
    }

    /// Waits until question `n` is answered, or until `limit` has passed
    /// since `started` (then `false`).
    pub fn wait(&self, n: u64, started: Instant, limit: Duration) -> bool {
        let mut spins = 0u32;
        while !self.answered(n) {
            std::hint::spin_loop();
            spins = spins.wrapping_add(1);
            if spins.is_multiple_of(1024) && started.elapsed() > limit {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Questions are answered in turn by another thread, and a stop ends
    /// its loop.
    #[test]
    fn questions_answered_until_stopped() {
        let line = PingLine::new();
        std::thread::scope(|scope| {
            scope.spawn(|| line.answer(Duration::from_secs(60)));
            let started = Instant::now();
            for n in 0..100 {
                assert!(!line.answered(n));
                line.ask(n);
                assert!(line.wait(n, started, Duration::from_secs(60)));
            }
            line.stop();
        });
    }

    /// With no one answering, waiting ends once its time has passed, and
    /// so does answering with no one asking.
    #[test]
    fn nobody_there_ends_in_time() {
        let line = PingLine::new();
        line.ask(0);
        assert!(!line.wait(0, Instant::now(), Duration::from_millis(1)));
        let quiet = PingLine::new();
        let started = Instant::now();
        quiet.answer(Duration::from_millis(1));
        assert!(started.elapsed() >= Duration::from_millis(1));
    }
}
