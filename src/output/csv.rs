//! The run CSV (pandas-friendly): `t_s`, then `u{i}_m`, `v{i}_mps`, `q{i}_N`
//! (step-mean force, or mean over the `every` steps of a row so impulses are
//! kept), `gap{i}_m`, `contact{i}` (0/1).

use crate::simulation::Simulation;
use std::io::Write;

/// The header row for `p` points.
pub fn header(p: usize) -> Vec<String> {
    let mut h = vec!["t_s".to_string()];
    for (prefix, suffix) in [
        ("u", "_m"),
        ("v", "_mps"),
        ("q", "_N"),
        ("gap", "_m"),
        ("contact", ""),
    ] {
        h.extend((0..p).map(|i| format!("{prefix}{i}{suffix}")));
    }
    h
}

/// Bytes of one value in a row: `-1.234567890e-03` and its comma.
pub const BYTES_PER_VALUE: u64 = 17;

/// Estimated size (bytes) of the CSV of a run of `steps` steps of `p` points
/// written every `every` steps: rows (header, initial state, one per `every`
/// steps and a last partial one) × columns (`1 + 5 p`) × [`BYTES_PER_VALUE`].
/// An overestimate for the 0/1 contact columns; exact enough to refuse a run
/// up front.
pub fn estimated_bytes(steps: u64, every: u64, p: usize) -> f64 {
    let rows = steps.div_ceil(every.max(1)) as f64 + 3.0;
    rows * (1 + 5 * p) as f64 * BYTES_PER_VALUE as f64
}

/// A byte count for messages, in decimal units (`8.52 TB`).
pub fn human_bytes(b: f64) -> String {
    let units = ["bytes", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut x = b;
    let mut k = 0;
    while x >= 1000.0 && k + 1 < units.len() {
        x /= 1000.0;
        k += 1;
    }
    if k == 0 {
        format!("{x:.0} bytes")
    } else {
        format!("{x:.2} {}", units[k])
    }
}

/// Streams rows of a run, averaging forces over `every` steps.
pub struct RunWriter<W: Write> {
    w: csv::Writer<W>,
    every: u64,
    count: u64,
    q_sum: Vec<f64>,
    row: Vec<String>,
}

impl<W: Write> RunWriter<W> {
    pub fn new(out: W, p: usize, every: u64) -> Result<Self, csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        w.write_record(header(p))?;
        Ok(RunWriter {
            w,
            every: every.max(1),
            count: 0,
            q_sum: vec![0.0; p],
            row: Vec::with_capacity(1 + 5 * p),
        })
    }

    /// Writes the initial state (t = 0) row.
    pub fn write_initial(&mut self, sim: &Simulation) -> Result<(), csv::Error> {
        self.q_sum.fill(0.0);
        self.write_row(sim, 1)
    }

    /// Call after every step; writes a row every `every` steps.
    pub fn after_step(&mut self, sim: &Simulation) -> Result<(), csv::Error> {
        for (s, q) in self.q_sum.iter_mut().zip(sim.force_n()) {
            *s += q;
        }
        self.count += 1;
        if self.count.is_multiple_of(self.every) || sim.finished() {
            let n = self.count % self.every;
            let n = if n == 0 { self.every } else { n };
            self.write_row(sim, n)?;
            self.q_sum.fill(0.0);
            self.count = 0;
        }
        Ok(())
    }

    fn write_row(&mut self, sim: &Simulation, n: u64) -> Result<(), csv::Error> {
        let p = sim.num_points();
        self.row.clear();
        self.row.push(format!("{:.9e}", sim.time_s()));
        self.row
            .extend(sim.displacement_m().iter().map(|x| format!("{x:.9e}")));
        self.row
            .extend(sim.velocity_mps().iter().map(|x| format!("{x:.9e}")));
        self.row
            .extend(self.q_sum.iter().map(|x| format!("{:.9e}", x / n as f64)));
        self.row
            .extend((0..p).map(|i| format!("{:.9e}", sim.gap_m(i))));
        self.row
            .extend(sim.in_contact().iter().map(|&c| (c as u8).to_string()));
        self.w.write_record(&self.row)
    }

    pub fn finish(mut self) -> std::io::Result<W> {
        self.w.flush()?;
        self.w.into_inner().map_err(|e| e.into_error())
    }
}
