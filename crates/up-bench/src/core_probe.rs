//! How long two cores take to hand one cache line back and forth: on a
//! shared virtual machine the host moves and shares the cores, the round
//! trip swings from tens to hundreds of nanoseconds within minutes, and a
//! two-thread run's speed swings with it (docs/perf-log.md). Taken before
//! and after a `--thread-times` run, so that its figures say what the cores
//! were doing.

use std::hint::spin_loop;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The most a probe takes, however slow the hand-over.
const BUDGET: Duration = Duration::from_millis(50);

/// Round trips between two looks at the clock.
const ROUNDS_PER_CHECK: u64 = 64;

/// The line handed over, alone on its cache line (and the next: some
/// cores fetch lines in pairs).
#[repr(align(128))]
struct Line(AtomicU64);

/// The mean round trip of one cache line between this thread and a second
/// one, ns, over `BUDGET`; `None` where the process has a single core (the
/// two threads would take turns on it instead).
pub fn round_trip_ns() -> Option<f64> {
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
        let mut rounds = 0u64;
        loop {
            let ask = 2 * rounds + 1;
            line.0.store(ask, Ordering::Release);
            while line.0.load(Ordering::Acquire) != ask + 1 {
                spin_loop();
            }
            rounds += 1;
            if rounds.is_multiple_of(ROUNDS_PER_CHECK) && started.elapsed() >= BUDGET {
                break;
            }
        }
        let elapsed = started.elapsed();
        stop.store(true, Ordering::Relaxed);
        Some(elapsed.as_secs_f64() * 1e9 / rounds as f64)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A round trip takes some time, and the probe says so where there
    /// are two cores; with one there is nothing to measure.
    #[test]
    fn a_round_trip_is_measured_where_there_are_two_cores() {
        match round_trip_ns() {
            Some(ns) => assert!(ns.is_finite() && ns > 0.0, "{ns} ns"),
            None => assert!(crate::system_info::threads() < 2),
        }
    }
}
