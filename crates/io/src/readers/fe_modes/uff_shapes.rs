//! Normal modes as finite-element programs export them in UFF: mode shapes
//! as data at nodes (dataset 55 or 2414), node coordinates (15 or 2411)
//! and units (164). Field positions follow the UFF dataset descriptions
//! (the SDRC/I-DEAS universal file specification, as pyuff writes and
//! reads them):
//!
//! - **55** (data at nodes): records 1–5 ID lines; record 6 `(6I10)` model
//!   type, analysis type (2 normal mode), data characteristic (2 three
//!   translations, 3 six: translations and rotations), specific data type
//!   (8 displacement), data type (2 real single, 4 real double; 5, 6
//!   complex single, double: see below), values per
//!   node `NDV`; for a normal mode record 7 `(8I10)` the number of integer
//!   values (2) and of real values (4), load case, mode number, and record
//!   8 `(6E13.5)` frequency (Hz), modal mass, modal viscous damping ratio,
//!   modal hysteretic damping ratio; then per node record 9 `(I10)` the
//!   node number and record 10 `(6E13.5)` its `NDV` values (X, Y, Z, then
//!   RX, RY, RZ).
//! - **2414** (analysis data): record 1 label, 2 name, 3 dataset location
//!   (1 data at nodes), 4–8 ID lines, 9 `(6I10)` model type, analysis type
//!   (2 normal mode), data characteristic, result type (8 displacement),
//!   data type (2, 4 real; 5, 6 complex), values per node `NVALDC`; 10 `(8I10)`
//!   integers 1–8 (the sixth the mode number), 11 `(8I10)` integers 9–10,
//!   12 `(6E13.5)` reals 1–6: time, frequency (Hz), eigenvalue, modal
//!   mass, viscous damping ratio, hysteretic damping ratio; 13 reals 7–12;
//!   then per node record 14 `(I10)` the node and record 15 its values.
//! - **15** (nodes): per node `(4I10,1P3E13.5)` label, definition and
//!   displacement coordinate systems, colour, X, Y, Z.
//! - **2411** (nodes, double precision): per node record 1 `(4I10)` label,
//!   export and displacement coordinate systems, colour; record 2
//!   `(1P3D25.16)` X, Y, Z.
//! - **2420** (coordinate systems) and the displacement coordinate system
//!   of each node: see [`coordinate_systems`]; displacements are turned to
//!   the part system once the whole file is read.
//! - **164** (units): read by [`crate::readers::measured::uff`]; `file value
//!   = SI value × factor` for length and force; time is in seconds, so the
//!   mass unit's factor is `force / length`.
//!
//! Complex data (types 5, 6) give each value as a real and an imaginary
//! part. Finite-element programs write real normal modes so (NX: imaginary
//! parts 0): such a record is read as a real normal mode when every
//! imaginary part is at most [`MAX_IMAGINARY_RATIO`] of the mode's largest
//! real part, and refused naming the mode and the ratio otherwise.
//!
//! Normal-mode records of other results (stresses, strain energy, …) or
//! on elements are skipped and listed, as are other analyses.
//!
//! Numbers are read whitespace-separated (`D` exponents accepted), a
//! node's values possibly over several lines. Other datasets are skipped
//! and listed; binary 58b records are stepped over.

use crate::readers::measured::uff::{self, Cursor, Units164};
use std::collections::BTreeMap;

pub mod coordinate_systems;

pub use coordinate_systems::{CoordinateSystem, CsKind, NodeSystems};

/// A refusal: where (record, dataset, line) and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UffShapesError {
    /// A dataset that does not parse.
    #[error("record {record} (dataset {dataset}, line {line}): {message}")]
    Record {
        /// Its place among the file's datasets (1-based).
        record: usize,
        dataset: String,
        /// 1-based line of the problem.
        line: usize,
        message: String,
    },
    /// The file is not a sequence of datasets.
    #[error("line {line}: {message}")]
    Layout { line: usize, message: String },
}

