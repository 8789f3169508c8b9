//! Writing results: stdout that tolerates a closed pipe, and files that appear whole or not
//! at all (written to a temporary file beside the target, then renamed into place).
//!
//! What the target is decides how it is written:
//! - a regular file, or no file yet: a temporary file in the same folder, renamed over it. An
//!   existing file keeps its permission bits; a new one is created 0644 less the umask.
//! - a symbolic link: followed (through any chain of links, even to a file not yet there); the
//!   temporary file goes beside the final target and replaces it, and the link stays a link.
//! - anything else that exists (a device such as `/dev/null` or `/dev/stdout`, a FIFO, a
//!   socket): written through directly, as `cat > path` would, since renaming over it would
//!   replace the device node with a regular file.
//!
//! A temporary file still pending when SIGINT or SIGTERM arrives is removed before the process
//! exits (130 for SIGINT, 143 for SIGTERM), so an interrupted run leaves nothing behind.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, Once};

use crate::error::Error;
use crate::input::io_reason;

/// Runs `write` against a buffered, locked stdout. A reader that went away (`| head`) is not
/// an error.
pub fn stdout(write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<(), Error> {
    let out = io::stdout();
    let mut w = io::BufWriter::new(out.lock());
    written(write(&mut w).and_then(|()| w.flush()))
}

/// The outcome of writing stdout: a reader that went away (`| head`) is not an error.
pub fn written(result: io::Result<()>) -> Result<(), Error> {
    match result {
        Err(e) if e.kind() != io::ErrorKind::BrokenPipe => {
            Err(Error::runtime(format!("cannot write to stdout: {}", io_reason(&e))))
        }
        _ => Ok(()),
    }
}

/// Appends `v` as `{v:?}` writes it (the shortest text that reads back to the same number, in
/// scientific notation below 1e-4 and from 1e16 up: `3.0`, `0.0001`, `1e-5`, `1.5e16`), about
/// four times faster. The digits come from `ryu`, which writes the same text but for two cases:
/// - magnitudes in [1e-5, 1e-4): ryu writes `0.0000ddd`, `{:?}` `d.dde-5`; rewritten here.
/// - an exact tie (the number exactly halfway between the two nearest shortest texts, as
///   1299689300638963.25 is between …63.2 and …63.3): ryu rounds to the even digit, `{:?}` up;
///   such a number is written by `{:?}` itself ([`halfway`] finds it).
///
/// Not finite: `{:?}`'s own text (`NaN`, `inf`, `-inf`).
pub fn push_f64(buf: &mut Vec<u8>, v: f64) {
    let mut ryu = ryu::Buffer::new();
    let text = if v.is_finite() { ryu.format_finite(v).as_bytes() } else { b"" };
    if text.is_empty() || halfway(v, text) {
        buf.extend_from_slice(format!("{v:?}").as_bytes());
        return;
    }
    let (sign, magnitude) = match text {
        [b'-', rest @ ..] => (&b"-"[..], rest),
        _ => (&b""[..], text),
    };
    match magnitude.strip_prefix(b"0.0000") {
        // [1e-5, 1e-4): `0.0000` and the significant digits.
        Some(digits) if v != 0.0 => {
            buf.extend_from_slice(sign);
            buf.push(digits[0]);
            if digits.len() > 1 {
                buf.push(b'.');
                buf.extend_from_slice(&digits[1..]);
            }
            buf.extend_from_slice(b"e-5");
        }
        _ => buf.extend_from_slice(text),
    }
}

/// Whether finite `v`, which ryu wrote as `text` (digits `D` times `10^E`, `D` without trailing
/// zeros), is exactly `(D + ½)·10^E`: a tie between `D` and `D + 1`, which ryu breaks to the
/// even one and `{:?}` upwards. With `|v| = m·2^e` (`m` odd), `(2D + 1)·5^E·2^(E−1)` is that
/// value exactly when `e = E − 1` and `m = (2D + 1)·5^E` (for `E ≥ 0`), `m·5^(−E) = 2D + 1`
/// (for `E < 0`).
///
/// `D` has at most 17 digits, so `2D + 1 < 2·10^17 < 5^25`: with `E < 0` that needs `E ≥ −24`,
/// so `e ≥ −25`, which most numbers fail (any with more than 25 bits after the binary point,
/// as every angle and error of a batch but round ones): they are done without reading `text`.
fn halfway(v: f64, text: &[u8]) -> bool {
    if v == 0.0 {
        return false;
    }
    // m and e of |v|, m odd.
    let bits = v.to_bits();
    let (fraction, biased) = (bits & ((1 << 52) - 1), ((bits >> 52) & 0x7ff) as i32);
    let (mut m, mut e) = if biased == 0 { (fraction, -1074) } else { (fraction | (1 << 52), biased - 1075) };
    let zeros = m.trailing_zeros();
    m >>= zeros;
    e += zeros as i32;
    if e < -25 {
        return false;
    }
    // D and E from the text: `[-]digits[.digits][e[-]exponent]`.
    let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
        Some(i) => (&text[..i], std::str::from_utf8(&text[i + 1..]).ok().and_then(|t| t.parse::<i32>().ok())),
        None => (text, Some(0)),
    };
    let Some(mut big_e) = exponent else { return false };
    let mut d: u64 = 0;
    let mut after_point = false;
    for &c in mantissa {
        match c {
            b'.' => after_point = true,
            b'0'..=b'9' => {
                d = d * 10 + u64::from(c - b'0');
                big_e -= i32::from(after_point);
            }
            _ => {}
        }
    }
    if d == 0 {
        return false;
    }
    while d % 10 == 0 {
        d /= 10;
        big_e += 1;
    }
    if e != big_e - 1 {
        return false;
    }
    let twice = u128::from(d) * 2 + 1;
    let five = 5u128.checked_pow(big_e.unsigned_abs());
    match five {
        Some(p) if big_e >= 0 => p.checked_mul(twice) == Some(u128::from(m)),
        Some(p) => p.checked_mul(u128::from(m)) == Some(twice),
        None => false,
    }
}

