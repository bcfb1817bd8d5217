//! UFF (universal file format) as modal-test systems and FE programs write
//! it: a sequence of datasets, each between two lines `    -1`, the first
//! line after the opening `-1` its number. Read here: dataset 58
//! (function at nodal DOF), ASCII or binary (`58b`), and dataset 164
//! (units); others are skipped. Dataset 58 has eleven header records:
//!
//! 1–5. identification text;
//! 6. `(2(I5,I10),2(1X,10A1,I10,I4))`: function type (1 time response, 4
//!    FRF, 6 coherence, …), function id, version, load case, response
//!    entity and node and direction, reference entity and node and
//!    direction (1 X, 2 Y, 3 Z, 4–6 rotations, negative for −);
//! 7. `(3I10,3E13.5)`: ordinate data type (2 real single, 4 real double,
//!    5 complex single, 6 complex double), number of values, abscissa
//!    spacing (1 even), abscissa minimum and increment, z;
//! 8. abscissa: `(I10,3I5,2(1X,20A1))` specific data type, length, force
//!    and temperature exponents, axis label, units label;
//! 9. ordinate numerator, same layout: specific data type 8 displacement,
//!    11 velocity, 12 acceleration;
//! 10. ordinate denominator: specific data type 13 excitation force;
//! 11. z axis;
//!
//! then the values, whitespace-separated or in fixed-width fields (13
//! characters single, 20 double): real, or real and imaginary parts in
//! turn. A binary `58b` has the ID line
//! `(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12)` — `58`, `b`, byte order (1
//! little endian, 2 big endian), floating-point format (2 IEEE 754),
//! ASCII lines (11), bytes following — and the values as 4-byte (types 2,
//! 5) or 8-byte (4, 6) IEEE numbers right after the eleventh line. The
//! byte count is taken from record 7 (some writers put half the complex
//! count in the ID line); an end of line before the closing `-1` is
//! allowed.
//!
//! Text fields are UTF-8 or, failing that, Latin-1 (`µ`, `°` of older
//! exports).
//!
//! Units: a record's units labels (`m`, `mm/s`, `g`, `m/s^2`, `N`, `lbf`,
//! …, products and quotients read left to right as in `(1/N)*(m/s²)`)
//! give the factor to SI when they are set; a label that cannot be
//! read is refused, naming it. Labels left blank or `NONE` take the
//! factors of dataset 164 (record 2: length, force and temperature
//! factors, file units = SI × factor) when the file has one, and SI
//! otherwise; the notes say which factor was applied.
//!
//! Function types used: FRFs (4) and impulse responses (1 over force).
//! Coherence (6, 26) is recognised and reported, not fitted; time
//! histories (1 without a force denominator) and other functions (spectra,
//! correlations, …) are not used for identification, and a file with
//! nothing else is refused saying so.
//!
//! Velocity and acceleration over force are made receptances: an FRF by
//! `H_d = H_v / (iω)` and `H_d = −H_a / ω²` (at ω = 0, the next bin's
//! value); a time response by integrating it once or twice (trapezoids
//! from rest).

use super::{PairSeries, ParseError, Series};
use std::collections::BTreeMap;

/// A dataset 58 as read, values in the file's units (see
/// [`Record58::si_factor`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Record58 {
    /// Its place among the file's datasets (1-based, every dataset
    /// counted).
    pub record: usize,
    /// Line of its `58` (1-based).
    pub line: usize,
    /// Whether it was a binary `58b`.
    pub binary: bool,
    /// Identification record 1 (decoded as UTF-8 or Latin-1).
    pub id1: String,
    pub function_type: i64,
    pub response_node: i64,
    pub response_direction: i64,
    pub reference_node: i64,
    pub reference_direction: i64,
    /// 2, 4 real; 5, 6 complex.
    pub ordinate_type: i64,
    pub abscissa_min: f64,
    pub abscissa_step: f64,
    /// 8 displacement, 11 velocity, 12 acceleration.
    pub numerator: i64,
    /// Units label of the numerator (record 9).
    pub numerator_units: String,
    /// 13 excitation force (0 unknown, taken as force).
    pub denominator: i64,
    /// Units label of the denominator (record 10).
    pub denominator_units: String,
    pub re: Vec<f64>,
    pub im: Vec<f64>,
}

