//! Parameter studies: a study file (RON) names a base preset, factors
//! (scene fields by the paths `sweep` knows, and the random road's
//! `road.seed`), a design (full factorial, Latin hypercube, scrambled
//! Sobol) and replicates over random-road seeds. Its rows are numbered;
//! any set of them runs on any machine (`--shard K/N`, `--rows A..B`) and
//! the parts merge into one table, byte for byte what one process writes.
//! Every row carries a hash of the study and its preset, so that parts of
//! different studies are not merged.

use crate::studies::sweep::engine::{PoolTiming, run_each};
use crate::studies::sweep::{RunSummary, SummaryError, get_param, run_summary, set_param};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use tirecontact_core::base::error::{FieldError, IoError};
use tirecontact_io::Scene;
use tirecontact_io::identify::{ModeCache, PreparedModel};
use tirecontact_io::scene::SceneError;

mod design;
pub mod report;
pub mod table;
use design::design_values;

/// Most rows a study may have.
pub const MAX_ROWS: usize = 1_000_000;
/// Most factors of a study (Sobol's dimensions).
pub const MAX_FACTORS: usize = 64;

/// The values of a factor.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Values {
    /// These values (full factorial: the levels; sampled designs: one of
    /// them, equally likely).
    List(Vec<f64>),
    /// `steps` evenly spaced values from `from` to `to` (full factorial);
    /// sampled designs take the interval.
    Range { from: f64, to: f64, steps: usize },
    /// Sampled designs: uniform over `[from, to]`.
    Uniform { from: f64, to: f64 },
}

/// A varied field of the scene.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Factor {
    /// A field path as `sweep` takes it (`speed_mps`,
    /// `tyre.modes[0].damping_ratio`, `road.amplitude_m`), or `road.seed`.
    pub path: String,
    pub values: Values,
}

/// How the rows are made from the factors.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub enum Design {
    /// Every combination of the factors' values (the last factor varies
    /// fastest).
    FullFactorial,
    /// `samples` rows, each factor's range cut into `samples` strata, one
    /// row in each (random permutations from `seed`).
    LatinHypercube { samples: usize, seed: u64 },
    /// The first `samples` points of an Owen-scrambled Sobol sequence
    /// (scrambled by `seed`).
    Sobol { samples: usize, seed: u64 },
}

/// A study file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Study {
    /// The base preset, relative to the study file's folder.
    pub preset: PathBuf,
    pub factors: Vec<Factor>,
    pub design: Design,
    /// Runs per design row, over random-road seeds (the base seed plus
    /// 0, 1, …): 1 for a scene without a random road.
    #[serde(default = "one")]
    pub replicates: usize,
    /// Overrides of the preset's duration and time step (s).
    #[serde(default)]
    pub duration_s: Option<f64>,
    #[serde(default)]
    pub dt_s: Option<f64>,
}

fn one() -> usize {
    1
}

/// A study that cannot be used: the file, where in it (`file:line:column`
/// of the field), the field, its value and what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StudyError {
    /// The study file cannot be read.
    #[error("{file}: {source}: expected a study file (RON)")]
    Read {
        file: String,
        #[source]
        source: IoError,
    },
    /// The study's text does not parse (line and column are 1-based).
    #[error("{file}:{line}:{col}: {source}")]
    Syntax {
        file: String,
        line: usize,
        col: usize,
        #[source]
        source: ron::Error,
    },
    /// The base preset cannot be loaded.
    #[error("{at}: preset = {preset:?}: {source}")]
    Preset {
        /// Where the study names it (`file:line:column`).
        at: String,
        /// As the study writes it.
        preset: PathBuf,
        #[source]
        source: Box<SceneError>,
    },
    /// The preset with the study's overrides (`duration_s`, `dt_s`) is
    /// invalid: each bad field, placed in the study when the study set it,
    /// else in the preset.
    #[error("{}", invalid_overrides(.preset, .errors))]
    Overrides {
        /// The preset's path as read.
        preset: PathBuf,
        /// Each bad field, with where the study sets it (`None`: the
        /// preset's own field).
        errors: Vec<(Option<String>, FieldError)>,
    },
    /// A field of the study cannot be used.
    #[error("{at}: {problem}")]
    Field {
        /// Where the field is written (`file:line:column`).
        at: String,
        problem: Problem,
    },
}

