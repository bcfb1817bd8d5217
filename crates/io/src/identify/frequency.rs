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
    self, ComplexFit, FitError, FitOptions, FrfSet, Pole, RealFit,
};
use tirecontact_core::model::stability::DiagramOrder;
use web_time::Instant;

/// Largest relative L2 error (over the band, all pairs) of the complex fit
/// or of the contact model for a fit to be kept without `--accept` (-).
pub const MAX_FIT_ERROR: f64 = 0.1;

/// Gauss-Newton steps of the pole refinement ([`lscf::refine`]).
pub const REFINE_ITERATIONS: usize = 20;

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
    /// The kept poles, refined.
    pub poles: Vec<Pole>,
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
    let (order, selected) = lscf::select(&diagram, &opts.fit);
    let (poles, complex) =
        lscf::refine(&data.set, &selected, REFINE_ITERATIONS).map_err(fit_err)?;
    let real = lscf::real_modes(&data.set, &poles).map_err(fit_err)?;
    let driving = driving_points(&data, &real);
    let contact = contact_model(&data.set, &data.dofs, &poles, &real, &driving);
    Ok(FrfIdentification {
        data,
        diagram,
        order,
        poles,
        complex,
        real,
        driving,
        contact,
        elapsed_s: start.elapsed().as_secs_f64(),
    })
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
