//! How a frame's parallel work is shared between threads: setup's chunks
//! and the bands, by their estimated cost.
//!
//! Design note. Threads end a phase together only if they are given about
//! the same work, and jobs differ manyfold. Bands: a dense mesh's middle
//! rows against the empty rows above and below it (the dragon at
//! 1920×1080, Phong, one thread: 2–191 µs a band, 6.1 ms in all). Chunks:
//! a back face stops at facing, a front face is set up and binned, and
//! meshes list their visible faces unevenly. Rayon's halving of the jobs by
//! count ended the dragon's bands with one thread waiting for the other
//! about 120 µs a frame; by then that thread had often gone to sleep, and
//! waking it cost about 50 µs more. So ([`by_cost`]):
//!
//! * **The cheapest jobs are kept for last**, a tail of about an eighth of
//!   the estimated cost, taken costliest first by whichever thread is free:
//!   what the estimates got wrong is made up with small jobs, and the
//!   threads end within a few microseconds of each other. Setup's tail is
//!   one queue; the bands' is two, one per end of the runs ([`Tail`]), so
//!   that a band of the tail is drawn by the same thread from frame to
//!   frame and its image rows stay in that thread's cache.
//! * **The others are cut into one run of neighbouring jobs per thread**,
//!   of about the same estimated cost, each done in order. That keeps
//!   what halving by count did well: the bins a thread's setup writes for a
//!   part of the image are mostly read by its own bands. All the jobs taken
//!   costliest first from one queue ended the dragon's bands together too,
//!   but made the bunny's 1920×1080 Phong 2–3 % slower with the two cores
//!   apart (BENCHMARKS.md, "Bands and chunks shared by cost").
//!
//! A band's cost is estimated from its bins: its triangles, and the pixels
//! of the columns they span ([`band_cost`]). A chunk's, from what its
//! polygons did in the last frame: how many were set up ([`chunk_cost`]);
//! a first frame's chunks are shared by count.
//!
//! The order changes no pixel: a chunk bins into bins of its own, and a
//! band is drawn alone, reading the chunks' bins in submission order.

use std::cmp::Reverse;
use std::sync::Mutex;

use rayon::prelude::*;

use super::chunk::{band_columns, Chunk};
use super::setup::BAND_ROWS;
use crate::scene::Shading;

/// A piece of a phase's work: its index (a chunk's or a band's), its
/// estimated cost and what it writes (`work`).
pub(super) struct Job<T> {
    pub(super) index: usize,
    cost: u64,
    pub(super) work: T,
}

impl<T> Job<T> {
    pub(super) fn new(index: usize, cost: u64, work: T) -> Option<Job<T>> {
        Some(Job { index, cost, work })
    }
}

/// A kind of job's work, which borrows a frame's buffers (`At<'a>`).
pub(super) trait Borrows {
    type At<'a>: Send;
}

/// A list of jobs kept from frame to frame for its allocation (the tiled
/// rasterizer allocates nothing per frame once warmed up). A job is taken
/// out of its slot when it is done.
pub(super) struct Jobs<B: Borrows>(Vec<Option<Job<B::At<'static>>>>);

impl<B: Borrows> Default for Jobs<B> {
    fn default() -> Jobs<B> {
        Jobs(Vec::new())
    }
}

impl<B: Borrows> std::fmt::Debug for Jobs<B> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Jobs(capacity {})", self.0.capacity())
    }
}

impl<B: Borrows> Jobs<B> {
    /// An empty list, with this one's allocation, for a frame's buffers.
    pub(super) fn take<'a>(&mut self) -> Vec<Option<Job<B::At<'a>>>> {
        relend(std::mem::take(&mut self.0))
    }

    /// Keeps the allocation of a frame's list.
    pub(super) fn keep(&mut self, jobs: Vec<Option<Job<B::At<'_>>>>) {
        self.0 = relend(jobs);
    }
}

