//! Spectra and summary figures of a run's steady part: a recorder fed after
//! every step, the spectra of the step-mean forces and the displacements of
//! every point and of the total force, CSV tables and a PNG figure.
//!
//! The step-mean force is the force averaged over each step (impulse / dt):
//! as a sampled signal it is the true force through a one-step moving
//! average, which lowers levels by `-20 log10(sinc(f dt))`, 0.04 dB at 5 kHz
//! for `dt = 1e-5 s`.

use super::{
    BandLevel, MIN_SAMPLES, Markers, Spectrum, SpectrumError, Window, band_label, markers, spectrum,
};
use crate::output::figures::{Figure, Panel, Series, Style};
use std::io::Write;
use tirecontact_core::solver::problem::RunShape;
use tirecontact_core::solver::simulation::Simulation;

/// Largest number of steady samples recorded per signal (bounds memory:
/// 2P signals of 8 bytes per sample).
pub const MAX_SAMPLES: u64 = 1 << 23;

/// Third-octave bands reported by default (nominal centres, Hz).
pub const DEFAULT_BANDS_HZ: (f64, f64) = (20.0, 5000.0);

/// Records every step of the steady part of a run (`t > start_s`).
#[derive(Debug, Clone)]
pub struct SteadyRecorder {
    /// Start of the steady part (s).
    pub start_s: f64,
    pub dt_s: f64,
    /// Step-mean force per point and step (N).
    pub q_n: Vec<Vec<f64>>,
    /// Displacement per point at each step end (m).
    pub u_m: Vec<Vec<f64>>,
    /// Steps ending in contact, per point.
    pub contact_steps: Vec<u64>,
}

impl SteadyRecorder {
    /// The number of steady samples of `scene` from `start_s` (default: the
    /// ramp time `ramp_s`) to its end, checked before any run: too few for a
    /// spectrum, or too many to hold, is an error (one sample of slack for
    /// the rounding of the steady part's first step; the spectrum checks
    /// the exact count).
    pub fn steady_samples(
        scene: &impl RunShape,
        start_s: Option<f64>,
    ) -> Result<u64, SpectrumError> {
        let start = start_s.unwrap_or(scene.ramp_s()).max(0.0);
        let steady = ((scene.duration_s() - start) / scene.dt_s()).max(0.0) as u64;
        if steady + 1 < MIN_SAMPLES as u64 {
            return Err(SpectrumError::TooShort {
                samples: steady as usize,
                min: MIN_SAMPLES,
            });
        }
        if steady > MAX_SAMPLES {
            return Err(SpectrumError::TooLong {
                samples: steady,
                max: MAX_SAMPLES,
            });
        }
        Ok(steady)
    }

    /// A recorder of the steady part of `scene` from `start_s` (default: the
    /// ramp time `ramp_s`). Errors when the part is too long to hold.
    pub fn new(scene: &impl RunShape, start_s: Option<f64>) -> Result<Self, SpectrumError> {
        let start = start_s.unwrap_or(scene.ramp_s()).max(0.0);
        let steady = Self::steady_samples(scene, start_s)?;
        let p = scene.num_points();
        let cap = steady as usize + 1;
        Ok(SteadyRecorder {
            start_s: start,
            dt_s: scene.dt_s(),
            q_n: vec![Vec::with_capacity(cap); p],
            u_m: vec![Vec::with_capacity(cap); p],
            contact_steps: vec![0; p],
        })
    }

    /// Call after every step.
    pub fn after_step(&mut self, sim: &Simulation) {
        // a step belongs to the steady part when it starts at or after start_s
        if sim.time_s() - sim.dt_s() < self.start_s - 1e-9 * sim.dt_s() {
            return;
        }
        let (q, u, c) = (sim.force_n(), sim.displacement_m(), sim.in_contact());
        for i in 0..self.q_n.len() {
            self.q_n[i].push(q[i]);
            self.u_m[i].push(u[i]);
            self.contact_steps[i] += u64::from(c[i]);
        }
    }