/// One normal mode as read, in the file's units.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeRecord {
    /// Its place among the file's datasets (1-based).
    pub record: usize,
    /// Line of its dataset number (1-based).
    pub line: usize,
    /// 55 or 2414.
    pub dataset: u32,
    pub mode_number: i64,
    pub freq_hz: f64,
    /// Modal mass in the file's mass unit; 0 when not given.
    pub modal_mass: f64,
    /// Modal viscous damping ratio (-); 0 when not given.
    pub viscous_damping: f64,
    /// Translations X, Y, Z of each node (file's length unit, scaled as
    /// the file scales its shapes).
    pub shape: BTreeMap<i64, [f64; 3]>,
}

/// What an FE export holds.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FeFile {
    /// Node coordinates X, Y, Z (file's length unit).
    pub nodes: BTreeMap<i64, [f64; 3]>,
    /// Records that gave node coordinates (place, dataset).
    pub node_records: Vec<(usize, u32)>,
    pub units: Option<Units164>,
    pub modes: Vec<ModeRecord>,
    /// Datasets read but not normal modes (place, what): data at nodes of
    /// other analyses, datasets skipped.
    pub other: Vec<(usize, String)>,
    /// Datasets read (place, what).
    pub read: Vec<(usize, String)>,
    /// Coordinate systems (dataset 2420) by label.
    pub coordinate_systems: BTreeMap<i64, CoordinateSystem>,
    /// The coordinate systems each node names (datasets 15 and 2411).
    pub node_systems: BTreeMap<i64, NodeSystems>,
    /// Nodes whose displacements were turned from their displacement
    /// coordinate system to the part system, by the system's kind.
    pub turned: Turned,
    /// Normal modes written as complex data (types 5, 6) and read as real.
    pub complex_modes: usize,
    /// Largest imaginary part of those, relative to the mode's largest
    /// real part.
    pub largest_imaginary_ratio: f64,
}

/// Nodes whose displacements were turned to the part system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Turned {
    /// Nodes in Cartesian displacement systems.
    pub cartesian: usize,
    /// Nodes in cylindrical displacement systems.
    pub cylindrical: usize,
    /// Nodes of dataset 15 whose coordinates were given in a Cartesian
    /// definition system.
    pub coordinates: usize,
}

/// Datasets by description and count, in order of first appearance.
pub fn grouped(list: &[(usize, String)]) -> Vec<(String, usize)> {
    let mut seen: Vec<(String, usize)> = Vec::new();
    for (_, s) in list {
        match seen.iter_mut().find(|(k, _)| k == s) {
            Some((_, n)) => *n += 1,
            None => seen.push((s.clone(), 1)),
        }
    }
    seen
}

