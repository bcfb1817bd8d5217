//! Recording a run for figures: displacement, window-mean force and contact
//! per point, at most `max_samples` samples (the run sampler's windows,
//! [`super::sampler`]: forces averaged over each window so impulses are
//! kept, and their impact part beside them so that the figure can clip
//! impact spikes).

use crate::output::figures::{Figure, Panel, Series, Style};
use crate::output::impacts::clip_level;
use crate::output::sampler::{LastWindow, Merge, Sampler, Stride, merge_windows};
use crate::output::summary;
use tirecontact_core::solver::simulation::Simulation;

/// Palette index of the clipped impacts' dots: black.
const IMPACT_COLOR: usize = 6;

/// Name of the series of clipped impact samples in a recording's figure.
pub const CLIPPED_IMPACTS: &str = "impacts (impulse / dt), clipped";

/// Samples kept by the command line's run figures (`run --plot`,
/// `identify --figures`).
pub const PLOT_SAMPLES: u64 = 4000;

/// Decimated time histories of a run.
#[derive(Debug, Clone, Default)]
pub struct Recording {
    pub t_s: Vec<f64>,
    /// `u[i][k]` (m).
    pub u_m: Vec<Vec<f64>>,
    /// Window-mean force `q[i][k]` (N).
    pub q_n: Vec<Vec<f64>>,
    /// Road height `r[i][k]` (m).
    pub r_m: Vec<Vec<f64>>,
    /// The impact part of `q_n`, window mean `qi[i][k]` (N): located
    /// impulses / dt, or the paper scheme's landing steps.
    pub q_impact_n: Vec<Vec<f64>>,
    /// `contact[i][k]`: point `i` was in contact at some step of window `k`.
    pub contact: Vec<Vec<bool>>,
    every: u64,
    sampler: Sampler,
}

/// A panel of a run figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunPanel {
    /// Displacement `u` (mm, positive up).
    Displacement,
    /// Window-mean contact force `q` (N).
    Force,
    /// Gap to the road `u − r` (mm).
    Gap,
    /// Contact state: a lane per point, raised while in contact.
    Contact,
}

impl RunPanel {
    /// The command line's run figure (`run --plot`).
    pub const RUN: [RunPanel; 2] = [RunPanel::Displacement, RunPanel::Force];
    /// The visualiser's time plots.
    pub const TIME_PLOTS: [RunPanel; 4] = [
        RunPanel::Displacement,
        RunPanel::Force,
        RunPanel::Gap,
        RunPanel::Contact,
    ];
}

/// What a run figure shows and how it is titled.
#[derive(Debug, Clone, Copy)]
pub struct FigureSpec<'a> {
    pub title: &'a str,
    /// One line of scene parameters (`output::summary::scene_summary`).
    pub subtitle: &'a str,
    /// The run's step (s): with the recording's window, the force's
    /// averaging time said in its caption.
    pub dt_s: f64,
    /// Cut impact spikes a margin above the force without impacts.
    pub clip_impacts: bool,
    /// The points drawn (`None`: all).
    pub points: Option<&'a [usize]>,
    pub panels: &'a [RunPanel],
}

impl Recording {
    /// A recording of `total_steps` steps keeping about `max_samples`
    /// samples: windows of `ceil(total_steps / max_samples)` steps, the last
    /// one partial. Its buffers are allocated here.
    pub fn new(p: usize, total_steps: u64, max_samples: u64) -> Self {
        let every = total_steps.div_ceil(max_samples.max(1)).max(1);
        let rows = usize::try_from(total_steps.div_ceil(every)).unwrap_or(0);
        // (one `Vec` per point, each with its room: `vec![v; p]` clones
        // without the capacity)
        fn per_point<T>(p: usize, rows: usize) -> Vec<Vec<T>> {
            (0..p).map(|_| Vec::with_capacity(rows)).collect()
        }
        Recording {
            t_s: Vec::with_capacity(rows),
            u_m: per_point(p, rows),
            q_n: per_point(p, rows),
            r_m: per_point(p, rows),
            q_impact_n: per_point(p, rows),
            contact: per_point(p, rows),
            every,
            sampler: Sampler::new(p, Stride::Every(every), LastWindow::Partial).with_impacts(),
        }
    }