    /// Steps recorded.
    pub fn len(&self) -> usize {
        self.q_n.first().map_or(0, Vec::len)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Sum of the forces of all points per step (N).
    pub fn total_force_n(&self) -> Vec<f64> {
        let mut total = vec![0.0; self.len()];
        for q in &self.q_n {
            for (t, x) in total.iter_mut().zip(q) {
                *t += x;
            }
        }
        total
    }

    /// Largest step-mean force per point over the steady part (N).
    pub fn max_force_n(&self) -> Vec<f64> {
        self.q_n
            .iter()
            .map(|q| q.iter().fold(0.0, |m: f64, &x| m.max(x)))
            .collect()
    }

    /// RMS of the step-mean force per point, static part included (N).
    pub fn force_rms_n(&self) -> Vec<f64> {
        self.q_n.iter().map(|q| rms(q)).collect()
    }

    /// Fraction of the steady steps ending in contact, per point.
    pub fn contact_fraction(&self) -> Vec<f64> {
        let n = self.len().max(1) as f64;
        self.contact_steps.iter().map(|&c| c as f64 / n).collect()
    }

    /// Spectra of every signal (mean removed before windowing).
    pub fn spectra(&self, window: Window) -> Result<RunSpectra, SpectrumError> {
        let fs = 1.0 / self.dt_s;
        let each = |sig: &[Vec<f64>]| -> Result<Vec<Spectrum>, SpectrumError> {
            sig.iter().map(|x| spectrum(x, fs, window, true)).collect()
        };
        Ok(RunSpectra {
            force: each(&self.q_n)?,
            displacement: each(&self.u_m)?,
            total_force: spectrum(&self.total_force_n(), fs, window, true)?,
            start_s: self.start_s,
        })
    }
}

impl tirecontact_core::solver::drive::Probe for SteadyRecorder {
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        SteadyRecorder::after_step(self, sim);
        Ok(())
    }
}

