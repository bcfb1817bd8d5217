//! The work each optimisation of the solver skips, measured: every
//! optimisation switched off and on in one process, timed alternately, with
//! what it changes in the result (`tirecontact bench`'s "Work skipped"
//! table).

use super::BenchError;
use super::work_precision;
use std::fmt::Write as _;
use tirecontact_core::solver::simulation::SolverOptions;
use tirecontact_io::identify::{ModeCache, PreparedModel};
use tirecontact_io::scene::Scene;

/// The markdown table of each optimisation switched off and on, timed in
/// this one process: every scene run to `duration_s`, each side timed
/// `repeats` times alternately with its other side (medians).
pub fn skipped_work(
    scenes: &[Scene],
    repeats: usize,
    duration_s: f64,
) -> Result<String, BenchError> {
    let mut s = format!(
        "## Work skipped, measured before/after (same process)\n\nBefore and after each timed {repeats} times, alternately; medians (s).\n\n| scene | optimisation | before (s) | after (s) | speed-up | detail |\n|---|---|---|---|---|---|\n",
    );
    for scene in scenes {
        let mut sc = scene.clone();
        sc.duration_s = duration_s;
        let model = PreparedModel::of(&sc)?;
        let all = SolverOptions::default();
        // each "before" is timed alternately with its own "after" runs
        let ((before, sim_r), (after, sim)) = work_precision::time_pair(
            &model,
            SolverOptions {
                rank_reduction: false,
                ..all
            },
            all,
            repeats,
        )?;
        let (t_rank, t_on) = (before.median_s(), after.median_s());
        let st = sim.stats().clone();
        let same = sim_r
            .displacement_m()
            .iter()
            .zip(sim.displacement_m())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let _ = writeln!(
            s,
            "| {} | rank-1 states for mode shapes / low-rank residues | {t_rank:.4} | {t_on:.4} | {:.2}x | same result to {same:.1e} m |",
            scene.name,
            t_rank / t_on
        );
        // identified residues: the default cut against every SVD term kept
        // (modes given in a scene are always exact: nothing to compare)
        let exact_tol = tirecontact_core::model::convolution::EXACT_RANK_TOLERANCE;
        if all.rank_tolerance_of(sc.modes_identified()) > exact_tol {
            let exact = SolverOptions {
                rank_tolerance: Some(exact_tol),
                ..all
            };
            let ((before, sim_e), (after, _)) =
                work_precision::time_pair(&model, exact, all, repeats)?;
            let (t_exact, t_cut) = (before.median_s(), after.median_s());
            let (du, dq) = option_difference(&sc, exact, all)?;
            let _ = writeln!(
                s,
                "| {} | identified residue terms below {:.0e} of the largest dropped ({} states instead of {}) | {t_exact:.4} | {t_cut:.4} | {:.2}x | largest displacement difference {du:.1e} of the largest displacement; force difference (RMS over steps) {dq:.1e} of the RMS force |",
                scene.name,
                all.rank_tolerance_of(sc.modes_identified()),
                sim.num_states(),
                sim_e.num_states(),
                t_exact / t_cut
            );
        }
        let ((before, sim_f), (after, _)) = work_precision::time_pair(
            &model,
            SolverOptions {
                reuse_factorisation: false,
                ..all
            },
            all,
            repeats,
        )?;
        let (t_fact, t_reuse) = (before.median_s(), after.median_s());
        let _ = writeln!(
            s,
            "| {} | reuse the contact factorisation while the active set is unchanged | {t_fact:.4} | {t_reuse:.4} | {:.2}x | {} factorisations for {} solves (else {}) |",
            scene.name,
            t_fact / t_reuse,
            st.factorisations,
            st.solves,
            sim_f.stats().factorisations
        );
        let ((before, sim_s), (after, _)) = work_precision::time_pair(
            &model,
            SolverOptions {
                steady_path: false,
                ..all
            },
            all,
            repeats,
        )?;
        let (t_loop, t_steady) = (before.median_s(), after.median_s());
        let identical = sim_s
            .displacement_m()
            .iter()
            .chain(sim_s.force_n())
            .zip(sim.displacement_m().iter().chain(sim.force_n()))
            .all(|(a, b)| a.to_bits() == b.to_bits());
        let _ = writeln!(
            s,
            "| {} | steps with the same contact set and no event outside the event loop | {t_loop:.4} | {t_steady:.4} | {:.2}x | {} |",
            scene.name,
            t_loop / t_steady,
            if identical {
                "bit-identical end state"
            } else {
                "END STATES DIFFER"
            }
        );
        let mean_active = st.contact_steps.iter().sum::<u64>() as f64 / st.steps.max(1) as f64;
        let _ = writeln!(
            s,
            "| {} | contact solve only for points on the road or landing | - | {t_on:.4} | - | {mean_active:.2} of {} points in the solve on average; {} located events in {} steps |",
            scene.name,
            scene.num_points(),
            st.events,
            st.steps
        );
    }
    Ok(s)
}

/// Two runs of `scene` with options `a` and `b`: the largest displacement
/// difference relative to the largest displacement, and the RMS of the
/// step-mean force difference relative to the RMS force.
fn option_difference(
    scene: &Scene,
    a: SolverOptions,
    b: SolverOptions,
) -> Result<(f64, f64), BenchError> {
    let cache = ModeCache::new();
    let run = |options| {
        work_precision::run_stable(
            scene,
            scene.contact_scheme,
            scene.dt_s,
            scene.duration_s,
            options,
            &cache,
        )
        .map(|(run, _, _)| run)
    };
    let (ra, rb) = (run(a)?, run(b)?);
    let (mut du, mut umax, mut dq2, mut q2) = (0.0f64, 0.0f64, 0.0, 0.0);
    for k in 0..ra.t_s.len().min(rb.t_s.len()) {
        for i in 0..scene.num_points() {
            let (ua, ub) = (ra.u_m[k][i], rb.u_m[k][i]);
            du = du.max((ua - ub).abs());
            umax = umax.max(ua.abs());
            let (qa, qb) = (ra.q_n[k][i], rb.q_n[k][i]);
            dq2 += (qa - qb).powi(2);
            q2 += qa * qa;
        }
    }
    Ok((
        du / umax.max(f64::MIN_POSITIVE),
        (dq2 / q2.max(f64::MIN_POSITIVE)).sqrt(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One row per optimisation and scene; the steady path changes no bit
    /// of the end state, and the rank-1 states change the result only by
    /// rounding.
    #[test]
    fn the_table_has_every_optimisation_and_the_steady_path_is_exact() {
        let mut scene = crate::analysis::bench::scenes::many_points(5, 20);
        scene.name = "five points".into();
        let table = skipped_work(&[scene], 1, 0.01).unwrap();
        let rows: Vec<&str> = table
            .lines()
            .filter(|l| l.starts_with("| five points |"))
            .collect();
        assert_eq!(rows.len(), 4, "{table}");
        assert!(rows[2].contains("bit-identical end state"), "{}", rows[2]);
        let same: f64 = rows[0]
            .split("same result to ")
            .nth(1)
            .and_then(|t| t.split(' ').next())
            .and_then(|t| t.parse().ok())
            .unwrap();
        assert!(same < 1e-12, "rank-1 states moved the result by {same} m");
    }
}