/// `jobs`, emptied, as a list for work of another lifetime, in the same
/// allocation: collected in place (the two types have the same layout),
/// with no job in it to outlive what it borrowed.
fn relend<T, U>(mut jobs: Vec<Option<Job<T>>>) -> Vec<Option<Job<U>>> {
    jobs.clear();
    jobs.into_iter().map(|_| unreachable!()).collect()
}

/// Does `jobs` (in index order; each slot emptied as its job is done) on
/// the threads of the current pool. `run` does job `index` with its work
/// and returns its counts; `add` adds them up.
///
/// The cheapest jobs, about a [`TAIL_SHARE`]th of the estimated cost, are
/// set apart as the tail. The others are cut into one run of neighbouring
/// jobs per thread, of about the same estimated cost ([`cut_point`], again
/// in each part for more than two threads). A thread does its run in
/// order, then takes jobs of the tail, costliest first, until none is
/// left: what the estimates got wrong is made up with cheap jobs. The tail
/// is one queue, or one per end of the runs ([`Tail`]). Rayon halves each
/// run for a thread that has nothing left to do.
pub(super) fn by_cost<T, R, F, A>(jobs: &mut [Option<Job<T>>], tail: Tail, run: &F, add: &A) -> R
where
    T: Send,
    R: Default + Send,
    F: Fn(usize, T) -> R + Sync,
    A: Fn(R, R) -> R + Sync,
{
    let threads = rayon::current_num_threads();
    if threads < 2 {
        // In index order, with no job handed to rayon.
        let jobs = jobs.iter_mut().filter_map(Option::take);
        return jobs.fold(R::default(), |counts, job| {
            add(counts, run(job.index, job.work))
        });
    }
    let (runs, front) = set_tail_apart(jobs, tail);
    let (runs, tail_jobs) = jobs.split_at_mut(runs);
    let (front, back) = tail_jobs.split_at_mut(front);
    let queues = [Queue::new(front), Queue::new(back)];
    let cuts = threads.next_power_of_two().trailing_zeros();
    // One queue: every thread takes from the front's.
    let end = match tail {
        Tail::One => Some(End::Front),
        Tail::PerEnd => None,
    };
    in_runs(runs, cuts, &queues, end, run, add)
}

/// How the threads share the tail ([`by_cost`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Tail {
    /// One queue, costliest first, for jobs whose output no thread keeps:
    /// setup's chunks, whose bins are read by every band wherever they
    /// were written. (Setup from two queues, as [`Tail::PerEnd`], made the
    /// bunny's two-thread frames 1 % slower: its cheap chunks, taken apart
    /// by index, balanced less well.)
    One,
    /// Two queues, one per end of the runs ([`set_tail_apart`]), for jobs
    /// whose output stays in the cache of the thread that wrote it: the
    /// bands, whose image rows the next frame writes again.
    PerEnd,
}

