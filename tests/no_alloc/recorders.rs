//! Zero heap allocations per step in the recorders of a run: the sampler
//! and the four that store its samples (the visualiser's history, merging
//! its windows in pairs as it goes; the figures' recording; the arrays; the
//! CSV writer between two formatted blocks).

use crate::allocations_in;
use tirecontact::SceneSimulation;
#[cfg(feature = "gui")]
use tirecontact::gui::History;
use tirecontact::output::arrays::RunArrays;
use tirecontact::output::csv::RunWriter;
use tirecontact::output::record::Recording;
use tirecontact::output::sampler::{LastWindow, Sampler, Stride};
use tirecontact::solver::drive::Probe;

#[test]
fn recording_a_step_does_not_allocate() {
    for scheme in ["Located", "Paper"] {
        let text = std::fs::read_to_string("presets/three_points.ron")
            .unwrap()
            .replace(
                "contact_scheme: Located",
                &format!("contact_scheme: {scheme}"),
            );
        let scene = tirecontact::Scene::parse(&text, "three_points").unwrap();
        let (p, n) = (scene.num_points(), scene.num_steps());
        let mut sim = tirecontact::Simulation::from_scene(&scene).unwrap();
        // 1024 windows kept: they merge in pairs several times below
        #[cfg(feature = "gui")]
        let mut history = History::new(p, 1024 * (5 * p + 1));
        let mut sampler = Sampler::new(p, Stride::Every(7), LastWindow::Partial).with_impacts();
        let mut recording = Recording::new(p, n, 4000);
        let mut arrays = RunArrays::new(p, n, 7);
        // rows of 1 + 5 p numbers: no block is formatted in 25000 steps
        let mut csv = RunWriter::with_layout(std::io::sink(), p, 7, 1, 1 << 17).unwrap();
        #[cfg(feature = "gui")]
        history.record_initial(&sim);
        sampler.start(&sim);
        arrays.start(&sim).unwrap();
        csv.write_initial(&sim).unwrap();
        let mut windows = 0;
        macro_rules! steps {
            ($n:expr) => {
                for _ in 0..$n {
                    sim.step().unwrap();
                    #[cfg(feature = "gui")]
                    history.after_step(&sim);
                    windows += usize::from(sampler.after_step(&sim).is_some());
                    recording.after_step(&sim);
                    arrays.after_step(&sim).unwrap();
                    csv.after_step(&sim).unwrap();
                }
            };
        }
        // warm up: the first events size the solver's scratch tables
        steps!(5000);
        #[cfg(feature = "gui")]
        let stride_before = history.stride();
        let allocs = allocations_in(|| steps!(20000));
        assert_eq!(allocs, 0, "{scheme}: {allocs} allocations in 20000 steps");
        // the history's windows doubled inside the measured steps
        #[cfg(feature = "gui")]
        assert!(history.stride() > stride_before, "{scheme}");
        assert_eq!(windows, 25000 / 7, "{scheme}");
        assert!(recording.len() > 1000 && arrays.rows() > 3000);
    }
}