impl FeFile {
    /// What the file holds, for a file without modes: datasets by number
    /// and count, in order of first appearance.
    pub fn holds(&self) -> String {
        let mut all = self.read.clone();
        all.extend(self.other.iter().cloned());
        all.sort_by_key(|(place, _)| *place);
        let seen = grouped(&all);
        if seen.is_empty() {
            return "no datasets".into();
        }
        seen.iter()
            .map(|(k, n)| format!("{n} × {k}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// What a data characteristic or analysis type is, for messages.
fn analysis_name(t: i64) -> &'static str {
    match t {
        1 => "static",
        2 => "normal mode",
        3 => "complex eigenvalue, first order",
        4 => "transient",
        5 => "frequency response",
        6 => "buckling",
        7 => "complex eigenvalue, second order",
        9 => "static non-linear",
        _ => "unknown analysis",
    }
}

/// A dataset's body: its lines and the line number of the first.
struct Body<'a> {
    record: usize,
    dataset: &'static str,
    /// Line number of `lines[0]`.
    first: usize,
    lines: &'a [String],
}

impl Body<'_> {
    fn err(&self, k: usize, message: String) -> UffShapesError {
        UffShapesError::Record {
            record: self.record,
            dataset: self.dataset.to_string(),
            line: self.first + k,
            message,
        }
    }

    fn line(&self, k: usize, what: &str) -> Result<&str, UffShapesError> {
        self.lines.get(k).map(String::as_str).ok_or_else(|| {
            self.err(
                k.min(self.lines.len()),
                format!(
                    "ends after {} lines: expected {what} on its line {} (truncated?)",
                    self.lines.len(),
                    k + 1
                ),
            )
        })
    }

    /// Whitespace-separated integers of line `k`, at least `n`.
    fn ints(&self, k: usize, n: usize, what: &str) -> Result<Vec<i64>, UffShapesError> {
        let l = self.line(k, what)?;
        let v: Result<Vec<i64>, _> = l.split_whitespace().map(str::parse::<i64>).collect();
        match v {
            Ok(v) if v.len() >= n => Ok(v),
            _ => Err(self.err(k, format!("`{}`: expected {what}: {n} integers", l.trim()))),
        }
    }

    /// Whitespace-separated finite reals of line `k`, at least `n`.
    fn reals(&self, k: usize, n: usize, what: &str) -> Result<Vec<f64>, UffShapesError> {
        let l = self.line(k, what)?;
        let v: Option<Vec<f64>> = l.split_whitespace().map(uff::number).collect();
        match v {
            Some(v) if v.len() >= n && v.iter().all(|x| x.is_finite()) => Ok(v),
            _ => Err(self.err(
                k,
                format!("`{}`: expected {what}: {n} finite numbers", l.trim()),
            )),
        }
    }

    /// Records "node, then `n` values" from line `k` on (`2 n` numbers,
    /// real and imaginary parts, when `complex`): node numbers and values
    /// (translations X, Y, Z kept, their real parts), and the largest
    /// absolute real and imaginary parts of all values.
    fn nodal(&self, k: usize, n: usize, complex: bool) -> Result<Nodal, UffShapesError> {
        let per = if complex { 2 } else { 1 };
        let n_numbers = n * per;
        let mut out = BTreeMap::new();
        let (mut max_re, mut max_im) = (0.0f64, 0.0f64);
        let mut k = k;
        while k < self.lines.len() {
            let l = self.lines[k].trim();
            if l.is_empty() {
                k += 1;
                continue;
            }
            let node: i64 = match l.split_whitespace().collect::<Vec<_>>().as_slice() {
                [one] => one.parse().map_err(|_| {
                    self.err(k, format!("`{l}`: expected a node number (an integer)"))
                })?,
                _ => {
                    return Err(self.err(
                        k,
                        format!("`{l}`: expected a node number alone on its line"),
                    ));
                }
            };
            let at = k;
            k += 1;
            let mut vals = Vec::with_capacity(n_numbers);
            while vals.len() < n_numbers {
                let Some(l) = self.lines.get(k) else {
                    return Err(self.err(
                        k,
                        format!(
                            "node {node}: {} of its {n_numbers} numbers before the end of the dataset (truncated?)",
                            vals.len()
                        ),
                    ));
                };
                for t in l.split_whitespace() {
                    let v = uff::number(t).filter(|v| v.is_finite()).ok_or_else(|| {
                        self.err(k, format!("node {node}: `{t}`: expected a finite number"))
                    })?;
                    vals.push(v);
                }
                k += 1;
            }
            if vals.len() != n_numbers {
                return Err(self.err(
                    k - 1,
                    format!(
                        "node {node}: {} numbers: expected {n_numbers} ({n} values per node in the record's header{})",
                        vals.len(),
                        if complex { ", each a real and an imaginary part" } else { "" }
                    ),
                ));
            }
            for pair in vals.chunks(per) {
                max_re = max_re.max(pair[0].abs());
                if complex {
                    max_im = max_im.max(pair[1].abs());
                }
            }
            let t = [vals[0], vals[per], vals[2 * per]];
            if out.insert(node, t).is_some() {
                return Err(self.err(at, format!("node {node} given twice: expected once")));
            }
        }
        Ok(Nodal {
            shape: out,
            max_re,
            max_im,
        })
    }
}

/// Whether a normal mode record's specific data (result) type is a
/// displacement: 8, or unknown, general or an unknown vector (0, 1, 93,
/// 95, 96). Other results of a modal analysis (stresses, strain energy,
/// …) are skipped and listed.
fn is_displacement(specific: i64) -> bool {
    matches!(specific, 0 | 1 | 8 | 93 | 95 | 96)
}

/// Name of a result type, for the list of skipped records.
fn result_name(t: i64) -> &'static str {
    match t {
        2 => "stress",
        3 => "strain",
        4 => "element force",
        5 => "temperature",
        7 => "strain energy",
        9 => "reaction force",
        10 => "kinetic energy",
        11 => "velocity",
        12 => "acceleration",
        13 => "strain energy density",
        14 => "kinetic energy density",
        _ => "result",
    }
}

