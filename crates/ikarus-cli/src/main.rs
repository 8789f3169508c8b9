//! `ikarus`: inverse kinematics for planar arms, from the command line.
//!
//! Data goes to stdout, messages to stderr. Exit codes: 0 success, 1 a failure at run time,
//! 2 bad input (flags, files, values), each reported in one line that names the field and
//! the value.

mod arm;
mod error;
mod options;
mod output;
mod solve;

use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{Parser, Subcommand};

use crate::error::CliError;

/// Inverse kinematics for planar chains: move an arm's tip to a goal.
#[derive(Debug, Parser)]
#[command(name = "ikarus", version, about, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Move the arm's tip to a goal and report the pose and the recorded frames
    #[command(allow_negative_numbers = true)]
    Solve(solve::SolveArgs),
}

fn main() -> ExitCode {
    // A bug must not greet the user with a backtrace: one line, and a distinct exit code.
    std::panic::set_hook(Box::new(|info| {
        let what = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".to_owned());
        let at = info.location().map_or(String::new(), |l| format!(" at {}:{}", l.file(), l.line()));
        eprintln!("ikarus: internal error{at}: {}", what.replace('\n', " "));
    }));

    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(&e),
    };
    let result: Result<(), CliError> = match &cli.command {
        Command::Solve(args) => solve::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ikarus: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// Help and version go out as clap renders them; every other parse error becomes one line.
fn usage_error(e: &clap::Error) -> ExitCode {
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            ExitCode::from(2)
        }
        _ => {
            // clap's message is the first paragraph (a missing argument lists the arguments on
            // the lines below it); the usage and help hint that follow are left out.
            let text = e.to_string();
            let message: Vec<&str> =
                text.lines().take_while(|l| !l.is_empty() && !l.starts_with("Usage:")).map(str::trim).collect();
            let message = message.join(" ");
            eprintln!("ikarus: {}", message.strip_prefix("error: ").unwrap_or(&message));
            ExitCode::from(2)
        }
    }
}
