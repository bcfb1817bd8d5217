//! The work-precision study behind `tirecontact bench`: on the three-point
//! preset, located events beat the paper's contact rule by orders of
//! magnitude at every dt, the α/β and direct baselines agree with the
//! paper's rule (same contact scheme, different convolution), and the CSV,
//! markdown and diagram are written.

use tirecontact::Scene;
use tirecontact::bench::work_precision::{Config, Method, figure, study, to_csv, to_markdown};

#[test]
fn located_beats_paper_and_baselines_agree() {
    let scene = Scene::load(std::path::Path::new("presets/three_points.ron")).unwrap();
    let cfg = Config {
        dts: vec![4e-5, 2e-5, 1e-5],
        duration_s: 0.06,
        direct_duration_s: 0.06,
        direct_max_steps: 1500,
        force_window_s: 1e-3,
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
    let csv = to_csv(&rows).unwrap();
    assert!(csv.starts_with("scene,method,dt_s"));
    assert_eq!(csv.lines().count(), rows.len() + 1);
    assert!(to_markdown(&rows).contains("Speed-up"));
    assert_eq!(figure(&rows, &scene.name).panels.len(), 2);
}
