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

use crate::arm::io_reason;
use crate::error::CliError;

/// Runs `write` against a buffered, locked stdout. A reader that went away (`| head`) is not
/// an error.
pub fn stdout(write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<(), CliError> {
    let out = io::stdout();
    let mut w = io::BufWriter::new(out.lock());
    let result = write(&mut w).and_then(|()| w.flush());
    match result {
        Err(e) if e.kind() != io::ErrorKind::BrokenPipe => {
            Err(CliError::runtime(format!("cannot write to stdout: {}", io_reason(&e))))
        }
        _ => Ok(()),
    }
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
    pub fn create(target: &Path, flag: &'static str) -> Result<Self, CliError> {
        let unwritable =
            |reason: String| CliError::runtime(format!("{flag} {}: cannot write: {reason}", target.display()));
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
    pub fn commit(mut self, bytes: &[u8]) -> Result<(), CliError> {
        let (path, flag) = (self.path.clone(), self.flag);
        let fail =
            |e: io::Error| CliError::runtime(format!("{flag} {}: cannot write: {}", path.display(), io_reason(&e)));
        match &mut self.sink {
            Sink::Direct => {
                let mut file = std::fs::OpenOptions::new().write(true).open(&path).map_err(fail)?;
                file.write_all(bytes).and_then(|()| file.flush()).map_err(fail)
            }
            Sink::Replace { temp, target, mode, .. } => {
                let Some(mut temp) = temp.take() else { return Ok(()) };
                temp.write_all(bytes).map_err(fail)?;
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

    /// Adds `path` to the files removed on SIGINT / SIGTERM, installing the handler once.
    pub fn register(path: &Path) {
        HANDLER.call_once(install);
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
    /// for `ikarus serve`; only installed once a file is pending, so serve keeps its own).
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