/// Dataset 164: the file's units, `file value = SI value × factor`.
#[derive(Debug, Clone, PartialEq)]
pub struct Units164 {
    /// Its place among the file's datasets (1-based).
    pub record: usize,
    pub code: i64,
    pub description: String,
    pub length: f64,
    pub force: f64,
    pub temperature: f64,
}

/// What a file holds: its datasets 58, its units (164) and the datasets
/// skipped (place, number).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct UffFile {
    pub records: Vec<Record58>,
    pub units: Option<Units164>,
    pub skipped: Vec<(usize, String)>,
}

/// A node and direction as messages name them: `node 101 +Z`.
pub fn dof(node: i64, direction: i64) -> String {
    let axis = match direction.abs() {
        1 => "X",
        2 => "Y",
        3 => "Z",
        4 => "RX",
        5 => "RY",
        6 => "RZ",
        _ => "",
    };
    match (axis, direction < 0) {
        ("", _) => format!("node {node}"),
        (a, false) => format!("node {node} +{a}"),
        (a, true) => format!("node {node} -{a}"),
    }
}

/// Function type's name (UFF 58 record 6 field 1).
pub fn function_name(function_type: i64) -> &'static str {
    match function_type {
        0 => "general function",
        1 => "time response",
        2 => "auto spectrum",
        3 => "cross spectrum",
        4 => "frequency response function",
        5 => "transmissibility",
        6 => "coherence",
        7 => "auto correlation",
        8 => "cross correlation",
        9 => "power spectral density",
        10 => "energy spectral density",
        11 => "probability density function",
        12 => "spectrum",
        18 => "mode indicator function",
        26 => "multiple coherence",
        _ => "function",
    }
}

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

    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let b = self.bytes.get(self.pos..self.pos.checked_add(n)?)?;
        self.pos += n;
        self.line += b.iter().filter(|&&c| c == b'\n').count();
        Some(b)
    }
}

pub(crate) fn is_delim(l: &[u8]) -> bool {
    l.trim_ascii() == b"-1"
}

/// Every dataset 58 of the file's bytes.
pub fn records(bytes: &[u8]) -> Result<Vec<Record58>, ParseError> {
    Ok(read(bytes)?.records)
}

/// The datasets 58 and 164 of the file's bytes.
pub fn read(bytes: &[u8]) -> Result<UffFile, ParseError> {
    let mut c = Cursor {
        bytes,
        pos: 0,
        line: 0,
    };
    let mut out = UffFile::default();
    let mut place = 0;
    while let Some(l) = c.next_line() {
        if l.trim_ascii().is_empty() {
            continue;
        }
        if !is_delim(l) {
            return Err((
                format!("line {}: ", c.line),
                format!(
                    "`{}`: expected `    -1`, the start of a dataset",
                    decode(l).trim()
                ),
            ));
        }
        let open = c.line;
        place += 1;
        let truncated = || {
            (
                format!("line {open}: "),
                format!(
                    "dataset {place}: no closing `    -1`: expected the file to end with it (truncated?)"
                ),
            )
        };
        let id_line = decode(c.next_line().ok_or_else(truncated)?);
        let first = c.line;
        let id = field(&id_line, 0, 6);
        let binary = id_line.chars().nth(6) == Some('b');
        if id == "58" && binary {
            out.records.push(binary58(&mut c, &id_line, place, first)?);
            continue;
        }
        let mut body = Vec::new();
        loop {
            let l = c.next_line().ok_or_else(truncated)?;
            if is_delim(l) {
                break;
            }
            body.push(decode(l));
        }
        let lines: Vec<&str> = body.iter().map(String::as_str).collect();
        match id.as_str() {
            "58" => out.records.push(ascii58(&lines, place, first)?),
            "164" => {
                let u = units164(&lines, place, first)?;
                if out.units.is_none() {
                    out.units = Some(u);
                }
            }
            _ => out.skipped.push((place, id)),
        }
    }
    Ok(out)
}

/// Dataset 164 from its records.
pub(crate) fn units164(
    lines: &[&str],
    record: usize,
    first: usize,
) -> Result<Units164, ParseError> {
    let at = format!("record {record} (dataset 164, line {first}): ");
    if lines.len() < 2 {
        return Err((
            at,
            format!(
                "{} lines: expected the units code and the three factors (truncated?)",
                lines.len()
            ),
        ));
    }
    let code = int(lines[0], 0, 10, "units code", &at)?;
    let description = field(lines[0], 10, 30);
    let f: Vec<f64> = lines[1].split_whitespace().filter_map(number).collect();
    if f.len() < 3 || f[..3].iter().any(|v| !v.is_finite() || *v <= 0.0) {
        return Err((
            at,
            format!(
                "factors `{}`: expected three positive numbers (length, force, temperature)",
                lines[1].trim()
            ),
        ));
    }
    Ok(Units164 {
        record,
        code,
        description,
        length: f[0],
        force: f[1],
        temperature: f[2],
    })
}

