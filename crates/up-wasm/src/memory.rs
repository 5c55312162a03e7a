//! Buffers the host writes into: `up_alloc` hands out zeroed byte buffers and
//! remembers them, so a `(ptr, len)` pair coming back is checked against the
//! table before it is read. A stale or forged pointer is an error, not
//! undefined behaviour.

use crate::status::WasmError;

/// Largest single buffer, bytes (a scene text larger than this is not a scene).
pub const MAX_ALLOC: usize = 64 << 20;
/// Most bytes held in live buffers at once: a host that forgets `up_free`
/// gets an error, not an out-of-memory trap.
pub const MAX_LIVE: usize = 128 << 20;

#[derive(Default)]
pub struct Allocations {
    /// Live buffers. Few at a time (one scene text), so a linear scan is fine.
    live: Vec<Box<[u8]>>,
}

impl Allocations {
    /// A zeroed buffer of `len` bytes (at least 1); returns its address.
    pub fn alloc(&mut self, len: usize) -> Result<*mut u8, WasmError> {
        if len > MAX_ALLOC {
            return Err(WasmError::Alloc(format!(
                "cannot allocate {len} bytes: at most {MAX_ALLOC} at a time"
            )));
        }
        let live: usize = self.live.iter().map(|b| b.len()).sum();
        if live + len > MAX_LIVE {
            return Err(WasmError::Alloc(format!(
                "cannot allocate {len} bytes: {live} bytes are still held \
                 (at most {MAX_LIVE} at once; free buffers with up_free)"
            )));
        }
        // `try_reserve_exact` turns an out-of-memory into an error instead of an abort.
        let mut bytes = Vec::new();
        bytes
            .try_reserve_exact(len.max(1))
            .map_err(|e| WasmError::Alloc(format!("cannot allocate {len} bytes: {e}")))?;
        bytes.resize(len.max(1), 0u8);
        let mut buffer = bytes.into_boxed_slice();
        let ptr = buffer.as_mut_ptr();
        self.live.push(buffer);
        Ok(ptr)
    }

    /// Frees the buffer at `ptr`; unknown pointers are an error.
    pub fn free(&mut self, ptr: *const u8) -> Result<(), WasmError> {
        match self.live.iter().position(|b| b.as_ptr() == ptr) {
            Some(i) => {
                self.live.swap_remove(i);
                Ok(())
            }
            None => Err(WasmError::OutOfRange(format!(
                "up_free: {ptr:?} was not allocated by up_alloc (or was freed already)"
            ))),
        }
    }

    /// The bytes `ptr..ptr + len`, which must lie inside one live buffer.
    pub fn bytes(&self, ptr: *const u8, len: usize) -> Result<&[u8], WasmError> {
        let start = ptr as usize;
        for b in &self.live {
            let base = b.as_ptr() as usize;
            if start >= base
                && start
                    .checked_add(len)
                    .is_some_and(|end| end <= base + b.len())
            {
                let offset = start - base;
                return Ok(&b[offset..offset + len]);
            }
        }
        Err(WasmError::OutOfRange(format!(
            "{len} bytes at {ptr:?} do not lie inside a buffer from up_alloc"
        )))
    }

    /// The text at `ptr..ptr + len`, UTF-8.
    pub fn text(&self, ptr: *const u8, len: usize) -> Result<&str, WasmError> {
        std::str::from_utf8(self.bytes(ptr, len)?)
            .map_err(|e| WasmError::Encoding(format!("the text is not UTF-8: {e}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_only_inside_live_buffers() {
        let mut a = Allocations::default();
        let p = a.alloc(8).unwrap();
        assert_eq!(a.bytes(p, 8).unwrap(), &[0u8; 8]);
        assert!(a.bytes(p, 9).is_err());
        assert!(a.bytes(p.wrapping_add(4), 4).is_ok());
        assert!(a.bytes(p.wrapping_add(4), 5).is_err());
        a.free(p).unwrap();
        assert!(a.bytes(p, 1).is_err());
        assert!(a.free(p).is_err());
    }

    #[test]
    fn refuses_huge_buffers_and_bad_utf8() {
        let mut a = Allocations::default();
        assert!(matches!(a.alloc(MAX_ALLOC + 1), Err(WasmError::Alloc(_))));
        let held: Vec<_> = (0..MAX_LIVE / MAX_ALLOC)
            .map(|_| a.alloc(MAX_ALLOC).unwrap())
            .collect();
        assert!(
            matches!(a.alloc(1), Err(WasmError::Alloc(_))),
            "past MAX_LIVE in all"
        );
        for p in held {
            a.free(p).unwrap();
        }
        let p = a.alloc(2).unwrap();
        // SAFETY: p points at 2 bytes this table owns.
        unsafe { p.copy_from([0xff, 0xfe].as_ptr(), 2) };
        assert!(matches!(a.text(p, 2), Err(WasmError::Encoding(_))));
    }
}
