//! Coordinate systems (dataset 2420) and the nodes that name them
//! (datasets 15 and 2411): node displacements given in a node's
//! displacement coordinate system are turned to the part system before
//! anything else sees them.
//!
//! - **2420** (coordinate systems): record 1 `(2I10)` part UID, 2 `(40A2)`
//!   part name, then per system record 3 `(4I10)` label, type (0
//!   Cartesian, 1 cylindrical, 2 spherical), colour; 4 `(40A2)` name; 5–8
//!   `(1P3D25.16)` the transformation matrix, four rows of three: rows 1–3
//!   the system's X, Y, Z axes as unit vectors in the part system, row 4
//!   its origin in the part system (file length unit). A point of local
//!   Cartesian coordinates `q` is at `origin + Σ q_i row_i`. Each system
//!   is defined in the part system: the dataset has no nesting.
//! - **2411** record 1: label, export coordinate system, displacement
//!   coordinate system, colour; the coordinates are in the part system
//!   whatever the export system. **15**: label, definition coordinate
//!   system, displacement coordinate system, colour, then the coordinates
//!   in the definition system.
//!
//! Label 0 is the part system. A Cartesian displacement system turns the
//! translations `u` (its X, Y, Z components) to `Σ u_i row_i`; a
//! cylindrical one gives radial, tangential and axial components at the
//! node, turned by the local basis at the node's position (angle about
//! the system's Z axis from its X axis); spherical systems are refused.
//! Only translations are kept, so rotations are not turned.

use super::{Body, FeFile, UffShapesError};
use std::collections::BTreeMap;

/// Largest departure of a system's axes from an orthonormal set accepted
/// (`|R Rᵀ − I|`, largest entry).
pub const MAX_AXES_DEVIATION: f64 = 1e-5;

/// The kind of a coordinate system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CsKind {
    Cartesian,
    Cylindrical,
    Spherical,
}

impl CsKind {
    pub fn name(self) -> &'static str {
        match self {
            CsKind::Cartesian => "Cartesian",
            CsKind::Cylindrical => "cylindrical",
            CsKind::Spherical => "spherical",
        }
    }
}

/// A coordinate system of dataset 2420, in the part system.
#[derive(Debug, Clone, PartialEq)]
pub struct CoordinateSystem {
    pub label: i64,
    pub kind: CsKind,
    pub name: String,
    /// Its X, Y, Z axes: unit vectors in the part system.
    pub axes: [[f64; 3]; 3],
    /// Its origin in the part system (file length unit).
    pub origin: [f64; 3],
    /// Its dataset's place among the file's datasets (1-based).
    pub record: usize,
    /// Line of its record 3 (1-based).
    pub line: usize,
}

/// The coordinate systems a node names, when one is not the part system.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeSystems {
    /// The system its coordinates are given in (dataset 15; 0 for 2411,
    /// whose coordinates are in the part system).
    pub definition: i64,
    /// The system its displacements are given in.
    pub displacement: i64,
    /// Where the node is given: dataset place, number, line (1-based).
    pub record: usize,
    pub dataset: &'static str,
    pub line: usize,
}

/// Dataset 2420.
pub(super) fn dataset2420(b: &Body, out: &mut FeFile) -> Result<(), UffShapesError> {
    b.ints(0, 1, "record 1 (part UID)")?;
    b.line(1, "record 2 (part name)")?;
    let mut k = 2;
    while k < b.lines.len() {
        if b.lines[k..].iter().all(|l| l.trim().is_empty()) {
            break;
        }
        let head = b.ints(k, 3, "record 3 (coordinate system label, type, colour)")?;
        let label = head[0];
        let kind = match head[1] {
            0 => CsKind::Cartesian,
            1 => CsKind::Cylindrical,
            2 => CsKind::Spherical,
            t => {
                return Err(b.err(
                    k,
                    format!(
                        "coordinate system {label}: type {t}: expected 0 (Cartesian), 1 (cylindrical) or 2 (spherical)"
                    ),
                ));
            }
        };
        let name = b
            .line(k + 1, "record 4 (coordinate system name)")?
            .trim()
            .to_string();
        let mut rows = [[0.0; 3]; 4];
        for (i, row) in rows.iter_mut().enumerate() {
            let what = if i < 3 {
                format!(
                    "record {} (transformation matrix row {}: the system's {} axis in the part system)",
                    5 + i,
                    i + 1,
                    ["X", "Y", "Z"][i]
                )
            } else {
                "record 8 (transformation matrix row 4: the system's origin in the part system)"
                    .to_string()
            };
            let v = b.reals(k + 2 + i, 3, &what)?;
            *row = [v[0], v[1], v[2]];
        }
        let axes = [rows[0], rows[1], rows[2]];
        let deviation = axes_deviation(&axes);
        if deviation.is_nan() || deviation > MAX_AXES_DEVIATION {
            return Err(b.err(
                k + 2,
                format!(
                    "coordinate system {label}: transformation matrix rows 1-3 depart from orthonormal axes by {deviation:e}: expected at most {MAX_AXES_DEVIATION:e}"
                ),
            ));
        }
        let cs = CoordinateSystem {
            label,
            kind,
            name,
            axes,
            origin: rows[3],
            record: b.record,
            line: b.first + k,
        };
        if let Some(prev) = out.coordinate_systems.get(&label) {
            if (prev.kind, prev.axes, prev.origin) != (cs.kind, cs.axes, cs.origin) {
                return Err(b.err(
                    k,
                    format!(
                        "coordinate system {label} defined again, differently from record {} line {}: expected one definition per label",
                        prev.record, prev.line
                    ),
                ));
            }
        } else {
            out.coordinate_systems.insert(label, cs);
        }
        k += 6;
    }
    out.read
        .push((b.record, "dataset 2420 (coordinate systems)".into()));
    Ok(())
}

