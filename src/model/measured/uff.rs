//! UFF 58 (universal file format, dataset 58: function at nodal DOF), the
//! ASCII exchange format of modal-test systems. A file is a sequence of
//! datasets, each between two lines `    -1`, the first line after the
//! opening `-1` its number. Dataset 58 has eleven header records:
//!
//! 1–5. identification text;
//! 6. `(2(I5,I10),2(1X,10A1,I10,I4))`: function type (1 time response, 4
//!    FRF), function id, version, load case, response entity and node and
//!    direction, reference entity and node and direction;
//! 7. `(3I10,3E13.5)`: ordinate type (2, 4 real; 5, 6 complex), number of
//!    values, abscissa spacing (1 even), abscissa minimum and increment, z;
//! 8. abscissa characteristics (specific data type, …);
//! 9. ordinate (numerator): `(I10,…)` specific data type (8 displacement,
//!    11 velocity, 12 acceleration);
//! 10. ordinate denominator: specific data type (13 excitation force);
//! 11. z axis;
//!
//! then the values, whitespace-separated (real, or real and imaginary
//! parts in turn). Other datasets (nodes, units, …) are skipped.
//!
//! Velocity and acceleration over force are made receptances: an FRF by
//! `H_d = H_v / (iω)` and `H_d = −H_a / ω²` (at ω = 0, the next bin's
//! value); a time response by integrating it once or twice (trapezoids
//! from rest). Values are taken as SI.

use super::{PairSeries, ParseError, Series};
use std::collections::BTreeMap;

/// A dataset 58 as read.
#[derive(Debug, Clone, PartialEq)]
pub struct Record58 {
    /// Line of its `58` (1-based).
    pub line: usize,
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
    /// 13 excitation force (0 unknown, taken as force).
    pub denominator: i64,
    pub re: Vec<f64>,
    pub im: Vec<f64>,
}

/// Fixed-width field `[a, b)` (0-based columns) of `line`, trimmed.
fn field(line: &str, a: usize, b: usize) -> &str {
    let b = b.min(line.len());
    if a >= b {
        return "";
    }
    line.get(a..b).unwrap_or("").trim()
}

fn int(line: &str, a: usize, b: usize, what: &str, n: usize) -> Result<i64, ParseError> {
    let s = field(line, a, b);
    s.parse().map_err(|_| {
        (
            format!("line {n}: "),
            format!(
                "{what} = `{s}` (columns {}-{b}): expected an integer",
                a + 1
            ),
        )
    })
}

fn real(line: &str, a: usize, b: usize, what: &str, n: usize) -> Result<f64, ParseError> {
    let s = field(line, a, b);
    let v: f64 = s.replace(['D', 'd'], "E").parse().map_err(|_| {
        (
            format!("line {n}: "),
            format!("{what} = `{s}` (columns {}-{b}): expected a number", a + 1),
        )
    })?;
    if !v.is_finite() {
        return Err((
            format!("line {n}: "),
            format!("{what} = {s}: expected a finite number"),
        ));
    }
    Ok(v)
}

/// Every dataset 58 of `text`.
pub fn records(text: &str) -> Result<Vec<Record58>, ParseError> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut k = 0;
    let is_delim = |l: &str| l.trim() == "-1";
    while k < lines.len() {
        if !is_delim(lines[k]) {
            if lines[k].trim().is_empty() {
                k += 1;
                continue;
            }
            return Err((
                format!("line {}: ", k + 1),
                format!(
                    "`{}`: expected `    -1`, the start of a dataset",
                    lines[k].trim()
                ),
            ));
        }
        let start = k + 1;
        let end = (start..lines.len()).find(|&m| is_delim(lines[m])).ok_or_else(|| {
            (
                format!("line {}: ", k + 1),
                "a dataset without its closing `    -1`: expected the file to end with it (truncated?)".to_string(),
            )
        })?;
        let id = lines.get(start).map_or("", |l| l.trim());
        if id == "58" {
            out.push(record(&lines[start..end], start + 1)?);
        }
        k = end + 1;
    }
    Ok(out)
}