/// The eleven header records of a dataset 58 (`head[0]` is record 1).
struct Header {
    function_type: i64,
    response_node: i64,
    response_direction: i64,
    reference_node: i64,
    reference_direction: i64,
    ordinate_type: i64,
    count: usize,
    abscissa_min: f64,
    abscissa_step: f64,
    numerator: i64,
    numerator_units: String,
    denominator: i64,
    denominator_units: String,
    id1: String,
}

fn header(head: &[&str], at: &str) -> Result<Header, ParseError> {
    let r6 = head[5];
    let r7 = head[6];
    let function_type = int(r6, 0, 5, "function type (record 6)", at)?;
    let response_node = int(r6, 41, 51, "response node (record 6)", at)?;
    let response_direction = int(r6, 51, 55, "response direction (record 6)", at)?;
    let reference_node = int(r6, 66, 76, "reference node (record 6)", at)?;
    let reference_direction = int(r6, 76, 80, "reference direction (record 6)", at)?;
    let ordinate_type = int(r7, 0, 10, "ordinate data type (record 7)", at)?;
    let count = int(r7, 10, 20, "number of values (record 7)", at)?;
    let even = int(r7, 20, 30, "abscissa spacing (record 7)", at)?;
    let abscissa_min = real(r7, 30, 43, "abscissa minimum (record 7)", at)?;
    let abscissa_step = real(r7, 43, 56, "abscissa increment (record 7)", at)?;
    let numerator = int(head[8], 0, 10, "ordinate specific data type (record 9)", at)?;
    let denominator = int(
        head[9],
        0,
        10,
        "ordinate denominator specific data type (record 10)",
        at,
    )?;
    let fail = |m: String| Err((at.to_string(), m));
    if !matches!(ordinate_type, 2 | 4 | 5 | 6) {
        return fail(format!(
            "ordinate data type {ordinate_type} (record 7): expected 2 or 4 (real) or 5 or 6 (complex)"
        ));
    }
    if even != 1 {
        return fail(format!(
            "abscissa spacing {even} (record 7): expected 1 (even spacing)"
        ));
    }
    if abscissa_step.is_nan() || abscissa_step <= 0.0 {
        return fail(format!(
            "abscissa increment {abscissa_step} (record 7): expected a positive step"
        ));
    }
    if !(4..=10_000_000).contains(&count) {
        return fail(format!(
            "{count} values (record 7): expected 4 to 10 000 000"
        ));
    }
    Ok(Header {
        function_type,
        response_node,
        response_direction,
        reference_node,
        reference_direction,
        ordinate_type,
        count: count as usize,
        abscissa_min,
        abscissa_step,
        numerator,
        numerator_units: field(head[8], 47, 67),
        denominator,
        denominator_units: field(head[9], 47, 67),
        id1: head[0].trim_end().to_string(),
    })
}

fn complete(h: Header, vals: Vec<f64>, record: usize, line: usize, binary: bool) -> Record58 {
    let complex = matches!(h.ordinate_type, 5 | 6);
    let (re, im) = if complex {
        (
            vals.iter().step_by(2).copied().collect(),
            vals.iter().skip(1).step_by(2).copied().collect(),
        )
    } else {
        (vals, Vec::new())
    };
    Record58 {
        record,
        line,
        binary,
        id1: h.id1,
        function_type: h.function_type,
        response_node: h.response_node,
        response_direction: h.response_direction,
        reference_node: h.reference_node,
        reference_direction: h.reference_direction,
        ordinate_type: h.ordinate_type,
        abscissa_min: h.abscissa_min,
        abscissa_step: h.abscissa_step,
        numerator: h.numerator,
        numerator_units: h.numerator_units,
        denominator: h.denominator,
        denominator_units: h.denominator_units,
        re,
        im,
    }
}

