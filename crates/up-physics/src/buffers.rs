//! The step's big buffers (contacts, constraints, impulses) grow to fit,
//! not by doubling: a `Vec` that doubles carries up to half its size unused,
//! and while it grows it holds its old block and the new one at once. These
//! buffers are refilled whole every step, so when one must grow its old block
//! is freed first and the new one takes what is needed and an eighth more.

/// Room kept past what is needed when a buffer grows: one item in eight.
const HEADROOM: usize = 8;

/// `len` and the headroom a growing buffer takes.
pub(crate) fn with_headroom(len: usize) -> usize {
    len + len / HEADROOM
}

/// Empties `v`, with room for `len` items to be pushed.
pub(crate) fn clear_to_refill<T>(v: &mut Vec<T>, len: usize) {
    v.clear();
    if v.capacity() < len {
        *v = Vec::new(); // the old block goes before the new one comes
        v.reserve_exact(with_headroom(len));
    }
}

/// Makes `v` `len` items long for the caller to overwrite every one: what
/// it held is lost when it must grow (new items are `fill`).
pub(crate) fn resize_to_overwrite<T: Clone>(v: &mut Vec<T>, len: usize, fill: T) {
    if v.capacity() < len {
        clear_to_refill(v, len);
    }
    v.resize(len, fill);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_buffer_grows_to_fit_and_keeps_its_block_when_it_shrinks() {
        let mut v: Vec<u64> = Vec::with_capacity(100);
        v.extend(0..100);
        clear_to_refill(&mut v, 1000);
        assert!(v.is_empty());
        assert_eq!(v.capacity(), 1000 + 125);
        resize_to_overwrite(&mut v, 1100, 7);
        assert_eq!((v.len(), v.capacity()), (1100, 1125));
        resize_to_overwrite(&mut v, 10, 7);
        assert_eq!((v.len(), v.capacity()), (10, 1125));
        resize_to_overwrite(&mut v, 2000, 7);
        assert_eq!((v.len(), v.capacity()), (2000, 2250));
        assert!(v.iter().all(|&x| x == 7));
    }
}
