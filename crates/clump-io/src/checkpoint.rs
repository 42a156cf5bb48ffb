//! Versioned binary checkpoints.
//!
//! Layout (all integers little endian):
//!
//! | bytes | content |
//! |-------|---------|
//! | 8     | magic `b"CLUMPCKP"` |
//! | 4     | format version, u32 ([`CHECKPOINT_VERSION`]) |
//! | 8     | scenario fingerprint, u64 (supplied by the caller) |
//! | 8     | payload length in bytes, u64 |
//! | 4     | CRC-32 (IEEE) of the payload, u32 |
//! | n     | payload: postcard encoding of the caller's value |
//!
//! Files are written atomically ([`crate::atomic`]). Reading never panics:
//! every kind of damage gives its own [`CheckpointError`] naming the file.

use crate::atomic::write_atomic;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The magic bytes at the start of every checkpoint.
pub const CHECKPOINT_MAGIC: [u8; 8] = *b"CLUMPCKP";

/// The format version this build writes and reads (2: the bodies carry
/// their temperatures and heat sources, the state the walls' heat).
pub const CHECKPOINT_VERSION: u32 = 2;

/// Size of the fixed header, bytes.
pub const HEADER_LEN: usize = 32;

/// Why a checkpoint could not be written or read.
#[derive(Debug, Error)]
pub enum CheckpointError {
    /// The file could not be read or written.
    #[error("checkpoint {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The file is shorter than the header.
    #[error(
        "checkpoint {path}: file is truncated ({len} bytes, the header alone has {HEADER_LEN})"
    )]
    TooShort {
        /// The file.
        path: PathBuf,
        /// Its length, bytes.
        len: usize,
    },
    /// The file does not start with the magic bytes.
    #[error("checkpoint {path}: not a Clump checkpoint (wrong magic bytes)")]
    BadMagic {
        /// The file.
        path: PathBuf,
    },
    /// The file has another format version.
    #[error("checkpoint {path}: format version {found}, this build reads version {expected}")]
    UnsupportedVersion {
        /// The file.
        path: PathBuf,
        /// Version in the file.
        found: u32,
        /// Version this build supports.
        expected: u32,
    },
    /// The payload is shorter or longer than the header says.
    #[error("checkpoint {path}: payload is {found} bytes but the header says {expected} (truncated or corrupt file)")]
    LengthMismatch {
        /// The file.
        path: PathBuf,
        /// Length from the header, bytes.
        expected: u64,
        /// Actual length, bytes.
        found: u64,
    },
    /// The payload checksum does not match.
    #[error("checkpoint {path}: checksum mismatch (stored {stored:#010x}, computed {computed:#010x}); the file is corrupt")]
    BadChecksum {
        /// The file.
        path: PathBuf,
        /// CRC-32 in the header.
        stored: u32,
        /// CRC-32 of the payload read.
        computed: u32,
    },
    /// The payload could not be decoded (a checkpoint of another program version?).
    #[error("checkpoint {path}: cannot decode the contents ({message}); was it written by another version of Clump?")]
    Decode {
        /// The file.
        path: PathBuf,
        /// Decoder message.
        message: String,
    },
    /// The value could not be encoded.
    #[error("checkpoint {path}: cannot encode the state: {message}")]
    Encode {
        /// The file.
        path: PathBuf,
        /// Encoder message.
        message: String,
    },
}

/// The header of a checkpoint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CheckpointHeader {
    /// Format version.
    pub version: u32,
    /// Scenario fingerprint.
    pub fingerprint: u64,
    /// Payload length, bytes.
    pub payload_len: u64,
    /// CRC-32 of the payload.
    pub crc: u32,
}

