//! Sweep results as a CSV table and a PNG figure.

use super::{RunSummary, SummaryError, SweepPoint};
use crate::analysis::metrics::ContactSummary;
use crate::analysis::spectrum::{band_label, third_octave_bands};
use crate::output::figures::{Figure, Panel, Series, Style};
use std::io::Write;
use tirecontact_io::scene::Scene;
use tirecontact_io::scene::fields;

/// Nominal centres of the bands of the sweep table (Hz): 20 Hz - 5 kHz.
fn table_bands() -> Vec<f64> {
    third_octave_bands(20.0, 5000.0)
        .iter()
        .map(|b| b.nominal_hz)
        .collect()
}

/// Level of the band of nominal centre `nominal_hz` in a run's summary
/// (NaN when the run failed or the band was not computed, e.g. above
/// Nyquist).
fn band_db(result: &Result<RunSummary, SummaryError>, nominal_hz: f64) -> f64 {
    result
        .as_ref()
        .ok()
        .and_then(|r| r.bands.iter().find(|b| b.band.nominal_hz == nominal_hz))
        .map_or(f64::NAN, |b| b.level_db)
}

/// The per-point metrics of [`crate::analysis::metrics::ContactSummary`] as table
/// columns: the name pattern (`{i}` is the point) and the field.
type PointMetric = (&'static str, fn(&ContactSummary) -> &Vec<f64>);

/// The per-point columns, in table order.
const POINT_METRICS: [PointMetric; 7] = [
    ("q{i}_smooth_max_N", |s| &s.force_max_n),
    ("q{i}_smooth_rms_N", |s| &s.force_rms_n),
    ("q{i}_1ms_max_N", |s| &s.window_force_max_n),
    ("impacts{i}_per_s", |s| &s.impacts_per_s),
    ("impulse{i}_mean_Ns", |s| &s.impulse_mean_ns),
    ("impulse{i}_max_Ns", |s| &s.impulse_max_ns),
    ("contact{i}_fraction", |s| &s.contact_fraction),
];

/// Which columns a table of runs holds: the per-point metrics when every
/// run has the same points, the patch's when the points make a contact
/// patch ([`crate::output::patch::PatchLayout`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Columns {
    /// The points of every run; `None` when the runs' points differ (a
    /// grid's `points.along` or `points.across` is swept).
    pub points: Option<usize>,
    /// The base scene's points make a contact patch.
    pub patch: bool,
}

/// The paths that change how many points a scene has.
pub const POINT_COUNT_PATHS: [&str; 2] = ["points.along", "points.across"];

impl Columns {
    /// The columns of runs of `base` with the parameters at `paths` varied.
    pub fn of(base: &Scene, paths: &[&str]) -> Self {
        let varies = paths.iter().any(|p| POINT_COUNT_PATHS.contains(&p.trim()));
        Columns {
            points: (!varies).then(|| base.num_points()),
            patch: crate::output::patch::PatchLayout::of(base).is_ok(),
        }
    }

    /// The contact plots show one curve per point (rather than the whole
    /// patch's).
    pub fn per_point(&self) -> bool {
        !self.patch && self.points.is_some()
    }
}

