//! The scanner under every dataset: lines of the file's bytes counted as
//! they are read, text decoded as UTF-8 or Latin-1, fixed-width fields read
//! as integers or numbers with the columns named in messages.

use super::ParseError;

/// A text line, UTF-8 or else Latin-1, without its line end.
pub(crate) fn decode(bytes: &[u8]) -> String {
    let b = bytes.strip_suffix(b"\r").unwrap_or(bytes);
    match std::str::from_utf8(b) {
        Ok(s) => s.to_string(),
        Err(_) => b.iter().map(|&c| char::from(c)).collect(),
    }
}

/// Fixed-width field `[a, b)` (0-based character columns) of `line`,
/// trimmed.
pub(crate) fn field(line: &str, a: usize, b: usize) -> String {
    line.chars()
        .skip(a)
        .take(b.saturating_sub(a))
        .collect::<String>()
        .trim()
        .to_string()
}

pub(crate) fn int(line: &str, a: usize, b: usize, what: &str, at: &str) -> Result<i64, ParseError> {
    let s = field(line, a, b);
    s.parse().map_err(|_| {
        (
            at.to_string(),
            format!(
                "{what} = `{s}` (columns {}-{b}): expected an integer",
                a + 1
            ),
        )
    })
}

pub(crate) fn number(s: &str) -> Option<f64> {
    s.replace(['D', 'd'], "E").parse().ok()
}

pub(crate) fn real(
    line: &str,
    a: usize,
    b: usize,
    what: &str,
    at: &str,
) -> Result<f64, ParseError> {
    let s = field(line, a, b);
    let v = number(&s).ok_or_else(|| {
        (
            at.to_string(),
            format!("{what} = `{s}` (columns {}-{b}): expected a number", a + 1),
        )
    })?;
    if !v.is_finite() {
        return Err((
            at.to_string(),
            format!("{what} = {s}: expected a finite number"),
        ));
    }
    Ok(v)
}

/// A cursor over the file's bytes that counts lines.
pub(crate) struct Cursor<'a> {
    pub(crate) bytes: &'a [u8],
    pub(crate) pos: usize,
    /// 1-based line of `pos`.
    pub(crate) line: usize,
}

impl<'a> Cursor<'a> {
    /// The next line (without its end), or `None` at the end.
    pub(crate) fn next_line(&mut self) -> Option<&'a [u8]> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let rest = &self.bytes[self.pos..];
        let n = rest.iter().position(|&c| c == b'\n');
        let (l, step) = match n {
            Some(n) => (&rest[..n], n + 1),
            None => (rest, rest.len()),
        };
        self.pos += step;
        self.line += 1;
        Some(l)
    }

    /// The next `n` bytes, lines counted; `None` past the end.
    pub(super) fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let b = self.bytes.get(self.pos..self.pos.checked_add(n)?)?;
        self.pos += n;
        self.line += b.iter().filter(|&&c| c == b'\n').count();
        Some(b)
    }
}

pub(crate) fn is_delim(l: &[u8]) -> bool {
    l.trim_ascii() == b"-1"
}
