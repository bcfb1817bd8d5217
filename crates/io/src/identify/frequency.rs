//! Measured FRFs -> modal model in the frequency domain (method §6.5): the
//! file's FRFs read in their own ordinate ([`read_frfs`]), poles by LSCF
//! over a stabilisation diagram, refined with the LSFD residues, real modal
//! constants of every measured pair, the driving-point check, and — when a
//! driving point allows it — mode shapes scaled by it: the contact model,
//! the full Green matrix between the measured degrees of freedom by modal
//! synthesis (`A_k = φ_k φ_kᵀ`, method §6.5.3).

use super::driving::{self, DrivingPoint, NEGLIGIBLE};
use crate::readers::measured::DataError;
use crate::readers::measured::frf::{Dof, FrfRequest, MeasuredFrfs, read_frfs};
use faer::c64;
use std::path::Path;
use tirecontact_core::base::modal::Mode;
use tirecontact_core::model::lscf::{
    self, ComplexFit, FitError, FitOptions, FrfSet, KeptPole, Pole, RealFit,
};
use tirecontact_core::model::stability::DiagramOrder;
use web_time::Instant;

/// Largest relative L2 error (over the band, all pairs) of the complex fit
/// or of the contact model for a fit to be kept without `--accept` (-).
pub const MAX_FIT_ERROR: f64 = 0.1;

/// Smallest ratio of a mode's term to the fit's residual over the mode's
/// half-power band ([`term_to_residual`]) for it to be a mode the data
/// show (-).
pub const MIN_TERM_TO_RESIDUAL: f64 = 3.0;

/// The half-width of the band of [`term_to_residual`] at least, in
/// frequency lines.
pub const NOISE_BAND_LINES: f64 = 2.0;

/// Gauss-Newton steps of the pole refinement ([`lscf::refine`]).
pub const REFINE_ITERATIONS: usize = 20;

/// Why a fitted pole is not listed as a mode: drawn in the diagram and
/// reported, but no mode, and out of the driving-point check and the
/// contact model.
#[derive(Debug, Clone, PartialEq)]
pub enum PoleFlag {
    /// Its damping ratio is at or above the fit's limit (or not positive):
    /// a term that fits noise or the residual of modes outside the band.
    Damping { limit: f64 },
    /// The refinement moved it out of the band (Hz).
    OutsideBand { band_hz: (f64, f64) },
    /// The refinement brought it within the frequency tolerance of the
    /// mode at `into_hz`, which has the larger term in the data: one
    /// physical pole fitted twice, merged into that mode.
    Split { into_hz: f64 },
    /// Its term stands no higher than the noise around it: over its
    /// half-power band (at least two lines each side) the term is `ratio`
    /// times the fit's residual there, below [`MIN_TERM_TO_RESIDUAL`]
    /// ([`term_to_residual`]).
    Noise { ratio: f64 },
}

impl std::fmt::Display for PoleFlag {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use tirecontact_core::base::error::fmt_sig;
        match self {
            PoleFlag::Damping { limit } => write!(
                f,
                "damping ratio outside 0 to {}: not a mode (a structural mode's half-power band would cover {} % of its frequency)",
                fmt_sig(*limit, 6),
                fmt_sig(200.0 * limit, 3)
            ),
            PoleFlag::OutsideBand { band_hz } => write!(
                f,
                "outside the band {} to {} Hz: not a mode",
                fmt_sig(band_hz.0, 6),
                fmt_sig(band_hz.1, 6)
            ),
            PoleFlag::Split { into_hz } => write!(
                f,
                "a split of the mode at {into_hz:.3} Hz (within the frequency tolerance, a smaller term): merged into it"
            ),
            PoleFlag::Noise { ratio } => write!(
                f,
                "its term over its half-power band (two lines each side at least) is {} times the fit's residual there: expected at least {MIN_TERM_TO_RESIDUAL}; noise the fit absorbed, not a mode",
                fmt_sig(*ratio, 3)
            ),
        }
    }
}

/// A fitted pole that is not a mode, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct FlaggedPole {
    pub pole: Pole,
    pub why: PoleFlag,
}

/// How a listed mode persists through the stabilisation diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct Persistence {
    /// The order its pole was taken at.
    pub order: usize,
    /// The consecutive orders `(first, last)` at which it is stable.
    pub stable_orders: (usize, usize),
    /// Other poles of that order within the frequency tolerance (Hz): a
    /// split pole, merged.
    pub split_hz: Vec<f64>,
}

