//! Spectra against closed forms: tones of known amplitude and frequency,
//! Parseval, third-octave bands of flat and white spectra and of a tone.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::f64::consts::{SQRT_2, TAU};
use tirecontact::analysis::spectrum::{Window, spectrum, third_octave_bands};

fn tone(n: usize, fs: f64, f: f64, amp: f64, phase: f64, offset: f64) -> Vec<f64> {
    (0..n)
        .map(|k| offset + amp * (TAU * f * k as f64 / fs + phase).sin())
        .collect()
}

fn rms_db(amp: f64) -> f64 {
    20.0 * (amp / SQRT_2).log10()
}

#[test]
fn on_bin_sinusoid_reads_its_level_and_frequency() {
    let (n, fs) = (6000, 20_000.0);
    let df = fs / n as f64;
    for window in [Window::Hann, Window::Rectangular] {
        for (bin, amp) in [(37usize, 3.7), (301, 0.02), (1500, 120.0)] {
            let f = bin as f64 * df;
            let x = tone(n, fs, f, amp, 0.3, 5.0);
            let s = spectrum(&x, fs, window, true).unwrap();
            let levels = s.levels_db(1.0);
            let peak = (1..levels.len())
                .max_by(|&a, &b| levels[a].total_cmp(&levels[b]))
                .unwrap();
            assert!(
                (s.freq_hz[peak] - f).abs() <= df,
                "{window:?}: peak at {}",
                s.freq_hz[peak]
            );
            let err = levels[bin] - rms_db(amp);
            assert!(
                err.abs() < 0.1,
                "{window:?} bin {bin}: level error {err} dB"
            );
            assert!(err.abs() < 1e-9, "on-bin reading is exact: {err} dB");
            assert!((s.removed_mean - 5.0).abs() < 1e-9);
        }
    }
}

#[test]
fn off_bin_sinusoid_tone_power_within_a_tenth_of_a_db() {
    let (n, fs) = (8191, 25_000.0); // odd, prime length: not a power of two
    let df = fs / n as f64;
    let mut worst = 0.0f64;
    for frac in [0.0, 0.13, 0.25, 0.37, 0.5, 0.71, 0.9] {
        let f = (410.0 + frac) * df;
        let amp = 2.5;
        let x = tone(n, fs, f, amp, 1.1, 0.0);
        let s = spectrum(&x, fs, Window::Hann, true).unwrap();
        let t = s.tone(f, 5.0 * df).unwrap();
        assert!(
            (t.freq_hz - f).abs() <= df,
            "frac {frac}: {} vs {f}",
            t.freq_hz
        );
        let err = 10.0 * (t.mean_square / (amp * amp / 2.0)).log10();
        worst = worst.max(err.abs());
        assert!(err.abs() < 0.1, "frac {frac}: {err} dB");
        // the plain bin reading suffers the Hann scalloping loss (1.42 dB at half a bin)
        if frac == 0.5 {
            let k = (t.freq_hz / df).round() as usize;
            let scallop = rms_db(amp) - s.levels_db(1.0)[k];
            assert!((scallop - 1.42).abs() < 0.05, "scalloping {scallop} dB");
        }
    }
    eprintln!("worst off-bin tone level error: {worst:.2e} dB");
}

fn windowed_mean_square(x: &[f64], w: &[f64]) -> f64 {
    let num: f64 = x.iter().zip(w).map(|(a, b)| a * a * b * b).sum();
    let den: f64 = w.iter().map(|b| b * b).sum();
    num / den
}

#[test]
fn parseval_psd_integral_equals_mean_square() {
    let mut rng = StdRng::seed_from_u64(7);
    for n in [1024usize, 1001, 4099] {
        let x: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.3).collect();
        let fs = 1234.5;
        // rectangular window: the plain mean square
        let s = spectrum(&x, fs, Window::Rectangular, false).unwrap();
        let ms = x.iter().map(|v| v * v).sum::<f64>() / n as f64;
        let rel = (s.mean_square() - ms).abs() / ms;
        eprintln!("N = {n}: Parseval relative error {rel:.1e} (rectangular)");
        assert!(rel < 1e-10, "N = {n}: {rel}");
        // Hann: the window-weighted mean square, window built here independently
        let w: Vec<f64> = (0..n)
            .map(|k| 0.5 - 0.5 * (TAU * k as f64 / n as f64).cos())
            .collect();
        let s = spectrum(&x, fs, Window::Hann, false).unwrap();
        let ms = windowed_mean_square(&x, &w);
        let rel = (s.mean_square() - ms).abs() / ms;
        eprintln!("N = {n}: Parseval relative error {rel:.1e} (Hann)");
        assert!(rel < 1e-10, "N = {n} Hann: {rel}");
        // the mean removed, against the de-meaned record
        let mean = x.iter().sum::<f64>() / n as f64;
        let xd: Vec<f64> = x.iter().map(|v| v - mean).collect();
        let s = spectrum(&x, fs, Window::Hann, true).unwrap();
        let ms = windowed_mean_square(&xd, &w);
        assert!((s.mean_square() - ms).abs() < 1e-10 * ms);
        // Hann ENBW is 1.5 bins
        assert!((s.enbw_hz / s.df_hz - 1.5).abs() < 1e-12);
    }
}

