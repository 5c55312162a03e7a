//! Blocks of work run stage after stage on rayon's threads, in one fork-join
//! for all the stages (the idea of Box2D v3's solver stages).
//!
//! A solver pass is a few dozen colours, each a stage whose blocks are
//! independent while the colours must run in order. Handing each colour to
//! rayon on its own costs a fork-join per colour, against a few microseconds
//! of work per block and thread, so that more threads barely speed the solve
//! up (docs/perf-log.md).
//!
//! Here every thread walks the stages itself. A stage's blocks are cut into
//! one share per thread, in order: the colouring fills the same share of
//! every colour with the same part of the room, so a thread that takes its
//! own share in every stage keeps moving the same bodies, whose states stay
//! in its core's cache instead of crossing to another's at every colour. A
//! thread runs its own share from the front, then takes what is left of the
//! others' from their backs (where their owners get to last); each share is
//! one atomic word, on a cache line of its own. A thread then adds the
//! blocks it ran to a count and waits until the count holds every block of
//! the stage before it starts the next.
//!
//! A thread only ever waits for blocks that running threads took, which
//! finish without waiting on anyone, so nothing can deadlock, however many
//! threads join and whenever they start; a thread that starts late finds the
//! blocks taken and catches up. The blocks of a stage touch disjoint data, so
//! which thread runs which block changes no result.

use std::hint::spin_loop;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};

use crate::threading::spare::{release_spare, BUFFER_FLOOR};
use crate::threading::tasks::threads_here;
use crate::threading::thread_times;

/// Spins before a waiting thread yields its core (to a thread that holds a
/// block, when there are more threads than cores); in WebAssembly, where it
/// then sleeps until woken (`give_way`), it spins far longer first: a sleep
/// and its wake cost tens of microseconds, and the solve crosses hundreds of
/// barriers a step (at 4,096 spins the page's two threads waited 2.5–4.1 ms
/// a step at them, at 65,536 1.3–1.9 ms: docs/perf-log.md).
#[cfg(not(all(target_arch = "wasm32", target_feature = "atomics")))]
const SPINS_BEFORE_YIELD: u32 = 64;
#[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
const SPINS_BEFORE_YIELD: u32 = 65_536;

/// An atomic alone on its cache line (128 bytes: some cores fetch lines in
/// pairs), so that threads updating neighbours do not contend.
#[derive(Debug)]
#[repr(align(128))]
struct Padded<T>(T);

/// The blocks of one share still to run: `[front, back)`, packed in one word
/// so that the owner (from the front) and the others (from the back) take
/// them with one compare-and-swap each.
#[derive(Debug)]
struct Share(Padded<AtomicU64>);

impl Share {
    fn new(front: usize, back: usize) -> Share {
        Share(Padded(AtomicU64::new(pack(front, back))))
    }

    /// The first block left, if any.
    fn take_front(&self) -> Option<usize> {
        self.take(|front, back| (front, pack(front + 1, back)))
    }

    /// The last block left, if any.
    fn take_back(&self) -> Option<usize> {
        self.take(|front, back| (back - 1, pack(front, back - 1)))
    }

    /// Takes the block `take(front, back)` names (front < back), leaving the word it gives.
    fn take(&self, take: impl Fn(usize, usize) -> (usize, u64)) -> Option<usize> {
        // Relaxed: a share only decides who runs a block; the stage's wait
        // (Acquire) ordered the block's start after the blocks it depends on.
        let mut word = self.0 .0.load(Ordering::Relaxed);
        loop {
            let (front, back) = unpack(word);
            if front >= back {
                return None;
            }
            let (block, left) = take(front, back);
            match self
                .0
                 .0
                .compare_exchange_weak(word, left, Ordering::Relaxed, Ordering::Relaxed)
            {
                Ok(_) => return Some(block),
                Err(now) => word = now,
            }
        }
    }
}

fn pack(front: usize, back: usize) -> u64 {
    debug_assert!(front <= u32::MAX as usize && back <= u32::MAX as usize);
    (back as u64) << 32 | front as u64
}

fn unpack(word: u64) -> (usize, usize) {
    ((word & u64::from(u32::MAX)) as usize, (word >> 32) as usize)
}

/// Blocks in stages, laid out once for the passes of a step that run them
/// (`run_in_stages`), with the shares those passes deal out and reset.
#[derive(Debug, Default)]
pub(crate) struct Stages {
    /// Each stage's first block, then the number of blocks.
    starts: Vec<u32>,
    /// Threads the blocks are shared among.
    threads: usize,
    /// `threads` shares a stage, stage after stage.
    shares: Vec<Share>,
    /// Whether a run deals out the shares now (runs must not overlap).
    running: AtomicBool,
}

