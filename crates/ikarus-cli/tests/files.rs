//! The files the binary reads and writes: outputs through symbolic links, to devices, keeping
//! permissions, cleaned up on SIGINT; inputs that are not regular files or are too large; and
//! the cost caps of the command line, each naming the flag that raises it.

mod common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{fails, ikarus, stderr};

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

fn batch(dir: &Path) -> String {
    let p = dir.join("goals.csv");
    std::fs::write(&p, "x,y\n2,3\n1,1\n").unwrap();
    p.to_str().unwrap().to_owned()
}

#[cfg(unix)]
#[test]
fn an_output_through_a_symlink_replaces_the_target_and_keeps_the_link() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let real_dir = dir.path().join("real");
    std::fs::create_dir(&real_dir).unwrap();
    let target = real_dir.join("summary.json");
    std::fs::write(&target, "old").unwrap();
    let link = dir.path().join("link.json");
    symlink(&target, &link).unwrap();
    let goals = batch(dir.path());

    let o = ikarus(&["solve", "--batch", &goals, "--summary-json", link.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "the link stays a link");
    let text = std::fs::read_to_string(&target).unwrap();
    assert!(text.contains("\"goals\": 2"), "the target holds the summary: {text}");
    assert_eq!(entries(&real_dir), ["summary.json"], "no temporary file beside the target");
    assert_eq!(entries(dir.path()), ["goals.csv", "link.json", "real"]);

    // A dangling link (relative, to a file not there yet) creates its target.
    let fresh = dir.path().join("fresh.svg");
    symlink("real/picture.svg", &fresh).unwrap();
    let o = ikarus(&["render", "ease", "--out", fresh.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(&fresh).unwrap().file_type().is_symlink());
    assert!(std::fs::read_to_string(real_dir.join("picture.svg")).unwrap().contains("<svg"));
}

#[cfg(unix)]
#[test]
fn a_device_is_written_through_not_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let dir = tempfile::tempdir().unwrap();
    let goals = batch(dir.path());
    // A null device of the test's own where it may make one (as root), so that a regression
    // replaces that copy and not the system's /dev/null (which the old code did, run as root);
    // otherwise /dev/null itself, which a user without root cannot replace anyway.
    let own = dir.path().join("null");
    let made = Command::new("mknod").args(["-m", "666"]).arg(&own).args(["c", "1", "3"]).stderr(Stdio::null()).status();
    let null = if made.is_ok_and(|s| s.success()) { own.clone() } else { "/dev/null".into() };
    let o = ikarus(&["solve", "--batch", &goals, "--summary-json", null.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::metadata(&null).unwrap().file_type().is_char_device(), "{} is still a device", null.display());
    let _ = std::fs::remove_file(&own);

    // A FIFO gets the bytes as written, and stays a FIFO.
    let fifo = dir.path().join("out.svg");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let o = ikarus(&["render", "ease", "--out", fifo.to_str().unwrap()]);
    if !o.status.success() {
        // Release the reader, which would wait for a writer forever.
        drop(std::fs::OpenOptions::new().write(true).open(&fifo));
    }
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = reader.join().unwrap();
    assert!(String::from_utf8(bytes).unwrap().contains("<svg"));
    assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    assert_eq!(entries(dir.path()), ["goals.csv", "out.svg"], "no temporary file left");
}

#[cfg(unix)]
#[test]
fn an_existing_file_keeps_its_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let goals = batch(dir.path());
    let private = dir.path().join("private.json");
    std::fs::write(&private, "old").unwrap();
    std::fs::set_permissions(&private, std::fs::Permissions::from_mode(0o600)).unwrap();
    let o = ikarus(&["solve", "--batch", &goals, "--summary-json", private.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&private).unwrap().contains("\"goals\": 2"));
    let mode = std::fs::metadata(&private).unwrap().permissions().mode() & 0o7777;
    assert_eq!(mode, 0o600, "a 0600 file stays 0600");

    let png = dir.path().join("e.png");
    std::fs::write(&png, "old").unwrap();
    std::fs::set_permissions(&png, std::fs::Permissions::from_mode(0o640)).unwrap();
    assert!(ikarus(&["render", "ease", "--out", png.to_str().unwrap()]).status.success());
    assert_eq!(std::fs::metadata(&png).unwrap().permissions().mode() & 0o7777, 0o640);
}