/// Writes every `(path, bytes)` of `files`, each whole or not at all: every file is prepared
/// before any is written, so that an unwritable folder fails before the first; `flag` names the
/// option in messages.
pub fn write_files<P: AsRef<Path>, B: AsRef<[u8]>>(
    flag: &'static str,
    files: impl IntoIterator<Item = (P, B)>,
) -> Result<(), Error> {
    let pending = files
        .into_iter()
        .map(|(path, bytes)| Ok((PendingFile::create(path.as_ref(), flag)?, bytes)))
        .collect::<Result<Vec<_>, Error>>()?;
    for (file, bytes) in pending {
        file.commit(bytes.as_ref())?;
    }
    Ok(())
}

/// The command line's stdout and output files, where `ikarus bench` writes its results.
pub struct Terminal;

impl crate::bench::Sink for Terminal {
    fn stdout(&self, write: &mut dyn FnMut(&mut dyn Write) -> io::Result<()>) -> Result<(), Error> {
        stdout(write)
    }

    fn files(&self, flag: &'static str, files: &[(PathBuf, String)]) -> Result<(), Error> {
        write_files(flag, files.iter().map(|(path, text)| (path, text.as_bytes())))
    }
}

/// Ends the process on SIGINT (exit 130) or SIGTERM (143) from now on, removing every output
/// file still pending then. The command line calls it before any work, so that an interrupt
/// ends every command the same way whenever it comes (while a batch writes its rows to stdout,
/// while the input is read), not only once an output file is pending; `ikarus serve` does not,
/// as it shuts down on its own.
pub fn handle_interrupts() {
    cleanup::handle();
}

/// Links followed at most when resolving a target, as the kernel's own limit (ELOOP).
const MAX_LINK_HOPS: usize = 40;

/// How a pending file reaches its target.
enum Sink {
    /// A temporary file renamed over `target` (the resolved path), with the permission bits
    /// to give it (`None`: a new file, created 0644 less the umask).
    Replace { temp: Option<tempfile::NamedTempFile>, temp_path: PathBuf, target: PathBuf, mode: Option<u32> },
    /// A device, FIFO or socket: opened and written at commit.
    Direct,
}

/// An output file being prepared: for a file, created as a temporary file in the target's
/// folder up front, so that an unwritable destination is reported before any work is done,
/// and renamed into place by [`PendingFile::commit`]. Dropped without commit, it leaves nothing
/// behind (nor on SIGINT or SIGTERM).
pub struct PendingFile {
    sink: Sink,
    /// The path as the user gave it, for messages and direct writes.
    path: PathBuf,
    flag: &'static str,
}