/// Options of [`identify_frfs`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FrfOptions {
    pub request: FrfRequest,
    pub fit: FitOptions,
}

/// Why no contact model is built from the fit (the fit itself stands).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactError {
    #[error(
        "no driving point (an FRF whose response node and direction are its reference's): the mode shapes cannot be scaled; measured pairs: {pairs}"
    )]
    NoDrivingPoint { pairs: String },
    #[error(
        "driving point {dof}: every mode's residue is negative: the response or reference direction is probably reversed (--flip-direction {node})"
    )]
    Negative { dof: Dof, node: i64 },
    #[error(
        "driving point {dof}: the residues change sign from mode to mode (negative at {modes}): the data have no valid driving point; no contact model is built"
    )]
    Mixed { dof: Dof, modes: String },
    #[error(
        "{dof}: no FRF with the driving point {driving}: expected a row or a column through the driving point"
    )]
    Unlinked { dof: Dof, driving: Dof },
    #[error("no mode kept: nothing to build a contact model of")]
    NoModes,
}

/// A refused identification: the file, or the fit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FrfError {
    #[error(transparent)]
    Data(#[from] DataError),
    #[error("{file}: {source}")]
    Fit {
        file: String,
        #[source]
        source: FitError,
    },
}

/// The contact model: mode shapes at the measured degrees of freedom.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactModel {
    /// The model's points, in order.
    pub dofs: Vec<Dof>,
    /// Real modes with shapes (`φ_k`, 1/√kg).
    pub modes: Vec<Mode>,
    /// The model at the measured pairs, `[pair][frequency]`.
    pub fit: Vec<Vec<c64>>,
    /// Its relative L2 error over the band, all pairs (-).
    pub error: f64,
    /// Modes left out, and why.
    pub notes: Vec<String>,
}

/// A frequency-domain identification of a file's FRFs.
#[derive(Debug, Clone)]
pub struct FrfIdentification {
    pub data: MeasuredFrfs,
    pub diagram: Vec<DiagramOrder>,
    /// The polynomial order whose poles were kept.
    pub order: usize,
    /// The modes: the kept poles, refined, by frequency; none flagged.
    pub poles: Vec<Pole>,
    /// How each mode persists through the diagram (as `poles`).
    pub persistence: Vec<Persistence>,
    /// Fitted poles that are not modes, and why.
    pub flagged: Vec<FlaggedPole>,
    /// The frequency lines' spacing (Hz): a mode whose half-power width
    /// `2ξf` is below two lines has a damping the data cannot resolve.
    pub line_hz: f64,
    /// The options of the fit (the rule's tolerances).
    pub options: FitOptions,
    /// Complex residues with residual terms.
    pub complex: ComplexFit,
    /// Real modal constants without residual terms.
    pub real: RealFit,
    /// The check of every driving point.
    pub driving: Vec<(Dof, DrivingPoint)>,
    pub contact: Result<ContactModel, ContactError>,
    pub elapsed_s: f64,
}

impl FrfIdentification {
    /// Whether mode `k`'s half-power width `2ξf` is below two frequency
    /// lines: its damping is then set by the fit's model, not resolved by
    /// the data (it moves with band and order).
    pub fn unresolved(&self, k: usize) -> bool {
        self.poles
            .get(k)
            .is_some_and(|p| half_power_width_hz(p) < 2.0 * self.line_hz)
    }

    /// Whether the fit is good enough to keep without `--accept`: both
    /// errors within [`MAX_FIT_ERROR`].
    pub fn is_good(&self) -> bool {
        let contact = self.contact.as_ref().map_or(0.0, |c| c.error);
        self.complex.error <= MAX_FIT_ERROR && contact <= MAX_FIT_ERROR && !self.poles.is_empty()
    }
}

