//! The scaling study's report: the table (CSV and markdown), the fitted
//! exponents and affine fits of the cost per step, the contact's share, and
//! the figure, from the measured sizes. The command line measures each size
//! in a process of its own ([`ScalingRow::to_line`] and
//! [`ScalingRow::from_line`] carry a row between them) and writes what this
//! module builds.

use super::{PRELOAD_M, Regime, ScalingRow, TREAD_TOTAL_N_M, figure, line_fit, loglog_slope};
use crate::output::figures::Figure;

/// A child's line that is not a measured row.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "P = {points}, K = {modes}: unreadable line `{line}`: expected P,K,steps,step_s,free_step_s,on_road,events_per_step,factorisations_per_step"
)]
pub struct UnreadableLine {
    pub points: usize,
    pub modes: usize,
    pub line: String,
}

impl ScalingRow {
    /// The row as the one CSV line a child process prints (instruction
    /// counts are added by the parent).
    pub fn to_line(&self) -> String {
        format!(
            "{},{},{},{:e},{:e},{},{},{}",
            self.points,
            self.modes,
            self.steps,
            self.step_s,
            self.free_step_s,
            self.on_road,
            self.events_per_step,
            self.factorisations_per_step
        )
    }

    /// The row of size `(points, modes, regime)` from the line its child
    /// printed ([`ScalingRow::to_line`]).
    pub fn from_line(
        points: usize,
        modes: usize,
        regime: Regime,
        line: &str,
    ) -> Result<ScalingRow, UnreadableLine> {
        let f: Vec<&str> = line.trim().split(',').collect();
        let num = |i: usize| -> Result<f64, UnreadableLine> {
            f.get(i)
                .and_then(|x| x.trim().parse().ok())
                .ok_or_else(|| UnreadableLine {
                    points,
                    modes,
                    line: line.trim().to_string(),
                })
        };
        Ok(ScalingRow {
            points,
            regime,
            modes,
            steps: num(2)? as u64,
            step_s: num(3)?,
            free_step_s: num(4)?,
            on_road: num(5)?,
            events_per_step: num(6)?,
            factorisations_per_step: num(7)?,
            instructions_per_step: None,
            free_instructions_per_step: None,
        })
    }
}

/// One measured size of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredSize {
    /// In the scan over the points (at fixed modes), else over the modes.
    pub by_points: bool,
    pub row: ScalingRow,
    /// Peak resident memory of one run in a process of its own (kB).
    pub peak_rss_kb: Option<u64>,
}

/// The measured sizes of a study and how they were timed.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalingReport {
    pub sizes: Vec<MeasuredSize>,
    /// Timed runs of each size (the fastest is kept).
    pub repeats: usize,
    /// Solver threads of each run.
    pub threads: usize,
}

/// The CSV table's header.
pub const CSV_HEADER: &str = "contact,points,modes,steps,step_s,free_step_s,contact_share,on_road,events_per_step,factorisations_per_step,instructions_per_step,free_instructions_per_step,contact_share_instructions,max_rss_kb\n";

fn or_empty(x: Option<f64>, f: impl Fn(f64) -> String) -> String {
    x.map_or(String::new(), f)
}

fn or_dash(t: String) -> String {
    if t.is_empty() { "-".to_string() } else { t }
}

impl ScalingReport {
    /// The rows of one scan (by `P` or by `K`) of a regime, in order.
    fn scan(&self, by_points: bool, regime: Regime) -> Vec<&ScalingRow> {
        self.sizes
            .iter()
            .filter(|s| s.by_points == by_points && s.row.regime == regime)
            .map(|s| &s.row)
            .collect()
    }

    /// The fixed modes of the scan by points and the fixed points of the
    /// scan by modes.
    fn fixed(&self) -> (usize, usize) {
        let first = |by_points: bool| self.sizes.iter().find(|s| s.by_points == by_points);
        (
            first(true).map_or(0, |s| s.row.modes),
            first(false).map_or(0, |s| s.row.points),
        )
    }

    fn x(r: &ScalingRow, by_points: bool) -> f64 {
        (if by_points { r.points } else { r.modes }) as f64
    }

    /// Fitted exponent of the wall time per step (with contact or off the
    /// road) along a scan.
    pub fn slope(&self, by_points: bool, regime: Regime, free: bool) -> f64 {
        let xy: Vec<(f64, f64)> = self
            .scan(by_points, regime)
            .iter()
            .map(|r| {
                let y = if free { r.free_step_s } else { r.step_s };
                (Self::x(r, by_points), y)
            })
            .collect();
        loglog_slope(&xy)
    }

