//! How long two cores take to hand one cache line back and forth: on a
//! shared virtual machine the host moves and shares the cores, the round
//! trip swings from tens to hundreds of nanoseconds within minutes, and a
//! two-thread run's speed may swing with it (docs/perf-log.md). Taken
//! before and after a `--thread-times` run, so that its figures say what
//! the cores were doing.

use std::hint::spin_loop;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// About the most a probe takes (a round under way when it runs out is
/// given up within a few microseconds of spinning).
const BUDGET: Duration = Duration::from_millis(50);

/// Round trips timed together; the probe reports the median batch, so that
/// a batch the host preempted does not weigh on it.
const ROUNDS_PER_BATCH: u64 = 64;

/// Spins between two looks at the clock while waiting for an answer.
const SPINS_PER_CHECK: u32 = 1024;

/// The line handed over, alone on its cache line (and the next: some
/// cores fetch lines in pairs).
#[repr(align(128))]
struct Line(AtomicU64);

/// The round trip of one cache line between this thread and a second one,
/// ns: the median over batches of `ROUNDS_PER_BATCH` within `BUDGET`, after
/// one round to start the other thread. `None` where the process has a
/// single core (the two threads would take turns on it instead), or if no
/// batch finished in time.
pub fn round_trip_ns() -> Option<f64> {
    round_trip_within(BUDGET)
}

/// `round_trip_ns` within `budget`.
fn round_trip_within(budget: Duration) -> Option<f64> {
    if crate::system_info::threads() < 2 {
        return None;
    }
    let line = Line(AtomicU64::new(0));
    let stop = AtomicBool::new(false);
    std::thread::scope(|scope| {
        // Answers each odd value with the even one after it.
        scope.spawn(|| {
            while !stop.load(Ordering::Relaxed) {
                let asked = line.0.load(Ordering::Acquire);
                if !asked.is_multiple_of(2) {
                    line.0.store(asked + 1, Ordering::Release);
                }
                spin_loop();
            }
        });
        let started = Instant::now();
        let mut asked = 0u64;
        // One round trip, unless the budget runs out waiting for it.
        let mut round_trip = || {
            asked += 2;
            line.0.store(asked - 1, Ordering::Release);
            let mut spins = 0u32;
            while line.0.load(Ordering::Acquire) != asked {
                spin_loop();
                spins += 1;
                if spins.is_multiple_of(SPINS_PER_CHECK) && started.elapsed() >= budget {
                    return false;
                }
            }
            true
        };
        let mut batches = Vec::new();
        if round_trip() {
            'batches: while started.elapsed() < budget {
                let batch = Instant::now();
                for _ in 0..ROUNDS_PER_BATCH {
                    if !round_trip() {
                        break 'batches;
                    }
                }
                batches.push(batch.elapsed().as_secs_f64() * 1e9 / ROUNDS_PER_BATCH as f64);
            }
        }
        stop.store(true, Ordering::Relaxed);
        batches.sort_by(f64::total_cmp);
        batches.get(batches.len() / 2).copied()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A round trip takes some time, and the probe says so where there
    /// are two cores (given long enough for a batch even when other tests
    /// share the cores); with one there is nothing to measure.
    #[test]
    fn a_round_trip_is_measured_where_there_are_two_cores() {
        match round_trip_within(Duration::from_millis(500)) {
            Some(ns) => assert!(ns.is_finite() && ns > 0.0, "{ns} ns"),
            None => assert!(crate::system_info::threads() < 2, "no round trip measured"),
        }
    }
}