/// RMS of a signal (its unit).
pub fn rms(x: &[f64]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

/// Spectra of a run's steady part.
#[derive(Debug, Clone)]
pub struct RunSpectra {
    /// Step-mean force of each point (N).
    pub force: Vec<Spectrum>,
    /// Displacement of each point (m).
    pub displacement: Vec<Spectrum>,
    /// Sum of the forces of all points (N).
    pub total_force: Spectrum,
    /// Start of the analysed part (s).
    pub start_s: f64,
}

impl RunSpectra {
    fn first(&self) -> &Spectrum {
        &self.total_force
    }

    /// One line describing the analysis, for subtitles and messages.
    pub fn describe(&self) -> String {
        let s = self.first();
        format!(
            "steady part from t = {:.3} s: {} samples at {:.0} Hz ({:.3} s), {} window, bin {:.2} Hz, ENBW {:.2} Hz, mean removed; RMS levels",
            self.start_s,
            s.num_samples,
            s.sample_rate_hz,
            s.num_samples as f64 / s.sample_rate_hz,
            s.window.name(),
            s.df_hz,
            s.enbw_hz
        )
    }

    /// A short description for panel titles.
    pub fn describe_short(&self) -> String {
        let s = self.first();
        format!(
            "t >= {:.3} s, {} window, bin {:.2} Hz, mean removed",
            self.start_s,
            s.window.name(),
            s.df_hz
        )
    }

    /// Writes `freq_hz, q{i}_db_re_1N.., q_total_db_re_1N, u{i}_db_re_1m..`
    /// for the bins up to `max_hz`.
    pub fn write_csv<W: Write>(&self, out: W, max_hz: f64) -> Result<(), csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        let p = self.force.len();
        let mut header = vec!["freq_hz".to_string()];
        header.extend((0..p).map(|i| format!("q{i}_db_re_1N")));
        header.push("q_total_db_re_1N".into());
        header.extend((0..p).map(|i| format!("u{i}_db_re_1m")));
        w.write_record(&header)?;
        let lq: Vec<Vec<f64>> = self.force.iter().map(|s| s.levels_db(1.0)).collect();
        let lt = self.total_force.levels_db(1.0);
        let lu: Vec<Vec<f64>> = self.displacement.iter().map(|s| s.levels_db(1.0)).collect();
        for (k, &f) in self.first().freq_hz.iter().enumerate() {
            if f > max_hz {
                break;
            }
            let mut row = vec![format!("{f}")];
            row.extend(lq.iter().map(|l| format!("{:.6}", l[k])));
            row.push(format!("{:.6}", lt[k]));
            row.extend(lu.iter().map(|l| format!("{:.6}", l[k])));
            w.write_record(&row)?;
        }
        w.flush()?;
        Ok(())
    }

    /// Third-octave band levels: `(bands of the total force, per point)`.
    pub fn force_bands(&self, lo_hz: f64, hi_hz: f64) -> (Vec<BandLevel>, Vec<Vec<BandLevel>>) {
        (
            self.total_force.third_octave_levels(lo_hz, hi_hz, 1.0),
            self.force
                .iter()
                .map(|s| s.third_octave_levels(lo_hz, hi_hz, 1.0))
                .collect(),
        )
    }

    /// Writes the band table: `band, centre_hz, lower_hz, upper_hz,
    /// resolved, q_total_db_re_1N, q{i}_db_re_1N.., u{i}_db_re_1m..`.
    pub fn write_bands_csv<W: Write>(
        &self,
        out: W,
        lo_hz: f64,
        hi_hz: f64,
    ) -> Result<(), csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        let p = self.force.len();
        let mut header: Vec<String> = ["band_hz", "centre_hz", "lower_hz", "upper_hz", "resolved"]
            .map(String::from)
            .to_vec();
        header.push("q_total_db_re_1N".into());
        header.extend((0..p).map(|i| format!("q{i}_db_re_1N")));
        header.extend((0..p).map(|i| format!("u{i}_db_re_1m")));
        w.write_record(&header)?;
        let (total, per) = self.force_bands(lo_hz, hi_hz);
        let disp: Vec<Vec<BandLevel>> = self
            .displacement
            .iter()
            .map(|s| s.third_octave_levels(lo_hz, hi_hz, 1.0))
            .collect();
        for (b, t) in total.iter().enumerate() {
            let mut row = vec![
                band_label(t.band.nominal_hz),
                format!("{}", t.band.centre_hz),
                format!("{}", t.band.lower_hz),
                format!("{}", t.band.upper_hz),
                format!("{}", u8::from(t.resolved)),
                format!("{:.6}", t.level_db),
            ];
            row.extend(per.iter().map(|l| format!("{:.6}", l[b].level_db)));
            row.extend(disp.iter().map(|l| format!("{:.6}", l[b].level_db)));
            w.write_record(&row)?;
        }
        w.flush()?;
        Ok(())
    }

    /// The spectrum figure: force levels, displacement levels (per point,
    /// against Hz on a log axis up to `max_hz`) with the road excitation and
    /// modal frequencies marked, and the third-octave levels of the forces.
    pub fn figure(&self, title: &str, subtitle: &str, marks: &Markers, max_hz: f64) -> Figure {
        let s = self.first();
        let max_hz = max_hz.min(0.5 * s.sample_rate_hz);
        let curves = |specs: &[Spectrum], name: &str| -> Vec<Series> {
            specs
                .iter()
                .enumerate()
                .map(|(i, sp)| {
                    let pts = sp
                        .freq_hz
                        .iter()
                        .zip(sp.levels_db(1.0))
                        .skip(1)
                        .take_while(|(f, _)| **f <= max_hz)
                        .map(|(&f, l)| (f, l))
                        .collect();
                    Series {
                        style: Style::ThinLine,
                        ..Series::line(format!("{name}{i}"), pts)
                    }
                })
                .collect()
        };
        let mut force = curves(&self.force, "q");
        let mut total = curves(std::slice::from_ref(&self.total_force), "");
        total[0].name = "total q".into();
        total[0].color = Some(6);
        force.append(&mut total);
        let disp = curves(&self.displacement, "u");
        let (tb, pb) = self.force_bands(DEFAULT_BANDS_HZ.0, max_hz.min(DEFAULT_BANDS_HZ.1));
        let band_series = |levels: &[BandLevel], name: String, color: Option<usize>| Series {
            name,
            points: levels
                .iter()
                .filter(|b| b.resolved)
                .map(|b| (b.band.centre_hz, b.level_db))
                .collect(),
            style: Style::LineMarkers(3),
            color,
        };
        let mut bands: Vec<Series> = pb
            .iter()
            .enumerate()
            .map(|(i, l)| band_series(l, format!("q{i}"), Some(i)))
            .collect();
        bands.push(band_series(&tb, "total q".into(), Some(6)));
        let mut panels = vec![
            Panel {
                title: format!("Contact force spectrum, {}", self.describe_short()),
                x_label: "frequency f (Hz)".into(),
                y_label: "force level (dB re 1 N)".into(),
                series: force,
                log_x: true,
                ..Panel::default()
            },
            Panel {
                title: "Displacement spectrum".into(),
                x_label: "frequency f (Hz)".into(),
                y_label: "displacement level (dB re 1 m)".into(),
                series: disp,
                log_x: true,
                ..Panel::default()
            },
            Panel {
                title: "Contact force in third-octave bands (IEC 61260, base 10)".into(),
                x_label: "band centre frequency (Hz)".into(),
                y_label: "band level (dB re 1 N)".into(),
                series: bands,
                log_x: true,
                ..Panel::default()
            },
        ];
        for panel in &mut panels {
            floor_levels(panel, 120.0);
        }
        // markers on the two narrow-band panels (the band panel stays readable)
        for panel in &mut panels[..2] {
            add_markers(panel, marks, s.df_hz, max_hz);
        }
        Figure {
            title: title.to_string(),
            subtitle: subtitle.to_string(),
            panels,
        }
    }
}