/// The patch's columns: name and value of a run (NaN for a run whose
/// points are not a patch).
type PatchMetric = (&'static str, fn(&RunSummary) -> f64);

/// The patch columns, in table order: the summed force without impacts
/// (largest, RMS), the points in contact (mean), the contact area (mean,
/// largest; points in contact × cell).
const PATCH_METRICS: [PatchMetric; 5] = [
    ("patch_force_max_N", |r| r.contact.total_force_max_n),
    ("patch_force_rms_N", |r| r.contact.total_force_rms_n),
    ("patch_points_in_contact_mean", |r| {
        r.contact.in_contact_mean
    }),
    ("patch_area_mean_m2", |r| {
        r.cell_area_m2
            .map_or(f64::NAN, |a| a * r.contact.in_contact_mean)
    }),
    ("patch_area_max_m2", |r| {
        r.cell_area_m2
            .map_or(f64::NAN, |a| a * r.contact.in_contact_max as f64)
    }),
];

/// The metric columns of runs with `columns`, all with a limit as dt → 0
/// ([`crate::analysis::metrics`]): per point (when the runs' points agree)
/// `q{i}_smooth_max_N`, `q{i}_smooth_rms_N` (contact force without
/// impacts), `q{i}_1ms_max_N` (largest 1 ms mean, impacts included),
/// `impacts{i}_per_s`, `impulse{i}_mean_Ns`, `impulse{i}_max_Ns`,
/// `contact{i}_fraction` (each for every point in turn); for a patch
/// `patch_force_max_N`, `patch_force_rms_N` (the summed force without
/// impacts), `patch_points_in_contact_mean`, `patch_area_mean_m2`,
/// `patch_area_max_m2`; then `band_{f}hz_db_re_1N`.. (total force).
pub fn metric_columns(columns: &Columns) -> Vec<String> {
    debug_assert_eq!(
        crate::analysis::metrics::FORCE_WINDOW_S,
        1e-3,
        "rename q{{i}}_1ms_max_N"
    );
    let p = columns.points.unwrap_or(0);
    let mut header: Vec<String> = POINT_METRICS
        .iter()
        .flat_map(|(name, _)| (0..p).map(move |i| name.replace("{i}", &i.to_string())))
        .collect();
    if columns.patch {
        header.extend(PATCH_METRICS.iter().map(|(name, _)| name.to_string()));
    }
    header.extend(
        table_bands()
            .iter()
            .map(|&b| format!("band_{}hz_db_re_1N", band_label(b))),
    );
    header
}

/// A run's values in [`metric_columns`]' order (NaN when it failed).
pub fn metric_values(result: &Result<RunSummary, SummaryError>, columns: &Columns) -> Vec<String> {
    let p = columns.points.unwrap_or(0);
    let mut row = Vec::new();
    match result {
        Ok(r) => {
            for (_, get) in POINT_METRICS {
                let v = get(&r.contact);
                row.extend((0..p).map(|i| v.get(i).map_or("NaN".into(), |x| format!("{x}"))));
            }
            if columns.patch {
                row.extend(PATCH_METRICS.iter().map(|(_, get)| format!("{}", get(r))));
            }
        }
        Err(_) => {
            let n = POINT_METRICS.len() * p
                + if columns.patch {
                    PATCH_METRICS.len()
                } else {
                    0
                };
            row.extend((0..n).map(|_| "NaN".to_string()));
        }
    }
    row.extend(
        table_bands()
            .iter()
            .map(|&b| format!("{:.6}", band_db(result, b))),
    );
    row
}

/// Writes one row per value: `<param>`, the [`metric_columns`], `error`
/// (empty when the run succeeded; its other columns are then NaN).
pub fn write_csv<W: Write>(
    out: W,
    param: &str,
    points: &[SweepPoint],
    columns: &Columns,
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    let mut header = vec![param.to_string()];
    header.extend(metric_columns(columns));
    header.push("error".into());
    w.write_record(&header)?;
    for p in points {
        let mut row = vec![format!("{}", p.value)];
        row.extend(metric_values(&p.result, columns));
        row.push(
            p.result
                .as_ref()
                .err()
                .map(ToString::to_string)
                .unwrap_or_default(),
        );
        w.write_record(&row)?;
    }
    w.flush()?;
    Ok(())
}

/// The y titles of the sweep's four plots, shared by the sweep view and
/// the sweep figure: largest force without impacts, largest impulse,
/// contact share, band levels.
pub const Y_TITLES: [&str; 4] = [
    "max contact force without impacts (N)",
    "largest impact impulse (N·s)",
    "fraction of steps in contact (%)",
    "total force, third-octave level (dB re 1 N)",
];

/// The factor from a contact fraction (0 to 1) to [`Y_TITLES`]' percent.
pub const CONTACT_PERCENT: f64 = 100.0;

/// The legend name of contact point `i`'s curve (view and figure).
pub fn point_series_name(i: usize) -> String {
    format!("point {i}")
}

/// The legend name of the band of nominal centre `nominal_hz`.
pub fn band_series_name(nominal_hz: f64) -> String {
    format!("{} Hz band", band_label(nominal_hz))
}

/// One named curve of a sweep plot: `(value, metric)` pairs.
pub type Curve = (String, Vec<(f64, f64)>);

/// The legend names of the whole-patch curves of the three contact plots.
pub const PATCH_CURVE_NAMES: [&str; 3] = [
    "all points: summed force",
    "all points: largest of any point",
    "all points: mean over the points",
];

/// The curves of the sweep's three contact plots ([`Y_TITLES`] 0 to 2),
/// one labelling for the sweep view and the figure: a curve per point, or,
/// for a patch or runs whose points differ ([`Columns::per_point`]), one
/// for all the points (the summed force without impacts, the largest
/// impulse of any point, the mean contact fraction over the points).
pub fn contact_curves(columns: &Columns, points: &[SweepPoint]) -> [Vec<Curve>; 3] {
    let ok: Vec<(f64, &RunSummary)> = points
        .iter()
        .filter_map(|p| p.result.as_ref().ok().map(|r| (p.value, r)))
        .collect();
    let curve = |name: String, get: &dyn Fn(&RunSummary) -> Option<f64>| -> Curve {
        let pts = ok
            .iter()
            .filter_map(|(v, r)| get(r).map(|y| (*v, y)))
            .collect();
        (name, pts)
    };
    match columns.points {
        Some(p) if columns.per_point() => {
            let per_point = |get: fn(&ContactSummary) -> &Vec<f64>, scale: f64| -> Vec<Curve> {
                (0..p)
                    .map(|i| {
                        curve(point_series_name(i), &|r| {
                            get(&r.contact).get(i).map(|y| scale * y)
                        })
                    })
                    .collect()
            };
            [
                per_point(|s| &s.force_max_n, 1.0),
                per_point(|s| &s.impulse_max_ns, 1.0),
                per_point(|s| &s.contact_fraction, CONTACT_PERCENT),
            ]
        }
        _ => {
            let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
            [
                vec![curve(PATCH_CURVE_NAMES[0].into(), &|r| {
                    Some(r.contact.total_force_max_n)
                })],
                vec![curve(PATCH_CURVE_NAMES[1].into(), &|r| {
                    Some(r.contact.impulse_max_ns.iter().fold(0.0, |a, &b| a.max(b)))
                })],
                vec![curve(PATCH_CURVE_NAMES[2].into(), &|r| {
                    Some(CONTACT_PERCENT * mean(&r.contact.contact_fraction))
                })],
            ]
        }
    }
}

/// The sweep's subtitle: how many values of which parameter, over which
/// range with its unit (`8 values of speed V from 8 to 36 m/s`).
pub fn sweep_subtitle(param: &str, count: usize, from: f64, to: f64) -> String {
    let unit = fields::unit(param)
        .filter(|u| *u != "-")
        .map_or(String::new(), |u| format!(" {u}"));
    format!(
        "{count} values of {} from {from} to {to}{unit}; steady part of each run (t ≥ ramp)",
        fields::label(param)
    )
}

/// The size (px) of `sweep --plot`'s figure: four stacked panels, each
/// plot about 260 px high (at 1400 × 1400, 160 px: two y tick labels, the
/// y titles longer than their plots).
pub const FIGURE_PX: (u32, u32) = (1400, 1800);

/// The sweep figure: max force without impacts, largest impact impulse,
/// contact fraction ([`contact_curves`]: per point, or for all the points
/// of a patch) and the rolling-noise bands (315, 500, 800, 1250, 2000 Hz) of the total
/// force, against the parameter.
pub fn figure(
    title: &str,
    subtitle: &str,
    param: &str,
    points: &[SweepPoint],
    columns: &Columns,
) -> Figure {
    let [force, impulse, contact] = contact_curves(columns, points).map(|curves| {
        curves
            .into_iter()
            .map(|(name, points)| Series {
                name,
                points,
                style: Style::LineMarkers(3),
                color: None,
            })
            .collect::<Vec<_>>()
    });
    // every other band of 315 Hz - 2 kHz (all of them are in the CSV)
    let bands: Vec<Series> = third_octave_bands(315.0, 2000.0)
        .iter()
        .step_by(2)
        .map(|b| Series {
            name: band_series_name(b.nominal_hz),
            points: points
                .iter()
                .map(|p| (p.value, band_db(&p.result, b.nominal_hz)))
                .filter(|p| p.1.is_finite())
                .collect(),
            style: Style::LineMarkers(3),
            color: None,
        })
        .collect();
    Figure {
        title: title.to_string(),
        subtitle: subtitle.to_string(),
        panels: vec![
            Panel {
                title: "Largest contact force without impacts (steady part)".into(),
                x_label: fields::axis_label(param),
                y_label: Y_TITLES[0].into(),
                series: force,
                ..Panel::default()
            },
            Panel {
                title: "Largest impact impulse (steady part; 0: no impact)".into(),
                x_label: fields::axis_label(param),
                y_label: Y_TITLES[1].into(),
                series: impulse,
                ..Panel::default()
            },
            Panel {
                title: "Fraction of steps in contact (steady part)".into(),
                x_label: fields::axis_label(param),
                y_label: Y_TITLES[2].into(),
                series: contact,
                ..Panel::default()
            },
            Panel {
                title:
                    "Total contact force, third-octave bands 315 Hz - 2 kHz, every other band (Hann, mean removed)"
                        .into(),
                x_label: fields::axis_label(param),
                y_label: Y_TITLES[3].into(),
                series: bands,
                ..Panel::default()
            },
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::{CONTACT_PERCENT, Columns, Y_TITLES, fields, figure, sweep_subtitle};

    const THREE: Columns = Columns {
        points: Some(3),
        patch: false,
    };

    #[test]
    fn swept_parameters_are_labelled_with_their_units() {
        for (param, want) in [
            ("speed_mps", "speed V (m/s)"),
            ("ramp_s", "ramp (s)"),
            ("dt_s", "time step dt (s)"),
            ("road.amplitude_m", "road amplitude a (m)"),
            ("points[*].h_m", "every point's height h (m)"),
            ("points[2].x_m", "point 2 position x (m)"),
            ("road.components[1].phase_rad", "harmonic 1 phase (rad)"),
            ("road.max_wavenumber_cpm", "highest wavenumber n (cycles/m)"),
            ("tyre.modes[0].freq_hz", "mode 0 frequency (Hz)"),
            (
                "tyre.modes[*].damping_ratio",
                "every mode's damping ratio (-)",
            ),
            (
                "tyre.modes[2].residue[0][1]",
                "mode 2 residue at point 0 of a force at point 1 (1/kg)",
            ),
            ("tyre.modes[2].shape[1]", "mode 2 shape at point 1 (1/√kg)"),
            (
                "contact.stiffness_n_m[3]",
                "tread stiffness of point 3 (N/m)",
            ),
            (
                "contact.stiffness_n_m[*]",
                "tread stiffness of every point (N/m)",
            ),
            ("tyre.ring.inflation_pa", "inflation (Pa)"),
            (
                "tyre.ring.radial_stiffness_n_m2",
                "ring radial stiffness (N/m²)",
            ),
            (
                "tyre.ring.bending_stiffness_n_m2",
                "ring bending stiffness EI (N·m²)",
            ),
            (
                "tyre.ring.extensional_stiffness_n",
                "ring extensional stiffness EA (N)",
            ),
            (
                "tyre.ring.mass_per_length_kg_m",
                "ring mass per length (kg/m)",
            ),
            (
                "tyre.identification.band_hz.1",
                "identification band to (Hz)",
            ),
            ("road.seed", "road.seed"),
        ] {
            assert_eq!(fields::axis_label(param), want);
        }
    }

    /// Every parameter the sweep offers on a shipped preset has a name in
    /// words, never its preset path (`speed_mps`, `points[0].x_m`,
    /// `tyre.modes[0].shape[1]`).
    #[test]
    fn every_parameter_of_the_shipped_presets_has_a_name_in_words() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets");
        let mut checked = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "ron") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let scene = tirecontact_io::scene::Scene::parse(&text, "preset").unwrap();
            for p in crate::studies::sweep::param_paths(&scene) {
                let label = fields::label(&p);
                assert!(
                    !label.contains('_') && !label.contains('[') && !label.contains('.'),
                    "{}: `{p}` is labelled {label:?}",
                    path.display()
                );
                checked += 1;
            }
        }
        assert!(checked > 100, "{checked} parameters");
    }

    /// The subtitle names the parameter as the editor does, with the
    /// range's unit, and no internal path.
    #[test]
    fn the_subtitle_names_the_parameter_and_its_unit() {
        let s = sweep_subtitle("speed_mps", 8, 8.0, 36.0);
        assert!(s.starts_with("8 values of speed V from 8 to 36 m/s"), "{s}");
        assert!(!s.contains("speed_mps") && !s.contains("ramp_s"), "{s}");
        // a ratio has no unit to name
        let s = sweep_subtitle("tyre.modes[0].damping_ratio", 3, 0.01, 0.1);
        assert!(
            s.starts_with("3 values of mode 0 damping ratio from 0.01 to 0.1;"),
            "{s}"
        );
    }

    /// The figure's panels carry the sweep view's y titles (with units),
    /// every per-point curve is named `point i` in every panel, the bands
    /// `… Hz band`, and the contact share is in percent as the title says.
    #[test]
    fn the_figure_speaks_as_the_sweep_view() {
        let pts = super::figure_tests::points();
        let fig = figure("t", "s", "speed_mps", &pts, &THREE);
        let titles: Vec<&str> = fig.panels.iter().map(|p| p.y_label.as_str()).collect();
        assert_eq!(titles, Y_TITLES.to_vec());
        for p in &fig.panels[..3] {
            let names: Vec<&str> = p.series.iter().map(|s| s.name.as_str()).collect();
            assert_eq!(names, ["point 0", "point 1", "point 2"], "{}", p.title);
            assert_eq!(p.x_label, "speed V (m/s)");
        }
        assert!(
            fig.panels[3]
                .series
                .iter()
                .all(|s| s.name.ends_with(" Hz band")),
            "{:?}",
            fig.panels[3]
                .series
                .iter()
                .map(|s| &s.name)
                .collect::<Vec<_>>()
        );
        // contact fractions up to 0.8 are drawn up to 80 %
        let top = fig.panels[2]
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold(0.0, f64::max);
        assert!(top > 70.0 && top <= 80.0 + 1e-9, "{top}");
        for (i, s) in fig.panels[2].series.iter().enumerate() {
            for (p, pt) in s.points.iter().zip(&pts) {
                let f = pt.result.as_ref().unwrap().contact.contact_fraction[i];
                assert!((p.1 - CONTACT_PERCENT * f).abs() < 1e-9);
            }
        }
    }
}

