//! The FRFs of a UFF file as measured, for the frequency-domain fit
//! (method §6.5): every dataset 58 of function type 4, in the ordinate the
//! file holds (receptance, mobility or accelerance), in SI, whatever the
//! layout (a row, a column, a full or partial matrix). Nodes keep their
//! numbers and directions; a negative direction (`−Z`) is made positive by
//! negating the record.

use super::uff::{self, Record58, Units164};
use super::{DataError, MAX_POINTS, ParseError, ResponsesError, read_bytes};
use faer::c64;
use std::path::Path;
use tirecontact_core::base::error::{count, fmt_sig};
use tirecontact_core::model::lscf::{FrfSet, Ordinate};

/// A degree of freedom: a node and a direction (1 X, 2 Y, 3 Z, 4–6
/// rotations; positive).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Dof {
    pub node: i64,
    pub direction: i64,
}

impl std::fmt::Display for Dof {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&uff::dof(self.node, self.direction))
    }
}

/// What to read: the band (Hz, the file's whole band above 0 Hz when
/// `None`), the nodes kept (all when `None`) and the nodes whose response
/// direction is reversed (`--flip-direction`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FrfRequest {
    pub band_hz: Option<(f64, f64)>,
    pub nodes: Option<Vec<i64>>,
    pub flip: Vec<i64>,
}

/// The FRFs read: `set.pairs` index `dofs`, sorted by node then
/// direction.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredFrfs {
    pub set: FrfSet,
    pub dofs: Vec<Dof>,
    /// The band fitted (Hz): the first and last frequency kept.
    pub band_hz: (f64, f64),
    /// What reading did (records, units, flips, skipped records).
    pub notes: Vec<String>,
}

/// Whether a UFF file holds FRFs (dataset 58 of function type 4): the
/// frequency-domain fit reads it; otherwise the time-domain path.
pub fn holds_frfs(path: &Path) -> Result<bool, DataError> {
    let file = path.display().to_string();
    let bytes = read_bytes(path, false).map_err(|source| DataError::Read {
        file: file.clone(),
        source,
    })?;
    let f = uff::read(&bytes).map_err(|(at, message)| DataError::Parse { file, at, message })?;
    Ok(f.records.iter().any(|r| r.function_type == 4))
}

/// Reads the FRFs of the UFF file `path` (module docs).
pub fn read_frfs(path: &Path, req: &FrfRequest) -> Result<MeasuredFrfs, DataError> {
    let file = path.display().to_string();
    let bytes = read_bytes(path, false).map_err(|source| DataError::Read {
        file: file.clone(),
        source,
    })?;
    let fail = |(at, message): ParseError| DataError::Parse {
        file: file.clone(),
        at,
        message,
    };
    let parsed = uff::read(&bytes).map_err(fail)?;
    let units = parsed.units.as_ref();
    let (recs, notes) = frf_records(&parsed.records);
    if recs.is_empty() {
        return Err(fail((
            String::new(),
            "no FRF (dataset 58 of function type 4): expected FRFs for the frequency-domain fit"
                .into(),
        )));
    }
    check_nodes(&recs, req).map_err(fail)?;
    let first = recs[0];
    let pairs = frf_pairs(&recs, req, units).map_err(fail)?;
    if pairs.list.is_empty() {
        return Err(fail((
            String::new(),
            format!(
                "no FRF between the nodes {:?}: expected at least one",
                req.nodes.clone().unwrap_or_default()
            ),
        )));
    }
    let mut dofs: Vec<Dof> = pairs.list.iter().flat_map(|(a, b, _)| [*a, *b]).collect();
    dofs.sort_unstable();
    dofs.dedup();
    if dofs.len() > MAX_POINTS {
        return Err(DataError::Responses {
            file,
            source: ResponsesError::TooManyPoints { points: dofs.len() },
        });
    }
    let freqs = band(first, req).map_err(fail)?;
    let index = |d: Dof| dofs.iter().position(|&x| x == d).unwrap_or(0);
    let set = FrfSet {
        freq_hz: freqs.iter().map(|&(_, f)| f).collect(),
        ordinate: pairs.ordinate,
        pairs: pairs
            .list
            .iter()
            .map(|(a, b, _)| (index(*a), index(*b)))
            .collect(),
        h: pairs
            .list
            .iter()
            .map(|(_, _, h)| freqs.iter().map(|&(k, _)| h[k]).collect())
            .collect(),
    };
    let band_hz = (set.freq_hz[0], set.freq_hz[set.freq_hz.len() - 1]);
    let mut head = vec![format!(
        "UFF 58: {} ({}, {}) of {} over {} to {} Hz ({} frequencies)",
        count(set.pairs.len(), "FRF"),
        pairs.ordinate.name(),
        pairs.ordinate.units(),
        dofs.iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", "),
        fmt_sig(band_hz.0, 6),
        fmt_sig(band_hz.1, 6),
        set.freq_hz.len()
    )];
    let binary = recs.iter().filter(|r| r.binary).count();
    if binary > 0 {
        head.push(format!("{binary} of them binary (58b)"));
    }
    if let Some(u) = units {
        head.push(format!(
            "dataset 164 (record {}): units `{}`, length factor {}, force factor {} (file = SI × factor)",
            u.record, u.description, u.length, u.force
        ));
    }
    head.extend(pairs.notes());
    head.extend(notes);
    Ok(MeasuredFrfs {
        set,
        dofs,
        band_hz,
        notes: head,
    })
}

