//! The byte reader of a `.skel` file: Spine's binary export's basic types (booleans, bytes,
//! big-endian 32-bit ints and floats, varints, strings and references into the strings table),
//! each read checked against the bytes left. Every problem is one line,
//! `skel: byte N: <what was being read>: <problem> (got V)`, the byte being where the value
//! starts.

use crate::error::Error;
use serde_json::Value;

/// A cursor over a `.skel` file's bytes, with the file's strings table once read and the path
/// of what is being read (`bones[3]`) for messages.
pub(super) struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// The strings table (`strings` after the header): what [`Reader::string_ref`] indexes.
    pub strings: Vec<String>,
    /// Where in the file's tree the reads are (`bones[3]`, `animations["walk"].bones`).
    pub at: String,
    /// The bytes of the strings [`Reader::string_ref`] has copied so far, held under
    /// [`Reader::copy_cap`]: a reference is one byte, the string it copies may be long.
    copied: usize,
}

impl<'a> Reader<'a> {
    /// A reader at the first byte of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, pos: 0, strings: Vec::new(), at: String::new(), copied: 0 }
    }

    /// The byte the next read starts at.
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// `n` bytes as they are.
    pub fn take_bytes(&mut self, n: usize, field: &str) -> Result<&'a [u8], Error> {
        self.take(n, field)
    }

    /// The bytes not read yet.
    pub fn left(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// The message of a problem with the value `field` (under [`Reader::at`]) that starts at
    /// byte `start`.
    pub fn fail_at(&self, start: usize, field: &str, problem: &str) -> Error {
        let path = match (self.at.is_empty(), field.is_empty()) {
            (true, _) => field.to_owned(),
            (false, true) => self.at.clone(),
            (false, false) => format!("{}.{field}", self.at),
        };
        Error::input(format!("skel: byte {start}: {path}: {problem}"))
    }

    /// [`Reader::fail_at`] at the current byte.
    pub fn fail(&self, field: &str, problem: &str) -> Error {
        self.fail_at(self.pos, field, problem)
    }

    fn take(&mut self, n: usize, field: &str) -> Result<&'a [u8], Error> {
        if self.left() < n {
            return Err(self.fail(field, &format!("the file ends: {n} bytes needed (got {})", self.left())));
        }
        let out = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(out)
    }

    /// One byte.
    pub fn byte(&mut self, field: &str) -> Result<u8, Error> {
        Ok(self.take(1, field)?[0])
    }

    /// A boolean: one byte, 0 or 1.
    pub fn bool(&mut self, field: &str) -> Result<bool, Error> {
        let start = self.pos;
        match self.byte(field)? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(self.fail_at(start, field, &format!("a boolean is 0 or 1 (got {b})"))),
        }
    }

    /// A 32-bit big-endian int.
    pub fn int(&mut self, field: &str) -> Result<i32, Error> {
        let b = self.take(4, field)?;
        Ok(i32::from_be_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// A 32-bit big-endian float, widened to f64 exactly; NaN and the infinities are refused.
    pub fn float(&mut self, field: &str) -> Result<f64, Error> {
        let start = self.pos;
        let b = self.take(4, field)?;
        let f = f32::from_be_bytes([b[0], b[1], b[2], b[3]]);
        if !f.is_finite() {
            return Err(self.fail_at(start, field, &format!("not a finite number (got {f})")));
        }
        Ok(f64::from(f))
    }

    /// A float as a JSON number.
    pub fn number(&mut self, field: &str) -> Result<Value, Error> {
        Ok(Value::from(self.float(field)?))
    }

    /// A varint of 1 to 5 bytes (7 bits each, low first, the high bit saying another follows);
    /// `optimize_positive` false undoes the zigzag of varint-.
    pub fn varint(&mut self, field: &str, optimize_positive: bool) -> Result<i32, Error> {
        let start = self.pos;
        let mut value: u32 = 0;
        for i in 0..5 {
            let b = self.byte(field)?;
            value |= u32::from(b & 0x7f) << (7 * i);
            if b & 0x80 == 0 {
                break;
            }
            if i == 4 {
                return Err(self.fail_at(
                    start,
                    field,
                    &format!("a varint has at most 5 bytes (got a 5th of {b:#04x})"),
                ));
            }
        }
        let value = if optimize_positive { value } else { (value >> 1) ^ (value & 1).wrapping_neg() };
        Ok(value as i32)
    }

    /// A varint+ that must be at least 0.
    pub fn unsigned(&mut self, field: &str) -> Result<usize, Error> {
        let start = self.pos;
        let v = self.varint(field, true)?;
        usize::try_from(v).map_err(|_| self.fail_at(start, field, &format!("a negative count or index (got {v})")))
    }

    /// A count of items of at least `min_bytes` each, refused beyond what the bytes left can
    /// hold (so no count makes a reader allocate more than the file's size allows).
    pub fn count(&mut self, field: &str, min_bytes: usize) -> Result<usize, Error> {
        let start = self.pos;
        let n = self.unsigned(field)?;
        if n.saturating_mul(min_bytes.max(1)) > self.left() {
            return Err(self.fail_at(
                start,
                field,
                &format!("a count beyond the {} bytes left (got {n})", self.left()),
            ));
        }
        Ok(n)
    }

    /// An index below `len` (`what` names the list, `bone` in `bone index 9 out of 4`).
    pub fn index(&mut self, field: &str, what: &str, len: usize) -> Result<usize, Error> {
        let start = self.pos;
        let i = self.unsigned(field)?;
        if i >= len {
            return Err(self.fail_at(start, field, &format!("{what} index {i} out of {len}")));
        }
        Ok(i)
    }

    /// A string: a varint+ length (0: none, 1: empty, else the byte count + 1), then UTF-8.
    pub fn string(&mut self, field: &str) -> Result<Option<String>, Error> {
        let start = self.pos;
        let n = self.unsigned(field)?;
        if n == 0 {
            return Ok(None);
        }
        let b = self.take(n - 1, field)?;
        match std::str::from_utf8(b) {
            Ok(s) => Ok(Some(s.to_owned())),
            Err(e) => Err(self.fail_at(
                start,
                field,
                &format!("not UTF-8 (got a bad byte at {})", start + 1 + e.valid_up_to()),
            )),
        }
    }

    /// A string that must be there (not the null string).
    pub fn name(&mut self, field: &str) -> Result<String, Error> {
        let start = self.pos;
        self.string(field)?.ok_or_else(|| self.fail_at(start, field, "a name is missing (got the null string)"))
    }

    /// A reference into the strings table: a varint+, 0 for none, else the index + 1.
    pub fn string_ref(&mut self, field: &str) -> Result<Option<String>, Error> {
        let start = self.pos;
        let i = self.unsigned(field)?;
        if i == 0 {
            return Ok(None);
        }
        match self.strings.get(i - 1) {
            Some(s) => {
                self.copied += s.len();
                if self.copied > self.copy_cap() {
                    let cap = self.copy_cap();
                    return Err(self.fail_at(
                        start,
                        field,
                        &format!("the strings referred to exceed {cap} bytes in all (got {})", self.copied),
                    ));
                }
                Ok(Some(s.clone()))
            }
            None => Err(self.fail_at(start, field, &format!("string index {} out of {}", i - 1, self.strings.len()))),
        }
    }

    /// The most bytes of strings the references may copy in all: 16 times the file's size
    /// and a mebibyte (Spine's own files copy less than their size).
    fn copy_cap(&self) -> usize {
        self.bytes.len().saturating_mul(16).saturating_add(1 << 20)
    }

    /// A colour stored as a 32-bit int, `rrggbbaa` in hex as JSON writes it.
    pub fn rgba(&mut self, field: &str) -> Result<String, Error> {
        Ok(format!("{:08x}", self.int(field)? as u32))
    }

    /// `n` floats.
    pub fn floats(&mut self, field: &str, n: usize) -> Result<Vec<Value>, Error> {
        if n.saturating_mul(4) > self.left() {
            return Err(self.fail(field, &format!("the file ends: {n} floats needed (got {} bytes)", self.left())));
        }
        (0..n).map(|_| self.number(field)).collect()
    }
}