#[cfg(test)]
mod figure_tests {
    #[cfg(feature = "figures")]
    use super::{Columns, FIGURE_PX, figure};
    use crate::analysis::metrics::ContactSummary;
    use crate::analysis::spectrum::{BandLevel, third_octave_bands};
    #[cfg(feature = "figures")]
    use crate::output::figures::tests::{ink, runs};
    #[cfg(feature = "figures")]
    use crate::output::figures::{render_rgb_layout, tick_label_px};
    use crate::studies::sweep::{RunSummary, SweepPoint};

    #[cfg(feature = "figures")]
    const THREE: Columns = Columns {
        points: Some(3),
        patch: false,
    };

    /// Fifteen speeds of a three-point scene shaped as the three-point
    /// preset's sweep (forces up to 900 kN, a band dipping to -70 dB).
    pub(super) fn points() -> Vec<SweepPoint> {
        (0..15)
            .map(|k| {
                let v = 8.0 + 2.0 * k as f64;
                let bump = |i: usize| (std::f64::consts::PI * (k as f64 + i as f64) / 16.0).sin();
                SweepPoint {
                    value: v,
                    result: Ok(RunSummary {
                        contact: ContactSummary {
                            force_max_n: (0..3).map(|i| 9e5 * bump(i)).collect(),
                            impulse_max_ns: (0..3).map(|i| 4e-3 * bump(i)).collect(),
                            contact_fraction: (0..3).map(|i| 0.8 * bump(i)).collect(),
                            ..ContactSummary::default()
                        },
                        bands: third_octave_bands(20.0, 5000.0)
                            .into_iter()
                            .map(|band| BandLevel {
                                band,
                                mean_square: 1.0,
                                level_db: if k == 8 { -70.0 } else { 60.0 + bump(0) },
                                resolved: true,
                            })
                            .collect(),
                        cell_area_m2: None,
                        steps: 1000,
                    }),
                }
            })
            .collect()
    }

