//! Tyre responses measured (hammer or shaker tests) or computed elsewhere
//! (finite elements, waveguides), read into the impulse responses LSCE
//! identifies (method §6), as for the ring tyre.
//!
//! Accepted files:
//! - CSV impulse responses `t_s, g{i}_{j}` (m/(N·s)): what
//!   `tirecontact identify --responses` writes;
//! - CSV receptances `freq_hz, h{i}_{j}_re, h{i}_{j}_im` (m/N);
//! - UFF 58 (`.uff`, `.unv`; see [`uff`]), ASCII or binary: impulse
//!   responses (function type 1 over force) or FRFs (4), displacement,
//!   velocity or acceleration over force, in the units its labels or
//!   dataset 164 give.
//!
//! An FRF `H(f)` sampled at `f_k = k Δf`, `k = 0 … K` becomes the impulse
//! response `g(t_n) = Δf Σ_{k=−K}^{K} H(f_k) e^{2πi f_k t_n}` (`H(−f) =
//! H(f)*`), by an inverse real FFT of length `N = 2K`: `t_n = n / (N Δf)`,
//! the first half kept (the second is the wrap-around of negative times).
//! The band past `K Δf` is taken as zero: keep the identification band
//! well inside the data's.
//!
//! A pair measured one way only is taken from reciprocity, `g_ij = g_ji`,
//! and the load note says so. Errors name the file, the line or record,
//! the field and what was expected.

use crate::fsio::read::{LineCap, open_regular};
use std::collections::BTreeMap;
use std::io::Read;
use std::path::Path;
use tirecontact_core::base::error::IoError;
use tirecontact_core::model::lsce::Responses;

pub mod frf;
pub mod uff;

/// Largest data file read (bytes).
pub const MAX_DATA_BYTES: u64 = 256 << 20;
/// Longest line of a data file (bytes): 5000 columns of 25 characters.
pub const MAX_LINE_BYTES: usize = 128 << 10;
/// Most points a data file may hold.
pub const MAX_POINTS: usize = 200;

/// A data file that cannot be used: the file, where in it, what is wrong
/// and what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DataError {
    /// The file cannot be read as text.
    #[error("{file}: {source}")]
    Read {
        file: String,
        #[source]
        source: ReadError,
    },
    /// A line or a record does not parse.
    #[error("{file}: {at}{message}")]
    Parse {
        file: String,
        /// "line 3: ", or empty.
        at: String,
        /// What was found and what was expected.
        message: String,
    },
    /// `tyre.nodes` names the file's nodes, and a CSV has none.
    #[error(
        "{file}: tyre.nodes is given: expected a UFF file (.uff, .unv), whose records name their nodes; a CSV's columns are the points in order"
    )]
    NodesOfCsv { file: String },
    /// The responses read are not those of the scene's points.
    #[error("{file}: {source}")]
    Responses {
        file: String,
        #[source]
        source: ResponsesError,
    },
}

/// A data file that cannot be read as text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReadError {
    /// Not found, not a regular file, not readable.
    #[error("{0}: expected a file of tyre responses (UFF 58, or CSV impulse responses or FRFs)")]
    Open(#[source] IoError),
    #[error("{0}")]
    Metadata(#[source] IoError),
    #[error(
        "more than {MAX_DATA_BYTES} bytes: expected a data file of at most {} MiB",
        MAX_DATA_BYTES >> 20
    )]
    TooLarge,
    /// A line longer than [`MAX_LINE_BYTES`], or the read failed.
    #[error("{0}: expected lines of at most {MAX_LINE_BYTES} bytes")]
    Lines(#[source] IoError),
    #[error("more than {MAX_DATA_BYTES} bytes (grown while read)")]
    Grown,
    #[error("empty: expected a header line and rows of data")]
    Empty,
    #[error("not UTF-8 text ({0}): expected a text file")]
    NotUtf8(#[source] std::str::Utf8Error),
}

/// Responses that do not make a model of the scene's points: the pair,
/// what it has and what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ResponsesError {
    #[error("no responses: expected at least one")]
    None,
    #[error("{points} points: expected at most {MAX_POINTS}")]
    TooManyPoints { points: usize },
    #[error(
        "responses of {points} points: expected the scene's {expected} points (its points map to the file's in order)"
    )]
    Points { points: usize, expected: usize },
    #[error("{}", missing_pair(*i, *j))]
    MissingPair { i: usize, j: usize },
    #[error(
        "g{i}_{j} sampled every {dt_s} s: expected every response sampled alike ({expected_s} s)"
    )]
    Sampling {
        i: usize,
        j: usize,
        dt_s: f64,
        expected_s: f64,
    },
    #[error("g{i}_{j} has {samples} samples: expected every response as long ({expected})")]
    Length {
        i: usize,
        j: usize,
        samples: usize,
        expected: usize,
    },
}

