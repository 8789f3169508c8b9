//! The edge's one error: what kind of failure it is, where in the input it lies, and what is
//! wrong there.
//!
//! Every function of the edge that can fail returns [`Error`] (or, at the API's door, a
//! [`Problem`](crate::api::Problem) made from one). An error has three parts:
//!
//! - its [`ErrorKind`]: bad input, input that cannot be read, input over a cap, a request cut
//!   short, or a failure at run time. The kind picks the command line's exit code (2 for the
//!   user's input, 1 for a failure at run time) and the API's status (422, 400, 413, 503, 500);
//! - where it lies: the document it was read from (a [`source`](Error::source_label) such as
//!   `request body` or `arm`), and the [`FieldPath`] inside it (`via[2][0].x`), both optional;
//! - the message, which names the value and what is wrong with it.
//!
//! Its text ([`Display`](fmt::Display)) is `source: path: message`, each part present only
//! when known (`request body: links[0].length: invalid type: …`, `arm: links[0].length = -1: …`,
//! `--fps 0: must be positive`).
//!
//! Context is added structurally as an error travels outwards, never by editing its text: a
//! caller that checks the `i`-th element of its field `via` wraps what the element's check
//! returned with [`Error::at`] and then [`Error::in_field`] (each puts its part in front of
//! the path), and a caller that knows which document was read names it with
//! [`Error::from_source`].
//!
//! ```
//! use ikarus_edge::error::{Error, ErrorKind};
//!
//! let e = Error::input("must be a finite number, got NaN").in_field("x").at(0).in_field("goals").at(2).in_field("via");
//! assert_eq!(e.to_string(), "via[2].goals[0].x: must be a finite number, got NaN");
//! assert_eq!(e.kind(), ErrorKind::Input);
//! let e = e.from_source("request body");
//! assert_eq!(e.to_string(), "request body: via[2].goals[0].x: must be a finite number, got NaN");
//! ```

use std::borrow::Cow;
use std::fmt;

/// What kind of failure an [`Error`] is; it picks the command line's exit code and the API's
/// status.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// The user's input is wrong: a flag, a file, a field's value. Exit code 2; HTTP 422.
    Input,
    /// The input cannot be read at all: malformed JSON, a body that is not text. Exit code 2;
    /// HTTP 400.
    Malformed,
    /// The input is larger than a cap of size. Exit code 2; HTTP 413.
    TooLarge,
    /// The work was cut short: interrupted, over its time budget, or the server too busy.
    /// Exit code 1; HTTP 503.
    Unavailable,
    /// Something failed at run time: an output that cannot be written, a fault of ikarus.
    /// Exit code 1; HTTP 500 (whose answer hides the message, which may hold paths).
    Runtime,
}

impl ErrorKind {
    /// Whether the failure lies in the user's input ([`Input`](Self::Input),
    /// [`Malformed`](Self::Malformed), [`TooLarge`](Self::TooLarge)) rather than in the run.
    #[must_use]
    pub fn is_input(self) -> bool {
        match self {
            Self::Input | Self::Malformed | Self::TooLarge => true,
            Self::Unavailable | Self::Runtime => false,
        }
    }
}

/// One step of a [`FieldPath`]: a field by name, or an element of a list by its index.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Segment {
    /// A field (`links`, `x`); written after a `.` unless it starts the path.
    Field(Cow<'static, str>),
    /// The element at this index of a list; written `[i]`.
    Index(usize),
}

/// Where in a document a value lies, as the document's author wrote it: fields and indices
/// from the outside in, written `via[2].goals[0].x` (serde_path_to_error's spelling, which
/// axum's `Json` uses too). An empty path is written as nothing.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub struct FieldPath(Vec<Segment>);

impl FieldPath {
    /// The empty path (the document itself).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether the path names no field.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The steps, from the outside in.
    #[must_use]
    pub fn segments(&self) -> &[Segment] {
        &self.0
    }

    /// This path with the field `name` in front: `x` becomes `goal.x`.
    #[must_use]
    pub fn in_field(mut self, name: impl Into<Cow<'static, str>>) -> Self {
        self.0.insert(0, Segment::Field(name.into()));
        self
    }

    /// This path with the index `i` in front: `x` becomes `[3].x`.
    #[must_use]
    pub fn at(mut self, i: usize) -> Self {
        self.0.insert(0, Segment::Index(i));
        self
    }

    /// This path followed by the field `name`: `goals[0]` becomes `goals[0].x`.
    #[must_use]
    pub fn field(mut self, name: impl Into<Cow<'static, str>>) -> Self {
        self.0.push(Segment::Field(name.into()));
        self
    }

    /// This path followed by the index `i`: `goals` becomes `goals[0]`.
    #[must_use]
    pub fn index(mut self, i: usize) -> Self {
        self.0.push(Segment::Index(i));
        self
    }

    /// `inner` with this path in front of it.
    #[must_use]
    pub fn then(mut self, inner: FieldPath) -> Self {
        self.0.extend(inner.0);
        self
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, segment) in self.0.iter().enumerate() {
            match segment {
                Segment::Field(name) if k == 0 => f.write_str(name)?,
                Segment::Field(name) => write!(f, ".{name}")?,
                Segment::Index(i) => write!(f, "[{i}]")?,
            }
        }
        Ok(())
    }
}