/// A record's values at nodes.
struct Nodal {
    /// Translations X, Y, Z of each node (real parts).
    shape: BTreeMap<i64, [f64; 3]>,
    /// Largest absolute real and imaginary part of all its values.
    max_re: f64,
    max_im: f64,
}

/// Checks the data definition of a normal mode's displacements: real data
/// (2, 4) or complex data (5, 6) whose imaginary parts are checked to be
/// zero, 3 or 6 values per node. Returns the values per node and whether
/// they are complex.
fn check_definition(
    b: &Body,
    k: usize,
    data_type: i64,
    per_node: i64,
) -> Result<(usize, bool), UffShapesError> {
    let complex = match data_type {
        2 | 4 => false,
        5 | 6 => true,
        _ => {
            return Err(b.err(
                k,
                format!(
                    "data type {data_type}: expected mode shapes as real data (2 single, 4 double precision) or as complex data with zero imaginary parts (5 single, 6 double)"
                ),
            ));
        }
    };
    if !matches!(per_node, 3 | 6) {
        return Err(b.err(
            k,
            format!(
                "{per_node} values per node: expected 3 (translations) or 6 (translations and rotations)"
            ),
        ));
    }
    Ok((per_node as usize, complex))
}

/// Largest imaginary part accepted in a normal mode written as complex
/// data, relative to the largest real part of the same mode.
pub const MAX_IMAGINARY_RATIO: f64 = 1e-6;

/// The shape of a normal mode record: its real parts, the imaginary parts
/// checked to be zero (below [`MAX_IMAGINARY_RATIO`] of the largest real
/// part) when the data are complex.
fn real_shape(
    b: &Body,
    k: usize,
    mode: i64,
    nodal: Nodal,
    complex: bool,
    out: &mut FeFile,
) -> Result<BTreeMap<i64, [f64; 3]>, UffShapesError> {
    if complex {
        let ratio = if nodal.max_im == 0.0 {
            0.0
        } else {
            nodal.max_im / nodal.max_re
        };
        if ratio.is_nan() || ratio > MAX_IMAGINARY_RATIO {
            return Err(b.err(
                k,
                format!(
                    "mode {mode}: complex shape with imaginary parts up to {:.3e}, {:.3e} of its largest real part ({:.6e}): expected at most {MAX_IMAGINARY_RATIO:e} (a real normal mode written as complex data); complex shapes are not normal modes",
                    nodal.max_im, ratio, nodal.max_re
                ),
            ));
        }
        out.complex_modes += 1;
        out.largest_imaginary_ratio = out.largest_imaginary_ratio.max(ratio);
    }
    Ok(nodal.shape)
}

/// Dataset 55.
fn dataset55(b: &Body, out: &mut FeFile) -> Result<(), UffShapesError> {
    let def = b.ints(5, 6, "record 6 (model type, analysis type, data characteristic, specific data type, data type, values per node)")?;
    let analysis = def[1];
    if analysis != 2 {
        out.other.push((
            b.record,
            format!(
                "dataset 55 of {} (analysis type {analysis})",
                analysis_name(analysis)
            ),
        ));
        return Ok(());
    }
    if !is_displacement(def[3]) {
        out.other.push((
            b.record,
            format!(
                "dataset 55 of normal mode {} (specific data type {})",
                result_name(def[3]),
                def[3]
            ),
        ));
        return Ok(());
    }
    let (n, complex) = check_definition(b, 5, def[4], def[5])?;
    let ints = b.ints(6, 4, "record 7 (2, 4, load case, mode number)")?;
    let reals = b.reals(
        7,
        4,
        "record 8 (frequency in Hz, modal mass, viscous damping ratio, hysteretic damping ratio)",
    )?;
    let shape = real_shape(b, 5, ints[3], b.nodal(8, n, complex)?, complex, out)?;
    out.modes.push(ModeRecord {
        record: b.record,
        line: b.first - 1,
        dataset: 55,
        mode_number: ints[3],
        freq_hz: reals[0],
        modal_mass: reals[1],
        viscous_damping: reals[2],
        shape,
    });
    out.read
        .push((b.record, "dataset 55 (normal mode shapes)".into()));
    Ok(())
}