/// The message of a pair measured neither way.
fn missing_pair(i: usize, j: usize) -> String {
    let which = if i == j {
        format!("g{i}_{i}")
    } else {
        format!("neither g{i}_{j} nor g{j}_{i}")
    };
    format!(
        "no response between points {i} and {j} ({which}): expected every pair measured one way or the other (a row or a column of FRFs in a UFF file is fitted in the frequency domain by `tirecontact identify --data FILE`)"
    )
}

/// The responses read from a file, and what was done to them.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Impulse responses of the pairs `i <= j` (m/(N·s)).
    pub responses: Responses,
    /// What the reading did that the user should know (the format, pairs
    /// taken from reciprocity, units converted), one sentence each.
    pub notes: Vec<String>,
}

/// One response as read: time samples (m/(N·s)) or receptances (m/N).
#[derive(Debug, Clone, PartialEq)]
pub enum Series {
    Time {
        dt_s: f64,
        g: Vec<f64>,
    },
    Frf {
        df_hz: f64,
        re: Vec<f64>,
        im: Vec<f64>,
    },
}

/// Reads `path`; `nodes` (UFF) maps the scene's points to the file's node
/// numbers, in order (the file's nodes in increasing order when `None`);
/// `num_points` is the scene's point count, checked against the file's.
pub fn read(path: &Path, nodes: Option<&[i64]>, num_points: usize) -> Result<Measured, DataError> {
    let file = path.display().to_string();
    let fail = |(at, message): ParseError| DataError::Parse {
        file: file.clone(),
        at,
        message,
    };
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let uff = ext == "uff" || ext == "unv";
    let bytes = read_bytes(path, !uff).map_err(|source| DataError::Read {
        file: file.clone(),
        source,
    })?;
    let (series, format) = if uff {
        uff::parse(&bytes, nodes).map_err(fail)?
    } else {
        let text = String::from_utf8(bytes).map_err(|e| DataError::Read {
            file: file.clone(),
            source: ReadError::NotUtf8(e.utf8_error()),
        })?;
        if nodes.is_some() {
            return Err(DataError::NodesOfCsv { file });
        }
        (parse_csv(&text).map_err(fail)?, Vec::new())
    };
    assemble(series, num_points, format).map_err(|source| DataError::Responses { file, source })
}

/// The file's bytes, refused when it is not a regular file, too large or
/// (`text`) has a line longer than [`MAX_LINE_BYTES`]. A UFF file may
/// hold binary values (58b), whose bytes are not lines.
pub(crate) fn read_bytes(path: &Path, text: bool) -> Result<Vec<u8>, ReadError> {
    let f = open_regular(path).map_err(|e| ReadError::Open(e.into()))?;
    if f.metadata()
        .map_err(|e| ReadError::Metadata(e.into()))?
        .len()
        > MAX_DATA_BYTES
    {
        return Err(ReadError::TooLarge);
    }
    let mut bytes = Vec::new();
    if text {
        LineCap::new(f.take(MAX_DATA_BYTES + 1), MAX_LINE_BYTES).read_to_end(&mut bytes)
    } else {
        f.take(MAX_DATA_BYTES + 1).read_to_end(&mut bytes)
    }
    .map_err(|e| ReadError::Lines(e.into()))?;
    if bytes.len() as u64 > MAX_DATA_BYTES {
        return Err(ReadError::Grown);
    }
    if bytes.is_empty() {
        return Err(ReadError::Empty);
    }
    Ok(bytes)
}

/// What a CSV column holds.
enum Column {
    Impulse(usize, usize),
    Re(usize, usize),
    Im(usize, usize),
}

