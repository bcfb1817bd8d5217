//! A study's report from its merged table: per factor, the main effects
//! (mean and spread of each summary metric at each level of the factor,
//! over the other factors and the replicates), a figure per factor and a
//! markdown summary.

use crate::output::figures::{Figure, Panel, Series, Style};

/// Summary metrics of a row, from its per-point columns: the mean over
/// the points of each (name, column suffix, unit). All have a limit as
/// dt → 0 ([`crate::analysis::metrics`]).
pub const METRICS: [(&str, &str, &str); 5] = [
    (
        "largest force without impacts, mean over the points",
        "_smooth_max_N",
        "N",
    ),
    (
        "largest 1 ms mean force, mean over the points",
        "_1ms_max_N",
        "N",
    ),
    ("impacts per second, mean over the points", "_per_s", "1/s"),
    ("largest impulse, mean over the points", "_max_Ns", "N·s"),
    ("contact fraction, mean over the points", "_fraction", "-"),
];

/// Summary metrics of a contact patch's row, each a column of its own
/// (name, column, unit): present when the table has the column.
pub const PATCH_METRICS: [(&str, &str, &str); 2] = [
    (
        "largest summed force of the patch without impacts",
        "patch_force_max_N",
        "N",
    ),
    ("mean contact area of the patch", "patch_area_mean_m2", "m²"),
];

/// A summary metric of a table: its name, unit and columns (their mean).
#[derive(Debug, Clone, PartialEq)]
pub struct Metric {
    pub name: &'static str,
    pub unit: &'static str,
    columns: Vec<usize>,
}

/// The metrics a table's header holds, in order: [`METRICS`] with at least
/// one per-point column (`q{i}…`, none when the factors change how many
/// points there are), then [`PATCH_METRICS`].
fn metrics_of(header: &[String], from: usize, to: usize) -> Vec<Metric> {
    let per_point = METRICS.iter().map(|(name, suffix, unit)| Metric {
        name,
        unit,
        columns: (from..to)
            .filter(|&c| header[c].ends_with(suffix) && !header[c].starts_with("patch_"))
            .collect(),
    });
    let patch = PATCH_METRICS.iter().map(|(name, column, unit)| Metric {
        name,
        unit,
        columns: (from..to).filter(|&c| header[c] == *column).collect(),
    });
    per_point
        .chain(patch)
        .filter(|m| !m.columns.is_empty())
        .collect()
}

/// The size (px) of a factor's figure of `metrics` panels: each plot
/// about 170 px high (1200 × 1400 for five).
pub fn figure_px(metrics: usize) -> (u32, u32) {
    (1200, 280 * metrics.max(1) as u32)
}

/// Levels of a factor with more distinct values than this are binned.
pub const MAX_LEVELS: usize = 8;

/// One level of one factor: its value (the bin's mean value for binned
/// factors), and the mean and the standard deviation of each metric over
/// its rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    pub value: f64,
    pub mean: Vec<f64>,
    pub std: Vec<f64>,
    pub rows: usize,
}

/// The main effects of one factor.
#[derive(Debug, Clone, PartialEq)]
pub struct Effect {
    pub factor: String,
    /// The metrics of the levels' means, as the table's.
    pub metrics: Vec<Metric>,
    pub levels: Vec<Level>,
}

/// A study table: its factor columns, and per successful row the factor
/// values and the summary metrics.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub factors: Vec<String>,
    /// The summary metrics of the rows, in the order of their values.
    pub metrics: Vec<Metric>,
    pub rows: Vec<(Vec<f64>, Vec<f64>)>,
    /// Rows that failed (their `error` not empty), left out.
    pub failed: usize,
}

/// A study table that cannot be read: the row (0-based, after the
/// header), the column, its value and what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TableError {
    #[error(
        "columns `study_hash`, `replicate` and `error` expected: a table of `study run` or `study merge`"
    )]
    Columns,
    #[error("row {row}: {fields} fields: expected {expected}")]
    Fields {
        row: usize,
        fields: usize,
        expected: usize,
    },
    #[error("row {row}: {column} = `{value}`: expected a number")]
    NotANumber {
        row: usize,
        column: String,
        value: String,
    },
}

