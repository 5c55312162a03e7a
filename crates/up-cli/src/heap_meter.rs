//! The bytes this process holds on the heap, counted at every allocation:
//! what `up soak` holds flat to find a leak.
//!
//! Resident memory (RSS) is no measure of a leak here: a vector's spare
//! capacity costs pages only once they are first written, so RSS creeps up
//! each time a busier moment (a stir's crowd of contacts) fills more of a
//! buffer that an earlier, quieter one had reserved, and it stays there.
//! The count below moves only when the program allocates or frees.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, Ordering};

/// The system allocator, counting the bytes it hands out and takes back.
/// The engine allocates a handful of times a step, so the count costs nothing
/// one can measure.
pub struct HeapMeter;

static HELD_BYTES: AtomicU64 = AtomicU64::new(0);

/// Bytes allocated and not yet freed, over all threads.
pub fn held_bytes() -> u64 {
    HELD_BYTES.load(Ordering::Relaxed)
}

fn held(grown: usize, shrunk: usize) {
    if grown > shrunk {
        HELD_BYTES.fetch_add((grown - shrunk) as u64, Ordering::Relaxed);
    } else {
        HELD_BYTES.fetch_sub((shrunk - grown) as u64, Ordering::Relaxed);
    }
}

// SAFETY: every call is passed on to `System` unchanged; the count is only
// updated for calls that succeeded.
unsafe impl GlobalAlloc for HeapMeter {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract for `alloc`, passed on.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            held(layout.size(), 0);
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract for `alloc_zeroed`, passed on.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            held(layout.size(), 0);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract for `dealloc`, passed on.
        unsafe { System.dealloc(ptr, layout) };
        held(0, layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller's contract for `realloc`, passed on.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            held(new_size, layout.size());
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_what_is_held_and_nothing_once_freed() {
        // The test binary's allocator is the meter too (up's main.rs, and
        // up-physics' soak test, which shares this file); other
        // tests run on other threads, so only a large, unmistakable change is
        // asserted.
        const SIZE: usize = 64 << 20;
        let before = held_bytes();
        let mut block = vec![1u8; SIZE];
        let during = held_bytes();
        block.resize(2 * SIZE, 2);
        let grown = held_bytes();
        assert_eq!(block[2 * SIZE - 1], 2);
        drop(block);
        let after = held_bytes();
        assert!(during >= before + SIZE as u64 / 2, "{before} -> {during}");
        assert!(grown >= during + SIZE as u64 / 2, "{during} -> {grown}");
        assert!(after + SIZE as u64 <= grown, "{grown} -> {after}");
    }
}