/// `g{i}_{j}`, `h{i}_{j}_re`, `h{i}_{j}_im`.
fn column(name: &str) -> Option<Column> {
    let pair = |s: &str| -> Option<(usize, usize)> {
        let (i, j) = s.split_once('_')?;
        Some((i.parse().ok()?, j.parse().ok()?))
    };
    if let Some(rest) = name.strip_prefix('g') {
        return pair(rest).map(|(i, j)| Column::Impulse(i, j));
    }
    let rest = name.strip_prefix('h')?;
    if let Some(p) = rest.strip_suffix("_re") {
        return pair(p).map(|(i, j)| Column::Re(i, j));
    }
    pair(rest.strip_suffix("_im")?).map(|(i, j)| Column::Im(i, j))
}

pub(crate) type ParseError = (String, String);

/// Responses by point pair `(i, j)`.
type PairSeries = BTreeMap<(usize, usize), Series>;

/// Impulse-response or FRF CSV: the first column `t_s` or `freq_hz`.
fn parse_csv(text: &str) -> Result<PairSeries, ParseError> {
    let line_err = |n: usize, m: String| (format!("line {n}: "), m);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (hn, header) = lines.next().ok_or_else(|| {
        line_err(
            1,
            "no header: expected `t_s, g0_0, …` or `freq_hz, h0_0_re, h0_0_im, …`".into(),
        )
    })?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let time = match names[0] {
        "t_s" => true,
        "freq_hz" => false,
        other => {
            return Err(line_err(
                hn,
                format!(
                    "first column `{other}`: expected `t_s` (impulse responses, m/(N·s)) or `freq_hz` (receptances, m/N)"
                ),
            ));
        }
    };
    let mut cols = Vec::with_capacity(names.len() - 1);
    for name in &names[1..] {
        let c = column(name).filter(|c| {
            matches!(
                (c, time),
                (Column::Impulse(..), true) | (Column::Re(..) | Column::Im(..), false)
            )
        });
        match c {
            Some(c) => cols.push(c),
            None => {
                return Err(line_err(
                    hn,
                    format!(
                        "column `{name}`: expected {}",
                        if time {
                            "`g{i}_{j}` (response at point i to a unit impulse at point j)"
                        } else {
                            "`h{i}_{j}_re` or `h{i}_{j}_im` (receptance at point i to a force at point j)"
                        }
                    ),
                ));
            }
        }
    }
    let mut abscissa = Vec::new();
    let mut values: Vec<Vec<f64>> = vec![Vec::new(); cols.len()];
    for (n, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(line_err(
                n,
                format!(
                    "{} values: expected {} (one per header column)",
                    cells.len(),
                    names.len()
                ),
            ));
        }
        for (c, cell) in cells.iter().enumerate() {
            let v: f64 = cell
                .parse()
                .map_err(|_| line_err(n, format!("{} = `{cell}`: expected a number", names[c])))?;
            if !v.is_finite() {
                return Err(line_err(
                    n,
                    format!("{} = {cell}: expected a finite number", names[c]),
                ));
            }
            if c == 0 {
                abscissa.push((n, v));
            } else {
                values[c - 1].push(v);
            }
        }
    }
    let step = even_step(&abscissa, names[0])?;
    let first = abscissa[0].1;
    if time && first.abs() > 1e-9 * step {
        return Err(line_err(
            abscissa[0].0,
            format!("t_s = {first}: expected the responses to start at t = 0"),
        ));
    }
    let mut out = BTreeMap::new();
    if time {
        for (c, v) in cols.iter().zip(values) {
            if let Column::Impulse(i, j) = *c {
                out.insert((i, j), Series::Time { dt_s: step, g: v });
            }
        }
        return Ok(out);
    }
    // FRFs: from f = 0 (a first row at Δf is extended down to 0 by its value)
    let k0 = (first / step).round();
    if (first - k0 * step).abs() > 1e-6 * step || k0 > 1.0 {
        return Err(line_err(
            abscissa[0].0,
            format!(
                "freq_hz = {first}: expected the FRFs to start at 0 or at the first step {step} Hz"
            ),
        ));
    }
    let mut re: BTreeMap<(usize, usize), Vec<f64>> = BTreeMap::new();
    let mut im: BTreeMap<(usize, usize), Vec<f64>> = BTreeMap::new();
    for (c, mut v) in cols.iter().zip(values) {
        if k0 == 1.0 {
            v.insert(0, v[0]);
        }
        match *c {
            Column::Re(i, j) => re.insert((i, j), v),
            Column::Im(i, j) => im.insert((i, j), v),
            Column::Impulse(..) => None,
        };
    }
    for (key, r) in re {
        let i = im.remove(&key).ok_or_else(|| {
            (
                String::new(),
                format!(
                    "h{}_{}_re has no h{}_{}_im: expected both parts of every receptance",
                    key.0, key.1, key.0, key.1
                ),
            )
        })?;
        out.insert(
            key,
            Series::Frf {
                df_hz: step,
                re: r,
                im: i,
            },
        );
    }
    if let Some((i, j)) = im.keys().next() {
        return Err((
            String::new(),
            format!("h{i}_{j}_im has no h{i}_{j}_re: expected both parts of every receptance"),
        ));
    }
    Ok(out)
}

