//! `ikarus`: inverse kinematics for planar arms, from the command line.
//!
//! Data goes to stdout, messages to stderr. Exit codes: 0 success, 1 a failure at run time,
//! 2 bad input (flags, files, values), each reported in one line that names the field and
//! the value.

use std::process::ExitCode;

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::{CommandFactory, Parser, Subcommand};

use crate::error::Error;
use crate::{animate, bench, input, output, pose, reach, render, rig, serve, shell, solve, track, workspace};

/// Inverse kinematics for planar chains: move an arm's tip to a goal.
#[derive(Debug, Parser)]
#[command(name = "ikarus", version, about, propagate_version = true)]
struct Cli {
    /// Largest input file read (--arm, --rig, --batch, --path), in bytes
    #[arg(long, global = true, value_name = "BYTES", default_value_t = input::DEFAULT_MAX_INPUT_BYTES)]
    max_input_bytes: u64,
    /// Most bones of a rig read (--rig of solve, animate, track, render rig), counted before anything else is checked
    #[arg(long, global = true, value_name = "N", default_value_t = rig::DEFAULT_MAX_BONES as u64, value_parser = clap::value_parser!(u64).range(1..))]
    max_bones: u64,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Move the arm's tip to a goal and report the pose and the recorded frames; with --rig,
    /// goals on a rig's bones and pins, solved together
    #[command(allow_negative_numbers = true)]
    Solve(solve::SolveArgs),
    /// Solve for a goal (through any via points) and turn it into a smooth, eased motion:
    /// frames on stdout, a picture or an animated GIF with --out
    #[command(allow_negative_numbers = true)]
    Animate(animate::AnimateArgs),
    /// The tip follows a path (a CSV file, a line, a circle or a figure-8) without flips:
    /// planned over the whole path, or followed online with every joint step bounded
    #[command(allow_negative_numbers = true)]
    Track(track::TrackArgs),
    /// The region the arm's tip can reach, exactly: radii, area, boundary loops, picture (the
    /// sampled occupancy grid with --grid)
    Workspace(workspace::WorkspaceArgs),
    /// Whether the arm's tip can reach a point (or every point of a CSV file), how far it is
    /// from the reachable region and the nearest reachable point
    #[command(allow_negative_numbers = true)]
    Reach(reach::ReachArgs),
    /// Pose a character file (Spine, DragonBones) as its runtime does: the setup pose, an
    /// animation at a time, bones moved to targets, the IK constraints in order
    #[command(allow_negative_numbers = true)]
    Pose(pose::PoseArgs),
    /// Draw figures that stand on their own
    #[command(subcommand)]
    Render(render::RenderCommand),
    /// Serve the playground page and the JSON API over HTTP on 127.0.0.1:7878
    Serve(serve::ServeArgs),
    /// Time every solver on seeded goal sets for the shipped arms, optionally beside Orocos KDL
    Bench(bench::BenchArgs),
    /// Print a completion script for a shell (bash, zsh, fish, elvish, powershell) to stdout
    Completions(shell::CompletionsArgs),
    /// Print the manual page (roff) to stdout, or write one page per command to a folder
    Man(shell::ManArgs),
}

/// The command line: parses the arguments, runs the command, prints a failure in one line.
pub fn main() -> ExitCode {
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
    input::set_max_bytes(cli.max_input_bytes);
    rig::set_max_bones(usize::try_from(cli.max_bones).unwrap_or(usize::MAX));
    // Ctrl-C (SIGINT) or SIGTERM ends every command but the server (which shuts down on its own)
    // with 130 or 143 and the unfinished output files removed, whenever it comes.
    if !matches!(cli.command, Command::Serve(_)) {
        output::handle_interrupts();
    }
    let result: Result<(), Error> = match &cli.command {
        Command::Solve(args) => solve::run(args),
        Command::Animate(args) => animate::run(args),
        Command::Track(args) => track::run(args),
        Command::Workspace(args) => workspace::run(args),
        Command::Reach(args) => reach::run(args),
        Command::Pose(args) => pose::run(args),
        Command::Render(command) => render::run(command),
        Command::Serve(args) => serve::run(args),
        Command::Bench(args) => bench::run(args, &output::Terminal),
        Command::Completions(args) => shell::completions(args, Cli::command()),
        Command::Man(args) => shell::man(args, Cli::command()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ikarus: {e}");
            ExitCode::from(exit_code(&e))
        }
    }
}

/// The exit code of a failed command: 2 for the user's input (a flag, a file, a value), 1 for a
/// failure at run time.
fn exit_code(e: &Error) -> u8 {
    if e.kind().is_input() { 2 } else { 1 }
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
            // the lines below it); the usage and help hint that follow are left out, and a
            // suggestion (`tip: a similar subcommand exists`) becomes `did you mean …?`.
            let text = e.to_string();
            let message: Vec<&str> =
                text.lines().take_while(|l| !l.is_empty() && !l.starts_with("Usage:")).map(str::trim).collect();
            let message = message.join(" ");
            let message = message.strip_prefix("error: ").unwrap_or(&message);
            eprintln!("ikarus: {message}{}", did_you_mean(e));
            ExitCode::from(2)
        }
    }
}

/// `; did you mean 'solve'?` when clap found a similar subcommand, flag or value for a
/// misspelt one, else nothing.
fn did_you_mean(e: &clap::Error) -> String {
    let kinds = [ContextKind::SuggestedSubcommand, ContextKind::SuggestedArg, ContextKind::SuggestedValue];
    let names: Vec<String> = kinds
        .iter()
        .filter_map(|&k| e.get(k))
        .flat_map(|v| match v {
            ContextValue::String(s) => vec![s.clone()],
            ContextValue::Strings(s) => s.clone(),
            _ => Vec::new(),
        })
        .map(|name| format!("'{name}'"))
        .collect();
    match &names[..] {
        [] => String::new(),
        [one] => format!("; did you mean {one}?"),
        [init @ .., last] => format!("; did you mean {} or {last}?", init.join(", ")),
    }
}
