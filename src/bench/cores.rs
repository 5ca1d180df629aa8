//! How far apart the cores are: the round trip of one cache line between
//! two threads, printed beside each bench run.
//!
//! A frame on two threads hands data from core to core: setup's bins are
//! written on one thread and read by the bands on both. On a virtual
//! machine the host decides where the two virtual cores run, and moves
//! them: on the Zen 5 EPYC of BENCHMARKS.md the same binary's two-thread
//! frame of the bunny at 1920×1080 (flat) took 1.7–1.8 ms while this round
//! trip was 40–60 ns (the cores share a last-level cache), 2.1–2.2 ms while
//! it was 430–650 ns, and as long as one thread's frame while it was
//! microseconds (the two virtual cores taking turns on one core). One
//! thread's frames did not change. A run that prints this can be read for
//! what the host did, not only for what the code did (BENCHMARKS.md,
//! "Where the two threads' cores are").

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Round trips per sample.
const TRIPS: u64 = 2_000;

/// Samples taken; their median is reported.
const SAMPLES: usize = 5;

/// The most one sample may take: where the two threads share one core, a
/// round trip can take a scheduler's time slice.
const SAMPLE_LIMIT: Duration = Duration::from_millis(20);

/// One cache line, alone on its line.
#[repr(align(128))]
struct Line(AtomicU64);

/// The median time, in nanoseconds, for one value to go from this thread
/// to another and back through one cache line, or `None` with fewer than
/// two `cores`.
pub(super) fn round_trip_ns(cores: usize) -> Option<f64> {
    if cores < 2 {
        return None;
    }
    let mut samples: Vec<f64> = (0..SAMPLES).filter_map(|_| sample()).collect();
    samples.sort_by(f64::total_cmp);
    samples.get(samples.len() / 2).copied()
}

/// One sample: this thread writes an odd number, the other answers with
/// the next even one, [`TRIPS`] times (fewer if [`SAMPLE_LIMIT`] passes).
fn sample() -> Option<f64> {
    let line = Line(AtomicU64::new(0));
    // The value that tells the other thread to stop.
    const STOP: u64 = u64::MAX;
    std::thread::scope(|scope| {
        scope.spawn(|| loop {
            // An odd value is a new question (the answer, even, stays until
            // the next one); `STOP` is odd too, so it is tested first.
            let value = line.0.load(Ordering::Acquire);
            if value == STOP {
                return;
            }
            if value % 2 == 1 {
                line.0.store(value + 1, Ordering::Release);
            }
            std::hint::spin_loop();
        });
        // The other thread may take a while to start: the first trip is
        // not timed.
        let mut trips = 0;
        let mut start = Instant::now();
        for trip in 0..=TRIPS {
            if trip == 1 {
                start = Instant::now();
            }
            let sent = 2 * trip + 1;
            line.0.store(sent, Ordering::Release);
            let mut waited = 0u32;
            while line.0.load(Ordering::Acquire) != sent + 1 {
                std::hint::spin_loop();
                waited = waited.wrapping_add(1);
                if waited.is_multiple_of(4096) && start.elapsed() > SAMPLE_LIMIT {
                    line.0.store(STOP, Ordering::Release);
                    return (trips > 0).then(|| per_trip(start, trips));
                }
            }
            trips = trip;
        }
        line.0.store(STOP, Ordering::Release);
        Some(per_trip(start, trips))
    })
}

fn per_trip(start: Instant, trips: u64) -> f64 {
    start.elapsed().as_nanos() as f64 / trips as f64
}

#[cfg(test)]
mod tests {
    use super::round_trip_ns;

    /// With two cores or more, a round trip is measured and takes some
    /// time, less than the limit of a sample.
    #[test]
    fn a_round_trip_is_measured_where_there_are_two_cores() {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        match round_trip_ns(cores) {
            Some(ns) => {
                assert!(cores >= 2);
                assert!(ns > 0.0 && ns < 20e6, "{ns} ns");
            }
            None => assert!(cores < 2),
        }
    }
}