impl Clone for Stages {
    fn clone(&self) -> Self {
        let mut stages = Stages::default();
        stages.starts.clone_from(&self.starts);
        stages.threads = self.threads;
        stages.shares = (0..self.shares.len()).map(|_| Share::new(0, 0)).collect();
        stages
    }
}

impl Stages {
    /// Lays out the stages of `stage_first`, where `stage_first[k]` is the
    /// first block of block k's stage (non-decreasing, `stage_first[k] <= k`,
    /// and a stage's first block is its own stage's first), for the threads
    /// of the current pool.
    pub fn lay_out(&mut self, stage_first: &[u32]) {
        let blocks = stage_first.len();
        debug_assert!(stage_first.iter().enumerate().all(|(k, &first)| {
            let first = first as usize;
            first <= k
                && stage_first[first] as usize == first
                && (k == 0 || stage_first[k - 1] as usize <= first)
        }));
        self.starts.clear();
        self.starts.extend(
            (0..blocks)
                .filter(|&k| stage_first[k] as usize == k)
                .map(|k| k as u32),
        );
        self.starts.push(blocks as u32);
        self.threads = threads_here().clamp(1, blocks.max(1));
        let shares = self.stages() * self.threads;
        if self.shares.len() != shares {
            self.shares.resize_with(shares, || Share::new(0, 0));
        }
    }

    /// Blocks in all.
    pub fn blocks(&self) -> usize {
        self.starts.last().map_or(0, |&n| n as usize)
    }

    fn stages(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// Deals each stage's blocks into its shares, in order.
    fn deal(&self) {
        let threads = self.threads;
        for (s, stage) in self.starts.windows(2).enumerate() {
            let (first, len) = (stage[0] as usize, (stage[1] - stage[0]) as usize);
            for t in 0..threads {
                let share = pack(first + len * t / threads, first + len * (t + 1) / threads);
                // Relaxed: the run's fork hands these to every thread.
                self.shares[s * threads + t]
                    .0
                     .0
                    .store(share, Ordering::Relaxed);
            }
        }
    }

    /// Gives back the capacity the last layout left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.starts, BUFFER_FLOOR);
        release_spare(&mut self.shares, BUFFER_FLOOR);
    }
}

/// Runs `run(k)` for every block `k` of `stages`, on rayon's threads: every
/// block of a stage starts after all the blocks of the stages before it have
/// finished, and the memory they wrote is visible to it. A panic in a block
/// keeps the blocks of later stages from starting and reaches the caller
/// (rather than leaving the others waiting for a block that will never be
/// done). Runs of the same `stages` must not overlap (they reuse its
/// shares): one that would panics instead.
///
/// `run` must not wait on rayon work (`join`, `scope`, parallel iterators):
/// a thread waiting there can take up a later block of this very run, which
/// then waits for the block below it on its own stack.
pub(crate) fn run_in_stages(stages: &Stages, run: impl Fn(usize) + Sync) {
    // Acquire: pairs with the Release that ended the last run.
    assert!(
        !stages.running.swap(true, Ordering::Acquire),
        "two runs of the same stages at once"
    );
    let _over = ClearOnDrop(&stages.running);
    let threads = stages.threads;
    stages.deal();
    thread_times::crossed(stages.stages().saturating_sub(1));
    let joined = AtomicUsize::new(0);
    let done = Padded(AtomicUsize::new(0));
    let failed = AtomicBool::new(false);
    let work = || {
        // A pool's thread takes the share of its index, the same in every
        // run, so that it keeps the same part of the room from pass to pass
        // (a pool larger than the layout's threads folds onto it); others by
        // order of arrival. A thread that never comes leaves its share to the
        // others.
        let own = rayon::current_thread_index()
            .unwrap_or_else(|| joined.fetch_add(1, Ordering::Relaxed))
            % threads;
        for (s, &first) in stages.starts[..stages.stages()].iter().enumerate() {
            if !wait_until_done(&done.0, first as usize, &failed) {
                return;
            }
            let stage = &stages.shares[s * threads..(s + 1) * threads];
            let mut ran = 0;
            let mut run_counted = |k: usize| {
                let unwinding = FlagOnUnwind(&failed);
                thread_times::task(|| run(k));
                std::mem::forget(unwinding);
                ran += 1;
            };
            while let Some(k) = stage[own].take_front() {
                run_counted(k);
            }
            for other in (own + 1..threads).chain(0..own) {
                while let Some(k) = stage[other].take_back() {
                    run_counted(k);
                }
            }
            // Release: the blocks' writes are seen by whoever sees the count.
            let counted = done.0.fetch_add(ran, Ordering::Release) + ran;
            if counted >= stages.starts[s + 1] as usize {
                wake_waiters(&done.0);
            }
        }
    };
    // One thread here (`tasks::alone`, or a layout for one): it takes every
    // share itself, and the pool is not asked.
    if threads == 1 || threads_here() == 1 {
        return work();
    }
    rayon::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(|_| work());
        }
        work();
    });
}