/// A failure of the edge: its [`ErrorKind`], the document and [`FieldPath`] where it lies (each
/// optional), and a one-line message that names the value. See the [module](self) for how its
/// text is made and how context is added.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Error {
    kind: ErrorKind,
    source: Option<Cow<'static, str>>,
    path: FieldPath,
    message: String,
}

impl Error {
    /// An error of `kind` with `message` and no place yet.
    #[must_use]
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Self { kind, source: None, path: FieldPath::new(), message: message.into() }
    }

    /// The user's input is wrong ([`ErrorKind::Input`]).
    #[must_use]
    pub fn input(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Input, message)
    }

    /// The input cannot be read at all ([`ErrorKind::Malformed`]).
    #[must_use]
    pub fn malformed(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Malformed, message)
    }

    /// Something failed at run time ([`ErrorKind::Runtime`]).
    #[must_use]
    pub fn runtime(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Runtime, message)
    }

    /// This error, the value at `path` of its document (in front of any path it has).
    #[must_use]
    pub fn within(mut self, path: FieldPath) -> Self {
        self.path = path.then(std::mem::take(&mut self.path));
        self
    }

    /// This error, in the field `name` (put in front of its path: `x: …` becomes `goal.x: …`).
    #[must_use]
    pub fn in_field(mut self, name: impl Into<Cow<'static, str>>) -> Self {
        self.path = std::mem::take(&mut self.path).in_field(name);
        self
    }

    /// This error, in the element `i` of a list (put in front of its path: `x: …` becomes
    /// `[3].x: …`, and then with [`in_field`](Self::in_field)`("goals")`, `goals[3].x: …`).
    #[must_use]
    pub fn at(mut self, i: usize) -> Self {
        self.path = std::mem::take(&mut self.path).at(i);
        self
    }

    /// This error, read from the document `label` (`request body`, `arm`), which its text
    /// starts with; it replaces any document named before.
    #[must_use]
    pub fn from_source(mut self, label: impl Into<Cow<'static, str>>) -> Self {
        self.source = Some(label.into());
        self
    }

    /// This error without the name of its document.
    #[must_use]
    pub fn without_source(mut self) -> Self {
        self.source = None;
        self
    }

    /// What kind of failure it is.
    #[must_use]
    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// The document it was read from, if known (`request body`).
    #[must_use]
    pub fn source_label(&self) -> Option<&str> {
        self.source.as_deref()
    }

    /// Where in the document it lies (empty if not known, or if the message says it).
    #[must_use]
    pub fn path(&self) -> &FieldPath {
        &self.path
    }

    /// What is wrong, without the document and the path.
    #[must_use]
    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(source) = &self.source {
            write!(f, "{source}: ")?;
        }
        if !self.path.is_empty() {
            write!(f, "{}: ", self.path)?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}

/// An error equals the text it displays (`assert_eq!(e, "goal.x: must be finite")`).
impl PartialEq<str> for Error {
    fn eq(&self, text: &str) -> bool {
        /// What is left of the text once the error's parts are matched against its start.
        struct Rest<'a>(&'a str);
        impl fmt::Write for Rest<'_> {
            fn write_str(&mut self, part: &str) -> fmt::Result {
                self.0 = self.0.strip_prefix(part).ok_or(fmt::Error)?;
                Ok(())
            }
        }
        let mut rest = Rest(text);
        fmt::write(&mut rest, format_args!("{self}")).is_ok() && rest.0.is_empty()
    }
}

/// An error equals the text it displays.
impl PartialEq<&str> for Error {
    fn eq(&self, text: &&str) -> bool {
        self == *text
    }
}

/// An error equals the text it displays.
impl PartialEq<String> for Error {
    fn eq(&self, text: &String) -> bool {
        self == text.as_str()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_text_is_the_source_the_path_and_the_message() {
        assert_eq!(Error::input("bad").to_string(), "bad");
        assert_eq!(Error::input("bad").from_source("arm").to_string(), "arm: bad");
        let e = Error::input("bad").in_field("length").at(0).in_field("links");
        assert_eq!(e.to_string(), "links[0].length: bad");
        assert_eq!(e.from_source("arm").to_string(), "arm: links[0].length: bad");
        assert_eq!(Error::input("bad").at(1).at(2).to_string(), "[2][1]: bad");
    }

    #[test]
    fn within_puts_a_path_in_front() {
        let e = Error::input("bad").in_field("bone").at(0).within(FieldPath::new().field("via").index(1));
        assert_eq!(e.to_string(), "via[1][0].bone: bad");
        assert_eq!(e.path().segments().len(), 4);
    }

    #[test]
    fn the_source_is_replaced_or_dropped() {
        let e = Error::malformed("malformed JSON: x").from_source("request body");
        assert_eq!(e.clone().from_source("arm").to_string(), "arm: malformed JSON: x");
        assert_eq!(e.without_source().to_string(), "malformed JSON: x");
    }

    #[test]
    fn an_error_equals_its_text_and_nothing_else() {
        let e = Error::input("bad").in_field("x").from_source("arm");
        assert_eq!(e, "arm: x: bad");
        assert_eq!(e, "arm: x: bad".to_owned());
        assert!(e != "arm: x: ba" && e != "arm: x: bad!" && e != "");
    }

    #[test]
    fn kinds_tell_input_from_run_time() {
        assert!(ErrorKind::TooLarge.is_input());
        assert!(!Error::runtime("disk full").kind().is_input());
    }
}
