use super::*;
use crate::analysis::bench::scenes::many_points;
use crate::analysis::bench::work_precision::{rms_rel, run_stable, sample};
use tirecontact_core::solver::simulation::SolverOptions;
use tirecontact_io::scene::{ContactScheme, Tyre};

/// One point on one mode, 0.5 mm above a 1 mm, 0.2 m sine road at
/// 20 m/s, no ramp: until it first touches, the tyre is at rest, so its
/// penalty force would be `k r(t) + c ṙ(t)` with `r(t) = a sin(2π v t / λ) - h`.
/// The first switch is that function's first zero (found here by
/// bisection), to far below any step size.
#[test]
fn the_first_landing_is_located_at_the_zero_of_the_road_force() {
    let mut scene = many_points(1, 1);
    let (a, lambda, v, h) = (0.001, 0.2, 20.0, 0.0005);
    scene.points[0] = tirecontact_io::scene::Point {
        x_m: 0.0,
        y_m: 0.0,
        h_m: h,
    };
    scene.ramp_s = 0.0;
    let k = 1e10;
    // the point's mass 1 / φ², φ its modal amplitude (unit modal mass)
    let phi = match &scene.tyre {
        Tyre::Modal { modes } => modes[0].shape[0],
        _ => unreachable!(),
    };
    let c = 2.0 * (k / (phi * phi)).sqrt();
    let w = std::f64::consts::TAU * v / lambda;
    let force = |t: f64| k * (a * (w * t).sin() - h) + c * a * w * (w * t).cos();
    assert!(force(0.0) < 0.0);
    let mut hi = 1e-6;
    while force(hi) < 0.0 {
        hi += 1e-6;
    }
    let mut lo = hi - 1e-6;
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if force(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let run = run_bdf(&scene, k, 1e-6, 1e-4, 0.01, &ModeCache::new()).unwrap();
    let first = run.switches[0];
    assert!(first.on && first.point == 0, "{first:?}");
    assert!(
        (first.t_s - hi).abs() < 1e-10,
        "switch at {} s, the road force crosses zero at {hi} s",
        first.t_s
    );
    // at rest until then
    for (t, u) in run.run.t_s.iter().zip(&run.run.u_m) {
        if *t < hi {
            assert_eq!(u[0], 0.0, "moved at {t} s");
        }
    }
}

/// The located reference of the single-mode preset (dt = 1 µs) and a
/// BDF penalty run's displacement error against it (RMS relative on
/// the 40 µs grid), with the switch times of the run.
fn single_mode_errors(ks: &[f64], rtol: f64) -> (Vec<f64>, Vec<Vec<Switch>>, BaselineRun) {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets/single_mode.ron");
    let scene = Scene::load(&path).unwrap();
    let (dur, dt, grid) = (0.2, 1e-6, 4e-5);
    let cache = ModeCache::new();
    let (reference, _, _) = run_stable(
        &scene,
        ContactScheme::Located,
        dt,
        dur,
        SolverOptions::default(),
        &cache,
    )
    .unwrap();
    let r = sample(
        &reference.t_s,
        &reference.u_m,
        &reference.q_n,
        grid,
        1e-3,
        dt,
        dur,
    );
    let mut errors = Vec::new();
    let mut switches = Vec::new();
    for &k in ks {
        let run = run_bdf(&scene, k, rtol, grid, dur, &cache).unwrap();
        let s = sample(
            &run.run.t_s,
            &run.run.u_m,
            &run.run.q_n,
            grid,
            1e-3,
            grid,
            dur,
        );
        errors.push(rms_rel(&s.u, &r.u));
        switches.push(run.switches);
    }
    (errors, switches, reference)
}

/// As the penalty stiffens, the BDF runs converge to the rigid contact
/// of the located solver (the penalty error falls as about `k^-1/2`),
/// to 4e-6 at 1e12 N/m; and their contact switches fall where the
/// located solver's contact begins and ends (its steps of 1 µs; the
/// penalty's own offset is about `√(m/k)`, 3 µs).
#[test]
fn bdf_converges_to_the_located_solution_and_its_switches() {
    let (errors, switches, reference) = single_mode_errors(&[1e8, 1e10, 1e12], 1e-8);
    assert!(
        errors[1] * 20.0 < errors[0] && errors[2] * 20.0 < errors[1] && errors[2] < 1e-5,
        "errors at k = 1e8, 1e10, 1e12 N/m: {errors:?}"
    );
    // the located run's contact changes: its step-mean force turning
    // positive (a landing: an impact or a force) or zero (leaving)
    let mut changes = Vec::new();
    let mut on = false;
    for (k, q) in reference.q_n.iter().enumerate() {
        if (q[0] > 0.0) != on {
            on = !on;
            // the step's start: the change falls inside the step
            changes.push((reference.t_s[k] - 1e-6, on));
        }
    }
    let stiff = &switches[2];
    assert_eq!(
        stiff.len(),
        changes.len(),
        "BDF switches {stiff:?}, located changes {changes:?}"
    );
    for (s, &(t, on)) in stiff.iter().zip(&changes) {
        assert_eq!(s.on, on, "{s:?} against {t} s");
        assert!(
            (s.t_s - t).abs() < 1e-5,
            "switch {s:?}, located change at {t} s"
        );
    }
}

/// [`many_points`]`(points, modes)` on undamped tread springs of
/// `k_n_m` (N/m) at every point.
fn on_tread_springs(points: usize, modes: usize, k_n_m: f64) -> Scene {
    let mut scene = many_points(points, modes);
    scene.contact = tirecontact_io::scene::Contact::Compliant {
        stiffness_n_m: vec![k_n_m],
    };
    scene
}

/// One point on one mode on a tread spring, 0.5 mm above a 1 mm, 0.2 m
/// sine road at 20 m/s, no ramp: at rest until it lands, so its first
/// landing is where the road reaches its height, `a sin(ω t) = h`, in
/// closed form; the BDF peer locates it there to far below any step size
/// (no damper: the root is the gap's, not a penalty force's).
#[test]
fn a_tread_spring_lands_where_the_road_reaches_the_point() {
    let mut scene = on_tread_springs(1, 1, 2e5);
    let (a, lambda, v, h) = (0.001, 0.2, 20.0, 0.0005);
    scene.points[0] = tirecontact_io::scene::Point {
        x_m: 0.0,
        y_m: 0.0,
        h_m: h,
    };
    scene.ramp_s = 0.0;
    let w = std::f64::consts::TAU * v / lambda;
    let landing_s = (h / a).asin() / w;
    let run = run_bdf_tread(&scene, 1e-6, 1e-4, 0.01, &ModeCache::new()).unwrap();
    let first = run.switches[0];
    assert!(first.on && first.point == 0, "{first:?}");
    assert!(
        (first.t_s - landing_s).abs() < 1e-10,
        "landing at {} s, the road reaches the point at {landing_s} s",
        first.t_s
    );
    // it also leaves: a release follows
    assert!(
        run.switches.iter().any(|s| !s.on && s.t_s > landing_s),
        "{:?}",
        run.switches
    );
}

/// A scene with rigid contact has no tread springs to integrate.
#[test]
fn the_tread_spring_peer_refuses_rigid_contact() {
    let scene = many_points(2, 2);
    assert!(matches!(
        run_bdf_tread(&scene, 1e-6, 1e-4, 0.01, &ModeCache::new()),
        Err(BenchError::NoTreadSprings)
    ));
}

/// Two points on four modes on undamped tread springs, pressed 1 mm into
/// a 1 mm sine road: they leave the road and land again. Two independent
/// integrators of the same equations, the located solver (convolution,
/// events located inside its steps, second order) at a tiny step and the
/// BDF peer (its landings and releases located on its interpolant) at
/// tightening tolerances: BDF's error falls in proportion to its
/// tolerance (at least 10x for each 100x), as an adaptive integrator's
/// does when no step spans a kink, until the two agree to the located
/// reference's own step error (below 1e-8 of the motion).
#[test]
fn bdf_with_located_switches_converges_to_the_located_solver_on_tread_springs() {
    let scene = on_tread_springs(2, 4, 2e5);
    let (dur, grid) = (0.05, 1e-4);
    let cache = ModeCache::new();
    let located = |dt: f64| {
        let (run, _, events) = run_stable(
            &scene,
            ContactScheme::Located,
            dt,
            dur,
            SolverOptions::default(),
            &cache,
        )
        .unwrap();
        (
            sample(&run.t_s, &run.u_m, &run.q_n, grid, 1e-3, dt, dur),
            events,
        )
    };
    let (reference, events) = located(2.5e-7);
    let (coarser, _) = located(5e-7);
    // the reference's own error: a second-order step halved
    let reference_err = rms_rel(&coarser.u, &reference.u) / 3.0;
    assert!(events > 4, "{events} located events");
    let rtols = [1e-4, 1e-6, 1e-8, 1e-10];
    let mut errors = Vec::new();
    for &rtol in &rtols {
        let run = run_bdf_tread(&scene, rtol, grid, dur, &cache).unwrap();
        assert!(
            run.switches.iter().any(|s| s.on) && run.switches.iter().any(|s| !s.on),
            "rtol {rtol}: switches {:?}",
            run.switches
        );
        let s = sample(
            &run.run.t_s,
            &run.run.u_m,
            &run.run.q_n,
            grid,
            1e-3,
            grid,
            dur,
        );
        errors.push(rms_rel(&s.u, &reference.u));
    }
    // measured: 1.2e-4, 2.0e-6, 4.4e-8, 5.2e-9 against the reference's own
    // 5.4e-9: about 50x for each 100x, then the reference's floor
    for k in 1..errors.len() {
        assert!(
            errors[k] * 10.0 < errors[k - 1] || errors[k] < 3.0 * reference_err,
            "BDF errors at rtol {rtols:?}: {errors:?} (reference's own {reference_err:e})"
        );
    }
    assert!(
        errors[errors.len() - 1] < 2.0 * reference_err && reference_err < 1e-8,
        "BDF errors at rtol {rtols:?}: {errors:?} (reference's own {reference_err:e})"
    );
}