    /// `(x, instructions per step)` of a scan where every row was counted
    /// and there are at least two.
    fn instructions(&self, by_points: bool, regime: Regime) -> Option<Vec<(f64, f64)>> {
        let xy: Option<Vec<(f64, f64)>> = self
            .scan(by_points, regime)
            .iter()
            .map(|r| r.instructions_per_step.map(|n| (Self::x(r, by_points), n)))
            .collect();
        xy.filter(|v| v.len() >= 2)
    }

    /// Fitted exponent of the instructions per step along a scan, where
    /// counted.
    pub fn instruction_slope(&self, by_points: bool, regime: Regime) -> Option<f64> {
        self.instructions(by_points, regime)
            .map(|v| loglog_slope(&v))
    }

    /// The table as CSV ([`CSV_HEADER`], one row per size).
    pub fn csv(&self) -> String {
        let mut csv = String::from(CSV_HEADER);
        for s in &self.sizes {
            let r = &s.row;
            csv.push_str(&format!(
                "{},{},{},{},{:e},{:e},{:.4},{:.4},{:.4},{:.4},{},{},{},{}\n",
                r.regime.key(),
                r.points,
                r.modes,
                r.steps,
                r.step_s,
                r.free_step_s,
                r.contact_share(),
                r.on_road,
                r.events_per_step,
                r.factorisations_per_step,
                or_empty(r.instructions_per_step, |n| format!("{n:.0}")),
                or_empty(r.free_instructions_per_step, |n| format!("{n:.0}")),
                or_empty(r.contact_share_instructions(), |x| format!("{x:.4}")),
                s.peak_rss_kb.map_or(String::new(), |v| v.to_string())
            ));
        }
        csv
    }

    /// The markdown report: how the sizes were measured, the table, the
    /// fitted exponents, the affine fits of the instructions with rigid
    /// contact, and where the contact takes more than half of a step.
    pub fn markdown(&self) -> String {
        let mut md = self.markdown_table();
        md.push_str(&self.markdown_exponents());
        md.push_str(&self.markdown_affine());
        md.push_str(&self.markdown_dominant());
        md.push_str(&self.markdown_active_set());
        md
    }

    fn markdown_table(&self) -> String {
        let mut md = format!(
            "# Cost of a step against the problem's size\n\nRank-1 modes; the middle third of the points pressed by up to {} mm on a 0.1 mm sine road at 10 m/s; dt = 1e-5 s. Rigid contact holds about one point on the road (the smooth mode shapes lift the neighbours of a pressed point); a soft tread spring at each point (compliant contact, {:e} N/m shared by the points) holds the pressed third. The patch is a grid 20 points across the tread by P / 20 along, 5 mm apart, on a tyre with a width (rank-1 plate modes, up to 7 half-waves across), with tread springs. Each size is timed in its own process on {} solver thread(s), the fastest of {} run(s); its peak resident memory is that of one 0.1 s run in a process of its own. The contact's share is 1 − (the same scene off the road) / (with contact), by wall time and by instructions. Instructions per step: callgrind's count over 1000 rolling steps (`-` without valgrind or with --quick); unlike wall times they repeat exactly.\n\n| contact | points P | modes K | µs per step | off the road | contact share | points on the road | events per step | factorisations per step | instructions per step | off the road | contact share by instructions | peak memory (MB) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            PRELOAD_M * 1e3,
            TREAD_TOTAL_N_M,
            self.threads,
            self.repeats,
        );
        for s in &self.sizes {
            let r = &s.row;
            md.push_str(&format!(
                "| {} | {} | {} | {:.2} | {:.2} | {:.0} % | {:.1} | {:.3} | {:.3} | {} | {} | {} | {} |\n",
                r.regime.key(),
                r.points,
                r.modes,
                r.step_s * 1e6,
                r.free_step_s * 1e6,
                100.0 * r.contact_share(),
                r.on_road * r.points as f64,
                r.events_per_step,
                r.factorisations_per_step,
                or_dash(or_empty(r.instructions_per_step, |n| format!("{n:.0}"))),
                or_dash(or_empty(r.free_instructions_per_step, |n| format!("{n:.0}"))),
                or_dash(or_empty(r.contact_share_instructions(), |x| format!(
                    "{:.0} %",
                    100.0 * x
                ))),
                s.peak_rss_kb
                    .map_or("-".into(), |v| format!("{:.1}", v as f64 / 1024.0))
            ));
        }
        md
    }

