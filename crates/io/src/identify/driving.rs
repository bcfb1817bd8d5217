//! The driving-point check: at a driving point (response node and
//! direction = reference node and direction) every mode's residue is
//! `φ_k,i² / m_k > 0` (method §6: `A_k = φ_k φ_kᵀ`), so the signs of the
//! identified `A_k[i][i]` tell whether the data can scale mode shapes.

use tirecontact_core::base::modal::Mode;

/// What the residues at one driving point say.
#[derive(Debug, Clone, PartialEq)]
pub enum DrivingPoint {
    /// Every mode's residue positive: the data can scale the shapes.
    Positive,
    /// Every residue negative: the response or reference direction is
    /// probably reversed (`--flip-direction`).
    Negative,
    /// Residues of both signs: the modes (0-based) with negative ones; no
    /// contact model can be built from this point.
    Mixed { negative_modes: Vec<usize> },
    /// No counted mode with a residue at the point (no stable mode, or
    /// every one on a node line): nothing is checked, so nothing passes.
    NoModes,
}

/// Residues smaller than this share of the point's largest are not
/// counted: a point on a mode's node line has `φ_k,i ≈ 0`, and noise
/// gives its residue either sign.
pub const NEGLIGIBLE: f64 = 0.02;

/// The check at point `i` over the modes `k` with `counted[k]` (the
/// stable ones): residues `A_k[i][i]` of `modes`, those within
/// [`NEGLIGIBLE`] of the largest not counted.
pub fn check(modes: &[Mode], counted: &[bool], i: usize) -> DrivingPoint {
    let a: Vec<f64> = modes
        .iter()
        .zip(counted)
        .map(|(m, &c)| if c { m.residue_matrix()[i][i] } else { 0.0 })
        .collect();
    check_values(&a)
}

/// The check of one driving point's residues `a[k]` (one per counted
/// mode), those within [`NEGLIGIBLE`] of the largest not counted.
pub fn check_values(a: &[f64]) -> DrivingPoint {
    let tol = NEGLIGIBLE * a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let negative_modes: Vec<usize> = (0..a.len()).filter(|&k| a[k] < -tol).collect();
    let positive = a.iter().filter(|&&v| v > tol).count();
    match (positive, negative_modes.len()) {
        (0, 0) => DrivingPoint::NoModes,
        (_, 0) => DrivingPoint::Positive,
        (0, _) => DrivingPoint::Negative,
        _ => DrivingPoint::Mixed { negative_modes },
    }
}

/// A sentence on the check at the point named `name` (`node 101 +Z`).
pub fn describe(d: &DrivingPoint, name: &str, node: i64) -> String {
    match d {
        DrivingPoint::Positive => {
            format!("driving point {name}: every stable mode's residue positive")
        }
        DrivingPoint::Negative => format!(
            "driving point {name}: every stable mode's residue negative: the response or reference direction is probably reversed (--flip-direction {node})"
        ),
        DrivingPoint::NoModes => format!(
            "driving point {name}: no stable mode has a residue here: nothing to check; no contact model is built from it"
        ),
        DrivingPoint::Mixed { negative_modes } => format!(
            "driving point {name}: stable modes' residues change sign from mode to mode (negative at modes {negative_modes:?}): the data have no valid driving point here; no contact model is built from it"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mode(a00: f64) -> Mode {
        Mode {
            freq_hz: 50.0,
            damping_ratio: 0.01,
            residue: vec![vec![a00, 0.1], vec![0.1, 1.0]],
            shape: Vec::new(),
        }
    }

    #[test]
    fn the_check_tells_positive_negative_and_mixed_residues_apart() {
        let all = [true; 4];
        // a node line's residue (-0.01 of 3) is not counted
        let pos = [mode(1.0), mode(0.2), mode(3.0), mode(-0.01)];
        let neg = [mode(-1.0), mode(-0.2)];
        let mixed = [mode(1.0), mode(-0.2), mode(3.0), mode(-1.0)];
        assert_eq!(check(&pos, &all, 0), DrivingPoint::Positive);
        assert_eq!(check(&neg, &all, 0), DrivingPoint::Negative);
        // no counted mode: nothing passes
        assert_eq!(check(&pos, &[false; 4], 0), DrivingPoint::NoModes);
        assert_eq!(check_values(&[]), DrivingPoint::NoModes);
        assert_eq!(check_values(&[0.0, 0.0]), DrivingPoint::NoModes);
        let s = describe(&DrivingPoint::NoModes, "node 3 +Z", 3);
        assert!(
            s.contains("no stable mode") && !s.contains("positive"),
            "{s}"
        );
        // unstable modes are not counted
        assert_eq!(
            check(&mixed, &[true, false, true, false], 0),
            DrivingPoint::Positive
        );
        assert_eq!(
            check(&mixed, &all, 0),
            DrivingPoint::Mixed {
                negative_modes: vec![1, 3]
            }
        );
        // the other point of the mixed set is positive throughout
        assert_eq!(check(&mixed, &all, 1), DrivingPoint::Positive);
        // shapes give positive driving points whatever their signs
        let shaped = Mode {
            freq_hz: 10.0,
            damping_ratio: 0.0,
            residue: Vec::new(),
            shape: vec![-0.7, 0.4],
        };
        assert_eq!(check(&[shaped], &all, 0), DrivingPoint::Positive);
        let s = describe(&check(&neg, &all, 0), "node 101 +Z", 101);
        assert!(
            s.contains("node 101 +Z") && s.contains("--flip-direction 101"),
            "{s}"
        );
        let s = describe(&check(&mixed, &all, 0), "node 7 -Y", 7);
        assert!(s.contains("node 7 -Y") && s.contains("[1, 3]"), "{s}");
    }
}