/// Clears its flag when dropped, however the run ends.
struct ClearOnDrop<'a>(&'a AtomicBool);

impl Drop for ClearOnDrop<'_> {
    fn drop(&mut self) {
        // Release: the run's writes come before the next run's start.
        self.0.store(false, Ordering::Release);
    }
}

/// Sets its flag when dropped, which only a panic does (it is forgotten otherwise).
struct FlagOnUnwind<'a>(&'a AtomicBool);

impl Drop for FlagOnUnwind<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Adds a barrier's wait to the thread's time when dropped, however the wait ends.
struct BarrierWaited(Option<f64>);

impl Drop for BarrierWaited {
    fn drop(&mut self) {
        thread_times::barrier_waited(self.0);
    }
}

/// Waits until `done` counts at least `blocks`: a thread counts a stage's
/// blocks it ran once it finds none left, and none starts the next stage
/// before the count holds all of them, so the count reaching a stage's first
/// block means every block before it has finished. Returns false, at once,
/// if a block panicked.
fn wait_until_done(done: &AtomicUsize, blocks: usize, failed: &AtomicBool) -> bool {
    if done.load(Ordering::Acquire) >= blocks {
        return true;
    }
    let started = thread_times::barrier_start();
    let _waited = BarrierWaited(started);
    let mut spins = 0;
    // Acquire: pairs with the Release of every block counted.
    while done.load(Ordering::Acquire) < blocks {
        if failed.load(Ordering::Relaxed) {
            return false;
        }
        if spins < SPINS_BEFORE_YIELD {
            spins += 1;
            spin_loop();
        } else {
            give_way(done, blocks);
        }
    }
    true
}

/// Lets another thread have this core while `done` is under `blocks`.
#[cfg(not(all(target_arch = "wasm32", target_feature = "atomics")))]
fn give_way(_done: &AtomicUsize, _blocks: usize) {
    std::thread::yield_now();
}

/// Lets another thread have this core while `done` is under `blocks`:
/// `yield_now` does nothing in WebAssembly, so a waiting thread would hold
/// its core from the very thread whose block it waits for (the page's own
/// threads, drawing, take cores too). It sleeps on the count instead, woken
/// by the stage's last block (`wake_waiters`); the millisecond's timeout
/// only bounds a wait should a wake ever be missed (a panic aborts in the
/// page, so no failed block is left to notice).
#[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
fn give_way(done: &AtomicUsize, blocks: usize) {
    let seen = done.load(Ordering::Acquire);
    if seen < blocks {
        // SAFETY: the count outlives the wait, and a usize is an i32 on wasm32;
        // a wait that finds the count moved returns at once.
        unsafe {
            core::arch::wasm32::memory_atomic_wait32(done.as_ptr().cast(), seen as i32, 1_000_000);
        }
    }
}

/// Wakes the threads asleep on a stage's count (`give_way`); natively none sleep.
#[cfg(not(all(target_arch = "wasm32", target_feature = "atomics")))]
fn wake_waiters(_done: &AtomicUsize) {}