    fn markdown_exponents(&self) -> String {
        let (k_fixed, p_fixed) = self.fixed();
        let mut md = format!(
            "\nFitted exponents (least squares, log-log) of the time per step: off the road P^{:.2} (K = {k_fixed}) and K^{:.2} (P = {p_fixed}).\n",
            self.slope(true, Regime::Rigid, true),
            self.slope(false, Regime::Rigid, true),
        );
        let exponent = |by_points: bool, regime: Regime| {
            if self.scan(by_points, regime).len() < 2 {
                "—".to_string()
            } else {
                format!("{:.2}", self.slope(by_points, regime, false))
            }
        };
        for regime in Regime::ALL {
            md.push_str(&format!(
                "- {}: P^{}, K^{}",
                regime.label(),
                exponent(true, regime),
                exponent(false, regime)
            ));
            if let (Some(a), Some(b)) = (
                self.instruction_slope(true, regime),
                self.instruction_slope(false, regime),
            ) {
                md.push_str(&format!("; instructions per step P^{a:.2}, K^{b:.2}"));
            }
            md.push_str(".\n");
        }
        md
    }

    /// Fitted exponent of the contact's cost (time per step with contact
    /// less off the road) against the points on the road, over the scan by
    /// points of a regime; `None` with fewer than two sizes or a cost not
    /// above zero.
    pub fn active_set_slope(&self, regime: Regime) -> Option<f64> {
        let xy: Vec<(f64, f64)> = self
            .scan(true, regime)
            .iter()
            .map(|r| (r.on_road * r.points as f64, r.step_s - r.free_step_s))
            .filter(|&(s, c)| s > 0.0 && c > 0.0)
            .collect();
        (xy.len() >= 2).then(|| loglog_slope(&xy))
    }

    /// The contact's cost against the active set, for the regimes whose
    /// pressed third is on the road.
    fn markdown_active_set(&self) -> String {
        let mut md = String::new();
        for regime in [Regime::Tread, Regime::Patch] {
            if let Some(a) = self.active_set_slope(regime) {
                let on: Vec<String> = self
                    .scan(true, regime)
                    .iter()
                    .map(|r| format!("{:.0}", r.on_road * r.points as f64))
                    .collect();
                md.push_str(&format!(
                    "\n{}: the contact's cost per step (with contact less off the road) grows as |S|^{a:.2} in the points on the road ({}).\n",
                    regime.label(),
                    on.join(", ")
                ));
            }
        }
        md
    }

    /// The small active set's instructions against `K` and against `P`:
    /// affine.
    fn markdown_affine(&self) -> String {
        let (k_fixed, p_fixed) = self.fixed();
        let fit = |by_points: bool| {
            self.instructions(by_points, Regime::Rigid)
                .map(|v| line_fit(&v))
        };
        match (fit(false), fit(true)) {
            (Some((ak, bk)), Some((ap, bp))) => format!(
                "\nWith rigid contact (a small active set) the instructions per step are {ak:.0} + {bk:.1} K at P = {p_fixed} and {ap:.0} + {bp:.1} P at K = {k_fixed}: each mode adds {:.2} instructions per point and step, each point {:.2} per mode (the O(K·P) modal update), on top of parts in P or K alone.\n",
                bk / p_fixed.max(1) as f64,
                bp / k_fixed.max(1) as f64
            ),
            _ => String::new(),
        }
    }

    /// The first `P` where the contact takes more than half of a step with
    /// tread springs, by instructions where counted.
    fn markdown_dominant(&self) -> String {
        let share = |r: &ScalingRow| {
            r.contact_share_instructions()
                .map_or((r.contact_share(), "wall time"), |s| (s, "instructions"))
        };
        let dominant = self
            .scan(true, Regime::Tread)
            .into_iter()
            .find(|r| share(r).0 > 0.5);
        match dominant {
            Some(r) => format!(
                "\nWith the pressed third on the road the contact takes more than half of a step from P = {} ({:.1} points on the road, {:.0} % of the step by {}).\n",
                r.points,
                r.on_road * r.points as f64,
                100.0 * share(r).0,
                share(r).1
            ),
            None => "\nWith the pressed third on the road the contact stays below half of a step at every measured P.\n".to_string(),
        }
    }

