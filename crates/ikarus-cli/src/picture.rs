//! Pictures of the commands: the format from the file name, the size flags, a progress bar for
//! slow renders, and writing the file whole or not at all. What to draw and the one path that
//! draws it are the edge's ([`ikarus_edge::picture`]).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::Args;
pub use ikarus_edge::picture::*;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::error::Error;
use crate::output::PendingFile;

/// A picture's size in pixels: `--width`, `--height`.
#[derive(Debug, Clone, Copy, Args)]
pub struct SizeArgs {
    /// Picture width in pixels
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub width: u32,
    /// Picture height in pixels
    #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub height: u32,
}

/// `--out` and the picture size.
#[derive(Debug, Clone, Args)]
pub struct PictureArgs {
    /// Draw the result to FILE (.svg, .png, or .gif where it animates)
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub size: SizeArgs,
    /// Largest GIF drawn, in frames × width × height pixels (about 6 s of rendering at the cap)
    #[arg(long, value_name = "PIXELS", default_value_t = DEFAULT_MAX_GIF_PIXELS)]
    pub max_gif_pixels: u64,
}

/// `--out` and the picture size of a command that draws one still picture (.svg, .png):
/// `ikarus solve`.
#[derive(Debug, Clone, Args)]
pub struct StillArgs {
    /// Draw the solved pose to FILE (.svg or .png): the goal and, for a rig, its pins
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub size: SizeArgs,
}

impl StillArgs {
    /// Checks the extension and prepares the file; `None` without `--out`.
    pub fn prepare(&self) -> Result<Option<PictureOut>, Error> {
        let Some(path) = &self.out else { return Ok(None) };
        let format = format_of(path, &[PictureFormat::Svg, PictureFormat::Png])?;
        let file = PendingFile::create(path, "--out")?;
        Ok(Some(PictureOut { format, file }))
    }
}

/// The format of a command's report on stdout, or `None` for none: the one asked for
/// (`--format`); else none when the command drew a picture (`drew`, with `--out`: the picture is
/// the result, so stdout stays quiet); else `text` on a terminal and `json` when piped. Every
/// command with `--out` (solve, animate, track, workspace, with an arm or a rig) decides so.
pub fn report_format<F>(asked: Option<F>, drew: bool, text: F, json: F) -> Option<F> {
    match (asked, drew) {
        (Some(f), _) => Some(f),
        (None, true) => None,
        (None, false) if std::io::stdout().is_terminal() => Some(text),
        (None, false) => Some(json),
    }
}

/// The default cap of `--max-gif-pixels`: 1000 frames of 800 × 800 and more (10⁹ pixels;
/// 100 frames at 4096 × 4096, 1.7·10⁹ pixels, took 11 s).
pub const DEFAULT_MAX_GIF_PIXELS: u64 = 1_000_000_000;

/// A picture to be written: its format, and the file prepared up front so that an unwritable
/// path fails before any work is done.
pub struct PictureOut {
    pub format: PictureFormat,
    file: PendingFile,
}

impl PictureArgs {
    /// Checks the extension against `allowed` and prepares the file; `None` without `--out`.
    pub fn prepare(&self, allowed: &[PictureFormat]) -> Result<Option<PictureOut>, Error> {
        let Some(path) = &self.out else { return Ok(None) };
        let format = format_of(path, allowed)?;
        let file = PendingFile::create(path, "--out")?;
        Ok(Some(PictureOut { format, file }))
    }
}

impl PictureOut {
    /// Writes the bytes and renames the file into place.
    pub fn commit(self, bytes: &[u8]) -> Result<(), Error> {
        self.file.commit(bytes)
    }
}

fn format_of(path: &Path, allowed: &[PictureFormat]) -> Result<PictureFormat, Error> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("svg") => Some(PictureFormat::Svg),
        Some("png") => Some(PictureFormat::Png),
        Some("gif") => Some(PictureFormat::Gif),
        _ => None,
    };
    let names: Vec<&str> = allowed.iter().map(|f| f.extension()).collect();
    match format {
        Some(f) if allowed.contains(&f) => Ok(f),
        _ => Err(Error::input(format!(
            "--out {}: unsupported picture format (use {})",
            path.display(),
            names.join(", ")
        ))),
    }
}

/// [`draw`] for a command, at the size of the flags: a GIF of more than `--max-gif-pixels`
/// pixels is refused; a GIF of `frames` frames shows a progress bar on stderr while it
/// renders, when stderr is a terminal.
pub fn draw_for_command(
    drawing: &Drawing<'_>,
    format: PictureFormat,
    picture: &PictureArgs,
    frames: usize,
) -> Result<Vec<u8>, Error> {
    let SizeArgs { width, height } = picture.size;
    if format == PictureFormat::Gif {
        gif_within_cap(picture, frames, "fewer --frames")?;
    }
    let bar = (format == PictureFormat::Gif).then(|| progress_bar(frames as u64, "rendering frames")).flatten();
    let report = |done: usize, total: usize| {
        if let Some(bar) = &bar {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        }
    };
    let bytes = draw(drawing, format, width, height, &report)?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(bytes)
}

/// A GIF of `frames` frames at `--width` × `--height` within `--max-gif-pixels`, checked before
/// any frame is made; else the one-line refusal, `fewer` saying how the command makes fewer
/// frames (`fewer --frames`; a character's motion: `a lower --fps or a shorter --duration`).
pub fn gif_within_cap(picture: &PictureArgs, frames: usize, fewer: &str) -> Result<(), Error> {
    let SizeArgs { width, height } = picture.size;
    let pixels = (frames as u64).saturating_mul(u64::from(width) * u64::from(height));
    if pixels > picture.max_gif_pixels {
        return Err(Error::input(format!(
            "--out: a GIF of {frames} frames of {width}×{height} is {pixels} pixels, more than the cap of {} ({fewer}, a smaller --width/--height, or raise it with --max-gif-pixels N)",
            picture.max_gif_pixels
        )));
    }
    Ok(())
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
