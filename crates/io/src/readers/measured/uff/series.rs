//! A file's usable datasets 58 (FRFs, impulse responses) made series by
//! scene point pair, in SI and as receptances.

use super::super::{PairSeries, ParseError, Series};
use super::{Record58, Units164, dof, function_name, read};
use std::collections::BTreeMap;

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
        return Err(no_dataset58(&file.skipped));
    }
    let sorted = sort_records(file.records)?;
    if sorted.usable.is_empty() {
        return Err(nothing_to_identify(&sorted));
    }
    let map = node_map(&sorted.usable, nodes)?;
    let mut notes = vec![format!(
        "UFF 58: {} records, nodes {:?} as points 0..{}",
        sorted.usable.len(),
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
    notes.extend(sorted.coherence);
    notes.extend(sorted.unused.into_iter().map(|u| format!("{u}: not used")));
    let mut conv = Conversions::default();
    let mut out = BTreeMap::new();
    for r in &sorted.usable {
        let point = |node: i64| map.iter().position(|&m| m == node);
        let (Some(i), Some(j)) = (point(r.response_node), point(r.reference_node)) else {
            if nodes.is_some() {
                continue; // a node the scene does not use
            }
            unreachable!("every node is mapped");
        };
        if out.contains_key(&(i, j)) {
            return Err((
                r.at(),
                format!(
                    "a second response of {} to {}: expected one record per pair",
                    dof(r.response_node, r.response_direction),
                    dof(r.reference_node, r.reference_direction)
                ),
            ));
        }
        out.insert((i, j), series(r, units.as_ref(), &mut conv)?);
    }
    notes.extend(conv.notes());
    Ok((out, notes))
}

/// A file with no dataset 58, naming the datasets it holds.
fn no_dataset58(skipped: &[(usize, String)]) -> ParseError {
    let skipped = record_runs(skipped);
    (
        String::new(),
        format!(
            "no dataset 58 ({}): expected function records (dataset 58 or 58b)",
            if skipped.is_empty() {
                "no datasets".to_string()
            } else {
                skipped.join(", ")
            }
        ),
    )
}

/// Records of their datasets, consecutive records of one dataset as one
/// run: `records 3 to 184 are dataset 2414` (a file of hundreds of records
/// in a few words).
pub(crate) fn record_runs(records: &[(usize, String)]) -> Vec<String> {
    let mut runs: Vec<(usize, usize, &str)> = Vec::new();
    for (k, id) in records {
        match runs.last_mut() {
            Some(last) if last.2 == id && last.1 + 1 == *k => last.1 = *k,
            _ => runs.push((*k, *k, id)),
        }
    }
    runs.into_iter()
        .map(|(a, b, id)| {
            if a == b {
                format!("record {a} is dataset {id}")
            } else {
                format!("records {a} to {b} are dataset {id}")
            }
        })
        .collect()
}

/// The datasets 58 by use: the responses to identify from, the coherences
/// shown, the rest said unused.
struct Sorted {
    usable: Vec<Record58>,
    unused: Vec<String>,
    coherence: Vec<String>,
}

/// Sorts the records; an FRF or impulse response whose numerator or
/// denominator is not a response over force is refused.
fn sort_records(records: Vec<Record58>) -> Result<Sorted, ParseError> {
    let mut sorted = Sorted {
        usable: Vec::new(),
        unused: Vec::new(),
        coherence: Vec::new(),
    };
    for r in records {
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
            sorted.usable.push(r);
        } else if matches!(r.function_type, 6 | 26) {
            let min = r.re.iter().copied().fold(f64::INFINITY, f64::min);
            let mean = r.re.iter().sum::<f64>() / r.re.len() as f64;
            sorted.coherence.push(format!(
                "{}coherence min {min:.3}, mean {mean:.3} (shown, not fitted)",
                r.at()
            ));
        } else if r.function_type == 1 {
            sorted.unused.push(format!(
                "{}a time history (function type 1 without a force denominator, record 10 type {}): a measured signal, not a response per unit force",
                r.at(),
                r.denominator
            ));
        } else {
            sorted.unused.push(format!(
                "{}{} (function type {})",
                r.at(),
                function_name(r.function_type),
                r.function_type
            ));
        }
    }
    Ok(sorted)
}