    /// The figure ([`figure`]) of both scans, both regimes.
    pub fn figure(&self) -> Figure {
        let rows = |by_points: bool| -> Vec<ScalingRow> {
            Regime::ALL
                .iter()
                .flat_map(|&r| self.scan(by_points, r).into_iter().cloned())
                .collect()
        };
        figure(&rows(true), &rows(false))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A size whose times follow `c P^a K^b` (with contact) and `P^a K^b`
    /// off the road, with instructions `i0 + i1 P K` where asked.
    fn size(by_points: bool, p: usize, k: usize, regime: Regime, counted: bool) -> MeasuredSize {
        let (pf, kf) = (p as f64, k as f64);
        let c = if regime == Regime::Tread { 4.0 } else { 1.5 };
        let free = 1e-7 * pf.powf(0.9) * kf.powf(1.1);
        let ins = |extra: f64| counted.then_some(8300.0 + 3.0 * pf * kf + extra);
        MeasuredSize {
            by_points,
            row: ScalingRow {
                points: p,
                regime,
                modes: k,
                steps: 1000,
                step_s: c * free,
                free_step_s: free,
                on_road: if regime == Regime::Tread {
                    1.0 / 3.0
                } else {
                    1.0 / pf
                },
                events_per_step: 0.01,
                factorisations_per_step: 0.5,
                instructions_per_step: ins(if regime == Regime::Tread { 1e6 } else { 0.0 }),
                free_instructions_per_step: ins(0.0),
            },
            peak_rss_kb: Some(2048),
        }
    }

    fn report(counted: bool) -> ScalingReport {
        let mut sizes = Vec::new();
        for regime in Regime::ALL {
            for p in [5, 20, 80, 400] {
                sizes.push(size(true, p, 400, regime, counted));
            }
            for k in [10, 50, 400] {
                sizes.push(size(false, 60, k, regime, counted));
            }
        }
        ScalingReport {
            sizes,
            repeats: 5,
            threads: 1,
        }
    }

    #[test]
    fn a_child_line_carries_its_row_exactly() {
        let row = size(true, 20, 50, Regime::Tread, false).row;
        let back = ScalingRow::from_line(20, 50, Regime::Tread, &row.to_line()).unwrap();
        assert_eq!(back, row);
        let bad = ScalingRow::from_line(20, 50, Regime::Rigid, "20,50,x").unwrap_err();
        let msg = bad.to_string();
        assert!(
            msg.contains("P = 20, K = 50") && msg.contains("`20,50,x`"),
            "{msg}"
        );
    }

    #[test]
    fn the_fitted_exponents_are_those_of_the_power_laws() {
        let r = report(false);
        for regime in Regime::ALL {
            assert!((r.slope(true, regime, false) - 0.9).abs() < 1e-12);
            assert!((r.slope(false, regime, false) - 1.1).abs() < 1e-12);
            assert!((r.slope(true, regime, true) - 0.9).abs() < 1e-12);
        }
        let md = r.markdown();
        assert!(
            md.contains("off the road P^0.90 (K = 400) and K^1.10 (P = 60)"),
            "{md}"
        );
        assert!(md.contains("- tread springs: P^0.90, K^1.10.\n"), "{md}");
        // without instruction counts: no affine fit, the share by wall time
        assert!(!md.contains("instructions per step are"), "{md}");
        assert!(
            md.contains("more than half of a step from P = 5 (1.7 points on the road, 75 % of the step by wall time)"),
            "{md}"
        );
    }

    #[test]
    fn the_affine_fit_of_the_instructions_finds_the_cost_per_mode_and_point() {
        let md = report(true).markdown();
        // 8300 + 3 P K: at P = 60, 8300 + 180 K; at K = 400, 8300 + 1200 P;
        // 3 instructions per mode, point and step
        assert!(
            md.contains("8300 + 180.0 K at P = 60 and 8300 + 1200.0 P at K = 400: each mode adds 3.00 instructions per point and step, each point 3.00 per mode"),
            "{md}"
        );
        assert!(md.contains("; instructions per step P^"), "{md}");
    }

    #[test]
    fn the_table_has_a_row_per_size_and_every_column() {
        let r = report(true);
        let csv = r.csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 1 + r.sizes.len());
        let columns = CSV_HEADER.trim().split(',').count();
        for l in &lines {
            assert_eq!(l.split(',').count(), columns, "{l}");
        }
        // contact share 1 - 1/1.5 of the rigid rows, memory in kB
        assert!(lines[1].starts_with("rigid,5,400,1000,"), "{}", lines[1]);
        assert!(lines[1].contains(",0.3333,"), "{}", lines[1]);
        assert!(lines[1].ends_with(",2048"), "{}", lines[1]);
        let md = r.markdown();
        assert_eq!(
            md.lines()
                .filter(|l| Regime::ALL
                    .iter()
                    .any(|r| l.starts_with(&format!("| {} |", r.key()))))
                .count(),
            r.sizes.len()
        );
        assert!(md.contains("| 2.0 |"), "peak memory in MB: {md}");
    }

    #[test]
    fn the_figure_draws_instructions_only_where_every_size_was_counted() {
        assert_eq!(report(false).figure().panels.len(), 2);
        assert_eq!(report(true).figure().panels.len(), 4);
    }
}
