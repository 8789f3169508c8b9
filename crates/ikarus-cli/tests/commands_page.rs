//! The book's page of every command's flags, `docs/src/reference/commands.md`, generated from
//! the command line's own definition as the manual pages are: each command's `--help`, as clap
//! prints it, for `ikarus` and every subcommand it lists, depth first. The test fails when the
//! committed page differs from what the binary prints; `IKARUS_WRITE_DOCS=1` writes it again.

use std::path::{Path, PathBuf};
use std::process::Command;

const PAGE: &str = "docs/src/reference/commands.md";
const REGENERATE: &str = "IKARUS_WRITE_DOCS=1 cargo test -p ikarus-cli --test commands_page";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// What `ikarus PATH… --help` prints.
fn help(path: &[String]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_ikarus")).args(path).arg("--help").output().unwrap();
    assert!(o.status.success(), "ikarus {} --help failed", path.join(" "));
    String::from_utf8(o.stdout).unwrap()
}

/// The subcommands a help text lists under `Commands:`, without `help`.
fn subcommands(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| l.trim_end() != "Commands:")
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        // A listed command starts two spaces in; a description wrapped onto the next line is
        // indented further.
        .filter(|l| l.starts_with("  ") && !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_owned)
        .collect()
}

/// Appends the section of the command at `path` and of every subcommand below it.
fn section(path: &[String], page: &mut String) {
    let text = help(path);
    let name = std::iter::once("ikarus").chain(path.iter().map(String::as_str)).collect::<Vec<_>>().join(" ");
    let level = "#".repeat(2 + path.len().saturating_sub(1));
    page.push_str(&format!("{level} `{name}`\n\n```text\n{}\n```\n\n", text.trim_end()));
    for sub in subcommands(&text) {
        let mut deeper = path.to_vec();
        deeper.push(sub);
        section(&deeper, page);
    }
}

/// The page as the binary describes itself today.
fn generated() -> String {
    let mut page = format!(
        "# Every command's flags\n\n\
         <!-- Generated from `ikarus … --help` by crates/ikarus-cli/tests/commands_page.rs: \
         edit the flags' doc comments, then run `{REGENERATE}`. -->\n\n\
         What `ikarus COMMAND --help` prints, for every command: the flags, their values and \
         defaults. `ikarus man` gives the same as manual pages, and `ikarus completions SHELL` \
         completes them in a shell ([Shell completions and manual pages](../guide/completions.md)).\n\n"
    );
    section(&[], &mut page);
    format!("{}\n", page.trim_end())
}

#[test]
fn the_commands_page_is_what_the_binary_prints() {
    let path = root().join(PAGE);
    let now = generated();
    if std::env::var_os("IKARUS_WRITE_DOCS").is_some() {
        std::fs::write(&path, &now).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != now {
        let line = committed
            .lines()
            .zip(now.lines())
            .position(|(a, b)| a != b)
            .map_or_else(|| committed.lines().count().min(now.lines().count()) + 1, |i| i + 1);
        panic!("{PAGE} is stale from line {line} on (the flags changed): `{REGENERATE}` writes it again");
    }
}

#[test]
fn the_page_covers_every_command() {
    let top = subcommands(&help(&[]));
    assert!(top.contains(&"solve".to_owned()) && top.contains(&"serve".to_owned()), "{top:?}");
    let page = generated();
    for command in &top {
        assert!(page.contains(&format!("## `ikarus {command}`")), "no section for {command}");
    }
    assert_eq!(subcommands("Commands:\n  solve  Solve\n         more\n  help   Print\n\nOptions:\n"), ["solve"]);
}
