//! The work-precision study behind `tirecontact bench`: on the three-point
//! preset, located events beat the paper's contact rule by orders of
//! magnitude at every dt, the α/β and direct baselines agree with the
//! paper's rule (same contact scheme, different convolution), and the CSV,
//! markdown and diagram are written.

use tirecontact::Scene;
use tirecontact::analysis::bench::work_precision::{
    Config, Method, figure, study, to_csv, to_markdown,
};

#[test]
fn located_beats_paper_and_baselines_agree() {
    let scene = Scene::load(std::path::Path::new("presets/three_points.ron")).unwrap();
    let cfg = Config {
        dts: vec![4e-5, 2e-5, 1e-5],
        duration_s: 0.06,
        direct_duration_s: 0.06,
        direct_max_steps: 1500,
        baselines: true,
        force_window_s: 1e-3,
        penalties_n_m: vec![1e8, 1e10],
        rtols: vec![1e-6],
        implicit_rtols: vec![1e-6],
    };
    let rows = study(&scene, &cfg, |_| {}).unwrap();
    let get = |m: Method, dt: f64| rows.iter().find(|r| r.method == m && r.dt_s == dt).unwrap();
    for &dt in &cfg.dts {
        let (l, p) = (get(Method::Located, dt), get(Method::Paper, dt));
        assert!(
            l.disp_err * 100.0 < p.disp_err,
            "dt {dt}: located {} paper {}",
            l.disp_err,
            p.disp_err
        );
        // the α/β convolution with the paper's rule is the paper's method
        let ab = get(Method::AlphaBeta, dt);
        assert!(
            (ab.disp_err / p.disp_err - 1.0).abs() < 0.05,
            "{} vs {}",
            ab.disp_err,
            p.disp_err
        );
    }
    // direct convolution with the paper's rule: same accuracy class as the paper's
    let d = get(Method::Direct, 4e-5);
    let p = get(Method::Paper, 4e-5);
    assert!(
        d.disp_err > 10.0 * get(Method::Located, 4e-5).disp_err,
        "{} vs {}",
        d.disp_err,
        p.disp_err
    );
    // the peers (feature `peers`): a stiffer penalty converges towards the
    // rigid reference
    let peer = |m: Method, k: f64| {
        rows.iter()
            .filter(|r| r.method == m && r.penalty_n_m == Some(k))
            .map(|r| r.disp_err)
            .fold(f64::INFINITY, f64::min)
    };
    for m in Method::PEERS
        .into_iter()
        .filter(|_| cfg!(feature = "peers"))
    {
        assert!(
            peer(m, 1e10) * 10.0 < peer(m, 1e8),
            "{m:?}: k 1e10 {} vs k 1e8 {}",
            peer(m, 1e10),
            peer(m, 1e8)
        );
    }
    assert_eq!(
        rows.iter().any(|r| Method::PEERS.contains(&r.method)),
        cfg!(feature = "peers")
    );
    let csv = to_csv(&rows).unwrap();
    assert!(csv.starts_with("scene,method,dt_s"));
    assert_eq!(csv.lines().count(), rows.len() + 1);
    let md = to_markdown(&rows);
    assert!(md.contains("Speed-up"), "{md}");
    assert_eq!(
        md.contains("Newmark + penalty"),
        cfg!(feature = "peers"),
        "{md}"
    );
    assert_eq!(figure(&rows, &scene.name).panels.len(), 2);
}