impl PendingFile {
    /// Prepares to write `target`; `flag` names the option in error messages.
    pub fn create(target: &Path, flag: &'static str) -> Result<Self, Error> {
        let unwritable =
            |reason: String| Error::runtime(format!("{flag} {}: cannot write: {reason}", target.display()));
        let (resolved, mode) = match std::fs::metadata(target) {
            Ok(m) if m.is_dir() => return Err(unwritable("is a directory".to_owned())),
            Ok(m) if !m.is_file() => {
                return Ok(Self { sink: Sink::Direct, path: target.to_path_buf(), flag });
            }
            Ok(m) => {
                let real = std::fs::canonicalize(target).map_err(|e| unwritable(io_reason(&e)))?;
                (real, Some(mode_of(&m)))
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => (resolve_links(target).map_err(unwritable)?, None),
            Err(e) => return Err(unwritable(io_reason(&e))),
        };
        let dir = match resolved.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let mut builder = tempfile::Builder::new();
        builder.prefix(".ikarus-").suffix(".tmp");
        // Created 0644 (the kernel takes the umask off), not tempfile's private 0600.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o644));
        }
        let temp = builder.tempfile_in(&dir).map_err(|e| unwritable(io_reason(&e)))?;
        let temp_path = temp.path().to_path_buf();
        cleanup::register(&temp_path);
        let sink = Sink::Replace { temp: Some(temp), temp_path, target: resolved, mode };
        Ok(Self { sink, path: target.to_path_buf(), flag })
    }

    /// Writes `bytes` and renames the file into place (or writes them through to a device).
    pub fn commit(self, bytes: &[u8]) -> Result<(), Error> {
        self.commit_with(|w: &mut dyn Write| w.write_all(bytes))
    }

    /// Writes what `write` writes, as it writes it (buffered), and renames the file into place
    /// (or writes it through to a device); an error of `write` leaves nothing behind.
    pub fn commit_with(mut self, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<(), Error> {
        let (path, flag) = (self.path.clone(), self.flag);
        let fail = |e: io::Error| Error::runtime(format!("{flag} {}: cannot write: {}", path.display(), io_reason(&e)));
        match &mut self.sink {
            Sink::Direct => {
                let file = std::fs::OpenOptions::new().write(true).open(&path).map_err(fail)?;
                let mut w = io::BufWriter::new(file);
                write(&mut w).and_then(|()| w.flush()).map_err(fail)
            }
            Sink::Replace { temp, target, mode, .. } => {
                let Some(mut temp) = temp.take() else { return Ok(()) };
                let mut w = io::BufWriter::new(temp.as_file_mut());
                write(&mut w).and_then(|()| w.flush()).map_err(fail)?;
                drop(w);
                temp.as_file().sync_all().map_err(fail)?;
                if let Some(mode) = *mode {
                    set_mode(temp.path(), mode).map_err(fail)?;
                }
                temp.persist(&*target).map(drop).map_err(|e| fail(e.error))
            }
        }
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        if let Sink::Replace { temp_path, .. } = &self.sink {
            cleanup::unregister(temp_path);
        }
    }
}

#[cfg(unix)]
fn mode_of(m: &std::fs::Metadata) -> u32 {
    use std::os::unix::fs::PermissionsExt;
    m.permissions().mode() & 0o7777
}

#[cfg(not(unix))]
fn mode_of(_: &std::fs::Metadata) -> u32 {
    0
}

#[cfg(unix)]
fn set_mode(path: &Path, mode: u32) -> io::Result<()> {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode))
}

#[cfg(not(unix))]
fn set_mode(_: &Path, _: u32) -> io::Result<()> {
    Ok(())
}

/// The path a write to `path` (which does not exist) creates: `path` itself, or, when it is a
/// symbolic link to a file not there yet, the end of the chain of links.
fn resolve_links(path: &Path) -> Result<PathBuf, String> {
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINK_HOPS {
        match std::fs::symlink_metadata(&current) {
            Ok(m) if m.file_type().is_symlink() => {
                let next = std::fs::read_link(&current).map_err(|e| io_reason(&e))?;
                current = match current.parent() {
                    Some(dir) if next.is_relative() => dir.join(next),
                    _ => next,
                };
            }
            _ => return Ok(current),
        }
    }
    Err(format!("more than {MAX_LINK_HOPS} symbolic links"))
}

