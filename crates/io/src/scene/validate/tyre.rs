//! Validation of a scene's tyre: its fields, its modes, and the points and
//! contact it allows.

use super::Validator;
use crate::scene::{Contact, MAX_RING_RESPONSE_VALUES, Mode, Point, Tyre};
use std::path::Path;
use tirecontact_core::base::error::fmt_num;
use tirecontact_core::model::lsce::IdentifyOptions;
use tirecontact_core::model::ring::RingParams;

/// The tyre of a scene of `p` points.
pub(super) fn validate_tyre(v: &mut Validator, tyre: &Tyre, p: usize) {
    match tyre {
        Tyre::Modal { modes } => {
            if modes.is_empty() {
                v.push("tyre.modes", "[]", "at least one mode");
            }
            for (k, m) in modes.iter().enumerate() {
                validate_mode(v, &format!("tyre.modes[{k}]"), m, p);
            }
        }
        Tyre::Ring {
            ring,
            identification,
        } => validate_ring_tyre(v, ring, identification, p),
        Tyre::Measured {
            file,
            identification,
            nodes,
        } => validate_measured_tyre(v, file, identification, nodes, p),
        Tyre::Plate { plate } => v.errors.extend(plate.validate("tyre.plate")),
        Tyre::FeModes { .. } => validate_fe_tyre(v, tyre, p),
    }
}

/// The fields of an FE tyre (method §5.4) for `p` points; the file itself
/// is read when the model is prepared.
fn validate_fe_tyre(v: &mut Validator, tyre: &Tyre, p: usize) {
    use crate::readers::fe_modes::{FeDamping, FeNodes};
    let Some(spec) = tyre.fe_spec(None) else {
        return;
    };
    if spec.file.as_os_str().is_empty() {
        v.push(
            "tyre.file",
            "\"\"",
            "the path of a UFF file of normal modes (datasets 55 or 2414)",
        );
    }
    if let FeNodes::List(nodes) = &spec.nodes {
        validate_node_list(v, nodes, p, ", or Nearest");
    }
    let (along, across, normal) = (spec.axes.along, spec.axes.across, spec.direction);
    if along == across {
        v.push(
            "tyre.axes.across",
            across.name(),
            &format!("an FE axis other than along ({})", along.name()),
        );
    }
    if normal == along || normal == across {
        v.push(
            "tyre.direction",
            normal.name(),
            &format!(
                "the FE axis normal to the road, other than the axes along ({}) and across ({})",
                along.name(),
                across.name()
            ),
        );
    }
    let ratio = |v: &mut Validator, field: &str, x: f64| {
        if !(x.is_finite() && (0.0..=MAX_FE_DAMPING).contains(&x)) {
            v.push(field, x, "a damping ratio from 0 to 10");
        }
    };
    match &spec.damping {
        FeDamping::Ratio(x) => ratio(v, "tyre.damping.0", *x),
        FeDamping::Modal(list) => {
            if list.is_empty() {
                v.push("tyre.damping.0", "[]", "one damping ratio per mode kept");
            }
            for (k, x) in list.iter().enumerate() {
                ratio(v, &format!("tyre.damping.0[{k}]"), *x);
            }
        }
        FeDamping::Rayleigh {
            alpha_per_s,
            beta_s,
        } => {
            if !(alpha_per_s.is_finite() && *alpha_per_s >= 0.0) {
                v.push("tyre.damping.alpha_per_s", *alpha_per_s, "α >= 0 (1/s)");
            }
            if !(beta_s.is_finite() && *beta_s >= 0.0) {
                v.push("tyre.damping.beta_s", *beta_s, "β >= 0 (s)");
            }
        }
        FeDamping::FromFile => {}
    }
    for (k, m) in spec.modal_mass_kg.iter().enumerate() {
        if !(m.is_finite() && *m > 0.0) {
            v.push(
                &format!("tyre.modal_mass_kg[{k}]"),
                *m,
                "a modal mass > 0 kg",
            );
        }
    }
    let (lo, hi) = spec.band_hz;
    if lo.is_nan() || hi.is_nan() || lo < 0.0 || hi <= lo {
        v.push(
            "tyre.band_hz",
            format!("({lo}, {hi})"),
            "a band (lo, hi) in Hz with 0 <= lo < hi",
        );
    }
    if !(spec.nearest_within_m.is_finite() && spec.nearest_within_m > 0.0) {
        v.push(
            "tyre.nearest_within_m",
            spec.nearest_within_m,
            "a distance > 0 m",
        );
    }
}

/// Largest damping ratio an FE tyre may state.
const MAX_FE_DAMPING: f64 = 10.0;

/// The points of a plate tyre lie inside the belt (its edges do not move),
/// and rigid contact needs at least as many modes as points (the contact
/// system is the sum of one rank-one term per mode).
pub(super) fn validate_plate_points(
    v: &mut Validator,
    tyre: &Tyre,
    contact: &Contact,
    points: &[Point],
) {
    let Tyre::Plate { plate } = tyre else {
        return;
    };
    if !plate.validate("tyre.plate").is_empty() {
        return;
    }
    let half = 0.5 * plate.width_m;
    for (i, pt) in points.iter().enumerate() {
        if pt.y_m.is_finite() && pt.y_m.abs() >= half {
            v.push(
                &format!("points[{i}].y_m"),
                pt.y_m,
                &format!(
                    "a position inside the belt, |y_m| < width_m / 2 = {} m (its edges do not move)",
                    fmt_num(half)
                ),
            );
        }
    }
    if contact.is_rigid() {
        let k = plate.plate_modes().len();
        if points.len() > k {
            v.push(
                "contact",
                "Rigid",
                &format!(
                    "Compliant(stiffness_n_m: [...]) tread springs: rigid contact of {} points on a plate tyre of {k} modes is singular (at most as many points as modes); or raise tyre.plate.max_freq_hz",
                    points.len()
                ),
            );
        }
    }
}

