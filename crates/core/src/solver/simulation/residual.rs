//! Residual flexibility ([`super::SolverOptions::residual_above_hz`]): the
//! modes above a cut-off replaced by their static contribution.

use super::{GA, GB, SQRT3};
use crate::model::convolution::Influence;
use crate::solver::error::BuildError;
use crate::solver::problem::Problem;

/// The modes kept in the convolution and the residual compliance
/// `Σ_dropped A_k / ω_k²` (m/N, row-major P x P; empty when none is dropped).
pub(super) fn split_residual(
    problem: &Problem,
    modes: Vec<crate::base::modal::Mode>,
    above_hz: Option<f64>,
) -> Result<(Vec<crate::base::modal::Mode>, Vec<f64>), BuildError> {
    let Some(fc) = above_hz else {
        return Ok((modes, Vec::new()));
    };
    let invalid = |expected: String| BuildError::Option {
        problem: problem.name.clone(),
        error: crate::base::error::FieldError {
            field: "solver_options.residual_above_hz".into(),
            value: format!("{fc}"),
            expected,
        },
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
    let p = problem.num_points();
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

/// Whether the residual compliance `c` (P x P, row-major) restricted to the
/// points `set` is positive definite: a Cholesky factorisation whose every
/// pivot is above `1e-9` of the largest diagonal entry. Then each point of
/// `set` meets the road through a massless static compliance in every
/// direction, and a landing needs no impulse (see `Simulation::impact`).
/// `scratch` (at least `|set|²` values) holds the factor: no allocation.
pub(super) fn compliant_on(c: &[f64], p: usize, set: &[usize], scratch: &mut [f64]) -> bool {
    let n = set.len();
    let scale = set.iter().map(|&i| c[i * p + i]).fold(0.0, f64::max);
    if scale.is_nan() || scale <= 0.0 || scale.is_infinite() {
        return false;
    }
    // lower triangle, row-major n x n
    let l = &mut scratch[..n * n];
    for a in 0..n {
        for b in 0..=a {
            let mut s = c[set[a] * p + set[b]];
            for k in 0..b {
                s -= l[a * n + k] * l[b * n + k];
            }
            if a == b {
                if s.is_nan() || s <= 1e-9 * scale {
                    return false;
                }
                l[a * n + a] = s.sqrt();
            } else {
                l[a * n + b] = s / l[b * n + b];
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::compliant_on;

    #[test]
    fn compliance_is_definite_only_with_every_direction_compliant() {
        // 3 x 3: a positive definite block on {0, 2}, rank 1 on {0, 1}
        let c = [
            2.0, 2.0, 1.0, //
            2.0, 2.0, 0.5, //
            1.0, 0.5, 3.0,
        ];
        assert!(compliant_on(&c, 3, &[0], &mut [0.0; 9]));
        assert!(compliant_on(&c, 3, &[0, 2], &mut [0.0; 9]));
        assert!(compliant_on(&c, 3, &[2, 1], &mut [0.0; 9]));
        // det of {0, 1} is 0: a rigid direction
        assert!(!compliant_on(&c, 3, &[0, 1], &mut [0.0; 9]));
        assert!(!compliant_on(&c, 3, &[0, 1, 2], &mut [0.0; 9]));
        // no compliance at all, or a NaN
        assert!(!compliant_on(&[0.0; 9], 3, &[1], &mut [0.0; 9]));
        let mut nan = c;
        nan[4] = f64::NAN;
        assert!(!compliant_on(&nan, 3, &[1], &mut [0.0; 9]));
        // indefinite
        let ind = [1.0, 2.0, 2.0, 1.0];
        assert!(!compliant_on(&ind, 2, &[0, 1], &mut [0.0; 9]));
    }
}
