//! Picture outputs shared by the commands: the format from the file name, the size flags,
//! a progress bar for slow renders, and writing the file whole or not at all.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::error::CliError;
use crate::output::PendingFile;

/// What a picture file holds, from its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PictureFormat {
    Svg,
    Png,
    Gif,
}

/// `--out` and the picture size.
#[derive(Debug, Clone, Args)]
pub struct PictureArgs {
    /// Draw the result to FILE (.svg, .png, or .gif where it animates)
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Picture width in pixels
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub width: u32,
    /// Picture height in pixels
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub height: u32,
}

/// A picture to be written: its format, and the file prepared up front so that an unwritable
/// path fails before any work is done.
pub struct PictureOut {
    pub format: PictureFormat,
    file: PendingFile,
}

impl PictureArgs {
    /// Checks the extension against `allowed` and prepares the file; `None` without `--out`.
    pub fn prepare(&self, allowed: &[PictureFormat]) -> Result<Option<PictureOut>, CliError> {
        let Some(path) = &self.out else { return Ok(None) };
        let format = format_of(path, allowed)?;
        let file = PendingFile::create(path, "--out")?;
        Ok(Some(PictureOut { format, file }))
    }
}

impl PictureOut {
    /// Writes the bytes and renames the file into place.
    pub fn commit(self, bytes: &[u8]) -> Result<(), CliError> {
        self.file.commit(bytes)
    }
}

fn format_of(path: &Path, allowed: &[PictureFormat]) -> Result<PictureFormat, CliError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("svg") => Some(PictureFormat::Svg),
        Some("png") => Some(PictureFormat::Png),
        Some("gif") => Some(PictureFormat::Gif),
        _ => None,
    };
    let names: Vec<&str> = allowed
        .iter()
        .map(|f| match f {
            PictureFormat::Svg => ".svg",
            PictureFormat::Png => ".png",
            PictureFormat::Gif => ".gif",
        })
        .collect();
    match format {
        Some(f) if allowed.contains(&f) => Ok(f),
        _ => Err(CliError::input(format!(
            "--out {}: unsupported picture format (use {})",
            path.display(),
            names.join(", ")
        ))),
    }
}

/// A progress bar on stderr when it is a terminal, for `total` steps of `what`.
pub fn progress_bar(total: u64, what: &str) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    let template = format!("{{spinner}} {what} [{{bar:30}}] {{percent}}% {{eta}}");
    bar.set_style(ProgressStyle::with_template(&template).expect("static template").progress_chars("=> "));
    Some(bar)
}

/// Maps a render error to the CLI's run-time error.
pub fn render_failed(e: &impl std::fmt::Display) -> CliError {
    CliError::runtime(format!("rendering failed: {e}"))
}
