//! Names from files (bones, animations, constraints, slots) as every message and text table
//! prints them: quoted and escaped as Rust's `{:?}` writes a string (a line break as `\n`, an
//! escape character as `\u{1b}`), so that a name can neither split a one-line error nor drive
//! the terminal, and cut to its first [`SHOWN_CHARS`] characters when longer, with its size, so
//! that a 30 MB name does not make a 30 MB message.

use std::fmt;

/// The most characters of a name a message shows.
pub const SHOWN_CHARS: usize = 64;

/// `name` quoted for a message: `"front-foot"`, `"two\nlines"`, or for a long one
/// `"aaaa…" (30000000 bytes)`. Formats as [`quoted`]'s text without allocating, with `{}` or
/// `{:?}` alike (so that a message's `{:?}` of a name becomes `{:?}` of `Quoted(name)`).
#[derive(Clone, Copy)]
pub struct Quoted<'a>(pub &'a str);

impl fmt::Debug for Quoted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

/// `names` as table cells ([`cell`]: bare when plain, else quoted) joined by `, `, or `none`
/// when there are none; at most
/// [`LISTED`] of them, then `… (N in all)`.
#[must_use]
pub fn listed<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
    let mut out = String::new();
    let mut count = 0;
    for name in names {
        if count < LISTED {
            if count > 0 {
                out.push_str(", ");
            }
            out.push_str(&cell(name));
        }
        count += 1;
    }
    match count {
        0 => "none".to_owned(),
        n if n > LISTED => format!("{out}, … ({n} in all)"),
        _ => out,
    }
}

/// The most names [`listed`] shows.
pub const LISTED: usize = 50;

impl fmt::Display for Quoted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = self.0;
        match name.char_indices().nth(SHOWN_CHARS) {
            None => write!(f, "{name:?}"),
            Some((cut, _)) => {
                let shown = format!("{:?}", &name[..cut]);
                write!(f, "{}…\" ({} bytes)", &shown[..shown.len() - 1], name.len())
            }
        }
    }
}

/// `name` quoted for a message ([`Quoted`]).
#[must_use]
pub fn quoted(name: &str) -> String {
    Quoted(name).to_string()
}

/// `name` for a column of a text table: as it is when it holds nothing to escape and is short,
/// else [`quoted`] (so that the table keeps one line per row).
#[must_use]
pub fn cell(name: &str) -> std::borrow::Cow<'_, str> {
    let plain = name.chars().count() <= SHOWN_CHARS
        && !name.chars().any(|c| c.is_control() || c == '"' || c == '\\' || c.is_whitespace() && c != ' ');
    if plain { name.into() } else { quoted(name).into() }
}

/// A number for a message: as Rust prints it below 10¹⁵ in size, else in scientific notation
/// (`2.4e19`, not twenty digits).
#[must_use]
pub fn count_text(n: f64) -> String {
    if n.abs() < 1e15 { format!("{n}") } else { format!("{n:e}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_quoted_escaped_and_cut() {
        assert_eq!(quoted("hip"), "\"hip\"");
        assert_eq!(quoted("a\nb\u{1b}[2J"), "\"a\\nb\\u{1b}[2J\"");
        let long = "é".repeat(100);
        assert_eq!(quoted(&long), format!("\"{}…\" (200 bytes)", "é".repeat(64)));
        assert_eq!(quoted(&"a".repeat(64)), format!("\"{}\"", "a".repeat(64)));
        assert_eq!(cell("front-foot"), "front-foot");
        assert_eq!(cell("left hand"), "left hand");
        assert_eq!(cell("a\nb"), "\"a\\nb\"");
        assert_eq!(cell(&"a".repeat(65)), format!("\"{}…\" (65 bytes)", "a".repeat(64)));
        assert_eq!(format!("{:?}", Quoted("a\nb")), "\"a\\nb\"");
        assert_eq!(listed(["walk", "run\n"]), "walk, \"run\\n\"");
        assert_eq!(listed([]), "none");
        let many: Vec<String> = (0..60).map(|k| k.to_string()).collect();
        assert!(listed(many.iter().map(String::as_str)).ends_with(", 49, … (60 in all)"));
    }
}