/// The common step of increasing, evenly spaced abscissae (`what` names
/// the column): at least four rows, every spacing within 1e-3 of the
/// median one (data printed to six digits stay even); the step returned
/// is the mean.
fn even_step(x: &[(usize, f64)], what: &str) -> Result<f64, ParseError> {
    if x.len() < 4 {
        return Err((
            String::new(),
            format!("{} rows of data: expected at least 4", x.len()),
        ));
    }
    for w in x.windows(2) {
        if w[1].1.partial_cmp(&w[0].1) != Some(std::cmp::Ordering::Greater) {
            return Err((
                format!("line {}: ", w[1].0),
                format!(
                    "{what} = {} after {}: expected increasing values",
                    w[1].1, w[0].1
                ),
            ));
        }
    }
    let mut gaps: Vec<f64> = x.windows(2).map(|w| w[1].1 - w[0].1).collect();
    gaps.sort_by(f64::total_cmp);
    let median = gaps[gaps.len() / 2];
    for w in x.windows(2) {
        let d = w[1].1 - w[0].1;
        if (d - median).abs() > 1e-3 * median {
            return Err((
                format!("line {}: ", w[1].0),
                format!(
                    "{what} = {} is {d} after the row before: expected an even spacing of {median}",
                    w[1].1
                ),
            ));
        }
    }
    Ok((x[x.len() - 1].1 - x[0].1) / (x.len() - 1) as f64)
}

/// Receptance samples `H(k Δf)`, `k = 0 … K`, to the impulse response's
/// first `K` samples at `dt = 1 / (2K Δf)` (module docs).
pub fn frf_to_impulse(df_hz: f64, re: &[f64], im: &[f64]) -> (f64, Vec<f64>) {
    use rustfft::FftPlanner;
    use rustfft::num_complex::Complex;
    let k = re.len().saturating_sub(1).max(1);
    let n = 2 * k;
    let mut spec: Vec<Complex<f64>> = vec![Complex::new(0.0, 0.0); n];
    for m in 0..=k.min(re.len() - 1) {
        spec[m] = Complex::new(re[m], im[m]);
        if m > 0 && m < k {
            spec[n - m] = spec[m].conj();
        }
    }
    // the Nyquist bin of a real signal is real
    spec[k].im = 0.0;
    spec[0].im = 0.0;
    FftPlanner::new().plan_fft_inverse(n).process(&mut spec);
    let dt = 1.0 / (n as f64 * df_hz);
    (dt, spec[..k].iter().map(|c| c.re * df_hz).collect())
}