/// [`by_cost`] of `jobs` cut `cuts` more times, then of the `tail`, taken
/// first from the queue of the thread's `end` (the first cut's side).
fn in_runs<T, R, F, A>(
    jobs: &mut [Option<Job<T>>],
    cuts: u32,
    tail: &[Queue<'_, T>; 2],
    end: Option<End>,
    run: &F,
    add: &A,
) -> R
where
    T: Send,
    R: Default + Send,
    F: Fn(usize, T) -> R + Sync,
    A: Fn(R, R) -> R + Sync,
{
    if cuts == 0 || jobs.len() < 2 {
        let (own, other) = match end.unwrap_or(End::Front) {
            End::Front => (&tail[0], &tail[1]),
            End::Back => (&tail[1], &tail[0]),
        };
        let mut counts = jobs
            .par_iter_mut()
            // Each job on its own, so that a thread out of work can take
            // any one left.
            .with_max_len(1)
            .filter_map(|slot| slot.take())
            .map(|job| run(job.index, job.work))
            .reduce(R::default, add);
        // Its own queue's jobs costliest first, then the other's cheapest
        // first (its threads take the costliest).
        while let Some(job) = own
            .take(Iterator::next)
            .or_else(|| other.take(|jobs| jobs.next_back()))
        {
            counts = add(counts, run(job.index, job.work));
        }
        return counts;
    }
    let (before, after) = jobs.split_at_mut(cut_point(jobs));
    // The first cut gives each side its end; later cuts keep it.
    let (first, second) = (end.or(Some(End::Front)), end.or(Some(End::Back)));
    let (a, b) = rayon::join(
        || in_runs(before, cuts - 1, tail, first, run, add),
        || in_runs(after, cuts - 1, tail, second, run, add),
    );
    add(a, b)
}

/// Which part of the tail a thread takes its jobs from first: the threads
/// of the runs before the first cut, the front's; the others, the back's
/// (see [`set_tail_apart`]).
#[derive(Clone, Copy)]
enum End {
    Front,
    Back,
}

/// One part of the tail, as a queue shared by the threads. Aligned to
/// keep each part's lock on cache lines of its own: a thread taking jobs
/// from its own part does not take the line of the other's.
#[repr(align(128))]
struct Queue<'s, T>(Mutex<std::slice::IterMut<'s, Option<Job<T>>>>);