/// A ring tyre of `p` points: the ring, the identification options, and the
/// size of the sampled responses that identification needs.
fn validate_ring_tyre(
    v: &mut Validator,
    ring: &RingParams,
    identification: &IdentifyOptions,
    p: usize,
) {
    v.errors.extend(ring.validate("tyre.ring"));
    let id_errors = identification.validate("tyre.identification");
    if id_errors.is_empty() {
        // identification samples the responses of every pair of points
        let n = identification.num_samples();
        let values = (p * (p + 1) / 2) as f64 * n as f64;
        if values > MAX_RING_RESPONSE_VALUES {
            let most = (0..=p)
                .rev()
                .find(|&q| (q * (q + 1) / 2) as f64 * n as f64 <= MAX_RING_RESPONSE_VALUES)
                .unwrap_or(0);
            v.push(
                "points",
                format!("{p} points"),
                &format!(
                    "at most {most} points with tyre: Ring at {n} samples per response (identification samples P(P+1)/2 responses: {values:.3e} values, at most {MAX_RING_RESPONSE_VALUES:e}, {} MB); use fewer points or a shorter tyre.identification.duration_s",
                    MAX_RING_RESPONSE_VALUES as u64 * 8 / 1_000_000
                ),
            );
        }
    }
    v.errors.extend(id_errors);
}

/// A measured tyre of `p` points: a file named, one distinct node per point
/// when nodes are given, and the identification options.
fn validate_measured_tyre(
    v: &mut Validator,
    file: &Path,
    identification: &IdentifyOptions,
    nodes: &[i64],
    p: usize,
) {
    if file.as_os_str().is_empty() {
        v.push(
            "tyre.file",
            "\"\"",
            "the path of a UFF 58 or CSV file of the tyre's responses",
        );
    }
    if !nodes.is_empty() {
        validate_node_list(v, nodes, p, "");
    }
    // the band against the data's Nyquist frequency, and the
    // samples, are checked when the file is read
    v.errors
        .extend(identification.validate_for_data("tyre.identification"));
}

/// `tyre.nodes` as a list: one node per point (`or_else`: the other form
/// the field takes, said after the count), none listed twice.
fn validate_node_list(v: &mut Validator, nodes: &[i64], p: usize, or_else: &str) {
    if nodes.len() != p {
        v.push(
            "tyre.nodes",
            format!("{} nodes", nodes.len()),
            &format!("one node number per point ({p}){or_else}"),
        );
    }
    for (k, a) in nodes.iter().enumerate() {
        if nodes[..k].contains(a) {
            v.push(
                &format!("tyre.nodes[{k}]"),
                a.to_string(),
                "a node not listed before",
            );
        }
    }
}

fn validate_mode(v: &mut Validator, at: &str, m: &Mode, p: usize) {
    if v.positive(
        &format!("{at}.freq_hz"),
        m.freq_hz,
        "a finite frequency > 0 Hz",
    ) && m.freq_hz > 1e6
    {
        v.push(&format!("{at}.freq_hz"), m.freq_hz, "a frequency <= 1e6 Hz");
    }
    if v.nonneg(
        &format!("{at}.damping_ratio"),
        m.damping_ratio,
        "a finite damping ratio >= 0 (0 undamped, 1 critical, > 1 overdamped)",
    ) && m.damping_ratio > 1e4
    {
        v.push(
            &format!("{at}.damping_ratio"),
            m.damping_ratio,
            "a damping ratio <= 1e4",
        );
    }
    match (m.residue.is_empty(), m.shape.is_empty()) {
        (true, true) => v.push(
            &format!("{at}.residue"),
            "(missing)",
            &format!("a {p}x{p} residue matrix or a shape of {p} values"),
        ),
        (false, false) => v.push(
            &format!("{at}.shape"),
            format!("{:?}", m.shape),
            "either `residue` or `shape`, not both",
        ),
        (false, true) => {
            if m.residue.len() != p || m.residue.iter().any(|r| r.len() != p) {
                let shape: Vec<usize> = m.residue.iter().map(Vec::len).collect();
                v.push(
                    &format!("{at}.residue"),
                    format!("{} rows of lengths {shape:?}", m.residue.len()),
                    &format!("a {p}x{p} matrix (one row and column per contact point)"),
                );
            }
            for (i, row) in m.residue.iter().enumerate() {
                for (j, a) in row.iter().enumerate() {
                    v.finite(
                        &format!("{at}.residue[{i}][{j}]"),
                        *a,
                        "a finite residue in 1/kg",
                    );
                }
            }
        }
        (true, false) => {
            if m.shape.len() != p {
                v.push(
                    &format!("{at}.shape"),
                    format!("{} values", m.shape.len()),
                    &format!("{p} values (one per contact point)"),
                );
            }
            for (i, a) in m.shape.iter().enumerate() {
                v.finite(
                    &format!("{at}.shape[{i}]"),
                    *a,
                    "a finite value in 1/sqrt(kg)",
                );
            }
        }
    }
}