/// An ASCII dataset 58 from its lines (`lines[0]` is record 1; the `58`
/// is on line `first`).
fn ascii58(lines: &[&str], record: usize, first: usize) -> Result<Record58, ParseError> {
    let at = format!("record {record} (dataset 58, line {first}): ");
    if lines.len() < 11 {
        return Err((
            at,
            format!(
                "{} lines: expected its 11 header records and values (truncated?)",
                lines.len()
            ),
        ));
    }
    let h = header(&lines[..11], &at)?;
    let complex = matches!(h.ordinate_type, 5 | 6);
    let want = h.count * if complex { 2 } else { 1 };
    let width = if matches!(h.ordinate_type, 2 | 5) {
        13
    } else {
        20
    };
    let mut vals = Vec::with_capacity(want);
    for (r, l) in lines[11..].iter().enumerate() {
        let lat = format!("record {record} (dataset 58), line {}: ", first + 12 + r);
        let toks: Vec<&str> = l.split_whitespace().collect();
        // fixed-width fields may touch (`-1.0E+00-2.0E+00`)
        let fixed: Vec<String>;
        let toks: Vec<&str> = if toks.iter().all(|t| number(t).is_some()) {
            toks
        } else {
            let chars: Vec<char> = l.trim_end().chars().collect();
            fixed = chars
                .chunks(width)
                .map(|c| c.iter().collect::<String>().trim().to_string())
                .collect();
            fixed.iter().map(String::as_str).collect()
        };
        for tok in toks {
            let v = number(tok)
                .ok_or_else(|| (lat.clone(), format!("value `{tok}`: expected a number")))?;
            if !v.is_finite() {
                return Err((lat, format!("value {tok}: expected a finite number")));
            }
            vals.push(v);
        }
    }
    if vals.len() != want {
        return Err((
            at,
            format!(
                "{} values: expected {want} ({} {}, record 7; truncated?)",
                vals.len(),
                h.count,
                if complex { "complex" } else { "real" }
            ),
        ));
    }
    Ok(complete(h, vals, record, first, false))
}

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
    let data = c.take(n * size).ok_or_else(|| {
        (
            at.clone(),
            format!(
                "{} bytes left: expected {} ({} {} values of {size} bytes, record 7; truncated?)",
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
                    "value {k} is {v}: expected finite numbers (byte order {order}: {}?)",
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
                "`{}` after the {} bytes of values: expected the closing `    -1` (the values' count, type or byte order wrong?)",
                decode(close).trim(),
                n * size
            ),
        ));
    }
    Ok(complete(h, vals, record, first, true))
}

/// Length (L), time (T) and force (F) exponents and the factor to SI.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Dim {
    l: i32,
    t: i32,
    f: i32,
    to_si: f64,
}

/// The factor to SI of a units label and its dimension, `None` when the
/// label is blank or `NONE`.
fn units_label(label: &str) -> Option<Result<Dim, String>> {
    let s: String = label
        .chars()
        .filter(|c| !c.is_whitespace() && *c != '(' && *c != ')')
        .collect::<String>()
        .replace('²', "^2")
        .replace('³', "^3")
        .replace("**", "^");
    if s.is_empty() || s.eq_ignore_ascii_case("none") || s == "-" {
        return None;
    }
    let mut d = Dim {
        l: 0,
        t: 0,
        f: 0,
        to_si: 1.0,
    };
    // `a/b*c` read left to right: `(a/b)·c`
    let mut toks = Vec::new();
    let mut sign = 1;
    let mut cur = String::new();
    for ch in s.chars() {
        if ch == '/' || ch == '*' {
            toks.push((sign, std::mem::take(&mut cur)));
            sign = if ch == '/' { -1 } else { 1 };
        } else {
            cur.push(ch);
        }
    }
    toks.push((sign, cur));
    for (k, (sign, tok)) in toks.iter().enumerate() {
        let (sign, tok) = (*sign, tok.as_str());
        let (base, exp) = match tok.split_once('^') {
            Some((b, e)) => (b, e.parse::<i32>().ok()),
            None => {
                // `s2`, `m2`: trailing digit as exponent
                let digits = tok.trim_start_matches(|c: char| !c.is_ascii_digit());
                if !digits.is_empty() && digits.len() < tok.len() {
                    (&tok[..tok.len() - digits.len()], digits.parse().ok())
                } else {
                    (tok, Some(1))
                }
            }
        };
        let Some(exp) = exp else {
            return Some(Err(format!("`{label}`: exponent of `{tok}` not read")));
        };
        let (l, t, f, factor) = match base {
            "m" => (1, 0, 0, 1.0),
            "mm" => (1, 0, 0, 1e-3),
            "cm" => (1, 0, 0, 1e-2),
            "um" | "µm" | "μm" | "micron" => (1, 0, 0, 1e-6),
            "in" | "inch" => (1, 0, 0, 0.0254),
            "ft" => (1, 0, 0, 0.3048),
            "s" | "sec" => (0, 1, 0, 1.0),
            "ms" => (0, 1, 0, 1e-3),
            "N" => (0, 0, 1, 1.0),
            "kN" => (0, 0, 1, 1e3),
            "lbf" | "lb" => (0, 0, 1, 4.448_221_615_260_5),
            "g" | "G" => (1, -2, 0, 9.806_65),
            "" | "1" if k == 0 => (0, 0, 0, 1.0), // `1/s`
            _ => {
                return Some(Err(format!(
                    "`{label}`: unit `{base}` not known (m, mm, cm, µm, in, ft, s, ms, N, kN, lbf, g)"
                )));
            }
        };
        let e = sign * exp;
        d.l += l * e;
        d.t += t * e;
        d.f += f * e;
        d.to_si *= f64::powi(factor, e);
    }
    Some(Ok(d))
}

