//! Frequency-domain identification of measured FRFs (method §6.5): poles by
//! the polyreference least-squares complex-frequency method (LSCF, the
//! "PolyMAX" form: a right matrix-fraction model in the z-domain basis with
//! real coefficients, normal equations reduced per output) over a
//! stabilisation diagram; residues of every measured pair by least squares
//! in the frequency domain (LSFD) with lower and upper residual terms; and
//! real (proportional) modal constants without residual terms, the form a
//! contact model uses.
//!
//! Every fit is made in the ordinate the data hold (receptance, mobility,
//! accelerance): the pole-residue model is multiplied by `(jω)^q`
//! (method §6.5.2), the data are never divided by `ω`.

use crate::base::linalg::LinalgError;
use crate::model::stability::{Criteria, DiagramPole, Matching, PersistenceRule};
use faer::c64;
use std::f64::consts::TAU;

mod poles;
mod residues;
pub use crate::model::stability::{KeptPole, Selection};
pub use poles::{keep, references, select, stabilisation};
pub use residues::{
    ComplexFit, NEGLIGIBLE_MODE, RealFit, contributions, lsfd, mode_term, real_modes, refine,
    relative_error, synthesise_real,
};

/// What an FRF's values are: response over force, the response
/// displacement (`q = 0`), velocity (`q = 1`) or acceleration (`q = 2`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ordinate {
    Receptance,
    Mobility,
    Accelerance,
}

impl Ordinate {
    /// The power `q` of `jω` that makes a receptance this ordinate.
    pub fn power(self) -> i32 {
        match self {
            Ordinate::Receptance => 0,
            Ordinate::Mobility => 1,
            Ordinate::Accelerance => 2,
        }
    }

    /// Its SI unit.
    pub fn units(self) -> &'static str {
        match self {
            Ordinate::Receptance => "m/N",
            Ordinate::Mobility => "m/(s·N)",
            Ordinate::Accelerance => "m/(s²·N)",
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Ordinate::Receptance => "receptance",
            Ordinate::Mobility => "mobility",
            Ordinate::Accelerance => "accelerance",
        }
    }

    /// `(jω)^q` at `ω` (rad/s).
    pub fn factor(self, omega: f64) -> c64 {
        let jw = c64::new(0.0, omega);
        match self {
            Ordinate::Receptance => c64::new(1.0, 0.0),
            Ordinate::Mobility => jw,
            Ordinate::Accelerance => jw * jw,
        }
    }
}

/// FRFs of measured pairs over one band, in SI, in one ordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfSet {
    /// Frequencies (Hz), increasing, all `> 0`.
    pub freq_hz: Vec<f64>,
    pub ordinate: Ordinate,
    /// `(response, reference)` of each FRF, indices of the caller's degrees
    /// of freedom.
    pub pairs: Vec<(usize, usize)>,
    /// `H[pair][frequency]`.
    pub h: Vec<Vec<c64>>,
}

/// A fit that cannot be made: the input, or a decomposition.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("{0}")]
    Input(String),
    #[error(transparent)]
    Linalg(#[from] LinalgError),
}

/// Options of the frequency-domain fit (method §6.5).
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// Highest polynomial order of the stabilisation diagram, as a pole
    /// count: each order `p` gives `p·N_i` poles (`N_i` the references of
    /// the polyreference model), the diagram goes to `max_order / N_i`.
    pub max_order: usize,
    /// The polynomial order whose poles are kept; `None`: the diagram's
    /// highest.
    pub order: Option<usize>,
    /// Largest damping ratio of a kept pole (-).
    pub max_damping_ratio: f64,
    /// Stable: relative frequency change between orders (-).
    pub freq_tol: f64,
    /// Stable: relative damping change between orders (-).
    pub damping_tol: f64,
    /// Stable: smallest MAC of the participation vectors (-), when there
    /// are several references.
    pub mac_min: f64,
    /// A kept pole is stable (frequency, damping, vector) at this many
    /// consecutive orders, the last of them the chosen order or one of the
    /// `persist` below it.
    pub persist: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            max_order: 40,
            order: None,
            max_damping_ratio: 0.2,
            freq_tol: 0.01,
            damping_tol: 0.05,
            mac_min: 0.98,
            persist: crate::model::stability::PERSIST,
        }
    }
}

impl FitOptions {
    /// The stabilisation criteria of LSCF (method §6.5.1): the options'
    /// tolerances on the participation vectors' MAC, each pole taking the
    /// best category any pole of the order below gives it (a polyreference
    /// model of a low-rank matrix has close twins of a physical pole; the
    /// nearest in frequency may be the twin).
    pub fn stability_criteria(&self) -> Criteria {
        Criteria {
            freq_tol: self.freq_tol,
            damping_tol: self.damping_tol,
            mac_min: self.mac_min,
            matching: Matching::Best,
        }
    }

    /// The persistence rule of the kept poles (method §6.5.1): the
    /// frequency tolerance and `persist`.
    pub fn persistence(&self) -> PersistenceRule {
        PersistenceRule {
            freq_tol: self.freq_tol,
            persist: self.persist,
        }
    }
}

/// A pole `λ = −ξω + jω√(1−ξ²)` found by LSCF: a pole of the
/// stabilisation diagram, with its category against the order below.
pub type Pole = DiagramPole;

