//! Spectra of uniformly sampled signals: one-sided amplitude and power
//! spectral density (PSD) of one windowed record (a single periodogram, no
//! averaging), third-octave band levels from the PSD, and the frequencies
//! worth marking on a spectrum of a run (road excitation `V/λ` and its
//! harmonics, modal frequencies).
//!
//! ## Definitions
//!
//! A record `x_n`, `n = 0..N-1`, sampled at `f_s`; window `w_n`;
//! `X_k = Σ_n w_n x_n e^{-2πikn/N}` (computed by `rustfft`); bin width
//! `Δf = f_s / N`; `S1 = Σ w_n`, `S2 = Σ w_n²`.
//!
//! * **PSD** (one-sided, unit²/Hz): `P_k = c_k |X_k|² / (f_s S2)` with
//!   `c_k = 2` for `0 < k < N/2` and `1` at DC and at Nyquist (`N` even).
//!   Parseval holds exactly: `Σ_k P_k Δf = Σ w_n² x_n² / S2`, the
//!   window-weighted mean square (the plain mean square for the rectangular
//!   window). The PSD is scaled by the window's energy (`S2`, i.e. the
//!   equivalent noise bandwidth `ENBW = f_s S2 / S1²`), so broadband levels
//!   are right.
//! * **Amplitude** (one-sided, unit, peak): `A_k = c'_k |X_k| / S1` with
//!   `c'_k = 2` except at DC and Nyquist: scaled by the window's coherent gain
//!   `S1 / N`, so a sinusoid centred on a bin reads its amplitude. Off-bin the
//!   Hann window reads up to 1.42 dB low (scalloping); [`Spectrum::tone`]
//!   sums the power of the main lobe instead and is within 0.01 dB anywhere.
//! * **Levels** are RMS levels: `L = 10 log10(mean square / ref²)` dB, i.e.
//!   `20 log10(A / √2 / ref)` for a sinusoid of amplitude `A`; `ref = 1 N` for
//!   forces and `1 m` for displacements.
//! * **Third-octave bands** (IEC 61260-1, base 10): centres
//!   `f_m = 1000 · 10^{n/10}` Hz, edges `f_m · 10^{±1/20}`; a band's mean square
//!   is the PSD integrated over its edges (bins weighted by the fraction of
//!   their width `[f_k - Δf/2, f_k + Δf/2]` inside the band).

pub mod run;

use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;

/// The window applied to the record before the transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Window {
    /// Periodic Hann `w_n = sin²(π n / N)`: coherent gain 0.5, ENBW 1.5 bins,
    /// worst-case scalloping 1.42 dB, side lobes -31 dB falling 18 dB/octave.
    #[default]
    Hann,
    /// No window: exact for periodic records (whole periods), leaks otherwise.
    Rectangular,
}

impl Window {
    /// The `N` window values.
    pub fn values(self, n: usize) -> Vec<f64> {
        match self {
            Window::Rectangular => vec![1.0; n],
            Window::Hann => (0..n)
                .map(|k| {
                    let s = (std::f64::consts::PI * k as f64 / n as f64).sin();
                    s * s
                })
                .collect(),
        }
    }

    /// Human name for captions and CSV headers.
    pub fn name(self) -> &'static str {
        match self {
            Window::Hann => "Hann",
            Window::Rectangular => "rectangular",
        }
    }
}

/// Errors of spectrum estimation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpectrumError {
    #[error(
        "spectrum of {samples} samples: expected at least {min} samples of the steady part (the steps from ramp_s, or --spectrum-from, to duration_s): lengthen duration_s (--duration) or start the analysis earlier"
    )]
    TooShort { samples: usize, min: usize },
    #[error(
        "spectrum of {samples} steady samples: at most {max} are held (shorten duration_s, raise dt_s or start the analysis later)"
    )]
    TooLong { samples: u64, max: u64 },
    #[error("spectrum: sample rate {0} Hz, expected a finite rate > 0 Hz")]
    SampleRate(f64),
    #[error("spectrum: sample {index} is {value}, expected finite values")]
    NonFinite { index: usize, value: f64 },
}

