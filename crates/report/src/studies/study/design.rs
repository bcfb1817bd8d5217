//! The points of a study's design: every combination of the factors'
//! levels, a Latin hypercube, or an Owen-scrambled Sobol sequence
//! (`sobol_burley`), one value per factor.

use super::{Design, MAX_ROWS, Problem, Study, Values, problem};
use crate::studies::sweep::linspace;
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};

/// A value of `v` at `u` in `[0, 1)` (sampled designs).
fn at_unit(v: &Values, u: f64) -> f64 {
    match v {
        Values::List(l) => l[((u * l.len() as f64) as usize).min(l.len() - 1)],
        Values::Range { from, to, .. } | Values::Uniform { from, to } => from + u * (to - from),
    }
}

/// The design's points, one value per factor.
pub(super) fn design_values(study: &Study) -> Result<Vec<Vec<f64>>, Problem> {
    let f = &study.factors;
    match study.design {
        Design::FullFactorial => {
            let levels: Vec<Vec<f64>> = f
                .iter()
                .enumerate()
                .map(|(k, x)| {
                    let field = format!("factors[{k}].values");
                    match &x.values {
                        Values::List(v) => Ok(v.clone()),
                        Values::Range { from, to, steps } => linspace(*from, *to, *steps)
                            .map_err(|e| problem(&field, format!("{field}: {e}"))),
                        Values::Uniform { .. } => Err(problem(
                            &field,
                            format!("{field} = Uniform(…): expected List or Range in a FullFactorial design"),
                        )),
                    }
                })
                .collect::<Result<_, _>>()?;
            let total = levels
                .iter()
                .try_fold(1usize, |a, l| a.checked_mul(l.len()));
            match total {
                Some(n) if n <= MAX_ROWS => {}
                _ => {
                    let sizes: Vec<String> = levels.iter().map(|l| l.len().to_string()).collect();
                    return Err(problem(
                        "design",
                        format!(
                            "design = FullFactorial: {} levels make more than {MAX_ROWS} rows: expected at most {MAX_ROWS} (fewer levels, or a LatinHypercube or Sobol design)",
                            sizes.join(" × ")
                        ),
                    ));
                }
            }
            let mut rows = vec![Vec::new()];
            for l in &levels {
                rows = rows
                    .into_iter()
                    .flat_map(|r| {
                        l.iter().map(move |&v| {
                            let mut r = r.clone();
                            r.push(v);
                            r
                        })
                    })
                    .collect();
            }
            Ok(rows)
        }
        Design::LatinHypercube { samples, seed } | Design::Sobol { samples, seed } => {
            if samples == 0 || samples > MAX_ROWS {
                return Err(problem(
                    "design.samples",
                    format!("design.samples = {samples}: expected 1 to {MAX_ROWS}"),
                ));
            }
            let lhs = matches!(study.design, Design::LatinHypercube { .. });
            let mut cols: Vec<Vec<f64>> = Vec::with_capacity(f.len());
            for (d, x) in f.iter().enumerate() {
                let units: Vec<f64> = if lhs {
                    // one point in each of `samples` strata, strata in a
                    // random order, the point uniform in its stratum
                    let mut rng = ChaCha8Rng::seed_from_u64(seed.wrapping_add(d as u64));
                    let unit =
                        |r: &mut ChaCha8Rng| (r.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                    let mut perm: Vec<usize> = (0..samples).collect();
                    for i in (1..samples).rev() {
                        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
                        perm.swap(i, j);
                    }
                    perm.iter()
                        .map(|&s| (s as f64 + unit(&mut rng)) / samples as f64)
                        .collect()
                } else {
                    (0..samples)
                        .map(|i| f64::from(sobol_burley::sample(i as u32, d as u32, seed as u32)))
                        .collect()
                };
                cols.push(units.iter().map(|&u| at_unit(&x.values, u)).collect());
            }
            Ok((0..samples)
                .map(|i| cols.iter().map(|c| c[i]).collect())
                .collect())
        }
    }
}