    /// Rows of `rgb` (`w` px wide) in `y0..y1` with dark ink in `x0..x1`.
    #[cfg(feature = "figures")]
    fn ink_rows(rgb: &[u8], w: u32, x: (i32, i32), y: (i32, i32)) -> Vec<i32> {
        ink(rgb, w, x, y).1
    }

    #[cfg(feature = "figures")]
    #[test]
    fn every_panel_reads_three_y_labels_and_its_y_title_once() {
        // at 1400 x 1400 the panels' plots were 160 px high: two y tick
        // labels (one, 500000, on the force panel), and the rotated y
        // titles ran past their plots towards their neighbours'
        let fig = figure("t", "s", "speed_mps", &points(), &THREE);
        let (w, h) = FIGURE_PX;
        let (rgb, l) = render_rgb_layout(&fig, w, h).unwrap();
        let px = tick_label_px(w, h) as i32;
        let left = l[0].plot_px[0];
        // the y titles: ink in the left third of the label area, below the
        // figure's title and subtitle
        let titles = runs(
            &ink_rows(&rgb, w, (0, left / 3), (l[0].plot_px[1] - px, h as i32)),
            px,
        );
        assert_eq!(titles.len(), 4, "y titles {titles:?}");
        for (k, (p, t)) in l.iter().zip(&titles).enumerate() {
            let [_, top, _, bottom] = p.plot_px;
            assert!(
                bottom - top >= 220,
                "panel {k}: plot {} px high",
                bottom - top
            );
            assert!(
                t.0 >= top - px / 2 && t.1 <= bottom + px / 2,
                "panel {k}: y title on rows {t:?}, plot {top}..{bottom}"
            );
            let labels = runs(
                &ink_rows(&rgb, w, (left - 4 * px, left - 7), (top - px, bottom + px)),
                px / 3,
            );
            assert!(labels.len() >= 3, "panel {k}: y tick labels {labels:?}");
            for r in &labels {
                assert!(r.1 - r.0 < px, "panel {k}: labels run together {labels:?}");
            }
        }
        if std::env::var_os("TC_DUMP_FIG").is_some() {
            let path = std::path::Path::new("/tmp/p12/sweep_like.png");
            crate::output::figures::render_png(&fig, path, w, h).unwrap();
        }
    }
}
