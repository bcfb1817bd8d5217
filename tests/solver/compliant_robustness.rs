//! Compliant contact on three coupled points: bounded for any tread
//! stiffness, and stiffnesses refused by field.

use tirecontact::identify::SceneSimulation;
use tirecontact::{Scene, SceneError, Simulation};

fn three_points(contact: &str) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/presets/three_points.ron"
    ))
    .unwrap()
    .replace("contact_scheme: Located", &format!("contact: {contact}"));
    Scene::parse(&text, "three_points")
}

/// Impacts and releases on three coupled points, from a soft tread to one
/// far stiffer than the step resolves: bounded, finite, every point
/// touching the road (and leaving it, for a stiff tread).
#[test]
fn coupled_impacts_stay_bounded_for_any_stiffness() {
    let mut rigid = three_points("Rigid, contact_scheme: Paper").unwrap();
    rigid.duration_s = 0.15;
    let mut sim = Simulation::from_scene(&rigid).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    let f_rigid = sim.stats().contact_fraction();
    for k in [1e5, 1e7, 1e9, 1e12, 1e15] {
        let mut scene = three_points(&format!("Compliant(stiffness_n_m: [{k:e}])")).unwrap();
        scene.duration_s = 0.15;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut umax = 0.0f64;
        while !sim.finished() {
            sim.step().unwrap();
            umax = sim
                .displacement_m()
                .iter()
                .fold(umax, |m, u| m.max(u.abs()));
        }
        let f = sim.stats().contact_fraction();
        eprintln!("k = {k:e}: max |u| = {umax:.3e} m, contact fractions {f:?}");
        assert!(umax < 0.02, "k = {k}: {umax}");
        // a soft tread keeps the points on the road; a stiff one lets them fly
        assert!(f.iter().all(|&c| c > 0.05), "k = {k}: {f:?}");
        if k >= 1e9 {
            assert!(f.iter().all(|&c| c < 0.99), "k = {k}: {f:?}");
        }
        // far beyond resolution (sqrt(k ΣA) dt >> 1) the step is the rigid one
        if k >= 1e15 {
            for (c, r) in f.iter().zip(&f_rigid) {
                assert!((c - r).abs() < 0.05, "k = {k}: {f:?} vs rigid {f_rigid:?}");
            }
        }
    }
}

#[test]
fn invalid_stiffness_names_field_value_and_expectation() {
    for (c, field) in [
        (
            "Compliant(stiffness_n_m: [1e6, 2e6])",
            "contact.stiffness_n_m",
        ),
        (
            "Compliant(stiffness_n_m: [1e6, -1.0, 1e6])",
            "contact.stiffness_n_m[1]",
        ),
        (
            "Compliant(stiffness_n_m: [0.0])",
            "contact.stiffness_n_m[0]",
        ),
        (
            "Compliant(stiffness_n_m: [inf])",
            "contact.stiffness_n_m[0]",
        ),
    ] {
        match three_points(c) {
            Err(SceneError::Invalid { errors, .. }) => {
                assert!(errors.iter().any(|e| e.field == field), "{c}: {errors:?}");
                assert!(errors.iter().all(|e| !e.expected.is_empty()));
            }
            other => panic!("{c}: {other:?}"),
        }
    }
    // valid per-point stiffnesses survive saving and re-reading
    let scene = three_points("Compliant(stiffness_n_m: [1e6, 2e6, 3e6])").unwrap();
    let again = Scene::parse(&scene.to_ron_string(), "roundtrip").unwrap();
    assert_eq!(again.contact, scene.contact);
    assert_eq!(again.contact.stiffness_per_point(3), [1e6, 2e6, 3e6]);
}