/// The series of pairs `i <= j`, each from `g_ij` or, missing, `g_ji`;
/// every pair of `num_points` points present one way or the other, all
/// of one kind and one sampling.
fn assemble(
    series: PairSeries,
    num_points: usize,
    mut notes: Vec<String>,
) -> Result<Measured, ResponsesError> {
    let p = series.keys().map(|&(i, j)| i.max(j) + 1).max().unwrap_or(0);
    if p == 0 {
        return Err(ResponsesError::None);
    }
    if p > MAX_POINTS {
        return Err(ResponsesError::TooManyPoints { points: p });
    }
    if p != num_points {
        return Err(ResponsesError::Points {
            points: p,
            expected: num_points,
        });
    }
    let mut reciprocal = Vec::new();
    let mut pairs = Vec::new();
    let mut chosen = Vec::new();
    for i in 0..p {
        for j in i..p {
            let s = match (series.get(&(i, j)), series.get(&(j, i))) {
                (Some(s), _) => s,
                (None, Some(s)) => {
                    reciprocal.push(format!("g{i}_{j}"));
                    s
                }
                (None, None) => return Err(ResponsesError::MissingPair { i, j }),
            };
            pairs.push((i, j));
            chosen.push(s);
        }
    }
    if !reciprocal.is_empty() {
        notes.push(format!(
            "taken from reciprocity (g_ij = g_ji): {}",
            reciprocal.join(", ")
        ));
    }
    let mut data = Vec::with_capacity(chosen.len());
    let mut dt = None;
    for (s, &(i, j)) in chosen.iter().zip(&pairs) {
        let (d, g) = match s {
            Series::Time { dt_s, g } => (*dt_s, g.clone()),
            Series::Frf { df_hz, re, im } => frf_to_impulse(*df_hz, re, im),
        };
        match dt {
            None => dt = Some(d),
            Some(d0) if (d - d0).abs() > 1e-9 * d0 => {
                return Err(ResponsesError::Sampling {
                    i,
                    j,
                    dt_s: d,
                    expected_s: d0,
                });
            }
            _ => {}
        }
        if let Some(first) = data.first().map(Vec::len)
            && g.len() != first
        {
            return Err(ResponsesError::Length {
                i,
                j,
                samples: g.len(),
                expected: first,
            });
        }
        data.push(g);
    }
    if chosen.iter().any(|s| matches!(s, Series::Frf { .. })) {
        notes.push(
            "FRFs made impulse responses by an inverse FFT (the band past the last frequency taken as zero)".into(),
        );
    }
    Ok(Measured {
        responses: Responses {
            dt_s: dt.unwrap_or(1.0),
            num_points: p,
            pairs,
            data,
        },
        notes,
    })
}

