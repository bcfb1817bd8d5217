//! A/B comparison: a run pinned as the reference (its scene and its
//! recording, owned, so it survives any later parameter change), the
//! difference of a current run against it, and its export as CSV.

use crate::output::record::Recording;
use crate::output::summary::short_num;
use std::io::Write;
use tirecontact_core::base::error::count;
use tirecontact_io::Scene;
use tirecontact_io::scene::Point;

/// Points whose positions along the road and across the tread each differ
/// by less than this (m) are the same point of two scenes.
pub const SAME_PLACE_M: f64 = 1e-6;

/// A run kept as a reference.
#[derive(Debug, Clone)]
pub struct PinnedRun {
    /// Name shown in legends, e.g. `"A: V = 10 m/s"`.
    pub label: String,
    /// The scene as it was when pinned.
    pub scene: Scene,
    /// The number of modes its tyre had (given or identified).
    pub num_modes: usize,
    /// Its time histories.
    pub recording: Recording,
}

/// `current - pinned` on the current run's time grid, over the times both
/// runs cover, per point of the current run that has a pinned point at the
/// same place (the others have empty series and a NaN RMS).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunDifference {
    pub t_s: Vec<f64>,
    /// For each current point, the pinned point it is compared with.
    pub matched: Vec<Option<usize>>,
    /// `du[i][k]` (m).
    pub du_m: Vec<Vec<f64>>,
    /// `dq[i][k]` (N).
    pub dq_n: Vec<Vec<f64>>,
    /// RMS of `du` per point (m).
    pub rms_du_m: Vec<f64>,
    /// RMS of `dq` per point (N).
    pub rms_dq_n: Vec<f64>,
}

/// Linear interpolation of `(t, y)` at `t0` (`t` increasing); `None` outside.
fn interp(t: &[f64], y: &[f64], t0: f64) -> Option<f64> {
    let k = t.partition_point(|&x| x < t0);
    if k == t.len() {
        return None;
    }
    if t[k] == t0 {
        return Some(y[k]);
    }
    if k == 0 {
        return None;
    }
    let s = (t0 - t[k - 1]) / (t[k] - t[k - 1]);
    Some(y[k - 1] + s * (y[k] - y[k - 1]))
}

