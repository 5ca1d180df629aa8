//! Where the pool's threads run: which of them are on cores apart from the
//! first thread's, found from a cache line's round trip, and what a band
//! does about it ([`HandBack`]).
//!
//! Design note. Each frame's bands read the bins that setup wrote on every
//! thread, and the next frame's setup writes the same lines again. A line
//! that another core has read must first be taken back from that core's
//! cache. Where the two cores share a last-level cache (a round trip of
//! 40–130 ns on the KVM Zen 5 EPYC of BENCHMARKS.md), that is quick;
//! where the host runs them apart (300–650 ns), setup waits for it: the
//! dragon's two-thread 1920×1080 Phong spent half a millisecond of its
//! setup's 1.6 ms on it. A band that flushes the lines of a bin set up
//! on a core apart from its own, once it has read them
//! ([`ReleaseLines`]), leaves them in memory alone, and the write takes
//! them from there (−6 % on two threads' mesh frames with the cores apart
//! on the Zen 5, −13 to −18 % on the KVM Zen 4 EPYC). With
//! the cores beside each other the same flush costs 3–6 %: the write
//! then waits for memory instead of the shared cache. The renderer
//! cannot see where the host puts its cores, and the host moves them, so
//! it measures ([`Placement::update`]): every tenth of a second
//! ([`EVERY`]), the first pool thread sends a value through one cache line
//! ([`PingLine`]) to each other thread and back, and a round trip above
//! [`APART`] puts that thread's core apart, one below [`BESIDE`] beside
//! (one between the two leaves it where it was: [`placed`]; BENCHMARKS.md,
//! "Bins handed back where the cores are apart").
//!
//! A measurement takes 25–40 µs on two threads; it changes no pixel, only
//! which lines are flushed.

use std::time::{Duration, Instant};

use super::chunk::{Bin, Chunk};
use crate::cores::PingLine;
use crate::simd::ReleaseLines;

/// Time between two measurements: a tenth of a second, so that a scene of
/// a few triangles, drawn in tens of microseconds, does not pay for one
/// every few frames.
const EVERY: Duration = Duration::from_millis(100);

/// A round trip longer than this puts a thread's core apart from the
/// first thread's; one shorter than [`BESIDE`], beside it; one between
/// the two keeps the thread where it was (at first: beside). On the KVM
/// Zen 5 EPYC the renderer's medians were 80–100 ns with the cores beside
/// each other and 340–460 ns apart, but 5 of 214 apart came to 220–231
/// ns: there a few of the trips take 190–250 ns, and sometimes most of
/// them do (BENCHMARKS.md, "Placement's readings").
const APART: Duration = Duration::from_nanos(250);

/// A round trip shorter than this puts a thread's core beside the first
/// thread's (see [`APART`]).
const BESIDE: Duration = Duration::from_nanos(150);

/// Round trips timed per thread; their median is taken.
const TRIPS: usize = 15;

/// How long the first thread waits for another to answer all its
/// questions (the first may find it asleep) before giving up this
/// measurement.
const ANSWER_LIMIT: Duration = Duration::from_millis(1);

/// Which of the pool's threads run on a core apart from the first
/// thread's, as last measured.
#[derive(Debug, Default)]
pub(super) struct Placement {
    /// Per pool thread, by index: whether its core is apart from thread
    /// 0's. Empty: one thread, or not known (no band hands anything back).
    apart: Vec<bool>,
    /// The pool's threads when last measured.
    threads: usize,
    /// When last measured.
    measured: Option<Instant>,
}

impl Placement {
    /// Called once a frame, on the calling thread of the frame's pool:
    /// measures where the threads are on the first frame, then once
    /// [`EVERY`] has passed, or as soon as the pool's size changes. With
    /// one thread it measures nothing; a measurement that fails (a thread
    /// that does not answer in time) keeps the last one, and is not tried
    /// again before [`EVERY`] has passed.
    pub(super) fn update(&mut self) {
        let threads = rayon::current_num_threads();
        if threads < 2 {
            self.apart.clear();
            return;
        }
        let now = Instant::now();
        let recent = self
            .measured
            .is_some_and(|at| now.saturating_duration_since(at) < EVERY);
        if recent && self.threads == threads {
            return;
        }
        self.measured = Some(now);
        self.threads = threads;
        if let Some(trips) = round_trips(threads) {
            self.apart = placed(&trips, &self.apart);
        } else if self.apart.len() != threads {
            self.apart.clear();
        }
    }