/// The temporary files pending at this moment, removed if the process is interrupted.
mod cleanup {
    use super::{Mutex, Once, Path, PathBuf};

    static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
    static HANDLER: Once = Once::new();

    /// Installs the handler of SIGINT / SIGTERM, once.
    pub fn handle() {
        HANDLER.call_once(install);
    }

    /// Adds `path` to the files removed on SIGINT / SIGTERM, installing the handler once.
    pub fn register(path: &Path) {
        handle();
        PENDING.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(path.to_path_buf());
    }

    /// Removes `path` from the list (it was renamed into place, or dropped).
    pub fn unregister(path: &Path) {
        PENDING.lock().unwrap_or_else(std::sync::PoisonError::into_inner).retain(|p| p != path);
    }

    /// Removes every pending file and exits with `code`.
    fn interrupted(code: u8) -> ! {
        let pending = PENDING.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        for p in pending.iter() {
            let _ = std::fs::remove_file(p);
        }
        let removed = if pending.is_empty() { "" } else { "; the unfinished output file is removed" };
        eprintln!("ikarus: interrupted{removed}");
        std::process::exit(i32::from(code))
    }

    /// A thread that waits for SIGINT or SIGTERM (tokio's signal handling, already a dependency
    /// for `ikarus serve`; installed by every command but serve, which keeps its own).
    #[cfg(all(unix, feature = "server"))]
    fn install() {
        let (ready, installed) = std::sync::mpsc::channel::<()>();
        let spawned = std::thread::Builder::new().name("ikarus-signals".to_owned()).spawn(move || {
            use tokio::signal::unix::{SignalKind, signal};
            let Ok(rt) = tokio::runtime::Builder::new_current_thread().enable_io().build() else { return };
            let code = rt.block_on(async {
                let (Ok(mut int), Ok(mut term)) = (signal(SignalKind::interrupt()), signal(SignalKind::terminate()))
                else {
                    return None;
                };
                let _ = ready.send(());
                tokio::select! {
                    _ = int.recv() => Some(130),
                    _ = term.recv() => Some(143),
                }
            });
            if let Some(code) = code {
                interrupted(code);
            }
        });
        // Wait until the handlers are in place, so that no interrupt slips between; without the
        // thread an interrupt still stops the process, only without the cleanup.
        if spawned.is_ok() {
            let _ = installed.recv();
        }
    }

    /// Without the command line (the edges' library), no files are written by a command.
    #[cfg(not(all(unix, feature = "server")))]
    fn install() {}
}

#[cfg(test)]
mod tests {
    use super::push_f64;

    fn text(v: f64) -> String {
        let mut buf = Vec::new();
        push_f64(&mut buf, v);
        String::from_utf8(buf).unwrap()
    }

    /// The edges of `{:?}`'s notations, and of ryu's: the same bytes.
    #[test]
    fn floats_are_written_as_debug_writes_them() {
        let edges = [
            0.0,
            -0.0,
            3.0,
            -3.0,
            0.1,
            1e-4,
            0.00012,
            9.999999999999999e-5,
            1e-5,
            -1e-5,
            1.2345e-5,
            f64::from_bits(1e-5f64.to_bits() + 1),
            9.99999999999e-6,
            1e-7,
            1.5e-7,
            1e15,
            1e16,
            -1e16,
            9999999999999998.0,
            123456789012345680.0,
            1e21,
            1e22,
            5e-324,
            -5e-324,
            2.2250738585072014e-308,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1299689300638963.2,
            1299689300638963.3,
            1299689300638963.5,
            0.25,
            0.5,
            2.5,
        ];
        for v in edges {
            assert_eq!(text(v), format!("{v:?}"), "{v:e}");
        }
    }

    /// Random bit patterns (every exponent), and random numbers around the notations' edges.
    #[test]
    fn random_floats_are_written_as_debug_writes_them() {
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..200_000 {
            let bits = f64::from_bits(next());
            let unit = (next() >> 11) as f64 / (1u64 << 53) as f64;
            let near = [1e-5, 1e-4, 1e15, 1e16][(next() % 4) as usize] * (0.5 + unit);
            for v in [bits, near, -near] {
                assert_eq!(text(v), format!("{v:?}"), "{:x}", v.to_bits());
            }
        }
    }
}
