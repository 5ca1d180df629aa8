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
//! "Where the two threads' cores are"). The line and its questions are
//! the renderer's own ([`PingLine`]), which measures them to decide where
//! its bands hand back their bins; here they are timed over many more
//! round trips, and averaged.

use std::time::{Duration, Instant};

use shadelab_core::cores::PingLine;

/// Round trips per sample.
const TRIPS: u64 = 2_000;

/// Samples taken; their median is reported.
const SAMPLES: usize = 5;

/// The most one sample may take: where the two threads share one core, a
/// round trip can take a scheduler's time slice.
const SAMPLE_LIMIT: Duration = Duration::from_millis(20);

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

/// One sample: the mean of [`TRIPS`] round trips to a thread of its own
/// (fewer if [`SAMPLE_LIMIT`] passes), the first not timed (the other
/// thread may take a while to start).
fn sample() -> Option<f64> {
    let line = PingLine::new();
    std::thread::scope(|scope| {
        scope.spawn(|| line.answer(2 * SAMPLE_LIMIT));
        let mut trips = 0;
        let mut start = Instant::now();
        for trip in 0..=TRIPS {
            if trip == 1 {
                start = Instant::now();
            }
            line.ask(trip);
            if !line.wait(trip, start, SAMPLE_LIMIT) {
                line.stop();
                return (trips > 0).then(|| per_trip(start, trips));
            }
            trips = trip;
        }
        line.stop();
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
