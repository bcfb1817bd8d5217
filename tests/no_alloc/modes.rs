//! The per-mode contributions that the classroom's mode bars show
//! (`Simulation::mode_displacement_m`) do not allocate.

use crate::allocations_in;
use tirecontact::SceneSimulation;

#[test]
fn mode_contributions_do_not_allocate() {
    let text = std::fs::read_to_string("presets/three_points.ron").unwrap();
    let scene = tirecontact::Scene::parse(&text, "three_points").unwrap();
    let mut sim = tirecontact::Simulation::from_scene(&scene).unwrap();
    let mut c = vec![0.0; sim.num_modes()];
    for _ in 0..2000 {
        sim.step().unwrap();
    }
    let mut sum = 0.0;
    let allocs = allocations_in(|| {
        for _ in 0..1000 {
            sim.step().unwrap();
            for i in 0..3 {
                sim.mode_displacement_m(i, &mut c);
                sum += c.iter().sum::<f64>();
            }
        }
    });
    assert_eq!(allocs, 0, "{allocs} allocations");
    assert!(sum.is_finite());
}
