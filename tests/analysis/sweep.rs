//! Sweeps: parameter paths, and a sweep point against the single run of the
//! scene with that value, summarised here independently.

use std::path::Path;
use std::sync::atomic::AtomicBool;
use tirecontact::SceneSimulation;
use tirecontact::analysis::spectrum::{Window, spectrum};
use tirecontact::studies::sweep::{
    Sweep, SweepError, get_param, param_paths, run_sweep, set_param,
};
use tirecontact::{Scene, Simulation};

fn three_points() -> Scene {
    let mut s = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    s.duration_s = 0.07;
    s
}

#[test]
fn parameter_paths_get_and_set() {
    let mut s = three_points();
    let paths = param_paths(&s);
    for p in [
        "speed_mps",
        "road.amplitude_m",
        "road.wavelength_m",
        "ramp_s",
        "dt_s",
        "duration_s",
        "points[1].y_m",
        "points[1].h_m",
        "tyre.modes[2].freq_hz",
        "tyre.modes[0].damping_ratio",
    ] {
        assert!(paths.iter().any(|q| q == p), "{p} missing from {paths:?}");
    }
    set_param(&mut s, "tyre.modes[2].freq_hz", 321.0).unwrap();
    assert_eq!(get_param(&s, "tyre.modes[2].freq_hz").unwrap(), 321.0);
    let tyre_ok = match &s.tyre {
        tirecontact::scene::Tyre::Modal { modes } => {
            modes[2].freq_hz == 321.0 && modes[1].freq_hz == 150.0
        }
        _ => false,
    };
    assert!(tyre_ok);
    set_param(&mut s, "points[*].h_m", -0.002).unwrap();
    assert!(s.points.iter().all(|p| p.h_m == -0.002));
    set_param(&mut s, "points[2].y_m", 0.03).unwrap();
    assert_eq!(get_param(&s, "points[2].y_m").unwrap(), 0.03);
    assert_eq!(s.points[2].y_m, 0.03);
    set_param(&mut s, "road.amplitude_m", 0.0007).unwrap();
    assert_eq!(get_param(&s, "road.amplitude_m").unwrap(), 0.0007);

    let e = set_param(&mut s, "speed_kmh", 50.0).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, SweepError::UnknownParam { .. }));
    assert!(
        msg.contains("speed_kmh") && msg.contains("speed_mps"),
        "{msg}"
    );
    // this scene's indices: 3 points, 3 modes (a wildcard is offered too)
    for want in [
        "points[0].h_m … points[2].h_m",
        "tyre.modes[0].freq_hz … tyre.modes[2].freq_hz",
        "[*]",
    ] {
        assert!(msg.contains(want), "`{want}` missing in: {msg}");
    }
    let e = set_param(&mut s, "dt_s", -1.0).unwrap_err().to_string();
    assert!(
        e.contains("dt_s") && e.contains("-1") && e.contains("> 0"),
        "{e}"
    );
    let e = set_param(&mut s, "tyre.modes[7].freq_hz", 1.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("tyre.modes[7].freq_hz"), "{e}");
}

struct Manual {
    smooth_max_n: Vec<f64>,
    smooth_rms_n: Vec<f64>,
    impacts_per_s: Vec<f64>,
    impulse_mean_ns: Vec<f64>,
    impulse_max_ns: Vec<f64>,
    window_max_n: Vec<f64>,
    contact_fraction: Vec<f64>,
    total_force_n: Vec<f64>,
    /// The summed force without impacts: largest and RMS (N).
    total_smooth_max_n: f64,
    total_smooth_rms_n: f64,
    /// Points in contact at a step's end: mean and most.
    in_contact_mean: f64,
    in_contact_max: usize,
}

