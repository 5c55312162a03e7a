//! Whether a step keeps the pool's other threads looking for work through it
//! (`keep_awake`), for every world in the process: on by default. A host
//! whose threads share the cores with other busy threads (a browser page
//! drawing on the same CPU) may turn it off, so that a thread with nothing to
//! run goes to rayon's sleep rather than spin while another needs the core.
//! Which thread runs which work changes no result, only how soon it runs.

use std::sync::atomic::{AtomicBool, Ordering};

static KEEP_AWAKE: AtomicBool = AtomicBool::new(true);

/// Turns keeping the pool's threads awake through a step on or off.
pub fn set_keep_threads_awake(on: bool) {
    KEEP_AWAKE.store(on, Ordering::Relaxed);
}

/// Whether steps keep the pool's threads awake.
#[cfg_attr(not(feature = "parallel"), allow(dead_code))]
pub(crate) fn keep_threads_awake() -> bool {
    KEEP_AWAKE.load(Ordering::Relaxed)
}