/// The CSV of impulse responses [`read`] reads back exactly: `t_s`, then
/// `g{i}_{j}` (m/(N·s)) for every `i, j` (mirrored from `i <= j`), every
/// number in the shortest form that parses back to itself.
pub fn impulse_csv(r: &Responses) -> String {
    use std::fmt::Write as _;
    let p = r.num_points;
    let mut col = vec![vec![None; p]; p];
    for (c, &(i, j)) in r.pairs.iter().enumerate() {
        col[i][j] = Some(c);
        if col[j][i].is_none() {
            col[j][i] = Some(c);
        }
    }
    let cols: Vec<(usize, usize, usize)> = (0..p)
        .flat_map(|i| (0..p).map(move |j| (i, j)))
        .filter_map(|(i, j)| col[i][j].map(|c| (i, j, c)))
        .collect();
    let mut s = String::from("t_s");
    for (i, j, _) in &cols {
        let _ = write!(s, ",g{i}_{j}");
    }
    s.push('\n');
    let len = r.data.first().map_or(0, Vec::len);
    for k in 0..len {
        let _ = write!(s, "{:e}", k as f64 * r.dt_s);
        for (_, _, c) in &cols {
            let _ = write!(s, ",{:e}", r.data[*c][k]);
        }
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn frfs_become_the_impulse_responses_of_the_same_model() {
        let m = crate::readers::two_mode_test_model();
        let (df, k) = (0.5, 4000); // to 2000 Hz
        let mut re = Vec::new();
        let mut im = Vec::new();
        for n in 0..=k {
            let h = m.frequency_response(0, 1, n as f64 * df);
            re.push(h.re);
            im.push(h.im);
        }
        let (dt, g) = frf_to_impulse(df, &re, &im);
        assert!((dt - 1.0 / (2.0 * k as f64 * df)).abs() < 1e-15);
        // against the closed-form impulse response, away from t = 0 where
        // the truncated band rings
        let mut worst: f64 = 0.0;
        let scale = g.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for (n, v) in g.iter().enumerate().skip(40).take(2000) {
            let exact = m.green(0, 1, n as f64 * dt).0;
            worst = worst.max((v - exact).abs());
        }
        assert!(worst < 2e-3 * scale, "worst {worst} of {scale}");
    }

    #[test]
    fn csv_errors_name_the_line_the_column_and_the_expectation() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let cases = [
            (
                "a.csv",
                "x,g0_0\n",
                "line 1: first column `x`: expected `t_s`",
            ),
            (
                "b.csv",
                "t_s,q0_0\n0,1\n",
                "column `q0_0`: expected `g{i}_{j}`",
            ),
            (
                "c.csv",
                "t_s,g0_0\n0,1\n1e-3,2\n3e-3,1\n4e-3,0\n",
                "line 4: t_s = 0.003 is 0.002 after the row before: expected an even spacing",
            ),
            (
                "d.csv",
                "t_s,g0_0\n0,1\n1e-3,NaN\n",
                "line 3: g0_0 = NaN: expected a finite number",
            ),
            (
                "e.csv",
                "t_s,g0_0\n0,1\n1e-3\n",
                "line 3: 1 values: expected 2",
            ),
            (
                "f.csv",
                "t_s,g0_0\n0,1\n1e-3,x\n",
                "line 3: g0_0 = `x`: expected a number",
            ),
            (
                "g.csv",
                "t_s,g0_0\n0,1\n",
                "1 rows of data: expected at least 4",
            ),
            ("h.csv", "", "empty: expected a header line"),
            (
                "i.csv",
                "freq_hz,h0_0_re\n0,1\n1,1\n2,1\n3,1\n",
                "h0_0_re has no h0_0_im",
            ),
            (
                "j.csv",
                "t_s,g0_0,g1_1\n0,1,1\n1,1,1\n2,1,1\n3,1,1\n",
                "no response between points 0 and 1",
            ),
            (
                "k.csv",
                "t_s,g0_0\n0,1\n2,1\n1,1\n3,1\n",
                "t_s = 1 after 2: expected increasing values",
            ),
        ];
        for (name, text, want) in cases {
            let p = write(d, name, text);
            let e = read(&p, None, 1).map(|_| ()).unwrap_err().to_string();
            let e2 = read(&p, None, 2).map(|_| ()).unwrap_err().to_string();
            assert!(
                (e.contains(want) || e2.contains(want)) && e.contains(name),
                "{name}: {e} / {e2}"
            );
        }
        // the point count of the scene
        let p = write(
            d,
            "ok.csv",
            "t_s,g0_0,g0_1,g1_1\n0,1,0,1\n1,1,0,1\n2,1,0,1\n3,1,0,1\n",
        );
        let e = read(&p, None, 3).unwrap_err().to_string();
        assert!(
            e.contains("responses of 2 points: expected the scene's 3 points"),
            "{e}"
        );
        // reciprocity said
        let m = read(&p, None, 2).unwrap();
        assert_eq!(m.responses.pairs, [(0, 0), (0, 1), (1, 1)]);
        let p = write(
            d,
            "rec.csv",
            "t_s,g0_0,g1_0,g1_1\n0,1,0,1\n1,1,0,1\n2,1,0,1\n3,1,0,1\n",
        );
        let m = read(&p, None, 2).unwrap();
        assert!(
            m.notes
                .iter()
                .any(|n| n.contains("reciprocity") && n.contains("g0_1")),
            "{:?}",
            m.notes
        );
        // not a regular file
        let e = read(d, None, 1).unwrap_err().to_string();
        assert!(e.contains("is a folder"), "{e}");
    }

    /// Files that are not regular, or never end a line, are refused with
    /// the file named: a FIFO (not waited on: the test would hang),
    /// `/dev/zero`, a folder, a 100 MB line.
    #[cfg(unix)]
    #[test]
    fn hostile_files_are_refused_at_once() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("fifo.csv");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        let line = dir.path().join("line.csv");
        std::fs::write(&line, vec![b'1'; 100 << 20]).unwrap();
        let mut cases = vec![
            (std::path::PathBuf::from("/dev/zero"), "not a regular file"),
            (dir.path().to_path_buf(), "is a folder"),
            (line, "longer than"),
        ];
        if made.is_ok_and(|s| s.success()) {
            cases.push((fifo, "not a regular file"));
        }
        for (path, want) in cases {
            let e = read(&path, None, 1).unwrap_err().to_string();
            assert!(
                e.contains(want) && e.contains(&path.display().to_string()),
                "{e}"
            );
        }
    }
}
