//! A tyre computed elsewhere: normal modes of a finite-element model read
//! from a UFF export (method §5.4), without identification. The mode
//! shapes (dataset 55 or 2414, see [`uff_shapes`]) are sampled at the
//! file's nodes that stand for the scene's points, along the FE axis
//! normal to the road, converted to SI by the file's units (dataset 164)
//! and mass-normalised; each mode is a rank-one term of the modal model of
//! method §2, `A_k = φ_k φ_kᵀ`.
//!
//! Units: with `file value = SI value × factor` for length (`c_L`) and
//! force (`c_F`) and time in seconds, masses carry `c_M = c_F / c_L`. In
//! a consistent unit system (`shape_units: Consistent`, the default) a
//! mass-normalised shape is in 1/√(mass unit) — `φᵀ M φ = 1` with the
//! displacements in the file's length unit and `M` in its mass unit — so
//! a shape `φ` scaled to the modal mass `M` (file units) becomes, in SI,
//!
//! ```text
//! φ_SI = φ / √(M / c_M)          (1/√kg; M / c_M is the modal mass in kg)
//! ```
//!
//! and a stated modal mass (kg) replaces `M / c_M`. A file in mm and mN
//! (UFF units code 5: masses in kg) thus holds the SI numbers; one in mm,
//! N and tonnes holds shapes in 1/√t, √1000 times the SI ones. Some
//! exports scale shapes as displacements per √kg in the file's length
//! unit instead (`shape_units: LengthPerSqrtKg`): `φ_SI = φ / (c_L √M_kg)`,
//! a shape in mm/√kg is divided by 1000.
//!
//! Sign: `direction` is the FE axis that points away from the road (the
//! road lies on its negative side), so a displacement along it is the
//! point's `u`, positive up, as for every tyre (method §1). The Green
//! functions do not depend on the sign (`A = φ φᵀ`); `Nearest` does: it
//! looks for nodes on the road side, the lowest along `direction`.

use crate::readers::measured::{self, ReadError};
use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use tirecontact_core::base::modal::Mode;

pub mod uff_shapes;

pub use uff_shapes::{FeFile, ModeRecord, UffShapesError};

/// Default largest distance (m) from a scene point to the node `Nearest`
/// picks for it.
pub const DEFAULT_NEAREST_WITHIN_M: f64 = 1e-3;

/// The default band: every mode.
pub const ALL_MODES_HZ: (f64, f64) = (0.0, f64::INFINITY);

/// Whether `band_hz` keeps every mode (not written when saved).
pub fn is_all_modes(band_hz: &(f64, f64)) -> bool {
    *band_hz == ALL_MODES_HZ
}

/// Whether `m` is the default distance of `Nearest` (not written when saved).
pub fn is_default_within(m: &f64) -> bool {
    *m == DEFAULT_NEAREST_WITHIN_M
}

/// Stated modal masses: one number for every mode, or a list.
pub fn de_masses<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
    struct V;
    impl<'de> Visitor<'de> for V {
        type Value = Vec<f64>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a modal mass in kg, or a list of one per mode")
        }
        fn visit_f64<E: de::Error>(self, v: f64) -> Result<Vec<f64>, E> {
            Ok(vec![v])
        }
        fn visit_i64<E: de::Error>(self, v: i64) -> Result<Vec<f64>, E> {
            Ok(vec![v as f64])
        }
        fn visit_u64<E: de::Error>(self, v: u64) -> Result<Vec<f64>, E> {
            Ok(vec![v as f64])
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut a: A) -> Result<Vec<f64>, A::Error> {
            let mut v = Vec::new();
            while let Some(x) = a.next_element::<f64>()? {
                v.push(x);
            }
            Ok(v)
        }
    }
    d.deserialize_any(V)
}

/// Highest mode frequency accepted (Hz), as for modes given in a preset.
pub const MAX_FE_FREQ_HZ: f64 = 1e6;

/// Largest damping ratio accepted from a file, as for modes given in a
/// preset.
pub const MAX_FE_DAMPING_RATIO: f64 = 1e4;

