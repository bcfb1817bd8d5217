//! Sweeps: parameter paths, and a sweep point against the single run of the
//! scene with that value, summarised here independently.

use std::path::Path;
use std::sync::atomic::AtomicBool;
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
    for k in 0..scene.num_steps() {
        sim.step().unwrap();
        if (k as f64) * dt < scene.ramp_s - 1e-9 * dt {
            continue;
        }
        let q = sim.force_n();
        let imp = sim.impact_impulse_ns();
        let mut t = 0.0;
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