/// The FRFs (function type 4) among `records`, and a note of each other
/// record (coherences shown, the rest not fitted).
fn frf_records(records: &[Record58]) -> (Vec<&Record58>, Vec<String>) {
    let mut notes = Vec::new();
    let mut recs: Vec<&Record58> = Vec::new();
    for r in records {
        if r.function_type == 4 {
            recs.push(r);
        } else if matches!(r.function_type, 6 | 26) {
            let min = r.re.iter().copied().fold(f64::INFINITY, f64::min);
            notes.push(format!(
                "{}coherence min {min:.3} (shown, not fitted)",
                r.at()
            ));
        } else {
            notes.push(format!(
                "{}{} (function type {}): not fitted",
                r.at(),
                uff::function_name(r.function_type),
                r.function_type
            ));
        }
    }
    (recs, notes)
}

/// The nodes of `--nodes` and `--flip-direction`, each one the FRFs have.
fn check_nodes(recs: &[&Record58], req: &FrfRequest) -> Result<(), ParseError> {
    let all_nodes: Vec<i64> = {
        let mut v: Vec<i64> = recs
            .iter()
            .flat_map(|r| [r.response_node, r.reference_node])
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    if let Some(n) = req.nodes.iter().flatten().find(|n| !all_nodes.contains(n)) {
        return Err((
            String::new(),
            format!(
                "--nodes {n}: no FRF has this node; expected one of the file's nodes {all_nodes:?}"
            ),
        ));
    }
    // a flip reverses a response direction (the sensor's): a node that is
    // only a reference (where the force was applied) has none to reverse
    let mut responses: Vec<i64> = recs.iter().map(|r| r.response_node).collect();
    responses.sort_unstable();
    responses.dedup();
    if let Some(n) = req.flip.iter().find(|n| !responses.contains(n)) {
        let why = if all_nodes.contains(n) {
            "this node is only a reference (where the force was applied) in this file; --flip-direction reverses a response direction (a sensor mounted the other way)"
        } else {
            "no FRF has this node"
        };
        return Err((
            String::new(),
            format!(
                "--flip-direction {n}: {why}; expected one of the response nodes {responses:?}"
            ),
        ));
    }
    Ok(())
}

/// The ordinate of an FRF: from its numerator's specific data type or
/// units.
fn ordinate_of(r: &Record58) -> Result<Ordinate, ParseError> {
    match r.response_kind() {
        Some(8) => Ok(Ordinate::Receptance),
        Some(11) => Ok(Ordinate::Mobility),
        Some(12) => Ok(Ordinate::Accelerance),
        _ => Err((
            r.at(),
            format!(
                "ordinate specific data type {} (record 9) with units `{}`: expected 8 (displacement), 11 (velocity) or 12 (acceleration), or units of one of them over force",
                r.numerator,
                r.numerator_units.trim()
            ),
        )),
    }
}

/// The FRFs kept, in SI, directions positive, and what was done to them.
struct Pairs {
    ordinate: Ordinate,
    list: Vec<(Dof, Dof, Vec<c64>)>,
    /// Factors to SI, each said once.
    factors: Vec<String>,
    /// Pairs with a negative direction, made positive.
    signs: Vec<String>,
    /// Pairs reversed by `--flip-direction`.
    flipped: Vec<String>,
}

impl Pairs {
    /// The sign that makes `r`'s directions positive and applies
    /// `--flip-direction`; what it did is noted.
    fn sign(&mut self, r: &Record58, req: &FrfRequest) -> f64 {
        let mut sign = 1.0;
        if r.response_direction < 0 {
            sign = -sign;
        }
        if r.reference_direction < 0 {
            sign = -sign;
        }
        if r.response_direction < 0 || r.reference_direction < 0 {
            self.signs.push(format!(
                "{} / {}",
                uff::dof(r.response_node, r.response_direction),
                uff::dof(r.reference_node, r.reference_direction)
            ));
        }
        if req.flip.contains(&r.response_node) {
            sign = -sign;
            self.flipped.push(format!(
                "{} / {}",
                uff::dof(r.response_node, r.response_direction.abs()),
                uff::dof(r.reference_node, r.reference_direction.abs())
            ));
        }
        sign
    }

    /// The notes of what was done: factors, signs, flips.
    fn notes(self) -> Vec<String> {
        let mut notes = self.factors;
        if !self.signs.is_empty() {
            notes.push(format!(
                "negative directions made positive (values negated): {}",
                self.signs.join(", ")
            ));
        }
        if !self.flipped.is_empty() {
            notes.push(format!(
                "response direction reversed by --flip-direction (values negated): {}",
                self.flipped.join(", ")
            ));
        }
        notes
    }
}

/// The FRFs between the nodes kept, all in the first one's ordinate and
/// sampling, one per pair.
fn frf_pairs(
    recs: &[&Record58],
    req: &FrfRequest,
    units: Option<&Units164>,
) -> Result<Pairs, ParseError> {
    let keep = |n: i64| req.nodes.as_ref().is_none_or(|ns| ns.contains(&n));
    let first = recs[0];
    let mut pairs = Pairs {
        ordinate: ordinate_of(first)?,
        list: Vec::new(),
        factors: Vec::new(),
        signs: Vec::new(),
        flipped: Vec::new(),
    };
    for r in recs {
        if !(keep(r.response_node) && keep(r.reference_node)) {
            continue;
        }
        check_like_first(r, first, pairs.ordinate)?;
        let (factor, how) = r.si_factor(units)?;
        let note = format!("values × {factor:.6e} to SI ({how})");
        if !pairs.factors.contains(&note) {
            pairs.factors.push(note);
        }
        let sign = pairs.sign(r, req);
        let resp = Dof {
            node: r.response_node,
            direction: r.response_direction.abs(),
        };
        let refd = Dof {
            node: r.reference_node,
            direction: r.reference_direction.abs(),
        };
        if pairs.list.iter().any(|(a, b, _)| (*a, *b) == (resp, refd)) {
            return Err((
                r.at(),
                format!("a second FRF of {resp} to {refd}: expected one record per pair"),
            ));
        }
        let h =
            r.re.iter()
                .zip(&r.im)
                .map(|(a, b)| c64::new(a * factor * sign, b * factor * sign))
                .collect();
        pairs.list.push((resp, refd, h));
    }
    Ok(pairs)
}

/// An FRF over force, complex, in the ordinate `ordinate` and sampled as
/// `first`.
fn check_like_first(r: &Record58, first: &Record58, ordinate: Ordinate) -> Result<(), ParseError> {
    let o = ordinate_of(r)?;
    if o != ordinate {
        return Err((
            r.at(),
            format!(
                "{}: expected every FRF in one ordinate ({}, as {})",
                o.name(),
                ordinate.name(),
                first.at().trim_end_matches(": ")
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
    if r.im.is_empty() {
        return Err((
            r.at(),
            "a real FRF: expected complex values (ordinate type 5 or 6)".into(),
        ));
    }
    let same = (r.abscissa_min - first.abscissa_min).abs() <= 1e-9 * first.abscissa_step
        && (r.abscissa_step - first.abscissa_step).abs() <= 1e-9 * first.abscissa_step
        && r.re.len() == first.re.len();
    if !same {
        return Err((
            r.at(),
            format!(
                "{} values from {} Hz every {} Hz: expected every FRF sampled as {} ({} values from {} Hz every {} Hz)",
                r.re.len(),
                r.abscissa_min,
                r.abscissa_step,
                first.at().trim_end_matches(": "),
                first.re.len(),
                first.abscissa_min,
                first.abscissa_step
            ),
        ));
    }
    Ok(())
}

/// The frequencies fitted (index, Hz): above 0 and within the request, at
/// least 8 of them.
fn band(first: &Record58, req: &FrfRequest) -> Result<Vec<(usize, f64)>, ParseError> {
    let (lo, hi) = req.band_hz.unwrap_or((0.0, f64::INFINITY));
    let freqs: Vec<(usize, f64)> = (0..first.re.len())
        .map(|k| (k, first.abscissa_min + k as f64 * first.abscissa_step))
        .filter(|&(_, f)| {
            f > 0.0 && f >= lo - 1e-9 * first.abscissa_step && f <= hi + 1e-9 * first.abscissa_step
        })
        .collect();
    if freqs.len() < 8 {
        let top = first.abscissa_min + (first.re.len() as f64 - 1.0) * first.abscissa_step;
        return Err((
            String::new(),
            format!(
                "{} holds {} of the FRFs' frequencies above 0 Hz ({} to {top} Hz every {} Hz): expected at least 8",
                match req.band_hz {
                    Some((lo, hi)) => format!("--band-hz {lo} {hi}"),
                    None => "the file".to_string(),
                },
                freqs.len(),
                first.abscissa_min,
                first.abscissa_step
            ),
        ));
    }
    Ok(freqs)
}