/// A dataset 58 from its lines (`lines[0]` is `58`, on line `first`).
fn record(lines: &[&str], first: usize) -> Result<Record58, ParseError> {
    if lines.len() < 12 {
        return Err((
            format!("line {first}: "),
            format!(
                "dataset 58 of {} lines: expected its 11 header records and values (truncated?)",
                lines.len()
            ),
        ));
    }
    let n = |r: usize| first + r; // line number of record r (1-based records)
    let r6 = lines[6];
    let r7 = lines[7];
    let function_type = int(r6, 0, 5, "function type", n(6))?;
    let response_node = int(r6, 41, 51, "response node", n(6))?;
    let response_direction = int(r6, 51, 55, "response direction", n(6))?;
    let reference_node = int(r6, 66, 76, "reference node", n(6))?;
    let reference_direction = int(r6, 76, 80, "reference direction", n(6))?;
    let ordinate_type = int(r7, 0, 10, "ordinate data type", n(7))?;
    let count = int(r7, 10, 20, "number of values", n(7))?;
    let even = int(r7, 20, 30, "abscissa spacing", n(7))?;
    let abscissa_min = real(r7, 30, 43, "abscissa minimum", n(7))?;
    let abscissa_step = real(r7, 43, 56, "abscissa increment", n(7))?;
    let numerator = int(lines[9], 0, 10, "ordinate specific data type", n(9))?;
    let denominator = int(
        lines[10],
        0,
        10,
        "ordinate denominator specific data type",
        n(10),
    )?;
    if !matches!(function_type, 1 | 4) {
        return Err((
            format!("line {}: ", n(6)),
            format!(
                "function type {function_type}: expected 1 (time response) or 4 (frequency response function)"
            ),
        ));
    }
    if !matches!(ordinate_type, 2 | 4 | 5 | 6) {
        return Err((
            format!("line {}: ", n(7)),
            format!(
                "ordinate data type {ordinate_type}: expected 2 or 4 (real) or 5 or 6 (complex)"
            ),
        ));
    }
    if even != 1 {
        return Err((
            format!("line {}: ", n(7)),
            format!("abscissa spacing {even}: expected 1 (even spacing)"),
        ));
    }
    if abscissa_step.is_nan() || abscissa_step <= 0.0 {
        return Err((
            format!("line {}: ", n(7)),
            format!("abscissa increment {abscissa_step}: expected a positive step"),
        ));
    }
    if !matches!(numerator, 8 | 11 | 12) {
        return Err((
            format!("line {}: ", n(9)),
            format!(
                "ordinate specific data type {numerator}: expected 8 (displacement), 11 (velocity) or 12 (acceleration)"
            ),
        ));
    }
    if !matches!(denominator, 0 | 13) {
        return Err((
            format!("line {}: ", n(10)),
            format!("denominator specific data type {denominator}: expected 13 (excitation force)"),
        ));
    }
    if !(4..=10_000_000).contains(&count) {
        return Err((
            format!("line {}: ", n(7)),
            format!("{count} values: expected 4 to 10 000 000"),
        ));
    }
    let complex = matches!(ordinate_type, 5 | 6);
    let want = count as usize * if complex { 2 } else { 1 };
    let mut vals = Vec::with_capacity(want);
    for (r, l) in lines[12..].iter().enumerate() {
        for tok in l.split_whitespace() {
            let v: f64 = tok.replace(['D', 'd'], "E").parse().map_err(|_| {
                (
                    format!("line {}: ", n(12 + r)),
                    format!("value `{tok}`: expected a number"),
                )
            })?;
            if !v.is_finite() {
                return Err((
                    format!("line {}: ", n(12 + r)),
                    format!("value {tok}: expected a finite number"),
                ));
            }
            vals.push(v);
        }
    }
    if vals.len() != want {
        return Err((
            format!("line {first}: "),
            format!(
                "{} values: expected {want} ({count} {}, record 7; truncated?)",
                vals.len(),
                if complex { "complex" } else { "real" }
            ),
        ));
    }
    let (re, im) = if complex {
        (
            vals.iter().step_by(2).copied().collect(),
            vals.iter().skip(1).step_by(2).copied().collect(),
        )
    } else {
        (vals, Vec::new())
    };
    Ok(Record58 {
        line: first,
        function_type,
        response_node,
        response_direction,
        reference_node,
        reference_direction,
        ordinate_type,
        abscissa_min,
        abscissa_step,
        numerator,
        denominator,
        re,
        im,
    })
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

/// The series of `text`'s datasets 58 by scene point pair; `nodes` maps
/// point `i` to node `nodes[i]` (the file's nodes in increasing order when
/// `None`). Returns the notes of what was converted.
pub fn parse(text: &str, nodes: Option<&[i64]>) -> Result<(PairSeries, Vec<String>), ParseError> {
    let recs = records(text)?;
    if recs.is_empty() {
        return Err((
            String::new(),
            "no dataset 58: expected function records (type 58)".into(),
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
    let mut out = BTreeMap::new();
    let (mut velocity, mut acceleration) = (false, false);
    for r in &recs {
        let at = format!("line {}: ", r.line);
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
                    "a second response of node {} to node {}: expected one record per pair",
                    r.response_node, r.reference_node
                ),
            ));
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
            Series::Frf { df_hz: df, re, im }
        };
        out.insert((i, j), s);
    }
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
mod tests {
    use super::*;

    /// A dataset 58 in the standard layout.
    pub fn dataset(
        func: i64,
        resp: i64,
        refn: i64,
        ord: i64,
        min: f64,
        step: f64,
        num: i64,
        vals: &[f64],
    ) -> String {
        let complex = matches!(ord, 5 | 6);
        let count = if complex { vals.len() / 2 } else { vals.len() };
        let mut s = String::from("    -1\n    58\n");
        for k in 1..=5 {
            s.push_str(&format!("ID line {k}\n"));
        }
        s.push_str(&format!(
            "{func:>5}{:>10}{:>5}{:>10} {:<10}{resp:>10}{:>4} {:<10}{refn:>10}{:>4}\n",
            1, 0, 0, "TYRE", 3, "TYRE", 3
        ));
        s.push_str(&format!(
            "{ord:>10}{count:>10}{:>10}{min:>13.5E}{step:>13.5E}{:>13.5E}\n",
            1, 0.0
        ));
        s.push_str(&format!(
            "{:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
            18, 0, 0, 0, "Time", "s"
        ));
        s.push_str(&format!(
            "{num:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
            1, 0, 0, "Disp", "m"
        ));
        s.push_str(&format!(
            "{:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
            13, 0, 1, 0, "Force", "N"
        ));
        s.push_str(&format!(
            "{:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
            0, 0, 0, 0, "NONE", "NONE"
        ));
        for chunk in vals.chunks(4) {
            for v in chunk {
                s.push_str(&format!("{v:>20.12E}"));
            }
            s.push('\n');
        }
        s.push_str("    -1\n");
        s
    }

    #[test]
    fn records_are_read_with_their_nodes_and_values() {
        let t = dataset(1, 101, 102, 4, 0.0, 1e-3, 8, &[0.0, 1.0, 2.0, 3.0, 4.5]);
        let r = records(&t).unwrap();
        assert_eq!(r.len(), 1);
        assert_eq!((r[0].response_node, r[0].reference_node), (101, 102));
        assert_eq!(r[0].re, [0.0, 1.0, 2.0, 3.0, 4.5]);
        assert_eq!(r[0].abscissa_step, 1e-3);
    }

    #[test]
    fn errors_name_the_line_the_field_and_the_expectation() {
        let good = dataset(1, 1, 1, 4, 0.0, 1e-3, 8, &[0.0, 1.0, 2.0, 3.0]);
        let cases: Vec<(String, &str)> = vec![
            (
                dataset(2, 1, 1, 4, 0.0, 1e-3, 8, &[0.0; 4]),
                "function type 2: expected 1 (time response) or 4",
            ),
            (
                dataset(1, 1, 1, 4, 0.0, 1e-3, 9, &[0.0; 4]),
                "ordinate specific data type 9: expected 8",
            ),
            (
                dataset(1, 1, 1, 3, 0.0, 1e-3, 8, &[0.0; 4]),
                "ordinate data type 3",
            ),
            (
                good.trim_end_matches("    -1\n").to_string(),
                "without its closing",
            ),
            (
                good.replace("3.000000000000E0", "NaN"),
                "expected a finite number",
            ),
            (
                good.replace("3.000000000000E0", "x"),
                "value `x`: expected a number",
            ),
            (format!("junk\n{good}"), "line 1: `junk`: expected `    -1`"),
        ];
        for (text, want) in cases {
            let e = parse(&text, None).map(|_| ()).unwrap_err();
            let msg = format!("{}{}", e.0, e.1);
            assert!(msg.contains(want), "{msg} (wanted {want})");
        }
        // a missing value
        let short = good.replace("   3.000000000000E0", "");
        let e = parse(&short, None).map(|_| ()).unwrap_err();
        assert!(e.1.contains("3 values: expected 4"), "{e:?}");
    }

    #[test]
    fn velocity_frfs_are_made_receptances() {
        // H_d(ω) = 1 / (k - m ω²): H_v = iω H_d
        let (k, m, df) = (1e6, 1.0, 1.0);
        let n = 64;
        let mut v = Vec::new();
        for q in 0..n {
            let w = std::f64::consts::TAU * q as f64 * df;
            let hd = 1.0 / (k - m * w * w);
            v.extend([0.0, w * hd]); // iω · real
        }
        let t = dataset(4, 1, 1, 6, 0.0, df, 11, &v);
        let (s, notes) = parse(&t, None).unwrap();
        assert!(notes.iter().any(|n| n.contains("velocity")));
        let Series::Frf { re, im, .. } = &s[&(0, 0)] else {
            panic!()
        };
        for q in 1..n {
            let w = std::f64::consts::TAU * q as f64 * df;
            let hd = 1.0 / (k - m * w * w);
            assert!(
                (re[q] - hd).abs() <= 1e-12 * hd.abs().max(1e-12),
                "{q}: {} vs {hd}",
                re[q]
            );
            assert!(im[q].abs() <= 1e-12 * hd.abs());
        }
    }
}