/// Largest mass-normalised shape value accepted (1/√kg): a mode of a
/// microgram.
pub const MAX_SHAPE: f64 = 1e4;

/// Most modes kept from a file.
pub const MAX_FE_MODES: usize = 4000;

/// An axis of the FE model's coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FeAxis {
    X,
    Y,
    Z,
}

impl FeAxis {
    /// Index into `[X, Y, Z]`.
    pub fn index(self) -> usize {
        match self {
            FeAxis::X => 0,
            FeAxis::Y => 1,
            FeAxis::Z => 2,
        }
    }

    pub fn name(self) -> &'static str {
        ["X", "Y", "Z"][self.index()]
    }
}

/// Which FE axes carry the scene's `x_m` (rolling direction) and `y_m`
/// (across the tread).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeAxes {
    pub along: FeAxis,
    pub across: FeAxis,
}

impl Default for FeAxes {
    fn default() -> Self {
        FeAxes {
            along: FeAxis::X,
            across: FeAxis::Y,
        }
    }
}

/// The file's nodes that stand for the scene's points: listed in the
/// points' order (`[101, 102]`), or the node nearest each point
/// (`Nearest`).
#[derive(Debug, Clone, PartialEq)]
pub enum FeNodes {
    List(Vec<i64>),
    Nearest,
}

impl Serialize for FeNodes {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            FeNodes::List(v) => v.serialize(s),
            FeNodes::Nearest => s.serialize_unit_variant("FeNodes", 1, "Nearest"),
        }
    }
}

impl<'de> Deserialize<'de> for FeNodes {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        // (untagged: RON hands a bare identifier to it by name)
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            List(Vec<i64>),
            Name(String),
        }
        let expected = "a list of node numbers `[101, 102]` or `Nearest`";
        match Raw::deserialize(d).map_err(|_| de::Error::custom(format!("expected {expected}")))? {
            Raw::List(v) => Ok(FeNodes::List(v)),
            Raw::Name(s) if s == "Nearest" => Ok(FeNodes::Nearest),
            Raw::Name(s) => Err(de::Error::custom(format!("`{s}`: expected {expected}"))),
        }
    }
}

/// Damping of the modes read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FeDamping {
    /// One damping ratio `ξ` (-) for every mode.
    Ratio(f64),
    /// One damping ratio per mode kept, by increasing frequency.
    Modal(Vec<f64>),
    /// Rayleigh damping `C = α M + β K`: `ξ = α / (2ω) + β ω / 2`.
    Rayleigh {
        /// `α` (1/s), >= 0.
        #[serde(alias = "alpha")]
        alpha_per_s: f64,
        /// `β` (s), >= 0.
        #[serde(alias = "beta")]
        beta_s: f64,
    },
    /// The modal viscous damping ratio each record gives.
    FromFile,
}

impl FeDamping {
    /// `ξ` of mode `k` (of `n` kept) at `f_hz` from record value
    /// `from_file`; `Modal` with a wrong count is refused earlier.
    pub fn ratio(&self, k: usize, f_hz: f64, from_file: f64) -> f64 {
        match self {
            FeDamping::Ratio(x) => *x,
            FeDamping::Modal(v) => v.get(k).copied().unwrap_or(f64::NAN),
            FeDamping::Rayleigh {
                alpha_per_s,
                beta_s,
            } => {
                let w = TAU * f_hz;
                alpha_per_s / (2.0 * w) + beta_s * w / 2.0
            }
            FeDamping::FromFile => from_file,
        }
    }
}

/// How the file's mode shapes are scaled (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum FeShapeUnits {
    /// In the file's consistent unit system: 1/√(mass unit) when
    /// mass-normalised. Default.
    #[default]
    Consistent,
    /// Displacements in the file's length unit per √kg.
    LengthPerSqrtKg,
}

impl FeShapeUnits {
    pub fn is_consistent(&self) -> bool {
        *self == FeShapeUnits::Consistent
    }
}