/// SIGINT or SIGTERM while a long run holds its temporary output: the temporary file is
/// removed and the exit code is 130 (143). The run is made endless on purpose (10⁹ workspace
/// samples of a seven-link arm), so that the signal always arrives during the work.
#[cfg(unix)]
#[test]
fn sigint_during_out_leaves_no_temporary_file() {
    for signal in ["-INT", "-TERM"] {
        let dir = tempfile::tempdir().unwrap();
        let arm = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/seven.toml");
        let out = dir.path().join("w.png");
        let args = ["workspace", "--limits", "--samples", "1000000000", "--max-samples", "1000000000"];
        let args = [&args[..], &["--resolution", "64", "--arm", arm.to_str().unwrap(), "--out", out.to_str().unwrap()]];
        interrupted_leaves_nothing(&args.concat(), dir.path(), signal, Until::File);
    }
}

/// When [`interrupted_leaves_nothing`] sends its signal.
#[cfg(unix)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Until {
    /// 0.3 s after the run's temporary output file appears in `dir`.
    File,
    /// As soon as the run's first bytes reach stdout (the work visibly under way); stdout is
    /// read to its end meanwhile.
    Output,
    /// A second after the run started (while it reads its input or works, before or after its
    /// file is made).
    Second,
}

/// Sends `signal` (`-INT` or `-TERM`) to a run of `args` (long on purpose, so that the signal
/// arrives during the work) at the moment `until` says. Checks the end: exit 130 (143 for
/// SIGTERM), one line on stderr, nothing in `dir`.
#[cfg(unix)]
fn interrupted_leaves_nothing(args: &[&str], dir: &Path, signal: &str, until: Until) {
    let output = if until == Until::Output { Stdio::piped() } else { Stdio::null() };
    let mut child =
        Command::new(env!("CARGO_BIN_EXE_ikarus")).args(args).stdout(output).stderr(Stdio::piped()).spawn().unwrap();
    // A hang while waiting is the failure: generous bounds.
    let started = Instant::now();
    let drain = child.stdout.take().map(|mut stdout| {
        let (tx, rx) = std::sync::mpsc::channel();
        let reader = std::thread::spawn(move || {
            let mut buf = [0u8; 1 << 16];
            let mut first = Some(tx);
            while let Ok(n @ 1..) = std::io::Read::read(&mut stdout, &mut buf) {
                if let Some(tx) = first.take() {
                    let _ = tx.send(n);
                }
            }
        });
        let first = rx.recv_timeout(Duration::from_secs(60));
        assert!(first.is_ok(), "{args:?}: nothing on stdout");
        reader
    });
    while until == Until::File && entries(dir).is_empty() {
        assert!(started.elapsed() < Duration::from_secs(60), "{args:?}: no temporary file appeared");
        std::thread::sleep(Duration::from_millis(20));
    }
    match until {
        Until::File => {
            let temp = entries(dir);
            assert!(temp[0].starts_with(".ikarus-") && temp[0].ends_with(".tmp"), "{temp:?}");
            std::thread::sleep(Duration::from_millis(300));
        }
        Until::Output => {}
        Until::Second => std::thread::sleep(Duration::from_secs(1)),
    }
    assert!(Command::new("kill").args([signal, &child.id().to_string()]).status().unwrap().success());
    let mut child = child;
    let signalled = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if signalled.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("{args:?}: the process kept running");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    if let Some(reader) = drain {
        reader.join().unwrap();
    }
    let err = stderr(&o);
    let want = if signal == "-INT" { 130 } else { 143 };
    assert_eq!(o.status.code(), Some(want), "{signal} {args:?}: {:?}, {err}", o.status);
    assert!(
        err == "ikarus: interrupted\n" || err == "ikarus: interrupted; the unfinished output file is removed\n",
        "{args:?}: {err}"
    );
    assert_eq!(entries(dir), Vec::<String>::new(), "{args:?}: no output file");
}