fn rms(x: &[f64]) -> f64 {
    if x.is_empty() {
        0.0
    } else {
        (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
    }
}

impl PinnedRun {
    /// `scene`'s run with its tyre of `num_modes` modes, recorded in
    /// `recording`, pinned under `label`.
    pub fn new(
        label: impl Into<String>,
        scene: &Scene,
        num_modes: usize,
        recording: &Recording,
    ) -> Self {
        PinnedRun {
            label: label.into(),
            scene: scene.clone(),
            num_modes,
            recording: recording.clone(),
        }
    }

    /// For each of `points` (the current scene's), the pinned point at the
    /// same place along the road and across the tread (within
    /// [`SAME_PLACE_M`]), if any.
    pub fn matched(&self, points: &[Point]) -> Vec<Option<usize>> {
        let recorded = self.recording.u_m.len();
        points
            .iter()
            .map(|p| {
                self.scene.points.iter().take(recorded).position(|q| {
                    (q.x_m - p.x_m).abs() < SAME_PLACE_M && (q.y_m - p.y_m).abs() < SAME_PLACE_M
                })
            })
            .collect()
    }

    /// How `scene` (its tyre of `num_modes` modes) differs from the pinned
    /// scene in ways that make the comparison one of unlike runs: its
    /// points, its time step, its number of modes, its speed and road (the
    /// runs are excited differently). One sentence each;
    /// empty when the runs are alike in these.
    pub fn unlike(&self, scene: &Scene, num_modes: usize) -> Vec<String> {
        let mut out = Vec::new();
        let matched = self.matched(&scene.points);
        let same = matched.iter().enumerate().all(|(i, m)| *m == Some(i));
        if scene.points.len() != self.scene.points.len() || !same {
            let pairs: Vec<String> = matched
                .iter()
                .enumerate()
                .filter_map(|(i, m)| {
                    m.map(|j| {
                        if i == j {
                            format!("p{i}")
                        } else {
                            format!("p{i} (reference p{j})")
                        }
                    })
                })
                .collect();
            let compared = if pairs.is_empty() {
                "no point is at the same place: nothing is compared".to_string()
            } else {
                format!(
                    "compared only at the {} at the same place: {}",
                    count(pairs.len(), "point"),
                    pairs.join(", ")
                )
            };
            out.push(format!(
                "The reference has {}, this scene {}; {compared}.",
                count(self.scene.points.len(), "point"),
                count(scene.points.len(), "point")
            ));
        }
        if scene.dt_s != self.scene.dt_s {
            out.push(format!(
                "Time step {} µs in the reference, {} µs here: forces are means over different steps, their difference is approximate.",
                short_num(self.scene.dt_s * 1e6, 4),
                short_num(scene.dt_s * 1e6, 4)
            ));
        }
        if num_modes != self.num_modes {
            out.push(format!(
                "The reference's tyre has {}, this one {}.",
                count(self.num_modes, "mode"),
                count(num_modes, "mode")
            ));
        }
        let excitation: Vec<String> = tirecontact_io::scene::edits_since(&self.scene, scene)
            .into_iter()
            .filter(|e| e.starts_with("speed") || e.contains("road"))
            .collect();
        if !excitation.is_empty() {
            out.push(format!(
                "The runs are excited differently (reference -> this scene): {}.",
                excitation.join("; ")
            ));
        }
        out
    }

    /// `current - self` at the current run's `points` that have a pinned
    /// point at the same place ([`Self::matched`]), the pinned run
    /// interpolated linearly onto the current run's samples. Forces are
    /// window means: with different windows their difference is approximate.
    pub fn difference(&self, points: &[Point], current: &Recording) -> RunDifference {
        let a = &self.recording;
        let p = current.u_m.len();
        let mut matched = self.matched(points);
        matched.resize(p, None);
        let mut d = RunDifference {
            du_m: vec![Vec::new(); p],
            dq_n: vec![Vec::new(); p],
            ..RunDifference::default()
        };
        let (t0, t1) = match (a.t_s.first(), a.t_s.last()) {
            (Some(&t0), Some(&t1)) => (t0, t1),
            _ => (f64::INFINITY, f64::NEG_INFINITY),
        };
        for (k, &t) in current.t_s.iter().enumerate() {
            if !(t0..=t1).contains(&t) {
                continue;
            }
            d.t_s.push(t);
            for (i, m) in matched.iter().enumerate() {
                let Some(j) = *m else { continue };
                let u = interp(&a.t_s, &a.u_m[j], t).unwrap_or(f64::NAN);
                let q = interp(&a.t_s, &a.q_n[j], t).unwrap_or(f64::NAN);
                d.du_m[i].push(current.u_m[i][k] - u);
                d.dq_n[i].push(current.q_n[i][k] - q);
            }
        }
        let rms_of = |x: &Vec<f64>, m: &Option<usize>| if m.is_some() { rms(x) } else { f64::NAN };
        d.rms_du_m = d
            .du_m
            .iter()
            .zip(&matched)
            .map(|(x, m)| rms_of(x, m))
            .collect();
        d.rms_dq_n = d
            .dq_n
            .iter()
            .zip(&matched)
            .map(|(x, m)| rms_of(x, m))
            .collect();
        d.matched = matched;
        d
    }

    /// Writes the pinned histories: `t_s, u{i}_m.., q{i}_N..`.
    pub fn write_csv<W: Write>(&self, out: W) -> Result<(), csv::Error> {
        let r = &self.recording;
        let p = r.u_m.len();
        let mut w = csv::Writer::from_writer(out);
        let mut header = vec!["t_s".to_string()];
        header.extend((0..p).map(|i| format!("u{i}_m")));
        header.extend((0..p).map(|i| format!("q{i}_N")));
        w.write_record(&header)?;
        for (k, t) in r.t_s.iter().enumerate() {
            let mut row = vec![format!("{t}")];
            row.extend(r.u_m.iter().map(|u| format!("{}", u[k])));
            row.extend(r.q_n.iter().map(|q| format!("{}", q[k])));
            w.write_record(&row)?;
        }
        w.flush()?;
        Ok(())
    }
}