/// A tyre read from an FE export: the scene's `tyre: FeModes(...)` fields.
#[derive(Debug, Clone, PartialEq)]
pub struct FeModesSpec {
    /// The UFF file (relative to the preset's folder, resolved by the
    /// caller).
    pub file: PathBuf,
    pub nodes: FeNodes,
    /// The FE axis normal to the road, pointing away from it.
    pub direction: FeAxis,
    pub axes: FeAxes,
    pub damping: FeDamping,
    /// Modal masses (kg): empty (the records'), one for every mode, or one
    /// per mode kept.
    pub modal_mass_kg: Vec<f64>,
    /// Modes kept: `lo <= f <= hi` (Hz).
    pub band_hz: (f64, f64),
    /// `Nearest`: largest distance (m) from a point to its node.
    pub nearest_within_m: f64,
    pub shape_units: FeShapeUnits,
}

/// A file that does not make a modal model of the scene's points.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FeModesError {
    #[error("{file}: {source}")]
    Read {
        file: String,
        #[source]
        source: ReadError,
    },
    #[error("{file}: {source}")]
    Parse {
        file: String,
        #[source]
        source: UffShapesError,
    },
    #[error(
        "{file}: no normal modes (dataset 55 or 2414 of analysis type 2): the file holds {holds}"
    )]
    NoModes { file: String, holds: String },
    #[error(
        "{file}: tyre.nodes = Nearest needs node coordinates (dataset 15 or 2411): the file has none; list the nodes instead"
    )]
    NoCoordinates { file: String },
    #[error(
        "{file}: points[{point}] at (x_m {x_m}, y_m {y_m}): the nearest node, {node}, is {distance_m} m away: expected a node within tyre.nearest_within_m = {within_m} m (check tyre.axes and the file's units)"
    )]
    TooFar {
        file: String,
        point: usize,
        x_m: f64,
        y_m: f64,
        node: i64,
        distance_m: f64,
        within_m: f64,
    },
    #[error(
        "{file}: node {node} of points[{point}]: record {record} (mode {mode}) has no value at node {node}: expected a node of every mode shape"
    )]
    MissingNode {
        file: String,
        point: usize,
        node: i64,
        record: usize,
        mode: i64,
    },
    #[error(
        "{file}: record {record} (mode {mode}, {freq_hz} Hz) gives no modal mass: state tyre.modal_mass_kg (1 if its shapes are mass-normalised in SI)"
    )]
    NoModalMass {
        file: String,
        record: usize,
        mode: i64,
        freq_hz: f64,
    },
    #[error(
        "{file}: record {record} (mode {mode}) at {freq_hz} Hz: expected a frequency > 0 and <= {MAX_FE_FREQ_HZ} Hz (a rigid-body mode? keep it out with tyre.band_hz)"
    )]
    Frequency {
        file: String,
        record: usize,
        mode: i64,
        freq_hz: f64,
    },
    #[error(
        "{file}: record {record} (mode {mode}) at node {node}: shape {value} 1/√kg in SI: expected a finite value of at most {MAX_SHAPE:e} (check the file's units and modal mass)"
    )]
    Shape {
        file: String,
        record: usize,
        mode: i64,
        node: i64,
        value: f64,
    },
    #[error("{file}: mode {mode} in records {first} and {second}: expected each mode once")]
    Duplicate {
        file: String,
        mode: i64,
        first: usize,
        second: usize,
    },
    #[error(
        "{file}: no mode in tyre.band_hz = ({lo}, {hi}) Hz: the file's modes run from {min_hz} to {max_hz} Hz"
    )]
    EmptyBand {
        file: String,
        lo: f64,
        hi: f64,
        min_hz: f64,
        max_hz: f64,
    },
    #[error("{file}: {modes} modes kept: expected at most {MAX_FE_MODES} (narrow tyre.band_hz)")]
    TooMany { file: String, modes: usize },
    #[error(
        "rigid contact of {points} points on {modes} modes is singular: expected at most as many points as modes; use contact: Compliant(stiffness_n_m: [...]) tread springs, or widen tyre.band_hz"
    )]
    RigidTooFew { points: usize, modes: usize },
    #[error("tyre.{field} has {given} values: expected one per mode kept ({modes})")]
    PerMode {
        field: &'static str,
        given: usize,
        modes: usize,
    },
    #[error(
        "{file}: record {record} (mode {mode}): damping ratio {ratio} at {freq_hz} Hz: expected a ratio from 0 to {MAX_FE_DAMPING_RATIO}"
    )]
    Damping {
        file: String,
        record: usize,
        mode: i64,
        freq_hz: f64,
        ratio: f64,
    },
}

