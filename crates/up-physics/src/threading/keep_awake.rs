//! Rayon's threads kept looking for work for the whole of a step (the idea of
//! Box2D v3's workers, which spin through a step rather than sleep).
//!
//! A step is hundreds of parallel passes, many of them a few hundred
//! microseconds long. Between two passes rayon puts an idle thread to sleep
//! after a few dozen rounds of looking for work (at once in WebAssembly,
//! where yielding the core does nothing), and the next pass must wake it: a
//! futex round trip that, between a browser's workers, takes about as long
//! as a pass, so that the other threads join each pass late or not at all.
//!
//! Here the step's thread hands every other thread of the pool a job that
//! keeps running rayon's pending work until the step is over. Which thread
//! runs which job changes no result, only how soon it runs.
//!
//! A thread that gets its job while inside other work (which only happens
//! when several steps share one pool at once) holds that work back until
//! the job ends; so the job also ends once it has found nothing to run for
//! `IDLE_LIMIT_MS`, and no step can wait on another's for longer.

use std::cell::Cell;
use std::hint::spin_loop;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::counters::now_ms;
use crate::threading::tasks::threads_here;

/// How long a kept thread looks for work in vain before it leaves the step
/// to rayon's sleep: longer than the step's serial stretches between passes.
const IDLE_LIMIT_MS: f64 = 4.0;

/// Rounds without work between two looks at the clock.
const ROUNDS_PER_CLOCK_READ: u32 = 64;

thread_local! {
    /// Whether this thread already runs a step or a keep-awake job: a second
    /// job on it would only spin on top of the first.
    static KEPT: Cell<bool> = const { Cell::new(false) };
}

/// Runs `work` on this thread (one of rayon's, or the caller's when it is not
/// in a pool) while the pool's other threads keep looking for the rayon work
/// it makes, and returns its result.
pub(crate) fn with_threads_kept_awake<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    let Some(owner) = rayon::current_thread_index() else {
        return work();
    };
    if threads_here() <= 1 || KEPT.get() || !super::keep_awake_switch::keep_threads_awake() {
        return work();
    }
    let over = AtomicBool::new(false);
    rayon::in_place_scope(|scope| {
        scope.spawn_broadcast(|_, context| {
            if context.index() != owner {
                keep_looking(&over);
            }
        });
        // Ends the other threads' jobs however `work` ends, a panic included.
        let _end = SetOnDrop(&over);
        let _kept = Kept::enter();
        work()
    })
}

/// Runs rayon's pending work until `over` is set, or until none has come for `IDLE_LIMIT_MS`.
fn keep_looking(over: &AtomicBool) {
    if KEPT.get() {
        return;
    }
    let _kept = Kept::enter();
    let mut idle_since = None;
    let mut idle_rounds = 0u32;
    // Acquire: pairs with the Release that ends the step.
    while !over.load(Ordering::Acquire) {
        match rayon::yield_now() {
            Some(rayon::Yield::Executed) => {
                idle_since = None;
                idle_rounds = 0;
            }
            Some(rayon::Yield::Idle) => {
                idle_rounds += 1;
                if idle_rounds.is_multiple_of(ROUNDS_PER_CLOCK_READ) {
                    let now = now_ms();
                    if now - *idle_since.get_or_insert(now) > IDLE_LIMIT_MS {
                        return;
                    }
                }
                spin_loop();
                // Natively, lets a thread that holds work have the core when
                // there are more threads than cores (WebAssembly has no such call).
                #[cfg(not(target_arch = "wasm32"))]
                std::thread::yield_now();
            }
            None => return,
        }
    }
}

/// Marks this thread as kept for as long as it lives.
struct Kept;

impl Kept {
    fn enter() -> Kept {
        KEPT.set(true);
        Kept
    }
}

impl Drop for Kept {
    fn drop(&mut self) {
        KEPT.set(false);
    }
}

/// Sets its flag when dropped.
struct SetOnDrop<'a>(&'a AtomicBool);

impl Drop for SetOnDrop<'_> {
    fn drop(&mut self) {
        // Release: the step's writes are seen by the threads that see the flag.
        self.0.store(true, Ordering::Release);
    }
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::AtomicUsize;
    use std::sync::Mutex;

    use rayon::prelude::*;

    use super::*;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

    /// The work's parallel passes run, with their results, on the threads kept
    /// awake as well as the owner's; every kept thread's job has ended when
    /// the call returns.
    #[test]
    fn passes_run_on_the_kept_threads_and_their_jobs_end_with_the_work() {
        let pool = pool(4);
        let seen = Mutex::new(std::collections::BTreeSet::new());
        let sums: Vec<u64> = pool.install(|| {
            with_threads_kept_awake(|| {
                (0..200)
                    .map(|pass| {
                        (0..4_000u32)
                            .into_par_iter()
                            .with_max_len(16)
                            .map(|i| {
                                seen.lock().unwrap().insert(rayon::current_thread_index());
                                u64::from(i) * pass
                            })
                            .sum()
                    })
                    .collect()
            })
        });
        let expected: Vec<u64> = (0..200).map(|pass| pass * 3_999 * 4_000 / 2).collect();
        assert_eq!(sums, expected);
        // Not a timing claim: only that the other threads took part at all.
        assert!(seen.lock().unwrap().len() > 1, "{:?}", seen.lock().unwrap());
        // Each thread is free for the next step: none is still marked kept.
        let kept = AtomicUsize::new(0);
        pool.broadcast(|_| {
            if KEPT.get() {
                kept.fetch_add(1, Ordering::Relaxed);
            }
        });
        assert_eq!(kept.load(Ordering::Relaxed), 0);
    }

    /// A panic in the work reaches the caller and ends the kept threads' jobs
    /// (the pool answers afterwards).
    #[test]
    fn a_panic_in_the_work_reaches_the_caller_and_frees_the_threads() {
        let pool = pool(3);
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.install(|| with_threads_kept_awake(|| panic!("the step fails")))
        }));
        assert!(result.is_err());
        assert_eq!(
            pool.install(|| (0..100).into_par_iter().sum::<i32>()),
            4_950
        );
    }

    /// Steps that share one pool, each from a thread of its own, all end
    /// (a thread kept by one, inside another's work, lets it go when idle).
    #[test]
    fn steps_sharing_a_pool_all_end() {
        let pool = pool(3);
        let totals: Vec<u64> = (0..6u32)
            .into_par_iter()
            .with_max_len(1)
            .map(|k| {
                let k = u64::from(k);
                pool.install(|| {
                    with_threads_kept_awake(|| {
                        (0..50)
                            .map(|_| {
                                (0..2_000u32)
                                    .into_par_iter()
                                    .map(|i| u64::from(i) + k)
                                    .sum::<u64>()
                            })
                            .sum()
                    })
                })
            })
            .collect();
        let expected: Vec<u64> = (0..6)
            .map(|k| 50 * (1_999 * 2_000 / 2 + 2_000 * k))
            .collect();
        assert_eq!(totals, expected);
    }

    /// Outside a pool, or on a pool of one thread, the work simply runs.
    #[test]
    fn without_other_threads_the_work_just_runs() {
        assert_eq!(with_threads_kept_awake(|| 7), 7);
        assert_eq!(pool(1).install(|| with_threads_kept_awake(|| 8)), 8);
    }
}
