//! A/B comparison: a run pinned as the reference (its scene and its
//! recording, owned, so it survives any later parameter change), the
//! difference of a current run against it, and its export as CSV.

use crate::Scene;
use crate::output::record::Recording;
use std::io::Write;

/// A run kept as a reference.
#[derive(Debug, Clone)]
pub struct PinnedRun {
    /// Name shown in legends, e.g. `"A: V = 10 m/s"`.
    pub label: String,
    /// The scene as it was when pinned.
    pub scene: Scene,
    /// Its time histories.
    pub recording: Recording,
}

/// `current - pinned` on the current run's time grid, over the times both
/// runs cover and the points both have.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunDifference {
    pub t_s: Vec<f64>,
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
    pub fn new(label: impl Into<String>, scene: &Scene, recording: &Recording) -> Self {
        PinnedRun {
            label: label.into(),
            scene: scene.clone(),
            recording: recording.clone(),
        }
    }

    /// `current - self`, the pinned run interpolated linearly onto the
    /// current run's samples. Forces are window means: with different
    /// decimation windows their difference is approximate.
    pub fn difference(&self, current: &Recording) -> RunDifference {
        let a = &self.recording;
        let p = a.u_m.len().min(current.u_m.len());
        let mut d = RunDifference {
            du_m: vec![Vec::new(); p],
            dq_n: vec![Vec::new(); p],
            ..RunDifference::default()
        };
        for (k, &t) in current.t_s.iter().enumerate() {
            let vals: Option<Vec<(f64, f64)>> = (0..p)
                .map(|i| Some((interp(&a.t_s, &a.u_m[i], t)?, interp(&a.t_s, &a.q_n[i], t)?)))
                .collect();
            let Some(vals) = vals else { continue };
            d.t_s.push(t);
            for (i, (u, q)) in vals.into_iter().enumerate() {
                d.du_m[i].push(current.u_m[i][k] - u);
                d.dq_n[i].push(current.q_n[i][k] - q);
            }
        }
        d.rms_du_m = d.du_m.iter().map(|x| rms(x)).collect();
        d.rms_dq_n = d.dq_n.iter().map(|x| rms(x)).collect();
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