/// How a point maps to a node.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeMap {
    pub node: i64,
    /// Distance from the point to the node (m); `None` for listed nodes
    /// without coordinates in the file.
    pub distance_m: Option<f64>,
}

/// One mode kept, as read.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeRead {
    pub record: usize,
    pub dataset: u32,
    pub mode_number: i64,
    pub freq_hz: f64,
    /// Modal mass used (kg).
    pub modal_mass_kg: f64,
    pub damping_ratio: f64,
}

/// A modal model of the scene's points read from an FE export.
#[derive(Debug, Clone, PartialEq)]
pub struct FeModel {
    /// Mass-normalised SI modes at the points, by increasing frequency.
    pub modes: Vec<Mode>,
    /// The modes as read (same order).
    pub read: Vec<ModeRead>,
    /// Node of each point.
    pub mapping: Vec<NodeMap>,
    /// `file value = SI value × factor`: length, force, mass.
    pub length_factor: f64,
    pub force_factor: f64,
    pub mass_factor: f64,
    /// What the reading did, one sentence each (units, normalisation,
    /// modes dropped).
    pub notes: Vec<String>,
}

/// Reads `spec.file` and builds the modal model at `points` (`(x_m, y_m)`).
pub fn load(spec: &FeModesSpec, points: &[(f64, f64)]) -> Result<FeModel, FeModesError> {
    let file = spec.file.display().to_string();
    let bytes = measured::read_bytes(&spec.file, false).map_err(|source| FeModesError::Read {
        file: file.clone(),
        source,
    })?;
    let fe = uff_shapes::read(&bytes).map_err(|source| FeModesError::Parse {
        file: file.clone(),
        source,
    })?;
    build(spec, &fe, points)
}

