//! The examples of the README and of every page of the book (`docs/src/**/*.md`), run and
//! compared with what they show, so that they cannot drift.
//!
//! The convention (also stated in the book, under "Developing", "Examples are tested"):
//!
//! - Every ```` ```console ```` block is checked unless the line just before it is
//!   `<!-- readme-test: not run (REASON) -->`. In a checked block every line starting with `$ `
//!   is a command, either `ikarus …` or `curl -s localhost:7878/…`; the lines up to the next
//!   command are its output (stdout, then stderr). A line ending in `\` continues on the next.
//! - `ikarus …` runs the binary built for the tests, from the repository root, with the
//!   arguments split as a shell would split them (single and double quotes). The commands whose
//!   output is text on a terminal (`solve`, `animate`, `track`, `workspace`, `reach`, `pose`) print JSON when
//!   piped, as here: when the command names no `--format` (and is no `--batch`), the test adds
//!   `--format text`, which is what a terminal gets.
//! - `curl -s [-o FILE] localhost:7878/PATH [-H …] [-d 'BODY']` is sent to an `ikarus serve`
//!   started for the test on a free port (GET without `-d`, POST with it). With `-o` the block
//!   shows no output, and the answer must be a picture.
//! - Comparison: `…` in the shown output matches any text (an elided part). Output that starts
//!   with `{` is JSON and is compared with all whitespace removed, so that a page may lay
//!   it out for reading; other output is compared line by line, trailing spaces ignored.
//! - Timing is the only thing allowed to differ, through [`normalise`]: a number followed by
//!   `µs` or `ms`, and the value of a JSON key ending in `_us`, `_ms` or `_s` or named
//!   `micros` or `took`, become `#` on both sides.

mod common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// Every page the examples are read from: README.md, then the book's pages in path order,
/// each as (its path from the repository's root, its text).
fn pages() -> Vec<(String, String)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut book = Vec::new();
    walk(&root().join("docs/src"), &mut book);
    book.sort();
    let root = root();
    std::iter::once(root.join("README.md"))
        .chain(book)
        .map(|path| {
            let name = path.strip_prefix(&root).unwrap().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(&path).unwrap())
        })
        .collect()
}

/// One command of a block and the output shown under it.
#[derive(Debug)]
struct Example {
    /// The page, from the repository's root.
    page: String,
    /// Line of the command in the page, from 1.
    line: usize,
    command: String,
    shown: String,
}

/// The examples of every checked console block of `page`, and the number of blocks marked not run.
fn examples(page: &str, text: &str) -> (Vec<Example>, usize) {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut skipped = 0;
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim_end() != "```console" {
            i += 1;
            continue;
        }
        let marked = i > 0 && lines[i - 1].starts_with("<!-- readme-test: not run (");
        let start = i + 1;
        let mut end = start;
        while end < lines.len() && !lines[end].starts_with("```") {
            end += 1;
        }
        if marked {
            skipped += 1;
        } else {
            let mut k = start;
            assert!(
                k < end && lines[k].starts_with("$ "),
                "{page}:{}: a console block must start with a command, or be marked not run",
                k + 1
            );
            while k < end {
                let line = k + 1;
                let mut command = lines[k][2..].to_owned();
                while command.ends_with('\\') {
                    command.pop();
                    k += 1;
                    command.push(' ');
                    command.push_str(lines[k].trim_start());
                }
                k += 1;
                let mut shown = Vec::new();
                while k < end && !lines[k].starts_with("$ ") {
                    shown.push(lines[k]);
                    k += 1;
                }
                while shown.last().is_some_and(|l| l.trim().is_empty()) {
                    shown.pop();
                }
                out.push(Example { page: page.to_owned(), line, command, shown: shown.join("\n") });
            }
        }
        i = end + 1;
    }
    (out, skipped)
}

/// Splits a command line as a shell would, for the quoting the pages use.
fn split(command: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut chars = command.chars();
    while let Some(c) = chars.next() {
        match c {
            '\'' => {
                in_word = true;
                for c in chars.by_ref() {
                    if c == '\'' {
                        break;
                    }
                    word.push(c);
                }
            }
            '"' => {
                in_word = true;
                while let Some(c) = chars.next() {
                    match c {
                        '"' => break,
                        '\\' => word.extend(chars.next()),
                        c => word.push(c),
                    }
                }
            }
            c if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            c => {
                in_word = true;
                word.push(c);
            }
        }
    }
    if in_word {
        words.push(word);
    }
    words
}