/// Issue 24: `ikarus solve --batch` (rows on stdout, the summary to a file) and `ikarus reach
/// --batch --out` died by the signal on SIGINT (exit −2 as Python reports it, no code) instead
/// of exiting 130. Each run here is long on purpose: a million goals on one thread; the reach
/// verdicts of 200,000 points on a seven-link limited arm.
#[cfg(unix)]
#[test]
fn sigint_during_a_batch_exits_130_and_leaves_no_file() {
    let inputs = tempfile::tempdir().unwrap();
    let out = tempfile::tempdir().unwrap();
    let summary = out.path().join("summary.json");
    // Rows on stdout only (no file was ever pending: no handler was installed before): a
    // million goals far out of reach on one thread, each solved by the Jacobian transpose to
    // its iteration limit (about a minute of work), interrupted as soon as the first rows are
    // out. (Goals near the arm, solved by LM, ended in 0.74 s on a quiet machine, before a
    // signal sent a second after the start.)
    let many = inputs.path().join("many.csv");
    let rows: String = (0..1_000_000).map(|i| format!("{},{}\n", 50.0 + f64::from(i % 1000) * 0.006, 1.5)).collect();
    std::fs::write(&many, format!("x,y\n{rows}")).unwrap();
    let batch = ["solve", "--batch", many.to_str().unwrap(), "--threads", "1", "--method", "transpose"];
    interrupted_leaves_nothing(&batch, out.path(), "-INT", Until::Output);
    // And with the summary to a file: that file is removed.
    let args = [&batch[..], &["--summary-json", summary.to_str().unwrap()]].concat();
    interrupted_leaves_nothing(&args, out.path(), "-INT", Until::File);
    let points = inputs.path().join("points.csv");
    // Two million points: about 18 s in a debug build, so that the signal (0.3 s after the
    // temporary file appears) arrives during the work; 200,000 finished first on a quiet machine
    // (the fresh-clone gate), leaving a complete file behind an exit of 130.
    let rows: String = (0..2_000_000).map(|i| format!("{},{}\n", f64::from(i % 1000) * 0.01, 1.5)).collect();
    std::fs::write(&points, format!("x,y\n{rows}")).unwrap();
    let arm = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/seven.toml");
    let csv = out.path().join("verdicts.csv");
    interrupted_leaves_nothing(
        &[
            "reach",
            "--arm",
            arm.to_str().unwrap(),
            "--limits",
            "--batch",
            points.to_str().unwrap(),
            "--out",
            csv.to_str().unwrap(),
        ],
        out.path(),
        "-INT",
        Until::Second,
    );
}

#[cfg(unix)]
#[test]
fn input_files_must_be_regular_and_within_the_cap() {
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["solve", "--arm", "/dev/zero", "--goal", "1,1"][..],
        &["solve", "--batch", "/dev/zero"],
        &["track", "--path", "/dev/zero"],
        &["workspace", "--arm", "/dev/null"],
    ] {
        let e = fails(args, 2);
        assert!(e.contains("cannot read: not a regular file"), "{args:?}: {e}");
    }
    // A FIFO would block forever once opened: refused before it is opened.
    let fifo = dir.path().join("goals.csv");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let e = fails(&["solve", "--batch", fifo.to_str().unwrap()], 2);
    assert!(e.ends_with("cannot read: not a regular file (a device, FIFO or socket); give a file\n"), "{e}");
    let e = fails(&["solve", "--arm", dir.path().to_str().unwrap(), "--goal", "1,1"], 2);
    assert!(e.ends_with("cannot read: is a directory\n"), "{e}");

    // The size cap, and the flag that raises it.
    let goals = dir.path().join("many.csv");
    let mut text = String::from("x,y\n");
    for _ in 0..200 {
        text.push_str("2,3\n");
    }
    std::fs::write(&goals, &text).unwrap();
    let path = goals.to_str().unwrap();
    let e = fails(&["solve", "--batch", path, "--max-input-bytes", "100"], 2);
    assert_eq!(
        e,
        format!(
            "ikarus: batch file {path}: larger than the cap of 100 bytes on input files (raise it with ikarus --max-input-bytes N)\n"
        )
    );
    let o = ikarus(&["--max-input-bytes", "1000", "solve", "--batch", path]);
    assert!(o.status.success(), "{}", stderr(&o));
    let arm = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/seven.toml");
    let e = fails(&["solve", "--arm", arm.to_str().unwrap(), "--goal", "1,1", "--max-input-bytes", "10"], 2);
    assert!(e.contains("larger than the cap of 10 bytes"), "{e}");
}