/// The modal model at `points` of the modes `fe` holds (method §5.4).
pub fn build(
    spec: &FeModesSpec,
    fe: &FeFile,
    points: &[(f64, f64)],
) -> Result<FeModel, FeModesError> {
    let file = spec.file.display().to_string();
    if fe.modes.is_empty() {
        return Err(FeModesError::NoModes {
            file,
            holds: fe.holds(),
        });
    }
    let mut notes = Vec::new();
    let (c_l, c_f) = match &fe.units {
        Some(u) => {
            notes.push(format!(
                "units from record {} (dataset 164, code {} `{}`): lengths ÷ {}, forces ÷ {}, masses ÷ {} to SI",
                u.record,
                u.code,
                u.description,
                u.length,
                u.force,
                u.force / u.length
            ));
            (u.length, u.force)
        }
        None => {
            notes.push("no units (dataset 164): SI taken (m, N, kg, s)".into());
            (1.0, 1.0)
        }
    };
    let c_m = c_f / c_l;
    // modes kept, by frequency; each mode number once
    let mut kept: Vec<&ModeRecord> = Vec::new();
    let mut by_number: std::collections::BTreeMap<i64, usize> = Default::default();
    for m in &fe.modes {
        if let Some(&first) = by_number.get(&m.mode_number) {
            return Err(FeModesError::Duplicate {
                file,
                mode: m.mode_number,
                first,
                second: m.record,
            });
        }
        by_number.insert(m.mode_number, m.record);
        let inside = m.freq_hz >= spec.band_hz.0 && m.freq_hz <= spec.band_hz.1;
        if inside {
            if !(m.freq_hz.is_finite() && m.freq_hz > 0.0 && m.freq_hz <= MAX_FE_FREQ_HZ) {
                return Err(FeModesError::Frequency {
                    file,
                    record: m.record,
                    mode: m.mode_number,
                    freq_hz: m.freq_hz,
                });
            }
            kept.push(m);
        }
    }
    if kept.is_empty() {
        let (lo, hi) = spec.band_hz;
        let f = fe.modes.iter().map(|m| m.freq_hz);
        return Err(FeModesError::EmptyBand {
            file,
            lo,
            hi,
            min_hz: f.clone().fold(f64::INFINITY, f64::min),
            max_hz: f.fold(f64::NEG_INFINITY, f64::max),
        });
    }
    if kept.len() > MAX_FE_MODES {
        return Err(FeModesError::TooMany {
            file,
            modes: kept.len(),
        });
    }
    if kept.len() < fe.modes.len() {
        notes.push(format!(
            "{} of the file's {} modes kept (tyre.band_hz)",
            kept.len(),
            fe.modes.len()
        ));
    }
    kept.sort_by(|a, b| a.freq_hz.total_cmp(&b.freq_hz));
    let n = kept.len();
    if !matches!(spec.modal_mass_kg.len(), 0 | 1) && spec.modal_mass_kg.len() != n {
        return Err(FeModesError::PerMode {
            field: "modal_mass_kg",
            given: spec.modal_mass_kg.len(),
            modes: n,
        });
    }
    if let FeDamping::Modal(v) = &spec.damping
        && v.len() != n
    {
        return Err(FeModesError::PerMode {
            field: "damping",
            given: v.len(),
            modes: n,
        });
    }
    let mapping = map_nodes(spec, fe, &kept, points, c_l)?;
    let (ia, ic, id) = (
        spec.axes.along.index(),
        spec.axes.across.index(),
        spec.direction.index(),
    );
    notes.push(format!(
        "FE axes: x_m along {}, y_m across {}, u along {} (away from the road)",
        spec.axes.along.name(),
        spec.axes.across.name(),
        spec.direction.name()
    ));
    let _ = (ia, ic);
    let mut modes = Vec::with_capacity(n);
    let mut read = Vec::with_capacity(n);
    let mut stated = false;
    for (k, m) in kept.iter().enumerate() {
        let mass_kg = match spec.modal_mass_kg.as_slice() {
            [] if m.modal_mass > 0.0 && m.modal_mass.is_finite() => m.modal_mass / c_m,
            [] => {
                return Err(FeModesError::NoModalMass {
                    file,
                    record: m.record,
                    mode: m.mode_number,
                    freq_hz: m.freq_hz,
                });
            }
            [one] => {
                stated = true;
                *one
            }
            v => {
                stated = true;
                v[k]
            }
        };
        let scale = match spec.shape_units {
            FeShapeUnits::Consistent => 1.0 / mass_kg.sqrt(),
            FeShapeUnits::LengthPerSqrtKg => 1.0 / (c_l * mass_kg.sqrt()),
        };
        let shape: Vec<f64> = mapping
            .iter()
            .map(|nm| m.shape[&nm.node][id] * scale)
            .collect();
        if let Some((k, v)) = shape
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && v.abs() <= MAX_SHAPE))
        {
            return Err(FeModesError::Shape {
                file,
                record: m.record,
                mode: m.mode_number,
                node: mapping[k].node,
                value: *v,
            });
        }
        let damping_ratio = spec.damping.ratio(k, m.freq_hz, m.viscous_damping);
        if !(damping_ratio.is_finite() && (0.0..=MAX_FE_DAMPING_RATIO).contains(&damping_ratio)) {
            return Err(FeModesError::Damping {
                file,
                record: m.record,
                mode: m.mode_number,
                freq_hz: m.freq_hz,
                ratio: damping_ratio,
            });
        }
        modes.push(Mode {
            freq_hz: m.freq_hz,
            damping_ratio,
            residue: Vec::new(),
            shape,
        });
        read.push(ModeRead {
            record: m.record,
            dataset: m.dataset,
            mode_number: m.mode_number,
            freq_hz: m.freq_hz,
            modal_mass_kg: mass_kg,
            damping_ratio,
        });
    }
    notes.push(format!(
        "shapes {} and normalised by {}",
        match spec.shape_units {
            FeShapeUnits::Consistent => format!(
                "in 1/√(file mass unit), × {} to 1/√kg",
                tirecontact_core::base::error::fmt_num(c_m.sqrt())
            ),
            FeShapeUnits::LengthPerSqrtKg => format!(
                "in file length per √kg, ÷ {} to m/√kg",
                tirecontact_core::base::error::fmt_num(c_l)
            ),
        },
        if stated {
            "the stated modal masses (tyre.modal_mass_kg)"
        } else {
            "the records' modal masses (÷ the mass factor to kg)"
        }
    ));
    Ok(FeModel {
        modes,
        read,
        mapping,
        length_factor: c_l,
        force_factor: c_f,
        mass_factor: c_m,
        notes,
    })
}

