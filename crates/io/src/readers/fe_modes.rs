//! A tyre computed elsewhere: normal modes of a finite-element model read
//! from a UFF export (method §5.4), without identification. The mode
//! shapes (dataset 55 or 2414, see [`uff_shapes`]; displacements given in
//! per-node coordinate systems of dataset 2420 turned to the part system
//! on reading) are sampled at the file's nodes that stand for the scene's points, along the FE axis
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

mod model;
#[cfg(test)]
mod tests;
pub mod uff_shapes;

pub use model::build;

pub use uff_shapes::{CoordinateSystem, CsKind, FeFile, ModeRecord, UffShapesError};

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
    /// What the reading did, one sentence each (units, coordinate
    /// systems, normalisation, modes dropped).
    pub notes: Vec<String>,
    /// The datasets read (description, count), in the file's order.
    pub datasets_read: Vec<(String, usize)>,
    /// The datasets skipped (description, count), in the file's order.
    pub datasets_skipped: Vec<(String, usize)>,
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

/// The file of `file` relative to a scene's folder.
pub fn resolve(base_dir: Option<&Path>, file: &Path) -> PathBuf {
    match base_dir {
        Some(d) if file.is_relative() => d.join(file),
        _ => file.to_path_buf(),
    }
}
