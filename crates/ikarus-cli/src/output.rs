//! Writing results: stdout that tolerates a closed pipe, and files that appear whole or not
//! at all (written to a temporary file beside the target, then renamed into place).

use std::io::{self, Write};
use std::path::{Path, PathBuf};

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

/// An output file being prepared: created as a temporary file in the target's folder up front,
/// so that an unwritable destination is reported before any work is done, and renamed into
/// place by [`PendingFile::commit`]. Dropped without commit, it leaves nothing behind.
pub struct PendingFile {
    temp: tempfile::NamedTempFile,
    target: PathBuf,
    flag: &'static str,
}

impl PendingFile {
    /// Prepares to write `target`; `flag` names the option in error messages.
    pub fn create(target: &Path, flag: &'static str) -> Result<Self, CliError> {
        let unwritable =
            |reason: String| CliError::runtime(format!("{flag} {}: cannot write: {reason}", target.display()));
        if target.is_dir() {
            return Err(unwritable("is a directory".to_owned()));
        }
        let dir = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let temp = tempfile::Builder::new()
            .prefix(".ikarus-")
            .suffix(".tmp")
            .tempfile_in(&dir)
            .map_err(|e| unwritable(io_reason(&e)))?;
        Ok(Self { temp, target: target.to_path_buf(), flag })
    }

    /// Writes `bytes` and renames the file into place.
    pub fn commit(mut self, bytes: &[u8]) -> Result<(), CliError> {
        let target = self.target.clone();
        let flag = self.flag;
        let fail =
            |e: io::Error| CliError::runtime(format!("{flag} {}: cannot write: {}", target.display(), io_reason(&e)));
        self.temp.write_all(bytes).and_then(|()| self.temp.as_file().sync_all()).map_err(fail)?;
        // A temporary file is private (0600); the output is an ordinary file like any other.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::Permissions::from_mode(0o644);
            std::fs::set_permissions(self.temp.path(), mode).map_err(fail)?;
        }
        self.temp.persist(&self.target).map_err(|e| fail(e.error))?;
        Ok(())
    }
}