/// A file with records but none to identify from, naming what it holds.
fn nothing_to_identify(sorted: &Sorted) -> ParseError {
    (
        String::new(),
        format!(
            "no FRF nor impulse response to identify from: {}; expected dataset 58 records of function type 4 (FRF) or 1 over force (impulse response)",
            sorted
                .unused
                .iter()
                .chain(&sorted.coherence)
                .map(String::as_str)
                .collect::<Vec<_>>()
                .join("; ")
        ),
    )
}

/// The node of each point: `nodes`, each one the records have, or the
/// records' nodes in increasing order.
fn node_map(recs: &[Record58], nodes: Option<&[i64]>) -> Result<Vec<i64>, ParseError> {
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
    Ok(nodes.map_or(all, <[i64]>::to_vec))
}

/// What converting the records did: their factors to SI (each said once)
/// and whether velocities or accelerations were made displacements.
#[derive(Default)]
struct Conversions {
    factors: Vec<String>,
    velocity: bool,
    acceleration: bool,
}

impl Conversions {
    fn notes(self) -> Vec<String> {
        let mut notes = self.factors;
        if self.velocity {
            notes.push(
                "velocity over force made displacement over force (÷ iω, or integrated once)"
                    .into(),
            );
        }
        if self.acceleration {
            notes.push(
                "acceleration over force made displacement over force (÷ −ω², or integrated twice)"
                    .into(),
            );
        }
        notes
    }
}

/// A usable record as a series in SI, displacement over force.
fn series(
    r: &Record58,
    units: Option<&Units164>,
    conv: &mut Conversions,
) -> Result<Series, ParseError> {
    let (factor, how) = r.si_factor(units)?;
    let note = format!("values × {factor:.6e} to SI ({how})");
    if !conv.factors.contains(&note) {
        conv.factors.push(note);
    }
    if r.function_type == 1 {
        time_series(r, factor, conv)
    } else {
        frf_series(r, factor, conv)
    }
}

/// An impulse response from `t = 0`, integrated to displacement.
fn time_series(r: &Record58, factor: f64, conv: &mut Conversions) -> Result<Series, ParseError> {
    let at = r.at();
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
            conv.velocity = true;
            integrate(&r.re, dt)
        }
        _ => {
            conv.acceleration = true;
            integrate(&integrate(&r.re, dt), dt)
        }
    };
    let g = g.into_iter().map(|v| v * factor).collect();
    Ok(Series::Time { dt_s: dt, g })
}

/// An FRF from 0 Hz (or its first step, 0 Hz then taken as that value),
/// made a receptance.
fn frf_series(r: &Record58, factor: f64, conv: &mut Conversions) -> Result<Series, ParseError> {
    let at = r.at();
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
                conv.velocity = true;
                re[k] = b / w;
                im[k] = -a / w;
            }
            12 => {
                conv.acceleration = true;
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
    Ok(Series::Frf { df_hz: df, re, im })
}

#[cfg(test)]
mod record_run_tests {
    use super::record_runs;

    #[test]
    fn consecutive_records_of_one_dataset_are_one_run() {
        let mut list: Vec<(usize, String)> = vec![(1, "164".into()), (2, "2411".into())];
        list.extend((3..=184).map(|k| (k, "2414".to_string())));
        list.push((186, "2414".into()));
        assert_eq!(
            record_runs(&list),
            [
                "record 1 is dataset 164",
                "record 2 is dataset 2411",
                "records 3 to 184 are dataset 2414",
                "record 186 is dataset 2414"
            ]
        );
        assert!(record_runs(&[]).is_empty());
    }
}
