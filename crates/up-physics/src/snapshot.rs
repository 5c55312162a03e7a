//! Snapshots: a whole world as bytes, restored exactly.
//!
//! Layout: the magic `UPSNAP`, a format version (u16, little endian), the
//! payload length (u64), the payload (postcard, every float as its bits) and
//! an FNV-1a checksum of the payload (u64). A truncated or corrupted file is
//! rejected before anything is decoded.

use thiserror::Error;

use crate::hash::Fnv1a;
use crate::world::World;

const MAGIC: &[u8; 6] = b"UPSNAP";
/// 2: `StepStats` counts quarantined bodies. 3: sleeping islands keep their impulses.
/// 4: `WorldDef` has the position passes' most and target. 5: joints; contact
/// features as two indices. 6: ribbons. 7: gas. 8: a ribbon's anchor.
/// 9: the moving air's sources. 10: `WorldDef`'s ribbon contacts and their friction.
const VERSION: u16 = 10;
const HEADER: usize = 6 + 2 + 8;

#[derive(Debug, Error, PartialEq)]
pub enum SnapshotError {
    #[error("not a UP snapshot (the file does not start with UPSNAP)")]
    BadMagic,
    #[error("snapshot format version {found}, this build reads version {VERSION}")]
    Version { found: u16 },
    #[error("snapshot truncated: expected {expected} bytes, found {found}")]
    Truncated { expected: usize, found: usize },
    #[error("snapshot corrupted: checksum mismatch")]
    Checksum,
    #[error("snapshot could not be decoded: {0}")]
    Decode(String),
    #[error("snapshot describes an inconsistent world: {0}")]
    Invalid(String),
}

pub(crate) fn encode(world: &World) -> Vec<u8> {
    // Serialising plain data into a Vec cannot fail.
    let payload = postcard::to_stdvec(world).unwrap_or_default();
    let mut out = Vec::with_capacity(HEADER + payload.len() + 8);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&payload);
    let mut h = Fnv1a::new();
    h.write_bytes(&payload);
    out.extend_from_slice(&h.finish().to_le_bytes());
    out
}

pub(crate) fn decode(bytes: &[u8]) -> Result<World, SnapshotError> {
    if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
        return Err(SnapshotError::BadMagic);
    }
    if bytes.len() < HEADER {
        return Err(SnapshotError::Truncated {
            expected: HEADER,
            found: bytes.len(),
        });
    }
    let version = u16::from_le_bytes([bytes[6], bytes[7]]);
    if version != VERSION {
        return Err(SnapshotError::Version { found: version });
    }
    let mut len_bytes = [0u8; 8];
    len_bytes.copy_from_slice(&bytes[8..16]);
    let len = u64::from_le_bytes(len_bytes);
    let expected = (HEADER as u64).saturating_add(len).saturating_add(8);
    if (bytes.len() as u64) != expected {
        return Err(SnapshotError::Truncated {
            expected: expected.min(usize::MAX as u64) as usize,
            found: bytes.len(),
        });
    }
    let payload = &bytes[HEADER..HEADER + len as usize];
    let mut sum = [0u8; 8];
    sum.copy_from_slice(&bytes[HEADER + len as usize..]);
    let mut h = Fnv1a::new();
    h.write_bytes(payload);
    if h.finish() != u64::from_le_bytes(sum) {
        return Err(SnapshotError::Checksum);
    }
    postcard::from_bytes(payload).map_err(|e| SnapshotError::Decode(e.to_string()))
}