/// Wakes the threads asleep on a stage's count (`give_way`).
#[cfg(all(target_arch = "wasm32", target_feature = "atomics"))]
fn wake_waiters(done: &AtomicUsize) {
    // SAFETY: the count is a live i32-sized atomic.
    unsafe {
        core::arch::wasm32::memory_atomic_notify(done.as_ptr().cast(), u32::MAX);
    }
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::AtomicU32;

    use super::*;

    /// Stages of 1 to 9 blocks; each block checks that every block of the
    /// earlier stages has run (and none of the later ones), then marks itself.
    #[test]
    fn each_stage_starts_after_the_stages_before_it_finish() {
        let sizes = [3usize, 1, 9, 2, 1, 1, 5, 7, 1, 4, 8, 2, 6];
        let mut stage_first = Vec::new();
        let mut stage_of = Vec::new();
        for (stage, &size) in sizes.iter().enumerate() {
            let first = stage_first.len() as u32;
            stage_first.extend(std::iter::repeat_n(first, size));
            stage_of.extend(std::iter::repeat_n(stage, size));
        }
        for threads in [1, 2, 4, 8] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            for _ in 0..200 {
                let ran: Vec<AtomicU32> = stage_of.iter().map(|_| AtomicU32::new(0)).collect();
                pool.install(|| {
                    let mut stages = Stages::default();
                    stages.lay_out(&stage_first);
                    run_in_stages(&stages, |k| {
                        for (j, flag) in ran.iter().enumerate() {
                            let seen = flag.load(Ordering::Relaxed);
                            if stage_of[j] < stage_of[k] {
                                assert_eq!(seen, 1, "block {j} before block {k}'s stage");
                            } else if stage_of[j] > stage_of[k] {
                                assert_eq!(seen, 0, "block {j} ran before block {k}'s stage");
                            }
                        }
                        ran[k].fetch_add(1, Ordering::Relaxed);
                    });
                });
                assert!(ran.iter().all(|r| r.load(Ordering::Relaxed) == 1));
            }
        }
    }

    /// What a stage's blocks write is what the next stage's blocks read, on
    /// any thread: each stage sums the cells the stage before wrote.
    #[test]
    fn a_stage_reads_what_the_stage_before_wrote() {
        const BLOCKS: usize = 16;
        const STAGES: usize = 40;
        let stage_first: Vec<u32> = (0..STAGES * BLOCKS)
            .map(|k| (k / BLOCKS * BLOCKS) as u32)
            .collect();
        // Stage s reads buffer s % 2 and writes its block's cell of the other.
        let next = |cells: &[u32], cell: usize| {
            cells
                .iter()
                .fold(cell as u32, |sum, &c| sum.wrapping_mul(31).wrapping_add(c))
        };
        let mut expected = [vec![1u32; BLOCKS], vec![0; BLOCKS]];
        for stage in 0..STAGES {
            let read = expected[stage % 2].clone();
            for cell in 0..BLOCKS {
                expected[(stage + 1) % 2][cell] = next(&read, cell);
            }
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        for _ in 0..50 {
            let cells: [Vec<AtomicU32>; 2] = [
                (0..BLOCKS).map(|_| AtomicU32::new(1)).collect(),
                (0..BLOCKS).map(|_| AtomicU32::new(0)).collect(),
            ];
            pool.install(|| {
                let mut stages = Stages::default();
                stages.lay_out(&stage_first);
                run_in_stages(&stages, |k| {
                    let (stage, cell) = (k / BLOCKS, k % BLOCKS);
                    // Relaxed: only the stages' own ordering makes the values current.
                    let read: Vec<u32> = cells[stage % 2]
                        .iter()
                        .map(|c| c.load(Ordering::Relaxed))
                        .collect();
                    // Long enough that other threads take the next blocks meanwhile.
                    (0..2_000).for_each(|_| spin_loop());
                    cells[(stage + 1) % 2][cell].store(next(&read, cell), Ordering::Relaxed);
                });
            });
            let last: Vec<u32> = cells[STAGES % 2]
                .iter()
                .map(|c| c.load(Ordering::Relaxed))
                .collect();
            assert_eq!(last, expected[STAGES % 2]);
        }
    }

    /// A run of stages already running is refused, and the stages run again after.
    #[test]
    fn a_second_run_of_the_same_stages_at_once_is_refused() {
        let stage_first: Vec<u32> = (0..8).map(|k| k / 4 * 4).collect();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(|| {
            let mut stages = Stages::default();
            stages.lay_out(&stage_first);
            let nested = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                run_in_stages(&stages, |k| {
                    if k == 5 {
                        run_in_stages(&stages, |_| {});
                    }
                })
            }));
            let message = nested.expect_err("the nested run must panic");
            assert_eq!(
                message.downcast_ref::<&str>(),
                Some(&"two runs of the same stages at once")
            );
            let ran = AtomicU32::new(0);
            run_in_stages(&stages, |_| {
                ran.fetch_add(1, Ordering::Relaxed);
            });
            assert_eq!(ran.load(Ordering::Relaxed), 8);
        });
    }

    /// A block that panics ends the run with its panic, on any thread,
    /// instead of leaving the others waiting for it.
    #[test]
    fn a_panicking_block_reaches_the_caller() {
        let stage_first: Vec<u32> = (0..64).map(|k| k / 8 * 8).collect();
        let (sender, receiver) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(4)
                .build()
                .unwrap();
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                pool.install(|| {
                    let mut stages = Stages::default();
                    stages.lay_out(&stage_first);
                    run_in_stages(&stages, |k| assert_ne!(k, 19, "block 19 fails"));
                })
            }));
            sender.send(result.is_err()).unwrap();
        });
        let panicked = receiver.recv_timeout(std::time::Duration::from_secs(20));
        assert_eq!(panicked, Ok(true), "the run must end, with the panic");
    }
}
