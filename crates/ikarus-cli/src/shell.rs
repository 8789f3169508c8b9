//! `ikarus completions SHELL` and `ikarus man`: the shell's completion script (clap_complete)
//! and the manual pages (clap_mangen), both made from the command line's own definition, so
//! that they name every command and flag there is.

use std::path::PathBuf;

use clap::Args;
use clap_complete::Shell;

use crate::error::Error;
use crate::input::io_reason;
use crate::output;

/// `ikarus completions SHELL`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell to complete in. Load it with, for bash: `source <(ikarus completions bash)`;
    /// zsh: `ikarus completions zsh > ~/.zfunc/_ikarus` (a folder on `fpath`); fish:
    /// `ikarus completions fish > ~/.config/fish/completions/ikarus.fish`
    #[arg(value_enum)]
    pub shell: Shell,
}

/// `ikarus man`.
#[derive(Debug, Args)]
pub struct ManArgs {
    /// Write one page per command into folder DIR (created if missing): ikarus.1,
    /// ikarus-solve.1, ikarus-render-arm.1, …; without it, the main page goes to stdout
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Prints the completion script of `command` for the shell asked for.
pub fn completions(args: &CompletionsArgs, mut command: clap::Command) -> Result<(), Error> {
    let name = command.get_name().to_owned();
    // Made in memory first: clap_complete panics on a failed write (a reader gone, `| head`).
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut command, name, &mut script);
    output::stdout(|w| w.write_all(&script))
}

/// Prints the main manual page of `command` (roff), or writes every command's page to
/// `--out DIR`, each whole or not at all.
pub fn man(args: &ManArgs, command: clap::Command) -> Result<(), Error> {
    let pages = pages(command).map_err(|e| Error::runtime(format!("cannot make the manual: {}", io_reason(&e))))?;
    let Some(dir) = &args.out else {
        let main = pages.into_iter().last().map(|(_, roff)| roff).unwrap_or_default();
        return output::stdout(|w| w.write_all(&main));
    };
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::runtime(format!("--out {}: cannot create the folder: {}", dir.display(), io_reason(&e))))?;
    output::write_files("--out", pages.into_iter().map(|(name, roff)| (dir.join(name), roff)))
}

/// Every visible command's page, `(file name, roff)`, the subcommands' before their parent's
/// (the main page, `ikarus.1`, last), as clap_mangen's `generate_to` names and orders them.
fn pages(command: clap::Command) -> std::io::Result<Vec<(String, Vec<u8>)>> {
    fn walk(command: &clap::Command, out: &mut Vec<(String, Vec<u8>)>) -> std::io::Result<()> {
        for sub in command.get_subcommands().filter(|s| !s.is_hide_set()) {
            walk(sub, out)?;
        }
        let man = clap_mangen::Man::new(command.clone());
        let mut roff = Vec::new();
        man.render(&mut roff)?;
        out.push((man.get_filename(), roff));
        Ok(())
    }
    // Built, so that each subcommand knows its full name (`ikarus-render-arm`); no `help`
    // subcommand, which has no page of its own.
    let mut command = command.disable_help_subcommand(true);
    command.build();
    let mut out = Vec::new();
    walk(&command, &mut out)?;
    Ok(out)
}