/// Fewest samples a spectrum is computed from.
pub const MIN_SAMPLES: usize = 8;

/// A one-sided spectrum of one record.
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Bin frequencies `k Δf`, `k = 0..=N/2` (Hz).
    pub freq_hz: Vec<f64>,
    /// One-sided PSD (unit²/Hz).
    pub psd: Vec<f64>,
    /// One-sided peak amplitude, coherent-gain corrected (unit).
    pub amplitude: Vec<f64>,
    /// Bin width `Δf = f_s / N` (Hz).
    pub df_hz: f64,
    /// Sample rate `f_s` (Hz).
    pub sample_rate_hz: f64,
    /// Record length `N`.
    pub num_samples: usize,
    pub window: Window,
    /// Equivalent noise bandwidth `f_s S2 / S1²` (Hz).
    pub enbw_hz: f64,
    /// Mean of the record, removed before windowing when asked (unit).
    pub removed_mean: f64,
}

/// Computes the spectrum of `x` sampled at `sample_rate_hz`; with
/// `remove_mean` the record's mean is subtracted first (kept in
/// [`Spectrum::removed_mean`]) so a static load does not leak into the first
/// bins.
pub fn spectrum(
    x: &[f64],
    sample_rate_hz: f64,
    window: Window,
    remove_mean: bool,
) -> Result<Spectrum, SpectrumError> {
    if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
        return Err(SpectrumError::SampleRate(sample_rate_hz));
    }
    let n = x.len();
    if n < MIN_SAMPLES {
        return Err(SpectrumError::TooShort {
            samples: n,
            min: MIN_SAMPLES,
        });
    }
    if let Some((index, &value)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(SpectrumError::NonFinite { index, value });
    }
    let mean = if remove_mean {
        x.iter().sum::<f64>() / n as f64
    } else {
        0.0
    };
    let w = window.values(n);
    let s1: f64 = w.iter().sum();
    let s2: f64 = w.iter().map(|v| v * v).sum();
    let mut buf: Vec<Complex64> = x
        .iter()
        .zip(&w)
        .map(|(&v, &wn)| Complex64::new((v - mean) * wn, 0.0))
        .collect();
    FftPlanner::<f64>::new()
        .plan_fft_forward(n)
        .process(&mut buf);
    let half = n / 2;
    let df = sample_rate_hz / n as f64;
    let mut psd = Vec::with_capacity(half + 1);
    let mut amplitude = Vec::with_capacity(half + 1);
    for (k, xk) in buf.iter().take(half + 1).enumerate() {
        let edge = k == 0 || (n.is_multiple_of(2) && k == half);
        let c = if edge { 1.0 } else { 2.0 };
        psd.push(c * xk.norm_sqr() / (sample_rate_hz * s2));
        amplitude.push(c * xk.norm() / s1);
    }
    Ok(Spectrum {
        freq_hz: (0..=half).map(|k| k as f64 * df).collect(),
        psd,
        amplitude,
        df_hz: df,
        sample_rate_hz,
        num_samples: n,
        window,
        enbw_hz: sample_rate_hz * s2 / (s1 * s1),
        removed_mean: mean,
    })
}

/// `10 log10(mean_square / ref²)` (dB), `-inf` for zero.
pub fn level_db(mean_square: f64, reference: f64) -> f64 {
    10.0 * (mean_square / (reference * reference)).log10()
}

/// A tone found in a spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tone {
    /// Frequency of the largest bin near the request (Hz).
    pub freq_hz: f64,
    /// Mean square in the main lobe around it (unit²).
    pub mean_square: f64,
    /// Peak amplitude `√(2 · mean square)` (unit).
    pub amplitude: f64,
}