/// Dataset 2414.
fn dataset2414(b: &Body, out: &mut FeFile) -> Result<(), UffShapesError> {
    let location = b.ints(2, 1, "record 3 (dataset location)")?[0];
    let def = b.ints(8, 6, "record 9 (model type, analysis type, data characteristic, result type, data type, values per node)")?;
    let analysis = def[1];
    if analysis != 2 {
        out.other.push((
            b.record,
            format!(
                "dataset 2414 of {} (analysis type {analysis})",
                analysis_name(analysis)
            ),
        ));
        return Ok(());
    }
    if location != 1 || !is_displacement(def[3]) {
        out.other.push((
            b.record,
            format!(
                "dataset 2414 of normal mode {} (result type {}{})",
                result_name(def[3]),
                def[3],
                if location != 1 {
                    format!(", dataset location {location}: not data at nodes")
                } else {
                    String::new()
                }
            ),
        ));
        return Ok(());
    }
    let (n, complex) = check_definition(b, 8, def[4], def[5])?;
    let ints = b.ints(9, 6, "record 10 (integers 1-8: the sixth the mode number)")?;
    b.ints(10, 1, "record 11 (integers 9-10)")?;
    let reals = b.reals(
        11,
        6,
        "record 12 (time, frequency in Hz, eigenvalue, modal mass, viscous and hysteretic damping ratios)",
    )?;
    b.reals(12, 1, "record 13 (reals 7-12)")?;
    // frequency, or from the eigenvalue ω² when only that is given
    let freq_hz = if reals[1] == 0.0 && reals[2] > 0.0 {
        reals[2].sqrt() / std::f64::consts::TAU
    } else {
        reals[1]
    };
    let shape = real_shape(b, 8, ints[5], b.nodal(13, n, complex)?, complex, out)?;
    out.modes.push(ModeRecord {
        record: b.record,
        line: b.first - 1,
        dataset: 2414,
        mode_number: ints[5],
        freq_hz,
        modal_mass: reals[3],
        viscous_damping: reals[4],
        shape,
    });
    out.read
        .push((b.record, "dataset 2414 (normal mode shapes)".into()));
    Ok(())
}

fn add_node(
    b: &Body,
    out: &mut FeFile,
    k: usize,
    node: i64,
    xyz: [f64; 3],
) -> Result<(), UffShapesError> {
    if out.nodes.insert(node, xyz).is_some() {
        return Err(b.err(
            k,
            format!("node {node}: coordinates given twice: expected once in the file"),
        ));
    }
    Ok(())
}

/// Notes the coordinate systems node `node` (line `k`) names, when one is
/// not the part system (0): `definition` (the system its coordinates are
/// given in) and `displacement` (the system of its displacements).
fn add_systems(
    b: &Body,
    out: &mut FeFile,
    k: usize,
    node: i64,
    definition: i64,
    displacement: i64,
) {
    if definition != 0 || displacement != 0 {
        out.node_systems.insert(
            node,
            NodeSystems {
                definition,
                displacement,
                record: b.record,
                dataset: b.dataset,
                line: b.first + k,
            },
        );
    }
}

/// Dataset 15: one line per node.
fn dataset15(b: &Body, out: &mut FeFile) -> Result<(), UffShapesError> {
    for (k, l) in b.lines.iter().enumerate() {
        if l.trim().is_empty() {
            continue;
        }
        let t: Vec<&str> = l.split_whitespace().collect();
        let node = t.first().and_then(|s| s.parse::<i64>().ok());
        let xyz: Option<Vec<f64>> = t.get(4..7).and_then(|s| {
            s.iter()
                .map(|v| uff::number(v).filter(|x| x.is_finite()))
                .collect()
        });
        let systems: Option<Vec<i64>> = t
            .get(1..3)
            .and_then(|s| s.iter().map(|v| v.parse().ok()).collect());
        match (t.len(), node, xyz, systems) {
            (7, Some(node), Some(x), Some(cs)) => {
                add_node(b, out, k, node, [x[0], x[1], x[2]])?;
                add_systems(b, out, k, node, cs[0], cs[1]);
            }
            _ => {
                return Err(b.err(
                    k,
                    format!(
                        "`{}`: expected a node: label, two coordinate systems, colour, X, Y, Z",
                        l.trim()
                    ),
                ));
            }
        }
    }
    out.node_records.push((b.record, 15));
    out.read
        .push((b.record, "dataset 15 (node coordinates)".into()));
    Ok(())
}