/// Encodes `value` with the checkpoint header (in memory).
pub fn encode_checkpoint<T: Serialize>(
    value: &T,
    fingerprint: u64,
) -> Result<Vec<u8>, postcard::Error> {
    let payload = postcard::to_allocvec(value)?;
    let mut out = Vec::with_capacity(HEADER_LEN + payload.len());
    out.extend_from_slice(&CHECKPOINT_MAGIC);
    out.extend_from_slice(&CHECKPOINT_VERSION.to_le_bytes());
    out.extend_from_slice(&fingerprint.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
    out.extend_from_slice(&payload);
    Ok(out)
}

/// Writes `value` as a checkpoint to `path` (atomically).
pub fn write_checkpoint<T: Serialize>(
    path: impl AsRef<Path>,
    value: &T,
    fingerprint: u64,
) -> Result<(), CheckpointError> {
    let path = path.as_ref();
    let bytes = encode_checkpoint(value, fingerprint).map_err(|e| CheckpointError::Encode {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_atomic(path, &bytes).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Parses and checks the header of checkpoint bytes (`path` is for messages).
pub fn decode_header(bytes: &[u8], path: &Path) -> Result<CheckpointHeader, CheckpointError> {
    let p = || path.to_path_buf();
    if bytes.len() < CHECKPOINT_MAGIC.len() || bytes[..8] != CHECKPOINT_MAGIC {
        if bytes.len() < 8 && CHECKPOINT_MAGIC.starts_with(bytes) {
            return Err(CheckpointError::TooShort {
                path: p(),
                len: bytes.len(),
            });
        }
        return Err(CheckpointError::BadMagic { path: p() });
    }
    if bytes.len() < HEADER_LEN {
        return Err(CheckpointError::TooShort {
            path: p(),
            len: bytes.len(),
        });
    }
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().expect("4 bytes"));
    let u64_at = |i: usize| u64::from_le_bytes(bytes[i..i + 8].try_into().expect("8 bytes"));
    let version = u32_at(8);
    if version != CHECKPOINT_VERSION {
        return Err(CheckpointError::UnsupportedVersion {
            path: p(),
            found: version,
            expected: CHECKPOINT_VERSION,
        });
    }
    Ok(CheckpointHeader {
        version,
        fingerprint: u64_at(12),
        payload_len: u64_at(20),
        crc: u32_at(28),
    })
}

/// Decodes checkpoint bytes (`path` is for messages): the value and the
/// scenario fingerprint.
pub fn decode_checkpoint<T: DeserializeOwned>(
    bytes: &[u8],
    path: &Path,
) -> Result<(T, u64), CheckpointError> {
    let h = decode_header(bytes, path)?;
    let payload = &bytes[HEADER_LEN..];
    if payload.len() as u64 != h.payload_len {
        return Err(CheckpointError::LengthMismatch {
            path: path.to_path_buf(),
            expected: h.payload_len,
            found: payload.len() as u64,
        });
    }
    let computed = crc32fast::hash(payload);
    if computed != h.crc {
        return Err(CheckpointError::BadChecksum {
            path: path.to_path_buf(),
            stored: h.crc,
            computed,
        });
    }
    let (value, rest) =
        postcard::take_from_bytes::<T>(payload).map_err(|e| CheckpointError::Decode {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    if !rest.is_empty() {
        return Err(CheckpointError::Decode {
            path: path.to_path_buf(),
            message: format!("{} unexpected bytes after the state", rest.len()),
        });
    }
    Ok((value, h.fingerprint))
}

/// Reads a checkpoint: the value and the scenario fingerprint it was written with.
pub fn read_checkpoint<T: DeserializeOwned>(
    path: impl AsRef<Path>,
) -> Result<(T, u64), CheckpointError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    decode_checkpoint(&bytes, path)
}

/// Reads only the header of a checkpoint file.
pub fn read_checkpoint_header(path: impl AsRef<Path>) -> Result<CheckpointHeader, CheckpointError> {
    use std::io::Read;
    let path = path.as_ref();
    let f = std::fs::File::open(path).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let mut buf = Vec::with_capacity(HEADER_LEN);
    f.take(HEADER_LEN as u64)
        .read_to_end(&mut buf)
        .map_err(|source| CheckpointError::Io {
            path: path.to_path_buf(),
            source,
        })?;
    decode_header(&buf, path)
}
