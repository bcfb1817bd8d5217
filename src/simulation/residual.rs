//! Residual flexibility ([`super::SolverOptions::residual_above_hz`]): the
//! modes above a cut-off replaced by their static contribution.

use super::{GA, GB, SQRT3};
use crate::convolution::Influence;
use crate::error::SceneError;
use crate::scene::Scene;

/// The modes kept in the convolution and the residual compliance
/// `Σ_dropped A_k / ω_k²` (m/N, row-major P x P; empty when none is dropped).
pub(super) fn split_residual(
    scene: &Scene,
    modes: Vec<crate::scene::Mode>,
    above_hz: Option<f64>,
) -> Result<(Vec<crate::scene::Mode>, Vec<f64>), SceneError> {
    let Some(fc) = above_hz else {
        return Ok((modes, Vec::new()));
    };
    let invalid = |expected: String| SceneError::Invalid {
        file: scene.name.clone(),
        errors: vec![crate::error::FieldError {
            field: "solver_options.residual_above_hz".into(),
            value: format!("{fc}"),
            expected,
        }],
    };
    if !(fc.is_finite() && fc > 0.0) {
        return Err(invalid("a finite frequency > 0 Hz".into()));
    }
    let lowest = modes
        .iter()
        .map(|m| m.freq_hz)
        .fold(f64::INFINITY, f64::min);
    if modes.iter().all(|m| m.freq_hz > fc) {
        return Err(invalid(format!(
            "a frequency that keeps at least one mode (the lowest is {lowest} Hz)"
        )));
    }
    let p = scene.num_points();
    let mut residual = vec![0.0; p * p];
    let mut kept = Vec::with_capacity(modes.len());
    for m in modes {
        if m.freq_hz <= fc {
            kept.push(m);
            continue;
        }
        let w2 = (std::f64::consts::TAU * m.freq_hz).powi(2);
        for (i, row) in m.residue_matrix().iter().enumerate().take(p) {
            for (j, a) in row.iter().enumerate().take(p) {
                residual[i * p + j] += a / w2;
            }
        }
    }
    if residual.iter().all(|&c| c == 0.0) {
        residual.clear();
    }
    Ok((kept, residual))
}

/// Adds the residual compliance `c` (P x P) to the influence of Gauss-point
/// forces over a step `tau_s`: the end value `-GB q1 + GA q2` on the
/// displacement, the slope `√3 (q2 - q1) / τ` on the velocity.
pub(super) fn add_residual(g: &mut Influence, c: &[f64], tau_s: f64) {
    let rate = SQRT3 / tau_s;
    for (k, &ck) in c.iter().enumerate() {
        g.gx1[k] += -GB * ck;
        g.gx2[k] += GA * ck;
        g.gv1[k] += -rate * ck;
        g.gv2[k] += rate * ck;
    }
}
