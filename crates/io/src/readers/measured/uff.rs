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

mod binary;
mod dataset58;
mod scan;
mod series;
mod units;

use super::ParseError;
pub(crate) use binary::binary58;
use dataset58::ascii58;
pub(crate) use scan::{Cursor, decode, field, is_delim, number};
pub use series::parse;
pub(crate) use units::units164;

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

#[cfg(test)]
mod tests;