impl<'s, T> Queue<'s, T> {
    fn new(jobs: &'s mut [Option<Job<T>>]) -> Queue<'s, T> {
        Queue(Mutex::new(jobs.iter_mut()))
    }

    /// The job that `at` picks, if any is left.
    fn take(
        &self,
        at: impl FnOnce(&mut std::slice::IterMut<'s, Option<Job<T>>>) -> Option<&'s mut Option<Job<T>>>,
    ) -> Option<Job<T>> {
        // The lock is held for the taking alone.
        let slot = at(&mut self
            .0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner()));
        slot.and_then(Option::take)
    }
}

/// How much of the jobs' estimated cost the tail holds: a
/// `TAIL_SHARE`th.
const TAIL_SHARE: u64 = 8;

/// Sets the tail apart (see [`by_cost`]): the cheapest jobs, whose costs
/// add up to at most a [`TAIL_SHARE`]th of the total, go to the end of
/// `jobs`; the others stay before them in index order. Returns how many
/// the others are, and how many of the tail's jobs are its front part.
///
/// With [`Tail::One`] the whole tail is the front part. With
/// [`Tail::PerEnd`] it is cut in two by index ([`cut_point`]): the front
/// part of lower index and the back part. Each part is costliest first
/// (ties in index order). The threads of the runs before the first cut
/// take the front part's jobs first, the others the back's ([`End`]): a
/// band of the tail then goes to the same thread frame after frame, but
/// where a thread takes from the other's part, and its image rows stay in
/// that thread's cache. (From one queue, the tail's bands changed threads
/// from frame to frame: the full-screen quad's 1920×1080 flat frames took
/// 2–4 % longer on two threads with the cores apart; BENCHMARKS.md, "The
/// tail's bands kept by their threads".)
fn set_tail_apart<T>(jobs: &mut [Option<Job<T>>], queues: Tail) -> (usize, usize) {
    let total: u64 = jobs.iter().map(cost).sum();
    // Cheapest first (ties: the later first), then the tail's length.
    jobs.sort_unstable_by_key(|job| job.as_ref().map(|job| (job.cost, Reverse(job.index))));
    let (mut tail, mut sum) = (0, 0);
    while tail < jobs.len() && (sum + cost(&jobs[tail])) * TAIL_SHARE <= total {
        sum += cost(&jobs[tail]);
        tail += 1;
    }
    let by_index = |job: &Option<Job<T>>| job.as_ref().map(|job| job.index);
    let (tail, runs) = jobs.split_at_mut(tail);
    runs.sort_unstable_by_key(by_index);
    let front = match queues {
        Tail::PerEnd if tail.len() >= 2 => {
            tail.sort_unstable_by_key(by_index);
            cut_point(tail)
        }
        _ => tail.len(),
    };
    let (before, after) = tail.split_at_mut(front);
    for part in [before, after] {
        part.sort_unstable_by_key(|job| (Reverse(cost(job)), by_index(job)));
    }
    let runs = runs.len();
    jobs.rotate_left(jobs.len() - runs);
    (runs, front)
}

/// A job's estimated cost, at least 1, so that jobs of unknown cost are
/// shared by count.
fn cost<T>(job: &Option<Job<T>>) -> u64 {
    job.as_ref().map_or(0, |job| job.cost).max(1)
}

/// Where to cut `jobs` (at least two) into two runs: after the job `k`
/// (1 ≤ `k` < jobs) where the running sum of the costs is closest to half
/// their total ([`cost`]: jobs of unknown cost are cut in the middle).
fn cut_point<T>(jobs: &[Option<Job<T>>]) -> usize {
    let total: u64 = jobs.iter().map(cost).sum();
    let (mut k, mut sum) = (0, 0);
    // The first running sum at or past half, or the one before it (ties:
    // the one before).
    while k < jobs.len() - 1 && 2 * (sum + cost(&jobs[k])) < total {
        sum += cost(&jobs[k]);
        k += 1;
    }
    let next = sum + cost(&jobs[k]);
    let k = if k > 0 && total - 2 * sum <= 2 * next - total {
        k
    } else {
        k + 1
    };
    k.min(jobs.len() - 1)
}

/// The estimated cost of band `index` of an image `width × height`, for
/// `method` (`None`: the three methods at once), from `chunks`' bins: its
/// triangles, the pixels of the columns they span, and its rows written.
pub(super) fn band_cost(
    chunks: &[Chunk],
    index: usize,
    (width, height): (u32, u32),
    method: Option<Shading>,
) -> u64 {
    let triangles: usize = chunks.iter().map(|c| c.bins[index].triangles.len()).sum();
    let rows = u64::from((height - (index as u32 * BAND_ROWS).min(height)).min(BAND_ROWS));
    let spanned = band_columns(chunks, index).len() as u64 * rows;
    triangles as u64 * TRIANGLE_COST + spanned * pixel_cost(method) + u64::from(width) * rows / 4
}

/// A triangle's cost in a band, in the units of [`pixel_cost`] (about half
/// a nanosecond). Fitted to one thread's band times (the bunny, the dragon
/// and the full-screen quad, 512² and 1920×1080, the three methods): about
/// 40–60 ns a triangle, and 1–3 µs for a band's 1920 × 16 pixels written.
const TRIANGLE_COST: u64 = 96;

/// The cost of a pixel of the columns a band's triangles span, against
/// [`TRIANGLE_COST`]: about 2.4–3.9 ns for Phong (the three methods at
/// once: Phong's walk), 0.7–1.2 ns for Gouraud and 0.05–0.6 ns for flat.
fn pixel_cost(method: Option<Shading>) -> u64 {
    match method {
        Some(Shading::Flat) => 1,
        Some(Shading::Gouraud) => 2,
        Some(Shading::Phong) | None => 6,
    }
}

/// The estimated cost of setting up `polygons` polygons in `chunk`, from
/// its last frame: each polygon faced, and those set up (front faces, and
/// back faces drawn) [`FRONT_COST`] times more.
pub(super) fn chunk_cost(chunk: &Chunk, polygons: usize) -> u64 {
    polygons as u64 + chunk.stats.rasterized * FRONT_COST
}

/// How much more a polygon set up and binned costs than one culled.
const FRONT_COST: u64 = 8;

#[cfg(test)]
mod tests {
    use super::*;