#[test]
fn cost_caps_name_the_flag_that_raises_them() {
    let e = fails(&["solve", "--goal", "2,3", "--restarts", "100000000"], 2);
    assert_eq!(e, "ikarus: --restarts 100000000: more than the cap of 10000 (raise it with --max-restarts N)\n");
    let o = ikarus(&["solve", "--goal", "2,3", "--restarts", "20000", "--max-restarts", "20000"]);
    assert!(o.status.success(), "raised: {}", stderr(&o));
    fails(&["animate", "--goal", "2,3", "--restarts", "10001"], 2);
    fails(&["track", "--line", "1,1,2,2", "--restarts", "10001"], 2);

    let dir = tempfile::tempdir().unwrap();
    let arm = dir.path().join("arm.toml");
    std::fs::write(&arm, "[[links]]\nlength = 1\n[[links]]\nlength = 1\n[solver]\nrestarts = 4000000000\n").unwrap();
    let arm = arm.to_str().unwrap();
    let e = fails(&["solve", "--arm", arm, "--goal", "1,1"], 2);
    assert_eq!(
        e,
        format!(
            "ikarus: arm file {arm}: [solver].restarts 4000000000: more than the cap of 10000 (raise it with --max-restarts N)\n"
        )
    );

    let e = fails(&["track", "--line", "1,1,2,2", "--samples", "1000000000"], 2);
    assert_eq!(e, "ikarus: --samples 1000000000: more than the cap of 1000000 (raise it with --max-samples N)\n");
    let path = dir.path().join("path.csv");
    std::fs::write(&path, "x,y\n2,3\n2,3.1\n2,3.2\n").unwrap();
    let e = fails(&["track", "--path", path.to_str().unwrap(), "--max-samples", "2"], 2);
    assert!(e.ends_with("3 samples, more than the cap of 2 (raise it with --max-samples N)\n"), "{e}");

    let e = fails(&["workspace", "--samples", "1000000000"], 2);
    assert_eq!(e, "ikarus: --samples 1000000000: more than the cap of 1000000 (raise it with --max-samples N)\n");
    fails(&["render", "workspace", "--samples", "20000000", "--out", "w.png"], 2);

    let e = fails(
        &["animate", "--goal", "2,3", "--frames", "100", "--width", "4096", "--height", "4096", "--out", "m.gif"],
        2,
    );
    assert!(e.contains("more than the cap of 1000000000") && e.contains("--max-gif-pixels N"), "{e}");
    assert!(!Path::new("m.gif").exists());
    let gif = dir.path().join("m.gif");
    let o = ikarus(&[
        "animate",
        "--goal",
        "2,3",
        "--frames",
        "4",
        "--width",
        "64",
        "--height",
        "64",
        "--max-gif-pixels",
        "16384",
        "--out",
        gif.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "at the cap exactly: {}", stderr(&o));
    fails(
        &["animate", "--goal", "2,3", "--frames", "5", "--width", "64", "--height", "64", "--max-gif-pixels", "16384"]
            .into_iter()
            .chain(["--out", gif.to_str().unwrap()])
            .collect::<Vec<_>>(),
        2,
    );
}

#[test]
fn solver_table_errors_name_the_arm_file_field() {
    let dir = tempfile::tempdir().unwrap();
    let arm = dir.path().join("arm.toml");
    std::fs::write(&arm, "[[links]]\nlength = 1\n[[links]]\nlength = 1\n[solver]\nrates = [1, 1, 1]\n").unwrap();
    let arm = arm.to_str().unwrap();
    let e = fails(&["solve", "--arm", arm, "--goal", "1,1"], 2);
    assert_eq!(e, format!("ikarus: arm file {arm}: [solver].rates: expected 2 values (one per joint), got 3\n"));
    // A flag is still named as the flag.
    let e = fails(&["solve", "--goal", "1,1", "--rates", "1,1"], 2);
    assert_eq!(e, "ikarus: --rates: expected 3 values (one per joint), got 2\n");
}