/// Reads the factor and metric columns of a table (`header` and its
/// records, as `study run` and `study merge` write them).
pub fn table(header: &[String], records: &[Vec<String>]) -> Result<Table, TableError> {
    let col = |name: &str| header.iter().position(|h| h == name);
    let (Some(hash), Some(rep), Some(err)) = (col("study_hash"), col("replicate"), col("error"))
    else {
        return Err(TableError::Columns);
    };
    let factors: Vec<String> = header[hash + 1..rep].to_vec();
    let metrics = metrics_of(header, rep + 1, err);
    let mut rows = Vec::new();
    let mut failed = 0;
    for (k, r) in records.iter().enumerate() {
        if r.len() != header.len() {
            return Err(TableError::Fields {
                row: k,
                fields: r.len(),
                expected: header.len(),
            });
        }
        if !r[err].is_empty() {
            failed += 1;
            continue;
        }
        let num = |c: usize| -> Result<f64, TableError> {
            r[c].parse().map_err(|_| TableError::NotANumber {
                row: k,
                column: header[c].clone(),
                value: r[c].clone(),
            })
        };
        let f: Vec<f64> = (hash + 1..rep).map(num).collect::<Result<_, _>>()?;
        let m: Vec<f64> = metrics
            .iter()
            .map(|metric| {
                let v: Vec<f64> = metric
                    .columns
                    .iter()
                    .map(|&c| num(c))
                    .collect::<Result<_, _>>()?;
                Ok(v.iter().sum::<f64>() / v.len().max(1) as f64)
            })
            .collect::<Result<_, TableError>>()?;
        rows.push((f, m));
    }
    Ok(Table {
        factors,
        metrics,
        rows,
        failed,
    })
}

/// Mean and (population) standard deviation of `v`.
fn mean_std(v: &[f64]) -> (f64, f64) {
    let n = v.len().max(1) as f64;
    let m = v.iter().sum::<f64>() / n;
    (
        m,
        (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / n).sqrt(),
    )
}

/// The main effects of every factor of `t`: rows grouped by the factor's
/// value (at most [`MAX_LEVELS`] groups: more distinct values, as sampled
/// designs give, are cut into equal-count bins by value).
pub fn main_effects(t: &Table) -> Vec<Effect> {
    (0..t.factors.len())
        .map(|d| {
            let mut idx: Vec<usize> = (0..t.rows.len()).collect();
            idx.sort_by(|&a, &b| t.rows[a].0[d].total_cmp(&t.rows[b].0[d]));
            let mut distinct: Vec<f64> = idx.iter().map(|&i| t.rows[i].0[d]).collect();
            distinct.dedup();
            let groups: Vec<Vec<usize>> = if distinct.len() <= MAX_LEVELS {
                distinct
                    .iter()
                    .map(|&v| {
                        idx.iter()
                            .copied()
                            .filter(|&i| t.rows[i].0[d] == v)
                            .collect()
                    })
                    .collect()
            } else {
                let n = idx.len();
                (0..MAX_LEVELS)
                    .map(|b| idx[b * n / MAX_LEVELS..(b + 1) * n / MAX_LEVELS].to_vec())
                    .filter(|g| !g.is_empty())
                    .collect()
            };
            let levels = groups
                .iter()
                .map(|g| {
                    let value = g.iter().map(|&i| t.rows[i].0[d]).sum::<f64>() / g.len() as f64;
                    let (mean, std): (Vec<f64>, Vec<f64>) = (0..t.metrics.len())
                        .map(|m| mean_std(&g.iter().map(|&i| t.rows[i].1[m]).collect::<Vec<_>>()))
                        .unzip();
                    Level {
                        value,
                        mean,
                        std,
                        rows: g.len(),
                    }
                })
                .collect();
            Effect {
                factor: t.factors[d].clone(),
                metrics: t.metrics.clone(),
                levels,
            }
        })
        .collect()
}