#[test]
fn iec_third_octave_centres_and_edges() {
    let nominal = [
        20.0, 25.0, 31.5, 40.0, 50.0, 63.0, 80.0, 100.0, 125.0, 160.0, 200.0, 250.0, 315.0, 400.0,
        500.0, 630.0, 800.0, 1000.0, 1250.0, 1600.0, 2000.0, 2500.0, 3150.0, 4000.0, 5000.0,
    ];
    let bands = third_octave_bands(20.0, 5000.0);
    let got: Vec<f64> = bands.iter().map(|b| b.nominal_hz).collect();
    assert_eq!(got, nominal);
    for b in &bands {
        // exact centre within 2 % of the nominal one, G = 10^(3/10) base-10 ratios
        assert!((b.centre_hz / b.nominal_hz - 1.0).abs() < 0.02, "{b:?}");
        assert!((b.upper_hz / b.lower_hz - 10f64.powf(0.1)).abs() < 1e-12);
        assert!(
            (b.lower_hz * b.upper_hz - b.centre_hz * b.centre_hz).abs()
                < 1e-9 * b.centre_hz * b.centre_hz
        );
    }
    for w in bands.windows(2) {
        assert!((w[0].upper_hz - w[1].lower_hz).abs() < 1e-9 * w[1].lower_hz);
    }
    assert_eq!(bands[17].centre_hz, 1000.0);
}

#[test]
fn flat_multisine_band_levels_match_closed_form() {
    // every bin 1..N/2-1 carries a cosine of amplitude a (random phase): with
    // the rectangular window the one-sided PSD is exactly a²/2 / Δf, so a
    // band [lo, hi] holds a²/2 (hi - lo) / Δf.
    let (n, fs) = (16384usize, 16384.0);
    let df = fs / n as f64;
    let a = 0.01;
    let mut rng = StdRng::seed_from_u64(3);
    let phases: Vec<f64> = (0..n / 2).map(|_| rng.random::<f64>() * TAU).collect();
    // x_n = Σ_k a cos(2π k n / N + φ_k), built by an inverse FFT (the direct
    // sum is O(N²)) and spot-checked against the direct sum below.
    use rustfft::FftPlanner;
    use rustfft::num_complex::Complex64;
    let mut spec = vec![Complex64::new(0.0, 0.0); n];
    for k in 1..n / 2 {
        let c = Complex64::from_polar(0.5 * a, phases[k]);
        spec[k] = c;
        spec[n - k] = c.conj();
    }
    FftPlanner::<f64>::new()
        .plan_fft_inverse(n)
        .process(&mut spec);
    let x: Vec<f64> = spec.iter().map(|c| c.re).collect();
    // spot check one sample against the direct sum
    let x5: f64 = (1..n / 2)
        .map(|k| a * (TAU * k as f64 * 5.0 / n as f64 + phases[k]).cos())
        .sum();
    assert!((x[5] - x5).abs() < 1e-12);
    let s = spectrum(&x, fs, Window::Rectangular, false).unwrap();
    for b in s.third_octave_levels(20.0, 5000.0, 1.0) {
        let expect = 0.5 * a * a * (b.band.upper_hz - b.band.lower_hz) / df;
        let err = b.level_db - 10.0 * expect.log10();
        assert!(err.abs() < 1e-9, "band {}: {err} dB", b.band.nominal_hz);
        assert!(b.resolved);
    }
}

#[test]
fn white_noise_band_levels_match_closed_form() {
    // Gaussian white noise of variance σ²: one-sided PSD 2σ²/f_s.
    let (n, fs, sigma) = (1 << 16, 16384.0, 0.7);
    let mut rng = StdRng::seed_from_u64(11);
    let x: Vec<f64> = (0..n / 2)
        .flat_map(|_| {
            let (u1, u2): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
            let r = sigma * (-2.0 * u1.ln()).sqrt();
            [r * (TAU * u2).cos(), r * (TAU * u2).sin()]
        })
        .collect();
    let s = spectrum(&x, fs, Window::Hann, true).unwrap();
    for b in s.third_octave_levels(315.0, 2000.0, 1.0) {
        let expect = 2.0 * sigma * sigma / fs * (b.band.upper_hz - b.band.lower_hz);
        let err = b.level_db - 10.0 * expect.log10();
        // ~ (bandwidth / ENBW) independent chi² values: a few % in power
        assert!(err.abs() < 0.6, "band {}: {err} dB", b.band.nominal_hz);
    }
}