/// Reads and fits `path` (module docs).
pub fn identify_frfs(path: &Path, opts: &FrfOptions) -> Result<FrfIdentification, FrfError> {
    let start = Instant::now();
    let data = read_frfs(path, &opts.request)?;
    let fit_err = |source: FitError| FrfError::Fit {
        file: path.display().to_string(),
        source,
    };
    let diagram = lscf::stabilisation(&data.set, data.band_hz, &opts.fit).map_err(fit_err)?;
    let selection = lscf::keep(&diagram, lscf::references(&data.set.pairs), &opts.fit);
    let order = selection.order;
    let selected: Vec<Pole> = selection.kept.iter().map(|k| k.pole.clone()).collect();
    let (refined, complex) =
        lscf::refine(&data.set, &selected, REFINE_ITERATIONS).map_err(fit_err)?;
    let limits = Limits {
        band_hz: data.band_hz,
        max_damping_ratio: opts.fit.max_damping_ratio,
        freq_tol: opts.fit.freq_tol,
    };
    let (mut poles, mut flagged) = flag(&data.set, refined, &complex, &limits);
    let complex = if flagged.is_empty() {
        complex
    } else {
        // the modes refined again without the flagged poles; any pole the
        // second refinement flags is left out and the rest fitted once more
        let (again, fit) = lscf::refine(&data.set, &poles, REFINE_ITERATIONS).map_err(fit_err)?;
        let (kept, more) = flag(&data.set, again, &fit, &limits);
        poles = kept;
        if more.is_empty() {
            fit
        } else {
            flagged.extend(more);
            lscf::lsfd(&data.set, &poles).map_err(fit_err)?
        }
    };
    flagged.sort_by(|a, b| a.pole.freq_hz.total_cmp(&b.pole.freq_hz));
    let persistence = poles
        .iter()
        .map(|p| persistence_of(p, &selection.kept))
        .collect();
    let f = &data.set.freq_hz;
    let line_hz = if f.len() > 1 {
        (f[f.len() - 1] - f[0]) / (f.len() - 1) as f64
    } else {
        0.0
    };
    let real = lscf::real_modes(&data.set, &poles).map_err(fit_err)?;
    let driving = driving_points(&data, &real);
    let contact = contact_model(&data.set, &data.dofs, &poles, &real, &driving);
    Ok(FrfIdentification {
        data,
        diagram,
        order,
        poles,
        persistence,
        flagged,
        line_hz,
        options: opts.fit.clone(),
        complex,
        real,
        driving,
        contact,
        elapsed_s: start.elapsed().as_secs_f64(),
    })
}

/// The half-power width `2ξf` of a pole (Hz).
pub fn half_power_width_hz(p: &Pole) -> f64 {
    2.0 * p.damping_ratio * p.freq_hz
}

/// What a refined pole must meet to be a mode.
struct Limits {
    band_hz: (f64, f64),
    max_damping_ratio: f64,
    freq_tol: f64,
}

/// The refined poles split into modes (by frequency) and flagged poles:
/// damping outside `0 < ξ < max_damping_ratio`, outside the band, or
/// within the frequency tolerance of a mode with a larger term in `fit`.
fn flag(
    set: &FrfSet,
    poles: Vec<Pole>,
    fit: &ComplexFit,
    limits: &Limits,
) -> (Vec<Pole>, Vec<FlaggedPole>) {
    let size = lscf::contributions(set, &poles, fit);
    let mut flagged = Vec::new();
    let mut modes: Vec<(Pole, f64)> = Vec::new();
    for (k, (p, s)) in poles.into_iter().zip(size).enumerate() {
        let why = if !(p.damping_ratio > 0.0 && p.damping_ratio < limits.max_damping_ratio) {
            Some(PoleFlag::Damping {
                limit: limits.max_damping_ratio,
            })
        } else if !(limits.band_hz.0..=limits.band_hz.1).contains(&p.freq_hz) {
            Some(PoleFlag::OutsideBand {
                band_hz: limits.band_hz,
            })
        } else {
            let ratio = term_to_residual(set, &p, fit, k);
            (ratio < MIN_TERM_TO_RESIDUAL).then_some(PoleFlag::Noise { ratio })
        };
        match why {
            Some(why) => flagged.push(FlaggedPole { pole: p, why }),
            None => modes.push((p, s)),
        }
    }
    // largest terms first: a smaller pole within the tolerance of a larger
    // one is its split
    modes.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut kept: Vec<Pole> = Vec::new();
    for (p, _) in modes {
        match kept
            .iter()
            .find(|k| (k.freq_hz - p.freq_hz).abs() <= limits.freq_tol * k.freq_hz)
        {
            Some(k) => flagged.push(FlaggedPole {
                why: PoleFlag::Split { into_hz: k.freq_hz },
                pole: p,
            }),
            None => kept.push(p),
        }
    }
    kept.sort_by(|a, b| a.freq_hz.total_cmp(&b.freq_hz));
    (kept, flagged)
}