/// The figure of one factor's main effects: a panel per metric, its mean
/// at each level and the mean ± one standard deviation.
pub fn figure(e: &Effect, title: &str) -> Figure {
    let panels = e
        .metrics
        .iter()
        .enumerate()
        .map(|(m, Metric { name, unit, .. })| {
            let at = |f: &dyn Fn(&Level) -> f64| -> Vec<(f64, f64)> {
                e.levels.iter().map(|l| (l.value, f(l))).collect()
            };
            // one legend, in the first panel (the same in all)
            let named = |n: &str| if m == 0 { n.to_string() } else { String::new() };
            Panel {
                title: (*name).to_string(),
                x_label: tirecontact_io::scene::fields::axis_label(&e.factor),
                y_label: format!("({unit})"),
                series: vec![
                    Series {
                        name: named("mean of the rows"),
                        points: at(&|l| l.mean[m]),
                        style: Style::LineMarkers(4),
                        color: Some(0),
                    },
                    Series {
                        name: named("± one standard deviation"),
                        points: at(&|l| l.mean[m] + l.std[m]),
                        style: Style::ThinLine,
                        color: Some(1),
                    },
                    Series {
                        name: String::new(),
                        points: at(&|l| l.mean[m] - l.std[m]),
                        style: Style::ThinLine,
                        color: Some(1),
                    },
                ],
                ..Panel::default()
            }
        })
        .collect();
    Figure {
        title: format!(
            "{title}: main effect of {}",
            tirecontact_io::scene::fields::label(&e.factor)
        ),
        subtitle: format!(
            "{} levels; each point the mean of its rows, the thin lines one standard deviation either side",
            e.levels.len()
        ),
        panels,
    }
}