/// Newmark, Dormand-Prince and BDF with located switches integrate the
/// same penalty equations: run finely, they agree with each other far more
/// closely than any agrees with the rigid contact (the penalty error), on
/// each shipped preset.
#[test]
#[cfg(feature = "peers")]
fn the_peer_integrators_agree_on_the_penalty_equations() {
    use tirecontact::ModeCache;
    use tirecontact::analysis::bench::peers::{run_bdf, run_dopri, run_newmark};
    use tirecontact::analysis::bench::work_precision::{rms_rel, run_stable};
    use tirecontact::scene::ContactScheme;
    let (dur, dt, k) = (0.05, 2.5e-6, 1e8);
    for name in ["single_mode", "three_points", "paper"] {
        let mut scene = Scene::load(std::path::Path::new(&format!("presets/{name}.ron"))).unwrap();
        scene.dt_s = dt;
        let cache = ModeCache::new();
        let steps = (dur / dt).round() as usize;
        let n = run_newmark(&scene, k, steps, &cache).unwrap();
        let (d, _) = run_dopri(&scene, k, 1e-9, dt, dur, &cache).unwrap();
        let b = run_bdf(&scene, k, 1e-9, dt, dur, &cache).unwrap().run;
        let (rigid, _, _) = run_stable(
            &scene,
            ContactScheme::Located,
            dt,
            dur,
            tirecontact::SolverOptions::default(),
            &cache,
        )
        .unwrap();
        let flat = |u: &[Vec<f64>]| u.iter().flatten().copied().collect::<Vec<f64>>();
        assert_eq!(n.u_m.len(), d.u_m.len());
        assert_eq!(b.u_m.len(), d.u_m.len());
        let between = rms_rel(&flat(&n.u_m), &flat(&d.u_m));
        let penalty = rms_rel(&flat(&n.u_m), &flat(&rigid.u_m));
        assert!(
            between < 0.05 * penalty && between < 1e-3,
            "{name}: Newmark vs Dormand-Prince {between:e}, vs rigid {penalty:e}"
        );
        // the two adaptive integrators, both at 1e-9, closer still (to a
        // few 1e-7 of the penalty error)
        let adaptive = rms_rel(&flat(&b.u_m), &flat(&d.u_m));
        assert!(
            adaptive < 1e-5 * penalty,
            "{name}: BDF vs Dormand-Prince {adaptive:e}, vs rigid {penalty:e}"
        );
    }
}

/// The default study's patch row (`patch_study` of the chip-seal preset,
/// as `tirecontact bench` runs it): the located solver at every time step
/// and, with the peers, BDF on the same tread springs at every tolerance,
/// each with a finite error and a CPU time, in the study's table; the
/// located solver converges at second order (its error at least 3x lower
/// each halving) and BDF reaches 1e-4 at some tolerance.
#[test]
fn the_patch_row_is_in_the_default_study_with_finite_errors() {
    use tirecontact::analysis::bench::work_precision::{TREAD_ERROR_LEVEL, patch_study};
    let preset = Scene::load(std::path::Path::new("presets/patch_chip_seal.ron")).unwrap();
    let (scene, cfg) = patch_study(&preset, false).unwrap();
    assert_eq!(scene.num_points(), 12);
    let rows = study(&scene, &cfg, |_| {}).unwrap();
    let located: Vec<_> = rows
        .iter()
        .filter(|r| r.method == Method::Located)
        .collect();
    assert_eq!(located.len(), cfg.dts.len());
    for (r, &dt) in located.iter().zip(&cfg.dts) {
        assert_eq!(r.dt_s, dt);
        assert!(
            r.disp_err.is_finite() && r.force_err.is_finite() && r.cpu_s.is_some(),
            "{r:?}"
        );
    }
    for w in located.windows(2) {
        assert!(
            w[1].disp_err * 3.0 < w[0].disp_err,
            "located errors {:?}",
            located.iter().map(|r| r.disp_err).collect::<Vec<_>>()
        );
    }
    let bdf: Vec<_> = rows
        .iter()
        .filter(|r| r.method == Method::BdfTread)
        .collect();
    if cfg!(feature = "peers") {
        assert_eq!(bdf.len(), cfg.implicit_rtols.len());
        for r in &bdf {
            assert!(
                r.disp_err.is_finite() && r.force_err.is_finite() && r.cpu_s.is_some(),
                "{r:?}"
            );
        }
        assert!(
            bdf.iter().any(|r| r.disp_err < TREAD_ERROR_LEVEL),
            "{bdf:?}"
        );
    } else {
        assert!(bdf.is_empty());
    }
    let md = to_markdown(&rows);
    assert!(md.contains(&scene.name), "{md}");
    assert_eq!(
        md.contains("Tread springs on a contact patch"),
        cfg!(feature = "peers"),
        "{md}"
    );
    assert_eq!(figure(&rows, &scene.name).panels.len(), 2);
}