/// Dataset 2411: two lines per node.
fn dataset2411(b: &Body, out: &mut FeFile) -> Result<(), UffShapesError> {
    let mut k = 0;
    while k < b.lines.len() {
        if b.lines[k].trim().is_empty() {
            k += 1;
            continue;
        }
        let head = b.ints(
            k,
            4,
            "record 1 (node label, export and displacement coordinate systems, colour)",
        )?;
        let x = b.reals(k + 1, 3, "record 2 (coordinates X, Y, Z)")?;
        add_node(b, out, k, head[0], [x[0], x[1], x[2]])?;
        add_systems(b, out, k, head[0], 0, head[2]);
        k += 2;
    }
    out.node_records.push((b.record, 2411));
    out.read
        .push((b.record, "dataset 2411 (node coordinates)".into()));
    Ok(())
}

/// Reads the datasets of an FE export.
pub fn read(bytes: &[u8]) -> Result<FeFile, UffShapesError> {
    let mut c = Cursor {
        bytes,
        pos: 0,
        line: 0,
    };
    let mut out = FeFile::default();
    let mut place = 0;
    while let Some(l) = c.next_line() {
        if l.trim_ascii().is_empty() {
            continue;
        }
        if !uff::is_delim(l) {
            return Err(UffShapesError::Layout {
                line: c.line,
                message: format!(
                    "`{}`: expected `    -1`, the start of a dataset",
                    uff::decode(l).trim()
                ),
            });
        }
        let open = c.line;
        place += 1;
        let truncated = |place: usize| UffShapesError::Layout {
            line: open,
            message: format!(
                "record {place}: no closing `    -1`: expected the file to end with it (truncated?)"
            ),
        };
        let id_line = uff::decode(c.next_line().ok_or_else(|| truncated(place))?);
        let first = c.line;
        let id = uff::field(&id_line, 0, 6);
        if id == "58" && id_line.chars().nth(6) == Some('b') {
            uff::binary58(&mut c, &id_line, place, first).map_err(|(at, message)| {
                UffShapesError::Layout {
                    line: first,
                    message: format!("{at}{message}"),
                }
            })?;
            out.other
                .push((place, "dataset 58b (function at a DOF)".into()));
            continue;
        }
        let mut body = Vec::new();
        loop {
            let l = c.next_line().ok_or_else(|| truncated(place))?;
            if uff::is_delim(l) {
                break;
            }
            body.push(uff::decode(l));
        }
        let name = |dataset| Body {
            record: place,
            dataset,
            first: first + 1,
            lines: &body,
        };
        match id.as_str() {
            "55" => dataset55(&name("55"), &mut out)?,
            "2414" => dataset2414(&name("2414"), &mut out)?,
            "15" => dataset15(&name("15"), &mut out)?,
            "2411" => dataset2411(&name("2411"), &mut out)?,
            "2420" => coordinate_systems::dataset2420(&name("2420"), &mut out)?,
            "164" => {
                let lines: Vec<&str> = body.iter().map(String::as_str).collect();
                let u = uff::units164(&lines, place, first).map_err(|(at, message)| {
                    UffShapesError::Layout {
                        line: first,
                        message: format!("{at}{message}"),
                    }
                })?;
                if out.units.is_none() {
                    out.units = Some(u);
                }
                out.read.push((place, "dataset 164 (units)".into()));
            }
            "58" => out
                .other
                .push((place, "dataset 58 (function at a DOF)".into())),
            other => out.other.push((place, format!("dataset {other}"))),
        }
    }
    coordinate_systems::to_part_system(&mut out)?;
    Ok(out)
}
