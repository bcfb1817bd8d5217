//! Dataset 58 in ASCII: its eleven header records (shared with the binary
//! variant) and its values, whitespace-separated or in fixed-width fields.

use super::scan::{field, int, number, real};
use super::{ParseError, Record58};

/// The eleven header records of a dataset 58 (`head[0]` is record 1).
pub(super) struct Header {
    function_type: i64,
    response_node: i64,
    response_direction: i64,
    reference_node: i64,
    reference_direction: i64,
    pub(super) ordinate_type: i64,
    pub(super) count: usize,
    abscissa_min: f64,
    abscissa_step: f64,
    numerator: i64,
    numerator_units: String,
    denominator: i64,
    denominator_units: String,
    id1: String,
}

pub(super) fn header(head: &[&str], at: &str) -> Result<Header, ParseError> {
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

pub(super) fn complete(
    h: Header,
    vals: Vec<f64>,
    record: usize,
    line: usize,
    binary: bool,
) -> Record58 {
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
pub(super) fn ascii58(lines: &[&str], record: usize, first: usize) -> Result<Record58, ParseError> {
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