/// The run of `scene` (located impacts), summarised over the steps starting
/// at or after `ramp_s` from the solver's own impact impulses, the 1 ms
/// means summed afresh at every step.
fn manual_run(scene: &Scene) -> Manual {
    let p = scene.num_points();
    let dt = scene.dt_s;
    let mut sim = Simulation::from_scene(scene).unwrap();
    let (mut max, mut sq, mut contact) = (vec![0.0f64; p], vec![0.0; p], vec![0u64; p]);
    let (mut impacts, mut imp_sum, mut imp_max) = (vec![0u64; p], vec![0.0; p], vec![0.0f64; p]);
    let mut q_hist: Vec<Vec<f64>> = vec![Vec::new(); p];
    let mut total = Vec::new();
    let (mut smooth_totals, mut touching) = (Vec::new(), Vec::new());
    for k in 0..scene.num_steps() {
        sim.step().unwrap();
        if (k as f64) * dt < scene.ramp_s - 1e-9 * dt {
            continue;
        }
        let q = sim.force_n();
        let imp = sim.impact_impulse_ns();
        let mut t = 0.0;
        smooth_totals.push((0..p).map(|i| q[i] - imp[i] / dt).sum::<f64>());
        touching.push(sim.in_contact().iter().filter(|&&c| c).count());
        for i in 0..p {
            let smooth = q[i] - imp[i] / dt;
            max[i] = max[i].max(smooth);
            sq[i] += smooth * smooth;
            if imp[i] > 0.0 {
                impacts[i] += 1;
                imp_sum[i] += imp[i];
                imp_max[i] = imp_max[i].max(imp[i]);
            }
            contact[i] += sim.in_contact()[i] as u64;
            q_hist[i].push(q[i]);
            t += q[i];
        }
        total.push(t);
    }
    let n = total.len() as f64;
    let w = (1e-3 / dt).round() as usize;
    Manual {
        smooth_max_n: max,
        smooth_rms_n: sq.iter().map(|s| (s / n).sqrt()).collect(),
        impacts_per_s: impacts.iter().map(|&c| c as f64 / (n * dt)).collect(),
        impulse_mean_ns: imp_sum
            .iter()
            .zip(&impacts)
            .map(|(s, &c)| if c > 0 { s / c as f64 } else { 0.0 })
            .collect(),
        impulse_max_ns: imp_max,
        window_max_n: q_hist
            .iter()
            .map(|q| {
                q.windows(w)
                    .map(|x| x.iter().sum::<f64>() / w as f64)
                    .fold(0.0, f64::max)
            })
            .collect(),
        contact_fraction: contact.iter().map(|&c| c as f64 / n).collect(),
        total_force_n: total,
        total_smooth_max_n: smooth_totals.iter().fold(0.0, |a, &b| a.max(b)),
        total_smooth_rms_n: (smooth_totals.iter().map(|x| x * x).sum::<f64>() / n).sqrt(),
        in_contact_mean: touching.iter().sum::<usize>() as f64 / n,
        in_contact_max: touching.iter().copied().max().unwrap_or(0),
    }
}

#[test]
fn a_sweep_point_equals_the_single_run() {
    let base = three_points();
    let values = vec![9.0, 12.5, 16.0];
    let cancel = AtomicBool::new(false);
    let sweep = |threads| {
        run_sweep(
            &base,
            &Sweep {
                param: "speed_mps".into(),
                values: values.clone(),
                threads,
            },
            &tirecontact::ModeCache::new(),
            &|_, _| {},
            &cancel,
        )
        .unwrap()
    };
    let two = sweep(2);
    let one = sweep(1);
    assert_eq!(one, two, "thread count changes results");
    for (k, &v) in values.iter().enumerate() {
        let mut scene = base.clone();
        scene.speed_mps = v;
        let m = manual_run(&scene);
        let r = two[k].result.as_ref().unwrap();
        assert_eq!(two[k].value, v);
        let close = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .all(|(x, y)| (x - y).abs() <= 1e-9 * y.abs().max(1e-300))
        };
        let c = &r.contact;
        for (name, got, want) in [
            ("smooth max", &c.force_max_n, &m.smooth_max_n),
            ("smooth rms", &c.force_rms_n, &m.smooth_rms_n),
            ("impacts/s", &c.impacts_per_s, &m.impacts_per_s),
            ("impulse mean", &c.impulse_mean_ns, &m.impulse_mean_ns),
            ("impulse max", &c.impulse_max_ns, &m.impulse_max_ns),
            ("1 ms max", &c.window_force_max_n, &m.window_max_n),
            ("contact", &c.contact_fraction, &m.contact_fraction),
        ] {
            assert!(close(got, want), "v = {v}, {name}: {got:?} vs {want:?}");
        }
        let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-300);
        assert!(
            near(c.total_force_max_n, m.total_smooth_max_n)
                && near(c.total_force_rms_n, m.total_smooth_rms_n),
            "v = {v}, summed force: {} {} vs {} {}",
            c.total_force_max_n,
            c.total_force_rms_n,
            m.total_smooth_max_n,
            m.total_smooth_rms_n
        );
        assert!(near(c.in_contact_mean, m.in_contact_mean), "v = {v}");
        assert_eq!(c.in_contact_max, m.in_contact_max, "v = {v}");
        // the scene has impacts: the impulse columns are not vacuous
        assert!(c.impacts_per_s.iter().any(|&x| x > 0.0), "{c:?}");
        let s = spectrum(&m.total_force_n, 1.0 / scene.dt_s, Window::Hann, true).unwrap();
        let bands = s.third_octave_levels(20.0, 5000.0, 1.0);
        assert_eq!(r.bands.len(), bands.len());
        for (a, b) in r.bands.iter().zip(&bands) {
            assert_eq!(a.band, b.band);
            assert!(
                (a.level_db - b.level_db).abs() < 1e-9,
                "v = {v}, {} Hz",
                a.band.nominal_hz
            );
        }
        // something happens: the points leave the road at these speeds
        assert!(
            m.contact_fraction.iter().any(|&c| c < 1.0),
            "{:?}",
            m.contact_fraction
        );
    }
    // the summaries differ between values (the parameter was applied)
    assert_ne!(two[0].result, two[2].result);
}

