//! The command line in the shell: suggestions for a misspelt command or flag, completion
//! scripts (`ikarus completions SHELL`) and manual pages (`ikarus man`).

mod common;

use common::{fails, ikarus, stderr, stdout, succeeds};

/// Every command `ikarus --help` lists.
const COMMANDS: [&str; 10] =
    ["solve", "animate", "track", "workspace", "reach", "render", "serve", "bench", "completions", "man"];

/// Issue 24: `ikarus solv` said only "unrecognized subcommand": clap's suggestion (its
/// `suggestions` feature is on) was in the lines the one-line message leaves out.
#[test]
fn a_misspelt_command_or_flag_gets_a_suggestion() {
    for (args, want) in [
        (&["solv", "--goal", "2,3"][..], "ikarus: unrecognized subcommand 'solv'; did you mean 'solve'?\n"),
        (&["animat"], "ikarus: unrecognized subcommand 'animat'; did you mean 'animate'?\n"),
        (&["solve", "--gaol", "2,3"], "ikarus: unexpected argument '--gaol' found; did you mean '--goal'?\n"),
        (
            &["track", "--circle", "0,2,1", "--mod", "follow"],
            "ikarus: unexpected argument '--mod' found; did you mean '--mode'?\n",
        ),
        (&["solve", "--goal", "2,3", "--method", "lmm"], "ikarus: invalid value 'lmm' for '--method <METHOD>'"),
    ] {
        let e = fails(args, 2);
        assert!(e.starts_with(want.trim_end()), "{args:?}: {e}");
    }
    // Nothing alike: no suggestion.
    let e = fails(&["xyz"], 2);
    assert_eq!(e, "ikarus: unrecognized subcommand 'xyz'\n");
}

#[test]
fn completion_scripts_name_every_command() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let script = succeeds(&["completions", shell]);
        for command in COMMANDS {
            assert!(script.contains(command), "{shell}: no {command}");
        }
        // (fish names a flag without its dashes.)
        for flag in ["goal", "limits", "max-step-deg", "max-input-bytes"] {
            assert!(script.contains(flag), "{shell}: no {flag}");
        }
    }
    let bash = succeeds(&["completions", "bash"]);
    assert!(bash.contains("complete -F _ikarus") && bash.contains("ikarus,solve)"), "{bash}");
    assert!(succeeds(&["completions", "zsh"]).starts_with("#compdef ikarus"));
    assert!(succeeds(&["completions", "fish"]).contains("complete -c ikarus"));
    let e = fails(&["completions", "tcsh"], 2);
    assert!(e.starts_with("ikarus: invalid value 'tcsh' for '<SHELL>'"), "{e}");
    let e = fails(&["completions"], 2);
    assert!(e.contains("<SHELL>"), "{e}");
}

/// A bash completion script that bash itself reads, completing `ikarus so` to `solve`.
#[cfg(unix)]
#[test]
fn bash_completes_a_command() {
    if std::process::Command::new("bash").arg("--version").output().is_err() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("ikarus.bash");
    std::fs::write(&script, succeeds(&["completions", "bash"])).unwrap();
    let probe = format!(
        "source '{}'; COMP_WORDS=(ikarus so); COMP_CWORD=1; COMP_LINE='ikarus so'; COMP_POINT=9; \
         _ikarus ikarus so ikarus; printf '%s\\n' \"${{COMPREPLY[@]}}\"",
        script.display()
    );
    let o = std::process::Command::new("bash").args(["-c", &probe]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(String::from_utf8_lossy(&o.stdout).trim(), "solve");
}

#[test]
fn the_man_page_goes_to_stdout() {
    let page = succeeds(&["man"]);
    assert!(page.starts_with(".ie \\n(.g .ds Aq \\(aq") || page.contains("\n.TH ikarus 1"), "{page}");
    assert!(page.contains(".TH ikarus 1"), "{page}");
    assert!(page.contains(".SH NAME") && page.contains(".SH SYNOPSIS") && page.contains(".SH SUBCOMMANDS"));
    for command in COMMANDS {
        assert!(page.contains(&format!("ikarus\\-{command}(1)")), "no {command} in the main page");
    }
}

#[test]
fn the_man_pages_go_to_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("man1");
    let o = ikarus(&["man", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.is_empty() && o.stderr.is_empty(), "{} {}", stdout(&o), stderr(&o));
    let mut names: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    for page in ["ikarus.1", "ikarus-solve.1", "ikarus-render.1", "ikarus-render-rig.1", "ikarus-man.1"] {
        assert!(names.iter().any(|n| n == page), "no {page} in {names:?}");
    }
    assert!(!names.iter().any(|n| n.starts_with('.') || n.contains("help")), "{names:?}");
    let solve = std::fs::read_to_string(out.join("ikarus-solve.1")).unwrap();
    assert!(solve.contains(".TH ikarus-solve 1") && solve.contains("\\-\\-goal"), "{solve}");
    // The folder's path is a file: one line, exit 1, nothing written.
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let o = ikarus(&["man", "--out", file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.starts_with(&format!("ikarus: --out {}: cannot create the folder: ", file.display())), "{e}");
    assert_eq!(e.lines().count(), 1, "{e}");
}