#[test]
fn sinusoid_band_level_and_neighbours() {
    let (n, fs) = (20000usize, 50_000.0);
    let amp = 40.0;
    let x = tone(n, fs, 997.0, amp, 0.2, 300.0);
    let s = spectrum(&x, fs, Window::Hann, true).unwrap();
    let levels = s.third_octave_levels(20.0, 5000.0, 1.0);
    let at = |nominal: f64| {
        levels
            .iter()
            .find(|b| b.band.nominal_hz == nominal)
            .unwrap()
    };
    let err = at(1000.0).level_db - rms_db(amp);
    assert!(err.abs() < 0.01, "1 kHz band: {err} dB");
    assert!(at(800.0).level_db < rms_db(amp) - 60.0);
    assert!(at(1250.0).level_db < rms_db(amp) - 60.0);
    // a sinusoid of amplitude A has an RMS level 20 log10(A / √2) re 1 unit
    assert!((rms_db(amp) - (20.0 * amp.log10() - 10.0 * 2f64.log10())).abs() < 1e-12);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    assert!(spectrum(&[1.0; 3], 100.0, Window::Hann, true).is_err());
    assert!(spectrum(&[1.0; 64], 0.0, Window::Hann, true).is_err());
    let mut x = vec![0.0; 64];
    x[10] = f64::NAN;
    let e = spectrum(&x, 100.0, Window::Hann, true).unwrap_err();
    assert!(e.to_string().contains("sample 10"), "{e}");
    assert!(third_octave_bands(-1.0, 10.0).is_empty());
}

/// The one-sided spectrum by the definition: an O(N²) DFT with the window
/// written out here (periodic Hann `sin²(πn/N)`), independent of the FFT.
fn naive(x: &[f64], fs: f64, hann: bool) -> (Vec<f64>, Vec<f64>) {
    let n = x.len();
    let w: Vec<f64> = (0..n)
        .map(|k| {
            if hann {
                (std::f64::consts::PI * k as f64 / n as f64).sin().powi(2)
            } else {
                1.0
            }
        })
        .collect();
    let (s1, s2) = (w.iter().sum::<f64>(), w.iter().map(|v| v * v).sum::<f64>());
    let (mut psd, mut amp) = (Vec::new(), Vec::new());
    for k in 0..=n / 2 {
        let (mut re, mut im) = (0.0, 0.0);
        for (m, (&xm, &wm)) in x.iter().zip(&w).enumerate() {
            let ang = TAU * (k * m % n) as f64 / n as f64;
            re += xm * wm * ang.cos();
            im -= xm * wm * ang.sin();
        }
        let one_sided = if k == 0 || 2 * k == n { 1.0 } else { 2.0 };
        psd.push(one_sided * (re * re + im * im) / (fs * s2));
        amp.push(one_sided * re.hypot(im) / s1);
    }
    (psd, amp)
}

#[test]
fn short_and_awkward_lengths_match_the_direct_dft() {
    // radix-2, mixed radix, primes (Rader / Bluestein inside the FFT), odd
    // and even: the FFT's spectrum against the definition, both windows
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    for n in [8usize, 9, 12, 15, 16, 17, 97, 210, 1009] {
        let x: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0) + 0.3).collect();
        for window in [Window::Rectangular, Window::Hann] {
            let s = spectrum(&x, 1000.0, window, false).unwrap();
            let (psd, amp) = naive(&x, 1000.0, matches!(window, Window::Hann));
            assert_eq!(s.psd.len(), n / 2 + 1, "N = {n}");
            let pmax = psd.iter().cloned().fold(0.0, f64::max);
            let amax = amp.iter().cloned().fold(0.0, f64::max);
            for k in 0..psd.len() {
                assert!(
                    (s.psd[k] - psd[k]).abs() <= 1e-12 * pmax
                        && (s.amplitude[k] - amp[k]).abs() <= 1e-12 * amax,
                    "N = {n}, {window:?}, bin {k}: psd {} vs {}, amplitude {} vs {}",
                    s.psd[k],
                    psd[k],
                    s.amplitude[k],
                    amp[k]
                );
            }
        }
    }
}

#[test]
fn dc_nyquist_and_odd_length_top_bin_read_their_amplitudes() {
    // x = B + A (-1)^n, even N, no window: amplitude B at DC, A at Nyquist,
    // levels with no √2 (not sinusoids)
    let (b, a, n) = (0.7, 0.25, 64);
    let x: Vec<f64> = (0..n)
        .map(|k| b + if k % 2 == 0 { a } else { -a })
        .collect();
    let s = spectrum(&x, 512.0, Window::Rectangular, false).unwrap();
    assert!((s.amplitude[0] - b).abs() < 1e-14, "{}", s.amplitude[0]);
    assert!(
        (s.amplitude[n / 2] - a).abs() < 1e-14,
        "{}",
        s.amplitude[n / 2]
    );
    let db = s.levels_db(1.0);
    assert!((db[0] - 20.0 * b.log10()).abs() < 1e-12);
    assert!((db[n / 2] - 20.0 * a.log10()).abs() < 1e-12);
    // odd N: the top bin (N-1)/2 is a sinusoid (one-sided factor 2)
    for n in [4099usize, 99] {
        for k in [(n - 1) / 2, n / 3] {
            let fs = n as f64;
            let x = tone(n, fs, k as f64, 1.3, 0.4, 0.0);
            let s = spectrum(&x, fs, Window::Rectangular, false).unwrap();
            assert!(
                (s.amplitude[k] - 1.3).abs() < 1e-11,
                "N = {n}, bin {k}: {}",
                s.amplitude[k]
            );
        }
    }
}