#[test]
fn an_invalid_value_stops_the_sweep_before_running() {
    let base = three_points();
    let cancel = AtomicBool::new(false);
    let e = run_sweep(
        &base,
        &Sweep {
            param: "road.wavelength_m".into(),
            values: vec![0.1, 0.0],
            threads: 2,
        },
        &tirecontact::ModeCache::new(),
        &|_, _| {},
        &cancel,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("road.wavelength_m") && e.contains("> 0"), "{e}");
}

/// The texture patch preset, cut short.
fn patch() -> Scene {
    let mut s = Scene::load(Path::new("presets/patch_texture.ron")).unwrap();
    s.ramp_s = 0.005;
    s.duration_s = 0.03;
    s
}

#[test]
fn a_grid_is_swept_by_its_own_fields_and_stays_a_grid() {
    let base = patch();
    let paths = param_paths(&base);
    for p in [
        "points.along",
        "points.across",
        "points.spacing_m.0",
        "points.spacing_m.1",
        "points.preload.depth_m",
        "points.preload.length_m",
        "road.length_m",
        "points[95].h_m",
    ] {
        assert!(paths.iter().any(|q| q == p), "{p} missing from {paths:?}");
    }
    // another field leaves the grid as written
    let mut s = base.clone();
    set_param(&mut s, "speed_mps", 20.0).unwrap();
    assert_eq!(s.points.grid(), base.points.grid());
    assert!(s.to_ron_string().contains("Grid("));
    // a grid field expands the grid again: along within rows across
    set_param(&mut s, "points.along", 10.0).unwrap();
    assert_eq!(get_param(&s, "points.along").unwrap(), 10.0);
    assert_eq!(s.num_points(), 60);
    assert_eq!(s.points[9].y_m, s.points[0].y_m);
    assert!(s.points[10].y_m > s.points[9].y_m);
    set_param(&mut s, "points.spacing_m.1", 0.025).unwrap();
    assert!((s.points[10].y_m - s.points[0].y_m - 0.025).abs() < 1e-15);
    set_param(&mut s, "points.preload.depth_m", 0.002).unwrap();
    // the footprint's centre is pressed deepest: parabolic, 2 mm
    let deepest = s.points.iter().map(|p| p.h_m).fold(0.0, f64::min);
    let centre = 0.5 * 0.006; // 10 points along: the nearest to x = 0
    let want = -0.002 * (1.0 - (2.0 * centre / 0.11f64).powi(2));
    assert!((deepest - want).abs() < 1e-15, "{deepest} vs {want}");
    assert!(s.points.grid().is_some());
    // refusals name the field, the value and what is expected
    for (path, v, want) in [
        ("points.along", 2.5, "whole number"),
        ("points.across", 0.0, "whole number"),
        ("points.spacing_m.0", -1.0, "> 0 m"),
        ("points.preload.depth_m", 2.0, "0 to 1 m"),
    ] {
        let before = s.clone();
        let e = set_param(&mut s, path, v).unwrap_err().to_string();
        assert!(
            e.contains(path) && e.contains(&format!("{v}")) && e.contains(want),
            "{path} = {v}: {e}"
        );
        assert_eq!(s, before, "{path}: a refused value changed the scene");
    }
    // a point's own field turns the grid into a list
    set_param(&mut s, "points[3].h_m", -0.0005).unwrap();
    assert!(s.points.grid().is_none());
    assert_eq!(s.points[3].h_m, -0.0005);
    // a list has no grid fields; a flat preload has no footprint length
    let e = set_param(&mut s, "points.along", 4.0).unwrap_err();
    assert!(matches!(e, SweepError::UnknownParam { .. }), "{e}");
    let mut grid = *base.points.grid().unwrap();
    grid.preload = tirecontact::scene::Preload::Flat { depth_m: 0.001 };
    let mut flat = base.clone();
    flat.points = tirecontact::scene::Points::from_grid(grid);
    let e = set_param(&mut flat, "points.preload.length_m", 0.1).unwrap_err();
    assert!(matches!(e, SweepError::UnknownParam { .. }), "{e}");
    set_param(&mut flat, "points.preload.depth_m", 0.0015).unwrap();
    assert!(flat.points.iter().all(|p| p.h_m == -0.0015));
    let e = set_param(&mut three_points(), "points.spacing_m.0", 0.01).unwrap_err();
    assert!(matches!(e, SweepError::UnknownParam { .. }), "{e}");
}