/// The size of pole `k`'s term in the complex fit `fit` against the noise
/// around it: the L2 norm over every pair of its term
/// ([`lscf::mode_term`]) over the lines of its half-power band, `|f − f_k|
/// <= ξ_k f_k` widened to [`NOISE_BAND_LINES`] lines each side, over the
/// norm of the fit's residual (data less fit) on the same lines (-). A
/// pole fitted to noise takes a share of the noise there and stands about
/// as high as what is left; a mode the data show stands above it. Infinite
/// when the residual there is zero (exact data).
pub fn term_to_residual(set: &FrfSet, pole: &Pole, fit: &ComplexFit, k: usize) -> f64 {
    let f = &set.freq_hz;
    let line_hz = if f.len() > 1 {
        (f[f.len() - 1] - f[0]) / (f.len() - 1) as f64
    } else {
        0.0
    };
    let half = (pole.damping_ratio.abs() * pole.freq_hz).max(NOISE_BAND_LINES * line_hz);
    let lines: Vec<usize> = (0..f.len())
        .filter(|&i| (f[i] - pole.freq_hz).abs() <= half)
        .collect();
    let term = lscf::mode_term(set, pole, &fit.residues, k);
    let (mut t2, mut r2) = (0.0, 0.0);
    for (pair, h) in set.h.iter().enumerate() {
        for &i in &lines {
            t2 += term[pair][i].norm_sqr();
            r2 += (h[i] - fit.fit[pair][i]).norm_sqr();
        }
    }
    if r2 > 0.0 {
        (t2 / r2).sqrt()
    } else if t2 > 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

/// The persistence of the kept pole nearest `p` in frequency.
fn persistence_of(p: &Pole, kept: &[KeptPole]) -> Persistence {
    kept.iter()
        .min_by(|a, b| {
            (a.pole.freq_hz - p.freq_hz)
                .abs()
                .total_cmp(&(b.pole.freq_hz - p.freq_hz).abs())
        })
        .map_or(
            Persistence {
                order: 0,
                stable_orders: (0, 0),
                split_hz: Vec::new(),
            },
            |k| Persistence {
                order: k.order,
                stable_orders: k.stable_orders,
                split_hz: k.split_hz.clone(),
            },
        )
}

/// The check of every measured driving point on the real modal constants.
fn driving_points(data: &MeasuredFrfs, real: &RealFit) -> Vec<(Dof, DrivingPoint)> {
    data.set
        .pairs
        .iter()
        .enumerate()
        .filter(|(_, (a, b))| a == b)
        .map(|(k, &(a, _))| (data.dofs[a], driving::check_values(&real.constants[k])))
        .collect()
}

/// Mode shapes scaled by the driving points (method §6.5.3, eq. LSFD-3):
/// `φ_k(n) = A_k(n, d) / √A_k(d, d)`, `d` the driving point with the
/// largest residue of mode `k`; every driving point must be positive.
fn contact_model(
    set: &FrfSet,
    dofs: &[Dof],
    poles: &[Pole],
    real: &RealFit,
    driving: &[(Dof, DrivingPoint)],
) -> Result<ContactModel, ContactError> {
    if poles.is_empty() {
        return Err(ContactError::NoModes);
    }
    if driving.is_empty() {
        return Err(ContactError::NoDrivingPoint {
            pairs: set
                .pairs
                .iter()
                .map(|&(a, b)| format!("{} / {}", dofs[a], dofs[b]))
                .collect::<Vec<_>>()
                .join(", "),
        });
    }
    for (dof, d) in driving {
        match d {
            DrivingPoint::Positive => {}
            DrivingPoint::NoModes => return Err(ContactError::NoModes),
            DrivingPoint::Negative => {
                return Err(ContactError::Negative {
                    dof: *dof,
                    node: dof.node,
                });
            }
            DrivingPoint::Mixed { negative_modes } => {
                return Err(ContactError::Mixed {
                    dof: *dof,
                    modes: negative_modes
                        .iter()
                        .map(|&k| format!("mode {k} ({:.2} Hz)", poles[k].freq_hz))
                        .collect::<Vec<_>>()
                        .join(", "),
                });
            }
        }
    }
    let pair = |a: usize, b: usize| {
        set.pairs
            .iter()
            .position(|&p| p == (a, b))
            .or_else(|| set.pairs.iter().position(|&p| p == (b, a)))
    };
    let drive_idx: Vec<(usize, usize)> = driving
        .iter()
        .map(|(dof, _)| {
            let i = dofs.iter().position(|d| d == dof).unwrap_or(0);
            (i, pair(i, i).unwrap_or(0))
        })
        .collect();
    let largest = drive_idx
        .iter()
        .flat_map(|&(_, k)| real.constants[k].iter().copied())
        .fold(0.0_f64, f64::max);
    let mut modes = Vec::new();
    let mut kept = Vec::new();
    let mut notes = Vec::new();
    for (m, pole) in poles.iter().enumerate() {
        let Some(&(d, kd)) = drive_idx
            .iter()
            .max_by(|a, b| real.constants[a.1][m].total_cmp(&real.constants[b.1][m]))
        else {
            continue;
        };
        let add = real.constants[kd][m];
        if add <= NEGLIGIBLE * largest {
            notes.push(format!(
                "mode {m} ({:.2} Hz) left out of the contact model: its driving-point residue {add:.3e} 1/kg is within {NEGLIGIBLE} of the largest (a node line: its shape cannot be scaled)",
                pole.freq_hz
            ));
            continue;
        }
        let root = add.sqrt();
        let mut shape = Vec::with_capacity(dofs.len());
        for (n, dof) in dofs.iter().enumerate() {
            let k = pair(n, d).ok_or(ContactError::Unlinked {
                dof: *dof,
                driving: dofs[d],
            })?;
            shape.push(real.constants[k][m] / root);
        }
        modes.push(Mode {
            freq_hz: pole.freq_hz,
            damping_ratio: pole.damping_ratio,
            residue: Vec::new(),
            shape,
        });
        kept.push(pole.clone());
    }
    if modes.is_empty() {
        return Err(ContactError::NoModes);
    }
    let constants: Vec<Vec<f64>> = set
        .pairs
        .iter()
        .map(|&(a, b)| modes.iter().map(|m| m.shape[a] * m.shape[b]).collect())
        .collect();
    let fit = lscf::synthesise_real(set, &kept, &constants);
    let error = lscf::relative_error(&set.h, &fit);
    Ok(ContactModel {
        dofs: dofs.to_vec(),
        modes,
        fit,
        error,
        notes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use tirecontact_core::model::lscf::Ordinate;
    use tirecontact_core::model::stability::Stability;

    fn pole(freq_hz: f64, damping_ratio: f64) -> Pole {
        Pole {
            freq_hz,
            damping_ratio,
            stability: Stability::Stable,
        }
    }

    /// One mode at 50 Hz (ξ = 0.01) in receptance, 30 to 200 Hz every 1 Hz;
    /// fitted poles holding it, an over-damped pole (ξ = 44.5), a pole
    /// above the band and a split of the mode: the mode alone is kept.
    #[test]
    fn over_damped_out_of_band_and_split_poles_are_flagged_not_modes() {
        let freq_hz: Vec<f64> = (30..=200).map(f64::from).collect();
        let w0 = std::f64::consts::TAU * 50.0;
        let h = vec![
            freq_hz
                .iter()
                .map(|f| {
                    let w = std::f64::consts::TAU * f;
                    c64::new(1.0, 0.0) / c64::new(w0 * w0 - w * w, 2.0 * 0.01 * w0 * w)
                })
                .collect(),
        ];
        let set = FrfSet {
            freq_hz,
            ordinate: Ordinate::Receptance,
            pairs: vec![(0, 0)],
            h,
        };
        let poles = vec![
            pole(37.0, 44.5),
            pole(50.0, 0.01),
            pole(50.3, 0.01),
            pole(1065.0, 0.01),
        ];
        let fit = lscf::lsfd(&set, &poles).unwrap();
        let limits = Limits {
            band_hz: (30.0, 200.0),
            max_damping_ratio: 0.2,
            freq_tol: 0.01,
        };
        let (modes, flagged) = flag(&set, poles, &fit, &limits);
        assert_eq!(modes.len(), 1, "{modes:?}");
        assert!((modes[0].freq_hz - 50.0).abs() <= 0.3);
        let why: Vec<String> = flagged.iter().map(|f| f.why.to_string()).collect();
        assert_eq!(flagged.len(), 3, "{why:?}");
        assert!(
            flagged
                .iter()
                .any(|f| f.pole.freq_hz == 37.0 && why[0].contains("0 to 0.2")),
            "{why:?}"
        );
        assert!(
            why.iter()
                .any(|w| w.contains("outside the band 30 to 200 Hz"))
        );
        assert!(why.iter().any(|w| w.contains("merged into")));
        assert!(matches!(flagged[0].why, PoleFlag::Damping { .. }));
    }
}