fn invalid_overrides(preset: &Path, errors: &[(Option<String>, FieldError)]) -> String {
    errors
        .iter()
        .map(|(at, e)| match at {
            Some(at) => format!("{at}: {e}"),
            None => format!(
                "{}: the preset with the study's overrides: {e}",
                preset.display()
            ),
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// A study field that cannot be used: its path in the study file
/// (`factors[1].values`, `design.samples`) and a message naming the field,
/// the value and what was expected.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    pub field: String,
    pub message: String,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

fn problem(field: impl Into<String>, message: impl Into<String>) -> Problem {
    Problem {
        field: field.into(),
        message: message.into(),
    }
}

/// One row of the design.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub id: usize,
    /// One value per factor.
    pub values: Vec<f64>,
    /// The replicate (random-road seed offset).
    pub replicate: usize,
}

/// A study loaded: its definition, base scene and hash.
#[derive(Debug, Clone)]
pub struct Loaded {
    pub study: Study,
    pub base: Scene,
    /// FNV-1a 64 of the study's and the preset's texts, hex: every output
    /// row carries it.
    pub hash: String,
    pub rows: Vec<Row>,
}

impl Loaded {
    /// The metric columns of the study's table: per point unless a factor
    /// changes how many points there are, the patch's for a patch.
    pub fn columns(&self) -> crate::studies::sweep::report::Columns {
        let paths: Vec<&str> = self.study.factors.iter().map(|f| f.path.as_str()).collect();
        crate::studies::sweep::report::Columns::of(&self.base, &paths)
    }
}

/// FNV-1a 64 of `parts`, in hex.
fn fnv(parts: &[&[u8]]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for p in parts {
        for &b in *p {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
        h ^= 0xff;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// Reads, checks and expands the study at `path`.
pub fn load(path: &Path) -> Result<Loaded, StudyError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| StudyError::Read {
        file: file.clone(),
        source: e.into(),
    })?;
    let study: Study = ron::from_str(&text).map_err(|e| StudyError::Syntax {
        file: file.clone(),
        line: e.span.start.line,
        col: e.span.start.col,
        source: e.code,
    })?;
    // `file:line:column` of a field of the study (its nearest written parent)
    let at = |field: &str| match tirecontact_io::scene::locate::locate(&text, field) {
        Some((line, col)) => format!("{file}:{line}:{col}"),
        None => file.clone(),
    };
    let dir = path.parent().unwrap_or(Path::new("."));
    let preset = if study.preset.is_relative() {
        dir.join(&study.preset)
    } else {
        study.preset.clone()
    };
    let preset_text = std::fs::read_to_string(&preset).unwrap_or_default();
    let mut base = Scene::load(&preset).map_err(|source| StudyError::Preset {
        at: at("preset"),
        preset: study.preset.clone(),
        source: Box::new(source),
    })?;
    if let Some(d) = study.duration_s {
        base.duration_s = d;
    }
    if let Some(d) = study.dt_s {
        base.dt_s = d;
    }
    base.validate().map_err(|errors| StudyError::Overrides {
        // an override the preset refuses is the study's field; another
        // error is the preset's (its own file's fields are fine alone)
        errors: errors
            .into_iter()
            .map(|e| {
                let overridden = (e.field == "duration_s" && study.duration_s.is_some())
                    || (e.field == "dt_s" && study.dt_s.is_some());
                (overridden.then(|| at(&e.field)), e)
            })
            .collect(),
        preset: preset.clone(),
    })?;
    let rows = rows(&study, &base).map_err(|problem| StudyError::Field {
        at: at(&problem.field),
        problem,
    })?;
    Ok(Loaded {
        hash: fnv(&[text.as_bytes(), preset_text.as_bytes()]),
        study,
        base,
        rows,
    })
}

/// Checks the factors against `base` and makes the design's rows.
pub fn rows(study: &Study, base: &Scene) -> Result<Vec<Row>, Problem> {
    if study.factors.is_empty() {
        return Err(problem(
            "factors",
            "factors = []: expected at least one factor",
        ));
    }
    if study.factors.len() > MAX_FACTORS {
        return Err(problem(
            "factors",
            format!(
                "factors: {} of them: expected at most {MAX_FACTORS}",
                study.factors.len()
            ),
        ));
    }
    for (k, f) in study.factors.iter().enumerate() {
        let at = format!("factors[{k}]");
        if f.path == "road.seed" {
            if base.road.seed().is_none() {
                return Err(problem(
                    format!("{at}.path"),
                    format!(
                        "{at}.path = road.seed: expected a preset with a random road or a texture"
                    ),
                ));
            }
        } else {
            get_param(base, &f.path)
                .map_err(|e| problem(format!("{at}.path"), format!("{at}.path: {e}")))?;
        }
        let values = format!("{at}.values");
        let finite = |x: f64| x.is_finite();
        match &f.values {
            Values::List(v) => {
                if v.is_empty() || !v.iter().copied().all(finite) {
                    return Err(problem(
                        values,
                        format!(
                            "{at}.values = {v:?}: expected a list of finite numbers, at least one"
                        ),
                    ));
                }
            }
            Values::Range { from, to, steps } => {
                if !(finite(*from) && finite(*to)) || *steps == 0 {
                    return Err(problem(
                        values,
                        format!(
                            "{at}.values = Range(from: {from}, to: {to}, steps: {steps}): expected finite ends and steps >= 1"
                        ),
                    ));
                }
            }
            Values::Uniform { from, to } => {
                if !(finite(*from) && finite(*to) && from < to) {
                    return Err(problem(
                        values,
                        format!(
                            "{at}.values = Uniform(from: {from}, to: {to}): expected finite ends, from < to"
                        ),
                    ));
                }
                if study.design == Design::FullFactorial {
                    return Err(problem(
                        values,
                        format!(
                            "{at}.values = Uniform(…): expected List or Range in a FullFactorial design (levels)"
                        ),
                    ));
                }
            }
        }
    }
    if study.replicates == 0 {
        return Err(problem("replicates", "replicates = 0: expected at least 1"));
    }
    if study.replicates > 1 && base.road.seed().is_none() {
        return Err(problem(
            "replicates",
            format!(
                "replicates = {}: expected 1 for a preset without a random road or a texture (its runs would be identical)",
                study.replicates
            ),
        ));
    }
    let design = design_values(study)?;
    let n = design.len().saturating_mul(study.replicates);
    if n > MAX_ROWS {
        return Err(problem(
            "replicates",
            format!(
                "replicates = {}: {} design rows × {} replicates = {n} rows: expected at most {MAX_ROWS}",
                study.replicates,
                design.len(),
                study.replicates
            ),
        ));
    }
    let mut out = Vec::with_capacity(n);
    for values in design {
        for replicate in 0..study.replicates {
            out.push(Row {
                id: out.len(),
                values: values.clone(),
                replicate,
            });
        }
    }
    Ok(out)
}

/// The scene of `row`.
pub fn scene_of(loaded: &Loaded, row: &Row) -> Result<Scene, SummaryError> {
    let mut s = loaded.base.clone();
    for (f, &v) in loaded.study.factors.iter().zip(&row.values) {
        if f.path == "road.seed" {
            if let Some(seed) = s.road.seed_mut() {
                *seed = v.round().max(0.0) as u64;
            }
        } else {
            set_param(&mut s, &f.path, v)?;
        }
    }
    if let Some(seed) = s.road.seed_mut() {
        *seed = seed.wrapping_add(row.replicate as u64);
    }
    s.validate().map_err(SummaryError::InvalidScene)?;
    Ok(s)
}

/// Runs `row` (its modes from `cache`): its summary, or why it failed.
pub fn run_row(
    loaded: &Loaded,
    row: &Row,
    cache: &ModeCache,
    cancel: &AtomicBool,
) -> Result<RunSummary, SummaryError> {
    let scene = scene_of(loaded, row)?;
    let model = PreparedModel::new(&scene, cache)?;
    run_summary(&model, &|_| {}, cancel)
}

/// Runs `rows` on `threads` threads on the engine sweeps use
/// ([`crate::studies::sweep::engine::run_each`]); `on_done(row, result)` is called
/// from the worker as each row ends.
pub fn run_rows(
    loaded: &Loaded,
    rows: &[Row],
    threads: usize,
    cache: &ModeCache,
    cancel: &AtomicBool,
    on_done: &(dyn Fn(&Row, Result<RunSummary, SummaryError>) + Sync),
) -> PoolTiming {
    run_each(
        rows.len(),
        threads,
        cache,
        cancel,
        &|k| scene_of(loaded, &rows[k]),
        &|_| {},
        &|k, r| on_done(&rows[k], r),
    )
}

/// The output table's header: `row, of` (the study's row count),
/// `study_hash, <factor paths>, replicate`, the sweep's metrics, `error`.
pub fn header(loaded: &Loaded) -> Vec<String> {
    let mut h = vec!["row".to_string(), "of".into(), "study_hash".into()];
    h.extend(loaded.study.factors.iter().map(|f| f.path.clone()));
    h.push("replicate".into());
    h.extend(crate::studies::sweep::report::metric_columns(
        &loaded.columns(),
    ));
    h.push("error".into());
    h
}

/// The bytes of a study table: `header`, then `rows` in the order given
/// (by row id): the one form of every table `study run` and `study merge`
/// write, so that merged shards equal a one-process run.
pub fn table_bytes<'a>(
    header: &[String],
    rows: impl IntoIterator<Item = &'a Vec<String>>,
) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header)?;
    for r in rows {
        w.write_record(r)?;
    }
    w.into_inner().map_err(|e| e.into_error().into())
}