/// Timing fields become `#`: a number before ` µs`/` ms`/`µs`/`ms`, and the value of a JSON key
/// ending in `_us`, `_ms` or `_s`, or named `micros` or `took`.
fn normalise(text: &str) -> String {
    let is_num = |c: char| c.is_ascii_digit() || c == '.' || c == 'e' || c == '-' || c == '+';
    let mut out = String::with_capacity(text.len());
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        // A JSON key that holds a time: copy the key and the colon, then replace the number.
        if chars[i] == '"' {
            if let Some(len) = chars[i + 1..].iter().position(|&c| c == '"') {
                let key: String = chars[i + 1..i + 1 + len].iter().collect();
                let timed = key.ends_with("_us")
                    || key.ends_with("_ms")
                    || key.ends_with("_s")
                    || key == "micros"
                    || key == "took";
                let mut j = i + len + 2;
                while j < chars.len() && chars[j].is_whitespace() {
                    j += 1;
                }
                if timed && j < chars.len() && chars[j] == ':' {
                    j += 1;
                    while j < chars.len() && chars[j].is_whitespace() {
                        j += 1;
                    }
                    out.extend(&chars[i..j]);
                    let start = j;
                    while j < chars.len() && is_num(chars[j]) {
                        j += 1;
                    }
                    out.push_str(if j > start { "#" } else { "" });
                    i = j;
                    continue;
                }
            }
        }
        // A number with a unit of time after it.
        if chars[i].is_ascii_digit() && (i == 0 || !is_num(chars[i - 1]) || chars[i - 1] == 'e') {
            let start = i;
            let mut j = i;
            while j < chars.len() && is_num(chars[j]) {
                j += 1;
            }
            let mut k = j;
            if k < chars.len() && chars[k] == ' ' {
                k += 1;
            }
            let unit: String = chars[k..chars.len().min(k + 2)].iter().collect();
            let ends = k + 2 >= chars.len() || !chars[k + 2].is_alphanumeric();
            if (unit == "µs" || unit == "ms") && ends {
                out.push('#');
                out.extend(&chars[j..k + 2]);
                i = k + 2;
                continue;
            }
            out.extend(&chars[start..j]);
            i = j;
            continue;
        }
        out.push(chars[i]);
        i += 1;
    }
    out
}

/// Whether `text` matches `pattern`, where `…` stands for any text.
fn matches(pattern: &str, text: &str) -> bool {
    let pieces: Vec<&str> = pattern.split('…').collect();
    if pieces.len() == 1 {
        return pattern == text;
    }
    let (first, last) = (pieces[0], pieces[pieces.len() - 1]);
    if !text.starts_with(first) || !text[first.len()..].ends_with(last) || text.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &text[first.len()..text.len() - last.len()];
    for piece in &pieces[1..pieces.len() - 1] {
        match rest.find(piece) {
            Some(at) => rest = &rest[at + piece.len()..],
            None => return false,
        }
    }
    true
}

/// Whether the output `actual` is what the page shows as `shown`.
fn agrees(shown: &str, actual: &str) -> bool {
    let (shown, actual) = (normalise(shown), normalise(actual));
    if shown.trim_start().starts_with('{') {
        let squeeze = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
        matches(&squeeze(&shown), &squeeze(&actual))
    } else {
        let tidy = |s: &str| s.lines().map(str::trim_end).collect::<Vec<_>>().join("\n").trim_end().to_owned();
        matches(&tidy(&shown), &tidy(&actual))
    }
}

/// Commands whose output is text on a terminal and JSON when piped.
const TERMINAL_TEXT: [&str; 6] = ["solve", "animate", "track", "workspace", "reach", "pose"];

