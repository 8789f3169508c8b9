//! Reading the files that flags name (`--arm`, `--rig`, `solve --batch`, `track --path`): only
//! regular files (a device such as `/dev/zero` would be read until memory runs out, a FIFO would block
//! until a writer comes), and at most [`max_bytes`] of them (64 MiB unless
//! `ikarus --max-input-bytes N` says otherwise).

use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::Error;

/// The default cap of an input file: far beyond any arm or goal file (a million goals of CSV
/// is about 30 MB).
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 64 << 20;

static MAX_INPUT_BYTES: AtomicU64 = AtomicU64::new(DEFAULT_MAX_INPUT_BYTES);

/// Sets the cap (from `--max-input-bytes`).
pub fn set_max_bytes(bytes: u64) {
    MAX_INPUT_BYTES.store(bytes, Ordering::Relaxed);
}

/// The cap of one input file, in bytes.
pub fn max_bytes() -> u64 {
    MAX_INPUT_BYTES.load(Ordering::Relaxed)
}

/// Reads the regular file `path` whole, refusing other kinds of file and anything larger than
/// [`max_bytes`]; errors start with `label` (e.g. `arm file a.toml`).
pub fn read(path: &Path, label: &str) -> Result<Vec<u8>, Error> {
    let cannot = |reason: String| Error::input(format!("{label}: cannot read: {reason}"));
    // The kind is checked before opening: opening a FIFO for reading blocks until a writer comes.
    let meta = std::fs::metadata(path).map_err(|e| cannot(io_reason(&e)))?;
    if meta.is_dir() {
        return Err(cannot("is a directory".to_owned()));
    }
    if !meta.is_file() {
        return Err(cannot("not a regular file (a device, FIFO or socket); give a file".to_owned()));
    }
    let cap = max_bytes();
    let too_big = || {
        Error::input(format!(
            "{label}: larger than the cap of {cap} bytes on input files (raise it with ikarus --max-input-bytes N)"
        ))
    };
    if meta.len() > cap {
        return Err(too_big());
    }
    let file = std::fs::File::open(path).map_err(|e| cannot(io_reason(&e)))?;
    let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    // The file may grow between the check and the read: never read more than the cap.
    file.take(cap.saturating_add(1)).read_to_end(&mut bytes).map_err(|e| cannot(io_reason(&e)))?;
    if bytes.len() as u64 > cap {
        return Err(too_big());
    }
    Ok(bytes)
}

/// [`read`] as UTF-8 text.
pub fn read_text(path: &Path, label: &str) -> Result<String, Error> {
    String::from_utf8(read(path, label)?).map_err(|e| {
        Error::input(format!("{label}: cannot read: not UTF-8 text (byte {})", e.utf8_error().valid_up_to()))
    })
}

/// [`read`] as the text of a file that may be a character ([`crate::character::skel::text_of`]): a
/// Spine binary export (`.skel`) as the JSON text of the same skeleton, anything else as UTF-8
/// text.
pub fn read_character_text(path: &Path, label: &str) -> Result<String, Error> {
    crate::character::skel::text_of(read(path, label)?, label)
}

/// The OS reason without Rust's "(os error N)" suffix.
pub fn io_reason(e: &std::io::Error) -> String {
    let s = e.to_string();
    match s.find(" (os error") {
        Some(i) => s[..i].to_owned(),
        None => s,
    }
}
