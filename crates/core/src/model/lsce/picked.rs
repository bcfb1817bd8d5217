//! The modes of given poles (the poles picked on a stabilisation diagram),
//! their residues fitted to the responses, and the `|G|` of the responses:
//! what the identification workbench refits at every pick.

use super::dtft::dtft_magnitudes;
use super::fit::{OrderFit, data_matrix, fit_order};
use super::{LsceError, Pole, Responses, check_input};
use crate::base::modal::Mode;
use std::f64::consts::TAU;

/// The modes of a fit: each pole with its residues, the `P×P` matrix
/// filled from the pairs (and mirrored where only `i <= j` was given).
pub(super) fn modes_of_fit(r: &Responses, fit: &OrderFit) -> Vec<Mode> {
    let p = r.num_points;
    (0..fit.poles.len())
        .map(|c| {
            let mut a = vec![vec![0.0; p]; p];
            let mut seen = vec![vec![false; p]; p];
            for (col, &(i, j)) in r.pairs.iter().enumerate() {
                a[i][j] = fit.residues[(c, col)];
                seen[i][j] = true;
            }
            for (col, &(i, j)) in r.pairs.iter().enumerate() {
                if !seen[j][i] {
                    a[j][i] = fit.residues[(c, col)];
                }
            }
            Mode {
                freq_hz: fit.poles[c].freq_hz(),
                damping_ratio: fit.poles[c].xi,
                residue: a,
                shape: Vec::new(),
            }
        })
        .collect()
}

/// Modes with the poles `(freq_hz, damping_ratio)` given, their residues
/// fitted to the responses by least squares (the real modal form of
/// method §6), and the fit's relative time error: the modes picked on a
/// stabilisation diagram.
pub fn modes_of_poles(r: &Responses, poles: &[(f64, f64)]) -> Result<(Vec<Mode>, f64), LsceError> {
    let len = check_input(r)?;
    if let Some(&(f, xi)) = poles
        .iter()
        .find(|(f, xi)| !(f.is_finite() && *f > 0.0 && xi.is_finite() && *xi >= 0.0 && *xi < 1.0))
    {
        return Err(LsceError::Input(format!(
            "pole {f} Hz, damping {xi}: expected f > 0 Hz and 0 <= damping < 1"
        )));
    }
    let data = data_matrix(r, len);
    let poles: Vec<Pole> = poles
        .iter()
        .map(|&(f, xi)| Pole { omega: TAU * f, xi })
        .collect();
    let fit = fit_order(poles, &data, r.dt_s, true)?;
    Ok((modes_of_fit(r, &fit), fit.time_error))
}

/// `|G(f)|` of each response (the DTFT of its samples, m/N) at `freqs_hz`:
/// one vector per response, in the order of `r.pairs`.
pub fn response_magnitudes(r: &Responses, freqs_hz: &[f64]) -> Result<Vec<Vec<f64>>, LsceError> {
    let len = check_input(r)?;
    let m = dtft_magnitudes(&data_matrix(r, len), r.dt_s, freqs_hz);
    Ok((0..m.ncols())
        .map(|c| (0..m.nrows()).map(|f| m[(f, c)]).collect())
        .collect())
}