    /// Call after every step.
    pub fn after_step(&mut self, sim: &Simulation) {
        let Some(w) = self.sampler.after_step(sim) else {
            return;
        };
        self.t_s.push(sim.time_s());
        for i in 0..w.q_n.len() {
            self.u_m[i].push(sim.displacement_m()[i]);
            self.r_m[i].push(sim.road_m()[i]);
            self.q_n[i].push(w.q_n[i]);
            self.q_impact_n[i].push(w.q_impact_n[i]);
            self.contact[i].push(w.contact[i]);
        }
    }

    /// A recording of samples taken elsewhere (the visualiser's history),
    /// each a window of `every` steps; the series are per point, all as
    /// long as `t_s`.
    pub fn from_samples(
        every: u64,
        t_s: Vec<f64>,
        u_m: Vec<Vec<f64>>,
        q_n: Vec<Vec<f64>>,
        r_m: Vec<Vec<f64>>,
        q_impact_n: Vec<Vec<f64>>,
        contact: Vec<Vec<bool>>,
    ) -> Self {
        Recording {
            t_s,
            u_m,
            q_n,
            r_m,
            q_impact_n,
            contact,
            every: every.max(1),
            sampler: Sampler::default(),
        }
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t_s.len()
    }

    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }

    /// The recording with every `factor` consecutive samples merged into
    /// one window ([`merge_windows`]), as if it had been recorded with
    /// `factor` times longer windows: forces averaged (impulses kept),
    /// displacement and road at the window's end, contact if any merged
    /// sample had it.
    pub fn merged(&self, factor: usize) -> Recording {
        self.merged_after(0, factor)
    }

    /// [`Recording::merged`] of the samples after the first, which stays
    /// on its own: a recording that starts with its t = 0 sample (the
    /// visualiser's history) merges into the windows of `factor` times its
    /// stride counted from t = 0, those of a command-line recording at that
    /// stride, instead of windows shifted by one sample.
    pub fn merged_after_start(&self, factor: usize) -> Recording {
        self.merged_after(1, factor)
    }

    /// The first `kept` samples as they are, the rest merged by `factor`.
    fn merged_after(&self, kept: usize, factor: usize) -> Recording {
        let factor = factor.max(1);
        if factor == 1 {
            return self.clone();
        }
        fn merged<T: crate::output::sampler::SampleValue>(
            v: &[T],
            kept: usize,
            factor: usize,
            how: Merge,
        ) -> Vec<T> {
            let mut v = v.to_vec();
            let kept = kept.min(v.len());
            let n = merge_windows(&mut v[kept..], factor, how);
            v.truncate(kept + n);
            v
        }
        let each = |series: &[Vec<f64>], how| -> Vec<Vec<f64>> {
            series
                .iter()
                .map(|v| merged(v, kept, factor, how))
                .collect()
        };
        Recording {
            t_s: merged(&self.t_s, kept, factor, Merge::End),
            u_m: each(&self.u_m, Merge::End),
            q_n: each(&self.q_n, Merge::Mean),
            r_m: each(&self.r_m, Merge::End),
            q_impact_n: each(&self.q_impact_n, Merge::Mean),
            contact: self
                .contact
                .iter()
                .map(|v| merged(v, kept, factor, Merge::Any))
                .collect(),
            every: self.every * factor as u64,
            sampler: Sampler::default(),
        }
    }

    /// Window length of a sample (steps).
    pub fn every(&self) -> u64 {
        self.every
    }

    /// The force level above which the figure clips impact spikes (N): a
    /// margin above the force without impacts; `None` without samples.
    pub fn clip_level_n(&self) -> Option<f64> {
        self.clip_level_of(None)
    }

    /// [`Self::clip_level_n`] of `points` only (`None`: all).
    pub fn clip_level_of(&self, points: Option<&[usize]>) -> Option<f64> {
        let smooth = self
            .q_n
            .iter()
            .zip(&self.q_impact_n)
            .enumerate()
            .filter(|(i, _)| points.is_none_or(|p| p.contains(i)))
            .flat_map(|(_, (q, qi))| q.iter().zip(qi).map(|(a, b)| a - b));
        let (lo, hi) = smooth.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        (lo <= hi).then(|| clip_level((lo, hi)))
    }

    /// Displacement (mm) of `points` (`None`: all), named `name(i)`.
    pub fn displacement_series(
        &self,
        points: Option<&[usize]>,
        name: &dyn Fn(usize) -> String,
    ) -> Vec<Series> {
        self.series(points, &|i, k| self.u_m[i][k] * 1e3, name)
    }

    /// Window-mean force (N) of `points` (`None`: all), named `name(i)`.
    /// With `clip_impacts` the spikes are cut at [`Self::clip_level_of`]
    /// the points (so the force without impacts sets the axis), drawn in
    /// thin lines, and the cut samples follow as one series of dots,
    /// [`CLIPPED_IMPACTS`]; the flag returned says whether any was cut.
    pub fn force_series(
        &self,
        clip_impacts: bool,
        points: Option<&[usize]>,
        name: &dyn Fn(usize) -> String,
    ) -> (Vec<Series>, bool) {
        let mut forces = self.series(points, &|i, k| self.q_n[i][k], name);
        let Some(top) = self.clip_level_of(points).filter(|_| clip_impacts) else {
            return (forces, false);
        };
        let mut marks = Vec::new();
        for s in &mut forces {
            for p in &mut s.points {
                if p.1 > top {
                    p.1 = top;
                    marks.push(*p);
                }
            }
            // one-pixel lines: wide ones overshoot the panel at the cuts
            s.style = Style::ThinLine;
        }
        let clipped = !marks.is_empty();
        if clipped {
            forces.push(Series {
                name: CLIPPED_IMPACTS.into(),
                points: marks,
                style: Style::Markers(3),
                color: Some(IMPACT_COLOR),
            });
        }
        (forces, clipped)
    }

    /// The drawn points: `points`, or all.
    fn chosen(&self, points: Option<&[usize]>) -> Vec<usize> {
        let p = self.u_m.len();
        points.map_or_else(
            || (0..p).collect(),
            |ps| ps.iter().copied().filter(|&i| i < p).collect(),
        )
    }

    /// `value(i, k)` over time for each chosen point, coloured by its index.
    fn series(
        &self,
        points: Option<&[usize]>,
        value: &dyn Fn(usize, usize) -> f64,
        name: &dyn Fn(usize) -> String,
    ) -> Vec<Series> {
        let chosen = self.chosen(points);
        chosen
            .iter()
            .map(|&i| {
                let pts = (0..self.t_s.len()).map(|k| (self.t_s[k], value(i, k)));
                let mut s = Series::line(name(i), pts.collect());
                s.color = Some(super::figures::point_color_index(&chosen, i));
                s
            })
            .collect()
    }

    /// The contact panel's lanes: lane `n` of point `chosen[n]` at `n`,
    /// raised by 0.7 while in contact, drawn as steps: window `k`'s state
    /// over its span `[t_{k-1}, t_k]`, a change a vertical edge at the
    /// window's start. A one-window contact is a narrow box, not a thick
    /// line's spike.
    fn contact_lanes(&self, chosen: &[usize], name: &dyn Fn(usize) -> String) -> Vec<Series> {
        chosen
            .iter()
            .enumerate()
            .map(|(lane, &i)| {
                let y = |k: usize| lane as f64 + if self.contact[i][k] { 0.7 } else { 0.0 };
                let mut pts = Vec::with_capacity(2 * self.t_s.len());
                for k in 0..self.t_s.len() {
                    if k > 0 && self.contact[i][k] != self.contact[i][k - 1] {
                        pts.push((self.t_s[k - 1], y(k)));
                    }
                    pts.push((self.t_s[k], y(k)));
                }
                let mut s = Series::line(name(i), pts);
                s.color = Some(super::figures::point_color_index(chosen, i));
                s
            })
            .collect()
    }

    /// Length of a sample's window (ms) for steps of `dt_s`.
    pub fn window_ms(&self, dt_s: f64) -> f64 {
        self.every as f64 * dt_s * 1e3
    }

    /// The run figure: `spec.panels` stacked over time, for the chosen
    /// points, one colour per point in every panel and one legend (in the
    /// first panel). With `clip_impacts` the force axis fits the force
    /// without impacts and impact spikes are cut a margin above it, each
    /// cut sample marked by a dot (impulse / dt of a rigid landing is tens
    /// of kN against a rolling force of about 1 kN).
    pub fn figure(&self, spec: &FigureSpec<'_>) -> Figure {
        let points = spec.points;
        let chosen = self.chosen(points);
        let window = summary::duration_text(self.window_ms(spec.dt_s) * 1e-3, 3);
        let panels = spec
            .panels
            .iter()
            .enumerate()
            .map(|(n, &what)| {
                let name = |i: usize| {
                    if n == 0 {
                        super::figures::point_legend_name(&chosen, i)
                    } else {
                        String::new()
                    }
                };
                let panel = |title: String, y_label: &str, series: Vec<Series>| Panel {
                    title,
                    x_label: "time t (s)".into(),
                    y_label: y_label.into(),
                    series,
                    ..Panel::default()
                };
                match what {
                    RunPanel::Displacement => panel(
                        "Displacement of the contact points (positive up)".into(),
                        "displacement u (mm)",
                        self.displacement_series(points, &name),
                    ),
                    // (clipped impacts are said by their legend entry)
                    RunPanel::Force => panel(
                        format!("Contact force, mean over {window} windows"),
                        "contact force q (N)",
                        self.force_series(spec.clip_impacts, points, &name).0,
                    ),
                    RunPanel::Gap => panel(
                        "Gap to the road (u − r)".into(),
                        "gap (mm)",
                        self.series(
                            points,
                            &|i, k| (self.u_m[i][k] - self.r_m[i][k]) * 1e3,
                            &name,
                        ),
                    ),
                    RunPanel::Contact => {
                        let chosen = self.chosen(points);
                        let lanes = self.contact_lanes(&chosen, &name);
                        Panel {
                            // the lanes named after their points
                            y_names: chosen.iter().map(|i| format!("p{i}")).collect(),
                            ..panel(
                                "Contact state (a lane per point, raised = in contact)".into(),
                                "point",
                                lanes,
                            )
                        }
                    }
                }
            })
            .collect();
        Figure {
            title: spec.title.to_string(),
            subtitle: spec.subtitle.to_string(),
            panels,
        }
    }
}