/// Largest entry of `|R Rᵀ − I|`.
fn axes_deviation(r: &[[f64; 3]; 3]) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|c| r[i][c] * r[j][c]).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            let d = (dot - want).abs();
            if d.is_nan() || d > worst {
                worst = d;
            }
        }
    }
    worst
}

/// `origin + Σ q_i axes_i`: a point given in `cs`'s Cartesian coordinates,
/// in the part system.
fn to_part(cs: &CoordinateSystem, q: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|c| cs.origin[c] + (0..3).map(|i| q[i] * cs.axes[i][c]).sum::<f64>())
}

/// A part-system point in `cs`'s Cartesian coordinates.
fn from_part(cs: &CoordinateSystem, p: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|c| cs.axes[i][c] * (p[c] - cs.origin[c])).sum())
}

/// What the file says about its systems, for a refusal.
fn defined(systems: &BTreeMap<i64, CoordinateSystem>) -> String {
    let labels: Vec<String> = systems.keys().take(8).map(i64::to_string).collect();
    match systems.len() {
        0 => "the file has no dataset 2420".into(),
        n if n > labels.len() => format!("the file defines {n}: {}, …", labels.join(", ")),
        n => format!("the file defines {n}: {}", labels.join(", ")),
    }
}

/// Node coordinates given in a definition system, and every mode's
/// displacements given in a displacement system, to the part system.
pub(super) fn to_part_system(out: &mut FeFile) -> Result<(), UffShapesError> {
    if out.node_systems.is_empty() {
        return Ok(());
    }
    let mut turn: BTreeMap<i64, [[f64; 3]; 3]> = BTreeMap::new();
    let node_systems = std::mem::take(&mut out.node_systems);
    for (&node, ns) in &node_systems {
        let err = |message: String| UffShapesError::Record {
            record: ns.record,
            dataset: ns.dataset.to_string(),
            line: ns.line,
            message: format!("node {node}: {message}"),
        };
        let systems = &out.coordinate_systems;
        let system = |label: i64, role: &str| {
            systems.get(&label).ok_or_else(|| {
                err(format!(
                    "{role} coordinate system {label} is not defined: expected it in a dataset 2420 ({})",
                    defined(systems)
                ))
            })
        };
        let Some(&at) = out.nodes.get(&node) else {
            continue;
        };
        let mut at = at;
        if ns.definition != 0 {
            let cs = system(ns.definition, "definition")?;
            if cs.kind != CsKind::Cartesian {
                return Err(err(format!(
                    "definition coordinate system {} (`{}`) is {}: node coordinates are read in Cartesian definition systems only",
                    cs.label,
                    cs.name,
                    cs.kind.name()
                )));
            }
            at = to_part(cs, at);
            out.nodes.insert(node, at);
            out.turned.coordinates += 1;
        }
        if ns.displacement != 0 {
            let cs = system(ns.displacement, "displacement")?;
            // local components → Cartesian components of `cs`: columns
            let local: [[f64; 3]; 3] = match cs.kind {
                CsKind::Cartesian => {
                    out.turned.cartesian += 1;
                    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
                }
                CsKind::Cylindrical => {
                    let q = from_part(cs, at);
                    let r = q[0].hypot(q[1]);
                    let scale = q[0].abs().max(q[1].abs()).max(q[2].abs());
                    if r.is_nan() || r <= 1e-12 * scale {
                        return Err(err(format!(
                            "lies on the axis of its cylindrical displacement coordinate system {} (`{}`): its radial and tangential directions are undefined",
                            cs.label, cs.name
                        )));
                    }
                    let (c, s) = (q[0] / r, q[1] / r);
                    out.turned.cylindrical += 1;
                    // rows: Cartesian component; columns: radial, tangential, axial
                    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
                }
                CsKind::Spherical => {
                    return Err(err(format!(
                        "displacement coordinate system {} (`{}`) is spherical: displacements are read in Cartesian and cylindrical systems only; export them in the part system or a Cartesian system",
                        cs.label, cs.name
                    )));
                }
            };
            // part component c of local component l: Σ_i axes[i][c] local[i][l]
            let t: [[f64; 3]; 3] = std::array::from_fn(|c| {
                std::array::from_fn(|l| (0..3).map(|i| cs.axes[i][c] * local[i][l]).sum())
            });
            turn.insert(node, t);
        }
    }
    out.node_systems = node_systems;
    if turn.is_empty() {
        return Ok(());
    }
    for m in &mut out.modes {
        for (node, u) in m.shape.iter_mut() {
            if let Some(t) = turn.get(node) {
                *u = std::array::from_fn(|c| (0..3).map(|l| t[c][l] * u[l]).sum());
            }
        }
    }
    Ok(())
}