    fn jobs(costs: &[u64]) -> Vec<Option<Job<usize>>> {
        costs
            .iter()
            .enumerate()
            .map(|(index, &cost)| Job::new(index, cost, index))
            .collect()
    }

    fn cut(costs: &[u64]) -> usize {
        cut_point(&jobs(costs))
    }

    #[test]
    fn cuts_where_the_costs_are_closest() {
        assert_eq!(cut(&[1, 1]), 1);
        assert_eq!(cut(&[1, 1, 1, 1]), 2);
        assert_eq!(cut(&[1, 1, 1, 1, 1]), 2);
        assert_eq!(cut(&[0, 0, 0, 0, 0, 0]), 3);
        assert_eq!(cut(&[10, 1, 1, 1]), 1);
        assert_eq!(cut(&[1, 1, 1, 10]), 3);
        assert_eq!(cut(&[50, 60]), 1);
        assert_eq!(cut(&[2, 2, 50, 40, 2, 2, 2]), 3);
        assert_eq!(cut(&[2, 2, 40, 50, 2, 2, 2]), 3);
        assert_eq!(cut(&[2, 2, 30, 30, 30, 2, 2]), 3);
    }

    /// Every job is done once, with its own work, and the counts add up:
    /// on one thread in index order, on more threads in any order, with
    /// the tail in one queue or two.
    #[test]
    fn every_job_once() {
        let costs: Vec<u64> = (0..200).map(|i| (i * 37) % 11).collect();
        let all = [1, 2, 3, 4].map(|threads| [(threads, Tail::One), (threads, Tail::PerEnd)]);
        for (threads, queues) in all.into_iter().flatten() {
            let mut list = jobs(&costs);
            let order = std::sync::Mutex::new(Vec::new());
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let run = |index: usize, work: usize| {
                assert_eq!(index, work);
                order.lock().unwrap().push(index);
                (1, index as u64)
            };
            let add = |a: (u64, u64), b: (u64, u64)| (a.0 + b.0, a.1 + b.1);
            let counts = pool.install(|| by_cost(&mut list, queues, &run, &add));
            assert_eq!(counts, (200, (0..200).sum()));
            assert!(list.iter().all(Option::is_none));
            let mut order = order.into_inner().unwrap();
            if threads == 1 {
                assert_eq!(order, (0..200).collect::<Vec<_>>());
            }
            order.sort();
            assert_eq!(order, (0..200).collect::<Vec<_>>());
        }
    }

    fn indices<T>(list: &[Option<Job<T>>]) -> Vec<usize> {
        list.iter().map(|job| job.as_ref().unwrap().index).collect()
    }

    /// The tail: the cheapest jobs, an eighth of the cost, at the end, in
    /// one part or two cut by index, each costliest first; the others in
    /// index order.
    #[test]
    fn the_cheapest_jobs_are_set_apart() {
        let costs = [40, 1, 30, 2, 0, 50, 2, 30, 1];
        // Total 157 (the 0 counts 1): the tail holds at most 19. It is 1,
        // 3, 4, 6 and 8, of costs 1, 2, 1, 2 and 1.
        let mut list = jobs(&costs);
        assert_eq!(set_tail_apart(&mut list, Tail::One), (4, 5));
        assert_eq!(indices(&list), [0, 2, 5, 7, 3, 6, 1, 4, 8]);
        // Cut after 3: the front part holds 3 then 1, the back 6, 4 and 8.
        let mut list = jobs(&costs);
        assert_eq!(set_tail_apart(&mut list, Tail::PerEnd), (4, 2));
        assert_eq!(indices(&list), [0, 2, 5, 7, 3, 1, 6, 4, 8]);
        // Equal costs: the last jobs make the tail.
        let mut list = jobs(&[5; 16]);
        assert_eq!(set_tail_apart(&mut list, Tail::PerEnd), (14, 1));
        assert_eq!(indices(&list), (0..16).collect::<Vec<_>>());
        // A tail of one job is all front.
        let mut list = jobs(&[5, 5, 5, 5, 1]);
        assert_eq!(set_tail_apart(&mut list, Tail::PerEnd), (4, 1));
    }

