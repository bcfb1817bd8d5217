//! Dataset 58b: the ID line's byte order and format, the eleven ASCII
//! header records, then the values as IEEE numbers and the closing `-1`.

use super::dataset58::{complete, header};
use super::scan::{Cursor, decode, int, is_delim};
use super::{ParseError, Record58};

/// A binary dataset 58b: `id_line` its ID line (on line `first`), the
/// cursor after it.
pub(crate) fn binary58(
    c: &mut Cursor,
    id_line: &str,
    record: usize,
    first: usize,
) -> Result<Record58, ParseError> {
    let at = format!("record {record} (dataset 58b, line {first}): ");
    let order = int(id_line, 7, 13, "byte order (ID line)", &at)?;
    let format = int(id_line, 13, 19, "floating-point format (ID line)", &at)?;
    let ascii = int(id_line, 19, 31, "ASCII lines (ID line)", &at)?;
    if !matches!(order, 1 | 2) {
        return Err((
            at,
            format!("byte order {order} (ID line): expected 1 (little endian) or 2 (big endian)"),
        ));
    }
    if format != 2 {
        return Err((
            at,
            format!("floating-point format {format} (ID line): expected 2 (IEEE 754)"),
        ));
    }
    if ascii != 11 {
        return Err((at, format!("{ascii} ASCII lines (ID line): expected 11")));
    }
    let mut head = Vec::with_capacity(11);
    for _ in 0..11 {
        let l = c.next_line().ok_or_else(|| {
            (
                at.clone(),
                "fewer than 11 header records: expected them before the binary values (truncated?)"
                    .to_string(),
            )
        })?;
        head.push(decode(l));
    }
    let head: Vec<&str> = head.iter().map(String::as_str).collect();
    let h = header(&head, &at)?;
    let complex = matches!(h.ordinate_type, 5 | 6);
    let size = if matches!(h.ordinate_type, 2 | 5) {
        4
    } else {
        8
    };
    let n = h.count * if complex { 2 } else { 1 };
    // byte offsets from the start of the file: a binary record's line
    // numbers mean nothing (its values hold newline bytes)
    let start = c.pos;
    let data = c.take(n * size).ok_or_else(|| {
        (
            at.clone(),
            format!(
                "{} bytes left after byte {start}: expected {} ({} {} values of {size} bytes, record 7; truncated?)",
                c.bytes.len() - c.pos.min(c.bytes.len()),
                n * size,
                h.count,
                if complex { "complex" } else { "real" }
            ),
        )
    })?;
    let mut vals = Vec::with_capacity(n);
    for (k, b) in data.chunks_exact(size).enumerate() {
        let v = match (size, order) {
            (4, 1) => f64::from(f32::from_le_bytes(b.try_into().expect("4 bytes"))),
            (4, _) => f64::from(f32::from_be_bytes(b.try_into().expect("4 bytes"))),
            (_, 1) => f64::from_le_bytes(b.try_into().expect("8 bytes")),
            _ => f64::from_be_bytes(b.try_into().expect("8 bytes")),
        };
        if !v.is_finite() {
            return Err((
                at,
                format!(
                    "value {k} (bytes {} to {} of the file) is {v}: expected finite numbers (byte order {order}: {}?)",
                    start + k * size,
                    start + (k + 1) * size - 1,
                    if order == 1 {
                        "little endian"
                    } else {
                        "big endian"
                    }
                ),
            ));
        }
        vals.push(v);
    }
    // the closing `-1`, right after the values or on the next line
    let end = c.pos;
    let close = c.next_line().unwrap_or(b"");
    let close = if close.trim_ascii().is_empty() {
        c.next_line().unwrap_or(b"")
    } else {
        close
    };
    if !is_delim(close) {
        return Err((
            at,
            format!(
                "`{}` after the {} bytes of values (bytes {start} to {}): expected the closing `    -1` (the values' count, type or byte order wrong?)",
                decode(close).trim(),
                n * size,
                end.saturating_sub(1)
            ),
        ));
    }
    Ok(complete(h, vals, record, first, true))
}