impl Spectrum {
    /// Level of every bin as an RMS level re `reference` (dB): a sinusoid
    /// centred on a bin reads `20 log10(A / √2 / ref)`.
    pub fn levels_db(&self, reference: f64) -> Vec<f64> {
        self.amplitude
            .iter()
            .enumerate()
            .map(|(k, &a)| {
                // DC and Nyquist bins hold no √2 (they are not sinusoids).
                let edge = k == 0 || 2 * k == self.num_samples;
                let rms = if edge {
                    a
                } else {
                    a / std::f64::consts::SQRT_2
                };
                20.0 * (rms / reference).log10()
            })
            .collect()
    }

    /// Mean square of the record from the PSD (Parseval), `Σ P_k Δf` (unit²).
    pub fn mean_square(&self) -> f64 {
        self.psd.iter().sum::<f64>() * self.df_hz
    }

    /// Half-width of the main lobe of the window (bins).
    fn lobe_bins(&self) -> usize {
        match self.window {
            Window::Hann => 2,
            Window::Rectangular => 1,
        }
    }

    /// The tone nearest `near_hz`: the largest bin within `search_hz` of it,
    /// and the power of the window's main lobe around that bin (for Hann
    /// ±2 bins hold 99.9 % of a tone's power at any offset from the bins).
    pub fn tone(&self, near_hz: f64, search_hz: f64) -> Option<Tone> {
        let lo = ((near_hz - search_hz) / self.df_hz).floor().max(1.0) as usize;
        let hi = (((near_hz + search_hz) / self.df_hz).ceil() as usize).min(self.psd.len() - 1);
        let k = (lo..=hi).max_by(|&a, &b| self.psd[a].total_cmp(&self.psd[b]))?;
        let l = self.lobe_bins();
        let from = k.saturating_sub(l).max(1);
        let to = (k + l).min(self.psd.len() - 1);
        let ms = self.psd[from..=to].iter().sum::<f64>() * self.df_hz;
        Some(Tone {
            freq_hz: self.freq_hz[k],
            mean_square: ms,
            amplitude: (2.0 * ms).sqrt(),
        })
    }

    /// Mean square between `lo_hz` and `hi_hz` from the PSD, each bin
    /// weighted by the fraction of its width inside the band (unit²).
    pub fn band_mean_square(&self, lo_hz: f64, hi_hz: f64) -> f64 {
        let df = self.df_hz;
        let mut ms = 0.0;
        for (k, &p) in self.psd.iter().enumerate() {
            let f = k as f64 * df;
            // The DC bin covers [0, Δf/2]; the others [f - Δf/2, f + Δf/2].
            let a = if k == 0 { 0.0 } else { f - 0.5 * df };
            let b = f + 0.5 * df;
            let overlap = (b.min(hi_hz) - a.max(lo_hz)).max(0.0);
            if overlap > 0.0 {
                ms += p * overlap;
            }
        }
        ms
    }

    /// Third-octave band levels re `reference` (dB) for the bands between
    /// `lo_hz` and `hi_hz` (centres; see [`third_octave_bands`]).
    pub fn third_octave_levels(&self, lo_hz: f64, hi_hz: f64, reference: f64) -> Vec<BandLevel> {
        third_octave_bands(lo_hz, hi_hz)
            .into_iter()
            .map(|band| {
                let ms = self.band_mean_square(band.lower_hz, band.upper_hz);
                BandLevel {
                    band,
                    mean_square: ms,
                    level_db: level_db(ms, reference),
                    resolved: band.upper_hz <= 0.5 * self.sample_rate_hz
                        && band.upper_hz - band.lower_hz >= self.df_hz,
                }
            })
            .collect()
    }
}

/// A third-octave band (IEC 61260-1, base 10).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// Band number `n`: exact centre `1000 · 10^{n/10}` Hz.
    pub index: i32,
    /// Exact mid-band frequency (Hz).
    pub centre_hz: f64,
    /// Nominal centre for labels (Hz): 20, 25, 31.5, ... 1000, 1250, ...
    pub nominal_hz: f64,
    pub lower_hz: f64,
    pub upper_hz: f64,
}