    /// What a band drawn on the calling thread hands back of the bins it
    /// reads.
    pub(super) fn hand_back(&self) -> HandBack<'_> {
        HandBack {
            lines: ReleaseLines::detect(),
            apart: &self.apart,
            here: rayon::current_thread_index(),
        }
    }

    /// As if measured: thread `k`'s core is apart from thread 0's where
    /// `apart[k]`.
    #[cfg(test)]
    pub(super) fn assume(&mut self, apart: Vec<bool>) {
        self.threads = apart.len();
        self.apart = apart;
        self.measured = Some(Instant::now() + Duration::from_secs(3600));
    }
}

/// What a band hands back to memory of the bins it has read: the lines of
/// those that setup wrote on a core apart from the band's own.
#[derive(Debug, Clone, Copy)]
pub(super) struct HandBack<'a> {
    lines: ReleaseLines,
    apart: &'a [bool],
    /// The band's thread.
    here: Option<usize>,
}

impl HandBack<'_> {
    /// Whether the bins of a chunk set up on thread `there` are handed back
    /// by this band: one of the two threads is apart from thread 0's core
    /// and the other is not. (Two threads both apart from it are taken to
    /// share a cache.)
    pub(super) fn from(&self, there: Option<usize>) -> bool {
        let side = |thread: Option<usize>| thread.and_then(|k| self.apart.get(k).copied());
        matches!((side(self.here), side(there)), (Some(a), Some(b)) if a != b)
    }

    /// Hands `bin`, of `chunk`, back once read, where [`HandBack::from`]
    /// says so.
    #[inline]
    pub(super) fn bin(&self, chunk: &Chunk, bin: &Bin) {
        if self.from(chunk.set_up_on) {
            bin.release(self.lines);
        }
    }
}

/// Where each thread is, from its round trip to thread 0 (`trips`) and
/// where it was (`last`; empty or of another pool: beside): apart above
/// [`APART`], beside below [`BESIDE`], and between the two where it was.
fn placed(trips: &[Duration], last: &[bool]) -> Vec<bool> {
    let was = |k: usize| last.len() == trips.len() && last[k];
    let place = |(k, &trip): (usize, &Duration)| trip > APART || (trip >= BESIDE && was(k));
    trips.iter().enumerate().map(place).collect()
}

/// Each pool thread's round trip to thread 0 (thread 0's own: zero), or
/// `None` if a thread did not answer in time.
fn round_trips(threads: usize) -> Option<Vec<Duration>> {
    let lines: Vec<PingLine> = (0..threads).map(|_| PingLine::new()).collect();
    // Every thread answers on its own line; thread 0 asks each in turn.
    let limit = ANSWER_LIMIT * threads as u32 + Duration::from_millis(10);
    let mut answers = rayon::broadcast(|context| match context.index() {
        0 => Some(
            lines[1..]
                .iter()
                .map(ask)
                .collect::<Option<Vec<Duration>>>(),
        ),
        k => {
            if let Some(line) = lines.get(k) {
                line.answer(limit);
            }
            None
        }
    });
    let mut trips = answers.swap_remove(0).flatten()?;
    trips.insert(0, Duration::ZERO);
    (trips.len() == threads).then_some(trips)
}

