//! Study and sweep metrics converge as dt → 0 on the paper's preset, where
//! every road period throws points off the road and lands them again; the
//! step-mean force they replace (impulse / dt at an impact) does not.

use crate::support::preset;
use std::sync::atomic::AtomicBool;
use tirecontact::analysis::metrics::ContactSummary;
use tirecontact::studies::sweep::{RunSummary, run_summary};
use tirecontact::{ModeCache, PreparedModel};

/// A per-point metric of a summary.
type Metric = fn(&ContactSummary) -> &Vec<f64>;

fn summary_at(dt_s: f64, cache: &ModeCache) -> RunSummary {
    let mut scene = preset("paper");
    scene.dt_s = dt_s;
    let model = PreparedModel::new(&scene, cache).unwrap();
    run_summary(&model, &|_| {}, &AtomicBool::new(false)).unwrap()
}

/// Largest relative spread of a per-point metric over the runs (against
/// `floor` where the values are near zero).
fn spread(runs: &[RunSummary], get: Metric, floor: f64) -> f64 {
    let p = get(&runs[0].contact).len();
    (0..p)
        .map(|i| {
            let v: Vec<f64> = runs.iter().map(|r| get(&r.contact)[i]).collect();
            let (lo, hi) = v
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            (hi - lo) / hi.abs().max(floor)
        })
        .fold(0.0, f64::max)
}

#[test]
fn every_metric_converges_as_the_time_step_shrinks() {
    let cache = ModeCache::new();
    let dts = [1e-5, 5e-6, 2.5e-6];
    let runs: Vec<RunSummary> = dts.iter().map(|&dt| summary_at(dt, &cache)).collect();
    let c = &runs[1].contact;
    // the preset lands points on every road period: impacts carry a large
    // part of the momentum, and as impulse / dt they would swamp the force
    assert!(c.impacts_per_s.iter().all(|&n| n >= 90.0), "{c:?}");
    for i in 0..c.force_max_n.len() {
        let step_mean_peak = c.impulse_max_ns[i] / dts[1];
        assert!(
            step_mean_peak > 20.0 * c.force_max_n[i],
            "point {i}: impact as impulse/dt {step_mean_peak} N against {} N",
            c.force_max_n[i]
        );
    }
    // ... and impulse/dt doubles when dt halves, the metrics do not move
    let peak = |r: &RunSummary, dt: f64| r.contact.impulse_max_ns[0] / dt;
    let ratio = peak(&runs[2], dts[2]) / peak(&runs[1], dts[1]);
    assert!((ratio - 2.0).abs() < 0.01, "impulse/dt ratio {ratio}");
    // (name, metric, floor of the relative spread, tolerance)
    let checks: [(&str, Metric, f64, f64); 7] = [
        ("max force without impacts", |s| &s.force_max_n, 1.0, 5e-3),
        ("RMS force without impacts", |s| &s.force_rms_n, 1.0, 5e-3),
        (
            "largest 1 ms mean force",
            |s| &s.window_force_max_n,
            1.0,
            1e-2,
        ),
        ("impacts per second", |s| &s.impacts_per_s, 1.0, 1e-12),
        ("mean impulse", |s| &s.impulse_mean_ns, 1e-6, 1e-6),
        ("largest impulse", |s| &s.impulse_max_ns, 1e-6, 1e-6),
        ("contact fraction", |s| &s.contact_fraction, 0.1, 1e-2),
    ];
    for (name, get, floor, tol) in checks {
        let s = spread(&runs, get, floor);
        assert!(
            s <= tol,
            "{name}: spread {s:e} over dt {dts:?} > {tol:e}: {:?}",
            runs.iter().map(|r| get(&r.contact)).collect::<Vec<_>>()
        );
    }
    // the total force's third-octave bands within 40 dB of the strongest
    // (below that, the Hann window's leakage floor)
    let top = runs[0]
        .bands
        .iter()
        .map(|b| b.level_db)
        .fold(f64::NEG_INFINITY, f64::max);
    let mut checked = 0;
    for (k, b) in runs[0].bands.iter().enumerate() {
        if b.level_db < top - 40.0 {
            continue;
        }
        for r in &runs[1..] {
            let d = (r.bands[k].level_db - b.level_db).abs();
            assert!(d < 0.2, "{} Hz band moves {d} dB", b.band.nominal_hz);
        }
        checked += 1;
    }
    assert!(checked >= 10, "{checked} bands checked");
}
