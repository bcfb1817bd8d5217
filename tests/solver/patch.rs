//! Contact patches: points across the tread on a tyre with a width and a
//! road that varies across it.

use crate::support::Gap;
use tirecontact::SceneSimulation;
use tirecontact::model::road::Road;
use tirecontact::scene::{Contact, PointGrid, Points, Preload, Scene, Tyre};
use tirecontact::{PreparedModel, Simulation, SolverOptions};

/// A patch pressed into a flat road settles where the static contact
/// problem puts it: `(C + K⁻¹) q = r` with `C` the static compliance of
/// the modes (`Σ φ_k φ_kᵀ / ω_k²`), `K` the tread springs and `r` the
/// press depths; a direct solve of the linear system against the run's
/// end forces.
#[test]
fn a_patch_on_a_flat_road_settles_to_the_static_solution() {
    let mut scene = Scene::load(std::path::Path::new("presets/patch_texture.ron")).unwrap();
    scene.road = Road::Sine {
        amplitude_m: 0.0,
        wavelength_m: 1.0,
    };
    scene.points = Points::from_grid(PointGrid {
        along: 6,
        across: 3,
        spacing_m: (0.01, 0.03),
        preload: Preload::Flat { depth_m: 0.001 },
    });
    if let Tyre::Plate { plate } = &mut scene.tyre {
        plate.damping_ratio = 0.3;
        plate.max_freq_hz = 800.0;
    }
    let k_n_m = 75_000.0;
    scene.contact = Contact::Compliant {
        stiffness_n_m: vec![k_n_m],
    };
    scene.speed_mps = 0.0;
    scene.ramp_s = 0.02;
    scene.dt_s = 5e-5;
    scene.duration_s = 0.2;
    let model = PreparedModel::of(&scene).unwrap();
    let mut sim = model.simulation(SolverOptions::default()).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    let p = scene.points.len();
    let modes = model.modes();
    // (C + 1/k) q = -h, all points pressed (checked below)
    let mut a = vec![vec![0.0; p + 1]; p];
    for i in 0..p {
        for j in 0..p {
            a[i][j] = modes
                .iter()
                .map(|m| m.shape[i] * m.shape[j] / (std::f64::consts::TAU * m.freq_hz).powi(2))
                .sum::<f64>();
        }
        a[i][i] += 1.0 / k_n_m;
        a[i][p] = -scene.points[i].h_m;
    }
    let q = solve(a);
    assert!(q.iter().all(|&f| f > 0.0), "every point pressed: {q:?}");
    for i in 0..p {
        let got = sim.force_n()[i];
        assert!(
            (got - q[i]).abs() < 1e-6 * q[i].abs().max(1e-3),
            "point {i}: run {got} N vs static {} N",
            q[i]
        );
    }
}