fn run_ikarus(args: &[String]) -> String {
    let mut args = args.to_vec();
    // A batch prints CSV wherever it goes (and takes no --format).
    let chooses = |a: &String| a == "--format" || a == "--batch";
    if args.first().is_some_and(|c| TERMINAL_TEXT.contains(&c.as_str())) && !args.iter().any(chooses) {
        args.extend(["--format".to_owned(), "text".to_owned()]);
    }
    let o = Command::new(env!("CARGO_BIN_EXE_ikarus")).args(&args).current_dir(root()).output().unwrap();
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

/// An `ikarus serve` for the curl examples, killed on drop.
struct Server {
    child: Child,
    base: String,
    agent: ureq::Agent,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Server {
    /// The examples' server, with an hour's budget: its examples are checked for what they
    /// answer, never for how fast this machine draws them.
    fn start() -> Self {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ikarus"))
            .args(["serve", "--port", "0", "--request-budget-ms", "3600000"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
        let base = line.trim().strip_prefix("ikarus serve: listening on ").unwrap().to_owned();
        let agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
        Self { child, base, agent }
    }

    /// Runs `curl` with `args`; the body of the answer, or a note on the file written by `-o`.
    fn curl(&self, args: &[String]) -> String {
        // curl's own content type for `-d`, unless `-H` gives one.
        let (mut url, mut body, mut to_file, mut content_type) =
            (None, None, false, "application/x-www-form-urlencoded".to_owned());
        let mut it = args.iter();
        while let Some(a) = it.next() {
            match a.as_str() {
                "-s" => {}
                "-o" => to_file = it.next().is_some(),
                "-H" => {
                    let header = it.next().and_then(|h| h.strip_prefix("content-type: "));
                    content_type =
                        header.unwrap_or_else(|| panic!("a -H the README test does not know: {args:?}")).to_owned();
                }
                "-d" => body = it.next().cloned(),
                u if u.starts_with("localhost:7878/") => url = Some(u.trim_start_matches("localhost:7878").to_owned()),
                other => panic!("curl: an option the README test does not know: {other}"),
            }
        }
        let url = format!("{}{}", self.base, url.expect("a URL on localhost:7878"));
        let mut response = match body {
            Some(b) => self.agent.post(url).header("Content-Type", &content_type).send(b.as_bytes()),
            None => self.agent.get(url).call(),
        }
        .unwrap();
        let bytes = response.body_mut().with_config().limit(64 << 20).read_to_vec().unwrap();
        if to_file {
            let picture = bytes.starts_with(b"\x89PNG") || bytes.starts_with(b"GIF8") || bytes.starts_with(b"<svg");
            assert!(picture, "curl -o: not a picture ({} bytes)", bytes.len());
            String::new()
        } else {
            String::from_utf8(bytes).unwrap()
        }
    }
}

#[test]
fn readme_and_book_examples_match_their_outputs() {
    let (mut examples, mut skipped) = (Vec::new(), 0);
    for (page, text) in pages() {
        let (found, marked) = self::examples(&page, &text);
        examples.extend(found);
        skipped += marked;
    }
    assert!(examples.len() >= 10, "the examples were found: {}", examples.len());
    assert!(skipped <= 4, "few blocks are exempt: {skipped}");
    let mut server: Option<Server> = None;
    let mut failures = Vec::new();
    for e in &examples {
        let words = split(&e.command);
        let actual = match words.first().map(String::as_str) {
            Some("ikarus") => run_ikarus(&words[1..]),
            Some("curl") => server.get_or_insert_with(Server::start).curl(&words[1..]),
            _ => panic!("{}:{}: `{}` is neither ikarus nor curl: mark the block not run", e.page, e.line, e.command),
        };
        if !agrees(&e.shown, &actual) {
            failures.push(format!(
                "{}:{}: $ {}\n--- shown ---\n{}\n--- actual ---\n{}",
                e.page,
                e.line,
                e.command,
                e.shown,
                actual.trim_end()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} examples drifted:\n\n{}",
        failures.len(),
        examples.len(),
        failures.join("\n\n")
    );
}

/// Every page with Rust blocks is compiled as doctests by the library
/// (`crates/ikarus/src/book.rs`, one `include_str!` per page).
#[test]
fn every_page_with_rust_blocks_is_a_doctest() {
    let book = std::fs::read_to_string(root().join("crates/ikarus/src/book.rs")).unwrap();
    let pages = pages();
    let mut missing = Vec::new();
    for (page, text) in &pages {
        if text.lines().any(|l| l.trim_end() == "```rust")
            && !book.contains(&format!("include_str!(\"../../../{page}\")"))
        {
            missing.push(page.as_str());
        }
    }
    assert!(pages.len() > 10, "the book's pages were found: {}", pages.len());
    assert!(
        missing.is_empty(),
        "pages with ```rust blocks that crates/ikarus/src/book.rs does not include: {missing:?}"
    );
}

#[test]
fn the_convention_itself() {
    assert_eq!(split(r#"a 'b c' "d\"e" f"#), ["a", "b c", "d\"e", "f"]);
    assert_eq!(normalise("status reached (34.4 µs), 12 ms, 3 items"), "status reached (# µs), # ms, 3 items");
    assert_eq!(
        normalise(r#"{"solve_us": 16.534000000000002, "wall_s":2.5, "error": 1e-7}"#),
        r#"{"solve_us": #, "wall_s":#, "error": 1e-7}"#
    );
    assert!(matches("a…c…e", "abcde") && matches("a…", "a") && !matches("a…c", "ab"));
    assert!(agrees("x (1.0 µs)\nangles …°", "x (2.5 µs)  \nangles 1°, 2°\n"));
    assert!(!agrees("error 1.2e-7", "error 6.254e-10"), "a number that drifted is caught");
    assert!(agrees("{ \"a\": [1, …] }", "{\n  \"a\": [\n    1,\n    2\n  ]\n}"));
}