/// The level of a signal in one band.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandLevel {
    pub band: Band,
    /// Mean square in the band (unit²).
    pub mean_square: f64,
    /// RMS level re the reference (dB).
    pub level_db: f64,
    /// The band lies below Nyquist and is at least one bin wide (otherwise
    /// its level is a coarse estimate from partial bins).
    pub resolved: bool,
}

/// Nominal third-octave centres of one decade (IEC 61260-1 / ISO 266).
const NOMINAL_DECADE: [f64; 10] = [10.0, 12.5, 16.0, 20.0, 25.0, 31.5, 40.0, 50.0, 63.0, 80.0];

/// The third-octave bands whose exact centres lie in `[lo_hz, hi_hz]`
/// (a small tolerance lets nominal values such as 20 or 5000 Hz select their band).
pub fn third_octave_bands(lo_hz: f64, hi_hz: f64) -> Vec<Band> {
    if !(lo_hz > 0.0 && hi_hz >= lo_hz && hi_hz.is_finite()) {
        return Vec::new();
    }
    let first = (10.0 * (lo_hz / 1000.0).log10() - 0.05).ceil() as i32;
    let last = (10.0 * (hi_hz / 1000.0).log10() + 0.05).floor() as i32;
    (first..=last)
        .map(|n| {
            let centre = 1000.0 * 10f64.powf(n as f64 / 10.0);
            // n = 10 d + r: nominal = NOMINAL_DECADE[r] · 10^(d + 2)
            let nominal =
                NOMINAL_DECADE[n.rem_euclid(10) as usize] * 10f64.powi(n.div_euclid(10) + 2);
            let half = 10f64.powf(1.0 / 20.0);
            Band {
                index: n,
                centre_hz: centre,
                nominal_hz: nominal,
                lower_hz: centre / half,
                upper_hz: centre * half,
            }
        })
        .collect()
}

/// Formats a nominal band centre for labels and CSV headers: `31.5`, `1000`.
pub fn band_label(nominal_hz: f64) -> String {
    let s = format!("{nominal_hz:.1}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Frequencies to mark on the spectrum of a run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Markers {
    /// Road excitation `n V / λ` (Hz) with its harmonic number `n`, every
    /// component of the road, up to the limit.
    pub excitation_hz: Vec<(u32, f64)>,
    /// Modal frequencies `f_k` (Hz).
    pub modal_hz: Vec<f64>,
}

/// Markers of a scene up to `max_hz`: road excitation frequencies of a sine
/// or multi-harmonic road (none for a measured or random profile) with harmonics up to
/// `max_harmonic`, and the modal frequencies.
pub fn markers(
    scene: &tirecontact_io::Scene,
    modes: &[tirecontact_core::base::modal::Mode],
    max_hz: f64,
    max_harmonic: u32,
) -> Markers {
    use tirecontact_core::model::road::Road;
    let wavelengths: Vec<f64> = match &scene.road {
        Road::Sine { wavelength_m, .. } => vec![*wavelength_m],
        Road::Harmonics { components } => components.iter().map(|c| c.wavelength_m).collect(),
        // broadband roads: no discrete excitation lines
        Road::Measured { .. }
        | Road::Random { .. }
        | Road::Surface { .. }
        | Road::Crg { .. }
        | Road::Texture { .. } => Vec::new(),
    };
    let mut excitation = Vec::new();
    for lambda in wavelengths {
        let f0 = scene.speed_mps / lambda;
        if !(f0 > 0.0 && f0.is_finite()) {
            continue;
        }
        for n in 1..=max_harmonic {
            let f = n as f64 * f0;
            if f > max_hz {
                break;
            }
            excitation.push((n, f));
        }
    }
    let modal_hz = modes
        .iter()
        .map(|m| m.freq_hz)
        .filter(|&f| f <= max_hz)
        .collect();
    Markers {
        excitation_hz: excitation,
        modal_hz,
    }
}