impl tirecontact_core::solver::drive::Probe for Recording {
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        Recording::after_step(self, sim);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tirecontact_io::Scene;
    use tirecontact_io::SceneSimulation;
    use tirecontact_io::scene::ContactScheme;

    /// Records the three-point preset (impacts at every landing) with `scheme`.
    fn record(scheme: ContactScheme) -> (Recording, f64) {
        let mut scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        scene.duration_s = 0.06;
        scene.contact_scheme = scheme;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut rec = Recording::new(scene.num_points(), scene.num_steps(), 3000);
        while !sim.finished() {
            sim.step().unwrap();
            rec.after_step(&sim);
        }
        (rec, scene.dt_s)
    }

    fn highest(series: &[Series], name_prefix: &str) -> f64 {
        series
            .iter()
            .filter(|s| s.name.starts_with(name_prefix))
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    #[test]
    fn the_force_panel_clips_impact_spikes_a_margin_above_the_rolling_force() {
        for scheme in [ContactScheme::Located, ContactScheme::Paper] {
            let (rec, dt) = record(scheme);
            let raw = rec.q_n.iter().flatten().fold(0.0f64, |m, &q| m.max(q));
            let top = rec.clip_level_n().unwrap();
            // the spikes are impulses / dt: far above the rolling force
            assert!(raw > 5.0 * top, "{scheme:?}: spikes {raw} N, clip {top} N");
            let spec = |clip_impacts| FigureSpec {
                title: "t",
                subtitle: "s",
                dt_s: dt,
                clip_impacts,
                points: None,
                panels: &RunPanel::RUN,
            };
            let clipped = rec.figure(&spec(true));
            let forces = &clipped.panels[1].series;
            assert!((highest(forces, "") - top).abs() <= 1e-9 * top);
            let marks = forces.iter().find(|s| s.name == CLIPPED_IMPACTS).unwrap();
            assert!(!marks.points.is_empty());
            assert!(marks.points.iter().all(|p| p.1 == top));
            // said once, by the legend entry, not again in the caption
            assert!(!clipped.panels[1].title.contains("clipped"));
            // unclipped: the spikes are drawn whole
            let full = rec.figure(&spec(false));
            assert_eq!(highest(&full.panels[1].series, ""), raw);
            assert!(
                full.panels[1]
                    .series
                    .iter()
                    .all(|s| s.name != CLIPPED_IMPACTS)
            );
        }
    }

    /// The contact lanes are steps: every segment is horizontal (a state)
    /// or vertical (a change), so that a thick line draws no spike at a
    /// short contact; each lane sits at its height, raised while in
    /// contact, keeps every sample, and draws each window's state over the
    /// window (`t_s` is a window's end).
    #[test]
    fn the_contact_lanes_are_drawn_as_steps() {
        let (rec, dt) = record(ContactScheme::Located);
        let fig = rec.figure(&FigureSpec {
            title: "t",
            subtitle: "s",
            dt_s: dt,
            clip_impacts: true,
            points: None,
            panels: &[RunPanel::Contact],
        });
        let lanes = &fig.panels[0].series;
        assert_eq!(lanes.len(), rec.contact.len());
        let mut changes = 0;
        for (lane, s) in lanes.iter().enumerate() {
            let lane = lane as f64;
            assert!(s.points.iter().all(|p| p.1 == lane || p.1 == lane + 0.7));
            for w in s.points.windows(2) {
                let (a, b) = (w[0], w[1]);
                assert!(a.0 == b.0 || a.1 == b.1, "lane {lane}: {a:?} to {b:?}");
                changes += usize::from(a.1 != b.1);
            }
            let c = &rec.contact[lane as usize];
            assert_eq!(s.points.len() - changes_in(c), rec.t_s.len());
            // the drawn height inside window k is window k's state
            for k in 1..rec.t_s.len() {
                let mid = 0.5 * (rec.t_s[k - 1] + rec.t_s[k]);
                let drawn = s
                    .points
                    .windows(2)
                    .find(|w| w[0].1 == w[1].1 && w[0].0 <= mid && mid <= w[1].0)
                    .map(|w| w[0].1);
                let want = lane + if c[k] { 0.7 } else { 0.0 };
                assert_eq!(drawn, Some(want), "lane {lane}, window {k}");
            }
        }
        assert!(changes > 0, "the run has landings and releases");
    }

    /// Changes of state between consecutive samples.
    fn changes_in(c: &[bool]) -> usize {
        c.windows(2).filter(|w| w[0] != w[1]).count()
    }

    /// Merging the samples of a run recorded every step into windows of
    /// `f` steps gives what recording with windows of `f` steps gives.
    #[test]
    fn merged_samples_equal_a_recording_with_longer_windows() {
        let mut scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        scene.duration_s = 0.01;
        let n = scene.num_steps();
        let f = 7u64;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut fine = Recording::new(scene.num_points(), n, n);
        let mut coarse = Recording::new(scene.num_points(), n, n.div_ceil(f));
        assert_eq!((fine.every(), coarse.every()), (1, f));
        while !sim.finished() {
            sim.step().unwrap();
            fine.after_step(&sim);
            coarse.after_step(&sim);
        }
        let merged = fine.merged(f as usize);
        assert_eq!(merged.every(), f);
        assert_eq!(merged.len(), coarse.len());
        assert_eq!(merged.t_s, coarse.t_s);
        assert_eq!(merged.u_m, coarse.u_m);
        assert_eq!(merged.r_m, coarse.r_m);
        assert_eq!(merged.contact, coarse.contact);
        assert!(merged.contact.iter().flatten().any(|&c| c));
        assert!(merged.contact.iter().flatten().any(|&c| !c));
        for (a, b) in [
            (&merged.q_n, &coarse.q_n),
            (&merged.q_impact_n, &coarse.q_impact_n),
        ] {
            for (x, y) in a.iter().flatten().zip(b.iter().flatten()) {
                assert!((x - y).abs() <= 1e-9 * (1.0 + y.abs()), "{x} vs {y}");
            }
        }
    }

    /// The figure draws the chosen points only, one colour per point in
    /// every panel, the contact lanes named after their points.
    #[test]
    fn the_time_plots_figure_draws_the_chosen_points_in_four_panels() {
        let (rec, dt) = record(ContactScheme::Located);
        let fig = rec.figure(&FigureSpec {
            title: "t",
            subtitle: "s",
            dt_s: dt,
            clip_impacts: true,
            points: Some(&[0, 2]),
            panels: &RunPanel::TIME_PLOTS,
        });
        assert_eq!(fig.panels.len(), 4);
        for panel in &fig.panels {
            let colours: Vec<_> = panel
                .series
                .iter()
                .filter(|s| s.name != CLIPPED_IMPACTS)
                .map(|s| s.color)
                .collect();
            assert_eq!(colours, [Some(0), Some(2)], "{}", panel.title);
        }
        let names: Vec<&str> = fig.panels[0]
            .series
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(names, ["point 0", "point 2"]);
        assert_eq!(fig.panels[3].y_names, ["p0", "p2"]);
        // lane 1 (point 2) sits at 1 or 1.7
        assert!(
            fig.panels[3].series[1]
                .points
                .iter()
                .all(|p| p.1 == 1.0 || p.1 == 1.7)
        );
        // the gap is u - r in mm
        let k = rec.len() / 2;
        let gap = fig.panels[2].series[1].points[k].1;
        assert!((gap - (rec.u_m[2][k] - rec.r_m[2][k]) * 1e3).abs() < 1e-12);
    }
}
