//! DTFT magnitudes of sampled responses at a few frequencies (the fit
//! report's `|G(f)|` errors, method §6).
//!
//! `dt Σ_n g_n e^{-iΩ n dt}` needs the phasor `e^{-iΩ n dt}` of every sample:
//! one `sin_cos` per (frequency, sample, response) was half of an
//! identification's time. Here the phasors of a frequency are built once for
//! all responses, by rotation from the previous sample and a direct
//! `sin_cos` every [`ANCHOR_EVERY`] samples (the rotations' round-off stays
//! near 1e-15), then each response is a dot product with them.

use faer::Mat;
use std::f64::consts::TAU;

/// Samples between direct evaluations of the phasor.
const ANCHOR_EVERY: usize = 64;

/// `|dt Σ_n g_n e^{-iΩ n dt}|` of each column of `m` (samples `g_n` down the
/// column) at each of `freqs_hz`: row `f`, column `c`.
pub(super) fn dtft_magnitudes(m: &Mat<f64>, dt: f64, freqs_hz: &[f64]) -> Mat<f64> {
    let len = m.nrows();
    let mut out = Mat::zeros(freqs_hz.len(), m.ncols());
    let (mut cos, mut sin) = (vec![0.0; len], vec![0.0; len]);
    for (f, &freq) in freqs_hz.iter().enumerate() {
        let w = TAU * freq * dt;
        let (s1, c1) = w.sin_cos();
        for n in 0..len {
            if n % ANCHOR_EVERY == 0 {
                (sin[n], cos[n]) = (w * n as f64).sin_cos();
            } else {
                // angle addition: (n - 1) w + w
                (sin[n], cos[n]) = (
                    sin[n - 1] * c1 + cos[n - 1] * s1,
                    cos[n - 1] * c1 - sin[n - 1] * s1,
                );
            }
        }
        for c in 0..m.ncols() {
            let g = m.col(c);
            let (mut re, mut im) = (0.0, 0.0);
            for n in 0..len {
                re += g[n] * cos[n];
                im -= g[n] * sin[n];
            }
            out[(f, c)] = dt * re.hypot(im);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition, one `sin_cos` per term (the control).
    fn direct(m: &Mat<f64>, dt: f64, freqs_hz: &[f64]) -> Mat<f64> {
        Mat::from_fn(freqs_hz.len(), m.ncols(), |f, c| {
            let w = TAU * freqs_hz[f] * dt;
            let (mut re, mut im) = (0.0, 0.0);
            for (n, g) in m.col(c).iter().enumerate() {
                let (s, co) = (w * n as f64).sin_cos();
                re += g * co;
                im -= g * s;
            }
            dt * re.hypot(im)
        })
    }

    #[test]
    fn rotated_phasors_give_the_direct_dtft() {
        // decaying oscillations (as impulse responses are) of mixed sign and
        // scale, 3000 samples, frequencies up to near Nyquist
        let (len, dt) = (3000, 1.0 / 4096.0);
        let m = Mat::from_fn(len, 4, |n, c| {
            let t = n as f64 * dt;
            let (f, a) = (60.0 + 90.0 * c as f64, 10f64.powi(c as i32 - 2));
            a * (-8.0 * t).exp() * (TAU * f * t + 0.3 * c as f64).sin()
        });
        let freqs: Vec<f64> = (0..120).map(|k| 1.0 + 17.0 * k as f64).collect();
        let (fast, slow) = (dtft_magnitudes(&m, dt, &freqs), direct(&m, dt, &freqs));
        let mut worst = 0.0f64;
        for c in 0..m.ncols() {
            let peak = (0..freqs.len()).map(|f| slow[(f, c)]).fold(0.0, f64::max);
            for f in 0..freqs.len() {
                worst = worst.max((fast[(f, c)] - slow[(f, c)]).abs() / peak);
            }
        }
        assert!(worst < 1e-12, "differs by {worst:e} of the peak");
        // and the spectrum is not trivial: a peak near each tone
        let at = |hz: f64| freqs.iter().position(|&f| f >= hz).unwrap_or(0);
        assert!(slow[(at(60.0), 0)] > 10.0 * slow[(at(900.0), 0)]);
    }
}