/// Checks a set's shape and values.
fn check(set: &FrfSet) -> Result<(), FitError> {
    let nf = set.freq_hz.len();
    if set.pairs.is_empty() || set.pairs.len() != set.h.len() {
        return Err(FitError::Input("no FRFs to fit".into()));
    }
    if nf < 8 {
        return Err(FitError::Input(format!(
            "{nf} frequencies in the band: expected at least 8"
        )));
    }
    if set.freq_hz.iter().any(|f| !(f.is_finite() && *f > 0.0))
        || set.freq_hz.windows(2).any(|w| w[1] <= w[0])
    {
        return Err(FitError::Input(
            "frequencies: expected increasing values above 0 Hz".into(),
        ));
    }
    for h in &set.h {
        if h.len() != nf {
            return Err(FitError::Input(format!(
                "an FRF of {} values: expected one per frequency ({nf})",
                h.len()
            )));
        }
        if h.iter().any(|v| !(v.re.is_finite() && v.im.is_finite())) {
            return Err(FitError::Input("an FRF holds a non-finite value".into()));
        }
    }
    Ok(())
}

/// Modal assurance criterion of two complex vectors (-).
pub fn mac(a: &[c64], b: &[c64]) -> f64 {
    let dot: c64 = a.iter().zip(b).map(|(x, y)| x.conj() * y).sum();
    let na: f64 = a.iter().map(|v| v.norm_sqr()).sum();
    let nb: f64 = b.iter().map(|v| v.norm_sqr()).sum();
    if na > 0.0 && nb > 0.0 {
        dot.norm_sqr() / (na * nb)
    } else {
        1.0
    }
}

/// `ω` (rad/s) of each frequency.
fn omegas(set: &FrfSet) -> Vec<f64> {
    set.freq_hz.iter().map(|f| TAU * f).collect()
}

#[cfg(test)]
mod tests {
    use super::poles::layout;
    use super::*;

    #[test]
    fn layouts_pick_the_references_of_the_polyreference_model() {
        // a row, a column, an incomplete matrix: one reference
        for pairs in [
            vec![(0, 0), (0, 1), (0, 2)],
            vec![(0, 0), (1, 0), (2, 0)],
            vec![(0, 0), (0, 1), (1, 1)],
        ] {
            let l = layout(&pairs);
            assert!(l.rows.iter().all(|r| r.len() == 1), "{pairs:?}");
            assert_eq!(l.rows.len(), pairs.len());
        }
        // 3 responses × 2 references: two references, three outputs
        let pairs: Vec<(usize, usize)> = (0..3).flat_map(|o| (3..5).map(move |i| (o, i))).collect();
        let l = layout(&pairs);
        assert_eq!((l.rows.len(), l.rows[0].len()), (3, 2));
        assert_eq!(pairs[l.rows[2][1]], (2, 4));
        // 2 responses × 3 references: swapped by reciprocity
        let pairs: Vec<(usize, usize)> = (0..2).flat_map(|o| (2..5).map(move |i| (o, i))).collect();
        let l = layout(&pairs);
        assert_eq!((l.rows.len(), l.rows[0].len()), (3, 2));
        assert_eq!(pairs[l.rows[0][1]], (1, 2));
    }

    #[test]
    fn ordinates_multiply_by_powers_of_j_omega() {
        let w = 3.0;
        assert_eq!(Ordinate::Receptance.factor(w), c64::new(1.0, 0.0));
        assert_eq!(Ordinate::Mobility.factor(w), c64::new(0.0, 3.0));
        assert_eq!(Ordinate::Accelerance.factor(w), c64::new(-9.0, 0.0));
        let a = [c64::new(1.0, 2.0), c64::new(-0.5, 0.0)];
        let b: Vec<c64> = a.iter().map(|v| v * c64::new(0.0, -3.0)).collect();
        assert!((mac(&a, &b) - 1.0).abs() < 1e-15);
        assert!(mac(&a, &[c64::new(0.0, 0.0), c64::new(1.0, 0.0)]) < 0.1);
    }

    #[test]
    fn bad_sets_are_refused_not_panicked_on() {
        let good = FrfSet {
            freq_hz: (1..=10).map(f64::from).collect(),
            ordinate: Ordinate::Receptance,
            pairs: vec![(0, 0)],
            h: vec![vec![c64::new(1.0, 0.0); 10]],
        };
        let mut nan = good.clone();
        nan.h[0][3].re = f64::NAN;
        let mut short = good.clone();
        short.freq_hz.truncate(5);
        short.h[0].truncate(5);
        let mut zero = good.clone();
        zero.freq_hz[0] = 0.0;
        let mut ragged = good.clone();
        ragged.h[0].pop();
        for (set, want) in [
            (nan, "non-finite"),
            (short, "5 frequencies"),
            (zero, "above 0 Hz"),
            (ragged, "9 values"),
        ] {
            let e = stabilisation(&set, (0.0, 10.0), &FitOptions::default())
                .unwrap_err()
                .to_string();
            assert!(e.contains(want), "{e}");
            assert!(lsfd(&set, &[]).is_err());
        }
        // no poles: the fit is the residual terms alone, finite
        let fit = lsfd(&good, &[]).unwrap();
        assert!(fit.error.is_finite());
    }
}