/// Gauss elimination with partial pivoting of an augmented `n × (n+1)`
/// system.
fn solve(mut a: Vec<Vec<f64>>) -> Vec<f64> {
    let n = a.len();
    for c in 0..n {
        let piv = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap();
        a.swap(c, piv);
        for r in c + 1..n {
            let f = a[r][c] / a[c][c];
            for k in c..=n {
                a[r][k] -= f * a[c][k];
            }
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (a[r][n] - s) / a[r][r];
    }
    x
}

/// A tread spring whose linear trial force, positive at its Gauss points,
/// extrapolates below zero at the sub-step start is held free up to the
/// next event and lands again in the step: on a chip seal at a coarse
/// step no point is left below the road at a step end (it was left up to
/// 0.2 mm below when such a spring was released for the rest of the step).
#[test]
fn springs_freed_before_an_event_land_again_in_the_step() {
    let mut scene = Scene::load(std::path::Path::new("presets/patch_chip_seal.ron")).unwrap();
    scene.dt_s = 2e-5;
    scene.duration_s = 0.08;
    let mut sim = Simulation::from_scene(&scene).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    let st = sim.stats();
    assert!(st.events > 5000, "{} events", st.events);
    assert!(
        st.worst_penetration_m < 1e-7,
        "a point was left {:e} m below the road at a step end",
        st.worst_penetration_m
    );
}

/// A point outside a surface file's grid across the tread is refused when
/// the road is loaded, naming the point and the grid's range; on the
/// grid, each point bears on its own row: on a road that rises across the
/// tread (`z = 2 mm · (y / 0.1 m)` where `y > 0`, flat elsewhere) a row at
/// `y = 0.05 m` is pressed 1 mm deeper than the row at `y = -0.05 m`,
/// and carries the larger force.
#[test]
fn points_bear_on_their_own_row_of_a_surface_and_outside_it_are_refused() {
    let dir = crate::support::temp_dir();
    let mut csv = String::from("x_m,y_m,z_m\n");
    for j in 0..5 {
        let y = -0.1 + 0.05 * j as f64;
        for i in 0..40 {
            let z = if y > 0.0 { 0.002 * y / 0.1 } else { 0.0 };
            csv.push_str(&format!("{},{y},{z}\n", i as f64 * 0.01));
        }
    }
    std::fs::write(dir.path().join("ramp.csv"), csv).unwrap();
    let mut scene = Scene::load(std::path::Path::new("presets/patch_texture.ron")).unwrap();
    scene.base_dir = Some(dir.path().to_path_buf());
    scene.road = Road::Surface {
        file: "ramp.csv".into(),
        looped: true,
    };
    scene.points = Points::from_grid(PointGrid {
        along: 3,
        across: 2,
        spacing_m: (0.01, 0.1),
        preload: Preload::Flat { depth_m: 0.0005 },
    });
    scene.speed_mps = 0.0;
    scene.duration_s = 0.05;
    let model = PreparedModel::of(&scene).unwrap();
    let mut sim = model.simulation(SolverOptions::default()).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    // points 0-2 at y = -0.05 (flat), 3-5 at y = +0.05 (1 mm up)
    let r = sim.road_m();
    for i in 0..3 {
        assert!((r[i] - 0.0005).abs() < 1e-12, "point {i}: road {}", r[i]);
        assert!(
            (r[i + 3] - 0.0015).abs() < 1e-12,
            "point {}: road {}",
            i + 3,
            r[i + 3]
        );
        assert!(sim.force_n()[i + 3] > sim.force_n()[i], "point {i}");
    }
    // a row outside the grid (on a belt wide enough to hold it)
    if let Tyre::Plate { plate } = &mut scene.tyre {
        plate.width_m = 0.4;
    }
    scene.points = Points::from_grid(PointGrid {
        along: 2,
        across: 2,
        spacing_m: (0.01, 0.24),
        preload: Preload::Flat { depth_m: 0.0005 },
    });
    let Err(e) = PreparedModel::of(&scene) else {
        panic!("a point outside the grid was accepted");
    };
    let e = e.to_string();
    assert!(
        e.contains("points[2].y_m = 0.12") && e.contains("-0.1 m to 0.1 m"),
        "{e}"
    );
}

/// On a rough road a compliant patch has an event or more a step, each
/// with sub-steps whose small systems (8 to 30 points on the road) are
/// solved by GMRES through the modal states; the same runs with every
/// sub-step filled and factorised give the same displacements and forces
/// to 1e-9 of their largest values, step by step, through the ramp and
/// the rolling, while the iterative solves did run and saved
/// factorisations.
#[test]
fn iterative_sub_steps_of_small_sets_agree_with_the_direct_solves() {
    for preset in ["presets/patch_chip_seal.ron", "presets/patch_texture.ron"] {
        let mut scene = Scene::load(std::path::Path::new(preset)).unwrap();
        scene.duration_s = 0.06;
        let model = PreparedModel::of(&scene).unwrap();
        // (the sub-steps of every event: no merged event steps)
        let sub_steps = SolverOptions {
            merged_events: false,
            ..SolverOptions::default()
        };
        let direct = SolverOptions {
            large_set_from: usize::MAX,
            compliant_large_set_from: usize::MAX,
            iterative_sub_from: usize::MAX,
            ..sub_steps
        };
        let mut a = model.simulation(direct).unwrap();
        let mut b = model.simulation(sub_steps).unwrap();
        let (mut u, mut q) = (Gap::default(), Gap::default());
        while !a.finished() {
            a.step().unwrap();
            b.step().unwrap();
            u.add(a.displacement_m(), b.displacement_m());
            q.add(a.force_n(), b.force_n());
        }
        let (sa, sb) = (a.stats(), b.stats());
        assert!(
            u.relative() <= 1e-9 && q.relative() <= 1e-9,
            "{preset}: u differs by {:e} of {:e} m, q by {:e} of {:e} N",
            u.diff,
            u.max,
            q.diff,
            q.max
        );
        assert_eq!(sa.events, sb.events, "{preset}: events");
        assert!(sb.krylov_applications > 1000, "{preset}: {sb:?}");
        assert!(
            2 * sb.factorisations < sa.factorisations,
            "{preset}: factorisations {} direct, {} iterative",
            sa.factorisations,
            sb.factorisations
        );
    }
}
