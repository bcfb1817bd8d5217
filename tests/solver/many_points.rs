//! A large scene (50 points x 200 rank-1 modes) steps without error, keeps
//! complementarity (non-negative forces, no penetration beyond round-off)
//! and stays bounded.

use tirecontact::SceneSimulation;
#[test]
fn fifty_points_two_hundred_modes() {
    let mut scene = tirecontact::analysis::bench::scenes::many_points(50, 200);
    scene.duration_s = 0.02;
    let mut sim = tirecontact::Simulation::from_scene(&scene).unwrap();
    let mut min_q = f64::INFINITY;
    while !sim.finished() {
        sim.step().unwrap();
        min_q = sim.force_n().iter().cloned().fold(min_q, f64::min);
        assert!(sim.displacement_m().iter().all(|u| u.abs() < 0.1));
    }
    let st = sim.stats();
    assert!(
        min_q >= -1e-9 * st.max_force_n.iter().cloned().fold(1.0, f64::max),
        "{min_q}"
    );
    assert!(st.worst_penetration_m < 1e-9, "{}", st.worst_penetration_m);
    let frac = st.contact_fraction();
    assert!(frac.iter().any(|&f| f > 0.1), "{frac:?}");
}