/// The dimension of a specific data type (records 9, 10).
fn data_dim(specific: i64) -> Option<(i32, i32, i32, &'static str)> {
    match specific {
        8 => Some((1, 0, 0, "displacement")),
        11 => Some((1, -1, 0, "velocity")),
        12 => Some((1, -2, 0, "acceleration")),
        9 | 13 => Some((0, 0, 1, "force")),
        _ => None,
    }
}

impl Record58 {
    /// Where messages place it.
    pub fn at(&self) -> String {
        format!(
            "record {} (dataset 58{}, line {}), {} / {}: ",
            self.record,
            if self.binary { "b" } else { "" },
            self.line,
            dof(self.response_node, self.response_direction),
            dof(self.reference_node, self.reference_direction)
        )
    }

    /// The response of the numerator: 8 displacement, 11 velocity, 12
    /// acceleration, from its specific data type (record 9) or — a general
    /// type (0 unknown, 1 general) — from its units label's dimension
    /// (`m/s^2`, or the whole ratio `(1/N)*(m/s²)`); `None` when neither
    /// says.
    pub fn response_kind(&self) -> Option<i64> {
        if matches!(self.numerator, 8 | 11 | 12) {
            return Some(self.numerator);
        }
        if !matches!(self.numerator, 0 | 1) {
            return None;
        }
        let Some(Ok(d)) = units_label(&self.numerator_units) else {
            return None;
        };
        match (d.l, d.t, d.f) {
            (1, 0, 0 | -1) => Some(8),
            (1, -1, 0 | -1) => Some(11),
            (1, -2, 0 | -1) => Some(12),
            _ => None,
        }
    }

    /// The factor that makes its values SI (numerator over denominator)
    /// and how it was found: the units labels when set, else dataset 164
    /// (`units`), else 1.
    pub fn si_factor(&self, units: Option<&Units164>) -> Result<(f64, String), ParseError> {
        let mut factor = 1.0;
        let mut how = Vec::new();
        for (specific, label, what) in [
            (
                self.response_kind().unwrap_or(self.numerator),
                &self.numerator_units,
                "numerator",
            ),
            (self.denominator, &self.denominator_units, "denominator"),
        ] {
            let zero_force = what == "denominator" && specific == 0;
            let Some((l, t, f, name)) =
                data_dim(specific).or(zero_force.then_some((0, 0, 1, "force")))
            else {
                continue;
            };
            let sign = if what == "numerator" { 1 } else { -1 };
            let to_si = match units_label(label) {
                Some(Ok(d)) if what == "numerator" && (d.l, d.t, d.f) == (l, t, f - 1) => {
                    // the whole ratio in the numerator's label
                    how.push(format!("{what} `{label}` (over force)"));
                    factor *= d.to_si;
                    break;
                }
                Some(Ok(d)) => {
                    if (d.l, d.t, d.f) != (l, t, f) {
                        return Err((
                            self.at(),
                            format!(
                                "{what} units `{label}` for {name} (specific data type {specific}): expected units of {name}"
                            ),
                        ));
                    }
                    how.push(format!("{what} `{label}`"));
                    d.to_si
                }
                Some(Err(m)) => {
                    return Err((
                        self.at(),
                        format!("{what} units {m}: expected a units label that can be read"),
                    ));
                }
                None => match units {
                    Some(u) => {
                        how.push(format!("{what} by dataset 164 ({})", u.description));
                        if f == 1 {
                            1.0 / u.force
                        } else {
                            1.0 / u.length
                        }
                    }
                    None => 1.0,
                },
            };
            factor *= if sign > 0 { to_si } else { 1.0 / to_si };
        }
        let how = if how.is_empty() {
            "no units labels nor dataset 164: taken as SI".to_string()
        } else {
            how.join(", ")
        };
        Ok((factor, how))
    }
}