/// A markdown summary: per factor, a table of its levels' means and
/// spreads, and its figure.
pub fn markdown(title: &str, t: &Table, effects: &[Effect], figures: &[String]) -> String {
    let short = crate::output::summary::short_num;
    let mut s = format!(
        "# {title}\n\n{} rows ({} failed, left out), {}.\n",
        t.rows.len() + t.failed,
        t.failed,
        tirecontact_core::base::error::count(t.factors.len(), "factor")
    );
    for (e, fig) in effects.iter().zip(figures) {
        s.push_str(&format!("\n## {}\n\n| level | rows |", e.factor));
        for Metric { name, unit, .. } in &t.metrics {
            s.push_str(&format!(" {name} ({unit}) |"));
        }
        s.push_str("\n|---|---|");
        s.push_str(&"---|".repeat(t.metrics.len()));
        s.push('\n');
        for l in &e.levels {
            s.push_str(&format!("| {} | {} |", short(l.value, 4), l.rows));
            for m in 0..t.metrics.len() {
                s.push_str(&format!(
                    " {} ± {} |",
                    short(l.mean[m], 4),
                    short(l.std[m], 2)
                ));
            }
            s.push('\n');
        }
        s.push_str(&format!("\n![{}]({fig})\n", e.factor));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(names: &[&str]) -> Vec<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    /// A 2 × 2 design whose metric is known: the main effects are the
    /// means over the other factor, checked by hand.
    #[test]
    fn main_effects_are_the_means_over_the_other_factors() {
        let h = header(&[
            "row",
            "of",
            "study_hash",
            "a",
            "b",
            "replicate",
            "q0_smooth_max_N",
            "q0_1ms_max_N",
            "impacts0_per_s",
            "impulse0_max_Ns",
            "contact0_fraction",
            "error",
        ]);
        let rec = |a: f64, b: f64| -> Vec<String> {
            let v = 10.0 * a + b;
            vec![
                "0".into(),
                "4".into(),
                "h".into(),
                a.to_string(),
                b.to_string(),
                "0".into(),
                v.to_string(),
                (2.0 * v).to_string(),
                "100".into(),
                "0.25".into(),
                "0.5".into(),
                String::new(),
            ]
        };
        let mut records = vec![rec(1.0, 1.0), rec(1.0, 3.0), rec(2.0, 1.0), rec(2.0, 3.0)];
        let mut bad = rec(9.0, 9.0);
        bad[11] = "failed".into();
        records.push(bad);
        let t = table(&h, &records).unwrap();
        assert_eq!((t.rows.len(), t.failed), (4, 1));
        let e = main_effects(&t);
        assert_eq!(e[0].factor, "a");
        // a = 1: forces 11 and 13: mean 12, std 1
        assert_eq!(e[0].levels[0].mean[0], 12.0);
        assert_eq!(e[0].levels[0].std[0], 1.0);
        assert_eq!(e[0].levels[1].mean[1], 2.0 * 22.0);
        // b = 3: 13 and 23: mean 18, std 5
        assert_eq!(e[1].levels[1].mean[0], 18.0);
        assert_eq!(e[1].levels[1].std[0], 5.0);
        let md = markdown("t", &t, &e, &["a.png".into(), "b.png".into()]);
        assert!(
            md.contains("| 1 | 2 | 12 ± 1 |") && md.contains("![a](a.png)"),
            "{md}"
        );
    }

    /// A patch whose factor changes its points: no per-point columns, the
    /// patch's two metrics from their own columns (not from the per-point
    /// suffixes they share, `_max_N`).
    #[test]
    fn a_patch_table_is_summarised_by_the_patch_metrics() {
        let h = header(&[
            "row",
            "of",
            "study_hash",
            "points.across",
            "replicate",
            "patch_force_max_N",
            "patch_force_rms_N",
            "patch_points_in_contact_mean",
            "patch_area_mean_m2",
            "patch_area_max_m2",
            "band_20hz_db_re_1N",
            "error",
        ]);
        let rec = |across: f64| -> Vec<String> {
            [
                "0",
                "2",
                "h",
                &across.to_string(),
                "0",
                &(100.0 * across).to_string(),
                "1",
                "2",
                &(1e-4 * across).to_string(),
                "9",
                "60",
                "",
            ]
            .iter()
            .map(|s| s.to_string())
            .collect()
        };
        let t = table(&h, &[rec(2.0), rec(4.0)]).unwrap();
        let names: Vec<&str> = t.metrics.iter().map(|m| m.name).collect();
        assert_eq!(names, [PATCH_METRICS[0].0, PATCH_METRICS[1].0]);
        assert_eq!(t.rows[1].1, vec![400.0, 4e-4]);
        let e = main_effects(&t);
        assert_eq!(e[0].metrics.len(), 2);
        assert_eq!(figure(&e[0], "t").panels.len(), 2);
        let md = markdown("t", &t, &e, &["a.png".into()]);
        assert!(md.contains("mean contact area of the patch (m²)"), "{md}");
        assert!(!md.contains("impacts per second"), "{md}");
    }

    #[test]
    fn many_distinct_values_are_binned_by_count() {
        let h = header(&[
            "row",
            "of",
            "study_hash",
            "a",
            "replicate",
            "q0_smooth_max_N",
            "q0_1ms_max_N",
            "impacts0_per_s",
            "impulse0_max_Ns",
            "contact0_fraction",
            "error",
        ]);
        let records: Vec<Vec<String>> = (0..80)
            .map(|k| {
                let a = k as f64 / 80.0;
                vec![
                    k.to_string(),
                    "80".into(),
                    "h".into(),
                    a.to_string(),
                    "0".into(),
                    a.to_string(),
                    "1".into(),
                    "1".into(),
                    "1".into(),
                    "1".into(),
                    String::new(),
                ]
            })
            .collect();
        let e = main_effects(&table(&h, &records).unwrap());
        assert_eq!(e[0].levels.len(), MAX_LEVELS);
        assert!(e[0].levels.iter().all(|l| l.rows == 10));
        assert!(e[0].levels.windows(2).all(|w| w[0].value < w[1].value));
    }
}