/// Raises levels more than `range_db` below the panel's highest to that floor
/// (round-off levels of -300 dB would flatten the rest).
fn floor_levels(panel: &mut Panel, range_db: f64) {
    let top = panel
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|v| v.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    if !top.is_finite() {
        return;
    }
    for s in &mut panel.series {
        for p in &mut s.points {
            if p.1.is_nan() || p.1 < top - range_db {
                p.1 = top - range_db;
            }
        }
    }
}

/// Vertical lines at the excitation (dashed look: grey) and modal
/// frequencies, spanning the panel's level range; one legend entry each.
/// They are drawn first, under the spectra: the response peaks sit on the
/// excitation lines, which hid them when drawn over (the spectra keep the
/// colours they had).
fn add_markers(panel: &mut Panel, marks: &Markers, min_hz: f64, max_hz: f64) {
    for (k, s) in panel.series.iter_mut().enumerate() {
        s.color.get_or_insert(k);
    }
    let n_data = panel.series.len();
    push_markers(panel, marks, min_hz, max_hz);
    let n_markers = panel.series.len() - n_data;
    panel.series.rotate_right(n_markers);
}

/// The marker lines of [`add_markers`], appended to `panel`'s series.
fn push_markers(panel: &mut Panel, marks: &Markers, min_hz: f64, max_hz: f64) {
    let (lo, hi) = panel
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return;
    }
    let in_range = |f: f64| f >= min_hz && f <= max_hz;
    let mut first = true;
    for &(n, f) in marks.excitation_hz.iter().filter(|m| in_range(m.1)) {
        panel.series.push(Series {
            name: if first {
                format!("road n·V/λ (n = 1: {f:.1} Hz)")
            } else {
                String::new()
            },
            points: vec![(f, lo), (f, if n == 1 { hi } else { lo + 0.8 * (hi - lo) })],
            style: Style::Line,
            color: Some(8),
        });
        first = false;
    }
    let mut first = true;
    for &f in marks.modal_hz.iter().filter(|&&f| in_range(f)) {
        panel.series.push(Series {
            name: if first {
                "modal frequencies".into()
            } else {
                String::new()
            },
            points: vec![(f, lo), (f, lo + 0.25 * (hi - lo))],
            style: Style::Line,
            color: Some(3),
        });
        first = false;
    }
}

/// Markers of a prepared scene for its spectra up to `max_hz` (10 road
/// harmonics).
pub fn scene_markers(model: &tirecontact_io::identify::PreparedModel, max_hz: f64) -> Markers {
    markers(model.scene(), model.modes(), max_hz, 10)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markers_go_under_the_spectra_which_keep_their_colours() {
        let mut panel = Panel {
            series: vec![
                Series::line("q0", vec![(10.0, -20.0), (100.0, 40.0)]),
                Series::line("q1", vec![(10.0, -30.0), (100.0, 30.0)]),
            ],
            ..Panel::default()
        };
        let marks = Markers {
            excitation_hz: vec![(1, 50.0), (2, 100.0)],
            modal_hz: vec![80.0],
        };
        add_markers(&mut panel, &marks, 1.0, 1000.0);
        let names: Vec<&str> = panel.series.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names.len(), 5, "{names:?}");
        // three marker lines first (drawn first: under), then the spectra
        assert!(names[0].starts_with("road"), "{names:?}");
        assert_eq!(names[2], "modal frequencies");
        assert_eq!(&names[3..], ["q0", "q1"]);
        assert_eq!(panel.series[3].color, Some(0));
        assert_eq!(panel.series[4].color, Some(1));
    }
}