/// Trapezoidal integral of `y` (step `dt`) from rest.
fn integrate(y: &[f64], dt: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(y.len());
    let mut acc = 0.0;
    for (k, v) in y.iter().enumerate() {
        if k > 0 {
            acc += 0.5 * dt * (y[k - 1] + v);
        }
        out.push(acc);
    }
    out
}

/// The series of the file's usable datasets 58 (FRFs, impulse responses)
/// by scene point pair, in SI; `nodes` maps point `i` to node `nodes[i]`
/// (the file's nodes in increasing order when `None`). Returns the notes
/// of what was read, skipped and converted.
pub fn parse(bytes: &[u8], nodes: Option<&[i64]>) -> Result<(PairSeries, Vec<String>), ParseError> {
    let file = read(bytes)?;
    let units = file.units.clone();
    let binary = file.records.iter().filter(|r| r.binary).count();
    if file.records.is_empty() {
        let skipped: Vec<String> = file
            .skipped
            .iter()
            .map(|(k, id)| format!("record {k} is dataset {id}"))
            .collect();
        return Err((
            String::new(),
            format!(
                "no dataset 58 ({}): expected function records (dataset 58 or 58b)",
                if skipped.is_empty() {
                    "no datasets".to_string()
                } else {
                    skipped.join(", ")
                }
            ),
        ));
    }
    let mut unused = Vec::new();
    let mut coherence = Vec::new();
    let mut recs = Vec::new();
    for r in file.records {
        let impulse = r.function_type == 1 && matches!(r.denominator, 9 | 13);
        if r.function_type == 4 || impulse {
            if !matches!(r.numerator, 8 | 11 | 12) {
                return Err((
                    r.at(),
                    format!(
                        "ordinate specific data type {} (record 9): expected 8 (displacement), 11 (velocity) or 12 (acceleration)",
                        r.numerator
                    ),
                ));
            }
            if !matches!(r.denominator, 0 | 9 | 13) {
                return Err((
                    r.at(),
                    format!(
                        "denominator specific data type {} (record 10): expected 13 (excitation force)",
                        r.denominator
                    ),
                ));
            }
            recs.push(r);
        } else if matches!(r.function_type, 6 | 26) {
            let min = r.re.iter().copied().fold(f64::INFINITY, f64::min);
            let mean = r.re.iter().sum::<f64>() / r.re.len() as f64;
            coherence.push(format!(
                "{}coherence min {min:.3}, mean {mean:.3} (shown, not fitted)",
                r.at()
            ));
        } else if r.function_type == 1 {
            unused.push(format!(
                "{}a time history (function type 1 without a force denominator, record 10 type {}): a measured signal, not a response per unit force",
                r.at(),
                r.denominator
            ));
        } else {
            unused.push(format!(
                "{}{} (function type {})",
                r.at(),
                function_name(r.function_type),
                r.function_type
            ));
        }
    }
    if recs.is_empty() {
        return Err((
            String::new(),
            format!(
                "no FRF nor impulse response to identify from: {}; expected dataset 58 records of function type 4 (FRF) or 1 over force (impulse response)",
                unused
                    .iter()
                    .chain(&coherence)
                    .map(String::as_str)
                    .collect::<Vec<_>>()
                    .join("; ")
            ),
        ));
    }
    let all: Vec<i64> = {
        let mut v: Vec<i64> = recs
            .iter()
            .flat_map(|r| [r.response_node, r.reference_node])
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    if let Some(ns) = nodes
        && let Some((k, n)) = ns.iter().enumerate().find(|(_, n)| !all.contains(n))
    {
        return Err((
            String::new(),
            format!(
                "tyre.nodes[{k}] = {n}: no record has this node; expected one of the file's nodes {all:?}"
            ),
        ));
    }
    let map: Vec<i64> = nodes.map_or(all.clone(), <[i64]>::to_vec);
    let mut notes = vec![format!(
        "UFF 58: {} records, nodes {:?} as points 0..{}",
        recs.len(),
        map,
        map.len()
    )];
    if binary > 0 {
        notes.push(format!("{binary} of them binary (58b)"));
    }
    if let Some(u) = &units {
        notes.push(format!(
            "dataset 164 (record {}): units {} `{}`, length factor {}, force factor {} (file = SI × factor)",
            u.record, u.code, u.description, u.length, u.force
        ));
    }
    notes.extend(coherence);
    notes.extend(unused.into_iter().map(|u| format!("{u}: not used")));
    let mut factors: Vec<String> = Vec::new();
    let mut out = BTreeMap::new();
    let (mut velocity, mut acceleration) = (false, false);
    for r in &recs {
        let at = r.at();
        let point = |node: i64| map.iter().position(|&m| m == node);
        let (Some(i), Some(j)) = (point(r.response_node), point(r.reference_node)) else {
            if nodes.is_some() {
                continue; // a node the scene does not use
            }
            unreachable!("every node is mapped");
        };
        if out.contains_key(&(i, j)) {
            return Err((
                at,
                format!(
                    "a second response of {} to {}: expected one record per pair",
                    dof(r.response_node, r.response_direction),
                    dof(r.reference_node, r.reference_direction)
                ),
            ));
        }
        let (factor, how) = r.si_factor(units.as_ref())?;
        let note = format!("values × {factor:.6e} to SI ({how})");
        if !factors.contains(&note) {
            factors.push(note);
        }
        let s = if r.function_type == 1 {
            if !r.im.is_empty() {
                return Err((at, "a complex time response: expected real values".into()));
            }
            if r.abscissa_min.abs() > 1e-9 * r.abscissa_step {
                return Err((
                    at,
                    format!("time response from t = {}: expected t = 0", r.abscissa_min),
                ));
            }
            let dt = r.abscissa_step;
            let g = match r.numerator {
                8 => r.re.clone(),
                11 => {
                    velocity = true;
                    integrate(&r.re, dt)
                }
                _ => {
                    acceleration = true;
                    integrate(&integrate(&r.re, dt), dt)
                }
            };
            let g = g.into_iter().map(|v| v * factor).collect();
            Series::Time { dt_s: dt, g }
        } else {
            if r.im.is_empty() {
                return Err((
                    at,
                    "a real FRF: expected complex values (ordinate type 5 or 6)".into(),
                ));
            }
            let df = r.abscissa_step;
            let k0 = (r.abscissa_min / df).round();
            if (r.abscissa_min - k0 * df).abs() > 1e-6 * df || k0 > 1.0 {
                return Err((
                    at,
                    format!(
                        "FRF from {} Hz: expected it to start at 0 or at the first step {df} Hz",
                        r.abscissa_min
                    ),
                ));
            }
            let (mut re, mut im) = (r.re.clone(), r.im.clone());
            if k0 == 1.0 {
                re.insert(0, re[0]);
                im.insert(0, im[0]);
            }
            // to receptance: H_d = H_v / (iω) = -i H_v / ω; H_d = -H_a / ω²
            for k in 1..re.len() {
                let w = std::f64::consts::TAU * k as f64 * df;
                let (a, b) = (re[k], im[k]);
                match r.numerator {
                    11 => {
                        velocity = true;
                        re[k] = b / w;
                        im[k] = -a / w;
                    }
                    12 => {
                        acceleration = true;
                        re[k] = -a / (w * w);
                        im[k] = -b / (w * w);
                    }
                    _ => {}
                }
            }
            if r.numerator != 8 && re.len() > 1 {
                re[0] = re[1];
                im[0] = 0.0;
            }
            re.iter_mut()
                .chain(im.iter_mut())
                .for_each(|v| *v *= factor);
            Series::Frf { df_hz: df, re, im }
        };
        out.insert((i, j), s);
    }
    notes.extend(factors);
    if velocity {
        notes.push(
            "velocity over force made displacement over force (÷ iω, or integrated once)".into(),
        );
    }
    if acceleration {
        notes.push(
            "acceleration over force made displacement over force (÷ −ω², or integrated twice)"
                .into(),
        );
    }
    Ok((out, notes))
}

#[cfg(test)]
mod tests;
