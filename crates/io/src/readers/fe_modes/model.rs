//! The modal model at the scene's points of the modes an FE export holds
//! (method §5.4): the modes kept, the node of each point, the shapes
//! converted to SI and mass-normalised.

use super::uff_shapes::grouped;
use super::{
    FeDamping, FeFile, FeModel, FeModesError, FeModesSpec, FeNodes, FeShapeUnits,
    MAX_FE_DAMPING_RATIO, MAX_FE_FREQ_HZ, MAX_FE_MODES, MAX_SHAPE, ModeRead, ModeRecord, NodeMap,
};
use tirecontact_core::base::modal::Mode;

/// The modal model at `points` of the modes `fe` holds (method §5.4).
pub fn build(
    spec: &FeModesSpec,
    fe: &FeFile,
    points: &[(f64, f64)],
) -> Result<FeModel, FeModesError> {
    if fe.modes.is_empty() {
        return Err(FeModesError::NoModes {
            file: spec.file.display().to_string(),
            holds: fe.holds(),
        });
    }
    let mut notes = Vec::new();
    let (c_l, c_f) = unit_factors(fe, &mut notes);
    systems_notes(fe, &mut notes);
    let c_m = c_f / c_l;
    let kept = kept_modes(spec, fe, &mut notes)?;
    check_per_mode(spec, kept.len())?;
    let mapping = map_nodes(spec, fe, &kept, points, c_l)?;
    notes.push(format!(
        "FE axes: x_m along {}, y_m across {}, u along {} (away from the road)",
        spec.axes.along.name(),
        spec.axes.across.name(),
        spec.direction.name()
    ));
    let mut modes = Vec::with_capacity(kept.len());
    let mut read = Vec::with_capacity(kept.len());
    for (k, m) in kept.iter().enumerate() {
        let (mode, as_read) = scaled_mode(spec, m, k, &mapping, c_l, c_m)?;
        modes.push(mode);
        read.push(as_read);
    }
    notes.push(shapes_note(spec, c_l, c_m));
    Ok(FeModel {
        modes,
        read,
        mapping,
        length_factor: c_l,
        force_factor: c_f,
        mass_factor: c_m,
        notes,
        datasets_read: grouped(&fe.read),
        datasets_skipped: grouped(&fe.other),
    })
}

/// The coordinate systems the displacements and coordinates were turned
/// from, and the modes written as complex data, noted.
fn systems_notes(fe: &FeFile, notes: &mut Vec<String>) {
    let t = &fe.turned;
    if t.cartesian + t.cylindrical > 0 {
        notes.push(format!(
            "displacements of {} nodes turned to the part system from their displacement coordinate systems (dataset 2420: {} Cartesian, {} cylindrical)",
            t.cartesian + t.cylindrical,
            t.cartesian,
            t.cylindrical
        ));
    }
    if t.coordinates > 0 {
        notes.push(format!(
            "coordinates of {} nodes (dataset 15) turned to the part system from their definition coordinate systems",
            t.coordinates
        ));
    }
    if fe.complex_modes > 0 {
        notes.push(format!(
            "{} modes written as complex data read as real normal modes: imaginary parts at most {:e} of each mode's largest real part",
            fe.complex_modes, fe.largest_imaginary_ratio
        ));
    }
}

/// The file's length and force factors (dataset 164, else SI), noted.
fn unit_factors(fe: &FeFile, notes: &mut Vec<String>) -> (f64, f64) {
    match &fe.units {
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
    }
}

/// The modes inside `spec.band_hz`, by increasing frequency: each mode
/// number once, each frequency in range, some and not too many.
fn kept_modes<'a>(
    spec: &FeModesSpec,
    fe: &'a FeFile,
    notes: &mut Vec<String>,
) -> Result<Vec<&'a ModeRecord>, FeModesError> {
    let file = spec.file.display().to_string();
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
    Ok(kept)
}

/// The lists given per mode (modal masses, damping ratios) against the
/// `n` modes kept.
fn check_per_mode(spec: &FeModesSpec, n: usize) -> Result<(), FeModesError> {
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
    Ok(())
}

/// Mode `k` kept, `m`, at the points' nodes: its modal mass (stated or the
/// record's), its shape along `direction` in SI normalised to it, its
/// damping ratio; and the mode as read.
fn scaled_mode(
    spec: &FeModesSpec,
    m: &ModeRecord,
    k: usize,
    mapping: &[NodeMap],
    c_l: f64,
    c_m: f64,
) -> Result<(Mode, ModeRead), FeModesError> {
    let file = || spec.file.display().to_string();
    let mass_kg = match spec.modal_mass_kg.as_slice() {
        [] if m.modal_mass > 0.0 && m.modal_mass.is_finite() => m.modal_mass / c_m,
        [] => {
            return Err(FeModesError::NoModalMass {
                file: file(),
                record: m.record,
                mode: m.mode_number,
                freq_hz: m.freq_hz,
            });
        }
        [one] => *one,
        v => v[k],
    };
    let scale = match spec.shape_units {
        FeShapeUnits::Consistent => 1.0 / mass_kg.sqrt(),
        FeShapeUnits::LengthPerSqrtKg => 1.0 / (c_l * mass_kg.sqrt()),
    };
    let id = spec.direction.index();
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
            file: file(),
            record: m.record,
            mode: m.mode_number,
            node: mapping[k].node,
            value: *v,
        });
    }
    let damping_ratio = spec.damping.ratio(k, m.freq_hz, m.viscous_damping);
    if !(damping_ratio.is_finite() && (0.0..=MAX_FE_DAMPING_RATIO).contains(&damping_ratio)) {
        return Err(FeModesError::Damping {
            file: file(),
            record: m.record,
            mode: m.mode_number,
            freq_hz: m.freq_hz,
            ratio: damping_ratio,
        });
    }
    let mode = Mode {
        freq_hz: m.freq_hz,
        damping_ratio,
        residue: Vec::new(),
        shape,
    };
    let read = ModeRead {
        record: m.record,
        dataset: m.dataset,
        mode_number: m.mode_number,
        freq_hz: m.freq_hz,
        modal_mass_kg: mass_kg,
        damping_ratio,
    };
    Ok((mode, read))
}

/// How the shapes were converted and normalised: by the stated modal
/// masses when `tyre.modal_mass_kg` gives them, else by the records'.
fn shapes_note(spec: &FeModesSpec, c_l: f64, c_m: f64) -> String {
    format!(
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
        if spec.modal_mass_kg.is_empty() {
            "the records' modal masses (÷ the mass factor to kg)"
        } else {
            "the stated modal masses (tyre.modal_mass_kg)"
        }
    )
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