/// The output line of `row` and its result.
pub fn record(
    loaded: &Loaded,
    row: &Row,
    result: &Result<RunSummary, SummaryError>,
) -> Vec<String> {
    let mut r = vec![
        row.id.to_string(),
        loaded.rows.len().to_string(),
        loaded.hash.clone(),
    ];
    r.extend(row.values.iter().map(|v| format!("{v}")));
    r.push(row.replicate.to_string());
    r.extend(crate::studies::sweep::report::metric_values(
        result,
        &loaded.columns(),
    ));
    r.push(
        result
            .as_ref()
            .err()
            .map(ToString::to_string)
            .unwrap_or_default(),
    );
    r
}

/// The rows of shard `k` of `n` (0-based `k`): every `n`-th row from `k`.
pub fn shard(rows: &[Row], k: usize, n: usize) -> Vec<Row> {
    rows.iter().filter(|r| r.id % n == k).cloned().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn study(design: Design, factors: Vec<Factor>) -> Study {
        Study {
            preset: "paper.ron".into(),
            factors,
            design,
            replicates: 1,
            duration_s: None,
            dt_s: None,
        }
    }

    fn base() -> Scene {
        Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../presets/paper.ron"
            )),
            "paper",
        )
        .unwrap()
    }

    #[test]
    fn a_full_factorial_has_every_combination_last_factor_fastest() {
        let s = study(
            Design::FullFactorial,
            vec![
                Factor {
                    path: "speed_mps".into(),
                    values: Values::Range {
                        from: 8.0,
                        to: 10.0,
                        steps: 3,
                    },
                },
                Factor {
                    path: "road.amplitude_m".into(),
                    values: Values::List(vec![5e-4, 1e-3]),
                },
            ],
        );
        let r = rows(&s, &base()).unwrap();
        let v: Vec<Vec<f64>> = r.iter().map(|r| r.values.clone()).collect();
        assert_eq!(
            v,
            [
                [8.0, 5e-4],
                [8.0, 1e-3],
                [9.0, 5e-4],
                [9.0, 1e-3],
                [10.0, 5e-4],
                [10.0, 1e-3]
            ]
        );
        assert!(r.iter().enumerate().all(|(k, r)| r.id == k));
    }

    /// Each factor's range is cut into `n` strata with one sample in each.
    #[test]
    fn a_latin_hypercube_has_one_sample_per_stratum_in_every_factor() {
        let n = 37;
        let s = study(
            Design::LatinHypercube {
                samples: n,
                seed: 7,
            },
            vec![
                Factor {
                    path: "speed_mps".into(),
                    values: Values::Uniform {
                        from: 5.0,
                        to: 25.0,
                    },
                },
                Factor {
                    path: "ramp_s".into(),
                    values: Values::Range {
                        from: 0.0,
                        to: 0.1,
                        steps: 2,
                    },
                },
            ],
        );
        let r = rows(&s, &base()).unwrap();
        assert_eq!(r.len(), n);
        for (d, (lo, hi)) in [(0, (5.0, 25.0)), (1, (0.0, 0.1))] {
            let mut strata: Vec<usize> = r
                .iter()
                .map(|row| (((row.values[d] - lo) / (hi - lo)) * n as f64) as usize)
                .collect();
            strata.sort_unstable();
            assert_eq!(strata, (0..n).collect::<Vec<_>>(), "factor {d}");
        }
        // the same seed, the same rows; another seed, others
        assert_eq!(rows(&s, &base()).unwrap(), r);
        let other = study(
            Design::LatinHypercube {
                samples: n,
                seed: 8,
            },
            s.factors.clone(),
        );
        assert_ne!(rows(&other, &base()).unwrap(), r);
    }

    /// Sobol points fill the unit square evenly: every one of the 16 × 16
    /// cells of 256 points holds exactly one for a (0, m, 2)-net… checked
    /// more loosely: each quarter of each axis holds a quarter of them.
    #[test]
    fn sobol_rows_are_balanced_over_each_factor() {
        let n = 256;
        let s = study(
            Design::Sobol {
                samples: n,
                seed: 3,
            },
            vec![
                Factor {
                    path: "speed_mps".into(),
                    values: Values::Uniform { from: 0.0, to: 1.0 },
                },
                Factor {
                    path: "ramp_s".into(),
                    values: Values::Uniform { from: 0.0, to: 1.0 },
                },
            ],
        );
        let r = rows(&s, &base()).unwrap();
        for d in 0..2 {
            let mut q = [0usize; 4];
            for row in &r {
                q[((row.values[d] * 4.0) as usize).min(3)] += 1;
            }
            assert_eq!(q, [64; 4], "factor {d}");
        }
    }

    #[test]
    fn bad_factors_name_the_field_and_the_expectation() {
        let b = base();
        let cases = [
            (study(Design::FullFactorial, vec![]), "factors = []"),
            (
                study(
                    Design::FullFactorial,
                    vec![Factor {
                        path: "nope".into(),
                        values: Values::List(vec![1.0]),
                    }],
                ),
                "factors[0].path",
            ),
            (
                study(
                    Design::FullFactorial,
                    vec![Factor {
                        path: "speed_mps".into(),
                        values: Values::List(vec![]),
                    }],
                ),
                "factors[0].values",
            ),
            (
                study(
                    Design::FullFactorial,
                    vec![Factor {
                        path: "speed_mps".into(),
                        values: Values::Uniform { from: 1.0, to: 2.0 },
                    }],
                ),
                "expected List or Range",
            ),
            (
                study(
                    Design::FullFactorial,
                    vec![Factor {
                        path: "road.seed".into(),
                        values: Values::List(vec![1.0]),
                    }],
                ),
                "expected a preset with a random road",
            ),
            (
                study(
                    Design::Sobol {
                        samples: 0,
                        seed: 1,
                    },
                    vec![Factor {
                        path: "speed_mps".into(),
                        values: Values::List(vec![1.0]),
                    }],
                ),
                "samples = 0",
            ),
        ];
        for (s, want) in cases {
            let e = rows(&s, &b).unwrap_err();
            assert!(e.message.contains(want), "{e} (wanted {want})");
        }
    }

    #[test]
    fn shards_partition_the_rows() {
        let s = study(
            Design::FullFactorial,
            vec![Factor {
                path: "speed_mps".into(),
                values: Values::Range {
                    from: 1.0,
                    to: 10.0,
                    steps: 10,
                },
            }],
        );
        let r = rows(&s, &base()).unwrap();
        let mut ids: Vec<usize> = (0..3).flat_map(|k| shard(&r, k, 3)).map(|r| r.id).collect();
        ids.sort_unstable();
        assert_eq!(ids, (0..10).collect::<Vec<_>>());
    }
}