/// A sweep over the points across the tread: the patch's columns against
/// the run's own per-point summary (the points in contact are the sum of
/// the contact fractions; the area is that times the cell).
#[test]
fn a_sweep_of_the_patch_width_reports_the_patch() {
    use tirecontact::studies::sweep::report::{Columns, metric_columns, write_csv};
    let mut base = patch();
    base.duration_s = 0.012;
    let values = vec![2.0, 4.0];
    let sweep = Sweep {
        param: "points.across".into(),
        values: values.clone(),
        threads: 1,
    };
    let pts = run_sweep(
        &base,
        &sweep,
        &tirecontact::ModeCache::new(),
        &|_, _| {},
        &AtomicBool::new(false),
    )
    .unwrap();
    let columns = Columns::of(&base, &["points.across"]);
    assert_eq!(
        columns,
        Columns {
            points: None,
            patch: true
        }
    );
    let header = metric_columns(&columns);
    assert!(!header.iter().any(|h| h.starts_with("q0_")), "{header:?}");
    let mut csv = Vec::new();
    write_csv(&mut csv, "points.across", &pts, &columns).unwrap();
    let text = String::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    for (k, line) in lines.enumerate() {
        let r = pts[k].result.as_ref().unwrap();
        let c = &r.contact;
        assert_eq!(c.contact_fraction.len(), 16 * values[k] as usize);
        let fractions: f64 = c.contact_fraction.iter().sum();
        assert!(
            (c.in_contact_mean - fractions).abs() <= 1e-9 * fractions,
            "{} vs {fractions}",
            c.in_contact_mean
        );
        assert!(c.in_contact_mean > 0.0, "the patch touches the road");
        let cells: Vec<&str> = line.split(',').collect();
        let area: f64 = cells[col("patch_area_mean_m2")].parse().unwrap();
        assert!((area - 0.006 * 0.02 * fractions).abs() <= 1e-12, "{area}");
        let most: f64 = cells[col("patch_area_max_m2")].parse().unwrap();
        assert!(most >= area && most <= 0.006 * 0.02 * c.contact_fraction.len() as f64);
        let force: f64 = cells[col("patch_force_max_N")].parse().unwrap();
        assert_eq!(force, c.total_force_max_n);
        // the summed force exceeds any one point's
        assert!(force > c.force_max_n.iter().fold(0.0, |a, &b| a.max(b)));
    }
    // a wider patch carries more
    let f = |k: usize| pts[k].result.as_ref().unwrap().contact.total_force_max_n;
    assert!(f(1) > f(0), "{} vs {}", f(1), f(0));
}

/// A sweep run in slices on one thread (as in the browser) gives the
/// points of the threaded sweep, whatever the slices; cancelling stops it.
#[test]
fn a_sweep_in_slices_equals_the_sweep() {
    use tirecontact::studies::sweep::SweepRun;
    let base = three_points();
    let sweep = Sweep {
        param: "speed_mps".into(),
        values: vec![9.0, 16.0, 12.5],
        threads: 2,
    };
    let cache = tirecontact::ModeCache::new();
    let cancel = AtomicBool::new(false);
    let whole = run_sweep(&base, &sweep, &cache, &|_, _| {}, &cancel).unwrap();
    let mut run = SweepRun::new(&base, &sweep).unwrap();
    assert_eq!(run.total_steps(), 3 * base.num_steps());
    let mut calls = 0;
    let sliced = loop {
        calls += 1;
        let deadline = web_time::Instant::now() + std::time::Duration::from_micros(200);
        if let Some(r) = run.advance(&cache, &cancel, Some(deadline)) {
            break r.unwrap();
        }
        assert!(run.done_steps() <= run.total_steps());
    };
    assert!(
        calls > 3,
        "{calls} slices: the deadline did not cut the runs"
    );
    assert_eq!(sliced, whole);
    let mut run = SweepRun::new(&base, &sweep).unwrap();
    assert!(
        run.advance(&cache, &cancel, Some(web_time::Instant::now()))
            .is_none()
    );
    cancel.store(true, std::sync::atomic::Ordering::Relaxed);
    assert!(matches!(
        run.advance(&cache, &cancel, None),
        Some(Err(SweepError::Cancelled))
    ));
}