/// Thread 0's side: the median of [`TRIPS`] timed round trips through
/// `line` (the first, which may wait for the other thread to wake, is not
/// timed), or `None` if the other thread does not answer them all within
/// [`ANSWER_LIMIT`].
fn ask(line: &PingLine) -> Option<Duration> {
    let started = Instant::now();
    let mut trips = [Duration::ZERO; TRIPS];
    for trip in 0..=TRIPS {
        let sent_at = Instant::now();
        line.ask(trip as u64);
        if !line.wait(trip as u64, started, ANSWER_LIMIT) {
            line.stop();
            return None;
        }
        if trip > 0 {
            trips[trip - 1] = sent_at.elapsed();
        }
    }
    line.stop();
    trips.sort_unstable();
    Some(trips[TRIPS / 2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

    /// On two threads or more (as many as there are cores, up to four),
    /// every thread's round trip is measured (a busy machine may make one
    /// fail: then nothing is known, and the test tries again), and thread
    /// 0 is never apart from itself.
    #[test]
    fn every_thread_is_placed() {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        for threads in 2..=cores.min(4) {
            // Tests running beside this one, or other programs, may keep a
            // thread from answering in time: tried again for up to half a
            // minute (a machine with both cores busy failed two seconds).
            let started = Instant::now();
            let apart = pool(threads).install(|| loop {
                let mut placement = Placement::default();
                placement.update();
                if !placement.apart.is_empty() || started.elapsed() > Duration::from_secs(30) {
                    break placement.apart;
                }
                std::thread::sleep(Duration::from_millis(10));
            });
            assert!(!apart.is_empty(), "no measurement within 30 s");
            assert_eq!(apart.len(), threads);
            assert!(!apart[0]);
        }
    }

    /// One thread: nothing measured, nothing handed back.
    #[test]
    fn one_thread_measures_nothing() {
        pool(1).install(|| {
            let mut placement = Placement::default();
            placement.assume(vec![false, true]);
            placement.update();
            assert!(placement.apart.is_empty());
            assert!(!placement.hand_back().from(Some(1)));
        });
    }

    /// A measurement is kept until [`EVERY`] has passed, then taken again.
    #[test]
    fn measured_again_once_its_time_has_passed() {
        pool(2).install(|| {
            let mut placement = Placement::default();
            placement.update();
            // As if the last measurement had found something impossible:
            placement.apart = vec![true, true];
            placement.measured = Some(Instant::now());
            for _ in 0..100 {
                placement.update();
                assert_eq!(placement.apart, [true, true]);
            }
            placement.measured = Instant::now().checked_sub(EVERY);
            placement.update();
            // Measured again: thread 0 is never apart from itself (unless
            // the measurement failed and kept the last one).
            assert!(placement.apart == [true, true] || !placement.apart[0]);
        });
    }

    /// A round trip above [`APART`] puts a thread apart, one below
    /// [`BESIDE`] beside, and one between the two leaves it where it was;
    /// a pool of another size starts beside.
    #[test]
    fn placed_with_a_margin() {
        let ns = |trips: &[u64]| -> Vec<Duration> {
            trips.iter().map(|&n| Duration::from_nanos(n)).collect()
        };
        let trips = ns(&[0, 400, 90, 220, 220]);
        let last = [false, false, true, true, false];
        assert_eq!(placed(&trips, &last), [false, true, false, true, false]);
        assert_eq!(placed(&trips, &[]), [false, true, false, false, false]);
        assert_eq!(
            placed(&trips, &[true, true]),
            [false, true, false, false, false]
        );
        let edges = ns(&[0, 250, 251, 150, 149]);
        let last = [false, true, false, true, true];
        assert_eq!(placed(&edges, &last), [false, true, true, true, false]);
    }

    /// Bins are handed back between threads on different sides of thread
    /// 0's core only, and never by or from a thread outside the pool.
    #[test]
    fn handed_back_between_sides_only() {
        let hand_back = |apart: &[bool], here, there| {
            HandBack {
                lines: ReleaseLines::detect(),
                apart,
                here,
            }
            .from(there)
        };
        let apart = [false, true, false, true];
        assert!(hand_back(&apart, Some(0), Some(1)));
        assert!(hand_back(&apart, Some(1), Some(2)));
        assert!(!hand_back(&apart, Some(0), Some(2)));
        assert!(!hand_back(&apart, Some(1), Some(3)));
        assert!(!hand_back(&apart, Some(1), Some(1)));
        assert!(!hand_back(&apart, None, Some(1)));
        assert!(!hand_back(&apart, Some(1), None));
        assert!(!hand_back(&apart, Some(1), Some(7)));
        assert!(!hand_back(&[], Some(0), Some(1)));
        assert!(!hand_back(&[false, false], Some(0), Some(1)));
    }
}