/// The node of each point: listed, or the nearest on the road side.
fn map_nodes(
    spec: &FeModesSpec,
    fe: &FeFile,
    kept: &[&ModeRecord],
    points: &[(f64, f64)],
    c_l: f64,
) -> Result<Vec<NodeMap>, FeModesError> {
    let file = spec.file.display().to_string();
    let (ia, ic, id) = (
        spec.axes.along.index(),
        spec.axes.across.index(),
        spec.direction.index(),
    );
    let si = |xyz: &[f64; 3]| [xyz[0] / c_l, xyz[1] / c_l, xyz[2] / c_l];
    let in_every = |node: i64| kept.iter().all(|m| m.shape.contains_key(&node));
    let out: Vec<NodeMap> = match &spec.nodes {
        FeNodes::List(list) => list
            .iter()
            .zip(points)
            .map(|(&node, &(x, y))| NodeMap {
                node,
                distance_m: fe.nodes.get(&node).map(|c| {
                    let c = si(c);
                    (c[ia] - x).hypot(c[ic] - y)
                }),
            })
            .collect(),
        FeNodes::Nearest => {
            let cands: Vec<(i64, [f64; 3])> = fe
                .nodes
                .iter()
                .filter(|(n, _)| in_every(**n))
                .map(|(n, c)| (*n, si(c)))
                .collect();
            if cands.is_empty() {
                return Err(FeModesError::NoCoordinates { file });
            }
            // the road side: the lowest nodes along `direction`
            let low = cands
                .iter()
                .map(|(_, c)| c[id])
                .fold(f64::INFINITY, f64::min);
            let mut out = Vec::with_capacity(points.len());
            for (i, &(x, y)) in points.iter().enumerate() {
                let mut best = (f64::INFINITY, 0);
                for (n, c) in &cands {
                    let d =
                        ((c[ia] - x).powi(2) + (c[ic] - y).powi(2) + (c[id] - low).powi(2)).sqrt();
                    if d < best.0 {
                        best = (d, *n);
                    }
                }
                if best.0 > spec.nearest_within_m {
                    // a node near enough, but not in every mode: say which
                    let near = fe.nodes.iter().find(|(n, c)| {
                        let c = si(c);
                        let d = ((c[ia] - x).powi(2) + (c[ic] - y).powi(2) + (c[id] - low).powi(2))
                            .sqrt();
                        d <= spec.nearest_within_m && !in_every(**n)
                    });
                    if let Some((&node, _)) = near
                        && let Some(m) = kept.iter().find(|m| !m.shape.contains_key(&node))
                    {
                        return Err(FeModesError::MissingNode {
                            file,
                            point: i,
                            node,
                            record: m.record,
                            mode: m.mode_number,
                        });
                    }
                    return Err(FeModesError::TooFar {
                        file,
                        point: i,
                        x_m: x,
                        y_m: y,
                        node: best.1,
                        distance_m: best.0,
                        within_m: spec.nearest_within_m,
                    });
                }
                out.push(NodeMap {
                    node: best.1,
                    distance_m: Some(best.0),
                });
            }
            out
        }
    };
    for (point, nm) in out.iter().enumerate() {
        if let Some(m) = kept.iter().find(|m| !m.shape.contains_key(&nm.node)) {
            return Err(FeModesError::MissingNode {
                file,
                point,
                node: nm.node,
                record: m.record,
                mode: m.mode_number,
            });
        }
    }
    Ok(out)
}

/// The file of `file` relative to a scene's folder.
pub fn resolve(base_dir: Option<&Path>, file: &Path) -> PathBuf {
    match base_dir {
        Some(d) if file.is_relative() => d.join(file),
        _ => file.to_path_buf(),
    }
}