    /// The order in which the tail's jobs are done while one thread's run
    /// is held up: the other thread does them all, its own part's
    /// costliest first, then, with two queues, the other part's from its
    /// cheapest. So with the runs ending together each thread keeps to its
    /// part, frame after frame.
    #[test]
    fn a_thread_takes_its_own_part_of_the_tail_first() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        use std::time::{Duration, Instant};
        // Runs 0..4 and 4..8; the tail 8..14 (costs 1 to 6) is cut after
        // 11: front 8..12, back 12..14.
        let costs = [100, 100, 100, 100, 100, 100, 100, 100, 1, 2, 3, 4, 5, 6];
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        for (queues, expected) in [
            (Tail::One, [13, 12, 11, 10, 9, 8]),
            (Tail::PerEnd, [11, 10, 9, 8, 12, 13]),
        ] {
            let mut list = jobs(&costs);
            let (tail, done) = (std::sync::Mutex::new(Vec::new()), AtomicUsize::new(0));
            let run = |index: usize, _| {
                if index >= 8 {
                    tail.lock().unwrap().push(index);
                    done.fetch_add(1, Ordering::SeqCst);
                } else if index == 4 {
                    // The second run's first job waits for the whole tail
                    // (done before it, if one thread took both runs).
                    let start = Instant::now();
                    while done.load(Ordering::SeqCst) < 6 {
                        assert!(
                            start.elapsed() < Duration::from_secs(20),
                            "the tail was not done"
                        );
                        std::thread::yield_now();
                    }
                }
            };
            pool.install(|| by_cost(&mut list, queues, &run, &|(), ()| ()));
            assert_eq!(tail.into_inner().unwrap(), expected, "{queues:?}");
        }
    }

    /// A band's cost: its triangles, the columns they span, its rows
    /// written; empty bins (whose columns are `i32::MAX..i32::MIN`) span
    /// none, and the last band may be short.
    #[test]
    fn band_costs_from_the_bins() {
        let mut chunks = [Chunk::default(), Chunk::default()];
        for chunk in &mut chunks {
            chunk.bins.resize_with(3, Default::default);
            chunk
                .bins
                .iter_mut()
                .for_each(super::super::chunk::Bin::clear);
        }
        let size = (64, 40);
        let phong = Some(Shading::Phong);
        assert_eq!(band_cost(&chunks, 0, size, phong), 64 * 16 / 4);
        assert_eq!(band_cost(&chunks, 2, size, phong), 64 * 8 / 4);
        chunks[0].bins[1].columns = (10, 20);
        chunks[1].bins[1].columns = (30, 40);
        let flat = Some(Shading::Flat);
        assert_eq!(band_cost(&chunks, 1, size, flat), 30 * 16 + 64 * 16 / 4);
        assert_eq!(band_cost(&chunks, 1, size, None), 6 * 30 * 16 + 64 * 16 / 4);
    }

    struct Numbers;

    impl Borrows for Numbers {
        type At<'a> = &'a mut u32;
    }

    /// The list keeps its allocation from frame to frame.
    #[test]
    fn the_list_keeps_its_allocation() {
        let mut kept = Jobs::<Numbers>::default();
        let mut numbers = [1, 2, 3, 4];
        let mut list = kept.take();
        list.extend(
            numbers
                .iter_mut()
                .enumerate()
                .map(|(i, n)| Job::new(i, 1, n)),
        );
        let (pointer, capacity) = (list.as_ptr() as usize, list.capacity());
        kept.keep(list);
        let again = kept.take();
        assert_eq!(
            (again.as_ptr() as usize, again.capacity()),
            (pointer, capacity)
        );
        assert!(again.is_empty());
    }
}
